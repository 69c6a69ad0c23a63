//! `region ID cylinder dim c1 c2 r lo hi`: a right circular cylinder along x, y or z; `c1 c2`
//! is the axis position in the other two dimensions (in x, y, z order), `lo hi` its extent
//! along the axis (INF or EDGE allowed). Faces for `open`: 1 and 2 the ends, 3 the side.

use super::{fixed, Shape, ShapeArgs, Style, Vec3, WallContact, BIG};
use dmhs_parser::DResult;

pub const STYLE: Style = Style { syntax: "cylinder dim c1 c2 r lo hi", vars: &[1, 2, 3], nargs: fixed::<6>, parse };

#[derive(Debug)]
struct Cylinder {
    axis: usize,
    /// A point on the axis (its axial component is 0).
    center: Vec3,
    radius: f64,
    lo: f64,
    hi: f64,
}

fn parse(s: &ShapeArgs) -> DResult<Box<dyn Shape>> {
    if let Some((ow, face)) = s.open.iter().find(|(_, f)| *f > 3) {
        return Err(s.error(ow, format!("region cylinder has no open face {face} (faces are 1-3)"), "invalid face"));
    }
    let w = &s.words[0];
    let axis = match w.text.as_str() {
        "x" => 0,
        "y" => 1,
        "z" => 2,
        _ => {
            return Err(s.error(w, format!("region cylinder axis must be x, y or z, found `{}`", w.text), "invalid axis"))
        }
    };
    let (d1, d2) = match axis {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    };
    let mut center = Vec3::zeros();
    center[d1] = s.scaled(1, d1, "c1")?;
    center[d2] = s.scaled(2, d2, "c2")?;
    // LAMMPS scales the radius by the y spacing for an x axis, by the x spacing otherwise
    let radius = s.scaled(3, if axis == 0 { 1 } else { 0 }, "radius")?;
    let lo = s.bound(4, axis, false, "lo")?;
    let hi = s.bound(5, axis, true, "hi")?;
    if radius <= 0.0 {
        let w = &s.words[3];
        return Err(s.error(w, format!("region cylinder radius must be > 0, found {}", w.text), "radius must be > 0"));
    }
    Ok(Box::new(Cylinder { axis, center, radius, lo, hi }))
}

impl Shape for Cylinder {
    fn inside(&self, x: &Vec3) -> bool {
        // distance from the axis: the offset without its axial component (the zero adds exactly)
        let mut radial = x - self.center;
        radial[self.axis] = 0.0;
        radial.norm() <= self.radius && x[self.axis] >= self.lo && x[self.axis] <= self.hi
    }

    fn extent(&self) -> Option<(Vec3, Vec3)> {
        let r = Vec3::repeat(self.radius);
        let (mut lo, mut hi) = (self.center - r, self.center + r);
        lo[self.axis] = self.lo;
        hi[self.axis] = self.hi;
        Some((lo, hi))
    }

    fn shape_frame(&self) -> Option<super::ShapeFrame> {
        Some(super::ShapeFrame { center: self.center.into(), radius: self.radius, axis: Some(self.axis) })
    }

    fn simple(&self) -> Option<super::Simple> {
        Some(super::Simple::Cylinder { axis: self.axis, center: self.center.into(), radius: self.radius, lo: self.lo, hi: self.hi })
    }

    fn has_surface(&self) -> bool {
        true
    }

    /// The curved side (wall 2, radius of curvature -2R; none on the axis), then the lo and hi
    /// ends (walls 0 and 1).
    fn surface_interior(&self, x: &Vec3, cutoff: f64, open: &[bool; 6], out: &mut Vec<WallContact>) {
        let (a, d1, d2) = self.axes();
        let del1 = x[d1] - self.center[d1];
        let del2 = x[d2] - self.center[d2];
        let r = (del1 * del1 + del2 * del2).sqrt();
        if r > self.radius || x[a] < self.lo || x[a] > self.hi {
            return;
        }
        let delta = self.radius - r;
        if delta < cutoff && r > 0.0 && !open[2] {
            let mut del = [0.0; 3];
            del[d1] = del1 * (1.0 - self.radius / r);
            del[d2] = del2 * (1.0 - self.radius / r);
            out.push(WallContact { r: delta, del, radius: -2.0 * self.radius, iwall: 2, vwall: [0.0; 3], varflag: true });
        }
        let delta = x[a] - self.lo;
        if delta < cutoff && !open[0] {
            out.push(WallContact::face(a, delta, 1.0, 0));
        }
        let delta = self.hi - x[a];
        if delta < cutoff && !open[1] {
            out.push(WallContact::face(a, delta, -1.0, 1));
        }
    }

    /// The nearest point of the outside (curvature 2R on the curved side, 0 elsewhere; 0 also
    /// when a face is open, as LAMMPS), wall 0.
    fn surface_exterior(&self, x: &Vec3, cutoff: f64, open: &[bool; 6], out: &mut Vec<WallContact>) {
        let (a, d1, d2) = self.axes();
        let (c1, c2, radius, lo, hi) = (self.center[d1], self.center[d2], self.radius, self.lo, self.hi);
        let del1 = x[d1] - c1;
        let del2 = x[d2] - c2;
        let r = (del1 * del1 + del2 * del2).sqrt();
        if r >= radius + cutoff || x[a] <= lo - cutoff || x[a] >= hi + cutoff {
            return;
        }
        if r < radius && x[a] > lo && x[a] < hi {
            return;
        }
        let mut p = [0.0; 3];
        let mut crad = 0.0;
        if !open.contains(&true) {
            if r > radius {
                p[d1] = c1 + del1 * radius / r;
                p[d2] = c2 + del2 * radius / r;
                crad = 2.0 * radius;
            } else {
                p[d1] = x[d1];
                p[d2] = x[d2];
            }
            p[a] = if x[a] < lo { lo } else if x[a] > hi { hi } else { x[a] };
        } else {
            let dr = r - radius;
            let dr2 = dr * dr;
            let mut d2prev = BIG;
            if !open[2] {
                p[d1] = c1 + del1 * radius / r;
                p[d2] = c2 + del2 * radius / r;
                let dx;
                (dx, p[a]) = if x[a] < lo { (lo - x[a], lo) } else if x[a] > hi { (x[a] - hi, hi) } else { (0.0, x[a]) };
                d2prev = dr2 + dx * dx;
            }
            for (face, end) in [(0, lo), (1, hi)] {
                if open[face] {
                    continue;
                }
                let dx = end - x[a];
                let dsq = if r < radius { dx * dx } else { dr2 + dx * dx };
                if dsq < d2prev {
                    p[a] = end;
                    if r < radius {
                        p[d1] = x[d1];
                        p[d2] = x[d2];
                    }
                    d2prev = dsq;
                }
            }
        }
        let mut c = WallContact::to_point(x, p);
        c.radius = crad;
        // the curved side moves with a variable radius (LAMMPS sets varflag where it sets crad)
        c.varflag = crad != 0.0;
        if c.r < cutoff {
            out.push(c);
        }
    }

    fn contact_counts(&self, interior: bool) -> (usize, usize) {
        (3, if interior { 2 } else { 1 })
    }
}

impl Cylinder {
    /// The axis and the two other dimensions, in x, y, z order.
    fn axes(&self) -> (usize, usize, usize) {
        match self.axis {
            0 => (0, 1, 2),
            1 => (1, 0, 2),
            _ => (2, 0, 1),
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::engine::lattice::tests::cmd;
    use crate::engine::lattice::Lattice;
    use crate::engine::region::tests::reg;
    use crate::engine::units::{UnitStyle, Units};

    #[test]
    fn cylinder_along_each_axis() {
        let c = reg("region c cylinder z 1 1 1 0 2 units box", None, None, &[]).unwrap();
        assert!(c.matches([1.0, 2.0, 2.0]) && !c.matches([1.0, 1.0, 2.1]));
        assert_eq!(c.extent(), Some(([0.0, 0.0, 0.0], [2.0, 2.0, 2.0])));
        let c = reg("region c cylinder x 1 2 0.5 -1 1 units box", None, None, &[]).unwrap();
        assert!(c.matches([-1.0, 1.5, 2.0]) && !c.matches([0.0, 1.5, 2.6]));
        assert_eq!(c.extent(), Some(([-1.0, 0.5, 1.5], [1.0, 1.5, 2.5])));
    }

    #[test]
    fn radius_scales_with_y_spacing_along_x() {
        let l = Lattice::from_lammps(&cmd("lattice custom 1.0 a1 1 0 0 a2 0 2 0 a3 0 0 3 basis 0 0 0"), &Units::new(UnitStyle::Si), 3).unwrap();
        let c = reg("region c cylinder x 0 0 1 0 1", None, Some(&l), &[]).unwrap();
        assert_eq!(c.extent(), Some(([0.0, -2.0, -2.0], [1.0, 2.0, 2.0])));
    }

    #[test]
    fn bad_axis_face_and_radius() {
        let e = reg("region c cylinder w 0 0 1 0 1", None, None, &[]).unwrap_err();
        assert!(e.message.contains("axis must be x, y or z"));
        let e = reg("region c cylinder z 0 0 1 0 1 open 4", None, None, &[]).unwrap_err();
        assert_eq!(e.message, "region cylinder has no open face 4 (faces are 1-3)");
        let e = reg("region c cylinder z 0 0 0 0 1", None, None, &[]).unwrap_err();
        assert!(e.message.contains("radius must be > 0"));
    }
}
