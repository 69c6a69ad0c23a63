//! `region ID ellipsoid x y z a b c`: an axis-aligned ellipsoid with centre (x, y, z) and half
//! axes a, b, c (each may be a variable). In 2D only x and y count, as LAMMPS' `inside`.
//!
//! No wall contacts: LAMMPS' RegEllipsoid surface functions (the version read, lammps/lammps
//! src/region_ellipsoid.cpp) return the nearest surface point itself where a contact's
//! displacement belongs, and leave its radius unset, so fix wall/gran/region and wall/region
//! would push along the wrong vector; dmhs refuses them on an ellipsoid (a located "does not
//! support region style ellipsoid" error).

use super::{fixed, Shape, ShapeArgs, Style, Vec3};
use dmhs_parser::DResult;

pub const STYLE: Style = Style { syntax: "ellipsoid x y z a b c", vars: &[0, 1, 2, 3, 4, 5], nargs: fixed::<6>, parse };

#[derive(Debug)]
struct Ellipsoid {
    center: Vec3,
    /// half axes a, b, c
    half: Vec3,
    dimension: usize,
}

fn parse(s: &ShapeArgs) -> DResult<Box<dyn Shape>> {
    let center = s.point(0, ["x", "y", "z"])?;
    let half = s.point(3, ["a", "b", "c"])?;
    if let Some(k) = (0..3).find(|&k| half[k] < 0.0) {
        let w = &s.words[3 + k];
        return Err(s.error(w, format!("region ellipsoid half axis {} must be >= 0, found {}", ["a", "b", "c"][k], half[k]), "negative half axis"));
    }
    let dimension = s.domain.map_or(3, |d| d.dimension);
    Ok(Box::new(Ellipsoid { center, half, dimension }))
}

impl Shape for Ellipsoid {
    /// LAMMPS' test, free of divisions: (b c dx)^2 + (a c dy)^2 + (a b dz)^2 <= (a b c)^2.
    fn inside(&self, x: &Vec3) -> bool {
        let (a, b, c) = (self.half[0], self.half[1], self.half[2]);
        let (xc, yc, zc) = (self.center[0], self.center[1], self.center[2]);
        if self.dimension == 3 {
            let delx = b * c * (x[0] - xc);
            let dely = a * c * (x[1] - yc);
            let delz = a * b * (x[2] - zc);
            delx * delx + dely * dely + delz * delz <= a * a * b * b * c * c
        } else {
            let delx = b * (x[0] - xc);
            let dely = a * (x[1] - yc);
            delx * delx + dely * dely <= a * a * b * b
        }
    }

    fn extent(&self) -> Option<(Vec3, Vec3)> {
        Some((self.center - self.half, self.center + self.half))
    }
}

#[cfg(test)]
mod tests {
    use crate::engine::region::tests::reg;

    #[test]
    fn ellipsoid_surface_is_inside() {
        let e = reg("region e ellipsoid 1 1 1 2 1 0.5 units box", None, None, &[]).unwrap();
        assert!(e.matches([3.0, 1.0, 1.0]) && e.matches([1.0, 1.0, 1.5]) && !e.matches([1.0, 1.0, 1.6]));
        assert_eq!(e.extent(), Some(([-1.0, 0.0, 0.5], [3.0, 2.0, 1.5])));
        let err = reg("region e ellipsoid 0 0 0 1 -1 1 units box", None, None, &[]).unwrap_err();
        assert!(err.message.contains("half axis b must be >= 0"), "{}", err.message);
        assert_eq!(e.without_surface(), Some("ellipsoid"));
    }
}
