//! `region ID prism xlo xhi ylo yhi zlo zhi xy xz yz`: a parallelepiped with lower corner
//! `(xlo, ylo, zlo)`, edges `hi - lo` along the axes sheared by the tilts `xy xz yz`.

use super::{fixed, point_on_segment, Shape, ShapeArgs, Style, Vec3, WallContact, BIG};
use dmhs_parser::DResult;
use nalgebra::Matrix3;

pub const STYLE: Style = Style { syntax: "prism xlo xhi ylo yhi zlo zhi xy xz yz", vars: &[0, 1, 2, 3, 4, 5, 6, 7, 8], nargs: fixed::<9>, parse };

#[derive(Debug)]
struct Prism {
    lo: Vec3,
    hi: Vec3,
    /// xy, xz, yz
    tilt: Vec3,
    /// Maps `x - lo` to the prism's own coordinates, each in [0, 1] inside.
    hinv: Matrix3<f64>,
    /// The 8 corners, x varying fastest, then y, then z (LAMMPS' `corners`).
    corners: [[f64; 3]; 8],
    /// Inward unit normals of the faces in LAMMPS' order: z lo/hi (the xy plane), y lo/hi,
    /// x lo/hi; an even face passes through the lower corner, an odd one through the upper.
    face: [[f64; 3]; 6],
}

/// The corners of the 12 triangles, two per face in face order, ordered so that the right-hand
/// rule gives the inward normal (LAMMPS' `tri`).
const TRI: [[usize; 3]; 12] =
    [[0, 1, 3], [0, 3, 2], [4, 7, 5], [4, 6, 7], [0, 4, 5], [0, 5, 1], [2, 7, 6], [2, 3, 7], [2, 6, 4], [2, 4, 0], [1, 5, 7], [1, 7, 3]];

/// Which `open` face (block numbering: xlo xhi ylo yhi zlo zhi) each prism face is.
const OPEN_FACE: [usize; 6] = [4, 5, 2, 3, 0, 1];

fn cross(u: &[f64; 3], v: &[f64; 3]) -> [f64; 3] {
    [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
}

fn dot(u: &[f64; 3], v: &[f64; 3]) -> f64 {
    u[0] * v[0] + u[1] * v[1] + u[2] * v[2]
}

fn sub(u: &[f64; 3], v: &[f64; 3]) -> [f64; 3] {
    [u[0] - v[0], u[1] - v[1], u[2] - v[2]]
}

fn parse(s: &ShapeArgs) -> DResult<Box<dyn Shape>> {
    let (lo, hi) = s.box_bounds()?;
    let tilt = Vec3::new(s.scaled(6, 0, "xy")?, s.scaled(7, 0, "xz")?, s.scaled(8, 1, "yz")?);
    for d in 0..3 {
        if lo[d] >= hi[d] {
            return Err(s.error(
                &s.words[2 * d],
                "region prism must have non-zero thickness in every dimension (lo < hi)",
                "lo >= hi",
            ));
        }
    }
    let inf = |d: usize| lo[d] == -BIG && hi[d] == BIG;
    for (k, (d1, d2)) in [(0, 1), (0, 2), (1, 2)].into_iter().enumerate() {
        if tilt[k] != 0.0 && (inf(d1) || inf(d2)) {
            return Err(s.error(
                &s.words[6 + k],
                "region prism tilt must be 0 when a tilted dimension is INF at both ends",
                "non-zero tilt",
            ));
        }
    }
    let (xy, xz, yz) = (tilt[0], tilt[1], tilt[2]);
    let h = Matrix3::new(hi[0] - lo[0], xy, xz, 0.0, hi[1] - lo[1], yz, 0.0, 0.0, hi[2] - lo[2]);
    // LAMMPS' closed-form inverse of the upper-triangular h, term by term (a general inverse
    // rounds differently)
    let hinv = Matrix3::new(
        1.0 / h.m11,
        -h.m12 / (h.m11 * h.m22),
        (h.m12 * h.m23 - h.m13 * h.m22) / (h.m11 * h.m22 * h.m33),
        0.0,
        1.0 / h.m22,
        -h.m23 / (h.m22 * h.m33),
        0.0,
        0.0,
        1.0 / h.m33,
    );
    // edge vectors a, b, c and the corners built from them as LAMMPS (lo + a + b + c, left to right)
    let a = [hi[0] - lo[0], 0.0, 0.0];
    let b = [xy, hi[1] - lo[1], 0.0];
    let c = [xz, yz, hi[2] - lo[2]];
    let mut corners = [[0.0; 3]; 8];
    for (k, corner) in corners.iter_mut().enumerate() {
        for d in 0..3 {
            let mut v = lo[d];
            if k & 1 != 0 {
                v += a[d];
            }
            if k & 2 != 0 {
                v += b[d];
            }
            if k & 4 != 0 {
                v += c[d];
            }
            corner[d] = v;
        }
    }
    let mut face = [cross(&a, &b), cross(&b, &a), cross(&c, &a), cross(&a, &c), cross(&b, &c), cross(&c, &b)];
    for f in &mut face {
        // LAMMPS' norm3: one reciprocal, three products
        let scale = 1.0 / dot(f, f).sqrt();
        *f = [f[0] * scale, f[1] * scale, f[2] * scale];
    }
    Ok(Box::new(Prism { lo, hi, tilt, hinv, corners, face }))
}

impl Prism {
    /// Distance of `x` inside face `i` along its inward normal (negative outside).
    fn depth(&self, x: &Vec3, i: usize) -> f64 {
        let corner = if i % 2 == 1 { &self.corners[7] } else { &self.corners[0] };
        (x[0] - corner[0]) * self.face[i][0] + (x[1] - corner[1]) * self.face[i][1] + (x[2] - corner[2]) * self.face[i][2]
    }

    /// LAMMPS `inside_tri`: the projected point `x` is inside triangle v1 v2 v3 or on its edges.
    fn inside_tri(x: &[f64; 3], v: [&[f64; 3]; 3], norm: &[f64; 3]) -> bool {
        (0..3).all(|k| dot(&cross(&sub(v[(k + 1) % 3], v[k]), &sub(x, v[k])), norm) >= 0.0)
    }

    /// LAMMPS `find_nearest`: the nearest point of the closed faces, triangle by triangle (the
    /// projection if it falls in the triangle, else the nearest points of its three edges),
    /// a later candidate kept only if strictly nearer.
    fn find_nearest(&self, x: &Vec3, open: &[bool; 6]) -> [f64; 3] {
        let xa: [f64; 3] = (*x).into();
        let mut distsq = BIG;
        let mut nearest = [0.0; 3];
        let mut closest = |near: [f64; 3]| {
            let d = sub(&xa, &near);
            let rsq = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if rsq < distsq {
                nearest = near;
                distsq = rsq;
            }
        };
        for (itri, t) in TRI.iter().enumerate() {
            let iface = itri / 2;
            if open[OPEN_FACE[iface]] {
                continue;
            }
            let (ci, cj, ck) = (&self.corners[t[0]], &self.corners[t[1]], &self.corners[t[2]]);
            let n = &self.face[iface];
            let d = (xa[0] - ci[0]) * n[0] + (xa[1] - ci[1]) * n[1] + (xa[2] - ci[2]) * n[2];
            let xproj = [xa[0] - d * n[0], xa[1] - d * n[1], xa[2] - d * n[2]];
            if Self::inside_tri(&xproj, [ci, cj, ck], n) {
                closest(xproj);
            } else {
                closest(point_on_segment(ci, cj, &xproj));
                closest(point_on_segment(cj, ck, &xproj));
                closest(point_on_segment(ci, ck, &xproj));
            }
        }
        nearest
    }
}

impl Shape for Prism {
    fn prism(&self) -> Option<([f64; 3], [f64; 3], [f64; 3])> {
        Some((self.lo.into(), self.hi.into(), self.tilt.into()))
    }
    fn inside(&self, x: &Vec3) -> bool {
        // Row by row as LAMMPS' RegPrism; the zeros below the diagonal only add signed zeros,
        // which the range test does not see.
        let t = self.hinv * (x - self.lo);
        t.iter().all(|c| (0.0..=1.0).contains(c))
    }

    fn extent(&self) -> Option<(Vec3, Vec3)> {
        // LAMMPS' MIN/MAX sequence: x is widened by xy, then by xz
        let min = |p: f64, q: f64| if p < q { p } else { q };
        let max = |p: f64, q: f64| if p > q { p } else { q };
        let (lo, hi, t) = (self.lo, self.hi, self.tilt);
        let xlo = min(lo[0], lo[0] + t[0]);
        let xlo = min(xlo, xlo + t[1]);
        let xhi = max(hi[0], hi[0] + t[0]);
        let xhi = max(xhi, xhi + t[1]);
        Some((Vec3::new(xlo, min(lo[1], lo[1] + t[2]), lo[2]), Vec3::new(xhi, max(hi[1], hi[1] + t[2]), hi[2])))
    }

    fn has_surface(&self) -> bool {
        true
    }

    /// One flat contact per closed face closer than the cutoff, walls numbered in LAMMPS' face
    /// order (z lo, z hi, y lo, y hi, x lo, x hi); none if the point is outside a face's plane.
    fn surface_interior(&self, x: &Vec3, cutoff: f64, open: &[bool; 6], out: &mut Vec<WallContact>) {
        if (0..6).any(|i| self.depth(x, i) < 0.0) {
            return;
        }
        for i in 0..6 {
            if open[OPEN_FACE[i]] {
                continue;
            }
            let dot = self.depth(x, i);
            if dot < cutoff {
                let f = &self.face[i];
                out.push(WallContact { r: dot, del: [dot * f[0], dot * f[1], dot * f[2]], radius: 0.0, iwall: i, ..WallContact::default() });
            }
        }
    }

    /// The nearest point of the closed faces (a face, edge or corner), wall 0, for a point
    /// outside or on the surface within the cutoff of every face's plane.
    fn surface_exterior(&self, x: &Vec3, cutoff: f64, open: &[bool; 6], out: &mut Vec<WallContact>) {
        if (0..6).any(|i| self.depth(x, i) <= -cutoff) {
            return;
        }
        if (0..6).all(|i| self.depth(x, i) > 0.0) {
            return;
        }
        let c = WallContact::to_point(x, self.find_nearest(x, open));
        if c.r < cutoff {
            out.push(c);
        }
    }

    fn contact_counts(&self, interior: bool) -> (usize, usize) {
        (6, if interior { 3 } else { 1 })
    }
}

#[cfg(test)]
mod tests {
    use crate::engine::domain::Domain;
    use crate::engine::region::tests::{boxed, reg};

    #[test]
    fn sheared_cell_and_its_extent() {
        let q = reg("region q prism 0 2 0 2 0 2 1 0 0 units box", None, None, &[]).unwrap();
        assert!(q.matches([2.8, 1.8, 0.5]) && !q.matches([0.1, 1.8, 0.5]));
        assert_eq!(q.extent(), Some(([0.0, 0.0, 0.0], [3.0, 2.0, 2.0])));
        // negative tilts widen the extent downwards; corners are inside
        let q = reg("region q prism 0 1 0 1 0 1 -0.5 -0.25 0.5 units box", None, None, &[]).unwrap();
        assert_eq!(q.extent(), Some(([-0.75, 0.0, 0.0], [1.0, 1.5, 1.0])));
        assert!(q.matches([0.0, 0.0, 0.0]) && q.matches([1.0 - 0.5 - 0.25, 1.5, 1.0]));
    }

    #[test]
    fn thickness_and_infinite_tilt_are_checked() {
        let e = reg("region q prism 0 2 1 1 0 2 0 0 0 units box", None, None, &[]).unwrap_err();
        assert!(e.message.contains("non-zero thickness"));
        let d: Domain = boxed([0.0; 3], [1.0; 3]);
        let e = reg("region q prism INF INF 0 1 0 1 0.5 0 0 units box", Some(&d), None, &[]).unwrap_err();
        assert!(e.message.contains("tilt must be 0"));
        assert!(reg("region q prism INF INF 0 1 0 1 0 0 0 units box", Some(&d), None, &[]).is_ok());
    }

    #[test]
    fn contacts_from_inside_by_face_and_from_outside_at_the_nearest_point() {
        let mut out = vec![];
        // an unsheared prism is a block: faces in LAMMPS' order z lo/hi, y lo/hi, x lo/hi
        let q = reg("region q prism 0 2 0 2 0 2 0 0 0 units box", None, None, &[]).unwrap();
        q.surface([0.2, 1.0, 1.9], 0.5, &mut out);
        let walls: Vec<(usize, f64)> = out.iter().map(|c| (c.iwall, c.r)).collect();
        assert_eq!(walls.len(), 2);
        assert_eq!(walls[0].0, 1);
        assert!((walls[0].1 - 0.1).abs() < 1e-15 && walls[1] == (4, 0.2));
        // open 5 (z lo in block numbering) is the prism's face 0
        let o = reg("region q prism 0 2 0 2 0 2 0 0 0 open 5 units box", None, None, &[]).unwrap();
        o.surface([1.0, 1.0, 0.1], 0.5, &mut out);
        assert!(out.is_empty());
        // outside a sheared prism: a corner, then an edge
        let s = reg("region s prism 0 2 0 2 0 2 1 0 0 side out units box", None, None, &[]).unwrap();
        s.surface([-0.3, -0.4, 1.0], 1.0, &mut out);
        assert_eq!(out.len(), 1);
        assert!((out[0].r - 0.5).abs() < 1e-15 && out[0].del == [-0.3, -0.4, 0.0], "{out:?}");
        s.surface([3.2, 2.0, 2.1], 1.0, &mut out);
        assert!((out[0].del[0] - 0.2).abs() < 1e-15 && (out[0].del[2] - 0.1).abs() < 1e-15, "{out:?}");
        // inside: no contact from outside
        s.surface([1.5, 1.0, 1.0], 1.0, &mut out);
        assert!(out.is_empty());
    }
}
