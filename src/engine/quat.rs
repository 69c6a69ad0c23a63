//! Quaternion arithmetic of LAMMPS' MathExtra, in its order of operations (so orientations
//! integrated here have LAMMPS' bits). A quaternion is (w, i, j, k).

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
