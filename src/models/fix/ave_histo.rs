//! `fix ID group ave/histo Nevery Nrepeat Nfreq lo hi Nbin value ... [mode scalar|vector]
//! [ave one|running|window M] [start S] [beyond ignore|end|extra] [overwrite] [file F]
//! [title1 T] [title2 T] [title3 T]`: a histogram of values sampled Nrepeat times Nevery steps
//! apart, ending on multiples of Nfreq, as LAMMPS' fix ave/histo. Values are all global (`c_ID`,
//! `c_ID[i]`, `f_ID`, `f_ID[i]`, `v_name`; in vector mode `c_ID`, `c_ID[j]` and `f_ID` are whole
//! vectors or array columns), all per-atom (`x y z vx vy vz fx fy fz`, `c_ID`, `c_ID[j]`, `f_ID`,
//! `f_ID[j]`, atom-style `v_name`, the group's atoms; vector mode) or all local (`c_ID`,
//! `c_ID[j]`; vector mode). Values outside [lo, hi] are not counted (`ignore`, counted as
//! missing), counted in the end bins (`end`), or in two extra bins (`extra`).
//!
//! f_ID[1..4] are the total and missing counts and the smallest and largest value seen; the
//! file holds each period's histogram in LAMMPS' layout. The histogram as a global array
//! (f_ID[i][j]) is not offered: dmhs' expressions have no two-index references.

use super::sampling::{Ave, AveFile, Sampling};
use super::{Fix, FixCtx, FixDef, FixHooks};
use crate::engine::state::{RunError, State};
use crate::models::compute::{LocalRef, PerAtomRef};
use crate::models::world::World;
use dmhs_parser::numfmt::{format_g, shortest};
use dmhs_parser::{Args, DResult, EvalContext, Word};

pub const SYNTAX: &str = "fix ID group ave/histo Nevery Nrepeat Nfreq lo hi Nbin value ... [mode scalar|vector] [ave one|running|window M] [start S] [beyond ignore|end|extra] [overwrite] [file F] [title1 T] [title2 T] [title3 T] [kind global|peratom|local]";

const ATOM_VALUES: [&str; 9] = ["x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz"];

#[derive(Clone, Copy, PartialEq, Debug)]
enum Kind {
    Global,
    PerAtom,
    Local,
}

impl Kind {
    fn name(self) -> &'static str {
        ["global", "per-atom", "local"][self as usize]
    }
}

#[derive(Clone, Copy, PartialEq)]
enum Beyond {
    Ignore,
    End,
    Extra,
}

/// One input value.
enum Value {
    /// x, v or f (0, 1, 2) and the component.
    Atom(usize, usize),
    /// `c_ID`/`f_ID` with its 1-based index (element or column).
    Compute(String, Option<usize>),
    Fix(String, Option<usize>),
    Variable(String),
}

/// Per-atom and local values need vector mode, as in LAMMPS.
fn check_mode(kind: Kind, vector_mode: bool) -> Result<(), String> {
    match (kind, vector_mode) {
        (Kind::PerAtom, false) => Err("fix ave/histo cannot process per-atom values in scalar mode".into()),
        (Kind::Local, false) => Err("fix ave/histo cannot process local values in scalar mode".into()),
        _ => Ok(()),
    }
}

/// Counts of one period or of the totals: total, missing, min, max (LAMMPS' stats) and bins.
#[derive(Clone)]
struct Histogram {
    stats: [f64; 4],
    bins: Vec<f64>,
}

impl Histogram {
    fn empty(nbins: usize) -> Histogram {
        Histogram { stats: [0.0, 0.0, 1.0e20, -1.0e20], bins: vec![0.0; nbins] }
    }
}

pub struct FixAveHisto {
    id: String,
    groupbit: u32,
    sampling: Sampling,
    lo: f64,
    hi: f64,
    bininv: f64,
    /// Bin centres (with `extra`, lo and hi for the two outer bins).
    coord: Vec<f64>,
    values: Vec<Value>,
    kind: Kind,
    /// The `kind` keyword named it (variables must then be of that kind).
    kind_given: bool,
    vector_mode: bool,
    beyond: Beyond,
    ave: Ave,
    /// This period's counts and the totals over periods.
    period: Histogram,
    total: Histogram,
    /// ave window: the last M periods, oldest replaced first.
    window: Vec<Histogram>,
    iwindow: usize,
    file: Option<AveFile>,
}

impl FixAveHisto {
    pub fn from_lammps(d: FixDef, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(d.args, d.cmd.span, SYNTAX);
        let mut sampling = Sampling::parse(&mut a, "ave/histo")?;
        let lo = a.f64("lo")?;
        let w_hi = a.peek();
        let hi = a.f64("hi")?;
        if lo >= hi {
            return Err(a.error_at(w_hi.expect("hi was read"), format!("fix ave/histo: lo {lo} must be below hi {hi}"), "hi <= lo"));
        }
        let nbins_word = a.peek().cloned();
        let nbins = a.usize_min("Nbin", 1)?;
        // the histograms of one step, the running total and the window's: a few per bin
        crate::engine::memory::check_fits(nbins as f64 * 4.0 * 8.0, &format!("fix ave/histo: {nbins} bins x 4 doubles"))
            .map_err(|m| a.error_at(nbins_word.as_ref().expect("Nbin was read"), m, "too many bins"))?;
        let mut raw: Vec<&Word> = Vec::new();
        while let Some(w) = a.peek() {
            if ATOM_VALUES.contains(&w.text.as_str()) || w.text.starts_with("c_") || w.text.starts_with("f_") || w.text.starts_with("v_") {
                raw.push(w);
                a.skip(1);
            } else {
                break;
            }
        }
        if raw.is_empty() {
            return Err(a.missing("a value (x, vx, fx, ..., c_ID, c_ID[i], f_ID, f_ID[i] or v_name)"));
        }
        let (mut vector_mode, mut ave, mut beyond, mut overwrite) = (false, Ave::One, Beyond::Ignore, false);
        let (mut file, mut titles): (Option<&Word>, [Option<String>; 3]) = (None, [None, None, None]);
        let mut forced: Option<(Kind, &Word)> = None;
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "mode" => vector_mode = a.choice("mode", &["scalar", "vector"])? == 1,
                "ave" => ave = Ave::parse(&mut a)?,
                "start" => sampling.start = a.i64("start step")?,
                "beyond" => beyond = [Beyond::Ignore, Beyond::End, Beyond::Extra][a.choice("beyond", &["ignore", "end", "extra"])?],
                "overwrite" => overwrite = true,
                "file" => file = Some(a.word("file name")?),
                "title1" | "title2" | "title3" => titles[(w.text.as_bytes()[5] - b'1') as usize] = Some(a.str("title")?.to_string()),
                "kind" => {
                    let k = [Kind::Global, Kind::PerAtom, Kind::Local][a.choice("kind", &["global", "peratom", "local"])?];
                    forced = Some((k, w));
                }
                "weights" | "append" => return Err(a.error_at(w, format!("fix ave/histo {} is not supported by dmhs", w.text), "not supported")),
                _ => return Err(a.unknown_keyword(w, &["mode", "ave", "start", "beyond", "overwrite", "file", "title1", "title2", "title3", "kind"])),
            }
        }
        if overwrite && ave != Ave::Running {
            return Err(a.missing("`ave running` (the overwrite keyword requires it)"));
        }

        // each value and its kind (global, per-atom or local), as LAMMPS decides it
        let mut values = Vec::new();
        let mut kind = None;
        for w in raw {
            let t = w.text.as_str();
            let (value, k) = if let Some(i) = ATOM_VALUES.iter().position(|v| *v == t) {
                if let Some((k, kw)) = forced.filter(|f| f.0 != Kind::PerAtom) {
                    return Err(a.error_at(kw, format!("fix ave/histo: `{t}` is a per-atom value, not {}", k.name()), "per-atom input"));
                }
                (Value::Atom(i / 3, i % 3), Some(Kind::PerAtom))
            } else {
                let name = &t[2..];
                let (id, index) = super::value::split_index(name, w, &a)?;
                match &t[..2] {
                    "c_" => {
                        let c = d.computes.iter().find(|c| c.id() == id).ok_or_else(|| a.error_at(w, format!("Compute ID {id} for fix ave/histo does not exist"), "unknown compute"))?;
                        let has = |k: Kind| match k {
                            Kind::PerAtom => c.peratom_cols().is_some(),
                            Kind::Local => c.local_cols().is_some(),
                            Kind::Global => c.peratom_cols().is_none() && c.local_cols().is_none() || c.size_vector().is_some(),
                        };
                        let k = match forced {
                            Some((k, _)) if !has(k) => return Err(a.error_at(w, format!("Fix ave/histo input is invalid compute: {id} has no {} values", k.name()), "wrong kind")),
                            Some((k, _)) => k,
                            None if c.peratom_cols().is_some() => Kind::PerAtom,
                            None if c.local_cols().is_some() => Kind::Local,
                            None => Kind::Global,
                        };
                        (Value::Compute(id.to_string(), index), Some(k))
                    }
                    "f_" => {
                        let f = d.fixes.iter().find(|f| f.id() == id).ok_or_else(|| a.error_at(w, format!("Fix ID {id} for fix ave/histo does not exist"), "unknown fix"))?;
                        let k = match forced {
                            Some((Kind::Local, _)) => return Err(a.error_at(w, format!("Fix ave/histo input is invalid fix: {id} has no local values"), "wrong kind")),
                            Some((Kind::PerAtom, _)) if f.peratom_cols().is_none() => return Err(a.error_at(w, format!("Fix ave/histo input is invalid fix: {id} has no per-atom values"), "wrong kind")),
                            Some((k, _)) => k,
                            None if f.peratom_cols().is_some() => Kind::PerAtom,
                            None => Kind::Global,
                        };
                        if k == Kind::Global && sampling.nevery % f.global_freq() != 0 {
                            return Err(a.error_at(w, format!("Fix {id} for fix ave/histo not computed at compatible time"), "every"));
                        }
                        (Value::Fix(id.to_string(), index), Some(k))
                    }
                    _ => {
                        if index.is_some() {
                            return Err(a.error_at(w, "fix ave/histo reads equal- and atom-style variables only (no vector-style element)", "vector variable"));
                        }
                        // equal or atom style: known when a run starts (or given by kind)
                        (Value::Variable(id.to_string()), forced.map(|f| f.0))
                    }
                }
            };
            if let (Some(k0), Some(k)) = (kind, k) {
                if k0 != k {
                    return Err(a.error_at(w, "Fix ave/histo inputs are not all global, peratom, or local", "another kind"));
                }
            }
            kind = kind.or(k);
            values.push(value);
        }
        if let Some(k) = kind {
            check_mode(k, vector_mode).map_err(|e| a.error_at(&d.cmd.name, e, "add `mode vector`"))?;
        }
        let nbins = if beyond == Beyond::Extra { nbins + 2 } else { nbins };
        let binsize = if beyond == Beyond::Extra { (hi - lo) / (nbins - 2) as f64 } else { (hi - lo) / nbins as f64 };
        let coord = (0..nbins)
            .map(|i| match beyond {
                Beyond::Extra if i == 0 => lo,
                Beyond::Extra if i == nbins - 1 => hi,
                Beyond::Extra => lo + ((i - 1) as f64 + 0.5) * binsize,
                _ => lo + (i as f64 + 0.5) * binsize,
            })
            .collect();
        let mut fix = FixAveHisto {
            id: d.id.clone(),
            groupbit: d.groupbit,
            sampling,
            lo,
            hi,
            bininv: 1.0 / binsize,
            coord,
            values,
            kind: kind.unwrap_or(Kind::Global),
            kind_given: forced.is_some(),
            vector_mode,
            beyond,
            ave,
            period: Histogram::empty(nbins),
            total: Histogram { stats: [0.0; 4], bins: vec![0.0; nbins] },
            window: Vec::new(),
            iwindow: 0,
            file: None,
        };
        // on ranks rank 0 alone writes the file (the counts are summed over the ranks)
        if let Some(w) = file.filter(|_| state.writes_files()) {
            let head = format!(
                "{}\n{}\n{}\n",
                titles[0].clone().unwrap_or_else(|| format!("# Histogrammed data for fix {}", d.id)),
                titles[1].clone().unwrap_or_else(|| "# TimeStep Number-of-bins Total-counts Missing-counts Min-value Max-value".into()),
                titles[2].clone().unwrap_or_else(|| "# Bin Coord Count Count/Total".into()),
            );
            let path = d.path(&w.text);
            fix.file = Some(AveFile::create(&path, &head, overwrite).map_err(|e| a.error_at(w, format!("Cannot open fix ave/histo file {}: {e}", path.display()), "cannot open"))?);
        }
        fix.sampling.begin(state.step);
        Ok(fix)
    }

    /// Count one value (LAMMPS' bin_one).
    fn bin_one(&mut self, x: f64) {
        let h = &mut self.period;
        let n = h.bins.len();
        h.stats[2] = h.stats[2].min(x);
        h.stats[3] = h.stats[3].max(x);
        if x < self.lo || x > self.hi {
            if self.beyond == Beyond::Ignore {
                h.stats[1] += 1.0;
                return;
            }
            h.bins[if x < self.lo { 0 } else { n - 1 }] += 1.0;
        } else {
            let mut ibin = (((x - self.lo) * self.bininv) as usize).min(n - 1);
            if self.beyond == Beyond::Extra {
                ibin += 1;
            }
            h.bins[ibin] += 1.0;
        }
        h.stats[0] += 1.0;
    }

    /// The values of one sample, in the order LAMMPS bins them (per-atom: the group's atoms).
    fn sample(&self, w: &World, ev: &mut dyn EvalContext) -> Result<Vec<f64>, String> {
        let s = w.state;
        let a = &s.atoms;
        let members = |vals: &dyn Fn(usize) -> f64| (0..a.nlocal).filter(|&i| a.mask[i] & self.groupbit != 0).map(vals).collect::<Vec<f64>>();
        let mut out = Vec::new();
        for v in &self.values {
            match (v, self.kind) {
                (Value::Atom(q, k), _) => out.extend(members(&|i| [a.x[i], a.v[i], a.f[i]][*q][*k])),
                (Value::Compute(id, index), Kind::Global) => {
                    let c = w.compute(id).ok_or_else(|| format!("compute `{id}` does not exist"))?;
                    match (self.vector_mode, index) {
                        (false, None) => out.push(c.scalar(w)?),
                        (false, Some(i)) => out.push(*c.vector(w)?.get(i - 1).ok_or_else(|| format!("Fix ave/histo compute {id} vector is accessed out-of-range"))?),
                        (true, None) => out.extend(c.vector(w)?),
                        (true, Some(j)) => {
                            for r in c.array(w)? {
                                out.push(*r.get(j - 1).ok_or_else(|| format!("Fix ave/histo compute {id} array is accessed out-of-range"))?);
                            }
                        }
                    }
                }
                (Value::Fix(id, index), Kind::Global) => {
                    let f = w.fix(id).ok_or_else(|| format!("fix `{id}` does not exist"))?;
                    let missing = || format!("fix `{id}` ({}) has no such global value", f.style());
                    match (self.vector_mode, index) {
                        (false, None) => out.push(f.scalar(s).ok_or_else(missing)?),
                        (false, Some(i)) => out.push(f.vector(s, *i).ok_or_else(missing)?),
                        (true, None) => {
                            for i in 1..=f.size_vector() {
                                out.push(f.vector(s, i).ok_or_else(missing)?);
                            }
                        }
                        (true, Some(_)) => return Err(format!("fix ave/histo: fix `{id}` has no global array dmhs can read")),
                    }
                }
                (Value::Compute(id, index) | Value::Fix(id, index), Kind::PerAtom) => {
                    let prefix = if matches!(v, Value::Fix(..)) { "f_" } else { "c_" };
                    let name = match index {
                        Some(i) => format!("{prefix}{id}[{i}]"),
                        None => format!("{prefix}{id}"),
                    };
                    let r = PerAtomRef::parse(&name, w).expect("c_ or f_")?;
                    let p = r.values(w)?;
                    out.extend(members(&|i| r.get(&p, i)));
                }
                (Value::Compute(id, index) | Value::Fix(id, index), Kind::Local) => {
                    let prefix = if matches!(v, Value::Fix(..)) { "f_" } else { "c_" };
                    let name = match index {
                        Some(i) => format!("{prefix}{id}[{i}]"),
                        None => format!("{prefix}{id}"),
                    };
                    for r in LocalRef::parse(&name, w, None).expect("c_ or f_")? {
                        out.extend(r.rows(w, Some(&mut *ev))?.iter().map(|row| r.get(row)));
                    }
                }
                (Value::Variable(name), _) => match (ev.variables().style(name), self.kind) {
                    (None, _) => return Err(format!("Variable name {name} for fix ave/histo does not exist")),
                    (Some("atom" | "atomfile"), Kind::PerAtom) => {
                        let vals = crate::models::atom_formula::atom_variable(name, w, ev)?;
                        out.extend(members(&|i| vals[i]));
                    }
                    (Some("atom" | "atomfile"), _) => return Err("Fix ave/histo inputs are not all global, peratom, or local".into()),
                    (Some(_), Kind::PerAtom | Kind::Local) => return Err("Fix ave/histo inputs are not all global, peratom, or local".into()),
                    (Some(_), Kind::Global) => out.push(dmhs_parser::variables::compute_equal(ev, name).map_err(|e| format!("variable `{name}`: {e}"))?),
                },
            }
        }
        Ok(out)
    }

    /// Bin one sample; at the last sample of a period, combine and write.
    fn invoke(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        let step = state.step;
        if !self.sampling.due(step) {
            return Ok(());
        }
        if self.sampling.irepeat == 0 {
            self.period = Histogram::empty(self.coord.len());
        }
        let xs = ctx.eval(state, self, |w, ev| self.sample(w, ev).map_err(|e| format!("fix ave/histo {}: {e}", self.id)))?;
        for x in xs {
            self.bin_one(x);
        }
        if !self.sampling.advance(step) {
            return Ok(());
        }
        if self.kind != Kind::Global {
            let h = &mut self.period;
            let mut sums = [h.stats[0], h.stats[1]];
            state.sum_ranks(&mut sums);
            let (mut lo, mut hi) = ([h.stats[2]], [h.stats[3]]);
            state.min_ranks(&mut lo);
            state.max_ranks(&mut hi);
            h.stats = [sums[0], sums[1], lo[0], hi[0]];
            state.sum_ranks(&mut h.bins);
        }
        self.combine();
        self.write(step).map_err(|e| RunError::new(step, format!("fix ave/histo {}: error writing the file: {e}", self.id)))
    }

    /// The totals from this period (LAMMPS' ave one, running, window).
    fn combine(&mut self) {
        let (p, t) = (&self.period, &mut self.total);
        match self.ave {
            Ave::One => *t = p.clone(),
            Ave::Running => {
                t.stats[0] += p.stats[0];
                t.stats[1] += p.stats[1];
                t.stats[2] = t.stats[2].min(p.stats[2]);
                t.stats[3] = t.stats[3].max(p.stats[3]);
                t.bins.iter_mut().zip(&p.bins).for_each(|(t, b)| *t += b);
            }
            Ave::Window(m) => {
                let full = self.window.len() == m;
                if full {
                    let old = &self.window[self.iwindow];
                    t.stats[0] = t.stats[0] + p.stats[0] - old.stats[0];
                    t.stats[1] = t.stats[1] + p.stats[1] - old.stats[1];
                    t.bins.iter_mut().zip(&p.bins).zip(&old.bins).for_each(|((t, b), o)| *t = *t + b - o);
                    self.window[self.iwindow] = p.clone();
                } else {
                    t.stats[0] += p.stats[0];
                    t.stats[1] += p.stats[1];
                    t.bins.iter_mut().zip(&p.bins).for_each(|(t, b)| *t += b);
                    self.window.push(p.clone());
                }
                // min and max over the periods held, in their slots' order
                t.stats[2] = self.window.iter().map(|h| h.stats[2]).fold(f64::INFINITY, f64::min);
                t.stats[3] = self.window.iter().map(|h| h.stats[3]).fold(f64::NEG_INFINITY, f64::max);
                self.iwindow = (self.iwindow + 1) % m;
            }
        }
    }

    /// The period's block in the file: the step line (counts and extremes as LAMMPS' `{}`),
    /// then `bin coord count fraction` with `%g`.
    fn write(&mut self, step: i64) -> std::io::Result<()> {
        let Some(file) = self.file.as_mut() else { return Ok(()) };
        let t = &self.total;
        let n = t.bins.len();
        let mut s = format!("{step} {n} {} {} {} {}\n", shortest(t.stats[0]), shortest(t.stats[1]), shortest(t.stats[2]), shortest(t.stats[3]));
        for (i, (&c, &b)) in self.coord.iter().zip(&t.bins).enumerate() {
            let (count, frac) = if t.stats[0] != 0.0 { (b, b / t.stats[0]) } else { (0.0, 0.0) };
            s += &format!("{} {} {} {}\n", i + 1, format_g(c, 6), format_g(count, 6), format_g(frac, 6));
        }
        file.write(&s)
    }
}

impl Fix for FixAveHisto {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "ave/histo"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { end_of_step: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        self.sampling.init(state.step);
        Ok(())
    }
    fn setup_pre_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        // the variables' kinds (equal: global, atom: per-atom), as LAMMPS finds them
        let names: Vec<String> = self.values.iter().filter_map(|v| if let Value::Variable(n) = v { Some(n.clone()) } else { None }).collect();
        if names.is_empty() {
            return Ok(());
        }
        let styles = ctx.eval(state, self, |_, ev| Ok(names.iter().map(|n| ev.variables().style(n)).collect::<Vec<_>>()))?;
        let err = |m: String| RunError::new(state.step, format!("fix ave/histo {}: {m}", self.id));
        let fixed = self.kind_given || self.values.iter().any(|v| !matches!(v, Value::Variable(_)));
        let mut kind = fixed.then_some(self.kind);
        for (n, st) in names.iter().zip(styles) {
            let k = match st {
                None => return Err(err(format!("Variable name {n} for fix ave/histo does not exist"))),
                Some("atom" | "atomfile") => Kind::PerAtom,
                Some(_) => Kind::Global,
            };
            if kind.is_some_and(|k0| k0 != k) {
                return Err(err("Fix ave/histo inputs are not all global, peratom, or local".into()));
            }
            kind = Some(k);
        }
        self.kind = kind.unwrap_or(Kind::Global);
        check_mode(self.kind, self.vector_mode).map_err(err)
    }
    fn setup(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.invoke(state, ctx)
    }
    fn end_of_step(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.invoke(state, ctx)
    }
    fn global_freq(&self) -> i64 {
        self.sampling.nfreq
    }
    fn wants_energy(&self, step: i64) -> bool {
        self.sampling.due(step)
    }
    fn size_vector(&self) -> usize {
        4
    }
    fn vector(&self, _state: &State, i: usize) -> Option<f64> {
        (1..=4).contains(&i).then(|| self.total.stats[i - 1])
    }
    /// Per bin: its coordinate, the count, the count over the total (0 while nothing counted).
    fn array(&self, _state: &State, i: usize, j: usize) -> Option<f64> {
        let t = &self.total;
        let b = *t.bins.get(i.wrapping_sub(1))?;
        match j {
            1 => Some(self.coord[i - 1]),
            2 => Some(b),
            3 => Some(if t.stats[0] != 0.0 { b / t.stats[0] } else { 0.0 }),
            _ => None,
        }
    }
    fn size_array(&self) -> Option<(usize, usize)> {
        Some((self.coord.len(), 3))
    }
}
