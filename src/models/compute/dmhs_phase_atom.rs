//! `compute ID group dmhs/phase/atom` — per-atom state of the phase-change model, 4 columns:
//! c_ID[1] temperature T (the `dmhs/T` field of fix dmhs/phase, else esph/cv),
//! c_ID[2] label (1 solid, 0 liquid; 0 without fix dmhs/phase),
//! c_ID[3] melt fraction by enthalpy (fix dmhs/phase group: clamp((e - e_sol)/L, 0, 1), e = esph/m;
//!         else 1 - label),
//! c_ID[4] SPH weight phi of the blend (the `dmhs/phi` field, else 1 - label).
//! Atoms outside the compute's group get 0 in every column.

use super::{expect_no_args, Compute, PerAtom};
use crate::engine::fields::{LIQUID_WEIGHT, PHASE, TEMPERATURE};
use crate::models::pair::dmhs_heatconduction::temperature;
use crate::models::world::World;
use dmhs_parser::{Command, DResult, Diagnostic, Word};

pub struct ComputeDmhsPhaseAtom {
    id: String,
    groupbit: u32,
}

impl ComputeDmhsPhaseAtom {
    pub fn from_lammps(id: String, groupbit: u32, style: &Word, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        expect_no_args(args, cmd, "compute ID group dmhs/phase/atom")?;
        if !w.state.atoms.features.sph {
            return Err(Diagnostic::at(style.span, "compute dmhs/phase/atom needs an atom style with SPH attributes", "atom style has no esph"));
        }
        Ok(ComputeDmhsPhaseAtom { id, groupbit })
    }
}

impl Compute for ComputeDmhsPhaseAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "dmhs/phase/atom"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn peratom_cols(&self) -> Option<usize> {
        Some(4)
    }
    fn peratom(&self, w: &World) -> Result<PerAtom, String> {
        let a = &w.state.atoms;
        let (kt, kl, kp) = (a.field(TEMPERATURE), a.field(PHASE), a.field(LIQUID_WEIGHT));
        // the EOS of the phase fix, for the melt fraction
        let eos = w.fixes.iter().find_map(|f| f.phase_eos().map(|e| (e, f.groupbit())));
        let mut data = Vec::with_capacity(4 * a.nlocal);
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                data.extend_from_slice(&[0.0; 4]);
                continue;
            }
            let label = kl.map(|k| a.extra[k].data[i]).unwrap_or(0.0);
            let melt = match eos {
                Some((e, bit)) if a.mask[i] & bit != 0 => e.melt_fraction(a.esph[i] / w.state.mass(i)),
                _ => 1.0 - label,
            };
            let phi = kp.map(|k| a.extra[k].data[i]).unwrap_or(1.0 - label);
            data.extend_from_slice(&[temperature(a, kt, i), label, melt, phi]);
        }
        Ok(PerAtom { cols: 4, data })
    }
}
