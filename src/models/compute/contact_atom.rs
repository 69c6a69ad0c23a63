//! `compute ID group contact/atom [group2]`: for each atom of the group, the number of atoms
//! of group2 (default all) it touches, |x_i - x_j| <= r_i + r_j (LAMMPS' GRANULAR compute
//! contact/atom). Pairs are those of the pair style's neighbour list, which holds every pair
//! within the radii sum for granular pair styles (LAMMPS builds its own list to r_i + r_j +
//! skin); excluded pairs and special pairs of weight 0 are not counted, as in LAMMPS' list.

use super::{Compute, PerAtom};
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};

const SYNTAX: &str = "compute ID group contact/atom [group2-ID]";

pub struct ComputeContactAtom {
    id: String,
    groupbit: u32,
    /// group2's bit
    jgroupbit: u32,
}

impl ComputeContactAtom {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let jgroupbit = match a.peek() {
            Some(g) => {
                a.skip(1);
                w.state.groups.bit(&g.text).ok_or_else(|| a.error_at(g, format!("Compute contact/atom group2 ID {} does not exist", g.text), "unknown group"))?
            }
            None => w.state.groups.bit("all").unwrap_or(1),
        };
        a.finish()?;
        if !w.state.atoms.features.sphere {
            return Err(Diagnostic::at(cmd.span, "Compute contact/atom requires atom style sphere", "no radii"));
        }
        Ok(ComputeContactAtom { id, groupbit, jgroupbit })
    }
}

impl Compute for ComputeContactAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "contact/atom"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn peratom_cols(&self) -> Option<usize> {
        Some(1)
    }
    fn peratom(&self, w: &World) -> Result<PerAtom, String> {
        let s = w.state;
        if s.neighbor.cutforce <= 0.0 {
            return Err(format!("compute contact/atom {}: Compute contact/atom requires a pair style be defined", self.id));
        }
        super::need_lists(s, self)?;
        let at = &s.atoms;
        let mut contact = vec![0.0; at.nlocal];
        super::group_pairs(s, self.groupbit, self.jgroupbit, |i, j, rsq, count_i, count_j, _| {
            let radsum = at.radius[i] + at.radius[j];
            if rsq <= radsum * radsum {
                if count_i {
                    contact[i] += 1.0;
                }
                if count_j {
                    contact[j] += 1.0;
                }
            }
        });
        Ok(PerAtom { cols: 1, data: contact })
    }
}
