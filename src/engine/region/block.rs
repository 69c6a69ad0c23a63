//! `region ID block xlo xhi ylo yhi zlo zhi`: an axis-aligned box; bounds may be INF or EDGE.

use super::{fixed, Shape, ShapeArgs, Style, Vec3};
use dmhs_parser::DResult;

pub const STYLE: Style = Style { syntax: "block xlo xhi ylo yhi zlo zhi", nargs: fixed::<6>, parse };

#[derive(Debug)]
struct Block {
    lo: Vec3,
    hi: Vec3,
}

fn parse(s: &ShapeArgs) -> DResult<Box<dyn Shape>> {
    let (lo, hi) = s.box_bounds()?;
    for d in 0..3 {
        if lo[d] > hi[d] {
            let axis = "xyz".as_bytes()[d] as char;
            return Err(s.error(
                &s.words[2 * d],
                format!("region block {axis}lo {} > {axis}hi {}", lo[d], hi[d]),
                "lower bound above upper bound",
            ));
        }
    }
    Ok(Box::new(Block { lo, hi }))
}

impl Shape for Block {
    fn inside(&self, x: &Vec3) -> bool {
        (0..3).all(|d| x[d] >= self.lo[d] && x[d] <= self.hi[d])
    }

    fn extent(&self) -> Option<(Vec3, Vec3)> {
        Some((self.lo, self.hi))
    }

    fn simple(&self) -> Option<super::Simple> {
        Some(super::Simple::Block { lo: self.lo.into(), hi: self.hi.into() })
    }
}

#[cfg(test)]
mod tests {
    use crate::engine::lattice::tests::cmd;
    use crate::engine::lattice::Lattice;
    use crate::engine::region::tests::reg;
    use crate::engine::units::{UnitStyle, Units};

    #[test]
    fn block_is_closed_and_scaled_by_lattice() {
        let l = Lattice::from_lammps(&cmd("lattice sc 2.0"), &Units::new(UnitStyle::Si), 3).unwrap();
        let r = reg("region b block 0 1 0 1 0 1", None, Some(&l), &[]).unwrap();
        assert!(r.matches([2.0, 2.0, 0.0]) && !r.matches([2.0000001, 1.0, 1.0]));
        assert_eq!(r.extent(), Some(([0.0; 3], [2.0; 3])));
    }

    #[test]
    fn bounds_must_be_ordered() {
        let e = reg("region b block 0 1 2 1 0 1 units box", None, None, &[]).unwrap_err();
        assert_eq!(e.message, "region block ylo 2 > yhi 1");
    }
}
