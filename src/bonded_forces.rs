//! The bonded pass: bonds, angles and dihedrals between owned atoms, each partner taken at
//! its periodic image closest to the atom LAMMPS stores the interaction on (atom 1 of a bond,
//! atom 2 of an angle or dihedral), with the image's coordinate computed as LAMMPS' ghost
//! copy is (`x + shift * L`), so displacements match LAMMPS bit for bit.

use crate::bonded::{angle_virial, bond_virial, dihedral_virial};
use crate::sim::{RunError, Simulation};
use crate::special::{build_special, Topology as SpecialTopology};

/// One interaction: local indices of its atoms, the periodic shift of each (relative to the
/// reference atom), and its type.
#[derive(Clone, Debug)]
pub struct Entry<const N: usize> {
    pub atoms: [u32; N],
    pub shift: [[i8; 3]; N],
    pub typ: usize,
}

#[derive(Clone, Debug, Default)]
pub struct BondedLists {
    pub bonds: Vec<Entry<2>>,
    pub angles: Vec<Entry<3>>,
    pub dihedrals: Vec<Entry<4>>,
}

/// Energies and virial of the bonded pass.
#[derive(Clone, Copy, Debug, Default)]
pub struct BondedTally {
    pub ebond: f64,
    pub eangle: f64,
    pub edihed: f64,
    pub virial: [f64; 6],
}

impl Simulation {
    /// Checks before a run: every used type has coefficients; the special lists.
    pub fn init_bonded(&mut self) -> Result<(), String> {
        let t = &self.topo;
        if let Some(s) = self.bond_style.as_mut() {
            s.set_types(t.nbondtypes);
            if t.nbondtypes > 0 {
                s.check_all_set()?;
            }
        }
        if let Some(s) = self.angle_style.as_mut() {
            s.set_types(t.nangletypes);
            if t.nangletypes > 0 {
                s.check_all_set()?;
            }
        }
        if let Some(s) = self.dihedral_style.as_mut() {
            s.set_types(t.ndihedraltypes);
            if t.ndihedraltypes > 0 {
                s.check_all_set()?;
            }
        }
        let missing = |n: usize, style: bool, what: &str| -> Option<String> {
            (n > 0 && !style).then(|| format!("{n} {what}s are defined but no {what}_style is set"))
        };
        for w in [
            missing(t.bonds.len(), self.bond_style.is_some(), "bond"),
            missing(t.angles.len(), self.angle_style.is_some(), "angle"),
            missing(t.dihedrals.len(), self.dihedral_style.is_some(), "dihedral"),
        ]
        .into_iter()
        .flatten()
        {
            self.out.print(&format!("WARNING: {w}"));
        }
        // special partners by atom ID
        self.special_table.flags = self.special_bonds.flags(false);
        if self.topo.bonds.is_empty() {
            self.special_table.by_tag.clear();
        } else {
            let bonds: Vec<[i64; 2]> = self.topo.bonds.iter().map(|b| b.atoms).collect();
            let angles: Vec<[i64; 3]> = self.topo.angles.iter().map(|a| a.atoms).collect();
            let dihedrals: Vec<[i64; 4]> = self.topo.dihedrals.iter().map(|d| d.atoms).collect();
            let ids = &self.atoms.tag[..self.atoms.nlocal];
            let (lists, _stats) = build_special(&self.special_bonds, ids, SpecialTopology { bonds: &bonds, angles: &angles, dihedrals: &dihedrals })?;
            let maxtag = ids.iter().copied().max().unwrap_or(0) as usize;
            let mut by_tag = vec![Default::default(); maxtag + 1];
            for (k, l) in lists.into_iter().enumerate() {
                by_tag[ids[k] as usize] = l;
            }
            self.special_table.by_tag = by_tag;
        }
        Ok(())
    }

    /// Map every interaction to local indices and closest-image shifts (after a rebuild).
    pub fn build_bonded_lists(&mut self) -> Result<(), RunError> {
        let t = &self.topo;
        if t.is_empty() {
            self.bonded_lists = BondedLists::default();
            return Ok(());
        }
        let map = self.atoms.tag_map();
        let domain = self.domain.as_ref().unwrap();
        let prd = domain.prd();
        let x = &self.atoms.x;
        let step = self.step;
        let find = |tag: i64, what: &str| -> Result<u32, RunError> {
            map.get(tag).map(|i| i as u32).ok_or_else(|| RunError::new(step, format!("{what} atom {tag} is missing")))
        };
        // shift of atom `o` that brings it closest to atom `r`, per periodic dimension
        let closest = |r: usize, o: usize| -> [i8; 3] {
            let mut s = [0i8; 3];
            for d in 0..3 {
                if domain.periodic(d) {
                    let dx = x[r][d] - x[o][d];
                    if dx > 0.5 * prd[d] {
                        s[d] = 1;
                    } else if dx < -0.5 * prd[d] {
                        s[d] = -1;
                    }
                }
            }
            s
        };
        let mut lists = BondedLists::default();
        if self.bond_style.is_some() {
            for b in &t.bonds {
                let i = [find(b.atoms[0], "bond")?, find(b.atoms[1], "bond")?];
                lists.bonds.push(Entry { atoms: i, shift: [[0; 3], closest(i[0] as usize, i[1] as usize)], typ: b.typ });
            }
        }
        if self.angle_style.is_some() {
            for a in &t.angles {
                let i = [find(a.atoms[0], "angle")?, find(a.atoms[1], "angle")?, find(a.atoms[2], "angle")?];
                let r = i[1] as usize;
                lists.angles.push(Entry { atoms: i, shift: [closest(r, i[0] as usize), [0; 3], closest(r, i[2] as usize)], typ: a.typ });
            }
        }
        if self.dihedral_style.is_some() {
            for d in &t.dihedrals {
                let i = [find(d.atoms[0], "dihedral")?, find(d.atoms[1], "dihedral")?, find(d.atoms[2], "dihedral")?, find(d.atoms[3], "dihedral")?];
                let r = i[1] as usize;
                let shift = [closest(r, i[0] as usize), [0; 3], closest(r, i[2] as usize), closest(r, i[3] as usize)];
                lists.dihedrals.push(Entry { atoms: i, shift, typ: d.typ });
            }
        }
        self.bonded_lists = lists;
        Ok(())
    }

    /// Bond, angle and dihedral forces on owned atoms.
    pub fn compute_bonded(&mut self, eflag: bool) -> Result<BondedTally, RunError> {
        let mut tally = BondedTally::default();
        let lists = &self.bonded_lists;
        if lists.bonds.is_empty() && lists.angles.is_empty() && lists.dihedrals.is_empty() {
            return Ok(tally);
        }
        let prd = self.domain.as_ref().unwrap().prd();
        let a = &mut self.atoms;
        let pos = |x: &[[f64; 3]], i: u32, s: [i8; 3]| -> [f64; 3] {
            let mut p = x[i as usize];
            for d in 0..3 {
                if s[d] != 0 {
                    p[d] += s[d] as f64 * prd[d];
                }
            }
            p
        };
        let sub = |p: [f64; 3], q: [f64; 3]| [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
        let add_virial = |t: &mut [f64; 6], v: [f64; 6]| {
            for k in 0..6 {
                t[k] += v[k];
            }
        };
        if let Some(style) = self.bond_style.as_deref() {
            for e in &lists.bonds {
                let x1 = pos(&a.x, e.atoms[0], e.shift[0]);
                let x2 = pos(&a.x, e.atoms[1], e.shift[1]);
                let del = sub(x1, x2);
                let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
                let (fbond, energy) = style.compute(e.typ, del, rsq);
                let (i1, i2) = (e.atoms[0] as usize, e.atoms[1] as usize);
                for d in 0..3 {
                    a.f[i1][d] += del[d] * fbond;
                    a.f[i2][d] -= del[d] * fbond;
                }
                if eflag {
                    tally.ebond += energy;
                    add_virial(&mut tally.virial, bond_virial(del, fbond));
                }
            }
        }
        if let Some(style) = self.angle_style.as_deref() {
            for e in &lists.angles {
                let x1 = pos(&a.x, e.atoms[0], e.shift[0]);
                let x2 = pos(&a.x, e.atoms[1], e.shift[1]);
                let x3 = pos(&a.x, e.atoms[2], e.shift[2]);
                let (del1, del2) = (sub(x1, x2), sub(x3, x2));
                let r = style.compute(e.typ, del1, del2);
                let f2 = r.f2();
                let [i1, i2, i3] = e.atoms.map(|i| i as usize);
                for d in 0..3 {
                    a.f[i1][d] += r.f1[d];
                    a.f[i2][d] += f2[d];
                    a.f[i3][d] += r.f3[d];
                }
                if eflag {
                    tally.eangle += r.energy;
                    add_virial(&mut tally.virial, angle_virial(del1, del2, r.f1, r.f3));
                }
            }
        }
        if let Some(style) = self.dihedral_style.as_deref() {
            for e in &lists.dihedrals {
                let p: Vec<[f64; 3]> = (0..4).map(|k| pos(&a.x, e.atoms[k], e.shift[k])).collect();
                let (vb1, vb2, vb3) = (sub(p[0], p[1]), sub(p[2], p[1]), sub(p[3], p[2]));
                let r = style.compute(e.typ, vb1, vb2, vb3);
                let [i1, i2, i3, i4] = e.atoms.map(|i| i as usize);
                for d in 0..3 {
                    a.f[i1][d] += r.f1[d];
                    a.f[i2][d] += r.f2[d];
                    a.f[i3][d] += r.f3[d];
                    a.f[i4][d] += r.f4[d];
                }
                if eflag {
                    tally.edihed += r.energy;
                    add_virial(&mut tally.virial, dihedral_virial(vb1, vb2, vb3, r.f1, r.f3, r.f4));
                }
            }
        }
        Ok(tally)
    }
}
