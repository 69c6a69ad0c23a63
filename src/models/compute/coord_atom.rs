//! `compute ID group coord/atom cutoff Rc [group group2-ID] [typeN ...]`: for each atom of the
//! group, the number of atoms of group2 (default all) closer than Rc, as LAMMPS' compute
//! coord/atom with the `cutoff` style: one column counting every type, or one column per type
//! range given (`2`, `1*3`, `*`). Counted over the pair style's neighbour list (LAMMPS'
//! occasional full list has the same pairs: Rc may not exceed the pair cutoff); excluded pairs
//! and special pairs of weight 0 are not counted, as in LAMMPS' lists. `orientorder` is refused.

use super::{Compute, PerAtom};
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

const SYNTAX: &str = "compute ID group coord/atom cutoff Rc [group group2-ID] [typeN ...]";

pub struct ComputeCoordAtom {
    id: String,
    groupbit: u32,
    cutoff: f64,
    /// group2's bit
    jgroupbit: u32,
    /// The inclusive type range of each column.
    types: Vec<(usize, usize)>,
}

impl ComputeCoordAtom {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let style = a.word("cstyle")?;
        if style.text == "orientorder" {
            return Err(a.error_at(style, "compute coord/atom orientorder is not supported by dmhs", "cutoff"));
        }
        if style.text != "cutoff" {
            return Err(a.error_at(style, format!("Invalid cstyle {} in compute coord/atom", style.text), "cutoff"));
        }
        let cutoff = a.positive_f64("Rc")?;
        let mut jgroupbit = w.state.groups.bit("all").unwrap_or(1);
        if a.peek().is_some_and(|k| k.text == "group") {
            a.skip(1);
            let g = a.word("group2-ID")?;
            jgroupbit = w.state.groups.bit(&g.text).ok_or_else(|| a.error_at(g, format!("Could not find compute coord/atom group2 ID {}", g.text), "an existing group"))?;
        }
        let ntypes = w.state.ntypes;
        let mut types = Vec::new();
        while a.peek().is_some() {
            types.push(a.type_range("typeN (a type range)", ntypes)?);
        }
        if types.is_empty() {
            types.push((1, ntypes));
        }
        Ok(ComputeCoordAtom { id, groupbit, cutoff, jgroupbit, types })
    }
}

impl Compute for ComputeCoordAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "coord/atom"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn peratom_cols(&self) -> Option<usize> {
        Some(self.types.len())
    }
    fn peratom(&self, w: &World) -> Result<PerAtom, String> {
        let s = w.state;
        if s.neighbor.cutforce <= 0.0 || self.cutoff > s.neighbor.cutforce {
            return Err(format!("compute coord/atom {}: Compute coord/atom cutoff is longer than pairwise cutoff", self.id));
        }
        super::need_lists(s, self)?;
        let at = &s.atoms;
        let cols = self.types.len();
        let cutsq = self.cutoff * self.cutoff;
        let mut count = vec![0.0; at.nlocal * cols];
        let mut add = |i: usize, jtype: usize| {
            for (c, &(lo, hi)) in self.types.iter().enumerate() {
                if (lo..=hi).contains(&jtype) {
                    count[i * cols + c] += 1.0;
                }
            }
        };
        super::group_pairs(s, self.groupbit, self.jgroupbit, |i, j, rsq, count_i, count_j, _| {
            if rsq < cutsq {
                if count_i {
                    add(i, at.typ[j]);
                }
                if count_j {
                    add(j, at.typ[i]);
                }
            }
        });
        Ok(PerAtom { cols, data: count })
    }
}
