//! The `region` command: geometric regions (block, sphere, cylinder, prism, plane) and their
//! boolean combinations (union, intersect), with LAMMPS' exact point tests (surface points
//! are inside), `side in|out`, `units lattice|box` scaling, `open` faces and the bounding box
//! ("extent") that `create_atoms` uses to narrow its lattice loop.

use crate::engine::domain::Domain;
use crate::engine::lattice::Lattice;
use dmhs_parser::{Args, Command, DResult, Word};

const SYNTAX: &str = "region ID style args keyword value ... \
(styles: block xlo xhi ylo yhi zlo zhi | sphere x y z r | cylinder dim c1 c2 r lo hi | \
prism xlo xhi ylo yhi zlo zhi xy xz yz | plane px py pz nx ny nz | union N id1 id2 ... | \
intersect N id1 id2 ...; keywords: side in|out, units lattice|box, open face)";

/// What LAMMPS substitutes for `INF` bounds.
const BIG: f64 = 1.0e20;

/// The geometry of a region, in box units.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    Block {
        lo: [f64; 3],
        hi: [f64; 3],
    },
    Sphere {
        center: [f64; 3],
        radius: f64,
    },
    /// `axis` = 0, 1, 2 for x, y, z; `c1`, `c2` = the centre in the other two dimensions
    /// (in x, y, z order); `lo`, `hi` = the extent along the axis.
    Cylinder {
        axis: usize,
        c1: f64,
        c2: f64,
        radius: f64,
        lo: f64,
        hi: f64,
    },
    /// A parallelepiped with lower corner `lo`, edges `hi - lo` and tilts `xy xz yz`;
    /// `hinv` maps box coordinates to tilt coordinates in [0, 1].
    Prism {
        lo: [f64; 3],
        hi: [f64; 3],
        tilt: [f64; 3],
        hinv: [[f64; 3]; 3],
    },
    /// Half space on the side the unit `normal` points to.
    Plane {
        point: [f64; 3],
        normal: [f64; 3],
    },
    Union(Vec<Region>),
    Intersect(Vec<Region>),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    pub id: String,
    pub style: String,
    pub shape: Shape,
    /// `side in` (true, the default) or `side out`.
    pub interior: bool,
    /// Faces listed with the `open` keyword (1-based in the command, 0-based here).
    pub open_faces: [bool; 6],
    /// Bounding box `(lo, hi)` when LAMMPS defines one (interior regions of finite shapes).
    pub extent: Option<([f64; 3], [f64; 3])>,
}

impl Region {
    /// LAMMPS `Region::inside`: the bare shape test, surface points included.
    pub fn inside(&self, x: [f64; 3]) -> bool {
        match &self.shape {
            Shape::Block { lo, hi } => {
                x[0] >= lo[0] && x[0] <= hi[0] && x[1] >= lo[1] && x[1] <= hi[1] && x[2] >= lo[2] && x[2] <= hi[2]
            }
            Shape::Sphere { center, radius } => {
                let dx = x[0] - center[0];
                let dy = x[1] - center[1];
                let dz = x[2] - center[2];
                (dx * dx + dy * dy + dz * dz).sqrt() <= *radius
            }
            Shape::Cylinder { axis, c1, c2, radius, lo, hi } => {
                let (p1, p2) = match axis {
                    0 => (x[1], x[2]),
                    1 => (x[0], x[2]),
                    _ => (x[0], x[1]),
                };
                let d1 = p1 - c1;
                let d2 = p2 - c2;
                let dist = (d1 * d1 + d2 * d2).sqrt();
                dist <= *radius && x[*axis] >= *lo && x[*axis] <= *hi
            }
            Shape::Prism { lo, hinv, .. } => {
                let a = hinv[0][0] * (x[0] - lo[0]) + hinv[0][1] * (x[1] - lo[1]) + hinv[0][2] * (x[2] - lo[2]);
                let b = hinv[1][1] * (x[1] - lo[1]) + hinv[1][2] * (x[2] - lo[2]);
                let c = hinv[2][2] * (x[2] - lo[2]);
                (0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b) && (0.0..=1.0).contains(&c)
            }
            Shape::Plane { point, normal } => {
                let dot = (x[0] - point[0]) * normal[0] + (x[1] - point[1]) * normal[1] + (x[2] - point[2]) * normal[2];
                dot >= 0.0
            }
            Shape::Union(subs) => subs.iter().any(|r| r.matches(x)),
            Shape::Intersect(subs) => subs.iter().all(|r| r.matches(x)),
        }
    }

    /// LAMMPS `Region::match`: is `x` in the region, honouring `side`. A primitive region
    /// with any `open` face matches every point (as in LAMMPS, where open faces only matter
    /// for wall contacts); union and intersect ignore `open`.
    pub fn matches(&self, x: [f64; 3]) -> bool {
        let composite = matches!(self.shape, Shape::Union(_) | Shape::Intersect(_));
        if !composite && self.open_faces.iter().any(|&o| o) {
            return true;
        }
        self.inside(x) == self.interior
    }

    /// The bounding box LAMMPS uses (`bboxflag` and `extent_*`), or None.
    pub fn extent(&self) -> Option<([f64; 3], [f64; 3])> {
        self.extent
    }

    /// Parse a `region` command. `domain` is needed for `EDGE`/`INF` bounds; `lattice` gives
    /// the spacings for `units lattice` (the default; without a lattice command LAMMPS uses
    /// its initial `lattice none 1.0`); `existing` holds the regions defined so far (for
    /// union/intersect and ID reuse).
    pub fn from_lammps(
        cmd: &Command,
        domain: Option<&Domain>,
        lattice: Option<&Lattice>,
        existing: &[Region],
    ) -> DResult<Region> {
        let mut a = Args::new(cmd, SYNTAX);
        let id_word = a.word("region ID")?;
        let id = id_word.text.clone();
        if id.is_empty() || !id.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
            return Err(a.error_at(
                id_word,
                format!("region ID `{id}` must use only letters, digits and underscores"),
                "invalid ID",
            ));
        }
        if existing.iter().any(|r| r.id == id) {
            return Err(a.error_at(id_word, format!("reuse of region ID `{id}`"), "already defined"));
        }
        let style_word = a.word("region style")?;
        let style = style_word.text.as_str();
        let nshape = match style {
            "block" => 6,
            "sphere" => 4,
            "cylinder" => 6,
            "prism" => 9,
            "plane" => 6,
            "union" | "intersect" => {
                let n = a.i64("number of sub-regions")?;
                if n < 2 {
                    return Err(a.error_at(
                        a.last().unwrap(),
                        format!("region {style} needs at least 2 sub-regions, found {n}"),
                        "must be >= 2",
                    ));
                }
                n as usize
            }
            "cone" | "ellipsoid" | "delete" => {
                return Err(a.error_at(
                    style_word,
                    format!("region style `{style}` is not supported"),
                    "not supported",
                ));
            }
            _ => {
                let known = ["block", "sphere", "cylinder", "prism", "plane", "union", "intersect"];
                return Err(a.unknown_keyword(style_word, &known));
            }
        };
        if a.len_remaining() < nshape {
            a.skip(a.len_remaining());
            return Err(a.missing(&format!("{} arguments of region {style}", nshape)));
        }
        let shape_words = &a.remaining()[..nshape];
        a.skip(nshape);

        // Keywords come first in LAMMPS (they set the scale the shape arguments use).
        let mut interior = true;
        let mut lattice_units = true;
        let mut open_faces = [false; 6];
        const KEYWORDS: [&str; 5] = ["side", "units", "open", "move", "rotate"];
        let mut open_words: Vec<(&Word, usize)> = vec![];
        while let Some(kw) = a.peek() {
            a.skip(1);
            match kw.text.as_str() {
                "side" => interior = a.choice("side", &["in", "out"])? == 0,
                "units" => lattice_units = a.choice("units", &["lattice", "box"])? == 0,
                "open" => {
                    let face = a.i64_in("open face", 1, 6)? as usize;
                    open_faces[face - 1] = true;
                    open_words.push((a.last().unwrap(), face));
                }
                "move" | "rotate" => {
                    return Err(a.error_at(
                        kw,
                        format!("region keyword `{}` (dynamic regions) is not supported", kw.text),
                        "not supported",
                    ));
                }
                _ => return Err(a.unknown_keyword(kw, &KEYWORDS)),
            }
        }
        let none = Lattice::none(1.0);
        let lat = lattice.unwrap_or(&none);
        let scale = if lattice_units { lat.spacing() } else { [1.0; 3] };

        let num = |w: &Word, what: &str| -> DResult<f64> {
            if w.text.starts_with("v_") {
                return Err(a.error_at(
                    w,
                    "variable region parameters (v_name) are not supported",
                    "variable not supported",
                ));
            }
            dmhs_parser::args::word_f64(w, what).map_err(|d| d.with_help(format!("syntax: {SYNTAX}")))
        };
        // A bound that may be INF (+-1e20) or EDGE (the box face).
        let bound = |w: &Word, dim: usize, upper: bool, what: &str| -> DResult<f64> {
            if w.text == "INF" || w.text == "EDGE" {
                let Some(d) = domain else {
                    return Err(a.error_at(
                        w,
                        format!("cannot use region {} when the box does not exist", w.text),
                        "no box yet",
                    ));
                };
                return Ok(match (w.text.as_str(), upper) {
                    ("INF", false) => -BIG,
                    ("INF", true) => BIG,
                    (_, false) => d.lo[dim],
                    (_, true) => d.hi[dim],
                });
            }
            Ok(scale[dim] * num(w, what)?)
        };

        let w = shape_words;
        let (shape, extent) = match style {
            "block" => {
                let mut lo = [0.0; 3];
                let mut hi = [0.0; 3];
                for d in 0..3 {
                    lo[d] = bound(&w[2 * d], d, false, ["xlo", "ylo", "zlo"][d])?;
                    hi[d] = bound(&w[2 * d + 1], d, true, ["xhi", "yhi", "zhi"][d])?;
                }
                for d in 0..3 {
                    if lo[d] > hi[d] {
                        return Err(a.error_at(
                            &w[2 * d],
                            format!(
                                "region block {}lo {} > {}hi {}",
                                "xyz".as_bytes()[d] as char,
                                lo[d],
                                "xyz".as_bytes()[d] as char,
                                hi[d]
                            ),
                            "lower bound above upper bound",
                        ));
                    }
                }
                (Shape::Block { lo, hi }, if interior { Some((lo, hi)) } else { None })
            }
            "sphere" => {
                let center = [scale[0] * num(&w[0], "x")?, scale[1] * num(&w[1], "y")?, scale[2] * num(&w[2], "z")?];
                let radius = scale[0] * num(&w[3], "radius")?;
                if radius < 0.0 {
                    return Err(a.error_at(
                        &w[3],
                        format!("region sphere radius must be >= 0, found {}", w[3].text),
                        "negative radius",
                    ));
                }
                let ext = (
                    [center[0] - radius, center[1] - radius, center[2] - radius],
                    [center[0] + radius, center[1] + radius, center[2] + radius],
                );
                (Shape::Sphere { center, radius }, if interior { Some(ext) } else { None })
            }
            "cylinder" => {
                if let Some((ow, face)) = open_words.iter().find(|(_, f)| *f > 3) {
                    return Err(a.error_at(
                        ow,
                        format!("region cylinder has no open face {face} (faces are 1-3)"),
                        "invalid face",
                    ));
                }
                let axis = match w[0].text.as_str() {
                    "x" => 0,
                    "y" => 1,
                    "z" => 2,
                    _ => {
                        return Err(a.error_at(
                            &w[0],
                            format!("region cylinder axis must be x, y or z, found `{}`", w[0].text),
                            "invalid axis",
                        ))
                    }
                };
                let (d1, d2) = match axis {
                    0 => (1, 2),
                    1 => (0, 2),
                    _ => (0, 1),
                };
                let c1 = scale[d1] * num(&w[1], "c1")?;
                let c2 = scale[d2] * num(&w[2], "c2")?;
                let mut radius = num(&w[3], "radius")?;
                radius *= if axis == 0 { scale[1] } else { scale[0] };
                let lo = bound(&w[4], axis, false, "lo")?;
                let hi = bound(&w[5], axis, true, "hi")?;
                if radius <= 0.0 {
                    return Err(a.error_at(
                        &w[3],
                        format!("region cylinder radius must be > 0, found {}", w[3].text),
                        "radius must be > 0",
                    ));
                }
                let mut elo = [0.0; 3];
                let mut ehi = [0.0; 3];
                elo[axis] = lo;
                ehi[axis] = hi;
                elo[d1] = c1 - radius;
                ehi[d1] = c1 + radius;
                elo[d2] = c2 - radius;
                ehi[d2] = c2 + radius;
                (Shape::Cylinder { axis, c1, c2, radius, lo, hi }, if interior { Some((elo, ehi)) } else { None })
            }
            "prism" => {
                let mut lo = [0.0; 3];
                let mut hi = [0.0; 3];
                for d in 0..3 {
                    lo[d] = bound(&w[2 * d], d, false, ["xlo", "ylo", "zlo"][d])?;
                    hi[d] = bound(&w[2 * d + 1], d, true, ["xhi", "yhi", "zhi"][d])?;
                }
                let xy = scale[0] * num(&w[6], "xy")?;
                let xz = scale[0] * num(&w[7], "xz")?;
                let yz = scale[1] * num(&w[8], "yz")?;
                for d in 0..3 {
                    if lo[d] >= hi[d] {
                        return Err(a.error_at(
                            &w[2 * d],
                            "region prism must have non-zero thickness in every dimension (lo < hi)",
                            "lo >= hi",
                        ));
                    }
                }
                let inf = |d: usize| lo[d] == -BIG && hi[d] == BIG;
                for (k, (t, d1, d2)) in [(xy, 0, 1), (xz, 0, 2), (yz, 1, 2)].into_iter().enumerate() {
                    if t != 0.0 && (inf(d1) || inf(d2)) {
                        return Err(a.error_at(
                            &w[6 + k],
                            "region prism tilt must be 0 when a tilted dimension is INF at both ends",
                            "non-zero tilt",
                        ));
                    }
                }
                let h = [[hi[0] - lo[0], xy, xz], [0.0, hi[1] - lo[1], yz], [0.0, 0.0, hi[2] - lo[2]]];
                let mut hinv = [[0.0; 3]; 3];
                hinv[0][0] = 1.0 / h[0][0];
                hinv[0][1] = -h[0][1] / (h[0][0] * h[1][1]);
                hinv[0][2] = (h[0][1] * h[1][2] - h[0][2] * h[1][1]) / (h[0][0] * h[1][1] * h[2][2]);
                hinv[1][1] = 1.0 / h[1][1];
                hinv[1][2] = -h[1][2] / (h[1][1] * h[2][2]);
                hinv[2][2] = 1.0 / h[2][2];
                let min = |p: f64, q: f64| if p < q { p } else { q };
                let max = |p: f64, q: f64| if p > q { p } else { q };
                let exlo = min(lo[0], lo[0] + xy);
                let exlo = min(exlo, exlo + xz);
                let exhi = max(hi[0], hi[0] + xy);
                let exhi = max(exhi, exhi + xz);
                let ext = ([exlo, min(lo[1], lo[1] + yz), lo[2]], [exhi, max(hi[1], hi[1] + yz), hi[2]]);
                (Shape::Prism { lo, hi, tilt: [xy, xz, yz], hinv }, if interior { Some(ext) } else { None })
            }
            "plane" => {
                let point = [scale[0] * num(&w[0], "px")?, scale[1] * num(&w[1], "py")?, scale[2] * num(&w[2], "pz")?];
                let mut n = [scale[0] * num(&w[3], "nx")?, scale[1] * num(&w[4], "ny")?, scale[2] * num(&w[5], "nz")?];
                let rsq = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
                if rsq == 0.0 {
                    return Err(a.error_at(&w[3], "region plane normal vector must not be zero", "zero normal"));
                }
                for c in &mut n {
                    *c /= rsq.sqrt();
                }
                (Shape::Plane { point, normal: n }, None)
            }
            _ => {
                // union / intersect: the sub-regions, looked up by ID.
                let mut subs = vec![];
                for sw in w {
                    match existing.iter().find(|r| r.id == sw.text) {
                        Some(r) => subs.push(r.clone()),
                        None => {
                            return Err(a.error_at(
                                sw,
                                format!("region {style} sub-region `{}` does not exist", sw.text),
                                "unknown region ID",
                            ))
                        }
                    }
                }
                let ext = if style == "union" {
                    // Bounding box only if every sub-region has one.
                    if interior && subs.iter().all(|r| r.extent.is_some()) {
                        let mut lo = [BIG; 3];
                        let mut hi = [-BIG; 3];
                        for r in &subs {
                            let (rlo, rhi) = r.extent.unwrap();
                            for d in 0..3 {
                                lo[d] = if lo[d] < rlo[d] { lo[d] } else { rlo[d] };
                                hi[d] = if hi[d] > rhi[d] { hi[d] } else { rhi[d] };
                            }
                        }
                        Some((lo, hi))
                    } else {
                        None
                    }
                } else {
                    // Bounding box = overlap of the sub-regions that have one.
                    let mut ext: Option<([f64; 3], [f64; 3])> = None;
                    if interior {
                        for (rlo, rhi) in subs.iter().filter_map(|r| r.extent) {
                            let (mut lo, mut hi) = ext.unwrap_or((rlo, rhi));
                            for d in 0..3 {
                                lo[d] = if lo[d] > rlo[d] { lo[d] } else { rlo[d] };
                                hi[d] = if hi[d] < rhi[d] { hi[d] } else { rhi[d] };
                            }
                            ext = Some((lo, hi));
                        }
                    }
                    ext
                };
                let shape = if style == "union" { Shape::Union(subs) } else { Shape::Intersect(subs) };
                (shape, ext)
            }
        };
        Ok(Region { id, style: style.to_string(), shape, interior, open_faces, extent })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::domain::BoundaryKind;
    use crate::engine::lattice::tests::cmd;
    use crate::engine::units::{UnitStyle, Units};

    fn boxed(lo: [f64; 3], hi: [f64; 3]) -> Domain {
        Domain { dimension: 3, lo, hi, boundary: [[BoundaryKind::Periodic; 2]; 3] }
    }

    fn reg(line: &str, d: Option<&Domain>, l: Option<&Lattice>, ex: &[Region]) -> DResult<Region> {
        Region::from_lammps(&cmd(line), d, l, ex)
    }

    #[test]
    fn block_is_closed_and_scaled_by_lattice() {
        let l = Lattice::from_lammps(&cmd("lattice sc 2.0"), &Units::new(UnitStyle::Si), 3).unwrap();
        let r = reg("region b block 0 1 0 1 0 1", None, Some(&l), &[]).unwrap();
        assert!(r.matches([2.0, 2.0, 0.0]) && !r.matches([2.0000001, 1.0, 1.0]));
        assert_eq!(r.extent(), Some(([0.0; 3], [2.0; 3])));
        let r = reg("region b block 0 1 0 1 0 1 units box side out", None, Some(&l), &[]).unwrap();
        assert!(!r.matches([1.0, 1.0, 1.0]) && r.matches([1.5, 0.5, 0.5]) && r.extent().is_none());
    }

    #[test]
    fn edge_and_inf_need_a_box() {
        let e = reg("region w block 0 1 0 1 EDGE EDGE units box", None, None, &[]).unwrap_err();
        assert!(e.message.contains("box does not exist"));
        let d = boxed([-0.035, -0.035, -0.005], [3.255, 1.8, 0.005]);
        let r = reg("region w block 0 1 0 1 EDGE INF units box", Some(&d), None, &[]).unwrap();
        assert_eq!(r.extent(), Some(([0.0, 0.0, -0.005], [1.0, 1.0, 1e20])));
        assert!(reg("region w block -INF 1 0 1 0 1 units box", Some(&d), None, &[]).is_err());
    }

    #[test]
    fn sphere_cylinder_plane_prism() {
        let s = reg("region s sphere 1 1 1 1 units box", None, None, &[]).unwrap();
        assert!(s.matches([2.0, 1.0, 1.0]) && !s.matches([1.8, 1.8, 1.0]));
        let c = reg("region c cylinder z 1 1 1 0 2 units box", None, None, &[]).unwrap();
        assert!(c.matches([1.0, 2.0, 2.0]) && !c.matches([1.0, 1.0, 2.1]));
        assert_eq!(c.extent(), Some(([0.0, 0.0, 0.0], [2.0, 2.0, 2.0])));
        let p = reg("region p plane 1 0 0 -1 0 0 units box", None, None, &[]).unwrap();
        assert!(p.matches([1.0, 5.0, 5.0]) && !p.matches([1.5, 0.0, 0.0]) && p.extent().is_none());
        let q = reg("region q prism 0 2 0 2 0 2 1 0 0 units box", None, None, &[]).unwrap();
        assert!(q.matches([2.8, 1.8, 0.5]) && !q.matches([0.1, 1.8, 0.5]));
        assert_eq!(q.extent(), Some(([0.0, 0.0, 0.0], [3.0, 2.0, 2.0])));
    }

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
    fn open_face_matches_everything() {
        // LAMMPS: a region with an open face matches all points, even with side out.
        let r = reg("region r block 0 2 0 2 0 2 units box open 1 side out", None, None, &[]).unwrap();
        assert!(r.matches([10.0, 10.0, 10.0]) && r.matches([1.0, 1.0, 1.0]));
    }

    #[test]
    fn dynamic_and_unknown_are_rejected() {
        let e = reg("region r block 0 1 0 1 0 1 move v_x NULL NULL", None, None, &[]).unwrap_err();
        assert!(e.message.contains("not supported"));
        let e = reg("region r blok 0 1 0 1 0 1", None, None, &[]).unwrap_err();
        assert!(e.help[0].contains("block"), "{:?}", e.help);
        let e = reg("region r sphere 0 0 0", None, None, &[]).unwrap_err();
        assert!(e.message.contains("missing"));
    }
}
