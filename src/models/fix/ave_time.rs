//! `fix ID group ave/time Nevery Nrepeat Nfreq value ... [mode scalar|vector] [ave one|running|window M]
//! [start S] [off col] [overwrite] [format F] [file F] [title1 T] [title2 T] [title3 T]`: averages of
//! global values (`c_ID`, `c_ID[i]`, `f_ID`, `f_ID[i]`, `v_name`; `[*]` expands) over Nrepeat
//! samples Nevery steps apart, ending on multiples of Nfreq, as LAMMPS' fix ave/time: the same
//! sampling steps, sums in the same order, and the same file layout (`%g` per value).
//!
//! Its result is `f_ID` (one value in scalar mode), `f_ID[i]` (several values, or the rows of one
//! vector in vector mode).

use super::sampling::{format_value, Ave, AveFile, Combine, FileOptions, Sampling};
use super::{Fix, FixCtx, FixDef, FixHooks};
use crate::engine::state::{RunError, State};
use crate::models::world::World;
use dmhs_parser::{Args, DResult, EvalContext, Word};

pub const SYNTAX: &str = "fix ID group ave/time Nevery Nrepeat Nfreq value ... [mode scalar|vector] [ave one|running|window M] [start S] [off col] [overwrite] [format F] [file F] [title1 T] [title2 T] [title3 T]";

/// Where a value comes from (shared with fix ave/correlate).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Source {
    Compute,
    Fix,
    Variable,
}

impl Source {
    /// The producer of a value word (`c_ID[i]`, `f_ID`, `v_name`, ...) and its ID.
    pub(super) fn of(text: &str) -> (Source, &str) {
        let source = match &text[..2] {
            "c_" => Source::Compute,
            "f_" => Source::Fix,
            _ => Source::Variable,
        };
        (source, text[2..].split('[').next().unwrap_or(""))
    }
}

/// One input value.
#[derive(Clone, Debug)]
struct Value {
    source: Source,
    id: String,
    /// 1-based element (scalar mode) or column (vector mode); None: the whole scalar/vector.
    index: Option<usize>,
    /// `off`: the last sample, not an average.
    off: bool,
    /// Extensive (thermo normalises it), from the producer.
    extensive: bool,
}

pub struct FixAveTime {
    id: String,
    groupbit: u32,
    sampling: Sampling,
    values: Vec<Value>,
    vector_mode: bool,
    format: Option<String>,
    file: Option<AveFile>,
    /// Sums of this Nfreq period: rows x values (one row in scalar mode).
    sum: Vec<Vec<f64>>,
    /// Accumulated over periods (ave running/window), divided by `combine.norm` when read.
    total: Vec<Vec<f64>>,
    combine: Combine,
}

/// The value words at the front of `a` (`c_`, `f_`, `v_`), at least one (shared with fix
/// ave/correlate).
pub(super) fn global_values<'a>(a: &mut Args<'a>) -> DResult<Vec<&'a Word>> {
    let mut raw = Vec::new();
    while let Some(w) = a.peek() {
        if w.text.starts_with("c_") || w.text.starts_with("f_") || w.text.starts_with("v_") {
            raw.push(w);
            a.skip(1);
        } else {
            break;
        }
    }
    if raw.is_empty() {
        return Err(a.missing("a value (c_ID, c_ID[i], f_ID, f_ID[i] or v_name)"));
    }
    Ok(raw)
}

/// Expand `c_ID[*]`, `c_ID[n*]`, `c_ID[*m]`, `c_ID[n*m]` into `c_ID[k]` for k in the range
/// (LAMMPS' utils::expand_args), where `len` is the number of elements of that value.
pub(super) fn expand(w: &Word, len: Option<usize>, a: &Args) -> DResult<Vec<String>> {
    let t = &w.text;
    let (Some(open), true) = (t.find('['), t.ends_with(']')) else { return Ok(vec![t.clone()]) };
    let inner = &t[open + 1..t.len() - 1];
    let Some(star) = inner.find('*') else { return Ok(vec![t.clone()]) };
    let n = len.ok_or_else(|| a.error_at(w, format!("`{t}`: the length of this value is not known, so `*` cannot be expanded"), "wildcard"))?;
    let bound = |s: &str, default: usize| -> DResult<usize> {
        if s.is_empty() {
            return Ok(default);
        }
        s.parse::<usize>().map_err(|_| a.error_at(w, format!("`{t}`: bad wildcard range"), "expected n*m"))
    };
    let lo = bound(&inner[..star], 1)?;
    let hi = bound(&inner[star + 1..], n)?.min(n);
    if lo < 1 || lo > hi {
        return Err(a.error_at(w, format!("`{t}`: the range {lo} to {hi} is empty (the value has {n} elements)"), "empty wildcard"));
    }
    Ok((lo..=hi).map(|k| format!("{}[{k}]", &t[..open])).collect())
}

/// One global value now: `c_ID`, `c_ID[i]`, `f_ID`, `f_ID[i]` (1-based `index`) or equal-style
/// `v_name`; `who` names the reading fix in errors (`fix ave/time ID`). Shared with fix
/// ave/correlate.
pub(super) fn global_value(source: Source, id: &str, index: Option<usize>, w: &World, ev: &mut dyn EvalContext, who: &str) -> Result<f64, String> {
    match source {
        Source::Compute => {
            let c = w.compute(id).ok_or_else(|| format!("compute `{id}` for {who} does not exist"))?;
            match index {
                None => c.scalar(w),
                Some(i) => {
                    let vec = c.vector(w)?;
                    vec.get(i - 1).copied().ok_or_else(|| format!("compute `{id}` vector has {} values, index {i} is out of range", vec.len()))
                }
            }
        }
        Source::Fix => {
            let f = w.fix(id).ok_or_else(|| format!("fix `{id}` for {who} does not exist"))?;
            let missing = |what: String| format!("fix `{id}` ({}) has no {what}", f.style());
            match index {
                None => f.scalar(w.state).ok_or_else(|| missing("global scalar".into())),
                Some(i) => f.vector(w.state, i).ok_or_else(|| missing(format!("global vector element {i}"))),
            }
        }
        Source::Variable => dmhs_parser::variables::compute_equal(ev, id).map_err(|e| format!("variable `{id}`: {e}")),
    }
}

impl FixAveTime {
    pub fn from_lammps(d: FixDef, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(d.args, d.cmd.span, SYNTAX);
        let mut sampling = Sampling::parse(&mut a, "ave/time")?;
        let raw = global_values(&mut a)?;
        let (mut vector_mode, mut ave, mut out, mut offs) = (false, Ave::One, FileOptions::default(), Vec::new());
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "mode" => vector_mode = a.choice("mode", &["scalar", "vector"])? == 1,
                "ave" => ave = Ave::parse(&mut a)?,
                "start" => sampling.start = a.i64("start step")?,
                "off" => offs.push((a.peek(), a.i64("off column")?)),
                _ if out.keyword(w, &mut a)? => {}
                _ => return Err(a.unknown_keyword(w, &[&["mode", "ave", "start", "off"][..], &FileOptions::KEYWORDS].concat())),
            }
        }
        out.check(ave, &a)?;

        // each value, wildcards expanded, checked against what its producer offers
        let mut values = Vec::new();
        let mut names = Vec::new();
        for w in raw {
            let (source, name) = Source::of(&w.text);
            let compute = d.computes.iter().find(|c| c.id() == name);
            let fix = d.fixes.iter().find(|f| f.id() == name);
            let len = match (source, vector_mode) {
                (Source::Compute, false) => compute.and_then(|c| c.size_vector()),
                (Source::Compute, true) => compute.and_then(|c| c.array_cols()),
                (Source::Fix, false) => fix.map(|f| f.size_vector()).filter(|&n| n > 0),
                _ => None,
            };
            for text in expand(w, len, &a)? {
                let (_, index) = super::value::split_index(&text, w, &a)?;
                let extensive = match source {
                    Source::Compute => {
                        let c = compute.ok_or_else(|| a.error_at(w, format!("compute `{name}` for fix ave/time does not exist"), "unknown compute"))?;
                        if vector_mode && index.is_some() && c.array_cols().is_none() {
                            return Err(a.error_at(w, format!("fix ave/time compute `{name}` ({}) does not calculate an array", c.style()), "no array"));
                        }
                        c.extensive(if vector_mode { None } else { index })
                    }
                    Source::Fix => {
                        let f = fix.ok_or_else(|| a.error_at(w, format!("fix `{name}` for fix ave/time does not exist"), "unknown fix"))?;
                        if vector_mode && index.is_some() {
                            return Err(a.error_at(w, format!("fix ave/time fix `{name}` ({}) does not calculate an array", f.style()), "no array"));
                        }
                        f.extensive(if vector_mode { None } else { index })
                    }
                    Source::Variable => {
                        if index.is_some() || vector_mode {
                            return Err(a.error_at(w, "fix ave/time reads equal-style variables only (vector-style variables are not supported)", "vector variable"));
                        }
                        false
                    }
                };
                values.push(Value { source, id: name.to_string(), index, off: false, extensive });
                names.push(text);
            }
        }
        for (w, col) in offs {
            if col < 1 || col as usize > values.len() {
                let w = w.expect("off had a value");
                return Err(a.error_at(w, format!("invalid fix ave/time off column {col}: there are {} values", values.len()), "out of range"));
            }
            values[col as usize - 1].off = true;
        }

        let mut fix = FixAveTime {
            id: d.id.clone(),
            groupbit: d.groupbit,
            sampling,
            values,
            vector_mode,
            format: out.format.clone(),
            file: None,
            sum: Vec::new(),
            total: Vec::new(),
            combine: Combine::new(ave),
        };
        // on ranks rank 0 alone writes the file (its values are the same on every rank)
        if let Some(w) = out.file.filter(|_| state.writes_files()) {
            if w.text.ends_with(".yaml") || w.text.ends_with(".yml") {
                return Err(a.error_at(w, "fix ave/time YAML output is not supported; use a plain file name", "YAML file"));
            }
            let path = d.path(&w.text);
            let head = fix.header(&names, &out.titles);
            fix.file = Some(AveFile::create(&path, &head, out.overwrite).map_err(|e| a.error_at(w, format!("cannot open fix ave/time file {}: {e}", path.display()), "cannot open"))?);
        }
        fix.sampling.begin(state.step);
        Ok(fix)
    }

    /// The comment lines at the top of the file (LAMMPS' titles).
    fn header(&self, names: &[String], titles: &[Option<String>; 3]) -> String {
        let mut s = String::new();
        match &titles[0] {
            Some(t) => s += &format!("{t}\n"),
            None => s += &format!("# Time-averaged data for fix {}\n", self.id),
        }
        match (&titles[1], self.vector_mode) {
            (Some(t), _) => s += &format!("{t}\n"),
            (None, false) => s += &format!("# TimeStep {}\n", names.join(" ")),
            (None, true) => s += "# TimeStep Number-of-rows\n",
        }
        if self.vector_mode {
            match &titles[2] {
                Some(t) => s += &format!("{t}\n"),
                None => s += &format!("# Row {}\n", names.join(" ")),
            }
        }
        s
    }

    /// One sample of every value: one column per value (one row in scalar mode).
    fn sample(&self, w: &World, ev: &mut dyn EvalContext) -> Result<Vec<Vec<f64>>, String> {
        let who = format!("fix ave/time {}", self.id);
        let mut cols = Vec::with_capacity(self.values.len());
        // a compute's array is made once per sample, however many of its columns are read
        let mut arrays: Vec<(&str, Vec<Vec<f64>>)> = Vec::new();
        for v in &self.values {
            if !self.vector_mode {
                cols.push(vec![global_value(v.source, &v.id, v.index, w, ev, &who)?]);
                continue;
            }
            let col = match v.source {
                Source::Compute => {
                    let c = w.compute(&v.id).ok_or_else(|| format!("compute `{}` for {who} does not exist", v.id))?;
                    match v.index {
                        None => c.vector(w)?,
                        Some(j) => {
                            let k = match arrays.iter().position(|(id, _)| *id == v.id) {
                                Some(k) => k,
                                None => {
                                    arrays.push((&v.id, c.array(w)?));
                                    arrays.len() - 1
                                }
                            };
                            let rows = &arrays[k].1;
                            rows.iter().map(|r| r.get(j - 1).copied().ok_or_else(|| format!("compute `{}` array has {} columns, column {j} is out of range", v.id, r.len()))).collect::<Result<_, _>>()?
                        }
                    }
                }
                Source::Fix => {
                    let f = w.fix(&v.id).ok_or_else(|| format!("fix `{}` for {who} does not exist", v.id))?;
                    (1..=f.size_vector()).map(|i| f.vector(w.state, i).ok_or_else(|| format!("fix `{}` ({}) has no global vector element {i}", v.id, f.style()))).collect::<Result<_, _>>()?
                }
                Source::Variable => vec![dmhs_parser::variables::compute_equal(ev, &v.id).map_err(|e| format!("variable `{}`: {e}", v.id))?],
            };
            cols.push(col);
        }
        Ok(cols)
    }

    /// Add one sample; at the last sample of a period, average, combine and write.
    fn accumulate(&mut self, step: i64, cols: Vec<Vec<f64>>) -> Result<(), String> {
        let nrows = cols.iter().map(|c| c.len()).max().unwrap_or(0);
        if cols.iter().any(|c| c.len() != nrows) {
            return Err(format!("fix ave/time {}: columns are inconsistent lengths", self.id));
        }
        let nvalues = self.values.len();
        if self.sum.len() != nrows {
            if !self.total.is_empty() {
                return Err(format!("fix ave/time {}: the number of rows changed from {} to {nrows}", self.id, self.total.len()));
            }
            self.sum = vec![vec![0.0; nvalues]; nrows];
            self.total = vec![vec![0.0; nvalues]; nrows];
        }
        if self.sampling.irepeat == 0 {
            self.sum.iter_mut().for_each(|r| r.fill(0.0));
        }
        for (j, col) in cols.iter().enumerate() {
            let off = self.values[j].off;
            for (i, &x) in col.iter().enumerate() {
                if off {
                    self.sum[i][j] = x;
                } else {
                    self.sum[i][j] += x;
                }
            }
        }
        if !self.sampling.advance(step) {
            return Ok(());
        }
        let repeat = self.sampling.nrepeat as f64;
        for row in self.sum.iter_mut() {
            for (j, x) in row.iter_mut().enumerate() {
                if !self.values[j].off {
                    *x /= repeat;
                }
            }
        }
        for (i, (t, s)) in self.total.iter_mut().zip(&self.sum).enumerate() {
            self.combine.row(i, t, s);
        }
        self.combine.end_period();
        let norm = self.combine.norm as f64;
        for (t, s) in self.total.iter_mut().zip(&self.sum) {
            for j in 0..nvalues {
                if self.values[j].off {
                    t[j] = norm * s[j];
                }
            }
        }
        self.write(step)
    }

    fn fmt(&self, x: f64) -> String {
        format_value(self.format.as_deref(), x)
    }

    /// The period's line(s) in the file.
    fn write(&mut self, step: i64) -> Result<(), String> {
        if self.file.is_none() {
            return Ok(());
        }
        let norm = self.combine.norm as f64;
        let mut s = String::new();
        if self.vector_mode {
            s += &format!("{step} {}\n", self.total.len());
            for (i, row) in self.total.iter().enumerate() {
                s += &(i + 1).to_string();
                row.iter().for_each(|x| s += &self.fmt(x / norm));
                s.push('\n');
            }
        } else {
            s += &step.to_string();
            self.total[0].iter().for_each(|x| s += &self.fmt(x / norm));
            s.push('\n');
        }
        let f = self.file.as_mut().expect("checked above");
        f.write(&s).map_err(|e| format!("fix ave/time {}: error writing the file: {e}", self.id))
    }

    fn value_out(&self, row: usize, col: usize) -> f64 {
        match self.total.get(row).and_then(|r| r.get(col)) {
            Some(x) if self.combine.norm > 0 => x / self.combine.norm as f64,
            _ => 0.0,
        }
    }

    fn invoke(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if !self.sampling.due(state.step) {
            return Ok(());
        }
        let cols = ctx.eval(state, self, |w, ev| self.sample(w, ev))?;
        self.accumulate(state.step, cols).map_err(|e| RunError::new(state.step, e))
    }
}

impl Fix for FixAveTime {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "ave/time"
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
    fn setup(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if self.vector_mode && self.total.is_empty() {
            // LAMMPS knows the rows from the inputs' lengths before the first sample: its
            // vector or array reads zeros of that length until then
            let nrows = ctx.eval(state, self, |w, ev| self.sample(w, ev))?.first().map_or(0, |c| c.len());
            self.sum = vec![vec![0.0; self.values.len()]; nrows];
            self.total = self.sum.clone();
        }
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
    fn scalar(&self, _state: &State) -> Option<f64> {
        (!self.vector_mode && self.values.len() == 1).then(|| self.value_out(0, 0))
    }
    fn vector(&self, _state: &State, i: usize) -> Option<f64> {
        if i == 0 {
            return None;
        }
        if self.vector_mode {
            // several values in vector mode make an array, not a vector (LAMMPS)
            (self.values.len() == 1).then(|| self.value_out(i - 1, 0))
        } else {
            (i <= self.values.len()).then(|| self.value_out(0, i - 1))
        }
    }
    fn array(&self, _state: &State, i: usize, j: usize) -> Option<f64> {
        (self.size_array().is_some() && i >= 1 && (1..=self.values.len()).contains(&j)).then(|| self.value_out(i - 1, j - 1))
    }
    fn size_array(&self) -> Option<(usize, usize)> {
        (self.vector_mode && self.values.len() > 1).then_some((self.total.len(), self.values.len()))
    }
    fn array_extensive(&self) -> bool {
        self.values[0].extensive
    }
    fn size_vector(&self) -> usize {
        if self.vector_mode {
            if self.values.len() > 1 {
                return 0;
            }
            self.total.len()
        } else if self.values.len() > 1 {
            self.values.len()
        } else {
            0
        }
    }
    fn extensive(&self, index: Option<usize>) -> bool {
        match (self.vector_mode, index) {
            (false, None) => self.values[0].extensive,
            (false, Some(i)) => self.values.get(i - 1).is_some_and(|v| v.extensive),
            (true, _) => self.values[0].extensive,
        }
    }
}
