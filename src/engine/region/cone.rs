//! `region ID cone dim c1 c2 radlo radhi lo hi`: a truncated cone along x, y or z, radius radlo
//! at `lo` and radhi at `hi` (one of them may be 0; lo and hi may be INF or EDGE). Faces for
//! `open`: 1 the lo end, 2 the hi end, 3 the conical side. Wall contacts follow LAMMPS'
//! RegCone, including its y-axis ends, whose contacts point along z.

use super::{fixed, point_on_segment, Shape, ShapeArgs, Style, Vec3, WallContact, BIG};
use dmhs_parser::DResult;

pub const STYLE: Style = Style { syntax: "cone dim c1 c2 radlo radhi lo hi", vars: &[1, 2, 3, 4, 5, 6], nargs: fixed::<7>, parse };

#[derive(Debug)]
struct Cone {
    /// Axis and the other two dimensions in x, y, z order.
    dims: (usize, usize, usize),
    c1: f64,
    c2: f64,
    radiuslo: f64,
    radiushi: f64,
    lo: f64,
    hi: f64,
}

fn parse(s: &ShapeArgs) -> DResult<Box<dyn Shape>> {
    if let Some((ow, face)) = s.open.iter().find(|(_, f)| *f > 3) {
        return Err(s.error(ow, format!("region cone has no open face {face} (faces are 1-3)"), "invalid face"));
    }
    let w = &s.words[0];
    let dims = match w.text.as_str() {
        "x" => (0, 1, 2),
        "y" => (1, 0, 2),
        "z" => (2, 0, 1),
        _ => return Err(s.error(w, format!("region cone axis must be x, y or z, found `{}`", w.text), "invalid axis")),
    };
    let (a, d1, d2) = dims;
    // the radii scale with the y spacing for an x axis, with the x spacing otherwise (LAMMPS)
    let rdim = if a == 0 { 1 } else { 0 };
    let cone = Cone {
        dims,
        c1: s.scaled(1, d1, "c1")?,
        c2: s.scaled(2, d2, "c2")?,
        radiuslo: s.scaled(3, rdim, "radlo")?,
        radiushi: s.scaled(4, rdim, "radhi")?,
        lo: s.bound(5, a, false, "lo")?,
        hi: s.bound(6, a, true, "hi")?,
    };
    for (k, r) in [(3, cone.radiuslo), (4, cone.radiushi)] {
        if r < 0.0 {
            return Err(s.error(&s.words[k], format!("region cone radius must be >= 0, found {}", s.words[k].text), "negative radius"));
        }
    }
    if cone.radiuslo == 0.0 && cone.radiushi == 0.0 {
        return Err(s.error(&s.words[3], "region cone radii must not both be 0", "zero radii"));
    }
    if cone.hi <= cone.lo {
        return Err(s.error(&s.words[6], format!("region cone hi {} must be above lo {}", cone.hi, cone.lo), "empty cone"));
    }
    Ok(Box::new(cone))
}

impl Cone {
    fn radius_at(&self, h: f64) -> f64 {
        self.radiuslo + (h - self.lo) * (self.radiushi - self.radiuslo) / (self.hi - self.lo)
    }

    fn maxradius(&self) -> f64 {
        if self.radiuslo > self.radiushi { self.radiuslo } else { self.radiushi }
    }

    /// Offset from the axis and its length.
    fn radial(&self, x: &Vec3) -> (f64, f64, f64) {
        let (_, d1, d2) = self.dims;
        let del1 = x[d1] - self.c1;
        let del2 = x[d2] - self.c2;
        (del1, del2, (del1 * del1 + del2 * del2).sqrt())
    }

    /// The point at height `h` on the axis (`scale` 0) or on the rim of radius `rad` in the
    /// direction of the particle.
    fn at(&self, h: f64, del1: f64, del2: f64, rad: f64, r: f64) -> [f64; 3] {
        let (a, d1, d2) = self.dims;
        let mut p = [0.0; 3];
        p[a] = h;
        p[d1] = self.c1 + del1 * rad / r;
        p[d2] = self.c2 + del2 * rad / r;
        p
    }
}

/// LAMMPS `RegCone::closest`: `near` if it is closer than `dsq`.
fn closest(x: &[f64; 3], near: [f64; 3], nearest: &mut [f64; 3], dsq: f64) -> f64 {
    let d = [x[0] - near[0], x[1] - near[1], x[2] - near[2]];
    let rsq = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if rsq >= dsq {
        return dsq;
    }
    *nearest = near;
    rsq
}

impl Shape for Cone {
    fn inside(&self, x: &Vec3) -> bool {
        let a = self.dims.0;
        let (_, _, dist) = self.radial(x);
        dist <= self.radius_at(x[a]) && x[a] >= self.lo && x[a] <= self.hi
    }

    fn extent(&self) -> Option<(Vec3, Vec3)> {
        let (a, d1, d2) = self.dims;
        let m = self.maxradius();
        let (mut lo, mut hi) = (Vec3::zeros(), Vec3::zeros());
        lo[a] = self.lo;
        hi[a] = self.hi;
        lo[d1] = self.c1 - m;
        hi[d1] = self.c1 + m;
        lo[d2] = self.c2 - m;
        hi[d2] = self.c2 + m;
        Some((lo, hi))
    }

    fn has_surface(&self) -> bool {
        true
    }

    /// The conical side (wall 2, the nearest point of the side line in the particle's
    /// direction, curvature -2 radius there), then the lo and hi ends (walls 0 and 1).
    fn surface_interior(&self, x: &Vec3, cutoff: f64, open: &[bool; 6], out: &mut Vec<WallContact>) {
        let a = self.dims.0;
        let (del1, del2, r) = self.radial(x);
        if r > self.radius_at(x[a]) || x[a] < self.lo || x[a] > self.hi {
            return;
        }
        let xa: [f64; 3] = (*x).into();
        if r > 0.0 && !open[2] {
            let surflo = self.at(self.lo, del1, del2, self.radiuslo, r);
            let surfhi = self.at(self.hi, del1, del2, self.radiushi, r);
            let xs = point_on_segment(&surflo, &surfhi, &xa);
            let del = [xa[0] - xs[0], xa[1] - xs[1], xa[2] - xs[2]];
            let dist = (del[0] * del[0] + del[1] * del[1] + del[2] * del[2]).sqrt();
            if dist < cutoff {
                out.push(WallContact { r: dist, del, radius: -2.0 * self.radius_at(xs[a]), iwall: 2, ..WallContact::default() });
            }
        }
        // LAMMPS' y-axis cone puts its end contacts along z
        let cap = if a == 1 { 2 } else { a };
        let delta = x[a] - self.lo;
        if delta < cutoff && !open[0] {
            out.push(WallContact::face(cap, delta, 1.0, 0));
        }
        let delta = self.hi - x[a];
        if delta < cutoff && !open[1] {
            out.push(WallContact::face(cap, delta, -1.0, 1));
        }
    }

    /// The nearest point of the side line and the end radii in the particle's half plane
    /// (curvature -2 radius on the side, 0 on an end, as LAMMPS), wall 0.
    fn surface_exterior(&self, x: &Vec3, cutoff: f64, open: &[bool; 6], out: &mut Vec<WallContact>) {
        let a = self.dims.0;
        let (del1, del2, r) = self.radial(x);
        if r >= self.maxradius() + cutoff || x[a] <= self.lo - cutoff || x[a] >= self.hi + cutoff {
            return;
        }
        if r < self.radius_at(x[a]) && x[a] > self.lo && x[a] < self.hi {
            return;
        }
        let corner1 = self.at(self.lo, del1, del2, self.radiuslo, r);
        let corner2 = self.at(self.hi, del1, del2, self.radiushi, r);
        let axis_at = |h: f64| {
            let (a, d1, d2) = self.dims;
            let mut p = [0.0; 3];
            p[a] = h;
            p[d1] = self.c1;
            p[d2] = self.c2;
            p
        };
        let (corner3, corner4) = (axis_at(self.lo), axis_at(self.hi));
        let xa: [f64; 3] = (*x).into();
        let mut nearest = [0.0; 3];
        let mut distsq = BIG;
        let mut crad = 0.0;
        if !open[2] {
            distsq = closest(&xa, point_on_segment(&corner1, &corner2, &xa), &mut nearest, distsq);
            crad = -2.0 * self.radius_at(nearest[a]);
        }
        for (face, (p, q)) in [(0, (corner1, corner3)), (1, (corner2, corner4))] {
            if !open[face] {
                let prev = distsq;
                distsq = closest(&xa, point_on_segment(&p, &q, &xa), &mut nearest, distsq);
                if distsq < prev {
                    crad = 0.0;
                }
            }
        }
        if distsq == BIG {
            return;
        }
        let mut c = WallContact::to_point(x, nearest);
        c.radius = crad;
        if c.r < cutoff {
            out.push(c);
        }
    }

    fn contact_counts(&self, interior: bool) -> (usize, usize) {
        (3, if interior { 2 } else { 1 })
    }
}

#[cfg(test)]
mod tests {
    use crate::engine::region::tests::reg;
    use crate::engine::region::WallContact;

    #[test]
    fn funnel_cone_inside_and_walls() {
        let c = reg("region c cone z 0 0 2 20 10 50 units box open 1 open 2", None, None, &[]).unwrap();
        // radius 11 at z = 30
        assert!(c.matches([100.0, 0.0, 0.0]), "open faces match everything");
        let c = reg("region c cone z 0 0 2 20 10 50 units box", None, None, &[]).unwrap();
        assert!(c.matches([10.9, 0.0, 30.0]) && !c.matches([11.1, 0.0, 30.0]) && !c.matches([0.0, 0.0, 9.9]));
        assert_eq!(c.extent(), Some(([-20.0, -20.0, 10.0], [20.0, 20.0, 50.0])));
        let mut out: Vec<WallContact> = vec![];
        c.surface([10.8, 0.0, 30.0], 0.5, &mut out);
        assert_eq!(out.len(), 1);
        assert!(out[0].r > 0.0 && out[0].r < 0.2 && out[0].iwall == 2 && out[0].radius < 0.0, "{out:?}");
        c.surface([1.0, 0.0, 10.3], 0.5, &mut out);
        assert_eq!(out.iter().map(|c| c.iwall).collect::<Vec<_>>(), vec![0]);
        let e = reg("region c cone z 0 0 0 0 0 1 units box", None, None, &[]).unwrap_err();
        assert!(e.message.contains("both be 0"));
        let e = reg("region c cone z 0 0 1 2 0 1 units box open 4", None, None, &[]).unwrap_err();
        assert!(e.message.contains("no open face 4"));
    }
}
