//! `region ID plane px py pz nx ny nz`: the half space on the side the normal points to.

use super::{fixed, Shape, ShapeArgs, Style, Vec3};
use dmhs_parser::DResult;

pub const STYLE: Style = Style { syntax: "plane px py pz nx ny nz", nargs: fixed::<6>, parse };

#[derive(Debug)]
struct Plane {
    point: Vec3,
    /// Unit normal.
    normal: Vec3,
}

fn parse(s: &ShapeArgs) -> DResult<Box<dyn Shape>> {
    let point = s.point(0, ["px", "py", "pz"])?;
    // LAMMPS scales the normal by the lattice spacings too
    let n = s.point(3, ["nx", "ny", "nz"])?;
    let len = n.norm();
    if len == 0.0 {
        return Err(s.error(&s.words[3], "region plane normal vector must not be zero", "zero normal"));
    }
    Ok(Box::new(Plane { point, normal: n / len }))
}

impl Shape for Plane {
    fn inside(&self, x: &Vec3) -> bool {
        (x - self.point).dot(&self.normal) >= 0.0
    }

    /// A half space is unbounded.
    fn extent(&self) -> Option<(Vec3, Vec3)> {
        None
    }
}

#[cfg(test)]
mod tests {
    use crate::engine::region::tests::reg;

    #[test]
    fn half_space_includes_the_plane() {
        let p = reg("region p plane 1 0 0 -1 0 0 units box", None, None, &[]).unwrap();
        assert!(p.matches([1.0, 5.0, 5.0]) && !p.matches([1.5, 0.0, 0.0]) && p.extent().is_none());
        let p = reg("region p plane 0 0 0 1 1 0 units box", None, None, &[]).unwrap();
        assert!(p.matches([1.0, -1.0, 3.0]) && !p.matches([1.0, -1.1, 0.0]));
        let e = reg("region p plane 0 0 0 0 0 0 units box", None, None, &[]).unwrap_err();
        assert!(e.message.contains("must not be zero"));
    }
}
