//! `dmhs._dmhs`: the engine behind the Python class `dmhs.lammps` (python/dmhs/__init__.py).
//!
//! One `Core` holds a simulation and the interpreter that feeds it commands (the pair
//! `dmhs::deck::prepare` makes), and its own worker-thread pool. Commands run with the GIL
//! released. Every engine error comes back as `DmhsError` with the rendered, located message;
//! a closed instance, an unknown name or a wrong type raise instead of crashing. Arrays come
//! back as `(dtype, bytearray, shape)` copies that the Python side views with numpy.

mod atoms;

use atoms::Column;
use dmhs::deck::DeckOptions;
use dmhs::parser::interp::Interpreter;
use dmhs::parser::{Span, Word};
use dmhs::sim::Simulation;
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyByteArray, PyList};
use pyo3::IntoPyObjectExt;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, TryLockError};

create_exception!(_dmhs, DmhsError, PyException, "An error of the dmhs engine (its message is located: file:line:col).");

/// The LAMMPS version whose behaviour dmhs follows (`lammps.version()`).
const LAMMPS_VERSION: i64 = 20250722;

// LAMMPS' style and type codes (lammps.constants)
const STYLE_GLOBAL: i32 = 0;
const STYLE_ATOM: i32 = 1;
const TYPE_SCALAR: i32 = 0;
const TYPE_VECTOR: i32 = 1;
const TYPE_ARRAY: i32 = 2;
const SIZE_VECTOR: i32 = 3;
const SIZE_ROWS: i32 = 4;
const SIZE_COLS: i32 = 5;
const VAR_EQUAL: i32 = 0;
const VAR_ATOM: i32 = 1;
const VAR_VECTOR: i32 = 2;
const VAR_STRING: i32 = 3;

struct Engine {
    sim: Simulation,
    interp: Interpreter,
    pool: rayon::ThreadPool,
}

/// What a command runs: a file, one line, or several lines.
enum Source<'a> {
    File(&'a str),
    Line(&'a str),
    Lines(&'a str, &'a str),
}

impl Engine {
    fn execute(&mut self, src: Source) -> Result<(), String> {
        let Engine { sim, interp, pool } = self;
        // the command's loops run on a team as large as the pool (made per command: the pool
        // runs it on any of its threads, and a team belongs to the thread that made it)
        let threads = pool.current_num_threads();
        let result = pool.install(|| {
            dmhs::engine::par::with_threads(threads, || match src {
                Source::File(path) => interp.run_file(path, sim),
                Source::Line(text) => interp.execute_line(text, sim),
                Source::Lines(name, text) => interp.run_source(name, text, sim),
            })
        });
        sim.out.flush();
        result.map(|_| ()).map_err(|diags| diags.iter().map(|d| d.render(interp.sources())).collect::<Vec<_>>().join("\n"))
    }

    fn state(&self) -> &dmhs::sim::State {
        &self.sim.state
    }

    fn domain(&self) -> Result<&dmhs::engine::domain::Domain, String> {
        self.sim.state.domain.as_ref().ok_or_else(|| "no simulation box yet (create_box or read_data first)".to_string())
    }

    /// Owned atoms sorted by ID, refused unless the IDs are 1..N (as LAMMPS' gather/scatter).
    fn consecutive(&self) -> Result<Vec<usize>, String> {
        let order = atoms::by_id(self.state());
        let tag = &self.state().atoms.tag;
        if order.iter().enumerate().any(|(k, &i)| tag[i] != k as i64 + 1) {
            return Err("gather/scatter need atom IDs 1..N with no gaps (use reset_atoms id)".into());
        }
        Ok(order)
    }
}

fn err(e: impl std::fmt::Display) -> PyErr {
    DmhsError::new_err(e.to_string())
}

/// A copy of per-atom or vector data for numpy: `(dtype, bytearray, shape)`.
fn array<'py>(py: Python<'py>, col: &Column, shape: Vec<usize>) -> PyResult<Bound<'py, PyAny>> {
    let (dtype, bytes): (&str, Vec<u8>) = match col {
        Column::F64(v) => ("f8", v.iter().flat_map(|x| x.to_ne_bytes()).collect()),
        Column::I32(v) => ("i4", v.iter().flat_map(|x| x.to_ne_bytes()).collect()),
    };
    (dtype, PyByteArray::new(py, &bytes), shape).into_bound_py_any(py)
}

fn rows_shape(n: usize, cols: usize) -> Vec<usize> {
    if cols == 1 {
        vec![n]
    } else {
        vec![n, cols]
    }
}

#[pyclass(module = "dmhs._dmhs")]
struct Core {
    engine: Mutex<Option<Engine>>,
    /// The simulation's cancellation flag, reachable while a command holds the engine.
    cancel: Arc<AtomicBool>,
}

impl Core {
    /// Run `f` on the engine; errors for a closed or busy instance.
    fn with<R>(&self, f: impl FnOnce(&mut Engine) -> Result<R, String>) -> Result<R, String> {
        let mut guard = match self.engine.try_lock() {
            Ok(g) => g,
            Err(TryLockError::WouldBlock) => return Err("this dmhs instance is busy: a command is running in another thread".into()),
            Err(TryLockError::Poisoned(_)) => return Err("this dmhs instance is unusable after an internal error; close it and make a new one".into()),
        };
        let engine = guard.as_mut().ok_or("this dmhs instance is closed")?;
        f(engine)
    }

    fn py_with<R>(&self, f: impl FnOnce(&mut Engine) -> Result<R, String>) -> PyResult<R> {
        self.with(f).map_err(err)
    }

    /// The flag is cleared by the caller (`clear_cancel`) before the command's thread starts:
    /// a clear here, on that thread, could come after a Ctrl-C's cancel and lose it.
    fn run(&self, py: Python, src: Source) -> PyResult<()> {
        py.allow_threads(|| self.with(|e| e.execute(src))).map_err(err)
    }
}

#[pymethods]
impl Core {
    #[new]
    fn new(cmdargs: Vec<String>) -> PyResult<Core> {
        let (opts, threads): (DeckOptions, Option<usize>) = dmhs::tools::cli::lmp_options(&cmdargs).map_err(err)?;
        let (sim, interp) = dmhs::deck::prepare(&opts).map_err(err)?;
        // worker stacks as large as a main thread's, for deeply nested decks (as the CLI)
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads.map(|n| n.max(1)).unwrap_or(0)).stack_size(8 << 20).build().map_err(err)?;
        let cancel = sim.cancel.clone();
        Ok(Core { engine: Mutex::new(Some(Engine { sim, interp, pool })), cancel })
    }

    /// Stop a running `run` at its next step (callable from any thread while it runs).
    fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    /// Forget a cancellation that came when no command ran (called before each command).
    fn clear_cancel(&self) {
        self.cancel.store(false, Ordering::Relaxed);
    }

    fn close(&self) -> PyResult<()> {
        match self.engine.try_lock() {
            Ok(mut g) => {
                if let Some(mut e) = g.take() {
                    e.sim.out.flush();
                }
                Ok(())
            }
            Err(TryLockError::Poisoned(p)) => {
                p.into_inner().take();
                Ok(())
            }
            Err(TryLockError::WouldBlock) => Err(err("cannot close: a command is running in another thread")),
        }
    }

    fn is_open(&self) -> bool {
        matches!(self.engine.try_lock().as_deref(), Ok(Some(_)))
    }

    fn file(&self, py: Python, path: &str) -> PyResult<()> {
        self.run(py, Source::File(path))
    }

    fn command(&self, py: Python, line: &str) -> PyResult<()> {
        self.run(py, Source::Line(line))
    }

    fn commands_string(&self, py: Python, name: &str, text: &str) -> PyResult<()> {
        self.run(py, Source::Lines(name, text))
    }

    fn version(&self) -> i64 {
        LAMMPS_VERSION
    }

    fn get_natoms(&self) -> PyResult<usize> {
        self.py_with(|e| Ok(e.state().atoms.nlocal))
    }

    fn get_thermo(&self, name: &str) -> PyResult<f64> {
        use dmhs::parser::EvalContext;
        self.py_with(|e| e.sim.thermo_keyword(name).unwrap_or_else(|| Err(format!("get_thermo: unknown thermo keyword `{name}`"))))
    }

    /// `extract_global`: ints, floats, strings and 3-lists as LAMMPS' Python module returns them.
    fn extract_global<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        enum G {
            I(i64),
            F(f64),
            S(String),
            F3([f64; 3]),
            I3([i64; 3]),
        }
        let g = self.py_with(|e| {
            let st = e.state();
            let box_d = |k: usize, hi: bool| e.domain().map(|d| if hi { d.hi[k] } else { d.lo[k] });
            Ok(match name {
                "units" => G::S(st.units.name().to_string()),
                "atom_style" => G::S(st.atom_style.join(" ")),
                "triclinic" => G::I(0),
                "xy" | "xz" | "yz" => G::F(0.0),
                "boxlo" => G::F3(e.domain()?.lo),
                "boxhi" => G::F3(e.domain()?.hi),
                "boxxlo" => G::F(box_d(0, false)?),
                "boxxhi" => G::F(box_d(0, true)?),
                "boxylo" => G::F(box_d(1, false)?),
                "boxyhi" => G::F(box_d(1, true)?),
                "boxzlo" => G::F(box_d(2, false)?),
                "boxzhi" => G::F(box_d(2, true)?),
                "sublo" => G::F3(e.domain()?.lo),
                "subhi" => G::F3(e.domain()?.hi),
                "periodicity" => {
                    let d = e.domain()?;
                    G::I3([0, 1, 2].map(|k| d.periodic(k) as i64))
                }
                "natoms" | "nlocal" => G::I(st.atoms.nlocal as i64),
                "nghost" => G::I(st.atoms.nghost() as i64),
                "nmax" => G::I(st.atoms.x.len() as i64),
                "ntypes" => G::I(st.ntypes as i64),
                "nbonds" => G::I(st.topo.bonds.len() as i64),
                "nangles" => G::I(st.topo.angles.len() as i64),
                "ndihedrals" => G::I(st.topo.dihedrals.len() as i64),
                "ntimestep" => G::I(st.step),
                "dt" => G::F(st.dt),
                "atime" => G::F(st.atime),
                "atimestep" => G::I(st.atimestep),
                "boltz" => G::F(st.units.boltz),
                "mvv2e" => G::F(st.units.mvv2e),
                "ftm2v" => G::F(st.units.ftm2v),
                "nktv2p" => G::F(st.units.nktv2p),
                "q_flag" => G::I(st.atoms.features.charge as i64),
                _ => return Err(format!("extract_global: `{name}` is not a global property dmhs knows (see docs/python.md; integer settings: extract_setting)")),
            })
        })?;
        match g {
            G::I(v) => v.into_bound_py_any(py),
            G::F(v) => v.into_bound_py_any(py),
            G::S(v) => v.into_bound_py_any(py),
            G::F3(v) => PyList::new(py, v)?.into_bound_py_any(py),
            G::I3(v) => PyList::new(py, v)?.into_bound_py_any(py),
        }
    }

    /// `extract_setting`: LAMMPS' integer settings (sizes, counts, flags).
    fn extract_setting(&self, name: &str) -> PyResult<i64> {
        self.py_with(|e| {
            let st = e.state();
            let f = &st.atoms.features;
            Ok(match name {
                "bigint" => 8,
                "tagint" | "imageint" => 4,
                "dimension" => st.dimension as i64,
                "box_exist" => st.domain.is_some() as i64,
                "triclinic" => 0,
                "nlocal" => st.atoms.nlocal as i64,
                "nghost" => st.atoms.nghost() as i64,
                "nall" => st.atoms.nall() as i64,
                "nmax" => st.atoms.x.len() as i64,
                "ntypes" => st.ntypes as i64,
                "nbondtypes" => st.topo.nbondtypes as i64,
                "nangletypes" => st.topo.nangletypes as i64,
                "ndihedraltypes" => st.topo.ndihedraltypes as i64,
                "nimpropertypes" => st.topo.nimpropertypes as i64,
                "newton_pair" => st.newton_pair as i64,
                "newton_bond" => st.newton_bond as i64,
                "world_rank" | "universe_rank" => 0,
                "world_size" | "universe_size" => 1,
                "nthreads" => e.pool.current_num_threads() as i64,
                "molecule_flag" => f.molecule as i64,
                "q_flag" => f.charge as i64,
                "rmass_flag" | "radius_flag" | "omega_flag" | "torque_flag" => f.sphere as i64,
                _ => return Err(format!("extract_setting: `{name}` is not a setting dmhs knows (see docs/python.md)")),
            })
        })
    }

    /// Per-atom data of the owned atoms in their current order (`mass`: the per-type masses,
    /// index 0 unused, as LAMMPS).
    fn extract_atom<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        let (col, shape) = self.py_with(|e| {
            let st = e.state();
            if name == "mass" {
                let mut m = st.type_mass.clone();
                m.resize(st.ntypes + 1, 0.0);
                return Ok((Column::F64(m), vec![st.ntypes + 1]));
            }
            let order: Vec<usize> = (0..st.atoms.nlocal).collect();
            let (col, cols) = atoms::read(st, name, &order)?;
            Ok((col, rows_shape(order.len(), cols)))
        })?;
        array(py, &col, shape)
    }

    /// `gather_atoms`: values of all atoms sorted by ID, `count` per atom.
    fn gather_atoms<'py>(&self, py: Python<'py>, name: &str, dtype: i32, count: usize) -> PyResult<Bound<'py, PyAny>> {
        let col = self.py_with(|e| {
            let order = e.consecutive()?;
            let pr = atoms::prop(name)?;
            check_type(name, pr, dtype, count)?;
            Ok(atoms::read(e.state(), name, &order)?.0)
        })?;
        let n = match &col {
            Column::F64(v) => v.len(),
            Column::I32(v) => v.len(),
        };
        array(py, &col, vec![n])
    }

    /// `scatter_atoms`: `data` (native bytes of `count` values per atom, sorted by ID).
    fn scatter_atoms(&self, name: &str, dtype: i32, count: usize, data: &[u8]) -> PyResult<()> {
        self.py_with(|e| {
            let order = e.consecutive()?;
            let pr = atoms::prop(name)?;
            check_type(name, pr, dtype, count)?;
            let width = if pr.int { 4 } else { 8 };
            let want = order.len() * count;
            if data.len() != want * width {
                return Err(format!("scatter_atoms {name}: {} values given, {want} expected ({} atoms x {count})", data.len() / width, order.len()));
            }
            let col = if pr.int {
                Column::I32(data.chunks_exact(4).map(|c| i32::from_ne_bytes(c.try_into().unwrap())).collect())
            } else {
                Column::F64(data.chunks_exact(8).map(|c| f64::from_ne_bytes(c.try_into().unwrap())).collect())
            };
            atoms::write(&mut e.sim.state, name, &order, &col)
        })
    }

    /// `extract_compute`: a float, an int (sizes) or an array.
    fn extract_compute<'py>(&self, py: Python<'py>, id: &str, style: i32, kind: i32) -> PyResult<Bound<'py, PyAny>> {
        enum R {
            F(f64),
            I(usize),
            A(Column, Vec<usize>),
        }
        let r = self.py_with(|e| {
            let world = e.sim.world();
            let c = world.compute(id).ok_or_else(|| format!("extract_compute: compute `{id}` does not exist"))?;
            let what = |s: &str| format!("extract_compute: compute `{id}` ({}) {s}", c.style());
            Ok(match (style, kind) {
                (STYLE_GLOBAL, TYPE_SCALAR) => R::F(c.scalar(&world).map_err(|m| what(&m))?),
                (STYLE_GLOBAL, TYPE_VECTOR) => {
                    let v = c.vector(&world).map_err(|m| what(&m))?;
                    let n = v.len();
                    R::A(Column::F64(v), vec![n])
                }
                (STYLE_GLOBAL, SIZE_VECTOR) => R::I(c.vector(&world).map_err(|m| what(&m))?.len()),
                (STYLE_ATOM, TYPE_VECTOR | TYPE_ARRAY | SIZE_COLS | SIZE_ROWS) => {
                    let cols = c.peratom_cols().ok_or_else(|| what("has no per-atom values"))?;
                    match kind {
                        SIZE_COLS => R::I(if cols == 1 { 0 } else { cols }),
                        SIZE_ROWS => R::I(e.state().atoms.nlocal),
                        TYPE_VECTOR if cols != 1 => return Err(what(&format!("has {cols} per-atom columns: ask for LMP_TYPE_ARRAY"))),
                        TYPE_ARRAY if cols == 1 => return Err(what("has one per-atom value: ask for LMP_TYPE_VECTOR")),
                        _ => {
                            let p = c.peratom(&world).map_err(|m| what(&m))?;
                            let n = p.data.len() / p.cols.max(1);
                            R::A(Column::F64(p.data), rows_shape(n, p.cols))
                        }
                    }
                }
                _ => return Err(what(&format!("style {style} type {kind}: dmhs has global scalars and vectors and per-atom vectors and arrays (no global arrays, no local data)"))),
            })
        })?;
        match r {
            R::F(v) => v.into_bound_py_any(py),
            R::I(v) => v.into_bound_py_any(py),
            R::A(col, shape) => array(py, &col, shape),
        }
    }

    /// `extract_fix`: a global scalar, or element `nrow` of a global vector (LAMMPS' semantics).
    fn extract_fix(&self, id: &str, style: i32, kind: i32, nrow: usize) -> PyResult<f64> {
        self.py_with(|e| {
            let k = e.sim.find_fix(id).ok_or_else(|| format!("extract_fix: fix `{id}` does not exist"))?;
            let fix = &e.sim.fixes[k];
            let st = e.state();
            let what = |s: &str| format!("extract_fix: fix `{id}` ({}) {s}", fix.style());
            match (style, kind) {
                (STYLE_GLOBAL, TYPE_SCALAR) => fix.scalar(st).ok_or_else(|| what("has no global scalar")),
                // nrow counts from 0, the engine's index (f_ID[i]) from 1
                (STYLE_GLOBAL, TYPE_VECTOR) => fix.vector(st, nrow + 1).ok_or_else(|| what(&format!("has no global vector element {nrow} (counted from 0)"))),
                (STYLE_GLOBAL, SIZE_VECTOR) => Ok((1..).take_while(|&i| fix.vector(st, i).is_some()).count() as f64),
                _ => Err(what(&format!("style {style} type {kind}: dmhs fixes have global scalars and vectors only"))),
            }
        })
    }

    /// `extract_variable`: vartype None detects it from the variable's style.
    fn extract_variable<'py>(&self, py: Python<'py>, name: &str, vartype: Option<i32>) -> PyResult<Bound<'py, PyAny>> {
        use dmhs::parser::variables;
        enum V {
            F(f64),
            S(String),
        }
        let v = self.py_with(|e| {
            let style = variables::style_of(&mut e.sim, name).ok_or_else(|| format!("extract_variable: variable `{name}` does not exist"))?;
            let detected = match style {
                "equal" | "internal" => VAR_EQUAL,
                "atom" => VAR_ATOM,
                "vector" => VAR_VECTOR,
                _ => VAR_STRING,
            };
            // LAMMPS returns a string-like variable (index, string, ...) as its string whatever
            // vartype asks for
            let kind = if detected == VAR_STRING { VAR_STRING } else { vartype.unwrap_or(detected) };
            match kind {
                VAR_EQUAL => variables::compute_equal(&mut e.sim, name).map(V::F).map_err(|m| format!("extract_variable {name}: {m}")),
                VAR_STRING => match variables::retrieve(&mut e.sim, name) {
                    Ok(Some(s)) => Ok(V::S(s)),
                    Ok(None) => Err(format!("extract_variable: variable `{name}` has no string value")),
                    Err(m) => Err(format!("extract_variable {name}: {m}")),
                },
                VAR_ATOM | VAR_VECTOR => Err(format!("extract_variable {name}: atom- and vector-style variables are not evaluated by dmhs")),
                other => Err(format!("extract_variable: vartype {other} is not one of LMP_VAR_EQUAL, LMP_VAR_ATOM, LMP_VAR_VECTOR, LMP_VAR_STRING")),
            }
        })?;
        match v {
            V::F(x) => x.into_bound_py_any(py),
            V::S(s) => s.into_bound_py_any(py),
        }
    }

    /// `set_string_variable` (and the older `set_variable`): 0, or -1 when `name` is a
    /// variable of another style (as LAMMPS).
    fn set_string_variable(&self, name: &str, value: &str) -> PyResult<i32> {
        self.py_with(|e| match e.sim.variables.style(name) {
            Some(s) if s != "string" => Ok(-1),
            _ => {
                let w = |t: &str| Word::new(t, Span::default());
                e.sim.variables.command(&[w(name), w("string"), w(value)]).map_err(|d| d.message.clone())?;
                Ok(0)
            }
        })
    }

    fn set_internal_variable(&self, name: &str, value: f64) -> PyResult<i32> {
        self.py_with(|e| match e.sim.variables.style(name) {
            Some(s) if s != "internal" => Ok(-1),
            _ => {
                e.sim.variables.set_internal(name, value);
                Ok(0)
            }
        })
    }

    /// `reset_box`: new bounds (dmhs has orthogonal boxes only: tilts must be 0).
    fn reset_box(&self, boxlo: [f64; 3], boxhi: [f64; 3], xy: f64, yz: f64, xz: f64) -> PyResult<()> {
        self.py_with(|e| {
            if xy != 0.0 || yz != 0.0 || xz != 0.0 {
                return Err("reset_box: dmhs has orthogonal boxes only (xy, yz, xz must be 0)".into());
            }
            if (0..3).any(|k| !(boxlo[k] < boxhi[k])) {
                return Err(format!("reset_box: boxlo {boxlo:?} must be below boxhi {boxhi:?}"));
            }
            let st = &mut e.sim.state;
            let d = st.domain.as_mut().ok_or("reset_box: no simulation box yet")?;
            d.lo = boxlo;
            d.hi = boxhi;
            st.lists_valid = false;
            Ok(())
        })
    }
}

/// gather/scatter's dtype (0 integers, 1 doubles) and count must fit the property.
fn check_type(name: &str, pr: &atoms::Prop, dtype: i32, count: usize) -> Result<(), String> {
    let want = if pr.int { 0 } else { 1 };
    if dtype != want {
        return Err(format!("per-atom property `{name}` holds {}: dtype must be {want}, not {dtype}", if pr.int { "integers" } else { "doubles" }));
    }
    if count != pr.cols {
        return Err(format!("per-atom property `{name}` has {} value(s) per atom: count must be {}, not {count}", pr.cols, pr.cols));
    }
    Ok(())
}

#[pymodule]
fn _dmhs(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Core>()?;
    m.add("DmhsError", m.py().get_type::<DmhsError>())?;
    m.add("DMHS_VERSION", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
