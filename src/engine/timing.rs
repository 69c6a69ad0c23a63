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

/// The clock is read at stage boundaries, and between two fixes of a stage only: a fix that
/// ran alone since the last reading is charged by the next one (`pending`). A tiny deck reads
/// the clock millions of times, and each reading (~30 ns) is a few per cent of its step.
#[derive(Clone, Debug)]
pub struct Timers {
    pub seconds: [f64; 6],
    /// Seconds in each fix (by position in the fix list), all hooks together.
    pub fix_seconds: Vec<f64>,
    last: Instant,
    /// The fix that ran since the last reading, not yet charged.
    pending: Option<usize>,
}

impl Default for Timers {
    fn default() -> Self {
        Timers { seconds: [0.0; 6], fix_seconds: Vec::new(), last: Instant::now(), pending: None }
    }
}

impl Timers {
    pub fn reset(&mut self) {
        self.seconds = [0.0; 6];
        self.fix_seconds.clear();
        self.last = Instant::now();
        self.pending = None;
    }
    /// A fix is about to run a hook (between a stamp and a charge of Modify): a fix that ran
    /// before it since the last reading gets its time now.
    pub fn fix_starts(&mut self) {
        if self.pending.is_some() {
            self.charge(Stage::Modify);
        }
    }
    /// Fix number `k` ran a hook: the next reading charges it.
    pub fn fix_ran(&mut self, k: usize) {
        self.pending = Some(k);
    }
    /// Start timing from now.
    pub fn stamp(&mut self) {
        self.last = Instant::now();
        self.pending = None;
    }
    /// Charge the time since the last reading to `stage` (and to the fix that ran in it).
    pub fn charge(&mut self, stage: Stage) {
        let now = Instant::now();
        let t = now.duration_since(self.last).as_secs_f64();
        self.seconds[stage as usize] += t;
        self.last = now;
        if let Some(k) = self.pending.take() {
            if self.fix_seconds.len() <= k {
                self.fix_seconds.resize(k + 1, 0.0);
            }
            self.fix_seconds[k] += t;
        }
    }
    /// The breakdown table for a run that took `total` seconds; `spread`: each stage's seconds
    /// over the ranks of a distributed run (None: this process's own).
    pub fn report(&self, total: f64, spread: Option<&[Spread; 6]>) -> String {
        let mut s = String::from("MPI task timing breakdown:\nSection |  min time  |  avg time  |  max time  |%varavg| %total\n---------------------------------------------------------------\n");
        let pct = |t: f64| if total > 0.0 { 100.0 * t / total } else { 0.0 };
        let mut used = 0.0;
        for (k, (_, name)) in STAGES.iter().enumerate() {
            let r = spread.map_or_else(|| Spread::of(&[self.seconds[k]]), |s| s[k]);
            used += r.avg;
            s += &format!("{:<8}| {:<10.5} | {:<10.5} | {:<10.5} | {:5.1} | {:5.2}\n", name, r.min, r.avg, r.max, r.varavg, pct(r.avg));
        }
        let other = (total - used).max(0.0);
        s += &format!("{:<8}|            | {:<10.5} |            |       | {:5.2}\n", "Other", other, pct(other));
        s
    }
}

/// One stage's seconds over the ranks: least, mean, most, and the spread as LAMMPS prints it
/// (`%varavg`: the standard deviation in per cent of the mean, 0 below a millisecond).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Spread {
    pub min: f64,
    pub avg: f64,
    pub max: f64,
    pub varavg: f64,
}

impl Spread {
    /// The spread of one value per rank.
    pub fn of(per_rank: &[f64]) -> Spread {
        let n = per_rank.len().max(1) as f64;
        let avg = per_rank.iter().sum::<f64>() / n;
        let sq = per_rank.iter().map(|t| t * t).sum::<f64>() / n;
        Spread::from_sums(per_rank.iter().copied().fold(f64::INFINITY, f64::min), avg, per_rank.iter().copied().fold(0.0, f64::max), sq)
    }
    /// From the reductions of a distributed run: least, mean, most and mean square.
    pub fn from_sums(min: f64, avg: f64, max: f64, mean_square: f64) -> Spread {
        let varavg = if avg > 0.001 { 100.0 * (mean_square - avg * avg).max(0.0).sqrt() / avg } else { 0.0 };
        Spread { min, avg, max, varavg }
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

    /// Fixes in one stage: each is charged the time up to the next reading, and together they
    /// make the stage's time (one fix alone costs no reading of its own).
    #[test]
    fn the_fixes_of_a_stage_share_its_time() {
        let mut t = Timers::default();
        t.stamp();
        for k in [0, 2] {
            t.fix_starts();
            std::thread::sleep(std::time::Duration::from_millis(2));
            t.fix_ran(k);
        }
        t.charge(Stage::Modify);
        let m = t.seconds[Stage::Modify as usize];
        assert_eq!(t.fix_seconds.len(), 3);
        assert!(t.fix_seconds[0] >= 0.002 && t.fix_seconds[1] == 0.0 && t.fix_seconds[2] >= 0.002);
        assert_eq!(m, t.fix_seconds[0] + t.fix_seconds[2]);
        t.charge(Stage::Pair);
        assert_eq!(t.fix_seconds[2] + t.fix_seconds[0], m, "a charge without a fix that ran charges no fix");
    }

    /// The spread over ranks: mean, extremes and the standard deviation in per cent of the mean.
    #[test]
    fn a_spread_is_lammps_varavg() {
        let s = Spread::of(&[1.0, 3.0]);
        assert_eq!((s.min, s.avg, s.max), (1.0, 2.0, 3.0));
        assert!((s.varavg - 50.0).abs() < 1e-12, "{s:?}");
        assert_eq!(Spread::of(&[0.0005, 0.0001]).varavg, 0.0, "below a millisecond: 0");
        let t = Timers { seconds: [2.0, 0.0, 0.0, 0.0, 0.0, 0.0], ..Timers::default() };
        let mut spread = [Spread::default(); 6];
        spread[0] = s;
        let table = t.report(4.0, Some(&spread));
        assert!(table.contains("Pair    | 1.00000    | 2.00000    | 3.00000    |  50.0 | 50.00"), "{table}");
        assert!(t.report(4.0, None).contains("Pair    | 2.00000    | 2.00000    | 2.00000    |   0.0 | 50.00"));
    }
}
