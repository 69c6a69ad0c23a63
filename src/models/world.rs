//! The read-only view that computes, fix values and expressions evaluate against: the state,
//! every compute and every fix (and the bond style). While a fix's hook runs, that fix is borrowed mutably; it
//! passes itself (`running`) when it evaluates an expression, so the view still shows every fix
//! in definition order, as LAMMPS does.

use crate::engine::state::State;
use crate::models::compute::Compute;
use crate::models::fix::Fix;
use crate::models::bonded::BondStyle;

/// Every fix, in definition order: those before the running one, the running one (if its
/// hook is evaluating an expression), and those after it.
#[derive(Clone, Copy)]
pub struct FixesView<'a> {
    pub before: &'a [Box<dyn Fix>],
    pub running: Option<&'a dyn Fix>,
    pub after: &'a [Box<dyn Fix>],
}

impl<'a> FixesView<'a> {
    /// All fixes (no hook running).
    pub fn all(fixes: &'a [Box<dyn Fix>]) -> FixesView<'a> {
        FixesView { before: fixes, running: None, after: &[] }
    }
    pub fn iter(&self) -> impl Iterator<Item = &'a dyn Fix> + '_ {
        self.before.iter().map(|f| f.as_ref()).chain(self.running).chain(self.after.iter().map(|f| f.as_ref()))
    }
    pub fn find(&self, id: &str) -> Option<&'a dyn Fix> {
        self.iter().find(|f| f.id() == id)
    }
}

#[derive(Clone, Copy)]
pub struct World<'a> {
    pub state: &'a State,
    pub computes: &'a [Box<dyn Compute>],
    pub fixes: FixesView<'a>,
    /// The bond style (compute bond/local's energies and forces); None where a view is made
    /// without the force field (while a fix is built, inside the expressions of a run's setup).
    pub bond: Option<&'a dyn BondStyle>,
    /// The pair style (compute pair/local's single); None where the view is made without the
    /// force field, as for `bond`.
    pub pair: Option<&'a dyn crate::models::pair::PairStyle>,
}

impl<'a> World<'a> {
    pub fn compute(&self, id: &str) -> Option<&'a dyn Compute> {
        self.computes.iter().find(|c| c.id() == id).map(|c| c.as_ref())
    }
    pub fn fix(&self, id: &str) -> Option<&'a dyn Fix> {
        self.fixes.find(id)
    }
    /// The energy of the fixes under `fix_modify energy yes`, summed in definition order
    /// (LAMMPS' Modify::energy_global); None when no fix has it on.
    pub fn fix_energy(&self) -> Option<f64> {
        let mut on = self.fixes.iter().filter(|f| f.thermo_tally().is_some_and(|t| t.energy)).peekable();
        on.peek()?;
        Some(on.fold(0.0, |e, f| e + f.scalar(self.state).unwrap_or(0.0)))
    }
    /// The energy the thermostats and barostats exchanged with their reservoirs (LAMMPS'
    /// Modify::energy_couple: the scalars of the fixes with ecouple_flag, in definition order).
    pub fn ecouple(&self) -> f64 {
        self.fixes.iter().filter(|f| f.couples_energy()).fold(0.0, |e, f| e + f.scalar(self.state).unwrap_or(0.0))
    }
    /// thermo's pe (LAMMPS' compute thermo_pe): the force field's energy, then the fixes'.
    pub fn pe(&self) -> f64 {
        let e = self.state.potential_energy();
        self.fix_energy().map_or(e, |f| e + f)
    }
    /// The virial of compute pressure: the force field's, then each fix's under `fix_modify
    /// virial yes`, in definition order (LAMMPS' ComputePressure::virial_compute); a fix's over
    /// every rank of a distributed run (each tallies its own atoms').
    pub fn virial(&self) -> [f64; 6] {
        let mut v = self.state.energies.virial;
        for t in self.fixes.iter().filter_map(|f| f.thermo_tally()).filter(|t| t.virial_on) {
            let mut fv = t.virial;
            self.state.sum_ranks(&mut fv);
            for k in 0..6 {
                v[k] += fv[k];
            }
        }
        v
    }
    /// Degrees of freedom that fixes remove from atoms of a group (for temperatures).
    pub fn fix_dof(&self, bit: u32) -> f64 {
        self.fixes.iter().map(|f| f.dof_removed(self.state, bit)).sum()
    }
}
