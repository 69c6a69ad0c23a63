//! `region ID plane px py pz nx ny nz`: the half space on the side the normal points to.

use super::{fixed, Shape, ShapeArgs, Style, Vec3, WallContact};
use dmhs_parser::DResult;

pub const STYLE: Style = Style { syntax: "plane px py pz nx ny nz", vars: &[0, 1, 2, 3, 4, 5], nargs: fixed::<6>, parse };

#[derive(Debug)]
struct Plane {
    point: Vec3,
    /// Unit normal.
    normal: Vec3,
}

fn parse(s: &ShapeArgs) -> DResult<Box<dyn Shape>> {
    let variables = s.words[3..6].iter().filter(|w| w.text.starts_with("v_")).count();
    if variables != 0 && variables != 3 {
        return Err(s.error(&s.words[3], "region plane: the components of the normal vector must be all variables or all constants", "mixed normal"));
    }
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

    fn has_surface(&self) -> bool {
        true
    }

    /// The plane seen from the normal side: one contact if 0 <= distance < cutoff.
    fn surface_interior(&self, x: &Vec3, cutoff: f64, _open: &[bool; 6], out: &mut Vec<WallContact>) {
        self.contact(self.distance(x), 1.0, cutoff, out);
    }

    /// The plane seen from the other side.
    fn surface_exterior(&self, x: &Vec3, cutoff: f64, _open: &[bool; 6], out: &mut Vec<WallContact>) {
        self.contact(-self.distance(x), -1.0, cutoff, out);
    }

    fn contact_counts(&self, _interior: bool) -> (usize, usize) {
        (1, 1)
    }
}

impl Plane {
    /// Signed distance along the normal, summed x, y, z as LAMMPS' RegPlane.
    fn distance(&self, x: &Vec3) -> f64 {
        let (p, n) = (&self.point, &self.normal);
        (x[0] - p[0]) * n[0] + (x[1] - p[1]) * n[1] + (x[2] - p[2]) * n[2]
    }

    /// A contact at distance `dot` on the side `sign` of the normal (wall 0, flat).
    fn contact(&self, dot: f64, sign: f64, cutoff: f64, out: &mut Vec<WallContact>) {
        if dot < cutoff && dot >= 0.0 {
            let n = &self.normal;
            let s = sign * dot;
            out.push(WallContact { r: dot, del: [s * n[0], s * n[1], s * n[2]], radius: 0.0, iwall: 0, ..WallContact::default() });
        }
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

    #[test]
    fn one_flat_contact_on_each_side() {
        let mut out = vec![];
        let p = reg("region p plane 0 0 1 0 0 2 units box", None, None, &[]).unwrap();
        p.surface([3.0, 4.0, 1.25], 0.5, &mut out);
        assert_eq!((out.len(), out[0].r, out[0].del), (1, 0.25, [0.0, 0.0, 0.25]));
        // on the other side (or beyond the cutoff) nothing from inside
        p.surface([3.0, 4.0, 0.75], 0.5, &mut out);
        assert!(out.is_empty());
        let q = reg("region q plane 0 0 1 0 0 2 side out units box", None, None, &[]).unwrap();
        q.surface([3.0, 4.0, 0.75], 0.5, &mut out);
        assert_eq!((out.len(), out[0].r, out[0].del), (1, 0.25, [0.0, 0.0, -0.25]));
        q.surface([3.0, 4.0, 1.25], 0.5, &mut out);
        assert!(out.is_empty());
    }
}
