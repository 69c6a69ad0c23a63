//! min_style cg (Polak-Ribiere, restarted every 3N iterations and when the direction is not
//! downhill) and sd, with LAMMPS' line searches along the direction h: backtrack and quadratic
//! (LAMMPS' MinCG, MinSD and MinLineSearch).

use super::{energy_converged, LineSearch, Min, MinStyle, Stop};
use crate::sim::{RunError, Simulation};

/// LAMMPS' constants of the line search: the largest alpha, the backtracking factor, the
/// sufficient-decrease slope, the tolerance of the quadratic model, the machine accuracy of
/// energy differences and the smallest projected force of the quadratic step.
const ALPHA_MAX: f64 = 1.0;
const ALPHA_REDUCE: f64 = 0.5;
const BACKTRACK_SLOPE: f64 = 0.4;
const QUADRATIC_TOL: f64 = 0.1;
const EMACH: f64 = 1.0e-8;
const EPS_QUAD: f64 = 1.0e-28;

/// Indices of the per-atom vectors: the start of the line search, the previous force, the
/// search direction.
const X0: usize = 0;
const G: usize = 1;
const H: usize = 2;

/// The iterations of cg or sd; returns why they stopped.
pub(super) fn iterate(sim: &mut Simulation, m: &mut Min, maxiter: i64) -> Result<Stop, RunError> {
    let n = sim.state.atoms.nlocal;
    let f0 = sim.state.atoms.f[..n].to_vec();
    m.vectors = vec![vec![[0.0; 3]; n], f0.clone(), f0];
    m.gextra.clone_from(&m.fextra);
    m.hextra.clone_from(&m.fextra);
    // CG restarts every ndof iterations (the extra degrees of freedom count)
    let nlimit = (3 * sim.state.natoms() as i64 + m.fextra.len() as i64).min(i32::MAX as i64).max(1);
    let mut gg = m.fnorm_sqr(sim);
    for _ in 0..maxiter {
        sim.state.step += 1;
        m.niter += 1;
        m.eprevious = m.ecurrent;
        let eoriginal = m.ecurrent;
        let fail = match m.set.line {
            LineSearch::Backtrack => backtrack(sim, m, eoriginal)?,
            LineSearch::Quadratic => quadratic(sim, m, eoriginal)?,
        };
        if let Some(stop) = fail {
            return Ok(stop);
        }
        if m.neval >= m.opts.maxeval {
            return Ok(Stop::MaxEval);
        }
        if energy_converged(m.opts.etol, m.ecurrent, m.eprevious) {
            return Ok(Stop::Etol);
        }
        let order = Min::order(sim);
        let f = &sim.state.atoms.f;
        match m.set.style {
            MinStyle::Sd => {
                if m.force_converged(sim, None) {
                    return Ok(Stop::Ftol);
                }
                m.vectors[H].copy_from_slice(&f[..n]);
                m.hextra.clone_from(&m.fextra);
            }
            _ => {
                let (mut ff, mut fg) = (0.0, 0.0);
                let g = &m.vectors[G];
                for &i in &order {
                    for k in 0..3 {
                        ff += f[i][k] * f[i][k];
                        fg += f[i][k] * g[i][k];
                    }
                }
                for (fe, ge) in m.fextra.iter().zip(&m.gextra) {
                    ff += fe * fe;
                    fg += fe * ge;
                }
                if m.force_converged(sim, Some(ff)) {
                    return Ok(Stop::Ftol);
                }
                // Polak-Ribiere, never negative; a restart every nlimit iterations
                let pr = (ff - fg) / gg;
                let mut beta = if 0.0 > pr { 0.0 } else { pr };
                if (m.niter + 1) % nlimit == 0 {
                    beta = 0.0;
                }
                gg = ff;
                let f = &sim.state.atoms.f;
                let [_, g, h] = &mut m.vectors[..] else { unreachable!("three vectors") };
                for i in 0..n {
                    for k in 0..3 {
                        g[i][k] = f[i][k];
                        h[i][k] = g[i][k] + beta * h[i][k];
                    }
                }
                for ((ge, he), fe) in m.gextra.iter_mut().zip(m.hextra.iter_mut()).zip(&m.fextra) {
                    *ge = *fe;
                    *he = *ge + beta * *he;
                }
                // not downhill: restart along the force
                let mut gh = 0.0;
                for &i in &order {
                    for k in 0..3 {
                        gh += g[i][k] * h[i][k];
                    }
                }
                for (ge, he) in m.gextra.iter().zip(&m.hextra) {
                    gh += ge * he;
                }
                if gh <= 0.0 {
                    h.copy_from_slice(g);
                    m.hextra.clone_from(&m.gextra);
                }
            }
        }
        if sim.output_due(sim.state.step, m.last) {
            sim.timers.stamp();
            sim.output_now(false, m.last, false)?;
            sim.timers.charge(crate::engine::timing::Stage::Output);
        }
    }
    Ok(Stop::MaxIter)
}

/// f.h with the extra degrees of freedom (divided by the atom count under thermo_modify
/// norm yes), the largest alpha the direction allows and the largest |h|.
fn projection(sim: &mut Simulation, m: &Min) -> (f64, f64, f64) {
    let f = &sim.state.atoms.f;
    let h = &m.vectors[H];
    let order = Min::order(sim);
    let mut fdoth = 0.0;
    for &i in &order {
        for k in 0..3 {
            fdoth += f[i][k] * h[i][k];
        }
    }
    for (fe, he) in m.fextra.iter().zip(&m.hextra) {
        fdoth += fe * he;
    }
    if m.normflag {
        fdoth /= m.natoms;
    }
    let mut hmax: f64 = 0.0;
    for &i in &order {
        for c in h[i] {
            let a = c.abs();
            hmax = if hmax > a { hmax } else { a };
        }
    }
    let mut alpha = alpha_max(m.set.dmax, hmax);
    if !m.fextra.is_empty() {
        let extra = m.max_alpha_extra(sim);
        alpha = if alpha < extra { alpha } else { extra };
        for he in &m.hextra {
            let a = he.abs();
            hmax = if hmax > a { hmax } else { a };
        }
    }
    (fdoth, alpha, hmax)
}

/// The largest alpha: no coordinate moves more than dmax, and alpha <= ALPHA_MAX.
fn alpha_max(dmax: f64, hmax: f64) -> f64 {
    let a = dmax / hmax;
    if ALPHA_MAX < a {
        ALPHA_MAX
    } else {
        a
    }
}

/// Keep the box, the positions and the extra degrees of freedom where the line search starts.
fn store_start(sim: &mut Simulation, m: &mut Min) -> Result<(), RunError> {
    let n = sim.state.atoms.nlocal;
    m.vectors[X0].copy_from_slice(&sim.state.atoms.x[..n]);
    // LAMMPS' FixMinimize::store_box: wrapped atoms' x0 are re-imaged with this box
    m.box0 = sim.state.domain.clone();
    m.store_extra(sim)
}

/// Positions x0 + alpha h (x0 itself when alpha is 0) and the extra degrees of freedom
/// likewise, their energy and forces.
fn alpha_step(sim: &mut Simulation, m: &mut Min, alpha: f64, reset: bool) -> Result<f64, RunError> {
    let n = sim.state.atoms.nlocal;
    m.step_extra(sim, 0.0)?;
    let x = &mut sim.state.atoms.x;
    x[..n].copy_from_slice(&m.vectors[X0]);
    if alpha > 0.0 {
        m.step_extra(sim, alpha)?;
        let x = &mut sim.state.atoms.x;
        let h = &m.vectors[H];
        for i in 0..n {
            for k in 0..3 {
                x[i][k] += alpha * h[i][k];
            }
        }
    }
    m.neval += 1;
    m.energy_force(sim, reset)
}

/// Backtracking line search: halve alpha from its largest value until the energy decreases
/// enough. None: success.
fn backtrack(sim: &mut Simulation, m: &mut Min, eoriginal: f64) -> Result<Option<Stop>, RunError> {
    let (fdoth, mut alpha, hmax) = projection(sim, m);
    if fdoth <= 0.0 {
        return Ok(Some(Stop::Downhill));
    }
    m.alpha_final = alpha;
    if hmax == 0.0 {
        return Ok(Some(Stop::ZeroForce));
    }
    store_start(sim, m)?;
    loop {
        m.ecurrent = alpha_step(sim, m, alpha, true)?;
        let de_ideal = -BACKTRACK_SLOPE * alpha * fdoth;
        let de = m.ecurrent - eoriginal;
        if de <= de_ideal {
            m.alpha_final = alpha;
            m.reset_ref(sim)?;
            return Ok(None);
        }
        alpha *= ALPHA_REDUCE;
        m.alpha_final = alpha;
        if alpha <= 0.0 || de_ideal >= -EMACH {
            m.ecurrent = alpha_step(sim, m, 0.0, false)?;
            return Ok(Some(if de < 0.0 { Stop::Etol } else { Stop::ZeroAlpha }));
        }
    }
}

/// Quadratic line search: backtrack until the energy along the line is close enough to the
/// quadratic model made from the projected forces at two alphas, then step to the zero of the
/// projected force (secant). None: success.
fn quadratic(sim: &mut Simulation, m: &mut Min, eoriginal: f64) -> Result<Option<Stop>, RunError> {
    let (fdoth, alphamax, hmax) = projection(sim, m);
    if fdoth <= 0.0 {
        return Ok(Some(Stop::Downhill));
    }
    if hmax == 0.0 {
        return Ok(Some(Stop::ZeroForce));
    }
    store_start(sim, m)?;
    let mut alpha = alphamax;
    let (mut fhprev, mut engprev, mut alphaprev) = (fdoth, eoriginal, 0.0);
    loop {
        m.alpha_final = alpha;
        m.ecurrent = alpha_step(sim, m, alpha, true)?;
        let (mut ff, mut fh) = (0.0, 0.0);
        {
            let f = &sim.state.atoms.f;
            let h = &m.vectors[H];
            for i in Min::order(sim) {
                for k in 0..3 {
                    ff += f[i][k] * f[i][k];
                    fh += f[i][k] * h[i][k];
                }
            }
            for (fe, he) in m.fextra.iter().zip(&m.hextra) {
                ff += fe * fe;
                fh += fe * he;
            }
        }
        if m.normflag {
            ff /= m.natoms;
            fh /= m.natoms;
        }
        let _ = ff;
        let delfh = fh - fhprev;
        if fh.abs() < EPS_QUAD || delfh.abs() < EPS_QUAD {
            m.ecurrent = alpha_step(sim, m, 0.0, false)?;
            return Ok(Some(Stop::ZeroQuad));
        }
        let relerr = (1.0 - (0.5 * (alpha - alphaprev) * (fh + fhprev) + m.ecurrent) / engprev).abs();
        let alpha0 = alpha - (alpha - alphaprev) * fh / delfh;
        if relerr <= QUADRATIC_TOL && alpha0 > 0.0 && alpha0 < alphamax {
            m.ecurrent = alpha_step(sim, m, alpha0, true)?;
            if m.ecurrent - eoriginal < EMACH {
                m.reset_ref(sim)?;
                return Ok(None);
            }
        }
        let de_ideal = -BACKTRACK_SLOPE * alpha * fdoth;
        let de = m.ecurrent - eoriginal;
        if de <= de_ideal {
            m.reset_ref(sim)?;
            return Ok(None);
        }
        fhprev = fh;
        engprev = m.ecurrent;
        alphaprev = alpha;
        alpha *= ALPHA_REDUCE;
        m.alpha_final = alpha;
        if alpha <= 0.0 || de_ideal >= -EMACH {
            m.ecurrent = alpha_step(sim, m, 0.0, false)?;
            return Ok(Some(Stop::ZeroAlpha));
        }
    }
}
