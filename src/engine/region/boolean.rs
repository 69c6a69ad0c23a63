//! `region ID union N id1 id2 ...` and `region ID intersect N id1 id2 ...`: a point is in a
//! union if it matches any sub-region, in an intersection if it matches all (each sub-region
//! with its own `side`). They have no faces of their own, so `open` does not apply.

use super::{Region, Shape, ShapeArgs, Style, Vec3, BIG};
use dmhs_parser::{Args, DResult};

pub const UNION: Style = Style { syntax: "union N id1 id2 ...", vars: &[], nargs: count, parse: |s| parse(s, false) };
pub const INTERSECT: Style = Style { syntax: "intersect N id1 id2 ...", vars: &[], nargs: count, parse: |s| parse(s, true) };

#[derive(Debug)]
struct Boolean {
    /// Intersect (all) or union (any).
    all: bool,
    /// Copies of the sub-regions as defined (handed to the Region, which looks them up again by
    /// ID before each run, as LAMMPS does).
    subs: Vec<Region>,
}

fn count(a: &mut Args, style: &str) -> DResult<usize> {
    let n = a.i64("number of sub-regions")?;
    if n < 2 {
        return Err(a.error_at(
            a.last().unwrap(),
            format!("region {style} needs at least 2 sub-regions, found {n}"),
            "must be >= 2",
        ));
    }
    Ok(n as usize)
}

fn parse(s: &ShapeArgs, all: bool) -> DResult<Box<dyn Shape>> {
    let mut subs = vec![];
    for w in s.words {
        match s.existing.iter().find(|r| r.id == w.text) {
            Some(r) => subs.push(r.clone()),
            None => {
                return Err(s.error(
                    w,
                    format!("region {} sub-region `{}` does not exist", s.style, w.text),
                    "unknown region ID",
                ))
            }
        }
    }
    Ok(Box::new(Boolean { all, subs }))
}

impl Shape for Boolean {
    // the Region takes the sub-regions (Kind::Boolean) and answers for them
    fn inside(&self, _x: &Vec3) -> bool {
        unreachable!("a union or intersection is answered by its Region")
    }

    fn extent(&self) -> Option<(Vec3, Vec3)> {
        unreachable!("a union or intersection is answered by its Region")
    }

    fn has_faces(&self) -> bool {
        false
    }

    fn boolean(&self) -> Option<(bool, Vec<Region>)> {
        Some((self.all, self.subs.clone()))
    }
}

/// The bounding box of an intersection (`all`) or union of `subs` (LAMMPS' extent_*).
pub(super) fn extent(all: bool, subs: &[Region]) -> Option<([f64; 3], [f64; 3])> {
    let min = |p: f64, q: f64| if p < q { p } else { q };
    let max = |p: f64, q: f64| if p > q { p } else { q };
    if all {
        // the overlap of the sub-regions that have a bounding box
        let mut ext: Option<(Vec3, Vec3)> = None;
        for (rlo, rhi) in subs.iter().filter_map(Region::extent) {
            let (rlo, rhi) = (Vec3::from(rlo), Vec3::from(rhi));
            let (lo, hi) = ext.unwrap_or((rlo, rhi));
            ext = Some((lo.zip_map(&rlo, max), hi.zip_map(&rhi, min)));
        }
        ext.map(|(lo, hi)| (lo.into(), hi.into()))
    } else {
        // only if every sub-region has one
        let mut lo = Vec3::repeat(BIG);
        let mut hi = Vec3::repeat(-BIG);
        for r in subs {
            let (rlo, rhi) = r.extent()?;
            lo = lo.zip_map(&Vec3::from(rlo), min);
            hi = hi.zip_map(&Vec3::from(rhi), max);
        }
        Some((lo.into(), hi.into()))
    }
}

#[cfg(test)]
mod tests {
    use crate::engine::region::tests::reg;

    #[test]
    fn union_intersect_extents() {
        let a = reg("region a block 0 1 0 1 0 1 units box", None, None, &[]).unwrap();
        let b = reg("region b sphere 2 2 2 1 units box", None, None, &[]).unwrap();
        let ex = vec![a, b];
        let u = reg("region u union 2 a b", None, None, &ex).unwrap();
        assert_eq!(u.extent(), Some(([0.0; 3], [3.0; 3])));
        assert!(u.matches([2.5, 2.0, 2.0]) && u.matches([0.5, 0.5, 0.5]) && !u.matches([1.5, 0.5, 0.5]));
        let i = reg("region i intersect 2 a b", None, None, &ex).unwrap();
        assert_eq!(i.extent(), Some(([1.0; 3], [1.0; 3])));
        assert!(reg("region i intersect 2 a c", None, None, &ex).unwrap_err().message.contains("`c`"));
        assert!(reg("region a block 0 1 0 1 0 1", None, None, &ex).unwrap_err().message.contains("reuse"));
    }

    #[test]
    fn unbounded_sub_regions() {
        let a = reg("region a block 0 1 0 1 0 1 units box", None, None, &[]).unwrap();
        let p = reg("region p plane 0.5 0 0 1 0 0 units box", None, None, &[]).unwrap();
        let ex = vec![a, p];
        // a union with a half space is unbounded; an intersection keeps the block's box
        assert_eq!(reg("region u union 2 a p", None, None, &ex).unwrap().extent(), None);
        let i = reg("region i intersect 2 a p", None, None, &ex).unwrap();
        assert_eq!(i.extent(), Some(([0.0; 3], [1.0; 3])));
        assert!(i.matches([0.75, 0.5, 0.5]) && !i.matches([0.25, 0.5, 0.5]));
        // open is ignored: union and intersect have no faces
        let i = reg("region i intersect 2 a p open 1", None, None, &ex).unwrap();
        assert!(!i.matches([0.25, 0.5, 0.5]));
        let e = reg("region u union 1 a", None, None, &ex).unwrap_err();
        assert_eq!(e.message, "region union needs at least 2 sub-regions, found 1");
    }
}
