//! `fix ID group ave/correlate Nevery Nrepeat Nfreq value ... [type auto|upper|lower|auto/upper|
//! auto/lower|full] [ave one|running] [start S] [prefactor p] [file F] [overwrite] [title1 T]
//! [title2 T] [title3 T]`: time correlations of global values (`c_ID`, `c_ID[i]`, `f_ID`,
//! `f_ID[i]`, `v_name`; `[*]` expands), as LAMMPS' fix ave/correlate: a sample every Nevery steps
//! (from the step it is defined, or `start`), the last Nrepeat samples kept, and with each new
//! sample C_ij(k Nevery) += V_i(t - k Nevery) V_j(t) for each pair of the `type` and each lag k
//! the samples reach. On multiples of Nfreq the averages (sum over count, times the prefactor)
//! become its global array, Nrepeat rows of (time delta, count, C of each pair), and go to the
//! file; `ave one` then starts the sums again from the latest sample.

use super::ave_time::{global_value, Source};
use super::sampling::{format_value, AveFile};
use super::{Fix, FixCtx, FixDef, FixHooks};
use crate::engine::state::{RunError, State};
use crate::models::world::World;
use dmhs_parser::{Args, DResult, EvalContext};

pub const SYNTAX: &str = "fix ID group ave/correlate Nevery Nrepeat Nfreq value ... [type auto|upper|lower|auto/upper|auto/lower|full] [ave one|running] [start S] [prefactor p] [file F] [overwrite] [title1 T] [title2 T] [title3 T]";

/// Which products of the values are correlated (LAMMPS' `type`).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Pairs {
    Auto,
    Upper,
    Lower,
    AutoUpper,
    AutoLower,
    Full,
}

impl Pairs {
    const NAMES: [&'static str; 6] = ["auto", "upper", "lower", "auto/upper", "auto/lower", "full"];
    const ALL: [Pairs; 6] = [Pairs::Auto, Pairs::Upper, Pairs::Lower, Pairs::AutoUpper, Pairs::AutoLower, Pairs::Full];

    /// The pairs (i, j) of `n` values in LAMMPS' order: C_ij pairs the older V_i with the newer V_j.
    fn of(self, n: usize) -> Vec<(usize, usize)> {
        let all = (0..n).flat_map(|i| (0..n).map(move |j| (i, j)));
        match self {
            Pairs::Auto => (0..n).map(|i| (i, i)).collect(),
            Pairs::Upper => all.filter(|(i, j)| j > i).collect(),
            Pairs::Lower => all.filter(|(i, j)| j < i).collect(),
            Pairs::AutoUpper => all.filter(|(i, j)| j >= i).collect(),
            Pairs::AutoLower => all.filter(|(i, j)| j <= i).collect(),
            Pairs::Full => all.collect(),
        }
    }
}

/// One input value: its producer and 1-based element (None: the scalar).
#[derive(Clone, Debug)]
struct Value {
    source: Source,
    id: String,
    index: Option<usize>,
}

pub struct FixAveCorrelate {
    id: String,
    groupbit: u32,
    nevery: i64,
    nrepeat: usize,
    nfreq: i64,
    start: i64,
    prefactor: f64,
    running: bool,
    values: Vec<Value>,
    pairs: Vec<(usize, usize)>,
    file: Option<AveFile>,
    /// The last `nrepeat` samples, a ring: `ring[last]` the newest, `len` of them filled.
    ring: Vec<Vec<f64>>,
    last: usize,
    len: usize,
    /// Per lag: the products summed and how many.
    corr: Vec<Vec<f64>>,
    count: Vec<u64>,
    /// What the array reads: the averages of the last Nfreq step.
    saved: Vec<Vec<f64>>,
    saved_count: Vec<u64>,
    /// The next sampling step, and the last one taken (a timestep moved back past it is an error).
    next: i64,
    last_taken: i64,
}

impl FixAveCorrelate {
    pub fn from_lammps(d: FixDef, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(d.args, d.cmd.span, SYNTAX);
        let nevery = a.i64("Nevery")?;
        let nrepeat = a.i64("Nrepeat")?;
        let nfreq = a.i64("Nfreq")?;
        let raw = super::ave_time::global_values(&mut a)?;
        let (mut kind, mut running, mut start, mut prefactor, mut overwrite) = (Pairs::Auto, false, 0, 1.0, None);
        let (mut file, mut titles) = (None, [None, None, None]);
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "type" => kind = Pairs::ALL[a.choice("type", &Pairs::NAMES)?],
                "ave" => running = a.choice("ave", &["one", "running"])? == 1,
                "start" => start = a.i64("start step")?,
                "prefactor" => prefactor = a.f64("prefactor")?,
                "file" => {
                    file = a.peek();
                    a.word("file name")?;
                }
                "overwrite" => overwrite = Some(w),
                "title1" | "title2" | "title3" => {
                    let k = (w.text.as_bytes()[5] - b'1') as usize;
                    titles[k] = Some(a.word("title")?.text.clone());
                }
                _ => return Err(a.unknown_keyword(w, &["type", "ave", "start", "prefactor", "file", "overwrite", "title1", "title2", "title3"])),
            }
        }
        // LAMMPS' checks, with its message
        let illegal = |what: &str| a.error_command(format!("Illegal fix ave/correlate command: {what}"), "illegal");
        if nevery <= 0 || nrepeat <= 0 || nfreq <= 0 {
            return Err(illegal("Nevery, Nrepeat and Nfreq must be positive"));
        }
        if nfreq % nevery != 0 {
            return Err(illegal("Nfreq must be a multiple of Nevery"));
        }
        if !running && nfreq < (nrepeat - 1) * nevery {
            return Err(illegal("with ave one, Nfreq must be at least (Nrepeat-1)*Nevery"));
        }
        if let (Some(w), false) = (overwrite, running) {
            return Err(a.error_at(w, "Illegal fix ave/correlate command: overwrite needs ave running", "overwrite"));
        }

        // each value, wildcards expanded, checked against what its producer offers
        let mut values = Vec::new();
        let mut names = Vec::new();
        for w in raw {
            let (source, name) = Source::of(&w.text);
            let compute = d.computes.iter().find(|c| c.id() == name);
            let fix = d.fixes.iter().find(|f| f.id() == name);
            let len = match source {
                Source::Compute => compute.and_then(|c| c.size_vector()),
                Source::Fix => fix.map(|f| f.size_vector()).filter(|&n| n > 0),
                Source::Variable => None,
            };
            for text in super::ave_time::expand(w, len, &a)? {
                let (_, index) = super::value::split_index(&text, w, &a)?;
                match source {
                    Source::Compute => {
                        let c = compute.ok_or_else(|| a.error_at(w, format!("Compute ID {name} for fix ave/correlate does not exist"), "unknown compute"))?;
                        // (a compute whose length is known only when it runs is checked then)
                        if let (Some(i), Some(n)) = (index, c.size_vector()) {
                            if i > n {
                                return Err(a.error_at(w, format!("Fix ave/correlate compute {name} vector is accessed out-of-range"), "out of range"));
                            }
                        }
                    }
                    Source::Fix => {
                        let f = fix.ok_or_else(|| a.error_at(w, format!("Fix ID {name} for fix ave/correlate does not exist"), "unknown fix"))?;
                        if index.is_some_and(|i| i > f.size_vector()) {
                            return Err(a.error_at(w, format!("Fix ave/correlate fix {name} vector is accessed out-of-range"), "out of range"));
                        }
                        if nevery % f.global_freq().max(1) != 0 {
                            return Err(a.error_at(w, format!("Fix {name} for fix ave/correlate not computed at compatible time"), "incompatible Nevery"));
                        }
                    }
                    Source::Variable => {
                        if index.is_some() {
                            return Err(a.error_at(w, "fix ave/correlate reads equal-style variables only (vector-style variables are not supported)", "vector variable"));
                        }
                    }
                }
                values.push(Value { source, id: name.to_string(), index });
                names.push(text);
            }
        }
        let pairs = kind.of(values.len());
        let nrepeat = nrepeat as usize;
        let mut fix = FixAveCorrelate {
            id: d.id.clone(),
            groupbit: d.groupbit,
            nevery,
            nrepeat,
            nfreq,
            start,
            prefactor,
            running,
            values,
            file: None,
            ring: vec![vec![0.0; names.len()]; nrepeat],
            last: nrepeat - 1,
            len: 0,
            corr: vec![vec![0.0; pairs.len()]; nrepeat],
            count: vec![0; nrepeat],
            saved: vec![vec![0.0; pairs.len()]; nrepeat],
            saved_count: vec![0; nrepeat],
            pairs,
            next: 0,
            last_taken: -1,
        };
        fix.next = fix.next_valid(state.step);
        // on ranks rank 0 alone writes the file (its values are the same on every rank)
        if let Some(w) = file.filter(|_| state.writes_files()) {
            let path = d.path(&w.text);
            let head = fix.header(kind, &names, &titles);
            fix.file = Some(AveFile::create(&path, &head, overwrite.is_some()).map_err(|e| a.error_at(w, format!("Cannot open fix ave/correlate file {}: {e}", path.display()), "cannot open"))?);
        }
        Ok(fix)
    }

    /// The first sampling step from `step` on: a multiple of Nevery, not before `start`.
    fn next_valid(&self, step: i64) -> i64 {
        let s = step.max(self.start);
        if s % self.nevery != 0 {
            (s / self.nevery) * self.nevery + self.nevery
        } else {
            s
        }
    }

    /// The comment lines at the top of the file (LAMMPS' titles). LAMMPS 22 Jul 2025's default
    /// third line names fewer pairs than it computes for two types: `lower` lists j < i - 1 and
    /// `auto/lower` j < i; written the same here.
    fn header(&self, kind: Pairs, names: &[String], titles: &[Option<String>; 3]) -> String {
        let line = |k: usize, default: String| titles[k].clone().unwrap_or(default) + "\n";
        let below = |gap: usize| (0..names.len()).flat_map(move |i| (0..i.saturating_sub(gap)).map(move |j| (i, j))).collect::<Vec<_>>();
        let listed = match kind {
            Pairs::Lower => below(1),
            Pairs::AutoLower => below(0),
            _ => self.pairs.clone(),
        };
        let columns: String = listed.iter().map(|&(i, j)| format!(" {}*{}", names[i], names[j])).collect();
        line(0, format!("# Time-correlated data for fix {}", self.id)) + &line(1, "# Timestep Number-of-time-windows".into()) + &line(2, format!("# Index TimeDelta Ncount{columns}"))
    }

    /// One sample of every value.
    fn sample(&self, w: &World, ev: &mut dyn EvalContext) -> Result<Vec<f64>, String> {
        let who = format!("fix ave/correlate {}", self.id);
        self.values.iter().map(|v| global_value(v.source, &v.id, v.index, w, ev, &who)).collect()
    }

    /// Add the products the newest sample makes with itself and each older one.
    fn accumulate(&mut self) {
        let newest = &self.ring[self.last];
        for k in 0..self.len {
            self.count[k] += 1;
            let older = &self.ring[(self.last + self.nrepeat - k) % self.nrepeat];
            for (c, &(i, j)) in self.corr[k].iter_mut().zip(&self.pairs) {
                *c += older[i] * newest[j];
            }
        }
    }

    fn invoke(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        let step = state.step;
        if step < self.last_taken || step > self.next {
            return Err(RunError::new(step, format!("Invalid timestep reset for fix ave/correlate {}", self.id)));
        }
        if step != self.next {
            return Ok(());
        }
        self.last_taken = step;
        let sample = ctx.eval(state, self, |w, ev| self.sample(w, ev))?;
        self.last = (self.last + 1) % self.nrepeat;
        self.ring[self.last] = sample;
        self.len = (self.len + 1).min(self.nrepeat);
        self.next += self.nevery;
        self.accumulate();
        if step % self.nfreq != 0 {
            return Ok(());
        }
        for k in 0..self.nrepeat {
            self.saved_count[k] = self.count[k];
            for (s, &c) in self.saved[k].iter_mut().zip(&self.corr[k]) {
                *s = if self.count[k] > 0 { self.prefactor * c / self.count[k] as f64 } else { 0.0 };
            }
        }
        self.write(step).map_err(|e| RunError::new(step, e))?;
        if !self.running {
            // the sums start again, from the latest sample alone
            self.corr.iter_mut().for_each(|r| r.fill(0.0));
            self.count.fill(0);
            self.len = 1;
            self.accumulate();
        }
        Ok(())
    }

    /// The Nfreq step's block in the file (`%g` values, `0.0` for a lag without samples).
    fn write(&mut self, step: i64) -> Result<(), String> {
        let Some(file) = self.file.as_mut() else { return Ok(()) };
        let mut s = format!("{step} {}\n", self.nrepeat);
        for k in 0..self.nrepeat {
            s += &format!("{} {} {}", k + 1, k as i64 * self.nevery, self.count[k]);
            for x in &self.saved[k] {
                s += &if self.count[k] > 0 { format_value(None, *x) } else { " 0.0".to_string() };
            }
            s.push('\n');
        }
        file.write(&s).map_err(|e| format!("fix ave/correlate {}: error writing the file: {e}", self.id))
    }
}

impl Fix for FixAveCorrelate {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "ave/correlate"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { end_of_step: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        // a step passed without sampling (a minimization): the ring starts again
        if self.next < state.step {
            self.len = 0;
            self.last = self.nrepeat - 1;
            self.next = self.next_valid(state.step);
        }
        Ok(())
    }
    fn setup(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.invoke(state, ctx)
    }
    fn end_of_step(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.invoke(state, ctx)
    }
    fn global_freq(&self) -> i64 {
        self.nfreq
    }
    fn wants_energy(&self, step: i64) -> bool {
        step == self.next
    }
    fn array(&self, _state: &State, i: usize, j: usize) -> Option<f64> {
        let k = i.checked_sub(1).filter(|&k| k < self.nrepeat)?;
        match j {
            1 => Some(k as f64 * self.nevery as f64),
            2 => Some(self.saved_count[k] as f64),
            // (zero for a lag without samples: `invoke` saves it so)
            _ => self.saved[k].get(j.checked_sub(3)?).copied(),
        }
    }
    fn size_array(&self) -> Option<(usize, usize)> {
        Some((self.nrepeat, self.pairs.len() + 2))
    }
    fn array_extensive(&self) -> bool {
        false
    }
}
