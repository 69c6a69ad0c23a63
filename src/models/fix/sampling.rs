//! The sampling steps of LAMMPS' averaging fixes (fix ave/time, fix ave/atom): Nrepeat samples
//! Nevery steps apart, the last on a multiple of Nfreq (at or after `start`).

use dmhs_parser::{Args, DResult};

#[derive(Clone, Debug)]
pub struct Sampling {
    pub nevery: i64,
    pub nrepeat: i64,
    pub nfreq: i64,
    /// Lower bound of the Nfreq multiples (fix ave/time `start`).
    pub start: i64,
    /// The next sampling step.
    pub nvalid: i64,
    /// Samples taken in the current period.
    pub irepeat: i64,
}

impl Sampling {
    /// Read `Nevery Nrepeat Nfreq`, checked as LAMMPS does.
    pub fn parse(a: &mut Args, style: &str) -> DResult<Sampling> {
        let nevery = a.i64_in("Nevery", 1, i64::MAX)?;
        let nrepeat = a.i64_in("Nrepeat", 1, i64::MAX)?;
        let w = a.peek();
        let nfreq = a.i64_in("Nfreq", 1, i64::MAX)?;
        if nfreq % nevery != 0 || nrepeat * nevery > nfreq {
            let w = w.expect("Nfreq was read");
            return Err(a.error_at(w, format!("inconsistent fix {style} Nevery/Nrepeat/Nfreq {nevery} {nrepeat} {nfreq}: Nfreq must be a multiple of Nevery and Nrepeat*Nevery <= Nfreq"), "inconsistent"));
        }
        Ok(Sampling { nevery, nrepeat, nfreq, start: 0, nvalid: 0, irepeat: 0 })
    }

    /// LAMMPS' nextvalid: `step` itself if it ends a period of one sample, else the first sample
    /// of the next period.
    pub fn next_valid(&self, step: i64) -> i64 {
        let mut nvalid = (step / self.nfreq) * self.nfreq + self.nfreq;
        while nvalid < self.start {
            nvalid += self.nfreq;
        }
        if nvalid - self.nfreq == step && self.nrepeat == 1 {
            nvalid = step;
        } else {
            nvalid -= (self.nrepeat - 1) * self.nevery;
        }
        if nvalid < step {
            nvalid += self.nfreq;
        }
        nvalid
    }

    /// When the fix is defined.
    pub fn begin(&mut self, step: i64) {
        self.nvalid = self.next_valid(step);
    }

    /// Before a run: a new period if the step moved past the next sample (reset_timestep).
    pub fn init(&mut self, step: i64) {
        if self.nvalid < step {
            self.irepeat = 0;
            self.nvalid = self.next_valid(step);
        }
    }

    /// Whether `step` is a sampling step.
    pub fn due(&self, step: i64) -> bool {
        step == self.nvalid
    }

    /// After the sample of `step`: the next sampling step; true if the sample ended a period.
    pub fn advance(&mut self, step: i64) -> bool {
        self.irepeat += 1;
        if self.irepeat < self.nrepeat {
            self.nvalid += self.nevery;
            return false;
        }
        self.irepeat = 0;
        self.nvalid = step + self.nfreq - (self.nrepeat - 1) * self.nevery;
        true
    }
}
