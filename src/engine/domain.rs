//! The simulation box: bounds, tilts, boundary conditions, periodic images. A triclinic box
//! (LAMMPS' restricted triclinic: edge vectors a = (lx, 0, 0), b = (xy, ly, 0),
//! c = (xz, yz, lz)) is handled as LAMMPS handles it, in box fractions ("lamda"
//! coordinates) wherever LAMMPS uses them, with LAMMPS' arithmetic so that the bits agree.

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
    /// The tilt factors `[xy, xz, yz]` of a triclinic box; `None` for an orthogonal box. A
    /// triclinic box with zero tilts is not an orthogonal one: LAMMPS moves its atoms through
    /// box fractions at every rebuild, which changes their last bits.
    pub tilt: Option<[f64; 3]>,
    /// How fast fix deform changes the box, and whether atoms crossing a face carry it.
    pub rate: BoxRate,
}

/// The rate at which fix deform changes the box (LAMMPS' Domain::h_rate, in `h`'s layout
/// `[lx, ly, lz, yz, xz, xy]`, and h_ratelo, the lower faces' velocities), and with `fix deform
/// ... remap v` the group whose atoms change velocity by the box's rate when they cross a
/// periodic face (LAMMPS' deform_vremap and deform_groupbit). The rates stay after the fix
/// is gone, as LAMMPS' do; the group is found again at each run.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BoxRate {
    pub h_rate: [f64; 6],
    pub h_ratelo: [f64; 3],
    pub vremap: Option<u32>,
}

impl BoxRate {
    /// The streaming velocity at box fractions `l`: h_rate l + h_ratelo (LAMMPS' order).
    pub fn streaming(&self, l: [f64; 3]) -> [f64; 3] {
        let (r, lo) = (&self.h_rate, &self.h_ratelo);
        [r[0] * l[0] + r[5] * l[1] + r[4] * l[2] + lo[0], r[1] * l[1] + r[3] * l[2] + lo[1], r[2] * l[2] + lo[2]]
    }
    /// The velocity change of an atom whose image along `dim` moves by `-sign` (it crossed the
    /// lower face for `sign` 1): the box's edge velocity of that dimension, component by
    /// component as LAMMPS' pbc adds them.
    pub fn cross(&self, v: &mut [f64; 3], dim: usize, sign: f64) {
        let r = &self.h_rate;
        match dim {
            0 => v[0] += sign * r[0],
            1 => {
                v[0] += sign * r[5];
                v[1] += sign * r[1];
            }
            _ => {
                v[0] += sign * r[4];
                v[1] += sign * r[3];
                v[2] += sign * r[2];
            }
        }
    }
}

impl Domain {
    /// An orthogonal box.
    pub fn new(dimension: usize, lo: [f64; 3], hi: [f64; 3], boundary: [[BoundaryKind; 2]; 3]) -> Domain {
        Domain { dimension, lo, hi, boundary, tilt: None, rate: BoxRate::default() }
    }
    pub fn triclinic(&self) -> bool {
        self.tilt.is_some()
    }
    /// `[xy, xz, yz]`, zero for an orthogonal box.
    pub fn tilts(&self) -> [f64; 3] {
        self.tilt.unwrap_or([0.0; 3])
    }
    /// LAMMPS' `h`: `[lx, ly, lz, yz, xz, xy]` (the tilts zero for an orthogonal box).
    pub fn h(&self) -> [f64; 6] {
        let p = self.prd();
        let [xy, xz, yz] = self.tilts();
        [p[0], p[1], p[2], yz, xz, xy]
    }
    /// LAMMPS' `h_inv` (Domain::set_global_box), the inverse of `h`'s matrix in the same layout.
    pub fn h_inv(&self) -> [f64; 6] {
        let h = self.h();
        let mut hi = [1.0 / h[0], 1.0 / h[1], 1.0 / h[2], 0.0, 0.0, 0.0];
        if self.triclinic() {
            hi[3] = -h[3] / (h[1] * h[2]);
            hi[4] = (h[3] * h[5] - h[1] * h[4]) / (h[0] * h[1] * h[2]);
            hi[5] = -h[5] / (h[0] * h[1]);
        }
        hi
    }
    /// Box fractions of a point (LAMMPS' x2lamda, term by term).
    pub fn x2lamda(&self, x: [f64; 3]) -> [f64; 3] {
        x2lamda_with(&self.h_inv(), &self.lo, x)
    }
    /// The point at box fractions `l` (LAMMPS' lamda2x, term by term).
    pub fn lamda2x(&self, l: [f64; 3]) -> [f64; 3] {
        lamda2x_with(&self.h(), &self.lo, l)
    }
    /// The corners of the box in LAMMPS' order (x fastest, then y, then z), as lamda2x of the
    /// unit cube's (LAMMPS' box_corners).
    pub fn corners(&self) -> [[f64; 3]; 8] {
        let mut c = [[0.0; 3]; 8];
        for (k, x) in c.iter_mut().enumerate() {
            *x = self.lamda2x([(k & 1) as f64, ((k >> 1) & 1) as f64, ((k >> 2) & 1) as f64]);
        }
        c
    }
    /// The axis-aligned box around the points of box fractions `lo..hi` (LAMMPS' Domain::bbox).
    pub fn bbox(&self, lo: [f64; 3], hi: [f64; 3]) -> ([f64; 3], [f64; 3]) {
        let (mut blo, mut bhi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for k in 0..8 {
            let l = [if k & 1 == 0 { lo[0] } else { hi[0] }, if k & 2 == 0 { lo[1] } else { hi[1] }, if k & 4 == 0 { lo[2] } else { hi[2] }];
            let x = self.lamda2x(l);
            for d in 0..3 {
                blo[d] = blo[d].min(x[d]);
                bhi[d] = bhi[d].max(x[d]);
            }
        }
        (blo, bhi)
    }
    /// The box's axis-aligned bounds (LAMMPS' boxlo_bound and boxhi_bound).
    pub fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        let [xy, xz, yz] = self.tilts();
        let (mut lo, mut hi) = (self.lo, self.hi);
        lo[0] = lo[0].min(lo[0] + xy);
        lo[0] = lo[0].min(lo[0] + xz);
        lo[1] = lo[1].min(lo[1] + yz);
        hi[0] = hi[0].max(hi[0] + xy);
        hi[0] = hi[0].max(hi[0] + xz);
        hi[1] = hi[1].max(hi[1] + yz);
        (lo, hi)
    }
    /// How far (in box fractions) a distance `cut` reaches across the box in each dimension:
    /// the ghost shell of LAMMPS' CommBrick::setup, `cut` over the distance between the
    /// box's opposite faces (for an orthogonal box, `cut / prd`).
    pub fn lamda_reach(&self, cut: f64) -> [f64; 3] {
        let hi = self.h_inv();
        [cut * (hi[0] * hi[0] + hi[5] * hi[5] + hi[4] * hi[4]).sqrt(), cut * (hi[1] * hi[1] + hi[3] * hi[3]).sqrt(), cut * hi[2]]
    }
    /// The box of box fractions: 0 to 1 along each dimension, orthogonal, with this box's
    /// boundaries. A triclinic box's atoms are in it from the wrap of a rebuild to the list
    /// build, where the ranks of a run cut it (LAMMPS' sub-domains in lamda coordinates).
    pub fn fractions(&self) -> Domain {
        Domain::new(self.dimension, [0.0; 3], [1.0; 3], self.boundary)
    }
    /// The areas of the box's faces normal to z, y and x (the xy, xz and yz faces: LAMMPS'
    /// ProcMap::best_factors, which chooses the processor grid with the least surface).
    pub fn face_areas(&self) -> [f64; 3] {
        let p = self.prd();
        let Some([xy, xz, yz]) = self.tilt else { return [p[0] * p[1], p[0] * p[2], p[1] * p[2]] };
        let norm = |a: [f64; 3], b: [f64; 3]| {
            let c = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
            (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
        };
        let (a, b, c) = ([p[0], 0.0, 0.0], [xy, p[1], 0.0], [xz, yz, p[2]]);
        [norm(a, b), norm(a, c), norm(b, c)]
    }
    /// The periodic shifts of this box, for ghost images and unwrapping.
    pub fn periods(&self) -> Periods {
        Periods { prd: self.prd(), tilt: self.tilt }
    }

    /// Whether an inserting fix (pour, deposit) keeps a new atom at `x`: inside the box, or
    /// above its top (z in 3D, y in 2D) and inside laterally (on one process the sub-box is the
    /// box, and LAMMPS' top process also takes atoms above it).
    pub fn takes_inserted(&self, x: [f64; 3]) -> bool {
        let vertical = self.dimension - 1;
        let (x, lo, hi) = if self.triclinic() { (self.x2lamda(x), [0.0; 3], [1.0; 3]) } else { (x, self.lo, self.hi) };
        let inside = (0..3).all(|k| x[k] >= lo[k] && x[k] < hi[k]);
        inside || (x[vertical] >= hi[vertical] && (0..vertical).all(|k| x[k] >= lo[k] && x[k] < hi[k]))
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
    /// True if `x` lies in `[lo, hi)` in every dimension (in box fractions `[0, 1)` for a
    /// triclinic box, as LAMMPS' Domain::inside).
    pub fn contains(&self, x: [f64; 3]) -> bool {
        if self.triclinic() {
            let l = self.x2lamda(x);
            return (0..3).all(|d| l[d] >= 0.0 && l[d] < 1.0);
        }
        (0..3).all(|d| x[d] >= self.lo[d] && x[d] < self.hi[d])
    }
    /// Unwrapped coordinate: `x + image * prd` (LAMMPS `Domain::unmap`; with the tilts for a
    /// triclinic box).
    pub fn unmap(&self, x: [f64; 3], image: [i32; 3]) -> [f64; 3] {
        self.periods().unmap(x, image)
    }
    /// Wrap a position back into a periodic box, updating its image flags, exactly as
    /// LAMMPS `Domain::pbc` does (one box length at most per call). A triclinic box wraps in
    /// box fractions ([`Domain::pbc`]), then converts back.
    pub fn wrap(&self, x: &mut [f64; 3], image: &mut [i32; 3]) {
        if self.triclinic() {
            let mut l = self.x2lamda(*x);
            self.pbc(&mut l, image, None);
            *x = self.lamda2x(l);
            return;
        }
        self.pbc(x, image, None);
    }
    /// The streaming velocity of the box fix deform changes, at position `x` (temp/deform's bias).
    pub fn stream_velocity(&self, x: [f64; 3]) -> [f64; 3] {
        self.rate.streaming(self.x2lamda(x))
    }
    /// LAMMPS' pbc() of one atom, positions in box fractions for a triclinic box: with
    /// `v` (an atom of fix deform's `remap v` group) each crossing also changes the velocity
    /// by the box's rate ([`BoxRate::cross`]).
    pub fn pbc(&self, x: &mut [f64; 3], image: &mut [i32; 3], v: Option<&mut [f64; 3]>) {
        match self.triclinic() {
            true => self.wrap_in(x, image, [0.0; 3], [1.0; 3], [1.0; 3], v),
            false => self.wrap_in(x, image, self.lo, self.hi, self.prd(), v),
        }
    }
    fn wrap_in(&self, x: &mut [f64; 3], image: &mut [i32; 3], lo: [f64; 3], hi: [f64; 3], p: [f64; 3], mut v: Option<&mut [f64; 3]>) {
        for d in 0..3 {
            if !self.periodic(d) {
                continue;
            }
            if x[d] < lo[d] {
                x[d] += p[d];
                if let Some(v) = v.as_deref_mut() {
                    self.rate.cross(v, d, 1.0);
                }
                image[d] -= 1;
            }
            if x[d] >= hi[d] {
                x[d] -= p[d];
                x[d] = x[d].max(lo[d]);
                if let Some(v) = v.as_deref_mut() {
                    self.rate.cross(v, d, -1.0);
                }
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
        if self.triclinic() {
            let mut l = self.x2lamda(*x);
            for d in 0..3 {
                if self.periodic(d) {
                    remap_coord(&mut l[d], &mut image[d], 0.0, 1.0, 1.0);
                }
            }
            *x = self.lamda2x(l);
            return;
        }
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
        if self.triclinic() {
            return self.minimum_image_tilted(dx);
        }
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

impl Domain {
    /// [`Domain::minimum_image`] of a triclinic box: z, then y, then x, each whole period of
    /// z carrying yz and xz along, each of y carrying xy (LAMMPS' order and arithmetic).
    fn minimum_image_tilted(&self, dx: &mut [f64; 3]) {
        let p = self.prd();
        let [xy, xz, yz] = self.tilts();
        // the displacement one period of each dimension makes: (dim, [x, y, z] shift)
        let steps = [(2, [xz, yz, p[2]]), (1, [xy, p[1], 0.0]), (0, [p[0], 0.0, 0.0])];
        for (d, s) in steps {
            if !self.periodic(d) {
                continue;
            }
            if dx[d].abs() > Self::REMAP_STEPS * p[d] {
                // far apart: whole periods at once, so that the steps end
                let n = (dx[d] / p[d]).trunc();
                for k in 0..=d {
                    dx[k] -= n * s[k];
                }
            }
            let half = 0.5 * p[d];
            let add = |dx: &mut [f64; 3], sign: f64| {
                for k in (0..=d).rev() {
                    dx[k] += sign * s[k];
                }
            };
            if dx[d].abs() > half {
                if dx[d] < 0.0 {
                    while dx[d] < 0.0 {
                        add(dx, 1.0);
                    }
                    if dx[d] > half {
                        add(dx, -1.0);
                    }
                } else {
                    while dx[d] > 0.0 {
                        add(dx, -1.0);
                    }
                    if dx[d] < -half {
                        add(dx, 1.0);
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
        if self.triclinic() {
            // in box fractions, as LAMMPS
            let (mut lnew, lold) = (self.x2lamda(*xnew), self.x2lamda(*xold));
            let flat = Domain { lo: [0.0; 3], hi: [1.0; 3], tilt: None, ..self.clone() };
            flat.remap_near(&mut lnew, &lold);
            *xnew = self.lamda2x(lnew);
            return;
        }
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
        Domain::new(3, [lo; 3], [hi; 3], [[BoundaryKind::Periodic; 2]; 3])
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

/// A point carried along when the box changes: its box fractions in the old box, then their
/// place in the new one (LAMMPS' x2lamda and lamda2x, term by term, so that the round-off is
/// LAMMPS'; the zero tilt terms of an orthogonal box are kept: an atom at the low face stays
/// at +0).
pub struct Dilation {
    lo_old: [f64; 3],
    hinv_old: [f64; 6],
    lo_new: [f64; 3],
    h_new: [f64; 6],
}

impl Dilation {
    pub fn new(old: &Domain, new: &Domain) -> Dilation {
        Dilation { lo_old: old.lo, hinv_old: old.h_inv(), lo_new: new.lo, h_new: new.h() }
    }
    pub fn apply(&self, x: &mut [f64; 3]) {
        *x = lamda2x_with(&self.h_new, &self.lo_new, x2lamda_with(&self.hinv_old, &self.lo_old, *x));
    }
}

/// The product of two upper-triangular matrices in `h`'s layout `[xx, yy, zz, yz, xz, xy]`
/// (LAMMPS' MathExtra::multiply_shape_shape, term by term).
pub fn shape_product(one: &[f64; 6], two: &[f64; 6]) -> [f64; 6] {
    [
        one[0] * two[0],
        one[1] * two[1],
        one[2] * two[2],
        one[1] * two[3] + one[3] * two[2],
        one[0] * two[4] + one[5] * two[3] + one[4] * two[2],
        one[0] * two[5] + one[5] * two[1],
    ]
}

/// LAMMPS' x2lamda with a given `h_inv` and box origin.
pub fn x2lamda_with(hinv: &[f64; 6], lo: &[f64; 3], x: [f64; 3]) -> [f64; 3] {
    let d = [x[0] - lo[0], x[1] - lo[1], x[2] - lo[2]];
    [hinv[0] * d[0] + hinv[5] * d[1] + hinv[4] * d[2], hinv[1] * d[1] + hinv[3] * d[2], hinv[2] * d[2]]
}

/// LAMMPS' lamda2x with a given `h` and box origin.
pub fn lamda2x_with(h: &[f64; 6], lo: &[f64; 3], l: [f64; 3]) -> [f64; 3] {
    [h[0] * l[0] + h[5] * l[1] + h[4] * l[2] + lo[0], h[1] * l[1] + h[3] * l[2] + lo[1], h[2] * l[2] + lo[2]]
}

/// The periodic shifts of a box: what a ghost image or an image flag adds to a position.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Periods {
    pub prd: [f64; 3],
    /// `[xy, xz, yz]` of a triclinic box.
    pub tilt: Option<[f64; 3]>,
}

impl Periods {
    /// The unwrapped position of `x` with image flags `image` (LAMMPS' Domain::unmap).
    pub fn unmap(&self, x: [f64; 3], image: [i32; 3]) -> [f64; 3] {
        let p = self.prd;
        let [a, b, c] = [image[0] as f64, image[1] as f64, image[2] as f64];
        match self.tilt {
            None => [x[0] + a * p[0], x[1] + b * p[1], x[2] + c * p[2]],
            Some([xy, xz, yz]) => [x[0] + p[0] * a + xy * b + xz * c, x[1] + p[1] * b + yz * c, x[2] + p[2] * c],
        }
    }
    /// [`Periods::unmap`] as LAMMPS' in-place Domain::unmap sums it (replicate): the images'
    /// shift first, then added to the position (the same bits as `unmap` for an orthogonal box).
    pub fn unmap_summed(&self, x: [f64; 3], image: [i32; 3]) -> [f64; 3] {
        let p = self.prd;
        let [a, b, c] = [image[0] as f64, image[1] as f64, image[2] as f64];
        match self.tilt {
            None => self.unmap(x, image),
            Some([xy, xz, yz]) => [x[0] + (p[0] * a + xy * b + xz * c), x[1] + (p[1] * b + yz * c), x[2] + p[2] * c],
        }
    }
    /// The position of the image `shift` of a point at `x`, as LAMMPS' forward communication
    /// makes it: one exchange per dimension in turn (x, y, z), each adding its own shift (for
    /// a triclinic box a shift along y moves x by xy too, one along z x and y by xz and yz).
    pub fn shifted(&self, mut x: [f64; 3], s: [i8; 3]) -> [f64; 3] {
        let p = self.prd;
        match self.tilt {
            None => {
                for d in 0..3 {
                    if s[d] != 0 {
                        x[d] += s[d] as f64 * p[d];
                    }
                }
            }
            Some([xy, xz, yz]) => {
                for d in 0..3 {
                    if s[d] == 0 {
                        continue;
                    }
                    let mut f = [0.0; 3];
                    f[d] = s[d] as f64;
                    x[0] += f[0] * p[0] + f[1] * xy + f[2] * xz;
                    x[1] += f[1] * p[1] + f[2] * yz;
                    x[2] += f[2] * p[2];
                }
            }
        }
        x
    }
}

#[cfg(test)]
mod tilted_tests {
    use super::*;

    fn tilted() -> Domain {
        Domain { tilt: Some([1.5, -0.7, 0.9]), ..Domain::new(3, [-1.0, 0.5, 2.0], [5.0, 4.5, 7.0], [[BoundaryKind::Periodic; 2]; 3]) }
    }

    #[test]
    fn face_areas_are_the_parallelepiped_faces() {
        // lengths 6, 4, 5, tilts xy 1.5, xz -0.7, yz 0.9: the xy face is a parallelogram of
        // base 6 and height 4; the xz face spans a = (6,0,0) and c = (-0.7,0.9,5); the yz face
        // spans b = (1.5,4,0) and c
        let a = tilted().face_areas();
        assert_eq!(a[0], 24.0);
        assert!((a[1] - 6.0 * (0.9f64 * 0.9 + 25.0).sqrt()).abs() < 1e-12);
        let c: [f64; 3] = [4.0 * 5.0, -1.5 * 5.0, 1.5 * 0.9 - 4.0 * -0.7];
        assert!((a[2] - (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()).abs() < 1e-12);
        let ortho = Domain::new(3, [0.0; 3], [2.0, 3.0, 4.0], [[BoundaryKind::Periodic; 2]; 3]);
        assert_eq!(ortho.face_areas(), [6.0, 8.0, 12.0]);
        // the box of fractions keeps the boundaries
        let f = Domain { boundary: [[BoundaryKind::Periodic; 2], [BoundaryKind::Shrink; 2], [BoundaryKind::Periodic; 2]], ..tilted() }.fractions();
        assert!(!f.triclinic() && f.lo == [0.0; 3] && f.hi == [1.0; 3] && !f.periodic(1) && f.periodic(2));
    }

    #[test]
    fn box_fractions_round_trip_and_wrap_as_lammps() {
        let d = tilted();
        // the corners: lamda2x of the unit cube's, x fastest
        let c = d.corners();
        assert_eq!(c[0], d.lo);
        assert_eq!(c[7], [5.0 + 1.5 - 0.7, 4.5 + 0.9, 7.0]);
        let x = [2.3, 1.1, 6.9];
        let l = d.x2lamda(x);
        let y = d.lamda2x(l);
        for k in 0..3 {
            assert!((x[k] - y[k]).abs() < 1e-14);
        }
        // an atom past the upper y face wraps by b = (xy, ly, 0) and counts an image
        let (mut p, mut img) = (d.lamda2x([0.5, 1.2, 0.5]), [0; 3]);
        d.remap(&mut p, &mut img);
        assert_eq!(img, [0, 1, 0]);
        let q = d.lamda2x([0.5, 0.2, 0.5]);
        for k in 0..3 {
            assert!((p[k] - q[k]).abs() < 1e-14, "{p:?} {q:?}");
        }
        let u = d.unmap(p, img);
        let want = d.lamda2x([0.5, 1.2, 0.5]);
        for k in 0..3 {
            assert!((u[k] - want[k]).abs() < 1e-13);
        }
        assert!(d.contains(q) && !d.contains(want));
    }

    #[test]
    fn minimum_image_carries_the_tilts() {
        let d = tilted();
        // one period along c minus a bit: the image is the short vector
        let mut dx = [-0.7 + 0.1, 0.9 + 0.2, 5.0 - 0.3];
        d.minimum_image(&mut dx);
        for (k, w) in [0.1, 0.2, -0.3].iter().enumerate() {
            assert!((dx[k] - w).abs() < 1e-14, "{dx:?}");
        }
        // ghost images: one exchange per dimension, a shift along y moves x by xy
        let flat = Periods { prd: [10.0, 5.0, 2.0], tilt: None };
        assert_eq!(flat.shifted([0.25, 1.0, 3.0], [1, 0, -1]), [10.25, 1.0, 1.0]);
        let p = d.periods();
        assert_eq!(p.shifted([0.0; 3], [0, 1, 0]), [1.5, 4.0, 0.0]);
        assert_eq!(p.shifted([0.0; 3], [1, 0, -1]), [6.0 + 0.7, -0.9, -5.0]);
    }
}
