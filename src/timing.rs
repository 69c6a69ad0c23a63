//! Per-stage wall-clock timing of a run, printed like LAMMPS' "MPI task timing breakdown".

use std::time::Instant;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    Pair,
    Bond,
    Neigh,
    Comm,
    Output,
    Modify,
}

pub const STAGES: [(Stage, &str); 6] = [
    (Stage::Pair, "Pair"),
    (Stage::Bond, "Bond"),
    (Stage::Neigh, "Neigh"),
    (Stage::Comm, "Comm"),
    (Stage::Output, "Output"),
    (Stage::Modify, "Modify"),
];

#[derive(Clone, Debug)]
pub struct Timers {
    pub seconds: [f64; 6],
    last: Instant,
}

impl Default for Timers {
    fn default() -> Self {
        Timers { seconds: [0.0; 6], last: Instant::now() }
    }
}

impl Timers {
    pub fn reset(&mut self) {
        self.seconds = [0.0; 6];
        self.last = Instant::now();
    }
    /// Start timing from now.
    pub fn stamp(&mut self) {
        self.last = Instant::now();
    }
    /// Charge the time since the last stamp to `stage`.
    pub fn charge(&mut self, stage: Stage) {
        let now = Instant::now();
        let k = STAGES.iter().position(|(s, _)| *s == stage).unwrap();
        self.seconds[k] += now.duration_since(self.last).as_secs_f64();
        self.last = now;
    }
    /// The breakdown table for a run that took `total` seconds.
    pub fn report(&self, total: f64) -> String {
        let mut s = String::from("MPI task timing breakdown:\nSection |  min time  |  avg time  |  max time  |%varavg| %total\n---------------------------------------------------------------\n");
        let pct = |t: f64| if total > 0.0 { 100.0 * t / total } else { 0.0 };
        let mut used = 0.0;
        for (k, (_, name)) in STAGES.iter().enumerate() {
            let t = self.seconds[k];
            used += t;
            s += &format!("{:<8}| {:<10.5} | {:<10.5} | {:<10.5} |   0.0 | {:5.2}\n", name, t, t, t, pct(t));
        }
        let other = (total - used).max(0.0);
        s += &format!("{:<8}|            | {:<10.5} |            |       | {:5.2}\n", "Other", other, pct(other));
        s
    }
}
