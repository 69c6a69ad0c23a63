//! Stability: time-step limits of the active models (shown by `dmhs check` and warned about at
//! the start of a run) and guards that stop an unstable run with a clear message, keeping every
//! file written so far.
//!
//! Limits, with the smoothing length hs = h/2 (LAMMPS' h in pair_coeff is the kernel support),
//! c the sound speed and mu the dynamic viscosity: acoustic CFL dt <= 0.25 hs/c; viscous
//! dt <= 0.125 hs^2 rho0/mu; force dt <= 0.25 sqrt(hs/|a|max); harmonic bonds dt <= T/20 with
//! T = 2 pi sqrt(m_min/(2K)) the period of the lightest pair. The acoustic limit is where the dam
//! break of docs/validation.md turns unstable (stable at 1x, unstable at 2x, all resolutions).
//! Sound-viscosity (Morris viscosity, fix sph): dt <= 2 nu/c^2 with nu = mu/rho0 of a fluid type
//! (one with atoms outside bonds). fix sph moves the density half a step behind the positions, so
//! the pressure of a sound wave lags it by dt/2: an anti-damping of energy rate k^2 c^2 dt/2 against
//! the viscous k^2 nu, for every wavelength. Measured in a periodic water box (tests/
//! stability_sound_viscosity.rs, examples/scenes/cubes/README.md): noise decays at 1x, grows from
//! about 1.3x (the same in LAMMPS). With delta-SPH density diffusion (dmhs/sph/delta) on the
//! type: 2 (nu + kappa)/c^2, kappa = delta h c0/2 (docs/multihybrid.md, "delta-SPH": the measured
//! map follows it). Pair potentials with a well (LJ): T/20 of the oscillation of the two
//! lightest atoms in the well, k = V''(r_min), as for harmonic bonds.
//!
//! Guards, checked after every step (every N with `dmhs/stability every N`) in one branch-free
//! pass over the atoms; only when it finds something is the particle searched for:
//! - non-finite positions or velocities (every model);
//! - SPH densities outside (lo, hi] x rho0 and non-finite SPH fields;
//! - motion: |v| dt > the neighbour skin (with skin 0: > the list cutoff), where v is the
//!   velocity at the end of the step. An atom that moves farther than the full skin in one step
//!   may have come within the cutoff of partners the lists do not hold (the lists keep pairs
//!   within cutoff + skin and LAMMPS rebuilds when an atom has moved skin/2), so the forces are
//!   wrong from then on. It bounds runaway velocities and kinetic energies of every model. Only
//!   runs with neighbour lists (a pair style) are checked; an instant jump between runs
//!   (`displace_atoms`, `velocity set`, `set`) is no step and is not seen. Measured on every deck of
//!   the project (docs/validation.md, "Instability guard"): correct decks stay below 0.21 of the
//!   bound, unstable LJ and granular runs exceed it 9x to 1e14x within 1 to 6 steps.

use crate::engine::domain::BoundaryKind;
use crate::engine::par::any_index;
use crate::sim::{RunError, Simulation};

pub use crate::models::Limit;

/// Settings of the guards (`dmhs/stability` extension command).
#[derive(Clone, Debug, PartialEq)]
pub struct Guard {
    pub enabled: bool,
    /// Allowed density range as factors of each type's rho0.
    pub rho_lo: f64,
    pub rho_hi: f64,
    /// Check every N steps.
    pub every: i64,
}

impl Default for Guard {
    /// Densities must stay positive and below 2 rho0 (the Tait pressure is then 127 B: no
    /// weakly compressible flow gets there). There is no useful lower bound by default:
    /// free-surface particles with density summation sit well below rho0.
    fn default() -> Self {
        Guard { enabled: true, rho_lo: 0.0, rho_hi: 2.0, every: 1 }
    }
}

/// Largest |f|/m over owned atoms (the current forces).
fn max_acceleration(sim: &Simulation) -> f64 {
    let a = &sim.state.atoms;
    (0..a.nlocal)
        .map(|i| {
            let f = a.f[i];
            (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt() / sim.state.mass(i)
        })
        .fold(0.0, f64::max)
}

/// The time-step limits of the active models (forces must be current for the force limit).
pub fn limits(sim: &Simulation, forces_known: bool) -> Vec<Limit> {
    let mut out = vec![];
    if let Some(info) = sim.pair.as_ref().and_then(|p| p.sph_info()) {
        let hs = 0.5 * info.h_min;
        if info.c_max > 0.0 && info.h_min.is_finite() {
            out.push(Limit { model: "SPH".into(), rule: format!("acoustic CFL 0.25 hs/c (hs = h/2 = {hs}, c = {})", info.c_max), dt_max: 0.25 * hs / info.c_max });
        }
        if let Some(mu) = info.mu_max.filter(|&m| m > 0.0) {
            if info.rho0_min.is_finite() {
                out.push(Limit {
                    model: "SPH".into(),
                    rule: format!("viscous 0.125 hs^2 rho0/mu (rho0 = {}, mu = {})", info.rho0_min, mu),
                    dt_max: 0.125 * hs * hs * info.rho0_min / mu,
                });
            }
        }
        if forces_known && info.h_min.is_finite() {
            let amax = max_acceleration(sim);
            if amax > 0.0 {
                out.push(Limit { model: "SPH".into(), rule: format!("force 0.25 sqrt(hs/|a|max) (|a|max = {amax:.4e})"), dt_max: 0.25 * (hs / amax).sqrt() });
            }
        }
    }
    if let Some(l) = sound_viscosity_limit(sim) {
        out.push(l);
    }
    if let Some(kn) = sim.pair.as_ref().and_then(|p| p.contact_stiffness()).filter(|&k| k > 0.0) {
        let m_min = (0..sim.state.atoms.nlocal).map(|i| sim.state.mass(i)).fold(f64::INFINITY, f64::min);
        if m_min.is_finite() && m_min > 0.0 {
            // undamped contact of the two lightest particles: m_eff = m/2, t_c = pi sqrt(m_eff/k_n)
            // (damping lengthens it, so this is the conservative value); t_c/10 is T/20 of the
            // contact oscillation, the rule used for harmonic bonds below
            let tc = std::f64::consts::PI * (0.5 * m_min / kn).sqrt();
            out.push(Limit { model: "DEM contact".into(), rule: format!("t_c/10, t_c = pi sqrt(m_eff/k_n) (k_n = {kn}, m_eff = {:.4e})", 0.5 * m_min), dt_max: tc / 10.0 });
        }
    }
    if let Some(p) = sim.pair.as_ref() {
        out.extend(p.dt_limits());
        // the well of a pair potential is a spring of k = V''(r_min): T/20 of the oscillation
        // of the two lightest atoms in it, as for harmonic bonds below. For LJ (k = 57.15
        // eps/sigma^2, m = 1) dt <= 0.0294 tau: LAMMPS' melt example (0.005) is at 0.17x; velocity
        // Verlet turns unstable at omega dt = 2, that is T/pi (6.4x this limit)
        if let (Some(k), Some(m)) = (p.well_stiffness().filter(|&k| k > 0.0), lightest(sim)) {
            out.push(Limit { model: format!("pair {}", p.style()), rule: format!("T/20 of the well, T = 2 pi sqrt(m/(2k)) (k = V''(r_min) = {k:.6}, m = {m})"), dt_max: pair_period(m, k) / 20.0 });
        }
    }
    if let Some(bond) = sim.bond_style.as_ref() {
        if bond.name() == "harmonic" && sim.state.topo.nbondtypes > 0 {
            if let Some(m_min) = lightest(sim) {
                let k_max = (1..=sim.state.topo.nbondtypes).map(|t| bond.stiffness(t)).fold(0.0, f64::max);
                if k_max > 0.0 {
                    // E = K (r - r0)^2 is a spring of 2K
                    out.push(Limit { model: "bond harmonic".into(), rule: format!("T/20, T = 2 pi sqrt(m/(2K)) (K = {k_max}, m = {m_min})"), dt_max: pair_period(m_min, 2.0 * k_max) / 20.0 });
                }
            }
        }
    }
    out
}

/// The mass of the lightest owned atom (None without atoms).
fn lightest(sim: &Simulation) -> Option<f64> {
    Some((0..sim.state.atoms.nlocal).map(|i| sim.state.mass(i)).fold(f64::INFINITY, f64::min)).filter(|m| m.is_finite())
}

/// Period of two atoms of mass m joined by a spring k (reduced mass m/2).
fn pair_period(m: f64, k: f64) -> f64 {
    2.0 * std::f64::consts::PI * (0.5 * m / k).sqrt()
}

/// The sound-viscosity limit 2 nu/c^2 of the tightest fluid type of a Morris style. Types whose
/// atoms are all bonded (CGMD solids inside the fluid) are left out: their bonded pairs have no SPH
/// (special_bonds), so no sound wave runs through them (a cube at 8x its own limit in water
/// within the water's limit stays quiet: examples/scenes/cubes/README.md); so are fix
/// sph/stationary walls, which do not move. With delta-SPH on a type: 2 (nu + kappa)/c^2.
fn sound_viscosity_limit(sim: &Simulation) -> Option<Limit> {
    let sv = sim.pair.as_ref().and_then(|p| p.sph_info())?.sound_visc;
    if sv.is_empty() {
        return None;
    }
    let bonded: std::collections::HashSet<i64> = sim.state.topo.bonds.iter().flat_map(|b| b.atoms).collect();
    // fix sph/stationary walls do not move: no sound wave runs through them
    let stationary = sim.fixes.iter().filter(|f| f.style() == "sph/stationary").fold(0u32, |m, f| m | f.groupbit());
    let a = &sim.state.atoms;
    let mut fluid = vec![false; sim.state.ntypes + 1];
    for i in 0..a.nlocal {
        if !bonded.contains(&a.tag[i]) && a.mask[i] & stationary == 0 {
            if let Some(f) = fluid.get_mut(a.typ[i]) {
                *f = true;
            }
        }
    }
    let pair = sim.pair.as_ref()?;
    sv.iter()
        .filter(|&&(t, rho0, c0, mu)| fluid.get(t).copied().unwrap_or(false) && rho0 > 0.0 && c0 > 0.0 && mu > 0.0)
        .map(|&(t, rho0, c0, mu)| {
            // delta-SPH density diffusion damps the wave's density as viscosity damps its velocity
            // (measured: the cubes' water map of docs/multihybrid.md, "delta-SPH", follows it)
            let kappa = pair.density_diffusivity(t);
            if kappa > 0.0 {
                Limit {
                    model: "SPH".into(),
                    rule: format!("sound-viscosity 2 (nu + kappa)/c^2 (type {t}: nu = mu/rho0 = {mu}/{rho0}, kappa = delta h c0/2 = {kappa:.4e}, c = {c0})"),
                    dt_max: 2.0 * (mu / rho0 + kappa) / (c0 * c0),
                }
            } else {
                Limit { model: "SPH".into(), rule: format!("sound-viscosity 2 nu/c^2 (type {t}: nu = mu/rho0 = {mu}/{rho0}, c = {c0})"), dt_max: 2.0 * mu / rho0 / (c0 * c0) }
            }
        })
        .min_by(|x, y| x.dt_max.total_cmp(&y.dt_max))
}

/// Text for `dmhs check` and the warnings at the start of a run.
pub fn report(sim: &Simulation, limits: &[Limit]) -> (String, Vec<String>) {
    let mut s = String::from("stable time step estimates:\n");
    let mut warnings = vec![];
    if limits.is_empty() {
        s += "  (no estimate for the active models)\n";
    }
    for l in limits {
        let ratio = sim.state.dt / l.dt_max;
        s += &format!("  {:<14} {:<60} dt <= {:.4e}   (timestep {:.4e} = {:.2}x)\n", l.model, l.rule, l.dt_max, sim.state.dt, ratio);
        // a time step set to the limit itself is within it (rounding of the two expressions)
        if ratio > 1.0 + 1e-9 {
            warnings.push(format!("the time step {:.4e} is {:.2}x the {} limit of {} ({:.4e}): the run may go unstable", sim.state.dt, ratio, l.rule.split(" (").next().unwrap_or(""), l.model, l.dt_max));
        }
    }
    (s, warnings)
}

/// The stable time-step estimate for an error message: "; the time step is N x the ... limit"
/// when the time step exceeds the tightest limit, else the tightest limit itself.
pub fn dt_hint(sim: &Simulation) -> String {
    let l = limits(sim, false);
    let dt = sim.state.dt;
    let worst = l.iter().max_by(|x, y| (dt / x.dt_max).total_cmp(&(dt / y.dt_max)));
    match worst {
        Some(w) if dt > w.dt_max => format!("; the time step {:.4e} is {:.2}x the {} limit {:.4e}", dt, dt / w.dt_max, w.rule.split(" (").next().unwrap_or(""), w.dt_max),
        Some(w) => format!("; the stable time step estimate is {:.4e} ({} limit of {}), the time step {:.4e} is {:.2}x it", w.dt_max, w.rule.split(" (").next().unwrap_or(""), w.model, dt, dt / w.dt_max),
        None => "; no stable time step estimate for the active models".into(),
    }
}

/// How far an atom may move in one step: the neighbour skin, as an atom that moves farther
/// than the skin in one step may have passed partners the lists do not hold (LAMMPS rebuilds
/// at skin/2, so a correct deck stays far below); with skin 0 (the lists are rebuilt on every
/// step), the list cutoff, as an atom that moves farther passed through its partners. None
/// without lists (no pair style). The bound only: its description is [`step_bound_name`], made
/// for an error alone (formatting it on every step cost a tiny deck a tenth of its time).
fn step_bound(sim: &Simulation) -> Option<f64> {
    let skin = sim.state.neigh_settings.skin;
    let cut = sim.state.neighbor.cutneighmax;
    if !(cut > 0.0) {
        return None;
    }
    Some(if skin > 0.0 { skin } else { cut })
}

/// What [`step_bound`] is, for the error message.
fn step_bound_name(sim: &Simulation) -> String {
    let skin = sim.state.neigh_settings.skin;
    let cut = sim.state.neighbor.cutneighmax;
    if skin > 0.0 { format!("the neighbour skin {skin}") } else { format!("the neighbour list cutoff {cut} (skin 0)") }
}

/// Whether some component is not finite: `v * 0` is 0 for finite v and NaN otherwise (a test
/// without branches, so the pass vectorizes).
#[inline(always)]
fn not_finite3(v: &[f64; 3]) -> bool {
    v[0] * 0.0 + v[1] * 0.0 + v[2] * 0.0 != 0.0
}

/// Atom types up to which [`check_state`] uses a fixed-size bounds table.
const SMALL: usize = 16;

/// Stop the run if the state went bad: non-finite positions, velocities or SPH fields, or an
/// SPH density outside the sane range. The message names step, particle, quantity and bound.
pub fn check_state(sim: &Simulation) -> Result<(), RunError> {
    let g = &sim.guard;
    if !g.enabled || sim.state.step % g.every != 0 {
        return Ok(());
    }
    let a = &sim.state.atoms;
    let step = sim.state.step;
    let hint = || dt_hint(sim);
    let n = a.nlocal;
    let rho0 = if a.features.sph { sim.pair.as_ref().and_then(|p| p.sph_info()).map(|s| s.rho0).unwrap_or_default() } else { Vec::new() };
    // fast path, one pass without branches over every atom; only when it finds something is the
    // particle searched for. A density is good inside (lo, hi] of its type: for a type without
    // rho0, (-inf, MAX], which only a non-finite density leaves (a NaN compares false).
    let (x, v) = (&a.x[..n], &a.v[..n]);
    // the step's motion |v| dt within the bound: |v|^2 <= (bound/dt)^2 (false for NaN)
    let bound = step_bound(sim);
    let vmax2 = bound.map(|b| (b / sim.state.dt.abs()).powi(2)).unwrap_or(f64::INFINITY);
    let bad_motion = |i: usize| {
        let w = &v[i];
        not_finite3(&x[i]) | not_finite3(w) | !(w[0] * w[0] + w[1] * w[1] + w[2] * w[2] <= vmax2)
    };
    let all_good = if a.features.sph {
        let bounds: Vec<(f64, f64)> = (0..=sim.state.ntypes)
            .map(|t| match rho0.get(t).copied().unwrap_or(0.0) {
                r0 if r0 > 0.0 => (g.rho_lo * r0, (g.rho_hi * r0).min(f64::MAX)),
                _ => (f64::NEG_INFINITY, f64::MAX),
            })
            .collect();
        let (rho, esph, typ) = (&a.rho[..n], &a.esph[..n], &a.typ[..n]);
        let bad = |i: usize, (lo, hi): (f64, f64)| {
            let r = rho[i];
            bad_motion(i) | !(r > lo && r <= hi) | (esph[i] * 0.0 != 0.0)
        };
        if bounds.len() <= SMALL {
            // a fixed table indexed by `typ & (SMALL - 1)` needs no bounds check, so the pass
            // vectorizes (types are <= ntypes < SMALL, so the mask changes nothing)
            let mut small = [(f64::NEG_INFINITY, f64::MAX); SMALL];
            small[..bounds.len()].copy_from_slice(&bounds);
            !any_index(n, |i| bad(i, small[typ[i] & (SMALL - 1)]))
        } else {
            !any_index(n, |i| bad(i, bounds[typ[i]]))
        }
    } else {
        !any_index(n, bad_motion)
    };
    if all_good {
        return Ok(());
    }
    for i in 0..a.nlocal {
        for (name, v) in [("position", a.x[i]), ("velocity", a.v[i])] {
            if !(v[0].is_finite() && v[1].is_finite() && v[2].is_finite()) {
                return Err(RunError::new(step, format!("particle {} has a non-finite {name} ({}, {}, {}): the run is unstable{}", a.tag[i], v[0], v[1], v[2], hint())));
            }
        }
    }
    if a.features.sph {
        for i in 0..a.nlocal {
            let r = a.rho[i];
            if !r.is_finite() || !a.esph[i].is_finite() {
                return Err(RunError::new(step, format!("particle {} has a non-finite density or energy (rho {}, esph {}): the run is unstable{}", a.tag[i], r, a.esph[i], hint())));
            }
            let r0 = rho0.get(a.typ[i]).copied().unwrap_or(0.0);
            if r0 > 0.0 && (r <= g.rho_lo * r0 || r > g.rho_hi * r0) {
                return Err(RunError::new(
                    step,
                    format!(
                        "particle {} (type {}) has density {:.6e}, outside the sane range ({:.4e}, {:.4e}] ({} to {} x rho0 = {}): the run is unstable{}",
                        a.tag[i], a.typ[i], r, g.rho_lo * r0, g.rho_hi * r0, g.rho_lo, g.rho_hi, r0, hint()
                    ),
                ));
            }
        }
    }
    // the fastest atom over the bound (squared speeds compare as the pass did)
    let speed2 = |i: usize| a.v[i][0] * a.v[i][0] + a.v[i][1] * a.v[i][1] + a.v[i][2] * a.v[i][2];
    if let (Some(i), Some(_)) = ((0..n).filter(|&i| !(speed2(i) <= vmax2)).max_by(|&i, &j| speed2(i).total_cmp(&speed2(j))), bound) {
        let (speed, dt, what) = (speed2(i).sqrt(), sim.state.dt, step_bound_name(sim));
        return Err(RunError::new(
            step,
            format!(
                "particle {} moved {:.4e} in one step (speed {:.4e} x time step {:.4e}), more than {what}: pairs that came within the cutoff may be missing from the neighbour lists, the run is unstable{}",
                a.tag[i], speed * dt.abs(), speed, dt, hint()
            ),
        ));
    }
    Ok(())
}

/// Atoms outside a fixed face are lost, as in LAMMPS: an error naming the first one (or, with
/// `thermo_modify lost ignore|warn`, they are removed; `warn` reports the first loss once, as
/// LAMMPS' "Lost atoms: original N current M").
pub fn check_lost(sim: &mut Simulation) -> Result<(), RunError> {
    let Some(domain) = sim.state.domain.as_ref() else { return Ok(()) };
    let a = &sim.state.atoms;
    let mut gone = vec![false; a.nlocal];
    let mut first: Option<(usize, usize)> = None;
    // (a triclinic box's atoms are in box fractions here, during a rebuild)
    let (lo, hi) = if domain.triclinic() { ([0.0; 3], [1.0; 3]) } else { (domain.lo, domain.hi) };
    for i in 0..a.nlocal {
        for d in 0..3 {
            let [blo, bhi] = domain.boundary[d];
            let x = a.x[i][d];
            let out = (blo == BoundaryKind::Fixed && x < lo[d]) || (bhi == BoundaryKind::Fixed && x >= hi[d]) || !x.is_finite();
            if out {
                gone[i] = true;
                first.get_or_insert((i, d));
            }
        }
    }
    if sim.thermo.lost_ignore {
        let tags: Vec<f64> = (0..a.nlocal).filter(|&k| gone[k]).map(|k| a.tag[k] as f64).collect();
        // the ranks of a distributed run keep one topology: each drops every rank's lost atoms
        let tags: std::collections::HashSet<i64> = sim.state.allgather_ranks(tags).into_iter().map(|t| t as i64).collect();
        if tags.is_empty() {
            return Ok(());
        }
        let before = sim.state.natoms();
        if first.is_some() {
            sim.state.atoms.retain(&gone);
        }
        sim.state.topo.remove_atoms(&tags);
        // a distributed run's index of the records by atom follows the records
        sim.state.stored_on = None;
        if sim.thermo.lost_warn && !sim.thermo.lost_warned {
            sim.thermo.lost_warned = true;
            sim.state.messages.push(format!("WARNING: Lost atoms: original {before} current {}", before - tags.len()));
        }
        return Ok(());
    }
    let Some((i, d)) = first else { return Ok(()) };
    let n_lost = gone.iter().filter(|&&g| g).count();
    Err(RunError::new(
        sim.state.step,
        format!(
            "lost atoms: {n_lost} of {} left the box through a fixed boundary (first: atom {} at {}{} = {}, box {}..{}){}",
            a.nlocal,
            a.tag[i],
            if domain.triclinic() { "box fraction " } else { "" },
            ["x", "y", "z"][d],
            a.x[i][d],
            lo[d],
            hi[d],
            dt_hint(sim)
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::check_state;
    use crate::sim::Simulation;

    /// A quiet 2D water box, with type 2 (rho0 0: no density bound) beside type 1 (rho0 1; its
    /// pair_coeff comes last, as the pair_coeff I J of a Tait style sets rho0 of type I).
    fn water_box() -> Simulation {
        let deck = "dimension 2\nunits lj\natom_style sph\nboundary p p p\nregion box block 0 10 0 10 -0.5 0.5\ncreate_box 2 box\n\
                    lattice sq 1.0\ncreate_atoms 1 box\nset atom 90*100 type 2\nmass * 1.0\nset group all sph/rho 1.0\n\
                    pair_style sph/taitwater\npair_coeff 1 2 0.0 0.0 0.1 1.3\npair_coeff 2 2 0.0 0.0 0.1 1.3\npair_coeff 1 1 1.0 10.0 0.1 1.3\n\
                    fix 1 all sph/stationary\ntimestep 0.001\nrun 0\n";
        let mut sim = Simulation::new();
        sim.out.captured = Some(String::new());
        crate::deck::commands::run_plain(&mut sim, deck).unwrap();
        sim.state.step = 1;
        sim
    }

    /// The one-pass check finds each kind of bad value, and the search names particle and value.
    #[test]
    fn the_one_pass_check_finds_every_bad_value() {
        assert_eq!(check_state(&water_box()), Ok(()));
        let cases: [(&str, fn(&mut crate::engine::atoms::Atoms, usize), &str); 6] = [
            ("position", |a, i| a.x[i][1] = f64::NAN, "has a non-finite position (5, NaN, 0)"),
            ("velocity", |a, i| a.v[i][2] = f64::NEG_INFINITY, "has a non-finite velocity (0, 0, -inf)"),
            ("energy", |a, i| a.esph[i] = f64::INFINITY, "has a non-finite density or energy (rho 1, esph inf)"),
            ("density NaN", |a, i| a.rho[i] = f64::NAN, "has a non-finite density or energy (rho NaN, esph 0)"),
            ("density of a type without rho0", |a, i| a.rho[i] = f64::INFINITY, "has a non-finite density or energy (rho inf, esph 0)"),
            ("density above the bound", |a, i| a.rho[i] = 2.5, "has density 2.500000e0, outside the sane range"),
        ];
        for (what, spoil, expect) in cases {
            let mut sim = water_box();
            let tag = if what.contains("without rho0") { 95 } else { 46 };
            let i = (0..sim.state.atoms.nlocal).find(|&i| sim.state.atoms.tag[i] == tag).unwrap();
            spoil(&mut sim.state.atoms, i);
            let e = check_state(&sim).expect_err(what);
            assert_eq!(e.step, 1);
            assert!(e.message.starts_with(&format!("particle {tag} ")) && e.message.contains(expect), "{what}: {}", e.message);
        }
    }
}
