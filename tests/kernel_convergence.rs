//! Kernel convergence of the Poiseuille and Couette decks (`dmhs validate convergence`, issue 20):
//! the `--quick` study (N = 20, 40 under the rising rule h/dx = 2.6 (N/10)^(1/3), a few seconds in
//! a release build) and the full one (`-- --ignored`, about 3 minutes on 2 cores).

use dmhs::models::pair::sph::Kernel;
use dmhs::tools::validate_convergence::{checks, lattice_moment, study, Rule, KERNELS};

#[test]
fn quick_study_error_falls_with_n_for_every_kernel() {
    let points = study(true, &|_| {}).unwrap();
    assert_eq!(points.len(), 2 * 3 * 2);
    let cs = checks(&points);
    assert_eq!(cs.len(), 6);
    for c in &cs {
        assert!(c.pass(), "{} {} >= {}", c.name, c.value, c.limit);
    }
    for p in &points {
        assert_eq!(p.rule, Rule::Rising);
        assert!(p.l2.is_finite() && p.linf >= p.l2 * 0.5, "{p:?}");
        // the wall offset grows with h/dx (0.12-0.34 dx at h/dx = 3.3-4.1)
        assert!(p.offset > 0.1 && p.offset < 0.4, "{p:?}");
        if p.case == "poiseuille" {
            // the fitted curvature's moment is within 1 % of 1, as the lattice moment
            assert!((p.moment_fit - 1.0).abs() < 1e-2, "{p:?}");
        }
    }
    // measured values (deterministic at any thread count)
    let l2 = |case: &str, k: Kernel, n: usize| points.iter().find(|p| p.case == case && p.kernel == k && p.n == n).unwrap().l2;
    assert!((l2("poiseuille", Kernel::Lucy, 40) - 4.5332e-2).abs() < 1e-6);
    assert!((l2("couette", Kernel::Wendland2, 40) - 5.6147e-3).abs() < 1e-7);
}

#[test]
fn lattice_moment_falls_to_one_with_the_support() {
    for k in KERNELS {
        let err = |h: f64| (lattice_moment(k, h) - 1.0).abs();
        // at the rising rule's supports the moment is within 1.2 % of 1, and within 0.3 % from 4 dx
        assert!(err(3.276) < 0.012 && err(4.127) < 3e-3 && err(5.2) < 3e-3, "{}", k.name());
    }
}

/// The full study (the numbers and charts of docs/validation.md): about 3 minutes.
#[test]
#[ignore]
fn full_study() {
    let points = study(false, &|_| {}).unwrap();
    assert_eq!(points.len(), 2 * 4 * 3 * 4);
    for c in checks(&points) {
        assert!(c.pass(), "{} {} >= {}", c.name, c.value, c.limit);
    }
    // at fixed h/dx = 3 and 4 the error is first order in dx for every kernel (Linf, 40 -> 80)
    for p in points.iter().filter(|p| p.n == 80 && matches!(p.rule, Rule::Fixed(h) if h >= 3.0)) {
        let q = points.iter().find(|q| q.case == p.case && q.rule == p.rule && q.kernel == p.kernel && q.n == 40).unwrap();
        let order = (q.linf / p.linf).log2();
        assert!(order > 0.7, "{p:?} order {order}");
    }
}
