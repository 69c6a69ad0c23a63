//! Expressions see the whole simulation: [`Eval`] is the evaluation context of variables,
//! thermo columns and dumps (the state, every compute and fix, the thermo settings and the
//! variables), and [`HookExpressions`] gives a fix's hook the same view while that fix is
//! borrowed (it passes itself; see [`crate::models::world::FixesView`]).

use crate::engine::state::State;
use crate::models::compute::Compute;
use crate::models::fix::{Expressions, Fix};
use crate::models::world::{FixesView, World};
use crate::output::thermo::Thermo;
use dmhs_parser::variables::Variables;
use dmhs_parser::EvalContext;

/// The evaluation context of expressions.
pub struct Eval<'a> {
    pub world: World<'a>,
    pub thermo: &'a Thermo,
    pub variables: &'a mut Variables,
    /// Seconds of the last run's loop (the `cpu` thermo keyword).
    pub cpu: f64,
}

impl EvalContext for Eval<'_> {
    fn variables(&mut self) -> &mut Variables {
        self.variables
    }
    fn thermo_keyword(&mut self, name: &str) -> Option<Result<f64, String>> {
        crate::output::thermo::keyword_value(&self.world, self.thermo, self.cpu, name)
    }
    fn compute_value(&mut self, id: &str, index: Option<usize>) -> Result<f64, String> {
        let c = self.world.compute(id).ok_or_else(|| format!("compute `{id}` does not exist"))?;
        match index {
            None => c.scalar(&self.world),
            Some(i) => {
                let v = c.vector(&self.world)?;
                v.get(i.wrapping_sub(1)).copied().ok_or_else(|| format!("compute `{id}` vector has {} values, index {i} is out of range", v.len()))
            }
        }
    }
    fn fix_value(&mut self, id: &str, index: Option<usize>) -> Result<f64, String> {
        let f = self.world.fix(id).ok_or_else(|| format!("fix `{id}` does not exist"))?;
        let state = self.world.state;
        match index {
            None => f.scalar(state).ok_or_else(|| format!("fix `{id}` ({}) has no global scalar", f.style())),
            Some(i) => f.vector(state, i).ok_or_else(|| format!("fix `{id}` ({}) has no global vector element {i}", f.style())),
        }
    }
    fn compute_array_value(&mut self, id: &str, i: usize, j: usize) -> Result<f64, String> {
        let c = self.world.compute(id).ok_or_else(|| format!("compute `{id}` does not exist"))?;
        let cols = c.array_cols().ok_or_else(|| format!("compute `{id}` ({}) has no global array", c.style()))?;
        let a = c.array(&self.world)?;
        let out = || format!("Variable formula compute array is accessed out-of-range: compute `{id}` has {} x {cols} values, element [{i}][{j}]", a.len());
        if j > cols {
            return Err(out());
        }
        a.get(i.wrapping_sub(1)).and_then(|r| r.get(j - 1)).copied().ok_or_else(out)
    }
    fn fix_array_value(&mut self, id: &str, i: usize, j: usize) -> Result<f64, String> {
        let f = self.world.fix(id).ok_or_else(|| format!("fix `{id}` does not exist"))?;
        let (rows, cols) = f.size_array().ok_or_else(|| format!("fix `{id}` ({}) has no global array", f.style()))?;
        let out = || format!("Variable formula fix array is accessed out-of-range: fix `{id}` has {rows} x {cols} values, element [{i}][{j}]");
        if j > cols {
            return Err(out());
        }
        // rows past the end are the fix's to judge (ave/time and ave/chunk give 0, as LAMMPS)
        f.array(self.world.state, i, j).ok_or_else(out)
    }
    fn global_values(&mut self, compute: bool, id: &str, column: Option<usize>) -> Result<Vec<f64>, String> {
        let mismatch = |kind: &str, style: &str| format!("{kind} '{id}' ({style}) in variable formula does not compute the requested property");
        if compute {
            let c = self.world.compute(id).ok_or_else(|| format!("Invalid compute ID '{id}' in variable formula"))?;
            match column {
                None => c.vector(&self.world).map_err(|_| mismatch("Compute", c.style())),
                Some(k) if c.array_cols().is_some() => {
                    if k > c.array_cols().unwrap_or(0) {
                        return Err("Variable formula compute array is accessed out-of-range".into());
                    }
                    Ok(c.array(&self.world)?.iter().map(|r| r[k - 1]).collect())
                }
                _ => Err(mismatch("Compute", c.style())),
            }
        } else {
            let f = self.world.fix(id).ok_or_else(|| format!("Invalid fix ID '{id}' in variable formula"))?;
            let state = self.world.state;
            let all = |n: usize, get: &dyn Fn(usize) -> Option<f64>| (1..=n).map(|i| get(i).unwrap_or(0.0)).collect();
            match (column, f.size_array()) {
                (None, _) if f.size_vector() > 0 || f.vector(state, 1).is_some() => Ok(all(f.size_vector(), &|i| f.vector(state, i))),
                (Some(k), Some((rows, cols))) => {
                    if k > cols {
                        return Err("Variable formula fix array is accessed out-of-range".into());
                    }
                    Ok(all(rows, &|i| f.array(state, i, k)))
                }
                _ => Err(mismatch("Fix", f.style())),
            }
        }
    }
    fn peratom_element(&mut self, compute: bool, id: &str, column: Option<usize>, atom: i64) -> Result<f64, String> {
        let (kind, cols) = if compute {
            let c = self.world.compute(id).ok_or_else(|| format!("Invalid compute ID '{id}' in variable formula"))?;
            ("Compute", c.peratom_cols())
        } else {
            let f = self.world.fix(id).ok_or_else(|| format!("Invalid fix ID '{id}' in variable formula"))?;
            ("Fix", f.peratom_cols())
        };
        let mismatch = || format!("{kind} '{id}' in variable formula does not compute the requested property");
        // one column: a per-atom vector; more: an array
        let name = match (cols, column) {
            (Some(1), None) => format!("{}_{id}", if compute { 'c' } else { 'f' }),
            (Some(n), Some(j)) if n > 1 => {
                if j > n {
                    return Err(format!("Variable formula {} array is accessed out-of-range", kind.to_lowercase()));
                }
                format!("{}_{id}[{j}]", if compute { 'c' } else { 'f' })
            }
            _ => return Err(mismatch()),
        };
        let r = crate::models::compute::PerAtomRef::parse(&name, &self.world).ok_or_else(mismatch)??;
        let values = r.values(&self.world)?;
        crate::models::compute::by_atom_id(self.world.state, atom, |i| r.get(&values, i))
    }
    fn atom_variable_element(&mut self, name: &str, atom: i64) -> Result<f64, String> {
        let w = self.world;
        let values = crate::models::atom_formula::atom_variable(name, &w, self)?;
        crate::models::compute::by_atom_id(w.state, atom, |i| values[i])
    }
    fn vector_variable(&mut self, name: &str) -> Result<Vec<f64>, String> {
        let w = self.world;
        crate::models::vector_formula::vector_variable(name, &w, self)
    }
    fn group_function(&mut self, name: &str, args: &[String]) -> Option<Result<f64, String>> {
        crate::models::compute::group_function(self.world.state, name, args)
    }
    fn atom_value(&mut self, keyword: &str, id: i64) -> Option<Result<f64, String>> {
        crate::models::compute::atom_value(self.world.state, keyword, id)
    }
    fn run_window(&mut self) -> Option<(i64, i64)> {
        self.world.state.run_window
    }
}

/// What a fix hook evaluates expressions with: everything but the state (which the hook holds
/// mutably and lends back for each evaluation) and the running fix (which passes itself).
pub struct HookExpressions<'a> {
    pub computes: &'a [Box<dyn Compute>],
    pub before: &'a [Box<dyn Fix>],
    pub after: &'a [Box<dyn Fix>],
    pub thermo: &'a Thermo,
    pub variables: &'a mut Variables,
    pub cpu: f64,
    /// The force field, for the computes that read it (bond/local, pair/local).
    pub bond: Option<&'a dyn crate::models::bonded::BondStyle>,
    pub pair: Option<&'a dyn crate::models::pair::PairStyle>,
}

impl Expressions for HookExpressions<'_> {
    fn equal(&mut self, state: &State, running: &dyn Fix, name: &str) -> Result<f64, String> {
        let fixes = FixesView { before: self.before, running: Some(running), after: self.after };
        let mut ev = Eval { world: World { state, computes: self.computes, fixes, bond: self.bond, pair: self.pair }, thermo: self.thermo, variables: self.variables, cpu: self.cpu };
        dmhs_parser::variables::compute_equal(&mut ev, name)
    }
    fn with_eval(&mut self, state: &State, running: &dyn Fix, work: &mut dyn FnMut(&World, &mut dyn EvalContext) -> Result<(), String>) -> Result<(), String> {
        let fixes = FixesView { before: self.before, running: Some(running), after: self.after };
        let world = World { state, computes: self.computes, fixes, bond: self.bond, pair: self.pair };
        let mut ev = Eval { world, thermo: self.thermo, variables: self.variables, cpu: self.cpu };
        work(&world, &mut ev)
    }
}
