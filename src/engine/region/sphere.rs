//! `region ID sphere x y z r`: a ball (the radius scales with the x lattice spacing, as LAMMPS).

use super::{fixed, Shape, ShapeArgs, Style, Vec3};
use dmhs_parser::DResult;

pub const STYLE: Style = Style { syntax: "sphere x y z r", nargs: fixed::<4>, parse };

#[derive(Debug)]
struct Sphere {
    center: Vec3,
    radius: f64,
}

fn parse(s: &ShapeArgs) -> DResult<Box<dyn Shape>> {
    let center = s.point(0, ["x", "y", "z"])?;
    let radius = s.scaled(3, 0, "radius")?;
    if radius < 0.0 {
        let w = &s.words[3];
        return Err(s.error(w, format!("region sphere radius must be >= 0, found {}", w.text), "negative radius"));
    }
    Ok(Box::new(Sphere { center, radius }))
}

impl Shape for Sphere {
    fn inside(&self, x: &Vec3) -> bool {
        // |x - c| summed x, y, z as LAMMPS' RegSphere (nalgebra's norm keeps that order)
        (x - self.center).norm() <= self.radius
    }

    fn extent(&self) -> Option<(Vec3, Vec3)> {
        let r = Vec3::repeat(self.radius);
        Some((self.center - r, self.center + r))
    }
}

#[cfg(test)]
mod tests {
    use crate::engine::region::tests::reg;

    #[test]
    fn sphere_surface_is_inside() {
        let s = reg("region s sphere 1 1 1 1 units box", None, None, &[]).unwrap();
        assert!(s.matches([2.0, 1.0, 1.0]) && !s.matches([1.8, 1.8, 1.0]));
        assert_eq!(s.extent(), Some(([0.0; 3], [2.0; 3])));
        let e = reg("region s sphere 1 1 1 -1 units box", None, None, &[]).unwrap_err();
        assert!(e.message.contains("radius must be >= 0"));
    }
}
