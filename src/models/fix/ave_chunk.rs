//! `fix ID group ave/chunk Nevery Nrepeat Nfreq chunkID value ... [norm all|sample|none]
//! [ave one|running|window M] [adof N] [cdof N] [file F] [overwrite] [format F] [title1 T]
//! [title2 T] [title3 T]`: per-chunk averages (chunks of a compute chunk/atom) of vx vy vz fx fy
//! fz, density/number, density/mass, mass, temp, per-atom computes and fixes (`c_ID`,
//! `c_ID[i]`, `f_ID`, `f_ID[i]`; `[*]` expands) and atom-style variables (`v_name`), over
//! Nrepeat samples Nevery steps apart ending on multiples of Nfreq, as LAMMPS' fix ave/chunk:
//! the same samples, sums over the atoms in LAMMPS' order, the same normalisations and the same
//! file (`%g` per value).
//!
//! While a period of several samples runs (or for ever with ave running/window) the chunks are
//! those of its first sample, as LAMMPS locks the compute; with `ids nfreq` the atoms' chunk IDs
//! are also those of the first sample.

use super::sampling::{format_value, Ave, AveFile, Combine, FileOptions, Sampling};
use super::{Fix, FixCtx, FixDef, FixHooks};
use crate::engine::state::{RunError, State};
use crate::models::compute::chunk_atom::{Chunks, Ids};
use crate::models::compute::{PerAtom, PerAtomRef};
use crate::models::world::World;
use dmhs_parser::{Args, DResult};
use std::collections::HashMap;

pub const SYNTAX: &str = "fix ID group ave/chunk Nevery Nrepeat Nfreq chunkID value ... (vx vy vz fx fy fz density/number density/mass mass temp c_ID c_ID[i] f_ID f_ID[i] v_name) [norm all|sample|none] [ave one|running|window M] [adof N] [cdof N] [file F] [overwrite] [format F] [title1 T] [title2 T] [title3 T]";

#[derive(Clone, Debug)]
enum Value {
    V(usize),
    F(usize),
    DensityNumber,
    DensityMass,
    Mass,
    Temp,
    PerAtom(PerAtomRef),
    /// An atom-style variable, evaluated at each sample.
    Variable(String),
}

pub struct FixAveChunk {
    id: String,
    groupbit: u32,
    sampling: Sampling,
    chunk_id: String,
    values: Vec<Value>,
    /// norm sample (or none); else all.
    norm_sample: bool,
    /// norm none: values are summed over the atoms of a chunk, not averaged.
    noscale: bool,
    adof: f64,
    cdof: f64,
    format: Option<String>,
    file: Option<AveFile>,
    /// The chunks of the current period (kept for ever with ave running/window).
    chunks: Option<Chunks>,
    lock_forever: bool,
    /// First step of the lock on the chunks, and the chunk IDs by atom ID taken then (ids nfreq).
    lock_start: i64,
    kept_ids: Option<HashMap<i64, usize>>,
    maxchunk: usize,
    /// Array columns before the count: the original ID (compress yes) and the bin coordinates.
    colextra: usize,
    count_many: Vec<f64>,
    count_sum: Vec<f64>,
    count_total: Vec<f64>,
    values_many: Vec<Vec<f64>>,
    values_sum: Vec<Vec<f64>>,
    values_total: Vec<Vec<f64>>,
    combine: Combine,
}

impl FixAveChunk {
    pub fn from_lammps(d: FixDef, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(d.args, d.cmd.span, SYNTAX);
        let sampling = Sampling::parse(&mut a, "ave/chunk")?;
        let cw = a.word("chunk/atom compute ID")?;
        let world = World { state, computes: d.computes, fixes: crate::models::world::FixesView::all(d.fixes), bond: None, pair: None };
        let chunk = world.compute(&cw.text).ok_or_else(|| a.error_at(cw, format!("compute `{}` for fix ave/chunk does not exist", cw.text), "unknown compute"))?;
        let chunk = chunk.as_chunk().ok_or_else(|| a.error_at(cw, format!("fix ave/chunk needs a compute chunk/atom; `{}` is compute {}", cw.text, chunk.style()), "not chunk/atom"))?;
        let attrs = ["vx", "vy", "vz", "fx", "fy", "fz", "density/number", "density/mass", "mass", "temp"];
        let (mut values, mut names) = (Vec::new(), Vec::new());
        while let Some(w) = a.peek() {
            if let Some(k) = attrs.iter().position(|n| *n == w.text) {
                values.push(match k {
                    0..=2 => Value::V(k),
                    3..=5 => Value::F(k - 3),
                    6 => Value::DensityNumber,
                    7 => Value::DensityMass,
                    8 => Value::Mass,
                    _ => Value::Temp,
                });
                names.push(w.text.clone());
            } else if let Some(name) = w.text.strip_prefix("v_") {
                values.push(Value::Variable(name.to_string()));
                names.push(w.text.clone());
            } else if w.text.starts_with("c_") || w.text.starts_with("f_") {
                // c_ID[*] and f_ID[*]: every column
                let expanded = match w.text.strip_suffix("[*]") {
                    Some(base) => {
                        let id = &base[2..];
                        let cols = if base.starts_with("c_") { world.compute(id).and_then(|c| c.peratom_cols()) } else { world.fix(id).and_then(|f| f.peratom_cols()) };
                        let n = cols.ok_or_else(|| a.error_at(w, format!("`{}` does not name a per-atom compute or fix", w.text), "wildcard"))?;
                        (1..=n).map(|k| format!("{base}[{k}]")).collect()
                    }
                    None => vec![w.text.clone()],
                };
                for n in expanded {
                    let r = PerAtomRef::parse(&n, &world).expect("c_ or f_");
                    values.push(Value::PerAtom(r.map_err(|e| a.error_at(w, format!("fix ave/chunk: {e}"), "not a per-atom value"))?));
                    names.push(n);
                }
            } else {
                break;
            }
            a.skip(1);
        }
        if values.is_empty() {
            return Err(a.missing("a value (vx vy vz fx fy fz density/number density/mass mass temp c_ID c_ID[i] f_ID f_ID[i] v_name)"));
        }
        let dimension = state.domain.as_ref().map_or(3, |d| d.dimension);
        let (mut norm_sample, mut noscale, mut ave, mut adof, mut cdof) = (false, false, Ave::One, dimension as f64, 0.0);
        let mut out = FileOptions::default();
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "norm" => (norm_sample, noscale) = [(false, false), (true, false), (true, true)][a.choice("norm", &["all", "sample", "none"])?],
                "ave" => ave = Ave::parse(&mut a)?,
                "adof" => adof = a.f64("adof")?,
                "cdof" => cdof = a.f64("cdof")?,
                _ if out.keyword(w, &mut a)? => {}
                "bias" => return Err(a.error_at(w, "fix ave/chunk bias is not supported: dmhs has no temperature compute with a velocity bias", "not supported")),
                "discard" | "scale" => return Err(a.error_at(w, format!("fix ave/chunk `{}` is not a keyword of LAMMPS 22 Jul 2025 (use norm, or discard of compute chunk/atom)", w.text), "unknown keyword")),
                _ => return Err(a.unknown_keyword(w, &[&["norm", "ave", "adof", "cdof"][..], &FileOptions::KEYWORDS].concat())),
            }
        }
        out.check(ave, &a)?;
        let mut fix = FixAveChunk {
            id: d.id.clone(),
            groupbit: d.groupbit,
            sampling,
            chunk_id: cw.text.clone(),
            values,
            norm_sample,
            noscale,
            adof,
            cdof,
            format: out.format.clone(),
            file: None,
            chunks: None,
            lock_forever: false,
            lock_start: -1,
            kept_ids: None,
            maxchunk: 0,
            colextra: usize::from(chunk.compress) + chunk.ncoord(),
            count_many: Vec::new(),
            count_sum: Vec::new(),
            count_total: Vec::new(),
            values_many: Vec::new(),
            values_sum: Vec::new(),
            values_total: Vec::new(),
            combine: Combine::new(ave),
        };
        // rank 0 alone writes the file (every rank averages the same sums)
        if let Some(w) = out.file.filter(|_| state.writes_files()) {
            let path = d.path(&w.text);
            let group = d.cmd.args.get(1).map_or("all", |g| g.text.as_str());
            let mut head = match &out.titles[0] {
                Some(t) => format!("{t}\n"),
                None => format!("# Chunk-averaged data for fix {} and group {group}\n", fix.id),
            };
            head += &match &out.titles[1] {
                Some(t) => format!("{t}\n"),
                None => "# Timestep Number-of-chunks Total-count\n".to_string(),
            };
            head += &match &out.titles[2] {
                Some(t) => format!("{t}\n"),
                None => {
                    let mut s = "# Chunk".to_string();
                    if chunk.compress {
                        s += " OrigID";
                    }
                    (1..=chunk.ncoord()).for_each(|k| s += &format!(" Coord{k}"));
                    format!("{s} Ncount {}\n", names.join(" "))
                }
            };
            fix.file = Some(AveFile::create(&path, &head, out.overwrite).map_err(|e| a.error_at(w, format!("cannot open fix ave/chunk file {}: {e}", path.display()), "cannot open"))?);
        }
        fix.sampling.begin(state.step);
        Ok(fix)
    }

    /// Grow the per-chunk arrays to `n` chunks (LAMMPS' allocate: the totals restart when they
    /// grow).
    fn allocate(&mut self, n: usize) {
        if n <= self.maxchunk {
            return;
        }
        self.maxchunk = n;
        let nv = self.values.len();
        self.count_many = vec![0.0; n];
        self.count_sum = vec![0.0; n];
        self.count_total = vec![0.0; n];
        self.values_many = vec![vec![0.0; nv]; n];
        self.values_sum = vec![vec![0.0; nv]; n];
        self.values_total = vec![vec![0.0; nv]; n];
    }

    /// One sample: the chunks (new at the start of a period unless locked), the atoms' chunk IDs,
    /// and per chunk the atom count and the sums of the values.
    fn sample(&self, w: &World, ev: &mut dyn dmhs_parser::EvalContext, first: bool) -> Result<Sample, String> {
        let c = w.compute(&self.chunk_id).and_then(|c| c.as_chunk()).ok_or_else(|| format!("compute chunk/atom `{}` for fix ave/chunk {} does not exist", self.chunk_id, self.id))?;
        let state = w.state;
        let new = match (&self.chunks, first && !self.lock_forever) {
            (Some(_), false) => None,
            _ => Some(c.setup_chunks(state)?),
        };
        let ch = new.as_ref().or(self.chunks.as_ref()).expect("one of them");
        let a = &state.atoms;
        let ichunk = match &self.kept_ids {
            Some(map) if c.ids == Ids::Nfreq && state.step > self.lock_start => (0..a.nlocal).map(|i| map.get(&a.tag[i]).copied().unwrap_or(0)).collect(),
            _ => c.ichunk(state, ch)?,
        };
        let n = ch.nchunk;
        let inputs: Vec<Option<PerAtom>> = self
            .values
            .iter()
            .map(|v| match v {
                Value::PerAtom(r) => r.values(w).map(Some),
                Value::Variable(name) => crate::models::atom_formula::atom_variable_input("ave/chunk", name, w, ev).map(|data| Some(PerAtom { cols: 1, data })),
                _ => Ok(None),
            })
            .collect::<Result<_, _>>()?;
        let order = state.lammps_order.indices(a.nlocal);
        let members: Vec<usize> = order.iter().copied().filter(|&i| a.mask[i] & self.groupbit != 0 && ichunk[i] > 0).collect();
        let mut count = vec![0.0; n];
        members.iter().for_each(|&i| count[ichunk[i] - 1] += 1.0);
        let mut sums = vec![vec![0.0; self.values.len()]; n];
        for (m, v) in self.values.iter().enumerate() {
            for &i in &members {
                sums[ichunk[i] - 1][m] += match v {
                    Value::V(k) => a.v[i][*k],
                    Value::F(k) => a.f[i][*k],
                    Value::DensityNumber => 1.0,
                    Value::DensityMass | Value::Mass => state.mass(i),
                    Value::Temp => {
                        let u = a.v[i];
                        (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) * state.mass(i)
                    }
                    Value::PerAtom(r) => r.get(inputs[m].as_ref().expect("read above"), i),
                    Value::Variable(_) => inputs[m].as_ref().expect("read above").get(i, 0),
                };
            }
        }
        if state.distributed.is_some() {
            // the sums of every rank's atoms
            let nv = self.values.len();
            let mut flat: Vec<f64> = count.iter().copied().chain(sums.iter().flatten().copied()).collect();
            state.sum_ranks(&mut flat);
            count.copy_from_slice(&flat[..n]);
            for (m, row) in sums.iter_mut().enumerate() {
                row.copy_from_slice(&flat[n + m * nv..n + (m + 1) * nv]);
            }
        }
        Ok(Sample { new, ids_nfreq: c.ids == Ids::Nfreq, ichunk, count, sums })
    }

    fn invoke(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if !self.sampling.due(state.step) {
            return Ok(());
        }
        let step = state.step;
        let first = self.sampling.irepeat == 0;
        let Sample { new, ids_nfreq, ichunk, count: count_one, sums: mut values_one } = ctx.eval(state, self, |w, ev| self.sample(w, ev, first))?;
        if let Some(ch) = new {
            self.chunks = Some(ch);
        }
        let ch = self.chunks.as_ref().expect("set by the first sample");
        let (n, volume) = (ch.nchunk, ch.volume);
        if first {
            self.allocate(n);
            // the lock on the chunks: for this period, or for ever with running averages
            let locked = if self.sampling.nrepeat > 1 && self.combine.ave == Ave::One {
                self.lock_start = step;
                true
            } else if self.combine.ave != Ave::One && !self.lock_forever {
                self.lock_forever = true;
                self.lock_start = step;
                true
            } else {
                self.lock_forever
            };
            if ids_nfreq && locked && step == self.lock_start {
                self.kept_ids = Some(state.values_by_id(|i| ichunk[i]));
            } else if !locked {
                self.kept_ids = None;
            }
            for m in 0..n {
                self.count_many[m] = 0.0;
                self.count_sum[m] = 0.0;
                self.values_many[m].fill(0.0);
            }
        }
        let (mvv2e, boltz, mv2d) = (state.units.mvv2e, state.units.boltz, 1.0);
        if !self.norm_sample {
            for m in 0..n {
                self.count_many[m] += count_one[m];
                for (j, x) in values_one[m].iter().enumerate() {
                    self.values_many[m][j] += x;
                }
            }
        } else {
            for m in 0..n {
                self.count_many[m] = count_one[m];
                let cnt = self.count_many[m];
                if cnt > 0.0 {
                    for (j, v) in self.values.iter().enumerate() {
                        let x = &mut values_one[m][j];
                        self.values_many[m][j] += match v {
                            Value::Temp => mvv2e * *x / ((self.cdof + self.adof * cnt) * boltz),
                            Value::DensityNumber => {
                                *x /= volume;
                                *x
                            }
                            Value::DensityMass => {
                                *x /= volume;
                                mv2d * *x
                            }
                            _ if self.noscale => *x,
                            _ => *x / cnt,
                        };
                    }
                }
                self.count_sum[m] += cnt;
            }
        }
        if !self.sampling.advance(step) {
            return Ok(());
        }
        if self.sampling.nrepeat > 1 && self.combine.ave == Ave::One {
            self.kept_ids = None;
        }
        let repeat = self.sampling.nrepeat as f64;
        for m in 0..n {
            if !self.norm_sample {
                self.count_sum[m] = self.count_many[m];
                self.values_sum[m].clone_from(&self.values_many[m]);
                let cnt = self.count_sum[m];
                if cnt > 0.0 {
                    for (j, v) in self.values.iter().enumerate() {
                        let x = &mut self.values_sum[m][j];
                        match v {
                            // cdof counts once per sample
                            Value::Temp => *x *= mvv2e / ((repeat * self.cdof + self.adof * cnt) * boltz),
                            Value::DensityNumber => {
                                *x /= volume;
                                *x /= repeat;
                            }
                            Value::DensityMass => {
                                *x /= volume;
                                *x *= mv2d / repeat;
                            }
                            _ if self.noscale => *x /= repeat,
                            _ => *x /= cnt,
                        }
                    }
                }
            } else {
                self.values_sum[m].clone_from(&self.values_many[m]);
                self.values_sum[m].iter_mut().for_each(|x| *x /= repeat);
            }
            self.count_sum[m] /= repeat;
        }
        // rows 2m: chunk m's values, 2m + 1: its count
        for m in 0..n {
            self.combine.row(2 * m, &mut self.values_total[m], &self.values_sum[m]);
            self.combine.row(2 * m + 1, std::slice::from_mut(&mut self.count_total[m]), &[self.count_sum[m]]);
        }
        self.combine.end_period();
        self.write(step).map_err(|e| RunError::new(step, e))
    }

    fn fmt(&self, x: f64) -> String {
        format_value(self.format.as_deref(), x)
    }

    /// The period's block in the file: `step nchunk total-count`, then one row per chunk.
    fn write(&mut self, step: i64) -> Result<(), String> {
        let Some(ch) = &self.chunks else { return Ok(()) };
        if self.file.is_none() {
            return Ok(());
        }
        let n = ch.nchunk;
        let norm = self.combine.norm as f64;
        let total: f64 = self.count_total[..n].iter().sum();
        let mut s = format!("{step} {n} {}\n", shortest(total));
        let ncoord = ch.ncoord;
        for m in 0..n {
            s += &format!("  {}", m + 1);
            let row = if ch.chunk_id.is_empty() {
                m
            } else {
                let orig = ch.chunk_id[m];
                s += &format!(" {orig}");
                (orig - 1).max(0) as usize
            };
            if let Some(c) = ch.coord.get(row) {
                c[..ncoord].iter().for_each(|x| s += &format!(" {}", g(*x)));
            }
            s += &format!(" {}", g(self.count_total[m] / norm));
            self.values_total[m].iter().for_each(|x| s += &self.fmt(x / norm));
            s.push('\n');
        }
        let f = self.file.as_mut().expect("checked above");
        f.write(&s).map_err(|e| format!("fix ave/chunk {}: error writing the file: {e}", self.id))
    }
}

/// What one sample gives: new chunks (at the start of a period, unless locked), the atoms'
/// chunk IDs, and per chunk the atom count and the value sums.
struct Sample {
    new: Option<Chunks>,
    ids_nfreq: bool,
    ichunk: Vec<usize>,
    count: Vec<f64>,
    sums: Vec<Vec<f64>>,
}

/// A number as LAMMPS' `fmt::print("{}")` writes it: the shortest digits that read back
/// exactly, in exponent form (`1e+16`, `2.5e-05`) below 1e-4 and from 1e16.
fn shortest(x: f64) -> String {
    let e = format!("{x:e}");
    let exp: i32 = e.rsplit('e').next().and_then(|t| t.parse().ok()).unwrap_or(0);
    if x == 0.0 || !x.is_finite() || (-4..16).contains(&exp) {
        return format!("{x}");
    }
    let mantissa = e.split('e').next().unwrap_or("");
    format!("{mantissa}e{}{:02}", if exp < 0 { '-' } else { '+' }, exp.abs())
}

/// `%g`.
fn g(x: f64) -> String {
    dmhs_parser::numfmt::format_g(x, 6)
}

impl Fix for FixAveChunk {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "ave/chunk"
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
    /// Per chunk: the original chunk ID (compress yes), the bin coordinates, the atom count
    /// and the values, as LAMMPS' FixAveChunk::compute_array (which reads the coordinates of
    /// row i, not of its original ID, under compress); rows beyond the chunks are 0.
    fn array(&self, _state: &State, i: usize, j: usize) -> Option<f64> {
        let (_, cols) = self.size_array()?;
        if i == 0 || j == 0 || j > cols {
            return None;
        }
        let Some(ch) = &self.chunks else { return Some(0.0) };
        let (i, mut j) = (i - 1, j - 1);
        if i >= ch.nchunk {
            return Some(0.0);
        }
        let compress = self.colextra.saturating_sub(ch.ncoord);
        if j < self.colextra {
            if compress == 1 && j == 0 {
                return Some(ch.chunk_id.get(i).map_or(0.0, |&c| c as f64));
            }
            return Some(ch.coord.get(i).map_or(0.0, |c| c[j - compress]));
        }
        j -= self.colextra;
        let norm = self.combine.norm as f64;
        if norm == 0.0 {
            return Some(0.0);
        }
        Some(if j == 0 { self.count_total[i] / norm } else { self.values_total[i][j - 1] / norm })
    }
    fn size_array(&self) -> Option<(usize, usize)> {
        // one row of zeros before the first sample, as LAMMPS' (its nchunk starts at 1)
        Some((self.chunks.as_ref().map_or(1, |c| c.nchunk), self.colextra + 1 + self.values.len()))
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn shortest_is_fmt_braces() {
        assert_eq!(super::shortest(600.0), "600");
        assert_eq!(super::shortest(599.9999999999999), "599.9999999999999");
        assert_eq!(super::shortest(26.35), "26.35");
        assert_eq!(super::shortest(2.5e-5), "2.5e-05");
        assert_eq!(super::shortest(1e16), "1e+16");
        assert_eq!(super::shortest(0.0), "0");
    }
}
