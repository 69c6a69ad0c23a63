//! Molecule templates (the `molecule` command): atoms with their relative coordinates, types
//! and optional per-atom values, and the bonds, angles and dihedrals among them. Commands that
//! insert copies of a molecule (`create_atoms ... mol`) rotate the displacements `dx` about the
//! geometric centre and add the copy's atom ID offset to the topology.

use crate::engine::atoms::NewAtom;
use crate::engine::domain::Domain;
use crate::engine::jacobi::{jacobi3, Sort};
use crate::engine::quat::{axisangle_to_quat, cross3, exyz_to_q, matvec, norm3, quat_to_mat, transpose_matvec_cols, Quat};
use crate::engine::state::State;
use crate::engine::topology::{Angle, Bond, Dihedral};

/// The rotation matrix LAMMPS builds from a random axis `r` (not yet normalised) and angle
/// `theta` when it inserts a molecule (`norm3`, `axisangle_to_quat`, `quat_to_mat`).
pub fn rotation(mut r: [f64; 3], theta: f64) -> [[f64; 3]; 3] {
    norm3(&mut r);
    quat_to_mat(&axisangle_to_quat(&r, theta))
}

/// Adds a point mass `m` at `d` from the centre to an inertia tensor in Voigt order (xx yy zz yz
/// xz xy), as LAMMPS sums it.
pub fn add_point_inertia(t: &mut [f64; 6], m: f64, [dx, dy, dz]: [f64; 3]) {
    t[0] += m * (dy * dy + dz * dz);
    t[1] += m * (dx * dx + dz * dz);
    t[2] += m * (dx * dx + dy * dy);
    t[3] -= m * dy * dz;
    t[4] -= m * dx * dz;
    t[5] -= m * dx * dy;
}

/// A template as one rigid body (LAMMPS' Molecule::compute_mass, compute_com and
/// compute_inertia): what fix rigid/small gives a body that fix pour or deposit inserts.
#[derive(Clone, Debug, PartialEq)]
pub struct RigidTemplate {
    pub masstotal: f64,
    pub com: [f64; 3],
    /// The geometric centre (where an insertion puts the template's `center`).
    pub center: [f64; 3],
    /// Principal moments (those below 1e-7 of the largest are 0).
    pub inertia: [f64; 3],
    pub quat: Quat,
    /// Each atom's displacement from the COM in the body frame.
    pub dxbody: Vec<[f64; 3]>,
    /// Finite-size atoms (the template has diameters).
    pub spheres: bool,
    /// The largest distance from the atom nearest the COM to any atom (LAMMPS' maxextent).
    pub maxextent: f64,
}

/// One molecule inserted as a rigid body (the arguments of LAMMPS' set_molecule).
#[derive(Clone, Debug)]
pub struct RigidInsert {
    /// The rigid fix named by the inserting fix.
    pub fix_id: String,
    /// The atom ID before the copy's first (its atoms are tagprev + 1 ..).
    pub tagprev: i64,
    pub mol: i64,
    /// Where the template's geometric centre went, the copy's velocity and rotation.
    pub xgeom: [f64; 3],
    pub vcm: [f64; 3],
    pub quat: Quat,
}

/// One molecule template, with the file's offsets and `scale` applied.
#[derive(Clone, Debug, PartialEq)]
pub struct Molecule {
    pub id: String,
    /// Coordinates as in the file (times `scale`).
    pub x: Vec<[f64; 3]>,
    /// Atom types (with `toff`), when the file has a Types section.
    pub typ: Option<Vec<usize>>,
    /// Molecule IDs inside the template (Molecules section).
    pub molecule: Option<Vec<i64>>,
    pub q: Option<Vec<f64>>,
    pub radius: Option<Vec<f64>>,
    pub rmass: Option<Vec<f64>>,
    /// Bonds (type with `boff`, 0-based atoms), in file order.
    pub bonds: Vec<(usize, [usize; 2])>,
    pub angles: Vec<(usize, [usize; 3])>,
    pub dihedrals: Vec<(usize, [usize; 4])>,
    /// The geometric centre and each atom's displacement from it (LAMMPS' `center`, `dx`).
    pub center: [f64; 3],
    pub dx: Vec<[f64; 3]>,
    /// The largest distance of an atom's surface from the centre.
    pub molradius: f64,
    /// The header's `M mass`, `x y z com` and `Ixx Iyy Izz Ixy Ixz Iyz inertia` (scaled):
    /// used as given in place of the computed values (LAMMPS' massflag, comflag, inertiaflag).
    pub user_mass: Option<f64>,
    pub user_com: Option<[f64; 3]>,
    pub user_inertia: Option<[f64; 6]>,
}

impl Molecule {
    /// A template from its parts; computes the centre as LAMMPS' `compute_center` does (sum in
    /// atom order, then one division per axis).
    pub fn new(id: String, x: Vec<[f64; 3]>) -> Molecule {
        let n = x.len() as f64;
        let mut center = [0.0; 3];
        for p in &x {
            for d in 0..3 {
                center[d] += p[d];
            }
        }
        for c in center.iter_mut() {
            *c /= n;
        }
        let dx: Vec<[f64; 3]> = x.iter().map(|p| [p[0] - center[0], p[1] - center[1], p[2] - center[2]]).collect();
        Molecule {
            id,
            x,
            typ: None,
            molecule: None,
            q: None,
            radius: None,
            rmass: None,
            bonds: vec![],
            angles: vec![],
            dihedrals: vec![],
            center,
            dx,
            molradius: 0.0,
            user_mass: None,
            user_com: None,
            user_inertia: None,
        }
        .with_radius()
    }

    /// Sets `molradius` from `dx` and the radii.
    pub fn with_radius(mut self) -> Molecule {
        self.molradius = 0.0;
        for (i, d) in self.dx.iter().enumerate() {
            let mut rad = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            if let Some(r) = &self.radius {
                rad += r[i];
            }
            self.molradius = if self.molradius > rad { self.molradius } else { rad };
        }
        self
    }

    /// The atoms of a copy turned by `rot` and centred at `center`, not yet wrapped into the
    /// box (LAMMPS: `matvec`, `add3`).
    pub fn unwrapped<'a>(&'a self, rot: &'a [[f64; 3]; 3], center: [f64; 3]) -> impl Iterator<Item = [f64; 3]> + 'a {
        self.dx.iter().map(move |dx| {
            let d = matvec(rot, dx);
            [d[0] + center[0], d[1] + center[1], d[2] + center[2]]
        })
    }

    /// The atoms of a copy turned by `rot` and centred at `center`, each wrapped into the
    /// periodic box, with its image flags (LAMMPS: `matvec`, `add3`, `remap`).
    pub fn place(&self, rot: &[[f64; 3]; 3], center: [f64; 3], domain: &Domain) -> Vec<([f64; 3], [i32; 3])> {
        self.unwrapped(rot, center)
            .map(|mut x| {
                let mut image = [0; 3];
                domain.remap(&mut x, &mut image);
                (x, image)
            })
            .collect()
    }

    /// Add a copy with atoms at `placed`: atom IDs `tag_offset + 1..`, molecule IDs
    /// `mol_offset +` the template's own (1 without a Molecules section), types shifted by
    /// `type_offset`, velocity `v`, the template's charges, radii and masses where the atom style
    /// holds them (a sphere without a mass gets density 1, as LAMMPS' `add_molecule_atom`), and
    /// the template's bonds, angles and dihedrals in LAMMPS' storage order (a bond with its first
    /// atom, an angle and a dihedral with their second; file order within an atom). Returns the
    /// local indices of the new atoms. The special lists are left to the caller.
    pub fn push_copy(&self, state: &mut State, placed: &[([f64; 3], [i32; 3])], tag_offset: i64, mol_offset: i64, type_offset: usize, v: [f64; 3]) -> std::ops::Range<usize> {
        let typ = self.typ.as_ref().expect("templates used for insertion have types (checked when parsed)");
        let first = state.atoms.nlocal;
        for (k, &(x, image)) in placed.iter().enumerate() {
            let mut a = NewAtom::at(tag_offset + k as i64 + 1, type_offset + typ[k], x);
            a.image = image;
            a.v = v;
            a.molecule = mol_offset + self.molecule.as_ref().map(|m| m[k]).unwrap_or(1);
            if let Some(q) = &self.q {
                a.q = q[k];
            }
            if let Some(r) = &self.radius {
                a.radius = r[k];
            }
            a.rmass = match &self.rmass {
                Some(m) => m[k],
                None => 4.0 * std::f64::consts::PI / 3.0 * a.radius * a.radius * a.radius,
            };
            state.atoms.push(&a);
        }
        self.push_topology(state, tag_offset);
        first..state.atoms.nlocal
    }

    /// The bonds, angles and dihedrals of a copy whose atoms have IDs `tag_offset + 1 ...` (every
    /// rank of a distributed run keeps the whole topology, whichever rank holds the atoms).
    pub fn push_topology(&self, state: &mut State, tag_offset: i64) {
        let id = |i: usize| tag_offset + i as i64 + 1;
        let topo = &mut state.topo;
        for k in 0..self.natoms() {
            for &(t, at) in self.bonds.iter().filter(|b| b.1[0] == k) {
                topo.bonds.push(Bond::new(t, at.map(id)));
            }
            for &(t, at) in self.angles.iter().filter(|b| b.1[1] == k) {
                topo.angles.push(Angle::new(t, at.map(id)));
            }
            for &(t, at) in self.dihedrals.iter().filter(|b| b.1[1] == k) {
                topo.dihedrals.push(Dihedral::new(t, at.map(id)));
            }
        }
    }

    /// The number of molecule IDs a copy uses.
    pub fn nmolecules(&self) -> i64 {
        self.molecule.as_ref().map(|v| v.iter().copied().max().unwrap_or(1)).unwrap_or(1)
    }

    /// Whether a copy adds bonds, angles or dihedrals (then the special lists need a rebuild).
    pub fn has_topology(&self) -> bool {
        !(self.bonds.is_empty() && self.angles.is_empty() && self.dihedrals.is_empty())
    }

    /// `Err` naming the first bond, angle or dihedral type beyond the box's counts.
    pub fn check_types(&self, state: &State) -> Result<(), String> {
        let t = &state.topo;
        for (kind, n, max) in [
            ("bond", t.nbondtypes, self.bonds.iter().map(|b| b.0).max()),
            ("angle", t.nangletypes, self.angles.iter().map(|b| b.0).max()),
            ("dihedral", t.ndihedraltypes, self.dihedrals.iter().map(|b| b.0).max()),
        ] {
            if let Some(mx) = max.filter(|&mx| mx > n) {
                return Err(format!("molecule template `{}` has {kind} type {mx}, but the box has {n} {kind} types", self.id));
            }
        }
        Ok(())
    }

    /// The template as a rigid body, in LAMMPS' order of operations: masses from the Masses
    /// section or the type masses, the COM (sum of x m, one division), the inertia tensor about
    /// it (spheres add 0.4 m r^2), principal axes by Jacobi rotations with the moments
    /// decreasing (jacobi3's default there), right-handed, the quaternion and the body-frame
    /// displacements. `Err` if the rotations do not converge or a type mass is missing.
    pub fn rigid(&self, type_mass: &[f64]) -> Result<RigidTemplate, String> {
        let typ = self.typ.as_ref().ok_or_else(|| format!("molecule template `{}` has no Types section", self.id))?;
        let mass = |i: usize| match &self.rmass {
            Some(m) => m[i],
            None => type_mass.get(typ[i]).copied().unwrap_or(0.0),
        };
        let n = self.natoms();
        // the header's values as given, else computed (the centre of mass over the header's
        // mass when only that is given, as LAMMPS divides by its masstotal)
        let masstotal = self.user_mass.unwrap_or_else(|| (0..n).map(mass).sum());
        if masstotal <= 0.0 {
            return Err(format!("molecule template `{}` has no mass (set type masses or a Masses section)", self.id));
        }
        let com = self.user_com.unwrap_or_else(|| {
            let mut com = [0.0; 3];
            for i in 0..n {
                for k in 0..3 {
                    com[k] += self.x[i][k] * mass(i);
                }
            }
            com.map(|c| c / masstotal)
        });
        let dxcom: Vec<[f64; 3]> = self.x.iter().map(|p| [p[0] - com[0], p[1] - com[1], p[2] - com[2]]).collect();
        // a header's six values fill LAMMPS' itensor in the order given (its Voigt order xx yy
        // zz yz xz xy)
        let t = self.user_inertia.unwrap_or_else(|| {
            let mut t = [0.0f64; 6];
            for (i, &d) in dxcom.iter().enumerate() {
                add_point_inertia(&mut t, mass(i), d);
            }
            if let Some(r) = &self.radius {
                for i in 0..n {
                    for v in t.iter_mut().take(3) {
                        *v += 0.4 * mass(i) * r[i] * r[i];
                    }
                }
            }
            t
        });
        let tensor = [[t[0], t[5], t[4]], [t[5], t[1], t[3]], [t[4], t[3], t[2]]];
        let (mut inertia, evec) = jacobi3(&tensor, Sort::Decreasing).ok_or_else(|| format!("insufficient Jacobi rotations for the rigid molecule `{}`", self.id))?;
        let ex = [evec[0][0], evec[1][0], evec[2][0]];
        let ey = [evec[0][1], evec[1][1], evec[2][1]];
        let mut ez = [evec[0][2], evec[1][2], evec[2][2]];
        let max = inertia[0].max(inertia[1]).max(inertia[2]);
        for v in inertia.iter_mut() {
            if *v < 1.0e-7 * max {
                *v = 0.0;
            }
        }
        let c = cross3(&ex, &ey);
        if c[0] * ez[0] + c[1] * ez[1] + c[2] * ez[2] < 0.0 {
            ez = [-ez[0], -ez[1], -ez[2]];
        }
        let quat = exyz_to_q(&ex, &ey, &ez);
        let dxbody = dxcom.iter().map(|d| transpose_matvec_cols(&ex, &ey, &ez, d)).collect();
        // LAMMPS' comatom: the first atom nearest the centre of mass
        let sq = |d: &[f64; 3]| d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        let comatom = (0..n).fold(0, |best, i| if sq(&dxcom[i]) < sq(&dxcom[best]) { i } else { best });
        let maxextent = (0..n).map(|i| sq(&std::array::from_fn(|k| self.x[comatom][k] - self.x[i][k]))).fold(0.0f64, f64::max).sqrt();
        Ok(RigidTemplate { masstotal, com, center: self.center, inertia, quat, dxbody, spheres: self.radius.is_some(), maxextent })
    }

    pub fn natoms(&self) -> usize {
        self.x.len()
    }

    /// The largest atom type (0 without types).
    pub fn max_type(&self) -> usize {
        self.typ.as_ref().and_then(|t| t.iter().max().copied()).unwrap_or(0)
    }

    /// Each atom's 1-2, 1-3 and 1-4 partners inside the molecule (0-based), as LAMMPS'
    /// `special_generate` finds them from the bonds: 1-2 in bond order, then partners of
    /// partners not already listed (and not the atom itself), likewise for 1-4.
    pub fn special_lists(&self) -> Vec<[Vec<usize>; 3]> {
        let n = self.natoms();
        let mut out: Vec<[Vec<usize>; 3]> = vec![Default::default(); n];
        for &(_, [a, b]) in &self.bonds {
            out[a][0].push(b);
            out[b][0].push(a);
        }
        for level in 1..3 {
            for i in 0..n {
                let mut next = vec![];
                for &j in &out[i][level - 1] {
                    for &k in &out[j][0] {
                        let known = k == i || (0..level).any(|l| out[i][l].contains(&k)) || next.contains(&k);
                        if !known {
                            next.push(k);
                        }
                    }
                }
                out[i][level] = next;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_and_radius_of_a_dimer() {
        let mut m = Molecule::new("d".into(), vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]]);
        assert_eq!(m.center, [1.0, 0.0, 0.0]);
        assert_eq!(m.dx, vec![[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]);
        assert_eq!(m.molradius, 1.0);
        m.radius = Some(vec![0.5, 0.25]);
        assert_eq!(m.with_radius().molradius, 1.5);
    }

    #[test]
    fn special_lists_of_a_chain() {
        let mut m = Molecule::new("c".into(), (0..5).map(|i| [i as f64, 0.0, 0.0]).collect());
        m.bonds = vec![(1, [0, 1]), (1, [1, 2]), (1, [2, 3]), (1, [3, 4])];
        let s = m.special_lists();
        assert_eq!(s[0], [vec![1], vec![2], vec![3]]);
        assert_eq!(s[2], [vec![1, 3], vec![0, 4], vec![]]);
    }
}
