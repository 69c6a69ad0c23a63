//! A group's rotation as LAMMPS' Group class computes it: the centre of mass of the unwrapped
//! positions, the angular momentum and inertia tensor about it, and the angular velocity
//! (velocity's `rot yes` and `zero angular`, fix momentum `angular`, the group functions
//! angmom(), inertia() and omega()). Sums run in the order of the arrays given.

use crate::engine::domain::Periods;

/// Threshold below which the inertia tensor is treated as singular (LAMMPS group.cpp).
const INERTIA_EPSILON: f64 = 1.0e-6;

/// `v -= omega x (u - cm)` for one atom at unwrapped position `u` (LAMMPS' zero_rotation and
/// fix momentum `angular`).
pub fn remove_rotation(v: &mut [f64; 3], u: [f64; 3], cm: [f64; 3], w: [f64; 3]) {
    let (dx, dy, dz) = (u[0] - cm[0], u[1] - cm[1], u[2] - cm[2]);
    v[0] -= w[1] * dz - w[2] * dy;
    v[1] -= w[2] * dx - w[0] * dz;
    v[2] -= w[0] * dy - w[1] * dx;
}

/// A group's centre of mass (unwrapped positions), angular momentum and inertia tensor about
/// it, summed in the order of the arrays (LAMMPS' Group::xcm, angmom and inertia).
pub struct GroupRotation {
    pub cm: [f64; 3],
    pub angmom: [f64; 3],
    pub inertia: [[f64; 3]; 3],
}

impl GroupRotation {
    /// Over the atoms `sel` marks (positions, image flags, masses, velocities `v`); None if the
    /// group has no mass. `reduce` sums partial sums over the ranks of a distributed run (as
    /// LAMMPS' MPI_Allreduce after each of mass, centre, angular momentum and inertia; a no-op
    /// on one rank).
    pub fn of(v: &[[f64; 3]], x: &[[f64; 3]], image: &[[i32; 3]], mass: &[f64], sel: &[bool], periods: Periods, reduce: &mut dyn FnMut(&mut [f64])) -> Option<GroupRotation> {
        let mut masstotal = [mass.iter().zip(sel).filter(|(_, &s)| s).fold(0.0, |t, (&m, _)| t + m)];
        reduce(&mut masstotal);
        let masstotal = masstotal[0];
        if masstotal <= 0.0 {
            return None;
        }
        let mut cm = [0.0; 3];
        for i in 0..v.len() {
            if sel[i] {
                let u = periods.unmap(x[i], image[i]);
                cm[0] += u[0] * mass[i];
                cm[1] += u[1] * mass[i];
                cm[2] += u[2] * mass[i];
            }
        }
        reduce(&mut cm);
        for c in &mut cm {
            *c /= masstotal;
        }
        let mut l = [0.0; 3];
        let mut inertia = [[0.0; 3]; 3];
        for i in 0..v.len() {
            if sel[i] {
                let u = periods.unmap(x[i], image[i]);
                let (dx, dy, dz) = (u[0] - cm[0], u[1] - cm[1], u[2] - cm[2]);
                let m = mass[i];
                l[0] += m * (dy * v[i][2] - dz * v[i][1]);
                l[1] += m * (dz * v[i][0] - dx * v[i][2]);
                l[2] += m * (dx * v[i][1] - dy * v[i][0]);
            }
        }
        for i in 0..v.len() {
            if sel[i] {
                let u = periods.unmap(x[i], image[i]);
                let (dx, dy, dz) = (u[0] - cm[0], u[1] - cm[1], u[2] - cm[2]);
                let m = mass[i];
                inertia[0][0] += m * (dy * dy + dz * dz);
                inertia[1][1] += m * (dx * dx + dz * dz);
                inertia[2][2] += m * (dx * dx + dy * dy);
                inertia[0][1] -= m * dx * dy;
                inertia[1][2] -= m * dy * dz;
                inertia[0][2] -= m * dx * dz;
            }
        }
        let mut sums = [l[0], l[1], l[2], inertia[0][0], inertia[1][1], inertia[2][2], inertia[0][1], inertia[1][2], inertia[0][2]];
        reduce(&mut sums);
        let [l0, l1, l2, ixx, iyy, izz, ixy, iyz, ixz] = sums;
        Some(GroupRotation { cm, angmom: [l0, l1, l2], inertia: [[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]] })
    }

    /// The angular velocity (LAMMPS' Group::omega).
    pub fn omega(&self) -> Result<[f64; 3], String> {
        omega(self.angmom, self.inertia)
    }
}

/// Angular velocity from angular momentum and inertia tensor (LAMMPS `Group::omega`):
/// the explicit inverse when the determinant is large enough, else the principal axes.
pub fn omega(l: [f64; 3], i: [[f64; 3]; 3]) -> Result<[f64; 3], String> {
    let det = i[0][0] * i[1][1] * i[2][2] + i[0][1] * i[1][2] * i[2][0] + i[0][2] * i[1][0] * i[2][1]
        - i[0][0] * i[1][2] * i[2][1]
        - i[0][1] * i[1][0] * i[2][2]
        - i[2][0] * i[1][1] * i[0][2];
    if det > INERTIA_EPSILON {
        let mut inv = [[0.0; 3]; 3];
        inv[0][0] = i[1][1] * i[2][2] - i[1][2] * i[2][1];
        inv[0][1] = -(i[0][1] * i[2][2] - i[0][2] * i[2][1]);
        inv[0][2] = i[0][1] * i[1][2] - i[0][2] * i[1][1];
        inv[1][0] = -(i[1][0] * i[2][2] - i[1][2] * i[2][0]);
        inv[1][1] = i[0][0] * i[2][2] - i[0][2] * i[2][0];
        inv[1][2] = -(i[0][0] * i[1][2] - i[0][2] * i[1][0]);
        inv[2][0] = i[1][0] * i[2][1] - i[1][1] * i[2][0];
        inv[2][1] = -(i[0][0] * i[2][1] - i[0][1] * i[2][0]);
        inv[2][2] = i[0][0] * i[1][1] - i[0][1] * i[1][0];
        for row in &mut inv {
            for c in row.iter_mut() {
                *c /= det;
            }
        }
        let mut w = [0.0; 3];
        for k in 0..3 {
            w[k] = inv[k][0] * l[0] + inv[k][1] * l[1] + inv[k][2] * l[2];
        }
        return Ok(w);
    }
    // Principal axes: columns of evec are ex, ey, ez (made right-handed).
    let (mut idiag, evec) = crate::engine::jacobi::jacobi3(&i, crate::engine::jacobi::Sort::Decreasing).ok_or("insufficient Jacobi rotations for the group's angular velocity")?;
    let ex = [evec[0][0], evec[1][0], evec[2][0]];
    let ey = [evec[0][1], evec[1][1], evec[2][1]];
    let mut ez = [evec[0][2], evec[1][2], evec[2][2]];
    let cross = [ex[1] * ey[2] - ex[2] * ey[1], ex[2] * ey[0] - ex[0] * ey[2], ex[0] * ey[1] - ex[1] * ey[0]];
    if cross[0] * ez[0] + cross[1] * ez[1] + cross[2] * ez[2] < 0.0 {
        ez = [-ez[0], -ez[1], -ez[2]];
    }
    let max = if idiag[0] > idiag[1] { idiag[0] } else { idiag[1] };
    let max = if max > idiag[2] { max } else { idiag[2] };
    for d in &mut idiag {
        if *d < INERTIA_EPSILON * max {
            *d = 0.0;
        }
    }
    // MathExtra::angmom_to_omega
    let axes = [ex, ey, ez];
    let mut wbody = [0.0; 3];
    for k in 0..3 {
        wbody[k] =
            if idiag[k] == 0.0 { 0.0 } else { (l[0] * axes[k][0] + l[1] * axes[k][1] + l[2] * axes[k][2]) / idiag[k] };
    }
    let mut w = [0.0; 3];
    for d in 0..3 {
        w[d] = wbody[0] * ex[d] + wbody[1] * ey[d] + wbody[2] * ez[d];
    }
    Ok(w)
}

/// The rotation of group `bit`: each rank's owned atoms summed in LAMMPS' local order, then
/// over the ranks; None for an empty group.
pub fn of_group(state: &crate::engine::state::State, bit: u32) -> Option<GroupRotation> {
    let a = &state.atoms;
    let order = state.lammps_order.indices(a.nlocal);
    let sel: Vec<usize> = order.iter().copied().filter(|&i| a.mask[i] & bit != 0).collect();
    let x: Vec<[f64; 3]> = sel.iter().map(|&i| a.x[i]).collect();
    let image: Vec<[i32; 3]> = sel.iter().map(|&i| a.image[i]).collect();
    let mass: Vec<f64> = sel.iter().map(|&i| state.mass(i)).collect();
    let v: Vec<[f64; 3]> = sel.iter().map(|&i| a.v[i]).collect();
    let periods = state.domain.as_ref().map_or(Periods::default(), |d| d.periods());
    GroupRotation::of(&v, &x, &image, &mass, &vec![true; sel.len()], periods, &mut |s| state.sum_ranks(s))
}
