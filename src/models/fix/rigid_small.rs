//! `fix ID group rigid/small molecule`: each molecule of the group moves as one rigid body
//! (LAMMPS' fix rigid/small with nve integration, 22 Jul 2025, serial order of operations).
//!
//! Setup (every run; with `reinit no` or `infile` the first run's only): mass and centre of mass
//! from unwrapped positions, the inertia tensor (finite-size spheres add 0.4 m r^2), principal
//! axes by LAMMPS' Jacobi rotations (ascending moments; in 2d the axis along z last), the
//! quaternion, each atom's displacement in the body frame; vcm and angular momentum from the
//! atoms' velocities.
//! Per step: initial_integrate (half kick of vcm and angular momentum, drift of the centre,
//! Richardson update of the quaternion, positions and velocities of the atoms from the
//! body), final_integrate (force and torque summed over the body's atoms, half kick,
//! velocities of the atoms). Sums over atoms run in LAMMPS' local order. The body centre
//! is wrapped into a periodic box on each list rebuild, as LAMMPS' pre_neighbor does.
//! With `fix enforce2d` (defined after this fix) the out-of-plane body values are zeroed at
//! its post_force, as LAMMPS' FixRigidSmall::enforce2d.
//!
//! `rigid/nve/small`, `rigid/nvt/small`, `rigid/npt/small` and `rigid/nph/small` are this fix
//! with another step (rigid_nh_small.rs). `fix rigid` and its integrators are this fix with the
//! bodies of rigid.rs (one set, fixed when the fix is defined, set up at the run's init).
//! `langevin Tstart Tstop Tperiod seed` (rigid/small only) adds to each body's force and torque,
//! at its final half step, a drag and a random kick drawn at post_force (LAMMPS'
//! apply_langevin_thermostat: Marsaglia's stream seeded with `seed`, six draws per body in body
//! order). `infile FILE` gives bodies (by molecule ID) their mass, centre, inertia tensor and
//! momenta from a file (LAMMPS' readfile); `gravity FIXID` adds that fix gravity's m g to each
//! body's force (at setup too, after the thermostat's), for a fix gravity with `disable`.

use super::box_stress::Couple;
use super::rigid::{read_infile, Global, Infile};
use super::rigid_nh_small::{Baro, Chains, RigidNh, Steps};
use super::thermostat::run_fraction;
use super::{Fix, FixCtx, FixDef, FixHooks, MinRole, ThermoTally};
use crate::engine::jacobi::{jacobi3, Sort};
use crate::engine::molecule::{add_point_inertia, RigidInsert, RigidTemplate};
use crate::engine::quat::{self, Quat};
use crate::engine::random_mars::RanMars;
use crate::engine::atoms::Atoms;
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, DResult, Word};
use std::collections::HashMap;

pub const SYNTAX_RIGID: &str = "fix ID group rigid|rigid/nve|rigid/nvt|rigid/npt|rigid/nph single|molecule|custom i_name|v_name|group N g1 ... gN [force M x y z] [torque M x y z] [reinit yes|no] [infile FILE] [gravity FIXID] [langevin Tstart Tstop Tperiod seed] [temp Tstart Tstop Tdamp] [tparam Tchain Titer Torder] [iso|aniso|x|y|z Pstart Pstop Pdamp] [couple none|xyz|xy|yz|xz] [dilate all|group] [pchain N]";
pub const SYNTAX: &str = "fix ID group rigid/small|rigid/nve/small|rigid/nvt/small|rigid/npt/small|rigid/nph/small molecule|custom i_name|v_name [mol TEMPLATE] [reinit yes|no] [infile FILE] [gravity FIXID] [langevin Tstart Tstop Tperiod seed] [temp Tstart Tstop Tdamp] [tparam Tchain Titer Torder] [iso|aniso|x|y|z Pstart Pstop Pdamp] [couple none|xyz|xy|yz|xz] [dilate all|group] [pchain N]";

/// Moment of inertia prefactor of a solid sphere.
const SINERTIA: f64 = 0.4;
/// Principal moments below EPSILON times the largest are zero (LAMMPS' EPSILON).
const EPSILON: f64 = 1.0e-7;

#[derive(Clone, Debug, Default)]
pub struct Body {
    pub mol: i64,
    pub mass: f64,
    pub xcm: [f64; 3],
    pub vcm: [f64; 3],
    pub fcm: [f64; 3],
    pub torque: [f64; 3],
    pub angmom: [f64; 3],
    pub omega: [f64; 3],
    pub inertia: [f64; 3],
    pub ex: [f64; 3],
    pub ey: [f64; 3],
    pub ez: [f64; 3],
    pub quat: Quat,
    /// The conjugate quaternion momentum (rigid/nve/small and rigid/nvt/small).
    pub conjqm: Quat,
    /// Image flags of the wrapped centre (LAMMPS' body image).
    pub image: [i32; 3],
    /// Atoms: point particles and finite-size ones (for the degrees of freedom).
    pub npoint: usize,
    pub nsphere: usize,
}

impl Body {
    /// The angular velocity in the body frame, from the angular momentum and the principal
    /// moments (0 about an axis without one).
    fn wbody(&self) -> [f64; 3] {
        let rot = quat::quat_to_mat(&self.quat);
        let mut wbody = quat::transpose_matvec(&rot, &self.angmom);
        for k in 0..3 {
            wbody[k] = if self.inertia[k] == 0.0 { 0.0 } else { wbody[k] / self.inertia[k] };
        }
        wbody
    }
}

/// A body atom: its body and its displacement from the centre in the body frame.
#[derive(Clone, Copy, Debug)]
struct Member {
    body: usize,
    displace: [f64; 3],
    sphere: bool,
}

pub struct FixRigidSmall {
    id: String,
    groupbit: u32,
    style: &'static str,
    bodies: Vec<Body>,
    members: HashMap<i64, Member>,
    /// A fix enforce2d follows this fix (2d).
    enforce2d: bool,
    /// `mol TEMPLATE`: the template's body (LAMMPS' onemols), for molecules fix pour inserts.
    template: Option<(String, RigidTemplate)>,
    /// The constraint forces' virial (LAMMPS' virial_global_flag, on by default for rigid fixes).
    tally: ThermoTally,
    /// rigid/nve/small and rigid/nvt/small: the NO_SQUISH step (and its thermostat).
    nh: Option<RigidNh>,
    /// `langevin`: the bodies' thermostat.
    langevin: Option<BodyLangevin>,
    /// Each molecule's place in LAMMPS' body array, fixed when the fix is defined (LAMMPS'
    /// create_bodies: bodies in the local order of their owning atoms, kept through sorts);
    /// bodies inserted later follow, by molecule ID.
    rank: HashMap<i64, usize>,
    /// A run has begun, which sets the bodies up (LAMMPS' setupflag): before, they remove no
    /// degrees of freedom from temperatures (a `velocity create` before the first run).
    set_up: bool,
    /// The members by local index (`slot`), valid while the owned atoms' IDs are `tags`: the
    /// per-step passes read this, not the map by ID.
    local: LocalMembers,
    /// `fix rigid` and its integrators: the bodies fixed at definition and their switches.
    global: Option<Global>,
    /// `fix_modify ID bodyforces early`: the bodies' forces and torques are summed at
    /// post_force, before later fixes change the atoms' forces (LAMMPS' earlyflag).
    early: bool,
    /// `fix_modify ID temp CID` of a barostat: the temperature its pressure reads (LAMMPS'
    /// id_temp; group all by default).
    press_temp: Option<crate::models::compute::temp_bias::TempSpec>,
    /// `reinit yes` (default): the bodies are set up again at every run (fix rigid at init,
    /// the /small styles at setup); `no` keeps the first run's.
    reinit: bool,
    /// `infile FILE`: bodies whose mass, centre, inertia tensor, vcm, angular momentum and image
    /// come from the file (keyed by body index for fix rigid, by molecule ID for /small).
    infile: Option<Infile>,
    /// `gravity FIXID`: the acceleration of that fix gravity acts on each body's centre of mass
    /// (LAMMPS' id_gravity; the fix gravity usually has `disable`).
    gravity: Option<String>,
    /// The bodies have been set up once (LAMMPS' setupflag, for `reinit no`).
    bodies_set_up: bool,
    /// /small with `custom`: the body ID of each atom of the group when the fix was defined,
    /// by atom ID (molecule IDs otherwise).
    custom: Option<HashMap<i64, i64>>,
    /// /small: the largest distance from a body's owner to its atoms when the fix was defined
    /// (a template's included), which the ghost cutoff must reach (LAMMPS' maxextent).
    maxextent: f64,
}

/// The body ID of owned atom `i` of a /small fix: its `custom` ID, or its molecule ID if it is
/// in the fix group; None for an atom in no body.
fn body_key(custom: Option<&HashMap<i64, i64>>, a: &crate::engine::atoms::Atoms, groupbit: u32, i: usize) -> Option<i64> {
    match custom {
        Some(ids) => ids.get(&a.tag[i]).copied(),
        None => (a.mask[i] & groupbit != 0).then(|| a.molecule[i]),
    }
}

#[derive(Default)]
struct LocalMembers {
    tags: Vec<i64>,
    slot: Vec<Option<Member>>,
}

/// `langevin Tstart Tstop Tperiod seed`: the force and torque of each body's thermostat,
/// drawn at post_force (the torque in the body frame), added to the body's sums at the final
/// half step.
struct BodyLangevin {
    t_start: f64,
    t_stop: f64,
    t_period: f64,
    random: RanMars,
    /// Per body: force (3) and torque (3).
    extra: Vec<[f64; 6]>,
}

impl FixRigidSmall {
    pub fn from_lammps(d: FixDef, style: &'static str, state: &mut State) -> DResult<Self> {
        let (groupbit, cmd) = (d.groupbit, d.cmd);
        let mut a = Args::from_words(d.args, cmd.span, if style.ends_with("/small") { SYNTAX } else { SYNTAX_RIGID });
        // fix rigid and its integrators: one set of bodies from the body style (rigid.rs)
        let mut global = if style.ends_with("/small") { None } else { Some(Global::parse(&mut a, style, groupbit, state, d.atom_values)?) };
        // the /small styles: bodies by molecule ID, or by `custom` IDs given when the fix is
        // defined (LAMMPS' bodyID; atoms outside the group or made later are in no body)
        let mut custom = None;
        let mut custom_word = None;
        if global.is_none() {
            let kind = a.word("body style (molecule or custom)")?;
            match kind.text.as_str() {
                "molecule" => {
                    if !state.atoms.features.molecule {
                        return Err(a.error_at(kind, "fix rigid/small requires atom attribute molecule", "no molecule IDs").with_help("use an atom style with molecule IDs (bond, molecular, full, or hybrid sphere molecular)"));
                    }
                }
                "custom" => {
                    let ids = super::rigid::custom_ids(&mut a, style, state, groupbit, d.atom_values)?;
                    let at = &state.atoms;
                    custom = Some((0..at.nlocal).filter(|&i| at.mask[i] & groupbit != 0).map(|i| (at.tag[i], ids[i])).collect::<HashMap<i64, i64>>());
                    custom_word = Some(kind.clone());
                }
                _ => return Err(a.error_at(kind, format!("illegal fix {style} body style `{}`", kind.text), "expected molecule or custom")),
            }
        }
        let mut template = None;
        // LAMMPS' ^rigid/n.t (a thermostat) and ^rigid/np. (a barostat)
        let nvt = style.starts_with("rigid/nvt") || style.starts_with("rigid/npt");
        let npx = style.starts_with("rigid/npt") || style.starts_with("rigid/nph");
        let plain = style == "rigid/small" || style == "rigid";
        let dim = state.dimension;
        let (mut p_start, mut p_stop, mut p_period, mut p_flag) = ([0.0; 3], [0.0; 3], [0.0; 3], [false; 3]);
        let mut couple = Couple::None;
        let mut dilate = None;
        let mut p_chain = 10;
        let mut press_word = None;
        let mut temp = None;
        let mut langevin = None;
        let (mut reinit, mut infile, mut gravity, mut reading) = (true, None, None, None);
        let (mut t_chain, mut t_iter, mut t_order) = (10, 1, 3);
        while let Some(w) = a.peek() {
            let what = match w.text.as_str() {
                "temp" if nvt => {
                    a.skip(1);
                    temp = Some((w, a.f64("Tstart")?, a.f64("Tstop")?, a.f64("Tdamp")?));
                    continue;
                }
                "tparam" if nvt => {
                    a.skip(1);
                    t_chain = a.i64_in("Tchain (thermostat chain length, 1 or more)", 1, 1000)? as usize;
                    t_iter = a.i64_in("Titer (thermostat iterations, 1 or more)", 1, 1000)? as usize;
                    let w = a.peek().cloned();
                    t_order = a.i64("Torder (3 or 5)")? as usize;
                    if t_order != 3 && t_order != 5 {
                        return Err(a.error_at(&w.unwrap(), "fix rigid nvt/small t_order must be 3 or 5", "expected 3 or 5"));
                    }
                    continue;
                }
                "iso" | "aniso" | "x" | "y" | "z" if npx => {
                    a.skip(1);
                    press_word.get_or_insert(w);
                    let (start, stop, period) = (a.f64("Pstart")?, a.f64("Pstop")?, a.f64("Pdamp")?);
                    let dims: &[usize] = match w.text.as_str() {
                        "iso" | "aniso" => &[0, 1, 2],
                        "x" => &[0],
                        "y" => &[1],
                        _ => &[2],
                    };
                    for &k in dims {
                        (p_start[k], p_stop[k], p_period[k], p_flag[k]) = (start, stop, period, true);
                    }
                    if w.text == "iso" {
                        couple = Couple::Xyz;
                    }
                    if matches!(w.text.as_str(), "iso" | "aniso") && dim == 2 {
                        (p_start[2], p_stop[2], p_period[2], p_flag[2]) = (0.0, 0.0, 0.0, false);
                    }
                    continue;
                }
                "couple" if npx => {
                    a.skip(1);
                    couple = Couple::parse(&mut a)?;
                    continue;
                }
                "dilate" if npx => {
                    a.skip(1);
                    let g = a.word("dilate group ID (or all)")?;
                    dilate = if g.text == "all" {
                        None
                    } else {
                        let k = state.groups.find(&g.text).ok_or_else(|| a.error_at(g, format!("fix {style} dilate group ID `{}` does not exist", g.text), "unknown group"))?;
                        Some(1u32 << k)
                    };
                    continue;
                }
                "pchain" if npx => {
                    a.skip(1);
                    p_chain = a.i64_in("pchain (barostat chain length, 1 or more)", 1, 1000)? as usize;
                    continue;
                }
                "mol" => {
                    a.skip(1);
                    let t = a.word("molecule template ID")?;
                    let m = state.molecules.iter().find(|m| m.id == t.text).ok_or_else(|| a.error_at(t, format!("molecule template `{}` does not exist", t.text), "unknown template"))?;
                    // LAMMPS computes the template's body once, here
                    let body = m.rigid(&state.type_mass).map_err(|e| a.error_at(t, e, "not a rigid body"))?;
                    template = Some((t.text.clone(), body));
                    continue;
                }
                "force" | "torque" if global.is_some() => {
                    a.skip(1);
                    global.as_mut().expect("checked").parse_flags(&mut a, w, style, dim)?;
                    continue;
                }
                "infile" => {
                    a.skip(1);
                    let f = a.word("body file name")?;
                    let file = match &global {
                        Some(g) => read_infile(&d.path(&f.text), "rigid", |id| g.file_body(id)),
                        None => {
                            // LAMMPS' maxmol: the largest body ID of the group
                            let at = &state.atoms;
                            let maxmol = (0..at.nlocal).filter_map(|i| body_key(custom.as_ref(), at, groupbit, i)).max().unwrap_or(-1);
                            read_infile(&d.path(&f.text), style, |id| usize::try_from(id).ok().filter(|_| id >= 1 && id <= maxmol).ok_or_else(|| format!("invalid rigid body molecule ID {id} in fix {style} infile")))
                        }
                    }
                    .map_err(|e| a.error_at(f, e, "this body file"))?;
                    reading = Some(format!("Reading rigid body data for {} bodies from file {}", file.bodies.len(), f.text));
                    (infile, reinit) = (Some(file), false);
                    continue;
                }
                "reinit" => {
                    a.skip(1);
                    reinit = a.logical("reinit (yes or no)")?;
                    continue;
                }
                "gravity" => {
                    a.skip(1);
                    gravity = Some(a.word("fix gravity ID")?.text.clone());
                    continue;
                }
                "langevin" if plain => {
                    a.skip(1);
                    let (t_start, t_stop) = (a.f64("Tstart")?, a.f64("Tstop")?);
                    let pw = a.peek().cloned();
                    let t_period = a.f64("Tperiod")?;
                    if t_period <= 0.0 {
                        return Err(a.error_at(&pw.unwrap(), format!("fix {style} langevin period must be > 0.0"), "Tperiod > 0"));
                    }
                    let seed = a.i64_in("random seed (> 0)", 1, i64::from(i32::MAX))? as i32;
                    langevin = Some(BodyLangevin { t_start, t_stop, t_period, random: RanMars::new(seed), extra: Vec::new() });
                    continue;
                }
                "langevin" => "it belongs to rigid and rigid/small (dmhs has the bodies' Langevin thermostat there only)",
                "temp" | "tparam" => "it belongs to rigid/nvt, rigid/npt and their /small forms (a thermostat)",
                "iso" | "aniso" | "x" | "y" | "z" | "couple" | "dilate" | "pchain" => "it belongs to rigid/npt, rigid/nph and their /small forms (a barostat)",
                "force" | "torque" => "it belongs to fix rigid and its integrators (one set of bodies)",
                _ => {
                    let mut known = vec!["mol", "infile", "reinit", "gravity"];
                    if global.is_some() {
                        known.extend(["force", "torque"]);
                    }
                    if plain {
                        known.push("langevin");
                    }
                    if nvt {
                        known.extend(["temp", "tparam"]);
                    }
                    if npx {
                        known.extend(["iso", "aniso", "x", "y", "z", "couple", "dilate", "pchain"]);
                    }
                    return Err(a.unknown_keyword(w, &known));
                }
            };
            return Err(a.error_at(w, format!("illegal fix {style} keyword `{}`: {what}", w.text), "not this style's keyword"));
        }
        let chains = match temp {
            Some((w, t_start, t_stop, t_period)) => {
                // rigid/nvt/small allows Tstart = 0, rigid/npt/small does not
                if (style == "rigid/npt/small" && t_start <= 0.0) || t_start < 0.0 || t_stop <= 0.0 {
                    return Err(a.error_at(w, format!("target temperature for fix {style} cannot be 0.0"), "Tstart >= 0 and Tstop > 0"));
                }
                if t_period <= 0.0 {
                    return Err(a.error_at(w, format!("fix {style} period must be > 0.0"), "Tdamp > 0"));
                }
                Some(Chains::new(t_start, t_stop, t_period, t_chain))
            }
            None if nvt => return Err(a.missing(&format!("`temp Tstart Tstop Tdamp` (did not set temp for fix {style})"))),
            None => None,
        };
        let baro = match press_word {
            Some(w) => Some(Self::barostat(&a, w, style, state, (p_start, p_stop, p_period, p_flag), couple, dilate, p_chain)?),
            None if npx => return Err(a.missing(&format!("`iso|aniso|x|y|z Pstart Pstop Pdamp` (pressure control must be used with fix {style})"))),
            None => None,
        };
        if let (Some(w), Some(_)) = (&custom_word, &template) {
            return Err(a.error_at(w, format!("fix {style} custom with a molecule template (`mol`) is not supported"), "inserted molecules are bodies by molecule ID"));
        }
        if global.is_some() && template.is_some() {
            return Err(a.error_at(&cmd.name, format!("fix {style} takes no molecule template (`mol` belongs to the /small styles)"), "not this style's keyword"));
        }
        let nh = (!plain).then(|| RigidNh::new(chains, baro, t_iter, t_order));
        let tally = ThermoTally { has_virial: true, virial_on: true, no_energy: true, ..ThermoTally::default() };
        let mut maxextent = 0.0;
        let rank = match &global {
            Some(g) => {
                state.messages.push(format!("  {} rigid bodies with {} atoms", g.nbody, g.body_of.len()));
                HashMap::new()
            }
            None => {
                // LAMMPS' create_bodies reports the bodies and their extent (a template's too)
                let (rank, mut extent) = Self::creation_order(state, groupbit, custom.as_ref());
                if let Some((_, t)) = &template {
                    extent = extent.max(t.maxextent);
                }
                maxextent = extent;
                let natoms = (0..state.atoms.nlocal).filter(|&i| body_key(custom.as_ref(), &state.atoms, groupbit, i).is_some()).count();
                state.messages.push(format!("  {} rigid bodies with {natoms} atoms\n  {} = max distance from body owner to body atom", rank.len(), dmhs_parser::numfmt::format_g(extent, 8)));
                rank
            }
        };
        // (LAMMPS reads the file at the run's setup, after the bodies' lines)
        state.messages.extend(reading);
        Ok(FixRigidSmall { id: d.id, groupbit, style, bodies: Vec::new(), members: HashMap::new(), enforce2d: false, template, tally, nh, langevin, rank, set_up: false, local: LocalMembers::default(), global, early: false, press_temp: None, reinit, infile, gravity, bodies_set_up: false, custom, maxextent })
    }

    /// LAMMPS' checks of the barostat's settings (FixRigidNHSmall's constructor).
    #[allow(clippy::too_many_arguments)]
    fn barostat(a: &Args, w: &Word, style: &str, state: &State, (p_start, p_stop, p_period, p_flag): ([f64; 3], [f64; 3], [f64; 3], [bool; 3]), couple: Couple, dilate: Option<u32>, p_chain: usize) -> DResult<Baro> {
        let dim = state.dimension;
        let bad = |m: String| Err(a.error_at(w, m, "invalid barostat settings"));
        if dim == 2 && (p_flag[2] || matches!(couple, Couple::Yz | Couple::Xz)) {
            return bad(format!("invalid fix {style} command for a 2d simulation"));
        }
        let needs: &[usize] = match couple {
            Couple::Xyz if dim == 3 => &[0, 1, 2],
            Couple::Xyz | Couple::Xy => &[0, 1],
            Couple::Yz => &[1, 2],
            Couple::Xz => &[0, 2],
            Couple::None => &[],
        };
        let same = |i: usize, j: usize| p_start[i] == p_start[j] && p_stop[i] == p_stop[j] && p_period[i] == p_period[j];
        if needs.iter().any(|&k| !p_flag[k]) || needs.windows(2).any(|p| !same(p[0], p[1])) {
            return bad(format!("invalid fix {style} command pressure settings"));
        }
        if (0..3).any(|k| p_flag[k] && !state.domain.as_ref().is_some_and(|d| d.periodic(k))) {
            return bad(format!("cannot use fix {style} on a non-periodic dimension"));
        }
        if (0..3).any(|k| p_flag[k] && p_period[k] <= 0.0) {
            return bad(format!("fix {style} damping parameters must be > 0.0"));
        }
        if (0..3).any(|k| p_start[k] < 0.0 || p_stop[k] < 0.0) {
            return bad(format!("target pressure for fix {style} cannot be < 0.0"));
        }
        Ok(Baro::new(p_start, p_stop, p_period, p_flag, couple, dilate, p_chain, dim))
    }

    /// The pressure the barostat reads (LAMMPS' compute fixID_press on compute fixID_temp,
    /// group all, coupled) and that temperature. `setup`: the temperature's degrees of freedom
    /// are counted (LAMMPS' compute setup, once per run), else the setup's count is used.
    fn measure_pressure(&mut self, state: &State, ctx: &mut FixCtx, setup: bool) -> Result<([f64; 3], f64), RunError> {
        if !self.changes_box() {
            return Ok(([0.0; 3], 0.0));
        }
        let spec = self.press_temp.clone().unwrap_or(crate::models::compute::temp_bias::TempSpec::plain(1));
        let bit = spec.groupbit;
        let (virial, fix_dof) = ctx.eval(state, &*self, |w, _| Ok((w.virial(), setup.then(|| w.fix_dof(bit)))))?;
        if let Some(fix_dof) = fix_dof {
            self.nh.as_mut().and_then(|nh| nh.baro.as_mut()).expect("a barostat").dof = spec.dof(state, fix_dof);
        }
        let b = self.nh.as_ref().and_then(|nh| nh.baro.as_ref()).expect("a barostat");
        let dof = b.dof;
        let (t, _) = spec.temperature(state, dof).map_err(|e| self.err(state, e))?;
        let volume = state.domain().map_err(|e| self.err(state, e))?.volume();
        let u = &state.units;
        let p = if b.iso {
            [crate::models::compute::pressure::scalar_pressure(state.dimension, dof * u.boltz * t, &virial, volume, u.nktv2p); 3]
        } else {
            let ke = spec.tensor(state).map_err(|e| self.err(state, e))?;
            let t = crate::models::compute::pressure::tensor_pressure(&ke, &virial, volume, u.nktv2p);
            b.couple.apply([t[0], t[1], t[2]])
        };
        if p.iter().any(|x| !x.is_finite()) {
            return Err(self.err(state, "non-numeric pressure - simulation unstable".into()));
        }
        Ok((p, t))
    }

    /// LAMMPS' create_bodies: each molecule of the group is owned by its atom closest to the
    /// centre of the molecule's bounding box (unwrapped; the smaller ID on a tie), and the
    /// bodies are numbered in the local order of their owners; also the largest distance from
    /// an owner to an atom of its body (unwrapped).
    fn creation_order(state: &State, groupbit: u32, custom: Option<&HashMap<i64, i64>>) -> (HashMap<i64, usize>, f64) {
        let a = &state.atoms;
        let Some(domain) = state.domain.as_ref() else { return (HashMap::new(), 0.0) };
        let keys: Vec<Option<i64>> = (0..a.nlocal).map(|i| body_key(custom, a, groupbit, i)).collect();
        let group: Vec<usize> = (0..a.nlocal).filter(|&i| keys[i].is_some()).collect();
        let key = |i: usize| keys[i].expect("an atom of a body");
        let mut bbox: HashMap<i64, ([f64; 3], [f64; 3])> = HashMap::new();
        for &i in &group {
            let u = domain.unmap(a.x[i], a.image[i]);
            let e = bbox.entry(key(i)).or_insert((u, u));
            for k in 0..3 {
                e.0[k] = e.0[k].min(u[k]);
                e.1[k] = e.1[k].max(u[k]);
            }
        }
        let mut close: HashMap<i64, (f64, i64)> = HashMap::new();
        for &i in &group {
            let (lo, hi) = bbox[&key(i)];
            let u = domain.unmap(a.x[i], a.image[i]);
            let d: [f64; 3] = std::array::from_fn(|k| u[k] - 0.5 * (lo[k] + hi[k]));
            let rsq = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            let e = close.entry(key(i)).or_insert((f64::INFINITY, i64::MAX));
            if rsq < e.0 || (rsq == e.0 && a.tag[i] < e.1) {
                *e = (rsq, a.tag[i]);
            }
        }
        let mut rank = HashMap::new();
        for &i in state.lammps_order.indices(a.nlocal).iter() {
            if keys[i].is_some() && close[&key(i)].1 == a.tag[i] {
                let n = rank.len();
                rank.insert(key(i), n);
            }
        }
        let map = a.tag_map();
        let mut rsqfar = 0.0f64;
        for &i in &group {
            let owner = map.get(close[&key(i)].1).expect("an owned atom");
            let (u, o) = (domain.unmap(a.x[i], a.image[i]), domain.unmap(a.x[owner], a.image[owner]));
            let d: [f64; 3] = std::array::from_fn(|k| u[k] - o[k]);
            rsqfar = rsqfar.max(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        }
        (rank, rsqfar.sqrt())
    }

    fn massone(state: &State, a: &Atoms, i: usize) -> f64 {
        if a.features.per_atom_mass() { a.rmass[i] } else { state.type_mass[a.typ[i]] }
    }

    /// The atoms the bodies are set up from, in the order their sums run: the owned atoms in
    /// LAMMPS' local order; on several ranks every rank's atoms gathered (in rank order), so
    /// that every rank sets up every body and knows every member, as a serial run.
    fn setup_atoms(state: &State) -> (std::borrow::Cow<'_, Atoms>, Vec<usize>) {
        match (&state.decomp, state.distributed) {
            (Some(d), Some(_)) => {
                let all = d.gathered(&state.atoms);
                let order = (0..all.nlocal).collect();
                (std::borrow::Cow::Owned(all), order)
            }
            _ => (std::borrow::Cow::Borrowed(&state.atoms), state.lammps_order.indices(state.atoms.nlocal).into_owned()),
        }
    }

    /// Atom `i` joins body `b` (counted as a point or a finite-size sphere).
    fn add_member(body: &mut Body, members: &mut HashMap<i64, Member>, a: &Atoms, i: usize, b: usize) {
        let sphere = a.features.sphere && a.radius[i] > 0.0;
        if sphere {
            body.nsphere += 1;
        } else {
            body.npoint += 1;
        }
        members.insert(a.tag[i], Member { body: b, displace: [0.0; 3], sphere });
    }

    /// The bodies of the group's molecules among atoms `a` (walked in `order`), in LAMMPS'
    /// body order (`rank`), with their membership counts; nothing else set.
    fn assign(&self, a: &Atoms, order: &[usize]) -> (Vec<Body>, HashMap<i64, Member>) {
        if let Some(g) = &self.global {
            // fix rigid: the bodies of the definition, in their order
            let mut bodies: Vec<Body> = (0..g.nbody).map(|k| Body { mol: k as i64 + 1, ..Body::default() }).collect();
            let mut members = HashMap::new();
            for i in 0..a.nlocal {
                let Some(&b) = g.body_of.get(&a.tag[i]) else { continue };
                Self::add_member(&mut bodies[b], &mut members, a, i, b);
            }
            return (bodies, members);
        }
        let mut bodies: Vec<Body> = Vec::new();
        let mut by_mol: HashMap<i64, usize> = HashMap::new();
        let mut members = HashMap::new();
        for &i in order {
            let Some(mol) = body_key(self.custom.as_ref(), a, self.groupbit, i) else { continue };
            let b = *by_mol.entry(mol).or_insert_with(|| {
                bodies.push(Body { mol, ..Body::default() });
                bodies.len() - 1
            });
            Self::add_member(&mut bodies[b], &mut members, a, i, b);
        }
        let mut order: Vec<usize> = (0..bodies.len()).collect();
        order.sort_by_key(|&b| self.rank.get(&bodies[b].mol).map_or((1, bodies[b].mol), |&r| (0, r as i64)));
        let mut place = vec![0; bodies.len()];
        for (new, &old) in order.iter().enumerate() {
            place[old] = new;
        }
        for m in members.values_mut() {
            m.body = place[m.body];
        }
        let bodies = order.iter().map(|&b| bodies[b].clone()).collect();
        (bodies, members)
    }

    /// The atom's body-relative image (LAMMPS' xcmimage = image - body image).
    fn xcmimage(atom: [i32; 3], body: [i32; 3]) -> [i32; 3] {
        [atom[0] - body[0], atom[1] - body[1], atom[2] - body[2]]
    }

    /// LAMMPS' setup_bodies_static and setup_bodies_dynamic.
    fn setup_bodies(&mut self, state: &State) -> Result<(), String> {
        let domain = state.domain()?.clone();
        let (a, order) = Self::setup_atoms(state);
        let a: &Atoms = &a;
        let (mut bodies, mut members) = self.assign(a, &order);
        let extended = members.values().any(|m| m.sphere);
        // centre of mass from unwrapped positions
        for &i in order.iter() {
            let Some(m) = members.get(&a.tag[i]) else { continue };
            let b = &mut bodies[m.body];
            let massone = Self::massone(state, a, i);
            let unwrap = domain.unmap(a.x[i], a.image[i]);
            for k in 0..3 {
                b.xcm[k] += unwrap[k] * massone;
            }
            b.mass += massone;
        }
        for b in bodies.iter_mut() {
            for k in 0..3 {
                b.xcm[k] /= b.mass;
            }
            b.image = [0; 3];
        }
        // infile: the atoms' dynamics first, then the file's bodies over them (LAMMPS 22 Jul
        // 2025's order in setup_bodies_static); fix rigid's file names body indices, the /small
        // styles' molecule IDs
        let infile = self.infile.as_ref();
        let by_index = self.global.is_some();
        let from_file = |k: usize, b: &Body| infile.and_then(|f| f.bodies.get(&if by_index { k } else { b.mol as usize }));
        if infile.is_some() {
            Self::setup_dynamic(&mut bodies, &members, state, a, &order, &domain);
            for (k, b) in bodies.iter_mut().enumerate() {
                if let Some(r) = from_file(k, b) {
                    (b.mass, b.xcm, b.vcm, b.angmom, b.image) = (r.mass, r.xcm, r.vcm, r.angmom, r.image);
                }
            }
        }
        // pre_neighbor: the centres wrapped into the box
        for b in bodies.iter_mut() {
            domain.remap(&mut b.xcm, &mut b.image);
        }
        // inertia tensor about the centre (Voigt: xx yy zz yz xz xy)
        let mut itensor = vec![[0.0f64; 6]; bodies.len()];
        for &i in order.iter() {
            let Some(m) = members.get(&a.tag[i]) else { continue };
            let b = &bodies[m.body];
            let unwrap = domain.unmap(a.x[i], Self::xcmimage(a.image[i], b.image));
            let d = [unwrap[0] - b.xcm[0], unwrap[1] - b.xcm[1], unwrap[2] - b.xcm[2]];
            add_point_inertia(&mut itensor[m.body], Self::massone(state, a, i), d);
        }
        if extended {
            for &i in order.iter() {
                let Some(m) = members.get(&a.tag[i]) else { continue };
                if m.sphere {
                    let massone = Self::massone(state, a, i);
                    let t = &mut itensor[m.body];
                    for k in 0..3 {
                        t[k] += SINERTIA * massone * a.radius[i] * a.radius[i];
                    }
                }
            }
        }
        for (k, b) in bodies.iter().enumerate() {
            if let Some(r) = from_file(k, b) {
                itensor[k] = r.itensor;
            }
        }
        for (b, t) in bodies.iter_mut().zip(&itensor) {
            let tensor = [[t[0], t[5], t[4]], [t[5], t[1], t[3]], [t[4], t[3], t[2]]];
            // ascending moments, so that in 2d the z axis comes last
            let Some((mut inertia, evec)) = jacobi3(&tensor, Sort::Increasing) else {
                return Err(format!("insufficient Jacobi rotations for the rigid body of molecule {}", b.mol));
            };
            let ex = [evec[0][0], evec[1][0], evec[2][0]];
            let mut ey = [evec[0][1], evec[1][1], evec[2][1]];
            let mut ez = [evec[0][2], evec[1][2], evec[2][2]];
            // 2d: the axis along z last, so the quaternion is a rotation about z
            if state.dimension == 2 && (ez[0].abs() > EPSILON || ez[1].abs() > EPSILON) {
                inertia.swap(1, 2);
                std::mem::swap(&mut ey, &mut ez);
            }
            let max = inertia[0].max(inertia[1]).max(inertia[2]);
            for k in 0..3 {
                if inertia[k] < EPSILON * max {
                    inertia[k] = 0.0;
                }
            }
            // right-handed axes
            let cross = quat::cross3(&ex, &ey);
            if cross[0] * ez[0] + cross[1] * ez[1] + cross[2] * ez[2] < 0.0 {
                ez = [-ez[0], -ez[1], -ez[2]];
            }
            b.quat = quat::exyz_to_q(&ex, &ey, &ez);
            (b.inertia, b.ex, b.ey, b.ez) = (inertia, ex, ey, ez);
        }
        // displacements in the body frame
        for &i in order.iter() {
            let Some(m) = members.get_mut(&a.tag[i]) else { continue };
            let b = &bodies[m.body];
            let unwrap = domain.unmap(a.x[i], Self::xcmimage(a.image[i], b.image));
            let delta = [unwrap[0] - b.xcm[0], unwrap[1] - b.xcm[1], unwrap[2] - b.xcm[2]];
            m.displace = quat::transpose_matvec_cols(&b.ex, &b.ey, &b.ez, &delta);
        }
        if infile.is_none() {
            Self::setup_dynamic(&mut bodies, &members, state, a, &order, &domain);
        }
        self.bodies = bodies;
        self.members = members;
        self.local.tags.clear();
        self.bodies_set_up = true;
        Ok(())
    }

    /// LAMMPS' setup_bodies_dynamic: vcm and angular momentum from the atoms' velocities, about
    /// the bodies' centres as they are.
    fn setup_dynamic(bodies: &mut [Body], members: &HashMap<i64, Member>, state: &State, a: &Atoms, order: &[usize], domain: &crate::engine::domain::Domain) {
        for b in bodies.iter_mut() {
            (b.vcm, b.angmom) = ([0.0; 3], [0.0; 3]);
        }
        for &i in order.iter() {
            let Some(m) = members.get(&a.tag[i]) else { continue };
            let b = &mut bodies[m.body];
            let massone = Self::massone(state, a, i);
            let v = a.v[i];
            for k in 0..3 {
                b.vcm[k] += v[k] * massone;
            }
            let unwrap = domain.unmap(a.x[i], Self::xcmimage(a.image[i], b.image));
            let (dx, dy, dz) = (unwrap[0] - b.xcm[0], unwrap[1] - b.xcm[1], unwrap[2] - b.xcm[2]);
            b.angmom[0] += dy * massone * v[2] - dz * massone * v[1];
            b.angmom[1] += dz * massone * v[0] - dx * massone * v[2];
            b.angmom[2] += dx * massone * v[1] - dy * massone * v[0];
        }
        if members.values().any(|m| m.sphere) {
            for &i in order.iter() {
                let Some(m) = members.get(&a.tag[i]) else { continue };
                if m.sphere {
                    let b = &mut bodies[m.body];
                    let radone = a.radius[i];
                    for k in 0..3 {
                        b.angmom[k] += SINERTIA * a.rmass[i] * radone * radone * a.omega[i][k];
                    }
                }
            }
        }
        for b in bodies.iter_mut() {
            for k in 0..3 {
                b.vcm[k] /= b.mass;
            }
        }
    }

    /// The members of the owned atoms by local index, renewed when the atoms' IDs changed.
    fn refresh_local(&mut self, state: &State) {
        let tags = &state.atoms.tag[..state.atoms.nlocal];
        if self.local.tags.as_slice() != tags {
            self.local.tags = tags.to_vec();
            self.local.slot = tags.iter().map(|t| self.members.get(t).copied()).collect();
        }
    }

    /// Force and torque on each body from its atoms (LAMMPS' compute_forces_and_torques).
    fn forces_and_torques(&mut self, state: &State) -> Result<(), String> {
        self.refresh_local(state);
        let domain = state.domain()?;
        let a = &state.atoms;
        for b in self.bodies.iter_mut() {
            b.fcm = [0.0; 3];
            b.torque = [0.0; 3];
        }
        let order = state.lammps_order.indices(a.nlocal);
        for &i in order.iter() {
            let Some(m) = self.local.slot[i] else { continue };
            let b = &mut self.bodies[m.body];
            let f = a.f[i];
            for k in 0..3 {
                b.fcm[k] += f[k];
            }
            let unwrap = domain.unmap(a.x[i], Self::xcmimage(a.image[i], b.image));
            let (dx, dy, dz) = (unwrap[0] - b.xcm[0], unwrap[1] - b.xcm[1], unwrap[2] - b.xcm[2]);
            b.torque[0] += dy * f[2] - dz * f[1];
            b.torque[1] += dz * f[0] - dx * f[2];
            b.torque[2] += dx * f[1] - dy * f[0];
        }
        if self.members.values().any(|m| m.sphere) {
            for &i in order.iter() {
                let Some(m) = self.local.slot[i] else { continue };
                if m.sphere {
                    let t = &mut self.bodies[m.body].torque;
                    for k in 0..3 {
                        t[k] += a.torque[i][k];
                    }
                }
            }
        }
        if state.distributed.is_some() {
            // each rank summed its own atoms: every rank gets the bodies' totals
            let mut sums: Vec<f64> = self.bodies.iter().flat_map(|b| b.fcm.into_iter().chain(b.torque)).collect();
            state.sum_ranks(&mut sums);
            for (b, s) in self.bodies.iter_mut().zip(sums.chunks_exact(6)) {
                b.fcm = [s[0], s[1], s[2]];
                b.torque = [s[3], s[4], s[5]];
            }
        }
        Ok(())
    }

    /// The thermostat's force and torque on each body (after forces_and_torques at the final
    /// half step; not at setup, as LAMMPS).
    fn add_langevin(&mut self) {
        let Some(l) = &self.langevin else { return };
        for (b, e) in self.bodies.iter_mut().zip(&l.extra) {
            for k in 0..3 {
                b.fcm[k] += e[k];
            }
            for k in 0..3 {
                b.torque[k] += e[3 + k];
            }
        }
    }

    /// `gravity FIXID`: m g on each body's centre of mass, with the fix gravity's acceleration of
    /// this step (after the thermostat's force, as LAMMPS' compute_forces_and_torques).
    fn add_gravity(&mut self, ctx: &FixCtx) {
        let Some(id) = &self.gravity else { return };
        let Some(g) = ctx.other_fixes().find(|f| f.id() == id).and_then(|f| f.gravity()) else { return };
        for b in self.bodies.iter_mut() {
            for k in 0..3 {
                b.fcm[k] += g.acc[k] * b.mass;
            }
        }
    }

    /// Positions (`with_x`) and velocities of the body atoms from their bodies (LAMMPS'
    /// set_xv and set_v); spheres take the body's angular velocity. Each call tallies half the
    /// virial of the constraint forces, m dv / dtf - f at the unwrapped position before the
    /// move, in LAMMPS' local order (the other half comes from the other call of the step).
    fn set_atoms(&mut self, state: &mut State, with_x: bool) -> Result<(), String> {
        self.refresh_local(state);
        let periods = state.domain()?.periods();
        let dtf = 0.5 * state.dt * state.units.ftm2v;
        let per_atom_mass = state.atoms.features.per_atom_mass();
        let order = state.lammps_order.indices(state.atoms.nlocal);
        let a = &mut state.atoms;
        let (members, bodies, tally) = (&self.local.slot, &self.bodies, &mut self.tally);
        for &i in order.iter() {
            let Some(m) = members[i] else { continue };
            let b = &bodies[m.body];
            let xbox = Self::xcmimage(a.image[i], b.image);
            let x0 = periods.unmap(a.x[i], xbox);
            let v0 = a.v[i];
            let d = quat::matvec_cols(&b.ex, &b.ey, &b.ez, &m.displace);
            a.v[i] = [
                b.omega[1] * d[2] - b.omega[2] * d[1] + b.vcm[0],
                b.omega[2] * d[0] - b.omega[0] * d[2] + b.vcm[1],
                b.omega[0] * d[1] - b.omega[1] * d[0] + b.vcm[2],
            ];
            if with_x {
                // back by the atom's images, as LAMMPS: xcm - xbox a - ybox b - zbox c
                let (p, m) = (periods.prd, xbox.map(|k| k as f64));
                let x = match periods.tilt {
                    None => [d[0] + (b.xcm[0] - m[0] * p[0]), d[1] + (b.xcm[1] - m[1] * p[1]), d[2] + (b.xcm[2] - m[2] * p[2])],
                    Some([xy, xz, yz]) => [
                        d[0] + (b.xcm[0] - m[0] * p[0] - m[1] * xy - m[2] * xz),
                        d[1] + (b.xcm[1] - m[1] * p[1] - m[2] * yz),
                        d[2] + (b.xcm[2] - m[2] * p[2]),
                    ],
                };
                a.x[i] = x;
            }
            if m.sphere {
                a.omega[i] = b.omega;
            }
            if tally.virial_on {
                let massone = if per_atom_mass { a.rmass[i] } else { state.type_mass[a.typ[i]] };
                let (v, f) = (a.v[i], a.f[i]);
                let fc = [massone * (v[0] - v0[0]) / dtf - f[0], massone * (v[1] - v0[1]) / dtf - f[1], massone * (v[2] - v0[2]) / dtf - f[2]];
                tally.v_tally([0.5 * x0[0] * fc[0], 0.5 * x0[1] * fc[1], 0.5 * x0[2] * fc[2], 0.5 * x0[0] * fc[1], 0.5 * x0[0] * fc[2], 0.5 * x0[1] * fc[2]]);
            }
        }
        Ok(())
    }

    /// LAMMPS' apply_langevin_thermostat: drag on the half-step vcm and omega, and uniform
    /// kicks scaled to the target temperature of the run's ramp.
    fn draw_langevin(&mut self, state: &State) {
        let Some(l) = self.langevin.as_mut() else { return };
        let t_target = l.t_start + run_fraction(state) * (l.t_stop - l.t_start);
        let tsqrt = t_target.sqrt();
        let u = &state.units;
        let kick = (24.0 * u.boltz / l.t_period / state.dt / u.mvv2e).sqrt();
        // the rotational drag and kick are the same for every body
        let (gamma1_rot, gamma2_rot) = (-1.0 / l.t_period / u.ftm2v, tsqrt * kick / u.ftm2v);
        l.extra.resize(self.bodies.len(), [0.0; 6]);
        for (b, e) in self.bodies.iter().zip(l.extra.iter_mut()) {
            let gamma1 = -b.mass / l.t_period / u.ftm2v;
            let gamma2 = b.mass.sqrt() * tsqrt * kick / u.ftm2v;
            for k in 0..3 {
                e[k] = gamma1 * b.vcm[k] + gamma2 * (l.random.uniform() - 0.5);
            }
            // the torque in the body frame, where the moments are
            let (gamma1, gamma2) = (gamma1_rot, gamma2_rot);
            let wbody = quat::transpose_matvec_cols(&b.ex, &b.ey, &b.ez, &b.omega);
            let mut tbody = [0.0; 3];
            for k in 0..3 {
                tbody[k] = b.inertia[k] * gamma1 * wbody[k] + b.inertia[k].sqrt() * gamma2 * (l.random.uniform() - 0.5);
            }
            let t = quat::matvec_cols(&b.ex, &b.ey, &b.ez, &tbody);
            e[3..].copy_from_slice(&t);
            if state.dimension == 2 {
                (e[2], e[3], e[4]) = (0.0, 0.0, 0.0);
            }
        }
    }

    /// LAMMPS' FixRigidSmall::enforce2d, called from fix enforce2d's post_force.
    fn zero_out_of_plane(&mut self) {
        if let Some(l) = self.langevin.as_mut() {
            for e in l.extra.iter_mut() {
                (e[2], e[3], e[4]) = (0.0, 0.0, 0.0);
            }
        }
        for b in self.bodies.iter_mut() {
            b.xcm[2] = 0.0;
            b.vcm[2] = 0.0;
            b.fcm[2] = 0.0;
            b.torque[0] = 0.0;
            b.torque[1] = 0.0;
            b.angmom[0] = 0.0;
            b.angmom[1] = 0.0;
            b.omega[0] = 0.0;
            b.omega[1] = 0.0;
        }
    }

    fn err(&self, state: &State, e: String) -> RunError {
        RunError::new(state.step, format!("fix {} ({}): {e}", self.id, self.style))
    }
}

impl Fix for FixRigidSmall {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        self.style
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn time_integrate(&self) -> bool {
        true
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { initial_integrate: true, pre_exchange: true, post_force: self.langevin.is_some() || self.early, final_integrate: true, ..FixHooks::default() }
    }
    fn min_role(&self) -> MinRole {
        MinRole::Refused(format!("fix {} ({}) is not supported in minimize", self.id, self.style))
    }
    fn init(&mut self, state: &State, ctx: &FixCtx) -> Result<(), String> {
        if let Some(f) = ctx.others[0].iter().find(|f| f.style() == "enforce2d") {
            return Err(format!("fix enforce2d {} must be defined after fix {} ({})", f.id(), self.id, self.style));
        }
        self.enforce2d = state.dimension == 2 && ctx.others[1].iter().any(|f| f.style() == "enforce2d");
        // fix rigid sets its bodies up here, before the run wraps and sorts the atoms (LAMMPS'
        // FixRigid::init); rigid/small at setup_pre_force
        if self.global.is_some() && (self.reinit || !self.bodies_set_up) {
            self.setup_bodies(state)?;
        }
        self.set_up = true;
        if let Some(id) = &self.gravity {
            match ctx.other_fixes().find(|f| f.id() == id) {
                None => return Err(format!("fix {} cannot find fix gravity ID {id}", self.style)),
                Some(f) if f.gravity().is_none() => return Err(format!("fix {} gravity fix ID {id} is not a gravity fix style", self.style)),
                Some(_) => {}
            }
        }
        if let Some(nh) = self.nh.as_mut().filter(|nh| nh.baro.is_some()) {
            // LAMMPS' own restriction (FixRigidNH and FixRigidNHSmall init)
            if state.domain()?.triclinic() {
                return Err(format!("fix {} does not yet allow triclinic box", self.style));
            }
            if let Some(f) = ctx.other_fixes().find(|f| f.style() == "deform" || f.changes_box()) {
                return Err(format!("fix {} ({}) with fix {} ({}): dmhs does not combine a rigid barostat with another fix that changes the box", self.id, self.style, f.id(), f.style()));
            }
            if let Some(f) = ctx.other_fixes().find(|f| f.rigid_template().is_some()) {
                return Err(format!("fix {} ({}) with fix {} ({}): the barostat moves only its own bodies with the box", self.id, self.style, f.id(), f.style()));
            }
            nh.init(state.domain()?.volume());
        }
        Ok(())
    }
    /// LAMMPS' warnings at a rigid fix's init: another rigid fix; gravity on bodies whose mass
    /// and centre come from a file or template but not from the `gravity` keyword; with
    /// `bodyforces early`, fixes after the first rigid fix that change forces after the sums.
    fn init_warnings(&self, [before, after]: [&[Box<dyn Fix>]; 2]) -> Vec<String> {
        let rigid = |f: &&Box<dyn Fix>| f.rigid_template().is_some();
        let mut out = Vec::new();
        if before.iter().chain(after).any(|f| rigid(&f)) {
            out.push(if self.global.is_some() { "More than one fix rigid" } else { "More than one fix rigid command" }.to_string());
        }
        if (self.infile.is_some() || self.template.is_some()) && self.gravity.is_none() && before.iter().chain(after).any(|f| f.style() == "gravity") {
            out.push("Gravity may not be correctly applied to rigid bodies if they consist of overlapped particles".to_string());
        }
        if self.early {
            let first = before.iter().position(|f| rigid(&f)).unwrap_or(before.len());
            for f in before[first..].iter().chain(after) {
                if !rigid(&f) && f.hooks().post_force {
                    out.push(format!("Fix {} with ID {} alters forces after fix rigid", f.style(), f.id()));
                }
            }
        }
        out
    }
    fn setup_pre_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        // fix rigid set its bodies up at init
        if self.global.is_some() {
            return Ok(());
        }
        if self.reinit || !self.bodies_set_up {
            return self.setup_bodies(state).map_err(|e| self.err(state, e));
        }
        // the bodies kept: LAMMPS' pre_neighbor (centres back into the box)
        self.pre_exchange(state, ctx)
    }
    fn setup(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        // LAMMPS' check for the /small styles, here because the lists' cutoff is known now
        let cutghost = state.neighbor.cutneighmax.max(state.comm_cutoff);
        if self.global.is_none() && self.maxextent > cutghost {
            return Err(self.err(state, format!("Rigid body extent {} > ghost atom cutoff - use comm_modify cutoff", self.maxextent)));
        }
        self.forces_and_torques(state).map_err(|e| self.err(state, e))?;
        self.add_gravity(ctx);
        for b in self.bodies.iter_mut() {
            b.omega = quat::angmom_to_omega(&b.angmom, &b.ex, &b.ey, &b.ez, &b.inertia);
        }
        self.tally.v_init();
        self.set_atoms(state, false).map_err(|e| self.err(state, e))?;
        // LAMMPS' guess of the setup virial: twice the set_v half
        for v in self.tally.virial.iter_mut() {
            *v *= 2.0;
        }
        let (p_current, t_now) = self.measure_pressure(state, ctx, true)?;
        let volume = state.domain().map_err(|e| self.err(state, e))?.volume();
        if let Some(nh) = self.nh.as_mut() {
            if let Some(b) = nh.baro.as_mut() {
                b.p_current = p_current;
            }
            nh.setup(&mut self.bodies, state.dimension, &state.units, run_fraction(state), state.dt, t_now, volume);
        }
        // fix enforce2d's setup (its post_force) follows
        if self.enforce2d {
            self.zero_out_of_plane();
        }
        Ok(())
    }
    fn initial_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        let dtv = state.dt;
        let dtf = 0.5 * state.dt * state.units.ftm2v;
        let dtq = 0.5 * state.dt;
        if let Some(nh) = self.nh.as_mut() {
            let flags = self.global.as_ref().map(|g| (&g.fflag[..], &g.tflag[..]));
            nh.initial_integrate(&mut self.bodies, &Steps { dtv, dtf, dtq }, state.dimension, &state.units, run_fraction(state), flags);
            self.tally.v_init();
            // a barostat scales the box by half a step before and after the atoms are placed
            nh.remap(state, &mut self.bodies, dtq).map_err(|e| RunError::new(state.step, format!("fix {} ({}): {e}", self.id, self.style)))?;
            self.set_atoms(state, true).map_err(|e| self.err(state, e))?;
            let nh = self.nh.as_mut().expect("checked above");
            return nh.remap(state, &mut self.bodies, dtq).map_err(|e| RunError::new(state.step, format!("fix {} ({}): {e}", self.id, self.style)));
        }
        let flags = self.global.as_ref().map(|g| (&g.fflag[..], &g.tflag[..]));
        for (n, b) in self.bodies.iter_mut().enumerate() {
            let (ff, tf) = flags.map_or(([1.0; 3], [1.0; 3]), |(f, t)| (f[n], t[n]));
            let dtfm = dtf / b.mass;
            for k in 0..3 {
                b.vcm[k] += dtfm * b.fcm[k] * ff[k];
            }
            for k in 0..3 {
                b.xcm[k] += dtv * b.vcm[k];
            }
            for k in 0..3 {
                b.angmom[k] += dtf * b.torque[k] * tf[k];
            }
            b.omega = quat::angmom_to_omega(&b.angmom, &b.ex, &b.ey, &b.ez, &b.inertia);
            quat::richardson(&mut b.quat, &b.angmom, &mut b.omega, &b.inertia, dtq);
            [b.ex, b.ey, b.ez] = quat::q_to_exyz(&b.quat);
        }
        self.tally.v_init();
        self.set_atoms(state, true).map_err(|e| self.err(state, e))
    }
    /// The Langevin draw, then (`bodyforces early`) the bodies' forces and torques.
    fn post_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.draw_langevin(state);
        if self.early {
            self.forces_and_torques(state).map_err(|e| self.err(state, e))?;
            self.add_langevin();
            self.add_gravity(ctx);
        }
        Ok(())
    }
    fn modify_temp(&mut self, spec: crate::models::compute::temp_bias::TempSpec) -> Result<(), String> {
        if self.nh.is_none() {
            return Err(format!("fix {} ({}) has no temperature to replace (fix_modify temp belongs to the rigid thermostats and barostats)", self.id, self.style));
        }
        if !matches!(spec.bias, crate::models::compute::temp_bias::Bias::None) {
            return Err(format!("fix {} ({}): a temperature with a velocity bias is not supported here", self.id, self.style));
        }
        self.press_temp = Some(spec);
        Ok(())
    }
    fn set_body_forces_early(&mut self, early: bool) -> Result<(), String> {
        self.early = early;
        Ok(())
    }
    fn pre_exchange(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        // LAMMPS' pre_neighbor: centres back into the box (atoms' images follow their wrap)
        let domain = state.domain().map_err(|e| self.err(state, e))?.clone();
        for b in self.bodies.iter_mut() {
            domain.remap(&mut b.xcm, &mut b.image);
        }
        Ok(())
    }
    fn final_integrate(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        // fix enforce2d's post_force came between the two halves
        if self.enforce2d {
            self.zero_out_of_plane();
        }
        if !self.early {
            self.forces_and_torques(state).map_err(|e| self.err(state, e))?;
            self.add_langevin();
            self.add_gravity(ctx);
        }
        let dtf = 0.5 * state.dt * state.units.ftm2v;
        if let Some(nh) = self.nh.as_mut() {
            let flags = self.global.as_ref().map(|g| (&g.fflag[..], &g.tflag[..]));
            nh.final_integrate(&mut self.bodies, &Steps { dtv: state.dt, dtf, dtq: 0.5 * state.dt }, flags);
            self.set_atoms(state, false).map_err(|e| self.err(state, e))?;
            if self.changes_box() {
                let (p_current, _) = self.measure_pressure(state, ctx, false)?;
                let volume = state.domain().map_err(|e| self.err(state, e))?.volume();
                let nh = self.nh.as_mut().expect("checked above");
                nh.baro.as_mut().expect("checked above").p_current = p_current;
                nh.end_of_final(&state.units, 0.5 * state.dt, volume, run_fraction(state));
            }
            return Ok(());
        }
        let flags = self.global.as_ref().map(|g| (&g.fflag[..], &g.tflag[..]));
        for (n, b) in self.bodies.iter_mut().enumerate() {
            let (ff, tf) = flags.map_or(([1.0; 3], [1.0; 3]), |(f, t)| (f[n], t[n]));
            let dtfm = dtf / b.mass;
            for k in 0..3 {
                b.vcm[k] += dtfm * b.fcm[k] * ff[k];
            }
            for k in 0..3 {
                b.angmom[k] += dtf * b.torque[k] * tf[k];
            }
            b.omega = quat::angmom_to_omega(&b.angmom, &b.ex, &b.ey, &b.ez, &b.inertia);
        }
        self.set_atoms(state, false).map_err(|e| self.err(state, e))
    }
    /// The temperature of the bodies (LAMMPS' compute_scalar): translational and rotational
    /// (in the body frame) kinetic energy over 6 degrees of freedom per body.
    fn scalar(&self, state: &State) -> Option<f64> {
        let volume = state.domain.as_ref().map_or(0.0, |d| d.volume());
        if let (Some(nh), None) = (&self.nh, &self.global) {
            return Some(nh.scalar(&self.bodies, &state.units, volume));
        }
        if let Some(g) = &self.global {
            // LAMMPS' FixRigid::compute_scalar: the switched-on components only
            let mut t = 0.0;
            for (n, b) in self.bodies.iter().enumerate() {
                let (ff, tf, v) = (g.fflag[n], g.tflag[n], b.vcm);
                t += b.mass * (ff[0] * v[0] * v[0] + ff[1] * v[1] * v[1] + ff[2] * v[2] * v[2]);
                let w = b.wbody();
                t += tf[0] * b.inertia[0] * w[0] * w[0] + tf[1] * b.inertia[1] * w[1] * w[1] + tf[2] * b.inertia[2] * w[2] * w[2];
            }
            let nlinear = self.bodies.iter().filter(|b| state.dimension == 3 && b.inertia.contains(&0.0)).count();
            let ndof = g.ndof(nlinear);
            let tfactor = if ndof > 0.0 { state.units.mvv2e / (ndof * state.units.boltz) } else { 0.0 };
            // FixRigidNH: the temperature plus the chains' and the barostat's energies
            return Some(self.nh.as_ref().map_or(t * tfactor, |nh| nh.extended(t * tfactor, &state.units, volume)));
        }
        let mut t = 0.0;
        for b in &self.bodies {
            let vcm = b.vcm;
            t += b.mass * (vcm[0] * vcm[0] + vcm[1] * vcm[1] + vcm[2] * vcm[2]);
            let wbody = b.wbody();
            t += b.inertia[0] * wbody[0] * wbody[0] + b.inertia[1] * wbody[1] * wbody[1] + b.inertia[2] * wbody[2] * wbody[2];
        }
        let tfactor = state.units.mvv2e / (6.0 * self.bodies.len() as f64 * state.units.boltz);
        Some(t * tfactor)
    }
    /// fix rigid's per-body array (LAMMPS' compute_array): centre, vcm, force, torque, image.
    fn array(&self, _state: &State, i: usize, j: usize) -> Option<f64> {
        self.global.as_ref()?;
        let b = self.bodies.get(i.checked_sub(1)?)?;
        let j = j.checked_sub(1)?;
        Some(match j {
            0..=2 => b.xcm[j],
            3..=5 => b.vcm[j - 3],
            6..=8 => b.fcm[j - 6],
            9..=11 => b.torque[j - 9],
            12..=14 => b.image[j - 12] as f64,
            _ => return None,
        })
    }
    fn size_array(&self) -> Option<(usize, usize)> {
        self.global.as_ref().map(|g| (g.nbody, 15))
    }
    fn rigid_kinetic(&self) -> Option<[f64; 2]> {
        let (mut ke, mut erot) = (0.0, 0.0);
        for b in &self.bodies {
            let v = b.vcm;
            ke += b.mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            let wbody = b.wbody();
            erot += b.inertia[0] * wbody[0] * wbody[0] + b.inertia[1] * wbody[1] * wbody[1] + b.inertia[2] * wbody[2] * wbody[2];
        }
        Some([0.5 * ke, 0.5 * erot])
    }
    fn rigid_template(&self) -> Option<&str> {
        Some(self.template.as_ref().map_or("", |(id, _)| id.as_str()))
    }
    fn rigid_body_mass(&self, state: &State) -> Option<Vec<f64>> {
        let a = &state.atoms;
        Some((0..a.nall()).map(|i| self.members.get(&a.tag[i]).map_or(0.0, |m| self.bodies[m.body].mass)).collect())
    }
    /// LAMMPS' set_molecule: the body from the template's mass, COM, moments and orientation,
    /// turned by the insertion's quaternion; the atoms keep the template's body-frame
    /// displacements; no angular momentum. The centre is wrapped as at a rebuild.
    fn add_rigid_molecule(&mut self, state: &State, ins: &RigidInsert) -> Result<(), String> {
        let Some((_, t)) = &self.template else {
            return Err(format!("fix {} ({}) has no molecule template (`mol TEMPLATE`) for inserted bodies", self.id, self.style));
        };
        let rot = quat::quat_to_mat(&ins.quat);
        let ctr2com = [t.com[0] - t.center[0], t.com[1] - t.center[1], t.com[2] - t.center[2]];
        let d = quat::matvec(&rot, &ctr2com);
        let mut xcm = [d[0] + ins.xgeom[0], d[1] + ins.xgeom[1], d[2] + ins.xgeom[2]];
        let q = quat::quatquat(&ins.quat, &t.quat);
        let [ex, ey, ez] = quat::q_to_exyz(&q);
        let mut image = [0; 3];
        state.domain()?.remap(&mut xcm, &mut image);
        let n = t.dxbody.len();
        let body = Body {
            mol: ins.mol,
            mass: t.masstotal,
            xcm,
            vcm: ins.vcm,
            inertia: t.inertia,
            quat: q,
            ex,
            ey,
            ez,
            image,
            npoint: if t.spheres { 0 } else { n },
            nsphere: if t.spheres { n } else { 0 },
            ..Body::default()
        };
        self.bodies.push(body);
        let b = self.bodies.len() - 1;
        for (m, &displace) in t.dxbody.iter().enumerate() {
            self.members.insert(ins.tagprev + m as i64 + 1, Member { body: b, displace, sphere: t.spheres });
        }
        self.local.tags.clear();
        Ok(())
    }
    fn dof_removed(&self, state: &State, groupbit: u32) -> f64 {
        // LAMMPS' FixRigidSmall::dof: none before the bodies are set up (LAMMPS warns "Cannot
        // count rigid body degrees-of-freedom before bodies are fully initialized"); then each
        // body wholly in the temperature group keeps 6 (3d; 5 if linear) or 3 (2d) degrees of
        // freedom of its 3N+6M (2N+3M)
        if !self.set_up {
            return 0.0;
        }
        // (on several ranks every rank's atoms, gathered)
        let (a, order) = Self::setup_atoms(state);
        let (bodies, members) = self.assign(&a, &order);
        let mut in_group = vec![0usize; bodies.len()];
        for i in 0..a.nlocal {
            if let Some(m) = members.get(&a.tag[i]) {
                if a.mask[i] & groupbit != 0 {
                    in_group[m.body] += 1;
                }
            }
        }
        let linear_mols: std::collections::HashSet<i64> = self.bodies.iter().filter(|s| s.inertia.contains(&0.0)).map(|s| s.mol).collect();
        let mut n = 0i64;
        for (k, b) in bodies.iter().enumerate() {
            if in_group[k] != b.npoint + b.nsphere {
                continue;
            }
            let (np, ns) = (b.npoint as i64, b.nsphere as i64);
            if state.dimension == 3 {
                n += 3 * np + 6 * ns - 6;
                // linear bodies (a zero principal moment) keep 5
                if linear_mols.contains(&b.mol) {
                    n += 1;
                }
            } else {
                n += 2 * np + 3 * ns - 3;
            }
        }
        n as f64
    }
    fn thermo_tally(&self) -> Option<&ThermoTally> {
        Some(&self.tally)
    }
    fn thermo_tally_mut(&mut self) -> Option<&mut ThermoTally> {
        Some(&mut self.tally)
    }
    /// The thermostat's and barostat's chains (LAMMPS' restart_global); the bodies are set up
    /// anew.
    fn write_restart(&self) -> Option<Vec<f64>> {
        self.nh.as_ref().filter(|nh| nh.chains.is_some() || nh.baro.is_some()).map(|nh| nh.write_restart())
    }
    fn restart(&mut self, values: &[f64]) {
        if let Some(nh) = self.nh.as_mut() {
            nh.restart(values);
        }
    }
    /// The thermostatted or barostatted styles' scalar is the energy of the extended system
    /// (extensive, and in ecouple).
    fn extensive(&self, _index: Option<usize>) -> bool {
        self.nh.as_ref().is_some_and(|nh| nh.chains.is_some() || nh.baro.is_some())
    }
    fn couples_energy(&self) -> bool {
        self.extensive(None)
    }
    fn changes_box(&self) -> bool {
        self.nh.as_ref().is_some_and(|nh| nh.baro.is_some())
    }
    /// The barostat reads the virial every step (LAMMPS' pressure->addstep(ntimestep+1)).
    fn wants_energy(&self, _step: i64) -> bool {
        self.changes_box()
    }
    fn set_dynamic_dof(&mut self, on: bool) {
        if let Some(nh) = self.nh.as_mut() {
            nh.dynamic = on;
        }
    }
    fn describe(&self) -> String {
        format!("fix {} {}: {} rigid bodies", self.id, self.style, self.bodies.len())
    }
}
