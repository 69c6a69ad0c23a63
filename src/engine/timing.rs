//! Per-stage wall-clock timing of a run, printed like LAMMPS' "MPI task timing breakdown".

use std::time::Instant;

/// A stage; its discriminant is its row in [`STAGES`].
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
    /// Seconds in each fix (by position in the fix list), all hooks together.
    pub fix_seconds: Vec<f64>,
    last: Instant,
}

impl Default for Timers {
    fn default() -> Self {
        Timers { seconds: [0.0; 6], fix_seconds: Vec::new(), last: Instant::now() }
    }
}

impl Timers {
    pub fn reset(&mut self) {
        self.seconds = [0.0; 6];
        self.fix_seconds.clear();
        self.last = Instant::now();
    }
    /// Charge the time since the last reading to fix number `k` and to the Modify stage. Fix
    /// hooks run between a stamp and a charge of Modify, so one clock reading per hook suffices
    /// (a tiny deck reads the clock millions of times: each reading is ~30 ns of a ~1 us step).
    pub fn charge_fix(&mut self, k: usize) {
        let now = Instant::now();
        let t = now.duration_since(self.last).as_secs_f64();
        self.last = now;
        self.seconds[Stage::Modify as usize] += t;
        if self.fix_seconds.len() <= k {
            self.fix_seconds.resize(k + 1, 0.0);
        }
        self.fix_seconds[k] += t;
    }
    /// Start timing from now.
    pub fn stamp(&mut self) {
        self.last = Instant::now();
    }
    /// Charge the time since the last stamp to `stage`.
    pub fn charge(&mut self, stage: Stage) {
        let now = Instant::now();
        self.seconds[stage as usize] += now.duration_since(self.last).as_secs_f64();
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

/// The per-model table printed after the stage breakdown: each active model's time and its share
/// of the loop (`rows`: label and seconds).
pub fn model_report(rows: &[(String, f64)], total: f64) -> String {
    let width = rows.iter().map(|(l, _)| l.len()).max().unwrap_or(5).max(5);
    let mut s = format!("Model timing breakdown:\n{:<width$} |  time (s)  | %total\n{}\n", "Model", "-".repeat(width + 23));
    for (label, t) in rows {
        let pct = if total > 0.0 { 100.0 * t / total } else { 0.0 };
        s += &format!("{label:<width$} | {t:<10.5} | {pct:5.2}\n");
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `charge` indexes `seconds` by the discriminant: it must be the stage's row.
    #[test]
    fn a_stage_discriminant_is_its_row() {
        for (k, (s, _)) in STAGES.iter().enumerate() {
            assert_eq!(*s as usize, k);
        }
    }
}
