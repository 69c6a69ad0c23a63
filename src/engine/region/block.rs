//! `region ID block xlo xhi ylo yhi zlo zhi`: an axis-aligned box; bounds may be INF or EDGE.

use super::{fixed, point_on_segment, Shape, ShapeArgs, Style, Vec3, WallContact, BIG};
use dmhs_parser::DResult;

pub const STYLE: Style = Style { syntax: "block xlo xhi ylo yhi zlo zhi", vars: &[0, 1, 2, 3, 4, 5], nargs: fixed::<6>, parse };

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

    fn has_surface(&self) -> bool {
        true
    }

    /// One contact per face closer than the cutoff: faces xlo xhi ylo yhi zlo zhi are walls 0-5.
    fn surface_interior(&self, x: &Vec3, cutoff: f64, open: &[bool; 6], out: &mut Vec<WallContact>) {
        if !self.inside(x) {
            return;
        }
        for d in 0..3 {
            let delta = x[d] - self.lo[d];
            if delta < cutoff && !open[2 * d] {
                out.push(WallContact::face(d, delta, 1.0, 2 * d));
            }
            let delta = self.hi[d] - x[d];
            if delta < cutoff && !open[2 * d + 1] {
                out.push(WallContact::face(d, delta, -1.0, 2 * d + 1));
            }
        }
    }

    /// The nearest point of the block (a face, edge or corner; of the closed faces if some are
    /// open), wall 0.
    fn surface_exterior(&self, x: &Vec3, cutoff: f64, open: &[bool; 6], out: &mut Vec<WallContact>) {
        let (lo, hi) = (&self.lo, &self.hi);
        if (0..3).any(|d| x[d] <= lo[d] - cutoff || x[d] >= hi[d] + cutoff) {
            return;
        }
        if (0..3).all(|d| x[d] > lo[d] && x[d] < hi[d]) {
            return;
        }
        let mut p = [0.0; 3];
        if !open.contains(&true) {
            for d in 0..3 {
                p[d] = if x[d] < lo[d] { lo[d] } else if x[d] > hi[d] { hi[d] } else { x[d] };
            }
        } else {
            let mut mindist = BIG;
            for face in 0..6 {
                if open[face] {
                    continue;
                }
                let (dist, c) = self.closest_on_face(face, x);
                if dist < mindist {
                    p = c;
                    mindist = dist;
                }
            }
        }
        let c = WallContact::to_point(x, p);
        if c.r < cutoff {
            out.push(c);
        }
    }

    fn contact_counts(&self, interior: bool) -> (usize, usize) {
        (6, if interior { 3 } else { 1 })
    }
}

impl Block {
    /// The corners of face `i` in LAMMPS' order (its `corners[i][0..4]`).
    fn corners(&self, i: usize) -> [[f64; 3]; 4] {
        let (l, h) = (&self.lo, &self.hi);
        let c = |a: f64, b: f64, z: f64| [a, b, z];
        let f0 = [c(l[0], l[1], l[2]), c(l[0], l[1], h[2]), c(l[0], h[1], h[2]), c(l[0], h[1], l[2])];
        let f1 = [c(h[0], l[1], l[2]), c(h[0], l[1], h[2]), c(h[0], h[1], h[2]), c(h[0], h[1], l[2])];
        match i {
            0 => f0,
            1 => f1,
            2 => [f0[0], f1[0], f1[1], f0[1]],
            3 => [f0[3], f0[2], f1[2], f1[3]],
            4 => [f0[0], f0[3], f1[3], f1[0]],
            _ => [f0[1], f1[1], f1[2], f0[2]],
        }
    }

    /// LAMMPS `find_closest_point`: squared distance to face `i` and the point, by projection
    /// onto the face if it falls inside, else the nearest point of its four edges.
    fn closest_on_face(&self, i: usize, x: &Vec3) -> (f64, [f64; 3]) {
        let corners = self.corners(i);
        let mut normal = [0.0; 3];
        normal[i / 2] = if i % 2 == 0 { -1.0 } else { 1.0 };
        let c0 = corners[0];
        let xr = [x[0] - c0[0], x[1] - c0[1], x[2] - c0[2]];
        let dot = normal[0] * xr[0] + normal[1] * xr[1] + normal[2] * xr[2];
        let xproj = [xr[0] - dot * normal[0], xr[1] - dot * normal[1], xr[2] - dot * normal[2]];
        // the projection is inside the face: strictly between the bounds of its two axes
        let (a, b) = match i / 2 {
            0 => (1, 2),
            1 => (0, 2),
            _ => (0, 1),
        };
        let size = self.hi - self.lo;
        if xproj[a] > 0.0 && xproj[a] < size[a] && xproj[b] > 0.0 && xproj[b] < size[b] {
            return (dot * dot, [xproj[0] + c0[0], xproj[1] + c0[1], xproj[2] + c0[2]]);
        }
        let mut best = (BIG, [0.0; 3]);
        let xa: [f64; 3] = (*x).into();
        for k in 0..4 {
            let p = point_on_segment(&corners[k], &corners[(k + 1) % 4], &xa);
            let d2 = (p[0] - xa[0]) * (p[0] - xa[0]) + (p[1] - xa[1]) * (p[1] - xa[1]) + (p[2] - xa[2]) * (p[2] - xa[2]);
            if d2 < best.0 {
                best = (d2, p);
            }
        }
        best
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
