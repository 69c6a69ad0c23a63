//! `region ID sphere x y z r`: a ball (the radius scales with the x lattice spacing, as LAMMPS).

use super::{fixed, Shape, ShapeArgs, Style, Vec3, WallContact};
use dmhs_parser::DResult;

pub const STYLE: Style = Style { syntax: "sphere x y z r", vars: &[0, 1, 2, 3], nargs: fixed::<4>, parse };

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

impl Sphere {
    /// The point minus the centre, and its length (summed x, y, z as LAMMPS).
    fn offset(&self, x: &Vec3) -> ([f64; 3], f64) {
        let del = [x[0] - self.center[0], x[1] - self.center[1], x[2] - self.center[2]];
        (del, (del[0] * del[0] + del[1] * del[1] + del[2] * del[2]).sqrt())
    }

    /// The contact `delta` from the surface along `del` (LAMMPS scales del by 1 - R/r).
    fn contact(&self, del: [f64; 3], r: f64, delta: f64, cutoff: f64, radius: f64, out: &mut Vec<WallContact>) {
        if delta < cutoff {
            let s = 1.0 - self.radius / r;
            out.push(WallContact { r: delta, del: [del[0] * s, del[1] * s, del[2] * s], radius, iwall: 0, vwall: [0.0; 3], varflag: true });
        }
    }
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

    fn has_surface(&self) -> bool {
        true
    }

    /// The one wall from inside (radius of curvature -R); none at the centre.
    fn surface_interior(&self, x: &Vec3, cutoff: f64, _open: &[bool; 6], out: &mut Vec<WallContact>) {
        let (del, r) = self.offset(x);
        if r > self.radius || r == 0.0 {
            return;
        }
        self.contact(del, r, self.radius - r, cutoff, -self.radius, out);
    }

    fn surface_exterior(&self, x: &Vec3, cutoff: f64, _open: &[bool; 6], out: &mut Vec<WallContact>) {
        let (del, r) = self.offset(x);
        if r < self.radius {
            return;
        }
        self.contact(del, r, r - self.radius, cutoff, self.radius, out);
    }

    fn contact_counts(&self, _interior: bool) -> (usize, usize) {
        (1, 1)
    }

    fn shape_frame(&self) -> Option<super::ShapeFrame> {
        Some(super::ShapeFrame { center: self.center.into(), radius: self.radius, axis: None })
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
