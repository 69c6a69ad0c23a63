//! Quaternion arithmetic of LAMMPS' MathExtra, in its order of operations (so orientations
//! integrated here have LAMMPS' bits). A quaternion is (w, i, j, k). The functions a lane
//! kernel uses (bpm/rotational's) are written over [`Real`], for one value or a batch.

use crate::engine::par::lanes::Real;

pub type Quat = [f64; 4];

/// `vecquat`: the product (0, a) * b.
#[inline]
pub fn vecquat(a: &[f64; 3], b: &Quat) -> Quat {
    [
        -a[0] * b[1] - a[1] * b[2] - a[2] * b[3],
        b[0] * a[0] + a[1] * b[3] - a[2] * b[2],
        b[0] * a[1] + a[2] * b[1] - a[0] * b[3],
        b[0] * a[2] + a[0] * b[2] - a[1] * b[1],
    ]
}

/// `qnormalize`: scale to unit length (one reciprocal, four products).
#[inline]
pub fn qnormalize(q: &mut Quat) {
    let norm = 1.0 / (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt();
    for c in q.iter_mut() {
        *c *= norm;
    }
}

/// The end of both Richardson updates: the second half step from `qhalf` with `w`, then
/// q = 2 q_half - q_full, renormalised.
fn second_half_and_extrapolate(q: &mut Quat, qfull: &Quat, mut qhalf: Quat, w: &[f64; 3], dtq: f64) {
    let wq = vecquat(w, &qhalf);
    for c in 0..4 {
        qhalf[c] += 0.5 * dtq * wq[c];
    }
    qnormalize(&mut qhalf);
    for c in 0..4 {
        q[c] = 2.0 * qhalf[c] - qfull[c];
    }
    qnormalize(q);
}

/// `richardson_sphere`: advance the orientation of a sphere by dq/dt = 1/2 w q over `dtq`
/// (callers pass half the time step, as LAMMPS does): a full Euler step and two half steps,
/// combined by Richardson extrapolation and renormalised.
pub fn richardson_sphere(q: &mut Quat, w: &[f64; 3], dtq: f64) {
    let wq = vecquat(w, q);
    let mut qfull = [0.0; 4];
    let mut qhalf = [0.0; 4];
    for c in 0..4 {
        qfull[c] = q[c] + dtq * wq[c];
        qhalf[c] = q[c] + 0.5 * dtq * wq[c];
    }
    qnormalize(&mut qfull);
    qnormalize(&mut qhalf);
    second_half_and_extrapolate(q, &qfull, qhalf, w, dtq);
}

/// `axisangle_to_quat`: the rotation by `angle` about the unit vector `v`.
pub fn axisangle_to_quat(v: &[f64; 3], angle: f64) -> Quat {
    let halfa = 0.5 * angle;
    let sina = halfa.sin();
    [halfa.cos(), v[0] * sina, v[1] * sina, v[2] * sina]
}

/// `quat_to_mat`: the rotation matrix of a unit quaternion (rows).
pub fn quat_to_mat(q: &Quat) -> [[f64; 3]; 3] {
    let w2 = q[0] * q[0];
    let i2 = q[1] * q[1];
    let j2 = q[2] * q[2];
    let k2 = q[3] * q[3];
    let twoij = 2.0 * q[1] * q[2];
    let twoik = 2.0 * q[1] * q[3];
    let twojk = 2.0 * q[2] * q[3];
    let twoiw = 2.0 * q[1] * q[0];
    let twojw = 2.0 * q[2] * q[0];
    let twokw = 2.0 * q[3] * q[0];
    [
        [w2 + i2 - j2 - k2, twoij - twokw, twojw + twoik],
        [twoij + twokw, w2 - i2 + j2 - k2, twojk - twoiw],
        [twoik - twojw, twojk + twoiw, w2 - i2 - j2 + k2],
    ]
}

/// `matvec`: m v.
pub fn matvec(m: &[[f64; 3]; 3], v: &[f64; 3]) -> [f64; 3] {
    [
        m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
        m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
        m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2],
    ]
}

/// `norm3`: scale a vector to unit length (one reciprocal, three products); a zero vector
/// stays zero.
#[inline]
pub fn norm3<T: Real>(v: &mut [T; 3]) {
    let val = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    let nonzero = T::splat(0.0).lt(val);
    let scale = T::splat(1.0) / val.sqrt();
    for c in v.iter_mut() {
        *c = T::select(nonzero, *c * scale, *c);
    }
}

/// `cross3`: a x b.
#[inline]
pub fn cross3<T: Real>(a: &[T; 3], b: &[T; 3]) -> [T; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// `qconjugate`: the inverse of a unit quaternion.
#[inline]
pub fn qconjugate<T: Real>(q: &[T; 4]) -> [T; 4] {
    [q[0], -q[1], -q[2], -q[3]]
}

/// `quatquat`: the product a * b.
#[inline]
pub fn quatquat<T: Real>(a: &[T; 4], b: &[T; 4]) -> [T; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + b[0] * a[1] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] + b[0] * a[2] + a[3] * b[1] - a[1] * b[3],
        a[0] * b[3] + b[0] * a[3] + a[1] * b[2] - a[2] * b[1],
    ]
}

/// `quatrotvec`: the vector v rotated by q, q (0, v) q* (the product with (0, v) first).
#[inline]
pub fn quatrotvec<T: Real>(q: &[T; 4], v: &[T; 3]) -> [T; 3] {
    let t = [
        -q[1] * v[0] - q[2] * v[1] - q[3] * v[2],
        q[0] * v[0] + q[2] * v[2] - q[3] * v[1],
        q[0] * v[1] + q[3] * v[0] - q[1] * v[2],
        q[0] * v[2] + q[1] * v[1] - q[2] * v[0],
    ];
    [
        -q[1] * t[0] + q[0] * t[1] - q[3] * t[2] + q[2] * t[3],
        -q[2] * t[0] + q[3] * t[1] + q[0] * t[2] - q[1] * t[3],
        -q[3] * t[0] - q[2] * t[1] + q[1] * t[2] + q[0] * t[3],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_spin_about_z_turns_by_omega_t() {
        // w = (0, 0, 1), 1000 time steps of 1e-3 (dtq is half a step): a turn of 1 rad about z,
        // q = (cos 0.5, 0, 0, sin 0.5)
        let mut q = [1.0, 0.0, 0.0, 0.0];
        let w = [0.0, 0.0, 1.0];
        for _ in 0..1000 {
            richardson_sphere(&mut q, &w, 0.5 * 1e-3);
        }
        let half: f64 = 0.5;
        // to the scheme's accuracy (measured: 1e-8 behind)
        assert!((q[0] - half.cos()).abs() < 5e-8 && (q[3] - half.sin()).abs() < 5e-8, "{q:?}");
        assert!(q[1] == 0.0 && q[2] == 0.0);
        let n = q.iter().map(|c| c * c).sum::<f64>();
        assert!((n - 1.0).abs() < 1e-15);
    }

    #[test]
    fn vecquat_is_the_hamilton_product_with_a_pure_quaternion() {
        // (0, i) * (0, j) = (0, k); (0, i) * 1 = (0, i)
        assert_eq!(vecquat(&[1.0, 0.0, 0.0], &[0.0, 0.0, 1.0, 0.0]), [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(vecquat(&[1.0, 0.0, 0.0], &[1.0, 0.0, 0.0, 0.0]), [0.0, 1.0, 0.0, 0.0]);
    }
}

/// A point `x` turned about the axis through `point` with unit direction `runit`, by the angle
/// whose sine and cosine are given, in LAMMPS' order (fix move rotate, region rotate,
/// displace_atoms rotate): returns `c`, the projection of x - point on the axis, and `disp`, the
/// turned part perpendicular to it; the turned point is point + c + disp.
#[inline]
pub fn rotate_about_axis(point: &[f64; 3], runit: &[f64; 3], x: &[f64], sine: f64, cosine: f64) -> ([f64; 3], [f64; 3]) {
    let (p, u) = (point, runit);
    let d = [x[0] - p[0], x[1] - p[1], x[2] - p[2]];
    let ddotr = d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
    let c = [ddotr * u[0], ddotr * u[1], ddotr * u[2]];
    let a = [d[0] - c[0], d[1] - c[1], d[2] - c[2]];
    let b = [u[1] * a[2] - u[2] * a[1], u[2] * a[0] - u[0] * a[2], u[0] * a[1] - u[1] * a[0]];
    let disp = [a[0] * cosine + b[0] * sine, a[1] * cosine + b[1] * sine, a[2] * cosine + b[2] * sine];
    (c, disp)
}

/// `matvec(ex, ey, ez, v)`: P v with the columns ex, ey, ez of P (body to space frame).
#[inline]
pub fn matvec_cols(ex: &[f64; 3], ey: &[f64; 3], ez: &[f64; 3], v: &[f64; 3]) -> [f64; 3] {
    [
        ex[0] * v[0] + ey[0] * v[1] + ez[0] * v[2],
        ex[1] * v[0] + ey[1] * v[1] + ez[1] * v[2],
        ex[2] * v[0] + ey[2] * v[1] + ez[2] * v[2],
    ]
}

/// `transpose_matvec(ex, ey, ez, v)`: P^T v (space to body frame).
#[inline]
pub fn transpose_matvec_cols(ex: &[f64; 3], ey: &[f64; 3], ez: &[f64; 3], v: &[f64; 3]) -> [f64; 3] {
    [
        ex[0] * v[0] + ex[1] * v[1] + ex[2] * v[2],
        ey[0] * v[0] + ey[1] * v[1] + ey[2] * v[2],
        ez[0] * v[0] + ez[1] * v[1] + ez[2] * v[2],
    ]
}

/// `transpose_matvec(m, v)`: m^T v.
#[inline]
pub fn transpose_matvec(m: &[[f64; 3]; 3], v: &[f64; 3]) -> [f64; 3] {
    [
        m[0][0] * v[0] + m[1][0] * v[1] + m[2][0] * v[2],
        m[0][1] * v[0] + m[1][1] * v[1] + m[2][1] * v[2],
        m[0][2] * v[0] + m[1][2] * v[1] + m[2][2] * v[2],
    ]
}

/// `exyz_to_q`: the unit quaternion of the rotation whose columns are ex, ey, ez (from the
/// largest of its squared components).
pub fn exyz_to_q(ex: &[f64; 3], ey: &[f64; 3], ez: &[f64; 3]) -> Quat {
    let q0sq = 0.25 * (ex[0] + ey[1] + ez[2] + 1.0);
    let q1sq = q0sq - 0.5 * (ey[1] + ez[2]);
    let q2sq = q0sq - 0.5 * (ex[0] + ez[2]);
    let q3sq = q0sq - 0.5 * (ex[0] + ey[1]);
    let mut q = [0.0; 4];
    if q0sq >= 0.25 {
        q[0] = q0sq.sqrt();
        q[1] = (ey[2] - ez[1]) / (4.0 * q[0]);
        q[2] = (ez[0] - ex[2]) / (4.0 * q[0]);
        q[3] = (ex[1] - ey[0]) / (4.0 * q[0]);
    } else if q1sq >= 0.25 {
        q[1] = q1sq.sqrt();
        q[0] = (ey[2] - ez[1]) / (4.0 * q[1]);
        q[2] = (ey[0] + ex[1]) / (4.0 * q[1]);
        q[3] = (ex[2] + ez[0]) / (4.0 * q[1]);
    } else if q2sq >= 0.25 {
        q[2] = q2sq.sqrt();
        q[0] = (ez[0] - ex[2]) / (4.0 * q[2]);
        q[1] = (ey[0] + ex[1]) / (4.0 * q[2]);
        q[3] = (ez[1] + ey[2]) / (4.0 * q[2]);
    } else if q3sq >= 0.25 {
        q[3] = q3sq.sqrt();
        q[0] = (ex[1] - ey[0]) / (4.0 * q[3]);
        q[1] = (ez[0] + ex[2]) / (4.0 * q[3]);
        q[2] = (ez[1] + ey[2]) / (4.0 * q[3]);
    }
    qnormalize(&mut q);
    q
}

/// `q_to_exyz`: the space-frame principal axes of orientation q.
pub fn q_to_exyz(q: &Quat) -> [[f64; 3]; 3] {
    [
        [q[0] * q[0] + q[1] * q[1] - q[2] * q[2] - q[3] * q[3], 2.0 * (q[1] * q[2] + q[0] * q[3]), 2.0 * (q[1] * q[3] - q[0] * q[2])],
        [2.0 * (q[1] * q[2] - q[0] * q[3]), q[0] * q[0] - q[1] * q[1] + q[2] * q[2] - q[3] * q[3], 2.0 * (q[2] * q[3] + q[0] * q[1])],
        [2.0 * (q[1] * q[3] + q[0] * q[2]), 2.0 * (q[2] * q[3] - q[0] * q[1]), q[0] * q[0] - q[1] * q[1] - q[2] * q[2] + q[3] * q[3]],
    ]
}

/// `angmom_to_omega`: space-frame angular velocity from angular momentum m, principal axes
/// ex, ey, ez and principal moments idiag (a zero moment gives no spin about its axis).
pub fn angmom_to_omega(m: &[f64; 3], ex: &[f64; 3], ey: &[f64; 3], ez: &[f64; 3], idiag: &[f64; 3]) -> [f64; 3] {
    let comp = |e: &[f64; 3], i: f64| if i == 0.0 { 0.0 } else { (m[0] * e[0] + m[1] * e[1] + m[2] * e[2]) / i };
    let wbody = [comp(ex, idiag[0]), comp(ey, idiag[1]), comp(ez, idiag[2])];
    [
        wbody[0] * ex[0] + wbody[1] * ey[0] + wbody[2] * ez[0],
        wbody[0] * ex[1] + wbody[1] * ey[1] + wbody[2] * ez[1],
        wbody[0] * ex[2] + wbody[1] * ey[2] + wbody[2] * ez[2],
    ]
}

/// `mq_to_omega`: angular velocity from angular momentum m at orientation q.
pub fn mq_to_omega(m: &[f64; 3], q: &Quat, moments: &[f64; 3]) -> [f64; 3] {
    let rot = quat_to_mat(q);
    let mut wbody = transpose_matvec(&rot, m);
    for k in 0..3 {
        if moments[k] == 0.0 {
            wbody[k] = 0.0;
        } else {
            wbody[k] /= moments[k];
        }
    }
    matvec(&rot, &wbody)
}

/// `richardson`: advance the orientation of a rigid body by dq/dt = 1/2 w q over `dtq`,
/// omega re-evaluated from the angular momentum at the half step; `w` becomes that omega.
pub fn richardson(q: &mut Quat, m: &[f64; 3], w: &mut [f64; 3], moments: &[f64; 3], dtq: f64) {
    let wq = vecquat(w, q);
    let mut qfull = [0.0; 4];
    let mut qhalf = [0.0; 4];
    for c in 0..4 {
        qfull[c] = q[c] + dtq * wq[c];
    }
    qnormalize(&mut qfull);
    for c in 0..4 {
        qhalf[c] = q[c] + 0.5 * dtq * wq[c];
    }
    qnormalize(&mut qhalf);
    *w = mq_to_omega(m, &qhalf, moments);
    second_half_and_extrapolate(q, &qfull, qhalf, w, dtq);
}

/// `quatvec`: the product a * (0, b).
pub fn quatvec(a: &Quat, b: &[f64; 3]) -> Quat {
    [
        -a[1] * b[0] - a[2] * b[1] - a[3] * b[2],
        a[0] * b[0] + a[2] * b[2] - a[3] * b[1],
        a[0] * b[1] + a[3] * b[0] - a[1] * b[2],
        a[0] * b[2] + a[1] * b[1] - a[2] * b[0],
    ]
}

/// `invquatvec`: the vector part of inv(a) * b for a four-component b.
pub fn invquatvec(a: &Quat, b: &Quat) -> [f64; 3] {
    [
        -a[1] * b[0] + a[0] * b[1] + a[3] * b[2] - a[2] * b[3],
        -a[2] * b[0] - a[3] * b[1] + a[0] * b[2] + a[1] * b[3],
        -a[3] * b[0] + a[2] * b[1] - a[1] * b[2] + a[0] * b[3],
    ]
}

/// `no_squish_rotate`: the free rotation about body axis k (1, 2, 3) over `dt` of the
/// orientation q and its conjugate momentum p (Miller et al. 2002); a zero moment does not turn.
pub fn no_squish_rotate(k: usize, p: &mut Quat, q: &mut Quat, inertia: &[f64; 3], dt: f64) {
    // the permutation P_k applied to p and q
    let perm = |v: &Quat| -> Quat {
        match k {
            1 => [-v[1], v[0], v[3], -v[2]],
            2 => [-v[2], -v[3], v[0], v[1]],
            _ => [-v[3], v[2], -v[1], v[0]],
        }
    };
    let (kp, kq) = (perm(p), perm(q));
    let mut phi = p[0] * kq[0] + p[1] * kq[1] + p[2] * kq[2] + p[3] * kq[3];
    if inertia[k - 1] == 0.0 {
        phi = 0.0;
    } else {
        phi /= 4.0 * inertia[k - 1];
    }
    let (c_phi, s_phi) = ((dt * phi).cos(), (dt * phi).sin());
    for c in 0..4 {
        p[c] = c_phi * p[c] + s_phi * kp[c];
    }
    for c in 0..4 {
        q[c] = c_phi * q[c] + s_phi * kq[c];
    }
}
