//! `compute ID group cluster/atom Rc`, `fragment/atom [single yes|no]` and `aggregate/atom Rc`:
//! each atom of the group gets the smallest atom ID of its connected set (LAMMPS' computes of
//! the same names), 0 outside the group. The links between two atoms of the group: for a
//! cluster, a pair of the pair style's neighbour list closer than Rc (special pairs of weight 0
//! are not in the list, so not linked, as LAMMPS' documentation warns); for a fragment, a 1-2
//! special partner (a bond that is not broken), an atom with none getting 0 unless `single
//! yes`; for an aggregate, either a bond (any type but 0) or a pair closer than Rc. Periodic
//! images are the same atom. The sets are found by union by ID over the links (LAMMPS
//! iterates minimum IDs over ghost copies to the same fixed point).

use super::{Compute, PerAtom};
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Cluster,
    Fragment,
    Aggregate,
}

pub struct ComputeClusterAtom {
    id: String,
    groupbit: u32,
    kind: Kind,
    /// Rc of cluster/atom and aggregate/atom.
    cutoff: f64,
    /// fragment/atom `single yes`: an atom without bonds is a fragment of its own.
    single: bool,
}

impl ComputeClusterAtom {
    pub fn from_lammps(id: String, groupbit: u32, style: &str, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        let (kind, syntax) = match style {
            "cluster/atom" => (Kind::Cluster, "compute ID group cluster/atom cutoff"),
            "aggregate/atom" => (Kind::Aggregate, "compute ID group aggregate/atom cutoff"),
            _ => (Kind::Fragment, "compute ID group fragment/atom [single yes|no]"),
        };
        let mut a = Args::from_words(args, cmd.span, syntax);
        if kind != Kind::Cluster && !w.state.atoms.features.bonds {
            return Err(a.error_at(&cmd.name, format!("Compute {style} used when bonds are not allowed"), "no bonds in this atom style"));
        }
        let (mut cutoff, mut single) = (0.0, false);
        if kind == Kind::Fragment {
            while let Some(k) = a.peek() {
                a.skip(1);
                match k.text.as_str() {
                    "single" => single = a.logical("single")?,
                    _ => return Err(a.unknown_keyword(k, &["single"])),
                }
            }
        } else {
            cutoff = a.positive_f64("cutoff")?;
            a.finish()?;
        }
        Ok(ComputeClusterAtom { id, groupbit, kind, cutoff, single })
    }
}

/// The root of `i`'s set, halving the path on the way.
fn find(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

fn union(parent: &mut [usize], a: usize, b: usize) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        parent[ra.max(rb)] = ra.min(rb);
    }
}

impl Compute for ComputeClusterAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        match self.kind {
            Kind::Cluster => "cluster/atom",
            Kind::Fragment => "fragment/atom",
            Kind::Aggregate => "aggregate/atom",
        }
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn peratom_cols(&self) -> Option<usize> {
        Some(1)
    }
    fn peratom(&self, w: &World) -> Result<PerAtom, String> {
        let s = w.state;
        let at = &s.atoms;
        let n = at.nlocal;
        let g = self.groupbit;
        let map = at.tag_map();
        // every owned atom starts as a set of its own; a ghost stands for its owner
        let mut parent: Vec<usize> = (0..n).collect();
        let owner = |j: usize| if j < n { Some(j) } else { map.get(at.tag[j]) };
        if self.kind != Kind::Fragment {
            if s.neighbor.cutforce <= 0.0 || self.cutoff > s.neighbor.cutforce {
                return Err(format!("compute {} {}: Compute {} cutoff is longer than pairwise cutoff", self.style(), self.id, self.style()));
            }
            super::need_lists(s, self)?;
            let cutsq = self.cutoff * self.cutoff;
            super::group_pairs(s, g, g, |i, j, rsq, in_i, _, _| {
                if in_i && rsq < cutsq {
                    if let Some(o) = owner(j) {
                        union(&mut parent, i, o);
                    }
                }
            });
        }
        match self.kind {
            Kind::Cluster => {}
            Kind::Aggregate => {
                for b in &s.topo.bonds {
                    if b.typ == 0 {
                        continue;
                    }
                    if let (Some(i), Some(j)) = (map.get(b.atoms[0]), map.get(b.atoms[1])) {
                        if at.mask[i] & g != 0 && at.mask[j] & g != 0 {
                            union(&mut parent, i, j);
                        }
                    }
                }
            }
            Kind::Fragment => {
                let table = &s.special_table;
                for i in 0..n {
                    if at.mask[i] & g == 0 {
                        continue;
                    }
                    for (tag, level) in table.partners_of(at.tag[i]) {
                        if level != 1 {
                            continue;
                        }
                        if let Some(j) = map.get(tag) {
                            if at.mask[j] & g != 0 {
                                union(&mut parent, i, j);
                            }
                        }
                    }
                }
            }
        }
        // the smallest ID of each set
        let mut least = vec![i64::MAX; n];
        for i in (0..n).filter(|&i| at.mask[i] & g != 0) {
            let r = find(&mut parent, i);
            least[r] = least[r].min(at.tag[i]);
        }
        let mut data = vec![0.0; n];
        for i in 0..n {
            if at.mask[i] & g == 0 {
                continue;
            }
            if self.kind == Kind::Fragment && !self.single && !s.special_table.partners_of(at.tag[i]).any(|(_, level)| level == 1) {
                continue;
            }
            let r = find(&mut parent, i);
            data[i] = least[r] as f64;
        }
        Ok(PerAtom { cols: 1, data })
    }
}
