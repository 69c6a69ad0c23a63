//! `compute ID group msd [com yes|no] [average yes|no]`: mean-squared displacement of the group
//! from the positions it had when the compute was defined (unwrapped with image flags), as
//! LAMMPS' compute msd: a vector of <dx^2>, <dy^2>, <dz^2> and their sum. `com yes` measures
//! from the centre of mass; `average yes` from each atom's running average position.

use super::Compute;
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};
use std::collections::HashMap;
use std::sync::Mutex;

pub const SYNTAX: &str = "compute ID group msd [com yes|no] [average yes|no]";

pub struct ComputeMsd {
    id: String,
    groupbit: u32,
    com: bool,
    average: bool,
    /// Atoms in the group when defined (LAMMPS' nmsd; the count must not change).
    count: usize,
    reference: Mutex<Reference>,
}

/// The reference positions by atom ID; `average yes` moves them, once per step (then the result
/// of a step is kept, so thermo and fix ave/time reading it on one step see the same value, as
/// LAMMPS' invoked flags ensure).
struct Reference {
    x: HashMap<i64, [f64; 3]>,
    naverage: u64,
    last: Option<(i64, [f64; 4])>,
}

impl ComputeMsd {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let (mut com, mut average) = (false, false);
        while let Some(k) = a.peek() {
            a.skip(1);
            match k.text.as_str() {
                "com" => com = a.yes_no("com")?,
                "average" => average = a.yes_no("average")?,
                _ => return Err(a.unknown_keyword(k, &["com", "average"])),
            }
        }
        let s = w.state;
        let d = s.domain.as_ref().expect("computes are defined after the box");
        let cm = if com { s.group_xcm(groupbit).0 } else { [0.0; 3] };
        let at = &s.atoms;
        let x = (0..at.nlocal)
            .filter(|&i| at.mask[i] & groupbit != 0)
            .map(|i| {
                let u = d.unmap(at.x[i], at.image[i]);
                (at.tag[i], [u[0] - cm[0], u[1] - cm[1], u[2] - cm[2]])
            })
            .collect();
        let count = s.group_count(groupbit);
        Ok(ComputeMsd { id, groupbit, com, average, count, reference: Mutex::new(Reference { x, naverage: 0, last: None }) })
    }
}

impl Compute for ComputeMsd {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "msd"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn size_vector(&self) -> Option<usize> {
        Some(4)
    }
    fn vector(&self, w: &World) -> Result<Vec<f64>, String> {
        let s = w.state;
        let mut r = self.reference.lock().map_err(|_| "compute msd: poisoned state".to_string())?;
        if let (true, Some((step, v))) = (self.average, r.last) {
            if step == s.step {
                return Ok(v.to_vec());
            }
        }
        if s.group_count(self.groupbit) != self.count {
            return Err(format!("compute msd {}: the number of atoms in its group must not change", self.id));
        }
        let d = s.domain.as_ref().ok_or("no simulation box")?;
        let cm = if self.com { s.group_xcm(self.groupbit).0 } else { [0.0; 3] };
        let navfac = if self.average {
            r.naverage += 1;
            1.0 / (r.naverage + 1) as f64
        } else {
            0.0
        };
        let nav = r.naverage as f64;
        let (at, periods) = (&s.atoms, d.periods());
        let mut msd = [0.0; 4];
        for i in 0..at.nlocal {
            if at.mask[i] & self.groupbit == 0 {
                continue;
            }
            let u = periods.unmap(at.x[i], at.image[i]);
            let (xt, yt, zt) = (u[0] - cm[0], u[1] - cm[1], u[2] - cm[2]);
            // an atom that joined the group later starts from where it is (LAMMPS' set_arrays)
            let o = r.x.entry(at.tag[i]).or_insert(at.x[i]);
            if self.average {
                o[0] = (o[0] * nav + xt) * navfac;
                o[1] = (o[1] * nav + yt) * navfac;
                o[2] = (o[2] * nav + zt) * navfac;
            }
            let (dx, dy, dz) = (xt - o[0], yt - o[1], zt - o[2]);
            msd[0] += dx * dx;
            msd[1] += dy * dy;
            msd[2] += dz * dz;
            msd[3] += dx * dx + dy * dy + dz * dz;
        }
        s.sum_ranks(&mut msd);
        if self.count > 0 {
            let n = self.count as f64;
            msd.iter_mut().for_each(|m| *m /= n);
        }
        r.last = Some((s.step, msd));
        Ok(msd.to_vec())
    }
}
