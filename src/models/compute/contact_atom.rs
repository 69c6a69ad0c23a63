//! `compute ID group contact/atom [group2]`: for each atom of the group, the number of atoms
//! of group2 (default all) it touches, |x_i - x_j| <= r_i + r_j (LAMMPS' GRANULAR compute
//! contact/atom). Pairs are those of the pair style's neighbour list, which holds every pair
//! within the radii sum for granular pair styles (LAMMPS builds its own list to r_i + r_j +
//! skin); excluded pairs and special pairs of weight 0 are not counted, as in LAMMPS' list.

use super::{Compute, PerAtom};
use crate::engine::neighbor::{special_level, NEIGH_MASK};
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
        if !s.lists_valid {
            return Err(format!("compute contact/atom {} needs neighbour lists: it can be read only during or after a run", self.id));
        }
        let at = &s.atoms;
        let (lj, coul) = (s.special_bonds.lj, s.special_bonds.coul);
        let mut contact = vec![0.0; at.nlocal];
        // a pair of owned atoms is listed once and counts for both; a pair with a ghost is
        // listed by each owned end, which counts for itself
        for chunk in &s.neighbor.list.chunks {
            for i in chunk.start..chunk.end {
                let (mi, xi, ri) = (at.mask[i], at.x[i], at.radius[i]);
                if mi & (self.groupbit | self.jgroupbit) == 0 {
                    continue;
                }
                for &e in chunk.neighbors(i) {
                    let level = special_level(e);
                    if lj[level] == 0.0 && coul[level] == 0.0 {
                        continue;
                    }
                    let j = (e & NEIGH_MASK) as usize;
                    let mj = at.mask[j];
                    let count_i = mi & self.groupbit != 0 && mj & self.jgroupbit != 0;
                    let count_j = j < at.nlocal && mj & self.groupbit != 0 && mi & self.jgroupbit != 0;
                    if !count_i && !count_j {
                        continue;
                    }
                    let (dx, dy, dz) = (xi[0] - at.x[j][0], xi[1] - at.x[j][1], xi[2] - at.x[j][2]);
                    let radsum = ri + at.radius[j];
                    if dx * dx + dy * dy + dz * dz <= radsum * radsum {
                        if count_i {
                            contact[i] += 1.0;
                        }
                        if count_j {
                            contact[j] += 1.0;
                        }
                    }
                }
            }
        }
        Ok(PerAtom { cols: 1, data: contact })
    }
}
