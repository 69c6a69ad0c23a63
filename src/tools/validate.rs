//! `dmhs validate CASE [--quick]`: run an SPH validation deck (examples/validation/), compare the
//! state with its analytic or experimental reference (src/analytic.rs), print the errors and the
//! pass/fail checks, write a JSON result and, with `--img DIR`, the charts.
//!
//! Cases: poiseuille, couette, heat, hydrostatic, dambreak, sod (`all` runs the six), and `chart`: the
//! speed-versus-accuracy chart of Poiseuille flow (error against wall-clock time over
//! resolutions, kernels and time steps, dmhs on one thread and LAMMPS serial).
//!
//! The decks are embedded in the binary and run unmodified in either engine: in dmhs through the
//! library (the state is read from `sim.state.atoms`; later sample times continue the same simulation
//! with `run` commands), in LAMMPS through lammps-refs/lammps_driver.py (one run per sample time).

use crate::tools::analytic;
use crate::tools::crosscheck::{capture_state, AtomTable};
use crate::deck::{run_text, DeckOptions};
use crate::output::plot::{Chart, Legend, Series};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

pub const CASES: [&str; 6] = ["poiseuille", "couette", "heat", "hydrostatic", "dambreak", "sod"];

/// The validation decks: (path in the source tree, text).
pub fn deck(case: &str) -> Option<(&'static str, &'static str)> {
    Some(match case {
        "poiseuille" => ("examples/validation/poiseuille/in.poiseuille", include_str!("../../examples/validation/poiseuille/in.poiseuille")),
        "couette" => ("examples/validation/couette/in.couette", include_str!("../../examples/validation/couette/in.couette")),
        "heat" => ("examples/validation/heat/in.heat", include_str!("../../examples/validation/heat/in.heat")),
        "hydrostatic" => ("examples/validation/hydrostatic/in.hydrostatic", include_str!("../../examples/validation/hydrostatic/in.hydrostatic")),
        "dambreak" => ("examples/validation/dambreak/in.dambreak", include_str!("../../examples/validation/dambreak/in.dambreak")),
        "sod" => ("examples/validation/sod/in.sod", include_str!("../../examples/validation/sod/in.sod")),
        _ => return None,
    })
}

/// A numeric constant of a deck: the value of `variable NAME equal|index NUMBER`, so the
/// analytic side uses exactly the deck's parameters.
pub fn deck_constant(case: &str, name: &str) -> Result<f64, String> {
    let (path, text) = deck(case).ok_or_else(|| format!("unknown case `{case}`"))?;
    for line in text.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        if w.len() >= 4 && w[0] == "variable" && w[1] == name && (w[2] == "equal" || w[2] == "index") {
            return w[3].parse::<f64>().map_err(|_| format!("{path}: variable {name} is `{}`, not a number", w[3]));
        }
    }
    Err(format!("{path}: no numeric `variable {name}`"))
}

/// Which engine runs the decks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Engine {
    Dmhs,
    Lammps,
}

impl Engine {
    pub fn name(self) -> &'static str {
        match self {
            Engine::Dmhs => "dmhs",
            Engine::Lammps => "LAMMPS",
        }
    }
}

/// The thermo table a run printed (all `run`s with the same columns, in order).
#[derive(Clone, Debug, Default)]
pub struct Thermo {
    pub columns: Vec<String>,
    pub rows: Vec<Vec<f64>>,
}

impl Thermo {
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let k = self.columns.iter().position(|c| c == name)?;
        Some(self.rows.iter().map(|r| r[k]).collect())
    }
}

/// Thermo rows of LAMMPS-format output (a `Step ...` header, numeric rows, then `Loop time`).
/// A later run with the same columns appends its rows; the repeated first step of a continued
/// run is dropped.
pub fn parse_thermo(text: &str) -> Thermo {
    let mut t = Thermo::default();
    let mut current: Option<Vec<String>> = None;
    for line in text.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        if w.first() == Some(&"Step") {
            current = Some(w.iter().map(|s| s.to_string()).collect());
            if t.columns.is_empty() {
                t.columns = current.clone().unwrap();
            }
            continue;
        }
        let Some(cols) = &current else { continue };
        let vals: Option<Vec<f64>> = w.iter().map(|s| s.parse::<f64>().ok()).collect();
        match vals {
            Some(v) if v.len() == cols.len() && !v.is_empty() => {
                if *cols == t.columns && t.rows.last().map(|r| r[0]) != Some(v[0]) {
                    t.rows.push(v);
                }
            }
            _ => current = None,
        }
    }
    t
}

/// The state of a run at one time.
#[derive(Clone, Debug)]
pub struct Sample {
    pub time: f64,
    pub step: i64,
    pub state: AtomTable,
}

/// A finished run of a validation deck.
#[derive(Clone, Debug)]
pub struct RunResult {
    pub engine: Engine,
    pub vars: Vec<(String, String)>,
    /// In time order; the last one is the end of the run.
    pub samples: Vec<Sample>,
    pub thermo: Thermo,
    /// Seconds of the main loop (all runs of the deck in dmhs; the longest run in LAMMPS).
    pub loop_seconds: f64,
    pub atoms: usize,
}

impl RunResult {
    pub fn last(&self) -> &Sample {
        self.samples.last().expect("a run has at least one sample")
    }
}

fn deck_vars(vars: &[(String, String)]) -> Vec<(String, Vec<String>)> {
    vars.iter().map(|(k, v)| (k.clone(), vec![v.clone()])).collect()
}

fn with_var(vars: &[(String, String)], name: &str, value: String) -> Vec<(String, String)> {
    let mut v: Vec<(String, String)> = vars.iter().filter(|(k, _)| k != name).cloned().collect();
    v.push((name.to_string(), value));
    v
}

/// Run `case` in dmhs with `vars`. With sample `times` (ascending), the deck runs to the first
/// (`-var tend`) and `run` commands continue it to the others; without, it runs as `vars` say.
pub fn run_dmhs(case: &str, vars: &[(String, String)], times: &[f64]) -> Result<RunResult, String> {
    let (path, text) = deck(case).ok_or_else(|| format!("unknown case `{case}`"))?;
    let vars = match times.first() {
        Some(t) => with_var(vars, "tend", format!("{t}")),
        None => vars.to_vec(),
    };
    let opts = DeckOptions { vars: deck_vars(&vars), screen: false, log: None, capture_text: true, ..Default::default() };
    let mut run = run_text(path, text, &opts).map_err(|f| format!("dmhs failed on {path} {}:\n{}", show_vars(&vars), f.rendered))?;
    let mut seconds = run.sim.last_loop_seconds;
    let sample = |sim: &crate::sim::Simulation| Sample { time: sim.state.step as f64 * sim.state.dt, step: sim.state.step, state: capture_state(sim) };
    let mut samples = vec![sample(&run.sim)];
    for &t in times.iter().skip(1) {
        let target = (t / run.sim.state.dt).round() as i64;
        let k = target - run.sim.state.step;
        if k <= 0 {
            continue;
        }
        run.interp
            .run_source("<dmhs validate>", &format!("run {k}"), &mut run.sim)
            .map_err(|d| format!("dmhs failed on {path} {} continuing to t = {t}:\n{}", show_vars(&vars), d.iter().map(|d| d.render(run.interp.sources())).collect::<String>()))?;
        seconds += run.sim.last_loop_seconds;
        samples.push(sample(&run.sim));
    }
    let thermo = parse_thermo(run.sim.out.captured.as_deref().unwrap_or(""));
    Ok(RunResult { engine: Engine::Dmhs, vars, samples, thermo, loop_seconds: seconds, atoms: run.sim.state.atoms.nlocal })
}

/// Run `case` in LAMMPS (lammps_driver.py), once per sample time (or once as `vars` say).
pub fn run_lammps(case: &str, vars: &[(String, String)], times: &[f64]) -> Result<RunResult, String> {
    let (path, text) = deck(case).ok_or_else(|| format!("unknown case `{case}`"))?;
    let dir = tempfile::tempdir().map_err(|e| format!("cannot make a temporary folder: {e}"))?;
    let deck_path = dir.path().join(Path::new(path).file_name().unwrap());
    std::fs::write(&deck_path, text).map_err(|e| format!("cannot write {}: {e}", deck_path.display()))?;
    let runs: Vec<Vec<(String, String)>> = if times.is_empty() { vec![vars.to_vec()] } else { times.iter().map(|t| with_var(vars, "tend", format!("{t}"))).collect() };
    let mut result = RunResult { engine: Engine::Lammps, vars: runs.last().unwrap().clone(), samples: vec![], thermo: Thermo::default(), loop_seconds: 0.0, atoms: 0 };
    for (k, v) in runs.iter().enumerate() {
        let out = dir.path().join(format!("run{k}"));
        std::fs::create_dir_all(&out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
        crate::tools::lammps::run_driver(&deck_path, &deck_vars(v), &out)?;
        let state = AtomTable::read(&out.join("final.txt"))?;
        let meta: Value = serde_json::from_str(&std::fs::read_to_string(out.join("meta.json")).map_err(|e| format!("meta.json: {e}"))?).map_err(|e| format!("meta.json: {e}"))?;
        let dt = meta["dt"].as_f64().ok_or("meta.json: no dt")?;
        let step = meta["step_final"].as_i64().ok_or("meta.json: no step_final")?;
        let log = std::fs::read_to_string(out.join("log.lammps")).unwrap_or_default();
        if let Some((sec, _, atoms)) = crate::tools::lammps::parse_loop_time(&log) {
            result.loop_seconds = result.loop_seconds.max(sec);
            result.atoms = atoms as usize;
        }
        result.thermo = parse_thermo(&log);
        result.samples.push(Sample { time: step as f64 * dt, step, state });
    }
    Ok(result)
}

pub fn run_engine(engine: Engine, case: &str, vars: &[(String, String)], times: &[f64]) -> Result<RunResult, String> {
    match engine {
        Engine::Dmhs => run_dmhs(case, vars, times),
        Engine::Lammps => run_lammps(case, vars, times),
    }
}

fn show_vars(vars: &[(String, String)]) -> String {
    vars.iter().map(|(k, v)| format!("-var {k} {v}")).collect::<Vec<_>>().join(" ")
}

pub(crate) fn var(name: &str, value: impl ToString) -> (String, String) {
    (name.to_string(), value.to_string())
}

// ---------------------------------------------------------------------------------------------
// Error measures
// ---------------------------------------------------------------------------------------------

/// sqrt(sum (a - b)^2 / sum b^2) over (computed, exact) pairs.
pub fn l2_relative(pairs: impl IntoIterator<Item = (f64, f64)>) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for (a, b) in pairs {
        num += (a - b) * (a - b);
        den += b * b;
    }
    if den > 0.0 { (num / den).sqrt() } else { num.sqrt() }
}

/// Observed orders of convergence between successive (resolution, error) pairs.
pub fn orders(points: &[(f64, f64)]) -> Vec<f64> {
    points.windows(2).map(|w| (w[0].1 / w[1].1).ln() / (w[1].0 / w[0].0).ln()).collect()
}

/// (column values) of the atoms of one type, from a state table.
pub(crate) fn columns_of_type(t: &AtomTable, typ: usize, cols: &[&str]) -> Result<Vec<Vec<f64>>, String> {
    let idx: Vec<usize> = cols.iter().map(|c| t.column(c).ok_or_else(|| format!("state has no column `{c}`"))).collect::<Result<_, _>>()?;
    Ok(t.rows.values().filter(|(ty, _)| *ty == typ).map(|(_, v)| idx.iter().map(|&k| v[k]).collect()).collect())
}

// ---------------------------------------------------------------------------------------------
// Reports
// ---------------------------------------------------------------------------------------------

/// One pass/fail criterion.
#[derive(Clone, Debug)]
pub struct Check {
    pub name: String,
    pub value: f64,
    pub limit: f64,
    /// true: value must be below the limit; false: above.
    pub below: bool,
}

impl Check {
    pub fn below(name: &str, value: f64, limit: f64) -> Check {
        Check { name: name.into(), value, limit, below: true }
    }
    pub fn above(name: &str, value: f64, limit: f64) -> Check {
        Check { name: name.into(), value, limit, below: false }
    }
    pub fn pass(&self) -> bool {
        if self.below { self.value < self.limit } else { self.value > self.limit }
    }
}

/// The result of a case.
pub struct CaseReport {
    pub case: String,
    pub engine: Engine,
    pub quick: bool,
    /// Per-run results (JSON objects).
    pub runs: Vec<Value>,
    pub checks: Vec<Check>,
    /// Printed table.
    pub table: String,
    /// Charts by file stem.
    pub charts: Vec<(String, Chart)>,
    /// Summary numbers by name (also in the JSON).
    pub summary: Vec<(String, f64)>,
}

impl CaseReport {
    fn new(case: &str, opts: &Options) -> CaseReport {
        CaseReport { case: case.into(), engine: opts.engine, quick: opts.quick, runs: vec![], checks: vec![], table: String::new(), charts: vec![], summary: vec![] }
    }
    pub fn passed(&self) -> bool {
        self.checks.iter().all(Check::pass)
    }
    pub fn summary_value(&self, name: &str) -> Option<f64> {
        self.summary.iter().find(|(k, _)| k == name).map(|(_, v)| *v)
    }
    pub fn to_json(&self) -> Value {
        json!({
            "case": self.case,
            "engine": self.engine.name(),
            "quick": self.quick,
            "dmhs_version": env!("CARGO_PKG_VERSION"),
            "deck": deck(&self.case).map(|d| d.0),
            "runs": self.runs,
            "summary": self.summary.iter().map(|(k, v)| (k.clone(), json!(v))).collect::<serde_json::Map<_, _>>(),
            "checks": self.checks.iter().map(|c| json!({"name": c.name, "value": c.value, "limit": c.limit,
                "kind": if c.below { "below" } else { "above" }, "pass": c.pass()})).collect::<Vec<_>>(),
            "passed": self.passed(),
        })
    }
    pub fn render(&self) -> String {
        let mut s = format!("== {} ({}, {})\n{}", self.case, self.engine.name(), if self.quick { "quick" } else { "full" }, self.table);
        for c in &self.checks {
            s += &format!("  {} {:<52} {:>11.4e} {} {:.4e}\n", if c.pass() { "PASS" } else { "FAIL" }, c.name, c.value, if c.below { "<" } else { ">" }, c.limit);
        }
        s
    }
}

/// Options of `dmhs validate`.
#[derive(Clone, Debug)]
pub struct Options {
    pub quick: bool,
    pub engine: Engine,
}

/// Run one case.
pub fn run_case(case: &str, opts: &Options) -> Result<CaseReport, String> {
    match case {
        "poiseuille" => poiseuille(opts),
        "couette" => couette(opts),
        "heat" => heat(opts),
        "hydrostatic" => hydrostatic(opts),
        "dambreak" => dambreak(opts),
        "sod" => sod(opts),
        _ => Err(format!("unknown validation case `{case}` (cases: {}, all, chart)", CASES.join(", "))),
    }
}

/// Morris, Fox & Zhu (1997) show the start-up profiles at these times (s); 1 s is steady.
pub const MORRIS_TIMES: [f64; 5] = [0.0225, 0.045, 0.1125, 0.225, 1.0];

/// Shared by Poiseuille and Couette: per-resolution runs sampled at MORRIS_TIMES, L2 errors of
/// vx over the fluid, convergence at the end time, profile and convergence charts.
fn channel_case(
    case: &str,
    opts: &Options,
    exact: &dyn Fn(f64, f64) -> f64,
    steady_limit: f64,
    order_limit: f64,
) -> Result<CaseReport, String> {
    let mut rep = CaseReport::new(case, opts);
    let l = deck_constant(case, "L")?;
    let ns: &[usize] = if opts.quick { &[10, 20, 40] } else { &[10, 20, 40, 80] };
    rep.table += &format!("  {:>4} {:>8}  {}\n", "N", "atoms", MORRIS_TIMES.iter().map(|t| format!("L2(t={t})")).map(|s| format!("{s:>13}")).collect::<String>());
    let mut conv = vec![];
    let mut profile_run = None;
    for &n in ns {
        let run = run_engine(opts.engine, case, &[var("N", n)], &MORRIS_TIMES)?;
        let mut errs = vec![];
        for s in &run.samples {
            let rows = columns_of_type(&s.state, 1, &["yu", "vx"])?;
            errs.push(l2_relative(rows.iter().map(|r| (r[1], exact(r[0], s.time)))));
        }
        rep.table += &format!("  {:>4} {:>8}  {}\n", n, run.atoms, errs.iter().map(|e| format!("{e:>13.4e}")).collect::<String>());
        conv.push((n as f64, *errs.last().unwrap()));
        rep.runs.push(json!({"N": n, "atoms": run.atoms, "loop_seconds": run.loop_seconds,
            "samples": run.samples.iter().zip(&errs).map(|(s, e)| json!({"time": s.time, "step": s.step, "l2_rel": e})).collect::<Vec<_>>()}));
        if n == 40 {
            profile_run = Some(run);
        }
    }
    let ords = orders(&conv);
    rep.table += &format!("  observed order at t = {}: {}\n", MORRIS_TIMES[4], ords.iter().map(|o| format!("{o:.2}")).collect::<Vec<_>>().join(", "));
    for (n, e) in &conv {
        rep.summary.push((format!("l2_N{n}"), *e));
    }
    for (k, o) in ords.iter().enumerate() {
        rep.summary.push((format!("order_{}_{}", conv[k].0, conv[k + 1].0), *o));
    }
    let e40 = conv.iter().find(|c| c.0 == 40.0).map(|c| c.1).unwrap_or(f64::NAN);
    rep.checks.push(Check::below(&format!("L2 velocity error, N = 40, t = {} s", MORRIS_TIMES[4]), e40, steady_limit));
    for (k, o) in ords.iter().enumerate() {
        rep.checks.push(Check::above(&format!("observed order N = {} -> {}", conv[k].0, conv[k + 1].0), *o, order_limit));
    }

    // charts: profiles at N = 40, convergence
    if let Some(run) = profile_run {
        let mut chart = Chart::new(&format!("{} start-up, N = 40 ({}) vs analytic", title_case(case), opts.engine.name()))
            .x_label("y (mm)")
            .y_label("u (mm/s)")
            .legend(Legend::UpperLeft);
        for (k, s) in run.samples.iter().enumerate() {
            let rows = columns_of_type(&s.state, 1, &["yu", "vx"])?;
            let pts: Vec<(f64, f64)> = rows.iter().map(|r| (r[0] * 1e3, r[1] * 1e3)).collect();
            let line: Vec<(f64, f64)> = (0..=200).map(|i| l * i as f64 / 200.0).map(|y| (y * 1e3, exact(y, s.time) * 1e3)).collect();
            chart = chart.series(Series::line(if k == 0 { "analytic" } else { "" }, line).color(6));
            chart = chart.series(Series::points(&format!("t = {} s", fmt_time(s.time)), pts).color(k));
        }
        rep.charts.push((format!("{case}_profiles"), chart));
    }
    let guide = |p: f64| -> Vec<(f64, f64)> { conv.iter().map(|(n, _)| (*n, conv[0].1 * (conv[0].0 / n).powf(p))).collect() };
    let chart = Chart::new(&format!("{}: L2 velocity error at t = {} s ({})", title_case(case), MORRIS_TIMES[4], opts.engine.name()))
        .x_label("N = L / dx (particle spacings across the channel)")
        .y_label("relative L2 error of u")
        .log_x()
        .log_y()
        .series(Series::line_points(&format!("{} (Lucy kernel)", opts.engine.name()), conv.clone()))
        .series(Series::dashed("order 1", guide(1.0)).color(8))
        .series(Series::dashed("order 2", guide(2.0)).color(6));
    rep.charts.push((format!("{case}_convergence"), chart));
    Ok(rep)
}

pub(crate) fn title_case(s: &str) -> String {
    let mut c = s.chars();
    c.next().map(|f| f.to_uppercase().collect::<String>() + c.as_str()).unwrap_or_default()
}

fn fmt_time(t: f64) -> String {
    let s = format!("{t:.4}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// The analytic start-up velocity u(y, t) of a channel case (poiseuille or couette), with the
/// deck's parameters.
pub fn channel_exact(case: &str) -> Result<Box<dyn Fn(f64, f64) -> f64 + Send + Sync>, String> {
    let l = deck_constant(case, "L")?;
    let nu = deck_constant(case, "mu")? / deck_constant(case, "rho0")?;
    Ok(match case {
        "poiseuille" => {
            let f = deck_constant(case, "F")?;
            Box::new(move |y, t| analytic::poiseuille_startup(y, t, l, f, nu))
        }
        "couette" => {
            let u = deck_constant(case, "U")?;
            Box::new(move |y, t| analytic::couette_startup(y, t, l, u, nu))
        }
        _ => return Err(format!("`{case}` is not a channel case (poiseuille, couette)")),
    })
}

fn poiseuille(opts: &Options) -> Result<CaseReport, String> {
    channel_case("poiseuille", opts, &*channel_exact("poiseuille")?, 0.01, 1.0)
}

fn couette(opts: &Options) -> Result<CaseReport, String> {
    channel_case("couette", opts, &*channel_exact("couette")?, 0.01, 0.8)
}

fn heat(opts: &Options) -> Result<CaseReport, String> {
    let mut rep = CaseReport::new("heat", opts);
    let d = deck_constant("heat", "D")?;
    let ns: &[usize] = if opts.quick { &[50, 100, 200] } else { &[50, 100, 200, 400] };
    rep.table += &format!("  {:>5} {:>8} {:>10} {:>13} {:>13}\n", "N", "atoms", "t", "max|T-Te|", "RMS(|x|<4l)");
    let mut conv = vec![];
    let mut profile = None;
    for &n in ns {
        let run = run_engine(opts.engine, "heat", &[var("N", n)], &[])?;
        let s = run.last();
        let rows = columns_of_type(&s.state, 1, &["xu", "esph"])?;
        // cv = 1 in the deck, so T = esph
        let exact = |x: f64| analytic::heat_half_spaces(x, s.time, d, 1.0, 0.0);
        let max = rows.iter().map(|r| (r[1] - exact(r[0])).abs()).fold(0.0, f64::max);
        let width = 4.0 * (d * s.time).sqrt();
        let near: Vec<f64> = rows.iter().filter(|r| r[0].abs() < width).map(|r| (r[1] - exact(r[0])).powi(2)).collect();
        let rms = (near.iter().sum::<f64>() / near.len().max(1) as f64).sqrt();
        rep.table += &format!("  {:>5} {:>8} {:>10.4} {:>13.4e} {:>13.4e}\n", n, run.atoms, s.time, max, rms);
        rep.runs.push(json!({"N": n, "atoms": run.atoms, "time": s.time, "step": s.step, "loop_seconds": run.loop_seconds, "max_abs": max, "rms_near": rms}));
        rep.summary.push((format!("max_N{n}"), max));
        conv.push((n as f64, max));
        if n == 100 {
            let pts: Vec<(f64, f64)> = rows.iter().map(|r| (r[0], r[1])).collect();
            profile = Some((pts, s.time));
        }
    }
    let max100 = rep.summary_value("max_N100").unwrap_or(f64::NAN);
    rep.checks.push(Check::below("max |T - T_exact|, N = 100 (T jump 1)", max100, 1e-3));
    let worst = conv.iter().map(|c| c.1).fold(0.0, f64::max);
    rep.checks.push(Check::below("max |T - T_exact|, every resolution", worst, 5e-3));
    if let Some((pts, t)) = profile {
        let w = 0.2;
        let line: Vec<(f64, f64)> = (0..=400).map(|i| -w + 2.0 * w * i as f64 / 400.0).map(|x| (x, analytic::heat_half_spaces(x, t, d, 1.0, 0.0))).collect();
        let pts: Vec<(f64, f64)> = pts.into_iter().filter(|p| p.0.abs() <= w).collect();
        let chart = Chart::new(&format!("Heat conduction, N = 100, t = {} s ({}) vs erf solution", fmt_time(t), opts.engine.name()))
            .x_label("x (m)")
            .y_label("T")
            .series(Series::line("analytic (erf)", line).color(6))
            .series(Series::points(opts.engine.name(), pts).color(0));
        rep.charts.push(("heat_profile".into(), chart));
    }
    Ok(rep)
}

fn hydrostatic(opts: &Options) -> Result<CaseReport, String> {
    let mut rep = CaseReport::new("hydrostatic", opts);
    let (h0, rho0, c, g) = (deck_constant("hydrostatic", "H")?, deck_constant("hydrostatic", "rho0")?, deck_constant("hydrostatic", "c")?, deck_constant("hydrostatic", "g")?);
    let col = analytic::TaitColumn::new(h0, rho0, c, g);
    let ns: &[usize] = if opts.quick { &[20, 40] } else { &[20, 40, 80] };
    rep.table += &format!("  {:>4} {:>8} {:>13} {:>13} {:>13}\n", "N", "atoms", "L2 rel", "interior L2", "max/p_bottom");
    let mut conv = vec![];
    let mut profile = None;
    for &n in ns {
        let run = run_engine(opts.engine, "hydrostatic", &[var("N", n)], &[])?;
        let s = run.last();
        let rows = columns_of_type(&s.state, 1, &["yu", "rho"])?;
        let pairs: Vec<(f64, f64, f64)> = rows.iter().map(|r| (r[0], col.pressure_of_density(r[1]), col.pressure(r[0]))).collect();
        let l2 = l2_relative(pairs.iter().map(|p| (p.1, p.2)));
        // away from the floor and the free surface by one kernel support
        let hk = 2.6 * h0 / n as f64;
        let interior = l2_relative(pairs.iter().filter(|p| p.0 > hk && p.0 < col.surface - hk).map(|p| (p.1, p.2)));
        let max = pairs.iter().map(|p| (p.1 - p.2).abs()).fold(0.0, f64::max) / col.pressure(0.0);
        rep.table += &format!("  {:>4} {:>8} {:>13.4e} {:>13.4e} {:>13.4e}\n", n, run.atoms, l2, interior, max);
        rep.runs.push(json!({"N": n, "atoms": run.atoms, "time": s.time, "step": s.step, "loop_seconds": run.loop_seconds, "l2_rel": l2, "interior_l2_rel": interior, "max_rel_bottom": max}));
        rep.summary.push((format!("l2_N{n}"), l2));
        conv.push((n as f64, l2));
        profile = Some((n, pairs));
    }
    let e40 = rep.summary_value("l2_N40").unwrap_or(f64::NAN);
    rep.checks.push(Check::below("L2 pressure error, N = 40", e40, 0.05));
    for w in conv.windows(2) {
        rep.checks.push(Check::below(&format!("error decreases N = {} -> {} (ratio)", w[0].0, w[1].0), w[1].1 / w[0].1, 1.0));
    }
    if let Some((n, pairs)) = profile {
        let line: Vec<(f64, f64)> = (0..=200).map(|i| col.surface * i as f64 / 200.0).map(|y| (y, col.pressure(y) / 1e3)).collect();
        let chart = Chart::new(&format!("Hydrostatic column, N = {n} ({}) vs Tait column", opts.engine.name()))
            .x_label("y (m)")
            .y_label("p (kPa)")
            .series(Series::line("analytic", line).color(6))
            .series(Series::points(opts.engine.name(), pairs.iter().map(|p| (p.0, p.1 / 1e3)).collect()).color(0));
        rep.charts.push(("hydrostatic_profile".into(), chart));
    }
    Ok(rep)
}

/// Front position Z = (xmax + dx/2) / a against T = t sqrt(2 g / a) from the thermo column c_xmax.
pub fn dambreak_front(run: &RunResult, dx: f64, a: f64, g: f64) -> Result<Vec<(f64, f64)>, String> {
    let t = run.thermo.column("Time").ok_or("dam break: no Time thermo column")?;
    let x = run.thermo.column("c_xmax").ok_or("dam break: no c_xmax thermo column")?;
    Ok(t.iter().zip(&x).map(|(t, x)| (t * (2.0 * g / a).sqrt(), (x + 0.5 * dx) / a)).collect())
}

/// Relative differences of a simulated front from the data points it covers (data Z below
/// `z_max`, T within the run): (T, Z_exp, Z_sim, rel).
pub fn front_differences(front: &[(f64, f64)], data: &[(f64, f64)], z_max: f64) -> Vec<(f64, f64, f64, f64)> {
    data.iter()
        .filter(|(_, z)| *z <= z_max)
        .filter_map(|&(t, z)| analytic::interpolate(front, t).map(|zs| (t, z, zs, (zs - z) / z)))
        .collect()
}

fn dambreak(opts: &Options) -> Result<CaseReport, String> {
    let mut rep = CaseReport::new("dambreak", opts);
    let (a, w, g) = (deck_constant("dambreak", "a")?, deck_constant("dambreak", "W")?, deck_constant("dambreak", "g")?);
    let dxs: &[f64] = if opts.quick { &[0.02] } else { &[0.02, 0.01] };
    // the front meets the far wall at Z = W / a; compare data up to a little before
    let z_max = w / a - 0.1;
    let mut chart = Chart::new(&format!("Dam break surge front ({}) vs Martin & Moyce (1952)", opts.engine.name()))
        .x_label("T = t sqrt(2 g / a)")
        .y_label("Z = x / a")
        .legend(Legend::UpperLeft)
        .x_range(0.0, 4.0)
        .y_range(1.0, 5.0);
    rep.table += &format!("  {:>6} {:>8} {:>9} {:>14} {:>14}\n", "dx", "atoms", "T end", "RMS rel diff", "mean rel diff");
    for (k, &dx) in dxs.iter().enumerate() {
        let run = run_engine(opts.engine, "dambreak", &[var("dx", dx)], &[])?;
        let front = dambreak_front(&run, dx, a, g)?;
        let mut diffs = front_differences(&front, &analytic::MARTIN_MOYCE_A225, z_max);
        diffs.extend(front_differences(&front, &analytic::MARTIN_MOYCE_A1125, z_max));
        if diffs.is_empty() {
            return Err("dam break: the run covers no Martin & Moyce data point".into());
        }
        let rms = (diffs.iter().map(|d| d.3 * d.3).sum::<f64>() / diffs.len() as f64).sqrt();
        let mean = diffs.iter().map(|d| d.3).sum::<f64>() / diffs.len() as f64;
        let tend = front.last().map(|p| p.0).unwrap_or(0.0);
        rep.table += &format!("  {:>6} {:>8} {:>9.3} {:>14.4e} {:>14.4e}\n", dx, run.atoms, tend, rms, mean);
        rep.runs.push(json!({"dx": dx, "atoms": run.atoms, "loop_seconds": run.loop_seconds, "rms_rel": rms, "mean_rel": mean,
            "points": diffs.iter().map(|d| json!({"T": d.0, "Z_exp": d.1, "Z_sim": d.2, "rel": d.3})).collect::<Vec<_>>(),
            "front": front.iter().map(|p| [p.0, p.1]).collect::<Vec<_>>()}));
        rep.summary.push((format!("rms_dx{dx}"), rms));
        rep.checks.push(Check::below(&format!("RMS relative front difference, dx = {dx}"), rms, 0.15));
        chart = chart.series(Series::line(&format!("{}, dx = {dx} ({} particles)", opts.engine.name(), run.atoms), front).color(k));
    }
    chart = chart
        .series(Series::points("Martin & Moyce, a = 2.25 in", analytic::MARTIN_MOYCE_A225.to_vec()).color(6))
        .series(Series::points("Martin & Moyce, a = 1.125 in", analytic::MARTIN_MOYCE_A1125.to_vec()).color(4));
    rep.charts.push(("dambreak_front".into(), chart));
    Ok(rep)
}

/// Sod's shock tube against the exact Riemann solution at the deck's end time: L1 errors (mean
/// absolute difference per particle) of density, velocity and pressure over the particles within
/// `SOD_WINDOW` of the diaphragm (the waves stay inside it; the tube's ends do not).
pub const SOD_WINDOW: f64 = 60.0;

fn sod(opts: &Options) -> Result<CaseReport, String> {
    let mut rep = CaseReport::new("sod", opts);
    let c = |n: &str| deck_constant("sod", n);
    let (x0, gamma) = (c("x0")?, 1.4);
    let left = analytic::GasState { rho: c("rhoL")?, u: 0.0, p: c("pL")? };
    let right = analytic::GasState { rho: c("rhoR")?, u: 0.0, p: c("pR")? };
    let masses = [c("mL")?, c("mR")?];
    let exact = analytic::Riemann::new(left, right, gamma, x0);
    let run = run_engine(opts.engine, "sod", &[], &[])?;
    let s = run.last();
    // (x, rho, u, p) of every particle in the window; p = (gamma - 1) rho esph / m
    let mut pts = vec![];
    for (typ, m) in [(1, masses[0]), (2, masses[1])] {
        for r in columns_of_type(&s.state, typ, &["xu", "rho", "vx", "esph"])? {
            if (r[0] - x0).abs() <= SOD_WINDOW {
                pts.push((r[0], r[1], r[2], (gamma - 1.0) * r[1] * r[3] / m));
            }
        }
    }
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let n = pts.len().max(1) as f64;
    let l1 = |q: fn(&(f64, f64, f64, f64), &analytic::GasState) -> f64| pts.iter().map(|p| q(p, &exact.sample(p.0, s.time)).abs()).sum::<f64>() / n;
    let (e_rho, e_u, e_p) = (l1(|p, e| p.1 - e.rho), l1(|p, e| p.2 - e.u), l1(|p, e| p.3 - e.p));
    rep.table += &format!("  exact: p* = {:.5}, u* = {:.5}; t = {}, {} particles within {SOD_WINDOW} of x0\n", exact.p_star, exact.u_star, fmt_time(s.time), pts.len());
    rep.table += &format!("  {:>8} {:>12} {:>12} {:>12}\n", "atoms", "L1 rho", "L1 u", "L1 p");
    rep.table += &format!("  {:>8} {:>12.4e} {:>12.4e} {:>12.4e}\n", run.atoms, e_rho, e_u, e_p);
    rep.runs.push(json!({"atoms": run.atoms, "time": s.time, "step": s.step, "loop_seconds": run.loop_seconds, "window": SOD_WINDOW,
        "compared": pts.len(), "p_star": exact.p_star, "u_star": exact.u_star, "l1_rho": e_rho, "l1_u": e_u, "l1_p": e_p}));
    rep.summary.extend([("l1_rho".to_string(), e_rho), ("l1_u".to_string(), e_u), ("l1_p".to_string(), e_p)]);
    // measured 0.0097, 0.028, 0.011 (docs/validation.md): a margin of about 2
    rep.checks.push(Check::below("L1 density error (rho jump 0.875)", e_rho, 0.02));
    rep.checks.push(Check::below("L1 velocity error (u* 0.93)", e_u, 0.05));
    rep.checks.push(Check::below("L1 pressure error (p jump 0.9)", e_p, 0.02));
    let xs: Vec<f64> = (0..=1200).map(|i| x0 - SOD_WINDOW + 2.0 * SOD_WINDOW * i as f64 / 1200.0).collect();
    let profiles: [(&str, &str, fn(&(f64, f64, f64, f64)) -> f64, fn(&analytic::GasState) -> f64); 3] = [
        ("density", "rho", |p| p.1, |e| e.rho),
        ("velocity", "u", |p| p.2, |e| e.u),
        ("pressure", "p", |p| p.3, |e| e.p),
    ];
    for (name, sym, of, ex) in profiles {
        let chart = Chart::new(&format!("Sod shock tube, {name} at t = {} ({}) vs exact Riemann solution", fmt_time(s.time), opts.engine.name()))
            .x_label("x")
            .y_label(sym)
            .series(Series::line("exact", xs.iter().map(|&x| (x, ex(&exact.sample(x, s.time)))).collect()).color(6))
            .series(Series::points(opts.engine.name(), pts.iter().map(|p| (p.0, of(p))).collect()).color(0));
        rep.charts.push((format!("sod_{name}"), chart));
    }
    Ok(rep)
}

// ---------------------------------------------------------------------------------------------
// Speed against accuracy (Poiseuille flow)
// ---------------------------------------------------------------------------------------------

/// One point of the speed-accuracy chart.
#[derive(Clone, Debug)]
pub struct SpeedPoint {
    pub engine: Engine,
    pub kernel: String,
    pub n: usize,
    /// Viscous time-step number nu dt / dx^2.
    pub cdt: f64,
    pub seconds: f64,
    /// L2 velocity error at t = 1 s; None: the run failed (unstable).
    pub error: Option<f64>,
    pub note: String,
}

/// The runs of the chart: (kernel, N, cdt, with LAMMPS too).
pub fn speed_configs(quick: bool) -> Vec<(&'static str, usize, f64, bool)> {
    let ns: &[usize] = if quick { &[10, 20] } else { &[10, 20, 40, 80] };
    // 0.4 is past the viscous stability limit of this set-up (the error jumps to ~20 %)
    let dts: &[f64] = if quick { &[0.2] } else { &[0.05, 0.2, 0.3, 0.4] };
    let ndt = if quick { 20 } else { 40 };
    let mut v = vec![];
    for &n in ns {
        v.push(("lucy", n, 0.1, true));
    }
    for &c in dts {
        v.push(("lucy", ndt, c, true));
    }
    for k in ["cubic", "wendland2"] {
        for &n in ns {
            v.push((k, n, 0.1, false));
        }
    }
    v
}

fn poiseuille_error(state: &AtomTable, t: f64) -> Result<f64, String> {
    let exact = channel_exact("poiseuille")?;
    let rows = columns_of_type(state, 1, &["yu", "vx"])?;
    Ok(l2_relative(rows.iter().map(|r| (r[1], exact(r[0], t)))))
}

/// Each timing of the speed sweep is the fastest of this many runs.
pub const TIMING_REPEATS: usize = 2;

/// Run the sweep: dmhs on one thread (its main-loop time), LAMMPS serial (`lmp`'s loop time,
/// with the state from the driver). `progress` is told each finished point.
pub fn speed_sweep(quick: bool, progress: &mut dyn FnMut(&SpeedPoint)) -> Result<Vec<SpeedPoint>, String> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().map_err(|e| e.to_string())?;
    let (path, text) = deck("poiseuille").unwrap();
    let dir = tempfile::tempdir().map_err(|e| e.to_string())?;
    let deck_path = dir.path().join(Path::new(path).file_name().unwrap());
    std::fs::write(&deck_path, text).map_err(|e| e.to_string())?;
    let mut out = vec![];
    for (kernel, n, cdt, with_lammps) in speed_configs(quick) {
        let vars = vec![var("N", n), var("cdt", cdt), var("kernel", kernel), var("tend", 1.0)];
        let mut p = SpeedPoint { engine: Engine::Dmhs, kernel: kernel.into(), n, cdt, seconds: 0.0, error: None, note: String::new() };
        match pool.install(|| run_dmhs("poiseuille", &vars, &[])) {
            Ok(run) => {
                // the fastest of TIMING_REPEATS runs (the runs are identical; the machine is not)
                p.seconds = run.loop_seconds;
                for _ in 1..TIMING_REPEATS {
                    p.seconds = p.seconds.min(pool.install(|| run_dmhs("poiseuille", &vars, &[]))?.loop_seconds);
                }
                let e = poiseuille_error(&run.last().state, run.last().time)?;
                p.error = Some(e).filter(|e| e.is_finite());
            }
            Err(e) => p.note = e.lines().find(|l| l.contains("error")).unwrap_or("failed").trim().to_string(),
        }
        progress(&p);
        out.push(p);
        if with_lammps {
            let mut q = SpeedPoint { engine: Engine::Lammps, kernel: kernel.into(), n, cdt, seconds: 0.0, error: None, note: String::new() };
            match run_lammps("poiseuille", &vars, &[]) {
                Ok(run) => {
                    let e = poiseuille_error(&run.last().state, run.last().time)?;
                    q.error = Some(e).filter(|e| e.is_finite());
                    q.seconds = f64::INFINITY;
                    for _ in 0..TIMING_REPEATS {
                        q.seconds = q.seconds.min(crate::tools::lammps::time_lmp(&deck_path, &deck_vars(&vars), crate::tools::lammps::LmpConfig::Serial)?.seconds);
                    }
                }
                Err(e) => q.note = e.lines().find(|l| l.contains("ERROR")).unwrap_or("failed").trim().to_string(),
            }
            progress(&q);
            out.push(q);
        }
    }
    Ok(out)
}

/// The speed-accuracy chart and the kernel convergence chart from a sweep.
pub fn speed_charts(points: &[SpeedPoint]) -> Vec<(String, Chart)> {
    let ok = |p: &&SpeedPoint| p.error.is_some() && p.seconds > 0.0;
    let mut chart = Chart::new("Poiseuille flow: L2 velocity error at t = 1 s against wall-clock time")
        .x_label("main-loop wall-clock time (s), one core")
        .y_label("relative L2 error of u")
        .log_x()
        .log_y()
        .x_range(0.01, 50.0)
        .y_range(1e-3, 0.5)
        .legend(Legend::LowerLeft);
    let mut conv = Chart::new("Poiseuille flow: convergence by kernel (t = 1 s, nu dt/dx^2 = 0.1)")
        .x_label("N = L / dx")
        .y_label("relative L2 error of u")
        .log_x()
        .log_y()
        .legend(Legend::LowerLeft);
    let groups: [(Engine, &str, usize); 4] = [(Engine::Dmhs, "lucy", 0), (Engine::Lammps, "lucy", 1), (Engine::Dmhs, "cubic", 2), (Engine::Dmhs, "wendland2", 3)];
    for (engine, kernel, color) in groups {
        let pts: Vec<&SpeedPoint> = points.iter().filter(ok).filter(|p| p.engine == engine && p.kernel == kernel && p.cdt == 0.1).collect();
        if pts.is_empty() {
            continue;
        }
        let name = format!("{} {kernel}, N = {}", engine.name(), pts.iter().map(|p| p.n.to_string()).collect::<Vec<_>>().join(", "));
        let mut series = Series::line_points(&name, pts.iter().map(|p| (p.seconds, p.error.unwrap())).collect()).color(color);
        if engine == Engine::Dmhs {
            // LAMMPS' points sit beside dmhs' (same N): label one engine only
            series = series.labels(pts.iter().map(|p| format!("N={}", p.n)).collect());
        }
        chart = chart.series(series);
        conv = conv.series(Series::line_points(&format!("{} {kernel}", engine.name()), pts.iter().map(|p| (p.n as f64, p.error.unwrap())).collect()).color(color));
    }
    // time-step sweeps at one resolution
    for (engine, color) in [(Engine::Dmhs, 5), (Engine::Lammps, 4)] {
        let mut pts: Vec<&SpeedPoint> = points.iter().filter(ok).filter(|p| p.engine == engine && p.kernel == "lucy" && p.cdt != 0.1).collect();
        if pts.is_empty() {
            continue;
        }
        let n = pts[0].n;
        // include the cdt = 0.1 point of that resolution
        pts.extend(points.iter().filter(ok).filter(|p| p.engine == engine && p.kernel == "lucy" && p.cdt == 0.1 && p.n == n));
        pts.sort_by(|a, b| b.cdt.total_cmp(&a.cdt));
        chart = chart.series(
            Series::line_points(&format!("{} lucy, N = {n}, nu dt/dx^2 = {}", engine.name(), pts.iter().map(|p| p.cdt.to_string()).collect::<Vec<_>>().join(", ")), pts.iter().map(|p| (p.seconds, p.error.unwrap())).collect())
                .color(color)
                .labels(if engine == Engine::Dmhs { pts.iter().map(|p| format!("{}", p.cdt)).collect() } else { vec![] }),
        );
    }
    vec![("speed_accuracy".into(), chart), ("poiseuille_kernels".into(), conv)]
}

// ---------------------------------------------------------------------------------------------
// Command line
// ---------------------------------------------------------------------------------------------

pub(crate) fn write_json(path: &Path, value: &Value) -> Result<(), String> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    }
    let text = serde_json::to_string_pretty(value).map_err(|e| e.to_string())? + "\n";
    std::fs::write(path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

pub(crate) fn save_charts(charts: &[(String, Chart)], dir: &Path) -> Result<(), String> {
    for (stem, chart) in charts {
        for f in chart.save(&dir.join(stem))? {
            println!("  wrote {}", f.display());
        }
    }
    Ok(())
}

/// `dmhs validate CASE [--quick] [--engine dmhs|lammps] [--json FILE] [--img DIR]`.
pub fn validate_cmd(args: &[PathBuf], quick: bool, engine: Option<&str>, json_path: Option<&Path>, img: Option<&Path>) -> i32 {
    let [case] = args else {
        eprintln!("dmhs validate: give one case: {}, all, chart or convergence", CASES.join(", "));
        return 2;
    };
    let case = case.to_string_lossy().to_string();
    let engine = match engine.unwrap_or("dmhs") {
        "dmhs" => Engine::Dmhs,
        "lammps" => Engine::Lammps,
        e => {
            eprintln!("dmhs validate: --engine {e}: expected dmhs or lammps");
            return 2;
        }
    };
    if case == "chart" {
        return chart_cmd(quick, json_path, img);
    }
    if case == "convergence" {
        return crate::tools::validate_convergence::convergence_cmd(quick, json_path, img);
    }
    let cases: Vec<&str> = if case == "all" { CASES.to_vec() } else { vec![case.as_str()] };
    if !cases.iter().all(|c| CASES.contains(c)) {
        eprintln!("dmhs validate: unknown case `{case}` (cases: {}, all, chart, convergence)", CASES.join(", "));
        return 2;
    }
    let opts = Options { quick, engine };
    let mut status = 0;
    for c in cases {
        let rep = match run_case(c, &opts) {
            Ok(r) => r,
            Err(e) => {
                eprintln!("dmhs validate {c}: {e}");
                status = 1;
                continue;
            }
        };
        print!("{}", rep.render());
        let path = match json_path {
            Some(p) if case != "all" => p.to_path_buf(),
            Some(p) => p.join(format!("{c}.json")),
            None => PathBuf::from(format!("out/validate/{c}{}.json", if engine == Engine::Lammps { "-lammps" } else { "" })),
        };
        if let Err(e) = write_json(&path, &rep.to_json()) {
            eprintln!("dmhs validate: {e}");
            status = 1;
        } else {
            println!("  wrote {}", path.display());
        }
        if let Some(dir) = img {
            if let Err(e) = save_charts(&rep.charts, dir) {
                eprintln!("dmhs validate: {e}");
                status = 1;
            }
        }
        if !rep.passed() {
            status = 1;
        }
    }
    status
}

fn chart_cmd(quick: bool, json_path: Option<&Path>, img: Option<&Path>) -> i32 {
    println!("{:<8} {:<10} {:>4} {:>6} {:>10} {:>12}  {}", "engine", "kernel", "N", "cdt", "seconds", "L2 error", "note");
    let mut show = |p: &SpeedPoint| {
        println!(
            "{:<8} {:<10} {:>4} {:>6} {:>10.4} {:>12}  {}",
            p.engine.name(),
            p.kernel,
            p.n,
            p.cdt,
            p.seconds,
            p.error.map(|e| format!("{e:.4e}")).unwrap_or("unstable".into()),
            p.note
        );
    };
    let points = match speed_sweep(quick, &mut show) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("dmhs validate chart: {e}");
            return 1;
        }
    };
    let value = json!({
        "case": "speed_accuracy",
        "deck": deck("poiseuille").map(|d| d.0),
        "quick": quick,
        "timing": format!("main-loop seconds, fastest of {TIMING_REPEATS} runs; dmhs on one thread, LAMMPS serial lmp (OMP_NUM_THREADS=1)"),
        "points": points.iter().map(|p| json!({"engine": p.engine.name(), "kernel": p.kernel, "N": p.n, "cdt": p.cdt,
            "seconds": p.seconds, "l2_rel": p.error, "note": p.note})).collect::<Vec<_>>(),
    });
    let path = json_path.map(Path::to_path_buf).unwrap_or(PathBuf::from("out/validate/speed_accuracy.json"));
    let mut status = 0;
    match write_json(&path, &value) {
        Ok(()) => println!("  wrote {}", path.display()),
        Err(e) => {
            eprintln!("dmhs validate chart: {e}");
            status = 1;
        }
    }
    // the tracked charts (docs/img) change only when asked (--img docs/img)
    let dir = img.map(Path::to_path_buf).unwrap_or(PathBuf::from("out/validate"));
    if let Err(e) = save_charts(&speed_charts(&points), &dir) {
        eprintln!("dmhs validate chart: {e}");
        status = 1;
    }
    status
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thermo_blocks_merge() {
        let text = "x\n   Step          Time          c_xmax    \n         0   0              0.695        \n        10   0.1            0.7\nLoop time of 0.1 on 1 procs\n\
                    Step          Time          c_xmax\n        10   0.1            0.7\n        20   0.2            0.8\nLoop time\n";
        let t = parse_thermo(text);
        assert_eq!(t.columns, vec!["Step", "Time", "c_xmax"]);
        assert_eq!(t.column("c_xmax").unwrap(), vec![0.695, 0.7, 0.8]);
    }

    #[test]
    fn deck_constants() {
        assert_eq!(deck_constant("poiseuille", "L").unwrap(), 1.0e-3);
        assert_eq!(deck_constant("poiseuille", "F").unwrap(), 2.0e-4);
        assert_eq!(deck_constant("couette", "U").unwrap(), 2.5e-5);
        assert_eq!(deck_constant("heat", "D").unwrap(), 1.0e-3);
        assert_eq!(deck_constant("dambreak", "a").unwrap(), 0.7);
        assert!(deck_constant("poiseuille", "dx").is_err()); // a formula, not a number
        assert!(deck_constant("nope", "L").is_err());
    }

    #[test]
    fn error_measures() {
        assert_eq!(l2_relative([(1.0, 1.0), (2.0, 2.0)]), 0.0);
        assert!((l2_relative([(1.1, 1.0), (0.0, 0.0)]) - 0.1).abs() < 1e-12);
        let o = orders(&[(10.0, 0.04), (20.0, 0.01), (40.0, 0.005)]);
        assert!((o[0] - 2.0).abs() < 1e-12 && (o[1] - 1.0).abs() < 1e-12);
        let front = vec![(0.0, 1.0), (1.0, 2.0), (2.0, 3.0)];
        let d = front_differences(&front, &[(0.5, 1.25), (1.5, 2.5), (3.0, 4.0)], 10.0);
        assert_eq!(d.len(), 2);
        assert!((d[0].3 - 0.2).abs() < 1e-12);
    }
}
