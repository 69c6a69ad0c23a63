//! `region ID prism xlo xhi ylo yhi zlo zhi xy xz yz`: a parallelepiped with lower corner
//! `(xlo, ylo, zlo)`, edges `hi - lo` along the axes sheared by the tilts `xy xz yz`.

use super::{fixed, Shape, ShapeArgs, Style, Vec3, BIG};
use dmhs_parser::DResult;
use nalgebra::Matrix3;

pub const STYLE: Style = Style { syntax: "prism xlo xhi ylo yhi zlo zhi xy xz yz", nargs: fixed::<9>, parse };

#[derive(Debug)]
struct Prism {
    lo: Vec3,
    hi: Vec3,
    /// xy, xz, yz
    tilt: Vec3,
    /// Maps `x - lo` to the prism's own coordinates, each in [0, 1] inside.
    hinv: Matrix3<f64>,
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
    Ok(Box::new(Prism { lo, hi, tilt, hinv }))
}

impl Shape for Prism {
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
}
