//! The per-atom state of the `mdr` normal model between force evaluations: what LAMMPS' fix
//! GRANULAR/MDR (added by the model itself, last in the fix list) does before each force
//! evaluation (its pre_force).
//!
//! 1. Atoms not yet initialised take their radius as initial radius R_o and zero sums.
//! 2. Each owned atom (outside a run's setup; at setup only new atoms) gets its geometric volume
//!    V_geo = min(4/3 pi R^3 - V_caps, V_o), elastic volume V_elas = V_o (1 + eps_bar), total
//!    area A_tot = 4 pi R^2 + sum and free-area ratio psi = (A_tot - A_con)/A_tot from the
//!    sums of the last force evaluation; while psi > psi_b the apparent radius grows by a
//!    running mean (window 10) of the increment the contacts' plastic flow asks for (up to 1.5
//!    R_o). Ghost images get the new values but keep their radius: LAMMPS forwards no radius
//!    here, so a contact across a periodic face sees its partner's radius of the step before.
//! 3. Outside setup the sums are zeroed for the coming pair pass, and each touching contact
//!    gets its penalty: for every third sphere touching both, the longest side of the triangle
//!    (the contact reaching through the third sphere) gains 1/(1 + exp(-50 (alpha/pi - 1/2))),
//!    alpha the angle at the third sphere. Then the mean surface displacement increment of each
//!    atom: each contact's new overlap split between its sides as the force will split it,
//!    weighted by the side's share of the atom's contact area.
//!
//! With two equally long sides LAMMPS gives the penalty to one of them by the order of its
//! neighbour list; here both get it (exact ties only).

use super::mdr::{touching, MdrAtom, Sums, AC, DELTAP, DELTA_MAX, OVERLAP_LIMIT, PENALTY};
use crate::engine::atoms::Atoms;
use crate::engine::contact_history::ContactHistory;
use crate::engine::fields::{self, Field};
use crate::engine::neighbor::NEIGH_MASK;
use crate::engine::state::State;
use std::f64::consts::PI;

const EPSILON: f64 = 1e-16;

/// Make the fields of `wanted` the atoms lack (the ghosts go: the next run makes them again).
/// Returns whether any was made.
pub fn ensure_fields_for(wanted: &[Field], atoms: &mut Atoms) -> bool {
    if wanted.iter().all(|&f| atoms.field(f).is_some()) {
        return false;
    }
    atoms.clear_ghosts();
    for &f in wanted {
        atoms.add_field(f);
    }
    true
}

fn index(atoms: &Atoms, f: Field) -> Result<usize, String> {
    atoms.field(f).ok_or_else(|| format!("pair granular mdr: the per-atom value {} is missing", f.name))
}

/// Copy a field of the owned atoms to their ghost images.
pub(crate) fn forward(atoms: &mut Atoms, k: usize) {
    let n = atoms.nlocal;
    let owner = std::mem::take(&mut atoms.ghost_owner);
    if atoms.extra[k].data.len() == n + owner.len() {
        Atoms::forward_field(&mut atoms.extra[k].data, n, &owner);
    }
    atoms.ghost_owner = owner;
}

/// LAMMPS FixGranularMDR::pre_force (and setup_pre_force with `setup`).
pub fn pre_force(state: &mut State, history: &mut ContactHistory, psi_b: f64, setup: bool) -> Result<(), String> {
    let a = &mut state.atoms;
    let k = |f| index(a, f);
    let [ro, vgeo, velas, acon0, atot, psi, ddelta_bar, dravg, flag] =
        [fields::MDR_RO, fields::MDR_VGEO, fields::MDR_VELAS, fields::MDR_ACON0, fields::MDR_ATOT, fields::MDR_PSI, fields::MDR_DDELTA_BAR, fields::MDR_DRAVG, fields::MDR_SETUP].map(k);
    let sums = fields::MDR_SUMS.map(k);
    let (ro, vgeo, velas, acon0, atot, psi, ddelta_bar, dravg, flag) = (ro?, vgeo?, velas?, acon0?, atot?, psi?, ddelta_bar?, dravg?, flag?);
    let mut s = [0usize; 9];
    for (d, r) in s.iter_mut().zip(sums) {
        *d = r?;
    }
    let [vcaps, eps_bar, drnum, drden, acon1, atot_sum, sxx, syy, szz] = s;

    let nlocal = a.nlocal;
    let nall = a.nall();
    for i in 0..nall {
        let owned = i < nlocal;
        let mut new_atom = false;
        if a.extra[flag].data[i] < EPSILON {
            a.extra[ro].data[i] = a.radius[i];
            a.extra[acon0].data[i] = 0.0;
            a.extra[ddelta_bar].data[i] = 0.0;
            if owned {
                for &kk in &[acon1, vcaps, eps_bar, drnum, drden, atot_sum, sxx, syy, szz] {
                    a.extra[kk].data[i] = 0.0;
                }
            }
            a.extra[flag].data[i] = 1.0;
            new_atom = true;
        }
        if !owned || (setup && !new_atom) {
            continue;
        }
        let e = |kk: usize| a.extra[kk].data[i];
        let r = a.radius[i];
        let rsq = r * r;
        let r0 = e(ro);
        let vo = 4.0 / 3.0 * PI * (r0 * r0 * r0);
        let vgeoi = 4.0 / 3.0 * PI * rsq * r - e(vcaps);
        let v_geo = if vgeoi < vo { vgeoi } else { vo };
        let v_elas = vo * (1.0 + e(eps_bar));
        let a_tot = 4.0 * PI * rsq + e(atot_sum);
        let p = (a_tot - e(acon1)) / a_tot;
        let mut radius = r;
        let mut avg = e(dravg);
        if psi_b < p {
            // the radius grows while the surface is mostly free
            let w = if p > 0.1 { 1.0 / (1.0 + (-75.0 * (p - 0.2)).exp()) } else { 0.0 };
            let x = e(drnum) / (e(drden) - 4.0 * PI * rsq) * w;
            let dr = if x > 0.0 { x } else { 0.0 };
            let n_window = 10.0;
            if dr > 0.0 {
                avg += (dr - avg) / n_window;
            }
            if r + dr < 1.5 * r0 && dr > 0.0 {
                radius += avg;
            }
        }
        let con1 = e(acon1);
        a.extra[vgeo].data[i] = v_geo;
        a.extra[velas].data[i] = v_elas;
        a.extra[atot].data[i] = a_tot;
        a.extra[psi].data[i] = p;
        a.extra[dravg].data[i] = avg;
        a.extra[acon0].data[i] = con1;
        a.radius[i] = radius;
    }
    // ghosts: the new values (LAMMPS' first forward communication), not the radius
    for kk in [ro, vgeo, velas, acon0, atot, psi, dravg, flag] {
        forward(a, kk);
    }
    a.extra[ddelta_bar].data.iter_mut().for_each(|v| *v = 0.0);
    if !setup {
        for kk in [vcaps, eps_bar, drnum, drden, acon1, atot_sum, sxx, syy, szz] {
            a.extra[kk].data.iter_mut().for_each(|v| *v = 0.0);
        }
        contact_penalty(a, &state.neighbor.list, history);
        mean_surface_displacement(a, &state.neighbor.list, history, acon0, ddelta_bar);
    }
    forward(a, ddelta_bar);
    Ok(())
}

/// Each listed pair's entry: (chunk, entry, i, j).
fn entries(list: &crate::engine::neighbor::NeighList) -> impl Iterator<Item = (usize, usize, usize, usize)> + '_ {
    list.chunks.iter().enumerate().flat_map(|(c, chunk)| {
        (chunk.start..chunk.end).flat_map(move |i| {
            let k0 = chunk.first_entry(i);
            chunk.neighbors(i).iter().enumerate().map(move |(k, &jraw)| (c, k0 + k, i, (jraw & NEIGH_MASK) as usize))
        })
    })
}

fn dist(x: &[[f64; 3]], from: usize, to: usize) -> ([f64; 3], f64) {
    let d = [x[to][0] - x[from][0], x[to][1] - x[from][1], x[to][2] - x[from][2]];
    (d, (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt())
}

/// LAMMPS FixGranularMDR::calculate_contact_penalty.
fn contact_penalty(a: &Atoms, list: &crate::engine::neighbor::NeighList, history: &mut ContactHistory) {
    let size = history.size();
    let (x, radius, nlocal) = (&a.x, &a.radius, a.nlocal);
    // the atoms each atom touches (a pair of owned atoms is listed once)
    let mut adj: Vec<Vec<usize>> = vec![Vec::new(); a.nall()];
    for (c, e, i, j) in entries(list) {
        history.chunks[c].values[e * size + PENALTY] = 0.0;
        let (_, r) = dist(x, i, j);
        if radius[i] + radius[j] - r >= 0.0 {
            adj[i].push(j);
            if j < nlocal {
                adj[j].push(i);
            }
        }
    }
    for (c, e, i, j) in entries(list) {
        let (_, r_ij) = dist(x, i, j);
        if radius[i] + radius[j] - r_ij < 0.0 {
            continue;
        }
        let mut p = 0.0;
        for &k in &adj[i] {
            if k == j {
                continue;
            }
            let (d_ik, r_ik) = dist(x, i, k);
            let (d_jk, r_jk) = dist(x, j, k);
            if radius[j] + radius[k] - r_jk < 0.0 || r_ij < r_ik || r_ij < r_jk {
                continue;
            }
            // the angle at k between i and j
            let (ri, rj) = (1.0 / r_ik, 1.0 / r_jk);
            let u = [-d_ik[0] * ri, -d_ik[1] * ri, -d_ik[2] * ri];
            let v = [-d_jk[0] * rj, -d_jk[1] * rj, -d_jk[2] * rj];
            let alpha = (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]).acos();
            p += 1.0 / (1.0 + (-50.0 * (alpha / PI - 0.5)).exp());
        }
        history.chunks[c].values[e * size + PENALTY] += p;
    }
}

/// LAMMPS FixGranularMDR::mean_surf_disp: contacts that no longer touch (with the new radii)
/// end here; each touching one adds its sides' overlap increments to ddelta_bar.
fn mean_surface_displacement(a: &mut Atoms, list: &crate::engine::neighbor::NeighList, history: &mut ContactHistory, acon0: usize, ddelta_bar: usize) {
    let size = history.size();
    for (c, e, i, j) in entries(list) {
        let (x, radius, tag) = (&a.x, &a.radius, &a.tag);
        let hc = &mut history.chunks[c];
        let Some((_, rsq, radsum)) = touching(hc, e, x, radius, i, j) else { continue };
        let h = &hc.values[e * size..(e + 1) * size];
        let delta = radsum - rsq.sqrt();
        let mut deltamax = h[DELTA_MAX];
        if delta > deltamax {
            deltamax = delta;
        }
        let (deltap0, deltap1) = (h[DELTAP], h[DELTAP + 1]);
        let (i0, i1) = if tag[i] > tag[j] { (i, j) } else { (j, i) };
        let (r0, r1) = (radius[i0], radius[i1]);
        let opt1 = deltamax * (deltamax - 2.0 * r1) / (2.0 * (deltamax - r0 - r1));
        let opt2 = deltamax * (deltamax - 2.0 * r0) / (2.0 * (deltamax - r0 - r1));
        let (big, small) = if opt1 > opt2 { (opt1, opt2) } else { (opt2, opt1) };
        let (mut geo0, mut geo1) = if r0 < r1 { (big, small) } else { (small, big) };
        if geo0 / r0 > OVERLAP_LIMIT {
            geo0 = r0 * OVERLAP_LIMIT;
            geo1 = deltamax - geo0;
        } else if geo1 / r1 > OVERLAP_LIMIT {
            geo1 = r1 * OVERLAP_LIMIT;
            geo0 = deltamax - geo1;
        }
        let deltap = deltap0 + deltap1;
        let delta0 = geo0 + (deltap0 - geo0) / (deltap - deltamax) * (delta - deltamax);
        let delta1 = geo1 + (deltap1 - geo1) / (deltap - deltamax) * (delta - deltamax);
        let ddel = [delta0 - h[0], delta1 - h[1]];
        let ac = [h[AC], h[AC + 1]];
        for (side, at) in [i0, i1].into_iter().enumerate() {
            let con = a.extra[acon0].data[at];
            if con != 0.0 {
                a.extra[ddelta_bar].data[at] += ac[side] / con * ddel[side];
            }
        }
    }
}

/// What a granular region wall with the mdr model reads and adds to on the atoms, taken out of
/// them for the wall's pass ([`MdrArrays::restore`] puts them back): the values of
/// [`MdrAtom`] and the sums of the pair pass, to which the wall's contacts add (LAMMPS: the
/// wall's model writes the same per-atom arrays after the pair pass).
pub struct MdrArrays {
    index: Vec<usize>,
    data: Vec<Vec<f64>>,
}

const READ: [Field; 6] = [fields::MDR_RO, fields::MDR_PSI, fields::MDR_DDELTA_BAR, fields::MDR_VGEO, fields::MDR_ACON0, fields::MDR_VELAS];

impl MdrArrays {
    pub fn take(atoms: &mut Atoms) -> Result<MdrArrays, String> {
        let index = READ.iter().chain(&fields::MDR_SUMS).map(|&f| index(atoms, f)).collect::<Result<Vec<_>, _>>()?;
        let data = index.iter().map(|&k| std::mem::take(&mut atoms.extra[k].data)).collect();
        Ok(MdrArrays { index, data })
    }

    /// Atom `i` as a contact reads it.
    pub fn atom(&self, i: usize, tag: i64, radius: f64) -> MdrAtom {
        let v = |k: usize| self.data[k][i];
        MdrAtom { tag, radius, ro: v(0), psi: v(1), ddelta_bar: v(2), vgeo: v(3), acon0: v(4), velas: v(5) }
    }

    pub fn sums(&mut self) -> Sums<'_> {
        let mut it = self.data[READ.len()..].iter_mut();
        Sums(std::array::from_fn(|_| &mut it.next().expect("nine sums")[..]))
    }

    pub fn restore(self, atoms: &mut Atoms) {
        for (k, d) in self.index.into_iter().zip(self.data) {
            atoms.extra[k].data = d;
        }
    }
}

/// The mean surface displacement increment of atom `i` from one region-wall contact (LAMMPS
/// FixGranularMDR::update_fix_gran_wall): the contact's new overlap `delta` against its last
/// (history value 0), weighted by its share of the atom's contact area (history value AC).
pub fn wall_surface_displacement(a: &mut Atoms, i: usize, delta: f64, h: &[f64]) -> Result<(), String> {
    let (kc, kd) = (index(a, fields::MDR_ACON0)?, index(a, fields::MDR_DDELTA_BAR)?);
    let con = a.extra[kc].data[i];
    if con != 0.0 {
        a.extra[kd].data[i] += h[AC] / con * (delta - h[0]);
    }
    Ok(())
}
