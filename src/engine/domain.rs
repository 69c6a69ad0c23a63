//! The simulation box: bounds, boundary conditions, periodic images (orthogonal boxes only).

/// Boundary condition of one box face, as in the `boundary` command.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BoundaryKind {
    /// `p`: periodic.
    Periodic,
    /// `f`: fixed face; atoms leaving are lost.
    Fixed,
    /// `s`: shrink-wrapped to the atoms.
    Shrink,
    /// `m`: shrink-wrapped with the initial value as a minimum.
    ShrinkMin,
}

impl BoundaryKind {
    pub fn letter(self) -> char {
        match self {
            BoundaryKind::Periodic => 'p',
            BoundaryKind::Fixed => 'f',
            BoundaryKind::Shrink => 's',
            BoundaryKind::ShrinkMin => 'm',
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Domain {
    /// 2 or 3.
    pub dimension: usize,
    pub lo: [f64; 3],
    pub hi: [f64; 3],
    /// `boundary[dim][0]` is the lower face, `[1]` the upper.
    pub boundary: [[BoundaryKind; 2]; 3],
}

impl Domain {
    /// Whether an inserting fix (pour, deposit) keeps a new atom at `x`: inside the box, or
    /// above its top (z in 3D, y in 2D) and inside laterally (on one process the sub-box is the
    /// box, and LAMMPS' top process also takes atoms above it).
    pub fn takes_inserted(&self, x: [f64; 3]) -> bool {
        let vertical = self.dimension - 1;
        let inside = (0..3).all(|k| x[k] >= self.lo[k] && x[k] < self.hi[k]);
        inside || (x[vertical] >= self.hi[vertical] && (0..vertical).all(|k| x[k] >= self.lo[k] && x[k] < self.hi[k]))
    }

    pub fn periodic(&self, d: usize) -> bool {
        self.boundary[d][0] == BoundaryKind::Periodic
    }
    /// Box lengths (LAMMPS `prd`).
    pub fn prd(&self) -> [f64; 3] {
        [self.hi[0] - self.lo[0], self.hi[1] - self.lo[1], self.hi[2] - self.lo[2]]
    }
    /// Volume in 3D, area in 2D (as LAMMPS uses for pressure).
    pub fn volume(&self) -> f64 {
        let p = self.prd();
        if self.dimension == 3 { p[0] * p[1] * p[2] } else { p[0] * p[1] }
    }
    /// True if `x` lies in `[lo, hi)` in every dimension.
    pub fn contains(&self, x: [f64; 3]) -> bool {
        (0..3).all(|d| x[d] >= self.lo[d] && x[d] < self.hi[d])
    }
    /// Unwrapped coordinate: `x + image * prd` (LAMMPS `Domain::unmap`).
    pub fn unmap(&self, x: [f64; 3], image: [i32; 3]) -> [f64; 3] {
        unmap_prd(x, image, self.prd())
    }
    /// Wrap a position back into a periodic box, updating its image flags, exactly as
    /// LAMMPS `Domain::pbc` does (one box length at most per call).
    pub fn wrap(&self, x: &mut [f64; 3], image: &mut [i32; 3]) {
        let p = self.prd();
        for d in 0..3 {
            if !self.periodic(d) {
                continue;
            }
            if x[d] < self.lo[d] {
                x[d] += p[d];
                image[d] -= 1;
            }
            if x[d] >= self.hi[d] {
                x[d] -= p[d];
                x[d] = x[d].max(self.lo[d]);
                image[d] += 1;
            }
        }
    }
    /// Wrap a position into a periodic box however far outside it is, updating its image
    /// flags (LAMMPS `Domain::remap`). LAMMPS adds or subtracts one box length per step; so
    /// does this, bit for bit, for a point up to [`Domain::REMAP_STEPS`] box lengths away. A
    /// point farther away (where the steps would take ages, or never end when a box length is
    /// below the spacing of doubles at the point, such as x = 1e100 in a box of 10) is first
    /// moved by a whole number of box lengths at once, with the exact remainder (`%`), so
    /// the time is O(1); its image flags saturate at the limits of i32. A non-finite
    /// coordinate ends at the lower bound (callers refuse non-finite positions first).
    pub fn remap(&self, x: &mut [f64; 3], image: &mut [i32; 3]) {
        let p = self.prd();
        for d in 0..3 {
            if self.periodic(d) {
                remap_coord(&mut x[d], &mut image[d], self.lo[d], self.hi[d], p[d]);
            }
        }
    }

    /// How many box lengths [`Domain::remap`] steps, as LAMMPS, before it jumps.
    pub const REMAP_STEPS: f64 = 1e6;

    /// Minimum-image displacement in periodic dimensions (LAMMPS `Domain::minimum_image`).
    /// LAMMPS steps one box length at a time; a displacement of more than
    /// [`Domain::REMAP_STEPS`] box lengths (an atom put far outside the box by `set`) is first
    /// reduced to its exact remainder, so that the steps end.
    pub fn minimum_image(&self, dx: &mut [f64; 3]) {
        let p = self.prd();
        for d in 0..3 {
            if self.periodic(d) && dx[d].abs() > Self::REMAP_STEPS * p[d] {
                dx[d] %= p[d];
            }
            if self.periodic(d) && dx[d].abs() > 0.5 * p[d] {
                if dx[d] < 0.0 {
                    while dx[d] < 0.0 {
                        dx[d] += p[d];
                    }
                    if dx[d] > 0.5 * p[d] {
                        dx[d] -= p[d];
                    }
                } else {
                    while dx[d] > 0.0 {
                        dx[d] -= p[d];
                    }
                    if dx[d] < -0.5 * p[d] {
                        dx[d] += p[d];
                    }
                }
            }
        }
    }
}

/// One coordinate of [`Domain::remap`] in a dimension `lo..hi` of length `p`.
fn remap_coord(x: &mut f64, image: &mut i32, lo: f64, hi: f64, p: f64) {
    // LAMMPS' steps, when there are few; a point this near cannot make a step that does not
    // move it unless the box is about one spacing of doubles long, hence the budget
    let mut budget = Domain::REMAP_STEPS as usize + 2;
    if ((*x - lo) / p).abs() < Domain::REMAP_STEPS {
        while *x < lo && budget > 0 {
            *x += p;
            *image = image.saturating_sub(1);
            budget -= 1;
        }
        while *x >= hi && budget > 0 {
            *x -= p;
            *image = image.saturating_add(1);
            budget -= 1;
        }
        if budget > 0 {
            // LAMMPS' MAX(x, lo)
            *x = if *x > lo { *x } else { lo };
            return;
        }
    }
    // far away: lo + the exact remainder of x - lo, and the whole box lengths in the image
    let periods = ((*x - lo) / p).floor();
    let mut r = (*x - lo) % p;
    if r < 0.0 {
        r += p;
    }
    *x = lo + r;
    *image = (*image as f64 + periods).clamp(i32::MIN as f64, i32::MAX as f64) as i32;
    // rounding of lo + r can reach hi; a non-finite x stays below
    if *x >= hi {
        *x -= p;
        *image = image.saturating_add(1);
    }
    *x = if *x < hi && *x > lo { *x } else { lo };
}

impl Domain {
    /// Move `xnew` by whole periods so it is the image closest to `xold`
    /// (LAMMPS `Domain::remap_near`, same arithmetic).
    pub fn remap_near(&self, xnew: &mut [f64; 3], xold: &[f64; 3]) {
        let period = self.prd();
        for d in 0..3 {
            if !self.periodic(d) {
                continue;
            }
            let half = 0.5 * period[d];
            // far apart (see minimum_image): the exact remainder first, so the steps end
            if (xnew[d] - xold[d]).abs() > Self::REMAP_STEPS * period[d] {
                xnew[d] = xold[d] + (xnew[d] % period[d] - xold[d] % period[d]);
            }
            if xnew[d] - xold[d] > period[d] {
                let n = ((xnew[d] - xold[d]) / period[d]) as i64;
                xnew[d] -= n as f64 * period[d];
            }
            while xnew[d] - xold[d] > half {
                xnew[d] -= period[d];
            }
            if xold[d] - xnew[d] > period[d] {
                let n = ((xold[d] - xnew[d]) / period[d]) as i64;
                xnew[d] += n as f64 * period[d];
            }
            while xold[d] - xnew[d] > half {
                xnew[d] += period[d];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn periodic(lo: f64, hi: f64) -> Domain {
        Domain { dimension: 3, lo: [lo; 3], hi: [hi; 3], boundary: [[BoundaryKind::Periodic; 2]; 3] }
    }

    /// LAMMPS' Domain::remap: one box length per step, then MAX(x, lo).
    fn lammps_steps(x: f64, lo: f64, hi: f64) -> (f64, i32) {
        let (mut x, mut img, p) = (x, 0, hi - lo);
        while x < lo {
            x += p;
            img -= 1;
        }
        while x >= hi {
            x -= p;
            img += 1;
        }
        (if x > lo { x } else { lo }, img)
    }

    #[test]
    fn remap_steps_as_lammps_nearby_and_jumps_far_away() {
        let d = periodic(-1.3, 2.9);
        for x in [0.1, -1.3, 2.9, 3.0, -1.30000001, 17.77, -123.456, 4.2e5, -4.19e6, 0.1 + 0.2] {
            let (mut y, mut img) = ([x, 0.0, 0.0], [0; 3]);
            d.remap(&mut y, &mut img);
            let (lx, limg) = lammps_steps(x, -1.3, 2.9);
            assert_eq!((y[0].to_bits(), img[0]), (lx.to_bits(), limg), "x = {x}");
        }
        // far away: O(1), the exact remainder, image flags saturated
        let d = periodic(0.0, 10.0);
        let (mut y, mut img) = ([1e100, -1e100, 25.0], [0; 3]);
        d.remap(&mut y, &mut img);
        assert_eq!((y, img), ([4.0, 6.0, 5.0], [i32::MAX, i32::MIN, 2]));
        // a box 1e-300 thick
        let d = Domain { hi: [1.0, 1.0, 1e-300], ..periodic(0.0, 1.0) };
        let (mut y, mut img) = ([0.5, 0.5, 1.0], [0; 3]);
        d.remap(&mut y, &mut img);
        assert!(y[2] >= 0.0 && y[2] < 1e-300, "{y:?}");
        // non-finite coordinates end at the lower bound instead of looping
        let (mut y, mut img) = ([f64::NAN, f64::INFINITY, f64::NEG_INFINITY], [0; 3]);
        d.remap(&mut y, &mut img);
        assert_eq!(y, [0.0; 3]);
        // minimum images and nearest images of points 1e100 apart end too
        let d = periodic(0.0, 10.0);
        let mut dx = [1e100, -1e100, 13.0];
        d.minimum_image(&mut dx);
        assert_eq!(dx, [4.0, -4.0, 3.0]);
        let mut x = [1e100, 2.0, 29.0];
        d.remap_near(&mut x, &[1.0, 1.0, 1.0]);
        assert_eq!(x, [4.0, 2.0, -1.0]);
    }
}

/// A point carried along when the (orthogonal) box changes: its box fractions in the old box,
/// then their place in the new one (LAMMPS' x2lamda and lamda2x, term by term, so that the
/// round-off is LAMMPS'; the zero tilt terms are kept: an atom at the low face stays at +0).
pub struct Dilation {
    lo_old: [f64; 3],
    hinv_old: [f64; 3],
    lo_new: [f64; 3],
    h_new: [f64; 3],
}

impl Dilation {
    pub fn new(old: &Domain, new: &Domain) -> Dilation {
        let (p, q) = (old.prd(), new.prd());
        Dilation { lo_old: old.lo, hinv_old: [1.0 / p[0], 1.0 / p[1], 1.0 / p[2]], lo_new: new.lo, h_new: q }
    }
    pub fn apply(&self, x: &mut [f64; 3]) {
        let (lo, hinv) = (&self.lo_old, &self.hinv_old);
        let d = [x[0] - lo[0], x[1] - lo[1], x[2] - lo[2]];
        let l = [hinv[0] * d[0] + 0.0 * d[1] + 0.0 * d[2], hinv[1] * d[1] + 0.0 * d[2], hinv[2] * d[2]];
        let (lo, h) = (&self.lo_new, &self.h_new);
        x[0] = h[0] * l[0] + 0.0 * l[1] + 0.0 * l[2] + lo[0];
        x[1] = h[1] * l[1] + 0.0 * l[2] + lo[1];
        x[2] = h[2] * l[2] + lo[2];
    }
}

/// [`Domain::unmap`] for callers that hold only the box lengths `prd` (orthogonal boxes).
pub fn unmap_prd(x: [f64; 3], image: [i32; 3], prd: [f64; 3]) -> [f64; 3] {
    [x[0] + image[0] as f64 * prd[0], x[1] + image[1] as f64 * prd[1], x[2] + image[2] as f64 * prd[2]]
}
