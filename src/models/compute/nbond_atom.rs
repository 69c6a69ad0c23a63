//! `compute ID group nbond/atom [bond/type T]` (LAMMPS BPM package): the number of intact
//! bonds of each atom, of every type or of type T only; bonds whose partner is gone (lost
//! atoms) are not counted; 0 outside the group.

use super::{Compute, PerAtom};
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

const SYNTAX: &str = "compute ID group nbond/atom [bond/type T]";

pub struct ComputeNBondAtom {
    id: String,
    groupbit: u32,
    /// Only bonds of this type (`bond/type`).
    btype: Option<usize>,
}

impl ComputeNBondAtom {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        if !w.state.atoms.features.bonds {
            return Err(a.error_at(&cmd.name, "compute nbond/atom requires an atom style with bonds", "no bonds").with_help("use atom_style bond, bpm/sphere, ... (or hybrid with one)"));
        }
        let mut btype = None;
        while let Some(kw) = a.peek() {
            a.skip(1);
            match kw.text.as_str() {
                // LAMMPS reads any integer here (a type that no bond has counts nothing)
                "bond/type" => btype = Some(a.i64("bond type")?),
                _ => return Err(a.unknown_keyword(kw, &["bond/type"])),
            }
        }
        let btype = btype.map(|t| usize::try_from(t).unwrap_or(usize::MAX));
        Ok(ComputeNBondAtom { id, groupbit, btype })
    }
}

impl Compute for ComputeNBondAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "nbond/atom"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn peratom_cols(&self) -> Option<usize> {
        Some(1)
    }
    fn peratom(&self, w: &World) -> Result<PerAtom, String> {
        let a = &w.state.atoms;
        let map = a.tag_map();
        // on the ranks of a distributed run, a partner owned by another rank is a ghost here
        let ghosts: std::collections::HashSet<i64> = if w.state.distributed.is_some() { a.tag[a.nlocal..a.nall()].iter().copied().collect() } else { Default::default() };
        let mut data = vec![0.0; a.nlocal];
        for b in &w.state.topo.bonds {
            if b.typ == 0 || b.off || self.btype.is_some_and(|t| t != b.typ) {
                continue;
            }
            let own = b.atoms.map(|t| map.get(t));
            if (0..2).all(|k| own[k].is_some() || ghosts.contains(&b.atoms[k])) {
                own.into_iter().flatten().for_each(|i| data[i] += 1.0);
            }
        }
        // after the count, as LAMMPS zeroes them after its reverse communication
        for (i, d) in data.iter_mut().enumerate() {
            if a.mask[i] & self.groupbit == 0 {
                *d = 0.0;
            }
        }
        Ok(PerAtom { cols: 1, data })
    }
}
