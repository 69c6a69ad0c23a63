//! `dmhs check`: what a deck sets up, without running it.

use crate::sim::run::RunOptions;
use crate::sim::{SetupError, Simulation};

impl Simulation {
    /// In check mode, `run` validates that the run could start, and records it.
    pub fn check_run(&mut self, opts: &RunOptions) -> Result<(), SetupError> {
        self.init_run()?;
        let n = if opts.upto { opts.nsteps - self.state.step } else { opts.nsteps };
        self.out.print(&format!("check: run {} steps from step {} (not run)", n, self.state.step));
        // the forces of the current state give the force-based limit
        let known = self.setup(opts.pre).is_ok();
        let (text, warnings) = crate::sim::stability::report(self, &crate::sim::stability::limits(self, known));
        self.out.print(&text);
        for w in warnings {
            self.out.print(&format!("WARNING: {w}"));
        }
        self.checked_runs += 1;
        Ok(())
    }

    /// A human-readable summary of the simulation set-up.
    pub fn describe(&self) -> String {
        let mut s = String::new();
        s += &format!("units {}, dimension {}, atom_style {}\n", self.state.units.name(), self.state.dimension, self.state.atom_style.join(" "));
        match &self.state.domain {
            Some(d) => {
                let b: Vec<String> = (0..3).map(|k| format!("{}{}", d.boundary[k][0].letter(), d.boundary[k][1].letter())).collect();
                s += &format!("box: ({}, {}, {}) to ({}, {}, {}), boundary {}\n", d.lo[0], d.lo[1], d.lo[2], d.hi[0], d.hi[1], d.hi[2], b.join(" "));
            }
            None => s += "box: not defined\n",
        }
        s += &format!("atoms: {} of {} types", self.state.atoms.nlocal, self.state.ntypes);
        let t = &self.state.topo;
        if !t.is_empty() {
            s += &format!("; {} bonds, {} angles, {} dihedrals", t.bonds.len(), t.angles.len(), t.dihedrals.len());
        }
        s += "\n";
        let mut counts = vec![0usize; self.state.ntypes + 1];
        for &t in &self.state.atoms.typ[..self.state.atoms.nlocal] {
            if let Some(c) = counts.get_mut(t) {
                *c += 1;
            }
        }
        for k in 1..=self.state.ntypes {
            let count = counts[k];
            let m = if self.state.atoms.features.per_atom_mass() { "per-atom".to_string() } else if self.state.mass_set[k] { format!("{}", self.state.type_mass[k]) } else { "NOT SET".to_string() };
            s += &format!("  type {k}: {count} atoms, mass {m}\n");
        }
        let groups: Vec<String> = self.state.groups.names().map(|(k, n)| format!("{n} ({})", self.state.group_count(1 << k))).collect();
        s += &format!("groups: {}\n", groups.join(", "));
        s += "models:\n";
        match &self.pair {
            Some(p) => s += &format!("  pair {}\n", p.describe().replace('\n', "\n  ")),
            None => s += "  pair: none\n",
        }
        if let Some(b) = &self.bond_style {
            s += &format!("  bond {} ({} types)\n", b.name(), t.nbondtypes);
        }
        if let Some(b) = &self.angle_style {
            s += &format!("  angle {} ({} types)\n", b.name(), t.nangletypes);
        }
        if let Some(b) = &self.dihedral_style {
            s += &format!("  dihedral {} ({} types)\n", b.name(), t.ndihedraltypes);
        }
        let sb = &self.state.special_bonds;
        s += &format!("  special_bonds lj {} {} {} coul {} {} {}\n", sb.lj[1], sb.lj[2], sb.lj[3], sb.coul[1], sb.coul[2], sb.coul[3]);
        s += &format!("neighbor: skin {}, every {} delay {} check {}\n", self.state.neigh_settings.skin, self.state.neigh_settings.every, self.state.neigh_settings.delay, if self.state.neigh_settings.check { "yes" } else { "no" });
        s += &format!("timestep: {}\n", self.state.dt);
        s += "fixes:\n";
        for f in &self.fixes {
            let g = self.state.groups.names().find(|(k, _)| 1u32 << k == f.groupbit()).map(|(_, n)| n).unwrap_or("?");
            s += &format!("  {} (group {g})\n", f.describe());
        }
        s += "computes:\n";
        for c in self.computes.iter().skip(3) {
            s += &format!("  {}\n", c.describe());
        }
        s += "outputs:\n";
        let every = match &self.thermo.every_var {
            Some(v) => format!("at the steps variable {v} gives"),
            None => format!("every {} steps", self.thermo.every),
        };
        s += &format!("  thermo {every}: {}\n", self.thermo.columns.iter().map(|c| c.label.as_str()).collect::<Vec<_>>().join(" "));
        for d in &self.dumps {
            let every = match &d.every_var {
                Some(v) => format!("at the steps variable {v} gives"),
                None => format!("every {}", d.every),
            };
            s += &format!("  dump {} {} {every} -> {}\n", d.id, d.style, d.path.display());
        }
        s
    }
}
