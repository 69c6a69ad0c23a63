//! `compute ID group property/local attribute ... [cutoff type|radius]`: one row per pair in
//! contact range, bond, angle or dihedral whose atoms are all in the group (LAMMPS' compute
//! property/local), read by `dump local` and `compute reduce`. Attributes of one kind only:
//! pairs `patom1 patom2 ptype1 ptype2` (the pairs within the pair style's cutoff of their
//! types, or with `cutoff radius` the finite-size pairs that overlap, rsq < (ri + rj)^2),
//! bonds `batom1 batom2 btype`, angles `aatom1 aatom2 aatom3 atype`, dihedrals `datom1 ..
//! datom4 dtype`. Interactions turned off by delete_bonds are listed with their type negated,
//! as LAMMPS; broken bonds (type 0) are not.
//!
//! Bonds, angles and dihedrals come in LAMMPS' order (the atom that stores each, in LAMMPS'
//! local order, then its list order). Pairs come once each, in dmhs' list order: LAMMPS lists
//! them from a half list of its own binning (which atom is `patom1` and the row order depend on
//! it), so the same set of pairs in another order and orientation.

use super::Compute;
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

const SYNTAX: &str = "compute ID group property/local attribute ... [cutoff type|radius]  (patom1 patom2 ptype1 ptype2 | batom1 batom2 btype | aatom1 aatom2 aatom3 atype | datom1 datom2 datom3 datom4 dtype)";

/// What the rows are: one kind per compute.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Pair,
    Bond,
    Angle,
    Dihedral,
}

/// Which atom's ID (its place in the pair or interaction, from 0) or which type (a pair's
/// first or second atom's; an interaction's own is 0).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Attr {
    Atom(usize),
    Type(usize),
}

const ATTRS: [(&str, Kind, Attr); 16] = [
    ("patom1", Kind::Pair, Attr::Atom(0)),
    ("patom2", Kind::Pair, Attr::Atom(1)),
    ("ptype1", Kind::Pair, Attr::Type(0)),
    ("ptype2", Kind::Pair, Attr::Type(1)),
    ("batom1", Kind::Bond, Attr::Atom(0)),
    ("batom2", Kind::Bond, Attr::Atom(1)),
    ("btype", Kind::Bond, Attr::Type(0)),
    ("aatom1", Kind::Angle, Attr::Atom(0)),
    ("aatom2", Kind::Angle, Attr::Atom(1)),
    ("aatom3", Kind::Angle, Attr::Atom(2)),
    ("atype", Kind::Angle, Attr::Type(0)),
    ("datom1", Kind::Dihedral, Attr::Atom(0)),
    ("datom2", Kind::Dihedral, Attr::Atom(1)),
    ("datom3", Kind::Dihedral, Attr::Atom(2)),
    ("datom4", Kind::Dihedral, Attr::Atom(3)),
    ("dtype", Kind::Dihedral, Attr::Type(0)),
];

pub struct ComputePropertyLocal {
    id: String,
    groupbit: u32,
    kind: Kind,
    /// Indices into [`ATTRS`].
    attrs: Vec<usize>,
    /// `cutoff radius`: pairs that overlap, not within the type cutoff.
    radius_cut: bool,
}

/// One row before the attributes are picked: the atoms' IDs and types (pairs: types of both
/// atoms; interactions: the interaction's type, negative when turned off).
struct Row {
    ids: [i64; 4],
    types: [i64; 2],
}

impl ComputePropertyLocal {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let mut kind: Option<Kind> = None;
        let mut attrs = Vec::new();
        let mut radius_cut = false;
        while let Some(word) = a.peek() {
            a.skip(1);
            let t = word.text.as_str();
            if t == "cutoff" {
                radius_cut = a.choice("cutoff", &["type", "radius"])? == 1;
                continue;
            }
            if matches!(t, "natom1" | "natom2" | "ntype1" | "ntype2") {
                return Err(a.error_at(word, format!("compute property/local {t}: the neighbour-list pairs (LAMMPS builds a list at cutoff + skin for it) are not supported; patom1/patom2/ptype1/ptype2 list the pairs within the cutoff"), "not supported"));
            }
            if matches!(t, "iatom1" | "iatom2" | "iatom3" | "iatom4" | "itype") {
                return Err(a.error_at(word, "Compute property/local for property that isn't allocated: dmhs has no impropers", "no impropers"));
            }
            let Some(k) = ATTRS.iter().position(|(n, _, _)| *n == t) else {
                let names: Vec<&str> = ATTRS.iter().map(|(n, _, _)| *n).collect();
                let mut d = a.error_at(word, format!("Invalid keyword `{t}` in compute property/local command"), "expected an attribute or `cutoff`");
                if let Some(h) = dmhs_parser::suggest::did_you_mean_help(t, names) {
                    d = d.with_help(h);
                }
                return Err(d);
            };
            let this = ATTRS[k].1;
            if kind.is_some_and(|was| was != this) {
                return Err(a.error_at(word, "Compute property/local cannot use these inputs together (one kind: pairs, bonds, angles or dihedrals)", "another kind"));
            }
            kind = Some(this);
            attrs.push(k);
        }
        let Some(kind) = kind else {
            return Err(a.missing("an attribute (patom1, batom1, aatom1, datom1, ...)"));
        };
        let f = &w.state.atoms.features;
        let allocated = match kind {
            Kind::Pair => true,
            Kind::Bond => f.bonds,
            Kind::Angle => f.angles,
            Kind::Dihedral => f.dihedrals,
        };
        if !allocated {
            return Err(a.error_at(&cmd.name, "Compute property/local for property that isn't allocated (the atom style has none)", "not in this atom style"));
        }
        if radius_cut && !f.sphere {
            return Err(a.error_at(&cmd.name, "Compute property/local with cutoff radius requires atom attribute radius", "needs atom_style sphere"));
        }
        Ok(ComputePropertyLocal { id, groupbit, kind, attrs, radius_cut })
    }

    /// The pairs of group atoms within the force cutoff of their types (or overlapping), each
    /// once, special pairs of weight 0 left out ([`super::group_pairs_once`]).
    fn pairs(&self, w: &World) -> Result<Vec<Row>, String> {
        let s = w.state;
        let a = &s.atoms;
        let list = &s.neighbor.list;
        if s.neighbor.cutforce <= 0.0 {
            return Err(format!("compute property/local {}: No pair style is defined for compute property/local", self.id));
        }
        super::need_lists(s, self)?;
        let stride = list.ntypes + 1;
        let mut rows = Vec::new();
        super::group_pairs_once(s, self.groupbit, |i, j, rsq, _| {
            let (ti, tj) = (a.typ[i], a.typ[j]);
            let inside = if self.radius_cut {
                let radsum = a.radius[i] + a.radius[j];
                rsq < radsum * radsum
            } else {
                rsq < list.cutsq[ti * stride + tj]
            };
            if inside {
                rows.push(Row { ids: [a.tag[i], a.tag[j], 0, 0], types: [ti as i64, tj as i64] });
            }
        });
        Ok(rows)
    }

    /// The angles or dihedrals of group atoms, listed by their second atom in LAMMPS' local
    /// order, each atom's in record order.
    fn interactions(&self, w: &World) -> Vec<Row> {
        let s = w.state;
        let a = &s.atoms;
        let map = a.tag_map();
        let in_group = |tag: i64| map.get(tag).is_some_and(|k| a.mask[k] & self.groupbit != 0);
        let items: Vec<(usize, &[i64], bool)> = match self.kind {
            Kind::Angle => s.topo.angles.iter().map(|t| (t.typ, &t.atoms[..], t.off)).collect(),
            _ => s.topo.dihedrals.iter().map(|t| (t.typ, &t.atoms[..], t.off)).collect(),
        };
        // each owned atom's interactions (it is their second atom), in record order
        let mut by_atom: Vec<Vec<usize>> = vec![Vec::new(); a.nlocal];
        for (rec, (typ, atoms, _)) in items.iter().enumerate() {
            if *typ == 0 {
                continue;
            }
            if let Some(k) = map.get(atoms[1]).filter(|&k| k < a.nlocal) {
                by_atom[k].push(rec);
            }
        }
        let mut rows = Vec::new();
        for &k in s.lammps_order.indices(a.nlocal).iter() {
            if a.mask[k] & self.groupbit == 0 {
                continue;
            }
            for &rec in &by_atom[k] {
                let (typ, atoms, off) = items[rec];
                if !atoms.iter().all(|&t| in_group(t)) {
                    continue;
                }
                let mut ids = [0; 4];
                ids[..atoms.len()].copy_from_slice(atoms);
                let t = if off { -(typ as i64) } else { typ as i64 };
                rows.push(Row { ids, types: [t, t] });
            }
        }
        rows
    }
}

impl Compute for ComputePropertyLocal {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "property/local"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn local_cols(&self) -> Option<usize> {
        Some(if self.attrs.len() == 1 { 0 } else { self.attrs.len() })
    }
    fn local(&self, w: &World, _ev: Option<&mut dyn dmhs_parser::EvalContext>) -> Result<Vec<Vec<f64>>, String> {
        let rows = match self.kind {
            Kind::Pair => self.pairs(w)?,
            Kind::Bond => {
                let s = w.state;
                let a = &s.atoms;
                super::bond_local::listed_bonds(w, self.groupbit)
                    .into_iter()
                    .map(|(i, j, rec)| {
                        let b = &s.topo.bonds[rec];
                        let t = if b.off { -(b.typ as i64) } else { b.typ as i64 };
                        Row { ids: [a.tag[i], a.tag[j], 0, 0], types: [t, t] }
                    })
                    .collect()
            }
            Kind::Angle | Kind::Dihedral => self.interactions(w),
        };
        Ok(rows
            .iter()
            .map(|r| {
                self.attrs
                    .iter()
                    .map(|&k| match ATTRS[k].2 {
                        Attr::Atom(m) => r.ids[m] as f64,
                        Attr::Type(m) => r.types[m] as f64,
                    })
                    .collect()
            })
            .collect())
    }
}
