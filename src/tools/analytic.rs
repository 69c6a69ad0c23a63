//! Analytic and experimental references for the SPH validation cases (`dmhs validate`):
//! Poiseuille and Couette flow start-up (Fourier series), 1D heat conduction (erf), the
//! hydrostatic pressure of a Tait fluid column, Martin & Moyce's dam-break surge-front data, and the
//! exact Riemann solution of an ideal gas (the Sod shock tube).

use std::f64::consts::PI;

/// Terms of a sine series are added until they fall below this fraction of the steady value.
const SERIES_TOL: f64 = 1e-17;
/// Hard cap on the number of series terms (only reached at t = 0 exactly).
const SERIES_MAX_TERMS: usize = 100_000;

/// Plane Poiseuille flow started from rest: plates at y = 0 and y = `l`, a body acceleration `f`
/// along x switched on at t = 0, kinematic viscosity `nu`. Velocity u(y, t) along x
/// (Morris, Fox & Zhu 1997, eq. 21, with y measured from the lower plate):
///
///   u = f y (l - y) / (2 nu) - sum_{n odd} 4 f l^2 / (nu pi^3 n^3) sin(n pi y / l) exp(-n^2 pi^2 nu t / l^2)
pub fn poiseuille_startup(y: f64, t: f64, l: f64, f: f64, nu: f64) -> f64 {
    let steady = f * y * (l - y) / (2.0 * nu);
    let scale = f * l * l / (8.0 * nu); // the centre-line speed
    let mut u = steady;
    let mut n = 1usize;
    while n < 2 * SERIES_MAX_TERMS {
        let nf = n as f64;
        let decay = (-nf * nf * PI * PI * nu * t / (l * l)).exp();
        let amp = 4.0 * f * l * l / (nu * PI.powi(3) * nf.powi(3));
        let term = amp * (nf * PI * y / l).sin() * decay;
        u -= term;
        if amp * decay < SERIES_TOL * scale {
            break;
        }
        n += 2;
    }
    u
}

/// Plane Couette flow started from rest: the plate at y = 0 stays, the plate at y = `l` moves at
/// `u_wall` along x from t = 0 on.
///
///   u = u_wall y / l + sum_{n >= 1} 2 u_wall (-1)^n / (n pi) sin(n pi y / l) exp(-n^2 pi^2 nu t / l^2)
pub fn couette_startup(y: f64, t: f64, l: f64, u_wall: f64, nu: f64) -> f64 {
    let mut u = u_wall * y / l;
    for n in 1..=SERIES_MAX_TERMS {
        let nf = n as f64;
        let decay = (-nf * nf * PI * PI * nu * t / (l * l)).exp();
        let amp = 2.0 * u_wall / (nf * PI);
        let sign = if n % 2 == 0 { 1.0 } else { -1.0 };
        u += sign * amp * (nf * PI * y / l).sin() * decay;
        if amp * decay < SERIES_TOL * u_wall.abs() {
            break;
        }
    }
    u
}

/// The error function, to about 1e-15 absolute. For |x| < 6 the series
/// erf x = 2/sqrt(pi) exp(-x^2) sum_n 2^n x^(2n+1) / (1 3 5 ... (2n+1)) (all terms positive, so
/// no cancellation); beyond, erf x = +-1 to double precision (erfc 6 = 2e-17).
pub fn erf(x: f64) -> f64 {
    if x.is_nan() {
        return x;
    }
    let a = x.abs();
    if a >= 6.0 {
        return x.signum();
    }
    let mut term = a;
    let mut sum = a;
    let mut k = 0.0;
    while term > 1e-17 * sum {
        k += 1.0;
        term *= 2.0 * a * a / (2.0 * k + 1.0);
        sum += term;
    }
    let v = 2.0 / PI.sqrt() * (-a * a).exp() * sum;
    v.min(1.0).copysign(x)
}

/// Two half-spaces in contact from t = 0: temperature `t_left` for x < 0 and `t_right` for x > 0,
/// diffusivity `d` (de/dt = d lap e, as sph/heatconduction's `D`).
///
///   T(x, t) = t_left + (t_right - t_left) (1 + erf(x / (2 sqrt(d t)))) / 2
pub fn heat_half_spaces(x: f64, t: f64, d: f64, t_left: f64, t_right: f64) -> f64 {
    let s = if t > 0.0 { erf(x / (2.0 * (d * t).sqrt())) } else { x.signum() };
    t_left + (t_right - t_left) * 0.5 * (1.0 + s)
}

/// A column of Tait fluid (P = B ((rho/rho0)^7 - 1), B = c^2 rho0 / 7) at rest under gravity `g`,
/// on a floor at y = 0, holding the mass of a column of height `h0` at density `rho0`.
/// dP/dy = -rho g with rho = rho0 (1 + P/B)^(1/7) integrates from the free surface y_s down to
/// (rho/rho0)^6 = 1 + k (y_s - y), k = (6/7) rho0 g / B.
#[derive(Clone, Copy, Debug)]
pub struct TaitColumn {
    pub rho0: f64,
    pub b: f64,
    pub k: f64,
    /// Height of the free surface (below `h0`: the fluid is compressed).
    pub surface: f64,
}

impl TaitColumn {
    pub fn new(h0: f64, rho0: f64, c: f64, g: f64) -> TaitColumn {
        let b = c * c * rho0 / 7.0;
        let k = 6.0 / 7.0 * rho0 * g / b;
        // mass: int_0^ys rho dy = rho0 ((1 + k ys)^(7/6) - 1) / (7k/6) = rho0 h0
        let surface = ((1.0 + 7.0 * k * h0 / 6.0).powf(6.0 / 7.0) - 1.0) / k;
        TaitColumn { rho0, b, k, surface }
    }
    /// Pressure at height y (0 above the surface).
    pub fn pressure(&self, y: f64) -> f64 {
        let s = (self.surface - y).max(0.0);
        self.b * ((1.0 + self.k * s).powf(7.0 / 6.0) - 1.0)
    }
    /// Density at height y (rho0 at and above the surface).
    pub fn density(&self, y: f64) -> f64 {
        let s = (self.surface - y).max(0.0);
        self.rho0 * (1.0 + self.k * s).powf(1.0 / 6.0)
    }
    /// The Tait equation of state with this column's constants.
    pub fn pressure_of_density(&self, rho: f64) -> f64 {
        self.b * ((rho / self.rho0).powi(7) - 1.0)
    }
}

/// Martin & Moyce (1952) surge-front data for a column of width a and height 2a (n^2 = 2):
/// (T = t sqrt(2 g / a), Z = z / a), z the front position measured from the back wall.
///
/// J. C. Martin and W. J. Moyce, "Part IV. An experimental study of the collapse of liquid
/// columns on a rigid horizontal plane", Phil. Trans. R. Soc. Lond. A 244 (882), 312-324 (1952),
/// Figure 3. Values as digitised in PySPH's `pysph/examples/db_exp_data.py` (mm_data_2 and
/// mm_data_1); columns of a = 2.25 in and a = 1.125 in respectively.
pub const MARTIN_MOYCE_A225: [(f64, f64); 15] = [
    (0.832, 1.217),
    (1.219, 1.474),
    (1.997, 2.292),
    (2.547, 2.995),
    (3.345, 4.134),
    (4.034, 4.944),
    (4.418, 5.881),
    (5.091, 6.980),
    (5.685, 7.945),
    (6.306, 8.966),
    (6.822, 9.986),
    (7.439, 10.963),
    (8.031, 11.977),
    (8.633, 13.005),
    (9.237, 13.970),
];

/// As [`MARTIN_MOYCE_A225`], the column of a = 1.125 in.
pub const MARTIN_MOYCE_A1125: [(f64, f64); 10] = [
    (0.849, 1.245),
    (1.212, 1.443),
    (1.602, 1.884),
    (2.283, 2.689),
    (2.950, 3.728),
    (3.598, 4.528),
    (3.905, 4.999),
    (4.592, 5.841),
    (4.961, 6.271),
    (5.316, 6.717),
];

/// Linear interpolation of y(x) in a table sorted by x; None outside it.
pub fn interpolate(table: &[(f64, f64)], x: f64) -> Option<f64> {
    let k = table.windows(2).position(|w| w[0].0 <= x && x <= w[1].0)?;
    let ((x0, y0), (x1, y1)) = (table[k], table[k + 1]);
    if x1 == x0 {
        return Some(y0);
    }
    Some(y0 + (y1 - y0) * (x - x0) / (x1 - x0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn erf_known_values() {
        // reference values of erf (Abramowitz & Stegun table 7.1 / high-precision tables)
        for (x, v) in [
            (0.0, 0.0),
            (0.1, 0.1124629160182849),
            (0.5, 0.5204998778130465),
            (1.0, 0.8427007929497149),
            (2.0, 0.9953222650189527),
            (3.0, 0.9999779095030014),
            (4.0, 0.9999999845827421),
        ] {
            assert!(close(erf(x), v, 2e-15), "erf({x}) = {} != {v}", erf(x));
            assert!(close(erf(-x), -v, 2e-15));
        }
        assert_eq!(erf(7.0), 1.0);
        assert_eq!(erf(-7.0), -1.0);
    }

    #[test]
    fn poiseuille_limits() {
        let (l, f, nu) = (1e-3, 2e-4, 1e-6);
        // at rest at t = 0 (the series converges slowly there: 1e-7 of vmax)
        assert!(poiseuille_startup(0.5e-3, 0.0, l, f, nu).abs() < 1e-7 * 2.5e-5);
        // steady centre-line speed f l^2 / (8 nu) = 2.5e-5
        assert!(close(poiseuille_startup(0.5e-3, 10.0, l, f, nu), 2.5e-5, 1e-18));
        // zero at the plates at all times
        assert!(poiseuille_startup(0.0, 0.05, l, f, nu).abs() < 1e-20);
        // early times: the core accelerates freely, u = f t, away from the plates
        let t = 1e-3; // diffusion length sqrt(nu t) = 3e-5 << l / 2
        assert!(close(poiseuille_startup(0.5e-3, t, l, f, nu), f * t, 1e-12 * f * t));
        // symmetric about the centre line
        let a = poiseuille_startup(0.2e-3, 0.1, l, f, nu);
        let b = poiseuille_startup(0.8e-3, 0.1, l, f, nu);
        assert!(close(a, b, 1e-20));
        // late times: one mode is left (the next, n = 3, has decayed by exp(-8 pi^2 0.2) = 1e-7)
        let one_mode = 2.5e-5 - 4.0 * f * l * l / (nu * PI.powi(3)) * (-PI * PI * 0.2).exp();
        let full = poiseuille_startup(0.5e-3, 0.2, l, f, nu);
        assert!((full - one_mode).abs() < 1e-8 * 2.5e-5, "{full} vs {one_mode}");
    }

    #[test]
    fn poiseuille_solves_the_equation() {
        // u_t = nu u_yy + f, by finite differences of the series
        let (l, f, nu) = (1e-3, 2e-4, 1e-6);
        let (y, t, dy, dt) = (0.3e-3, 0.05, 1e-6, 1e-5);
        let u = |y: f64, t: f64| poiseuille_startup(y, t, l, f, nu);
        let ut = (u(y, t + dt) - u(y, t - dt)) / (2.0 * dt);
        let uyy = (u(y + dy, t) - 2.0 * u(y, t) + u(y - dy, t)) / (dy * dy);
        assert!((ut - (nu * uyy + f)).abs() < 1e-6 * f, "{ut} vs {}", nu * uyy + f);
    }

    #[test]
    fn couette_limits_and_equation() {
        let (l, uw, nu) = (1e-3, 2.5e-5, 1e-6);
        assert!(close(couette_startup(0.25e-3, 10.0, l, uw, nu), 0.25 * uw, 1e-18));
        assert!(couette_startup(0.0, 0.1, l, uw, nu).abs() < 1e-20);
        // the moving plate itself (sin(n pi) = 0 to rounding)
        assert!(close(couette_startup(l, 0.1, l, uw, nu), uw, 1e-12 * uw));
        // at the mid plane the series is exactly the alternating even terms; early on the fluid
        // away from the moving plate is still at rest
        assert!(couette_startup(0.5e-3, 1e-3, l, uw, nu).abs() < 1e-10 * uw);
        let u = |y: f64, t: f64| couette_startup(y, t, l, uw, nu);
        let (y, t, dy, dt) = (0.6e-3, 0.03, 1e-6, 1e-5);
        let ut = (u(y, t + dt) - u(y, t - dt)) / (2.0 * dt);
        let uyy = (u(y + dy, t) - 2.0 * u(y, t) + u(y - dy, t)) / (dy * dy);
        assert!((ut - nu * uyy).abs() < 1e-6 * uw / 0.1, "{ut} vs {}", nu * uyy);
    }

    #[test]
    fn heat_half_spaces_values() {
        assert_eq!(heat_half_spaces(0.0, 1.0, 1e-3, 1.0, 0.0), 0.5);
        // x = 2 sqrt(D t) -> erf(1)
        let d: f64 = 1e-3;
        let t = 2.5;
        let x = 2.0 * (d * t).sqrt();
        assert!(close(heat_half_spaces(x, t, d, 1.0, 0.0), 0.5 * (1.0 - 0.8427007929497149), 1e-15));
        assert!(close(heat_half_spaces(-x, t, d, 1.0, 0.0), 0.5 * (1.0 + 0.8427007929497149), 1e-15));
        assert_eq!(heat_half_spaces(-0.1, 0.0, d, 1.0, 0.0), 1.0);
        assert_eq!(heat_half_spaces(0.1, 0.0, d, 1.0, 0.0), 0.0);
    }

    #[test]
    fn tait_column_mass_and_balance() {
        let col = TaitColumn::new(1.0, 1000.0, 20.0, 9.81);
        // compressed: the surface is below h0
        assert!(col.surface < 1.0 && col.surface > 0.98, "{}", col.surface);
        assert_eq!(col.pressure(col.surface), 0.0);
        assert_eq!(col.pressure(2.0), 0.0);
        // mass conservation by quadrature (midpoint, 1e5 cells)
        let n = 100_000;
        let dy = col.surface / n as f64;
        let mass: f64 = (0..n).map(|i| col.density((i as f64 + 0.5) * dy) * dy).sum();
        assert!((mass - 1000.0).abs() < 1e-6, "{mass}");
        // hydrostatic balance dP/dy = -rho g
        let (y, e) = (0.4, 1e-5);
        let dpdy = (col.pressure(y + e) - col.pressure(y - e)) / (2.0 * e);
        assert!((dpdy + col.density(y) * 9.81).abs() < 1e-4, "{dpdy}");
        // EOS consistent
        assert!((col.pressure_of_density(col.density(0.3)) - col.pressure(0.3)).abs() < 1e-8);
        // incompressible limit: rho0 g (h0 - y)
        let stiff = TaitColumn::new(1.0, 1000.0, 1e4, 9.81);
        assert!((stiff.pressure(0.0) - 9810.0).abs() < 0.01, "{}", stiff.pressure(0.0));
    }

    #[test]
    fn martin_moyce_tables() {
        for t in [&MARTIN_MOYCE_A225[..], &MARTIN_MOYCE_A1125[..]] {
            assert!(t.windows(2).all(|w| w[0].0 < w[1].0 && w[0].1 < w[1].1));
        }
        assert_eq!(interpolate(&MARTIN_MOYCE_A225, 0.832), Some(1.217));
        assert!(close(interpolate(&MARTIN_MOYCE_A225, 1.0255).unwrap(), (1.217 + 1.474) / 2.0, 1e-12));
        assert_eq!(interpolate(&MARTIN_MOYCE_A225, 0.5), None);
    }
}

/// Two-phase Stefan problem (Neumann's solution): a liquid at `t_init` above the melting point
/// `t_melt` fills x > 0 and solidifies from a wall held at `t_wall` < `t_melt` at x = 0. The
/// front is X(t) = 2 lambda sqrt(alpha_s t), lambda the root of
///   exp(-l^2)/erf(l) - (k_l/k_s) sqrt(a_s/a_l) (T_i - T_m)/(T_m - T_w) exp(-l^2 a_s/a_l)/erfc(l sqrt(a_s/a_l))
///     = l sqrt(pi) L/(c_s (T_m - T_w)),
/// with a = k/(rho c). Returns lambda (bisection to round-off).
#[allow(clippy::too_many_arguments)]
pub fn stefan_lambda(rho: f64, k_s: f64, c_s: f64, k_l: f64, c_l: f64, latent: f64, t_wall: f64, t_melt: f64, t_init: f64) -> f64 {
    let (a_s, a_l) = (k_s / (rho * c_s), k_l / (rho * c_l));
    let r = (a_s / a_l).sqrt();
    let f = |l: f64| {
        (-l * l).exp() / erf(l) - (k_l / k_s) * r * (t_init - t_melt) / (t_melt - t_wall) * (-l * l * r * r).exp() / (1.0 - erf(l * r))
            - l * PI.sqrt() * latent / (c_s * (t_melt - t_wall))
    };
    let (mut lo, mut hi) = (1e-9, 5.0);
    for _ in 0..200 {
        let m = 0.5 * (lo + hi);
        if f(m) > 0.0 {
            lo = m;
        } else {
            hi = m;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod stefan_tests {
    #[test]
    fn stefan_lambda_limits() {
        // one-phase limit (liquid at T_m): lambda exp(l^2) erf(l) = St/sqrt(pi); St = 1 -> 0.6201
        let l = super::stefan_lambda(1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 0.0, 1.0, 1.0);
        assert!((l * (l * l).exp() * super::erf(l) - 1.0 / std::f64::consts::PI.sqrt()).abs() < 1e-12);
        assert!((l - 0.6200633).abs() < 1e-6, "{l}");
        // the paper's casting values with T_i = 100 (examples/heat/in.stefan)
        let l = super::stefan_lambda(1000.0, 1.0, 2.0, 1.0, 1.0, 50.0, 0.0, 25.0, 100.0);
        assert!((l - 0.27301889799).abs() < 1e-9, "{l}");
    }
}

/// A state of an ideal gas in one dimension: density, velocity, pressure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GasState {
    pub rho: f64,
    pub u: f64,
    pub p: f64,
}

/// The exact solution of the Riemann problem of an ideal gas (Toro, "Riemann Solvers and
/// Numerical Methods for Fluid Dynamics", ch. 4): `left` for x < x0 and `right` for x > x0 at
/// t = 0, ratio of specific heats `gamma`. [`Riemann::sample`] gives the state at (x, t).
#[derive(Clone, Copy, Debug)]
pub struct Riemann {
    pub left: GasState,
    pub right: GasState,
    pub gamma: f64,
    pub x0: f64,
    /// Pressure and velocity of the star region between the two waves.
    pub p_star: f64,
    pub u_star: f64,
}

impl Riemann {
    pub fn new(left: GasState, right: GasState, gamma: f64, x0: f64) -> Riemann {
        let g = gamma;
        let sound = |s: &GasState| (g * s.p / s.rho).sqrt();
        let (cl, cr) = (sound(&left), sound(&right));
        // f_K(p) and its derivative: shock (p > p_K) or rarefaction (p <= p_K) branch
        let f = |p: f64, s: &GasState, c: f64| -> (f64, f64) {
            if p > s.p {
                let a = 2.0 / ((g + 1.0) * s.rho);
                let b = (g - 1.0) / (g + 1.0) * s.p;
                let q = (a / (p + b)).sqrt();
                ((p - s.p) * q, q * (1.0 - 0.5 * (p - s.p) / (b + p)))
            } else {
                let e = (g - 1.0) / (2.0 * g);
                let r = (p / s.p).powf(e);
                (2.0 * c / (g - 1.0) * (r - 1.0), r / (s.rho * c) * (s.p / p))
            }
        };
        // Newton from the two-rarefaction guess, p kept positive
        let e = (g - 1.0) / (2.0 * g);
        let du = right.u - left.u;
        let mut p = ((cl + cr - 0.5 * (g - 1.0) * du) / (cl / left.p.powf(e) + cr / right.p.powf(e))).powf(1.0 / e).max(1e-12);
        for _ in 0..100 {
            let ((fl, dl), (fr, dr)) = (f(p, &left, cl), f(p, &right, cr));
            let next = (p - (fl + fr + du) / (dl + dr)).max(1e-14);
            let done = (next - p).abs() <= 1e-15 * (next + p);
            p = next;
            if done {
                break;
            }
        }
        let u = 0.5 * (left.u + right.u) + 0.5 * (f(p, &right, cr).0 - f(p, &left, cl).0);
        Riemann { left, right, gamma, x0, p_star: p, u_star: u }
    }

    /// The state at position x and time t > 0.
    pub fn sample(&self, x: f64, t: f64) -> GasState {
        let g = self.gamma;
        let s = (x - self.x0) / t;
        let (ps, us) = (self.p_star, self.u_star);
        // mirror the right side onto the left: the same formulas with u -> -u
        let (k, sign, s) = if s <= us { (self.left, 1.0, s) } else { (self.right, -1.0, -s) };
        let (u_k, us) = (sign * k.u, sign * us);
        let c = (g * k.p / k.rho).sqrt();
        let state = |rho: f64, u: f64, p: f64| GasState { rho, u: sign * u, p };
        if ps > k.p {
            // shock moving away from the contact
            let r = ps / k.p;
            let gm = (g - 1.0) / (g + 1.0);
            let speed = u_k - c * ((g + 1.0) / (2.0 * g) * r + (g - 1.0) / (2.0 * g)).sqrt();
            if s < speed { state(k.rho, u_k, k.p) } else { state(k.rho * (r + gm) / (gm * r + 1.0), us, ps) }
        } else {
            let c_star = c * (ps / k.p).powf((g - 1.0) / (2.0 * g));
            let (head, tail) = (u_k - c, us - c_star);
            if s < head {
                state(k.rho, u_k, k.p)
            } else if s > tail {
                state(k.rho * (ps / k.p).powf(1.0 / g), us, ps)
            } else {
                // inside the fan
                let f = 2.0 / (g + 1.0) + (g - 1.0) / ((g + 1.0) * c) * (u_k - s);
                state(k.rho * f.powf(2.0 / (g - 1.0)), 2.0 / (g + 1.0) * (c + 0.5 * (g - 1.0) * u_k + s), k.p * f.powf(2.0 * g / (g - 1.0)))
            }
        }
    }
}

#[cfg(test)]
mod riemann_tests {
    use super::*;

    #[test]
    fn sod_star_state_is_toros() {
        // Toro's test 1 (Sod): p* = 0.30313, u* = 0.92745, rho*L = 0.42632, rho*R = 0.26557
        let r = Riemann::new(GasState { rho: 1.0, u: 0.0, p: 1.0 }, GasState { rho: 0.125, u: 0.0, p: 0.1 }, 1.4, 0.5);
        assert!((r.p_star - 0.30313).abs() < 1e-5, "{}", r.p_star);
        assert!((r.u_star - 0.92745).abs() < 1e-5, "{}", r.u_star);
        let t = 0.25;
        let left_star = r.sample(0.5 + 0.5 * r.u_star * t, t);
        let right_star = r.sample(0.5 + 1.2 * r.u_star * t, t);
        assert!((left_star.rho - 0.42632).abs() < 1e-5, "{left_star:?}");
        assert!((right_star.rho - 0.26557).abs() < 1e-5, "{right_star:?}");
        // far states untouched, and the fan continuous at its head
        assert_eq!(r.sample(0.0, t), GasState { rho: 1.0, u: 0.0, p: 1.0 });
        assert_eq!(r.sample(1.0, t), GasState { rho: 0.125, u: 0.0, p: 0.1 });
        let head = 0.5 - 1.4f64.sqrt() * t;
        assert!((r.sample(head + 1e-9, t).rho - 1.0).abs() < 1e-8);
    }

    #[test]
    fn mirrored_problem_mirrors_the_solution() {
        let (a, b) = (GasState { rho: 1.0, u: 0.0, p: 1.0 }, GasState { rho: 0.25, u: 0.0, p: 0.25 });
        let (r, m) = (Riemann::new(a, b, 1.4, 0.0), Riemann::new(b, a, 1.4, 0.0));
        for x in [-0.9, -0.5, -0.1, 0.05, 0.3, 0.7] {
            let (s, t) = (r.sample(x, 1.0), m.sample(-x, 1.0));
            assert!((s.rho - t.rho).abs() < 1e-12 && (s.u + t.u).abs() < 1e-12 && (s.p - t.p).abs() < 1e-12, "{x}: {s:?} {t:?}");
        }
    }
}
