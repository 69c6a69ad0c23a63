//! `compute ID group pe/atom [pair] [bond] [angle] [dihedral] [improper] [kspace] [fix]`:
//! each atom's share of the potential energy (LAMMPS' compute pe/atom: pairs half to each
//! atom, bonds 1/2, angles 1/3, dihedrals 1/4), summed pair, bond, angle, dihedral in that
//! order; 0 outside the group. Its sum over all atoms is the potential energy. dmhs has no
//! impropers, kspace or fixes with per-atom energies: those keywords add nothing.

use super::{Compute, PerAtom};
use crate::engine::state::State;
use crate::engine::tally::PerAtomTally;
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "compute ID group pe/atom [pair] [bond] [angle] [dihedral] [improper] [kspace] [fix]";

pub struct ComputePeAtom {
    id: String,
    groupbit: u32,
    /// pair, bond, angle, dihedral
    terms: [bool; 4],
}

/// Read `pair bond angle dihedral improper kspace fix` keywords (none: all), as pe/atom and
/// stress/atom do; `extra` are more keywords the caller handles (index in `extra` + 7).
pub fn terms(a: &mut Args, extra: &[&str]) -> DResult<([bool; 4], Vec<usize>)> {
    let mut names = vec!["pair", "bond", "angle", "dihedral", "improper", "kspace", "fix"];
    names.extend_from_slice(extra);
    if a.is_empty() {
        return Ok(([true; 4], Vec::new()));
    }
    let (mut t, mut others) = ([false; 4], Vec::new());
    while !a.is_empty() {
        match a.choice("energy term", &names)? {
            k @ 0..=3 => t[k] = true,
            4..=6 => {}
            k => others.push(k - 7),
        }
    }
    Ok((t, others))
}

/// The per-atom tallies of the current step, or why there are none.
pub fn tallies<'a>(state: &'a State, id: &str, style: &str) -> Result<&'a PerAtomTally, String> {
    match &state.peratom {
        Some(t) if t.step == state.step && t.energy[0].len() == state.atoms.nlocal => Ok(t),
        _ => match &state.peratom_missing {
            Some((step, why)) if *step == state.step => Err(format!("compute {id} ({style}): {why}")),
            _ => Err(format!("compute {id} ({style}): per-atom energies and virials are tallied on the steps of thermo output, dumps and averaging-fix samples; step {} is none of them", state.step)),
        },
    }
}

impl ComputePeAtom {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let (terms, _) = terms(&mut a, &[])?;
        Ok(ComputePeAtom { id, groupbit, terms })
    }
}

impl Compute for ComputePeAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "pe/atom"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn uses_peratom_tally(&self) -> bool {
        true
    }
    fn peratom_cols(&self) -> Option<usize> {
        Some(1)
    }
    fn peratom(&self, w: &World) -> Result<PerAtom, String> {
        let t = tallies(w.state, &self.id, "pe/atom")?;
        let a = &w.state.atoms;
        let data = (0..a.nlocal)
            .map(|i| {
                let mut e = 0.0;
                for k in (0..4).filter(|&k| self.terms[k]) {
                    e += t.energy[k][i];
                }
                if a.mask[i] & self.groupbit == 0 { 0.0 } else { e }
            })
            .collect();
        Ok(PerAtom { cols: 1, data })
    }
}
