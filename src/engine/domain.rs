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
        let p = self.prd();
        [x[0] + image[0] as f64 * p[0], x[1] + image[1] as f64 * p[1], x[2] + image[2] as f64 * p[2]]
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
    /// Minimum-image displacement in periodic dimensions (LAMMPS `Domain::minimum_image`).
    pub fn minimum_image(&self, dx: &mut [f64; 3]) {
        let p = self.prd();
        for d in 0..3 {
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
    /// Move `xnew` by whole periods so it is the image closest to `xold`
    /// (LAMMPS `Domain::remap_near`, same arithmetic).
    pub fn remap_near(&self, xnew: &mut [f64; 3], xold: &[f64; 3]) {
        let period = self.prd();
        for d in 0..3 {
            if !self.periodic(d) {
                continue;
            }
            let half = 0.5 * period[d];
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
