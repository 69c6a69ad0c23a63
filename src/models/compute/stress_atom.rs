//! `compute ID group stress/atom temp-ID|NULL [ke] [pair] [bond] [angle] [dihedral] [improper]
//! [kspace] [fix] [virial]`: each atom's stress times volume, -(m v v + virial share) nktv2p,
//! six columns xx yy zz xy xz yz, as LAMMPS' compute stress/atom: the virial shares of pairs,
//! bonds, angles and dihedrals summed in that order, then the kinetic term, then the sign and
//! units; 0 outside the group. Minus the sum of the first three columns over all atoms,
//! divided by 3V (2V in 2d), is the pressure. With a temp-ID of a bias compute (temp/partial,
//! temp/com, temp/region) the kinetic term is that of the velocities less the compute's bias, as
//! LAMMPS' remove_bias_all around it; a plain compute temp gives NULL's. The `fix` term (also in `virial` and the
//! default) is the per-atom virial of fixes whose virial counts (`fix_modify virial yes`):
//! dmhs does not tally those per atom, so such a fix makes the compute an error rather than a
//! silently smaller stress; with no such fix the term is zero, as in LAMMPS.

use super::pe_atom::{tallies, terms};
use super::{Compute, PerAtom};
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "compute ID group stress/atom temp-ID|NULL [ke] [pair] [bond] [angle] [dihedral] [improper] [kspace] [fix] [virial]";

pub struct ComputeStressAtom {
    id: String,
    groupbit: u32,
    /// Virial shares of pair, bond, angle, dihedral.
    terms: [bool; 4],
    ke: bool,
    /// The temperature compute whose velocity bias the kinetic term leaves out.
    temp_id: Option<String>,
    /// The fixes' per-atom virials were asked for (`fix`, `virial` or no keyword).
    fix: bool,
}

impl ComputeStressAtom {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let tw = a.word("temperature compute ID or NULL")?;
        if tw.text != "NULL" {
            match w.compute(&tw.text) {
                None => return Err(a.error_at(tw, format!("compute `{}` for compute stress/atom does not exist", tw.text), "unknown compute")),
                Some(c) if !c.style().starts_with("temp") => return Err(a.error_at(tw, format!("compute stress/atom: compute `{}` ({}) does not compute a temperature", tw.text, c.style()), "not a temperature")),
                _ => {}
            }
        }
        let any = !a.is_empty();
        let fix_named = a.remaining().iter().any(|w| w.text == "fix");
        let (mut terms, others) = terms(&mut a, &["ke", "virial"])?;
        let ke = !any || others.contains(&0);
        if others.contains(&1) {
            terms = [true; 4];
        }
        let fix = !any || fix_named || others.contains(&1);
        let temp_id = (tw.text != "NULL").then(|| tw.text.clone());
        Ok(ComputeStressAtom { id, groupbit, terms, ke, fix, temp_id })
    }
}

impl Compute for ComputeStressAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "stress/atom"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn uses_peratom_tally(&self) -> bool {
        true
    }
    fn peratom_cols(&self) -> Option<usize> {
        Some(6)
    }
    fn peratom(&self, w: &World) -> Result<PerAtom, String> {
        let s = w.state;
        if self.fix {
            if let Some(f) = w.fixes.iter().find(|f| f.thermo_tally().is_some_and(|t| t.virial_on)) {
                return Err(format!(
                    "compute {} (stress/atom): fix {} ({}) adds its virial to the pressure (fix_modify virial yes), but dmhs does not tally fix virials per atom; leave `fix` out of the compute's terms (e.g. `pair bond angle dihedral ke`) or the fix's virial off",
                    self.id, f.id(), f.style()
                ));
            }
        }
        let t = tallies(s, &self.id, "stress/atom")?;
        let a = &s.atoms;
        let (mvv2e, nktv2p) = (s.units.mvv2e, -s.units.nktv2p);
        let bias = match self.temp_id.as_deref().filter(|_| self.ke) {
            Some(tid) => {
                let c = w.compute(tid).ok_or_else(|| format!("compute {} (stress/atom): temperature compute `{tid}` does not exist", self.id))?;
                match c.temp_spec() {
                    Some(spec) => spec.field(s, self.groupbit)?,
                    None => None,
                }
            }
            None => None,
        };
        let mut data = vec![0.0; a.nlocal * 6];
        for (i, st) in data.chunks_exact_mut(6).enumerate() {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            for k in (0..4).filter(|&k| self.terms[k]) {
                st.iter_mut().zip(&t.virial[k][i]).for_each(|(s, v)| *s += v);
            }
            if self.ke {
                let onemass = mvv2e * s.mass(i);
                let mut v = a.v[i];
                if let Some(b) = &bias {
                    (0..3).for_each(|k| v[k] -= b[i][k]);
                }
                for (m, (p, q)) in [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)].into_iter().enumerate() {
                    st[m] += onemass * v[p] * v[q];
                }
            }
            st.iter_mut().for_each(|x| *x *= nktv2p);
        }
        Ok(PerAtom { cols: 6, data })
    }
}
