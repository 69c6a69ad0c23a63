//! `fix ID group wall/gran granular NORMAL coeffs [damping ...] [tangential ...] [limit_damping]
//! xplane|yplane|zplane lo hi [wiggle dim A period | shear dim v]`: a flat frictional wall
//! pair of planes at lo and hi (NULL: none) acting on spheres with the sub-models of
//! `pair_style granular` (see [`crate::models::pair::granular`]), as LAMMPS 2025's fix wall/gran.
//! Material models (hertz/material, dmt) use the wall rule E_eff = E/(2 (1-nu^2)): the sphere's
//! material against a rigid wall (LAMMPS' contact_type WALL).
//!
//! Each sphere interacts with the nearer of the two planes; its tangential spring (3 values per
//! atom) lives in the atoms' extra arrays, so it follows the atom through sorting and is saved
//! by write_restart. The wall has radius 0 and the sphere's full mass; the torque lever is the
//! full radius.
//!
//! `contacts` gives the per-atom array of LAMMPS (8 columns, f_ID[1..8]): 1 where the atom
//! touches the wall this step, the wall's force on it (3), the contact point x - dx (3) and its
//! radius; zero for every other owned atom. It lives in the atoms' extra arrays too.
//!
//! LAMMPS' classic forms `hooke|hooke/history|hertz/history Kn Kt gamma_n gamma_t xmu dampflag`
//! are LAMMPS 2025's: sub-models of the granular form chosen as its GranularModel chooses them
//! ([`classic_spec`]). So `hooke/history` uses linear_history_classic, whose spring creeps (a
//! sphere resting on a 0.2 slope with mu 0.3 moves 57 times the elastic m g sin(theta)/k_t, as
//! in LAMMPS); `dmhs check` warns, and the `granular` form with linear_history avoids it.

use super::{Fix, FixCtx, FixHooks};
use crate::models::pair::classic::Classic;
use crate::models::pair::contact::Contact;
use crate::models::pair::contact::MAX_HISTORY;
use super::value::FixValue;
use crate::engine::fields::{HEATFLOW, TEMPERATURE};
use crate::models::pair::granular::{check_heat_fields, contact_heat, granular_contact, model_syntax, GranModel, GranSpec};
use crate::engine::state::{RunError, State};
use crate::engine::par::{ranges, AtomsMut};
use dmhs_parser::{Args, Command, DResult, Word};

pub(super) fn syntax() -> &'static str {
    static S: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    S.get_or_init(|| {
        format!(
            "fix ID group wall/gran granular {} | hooke|hooke/history|hertz/history Kn Kt gamma_n gamma_t xmu dampflag [limit_damping]  xplane|yplane|zplane lo hi [wiggle x|y|z A period | shear x|y|z v] [temperature T] [contacts]",
            model_syntax()
        )
    })
}

/// The granular sub-models LAMMPS 2025 builds for a classic wall form (its
/// `GranularModel::define_classic_model`): `hooke` = hooke + linear_nohistory + mass_velocity,
/// `hooke/history` = hooke + linear_history_classic + mass_velocity, `hertz/history` = hertz +
/// mindlin_classic + viscoelastic; normal coefficients [Kn, gamma_n] and tangential [Kt,
/// gamma_t/gamma_n, xmu] ([gamma_t/gamma_n, xmu] for linear_nohistory, which has no spring;
/// measured against LAMMPS 22 Jul 2025: lammps-refs deck gran_wall_classic).
fn classic_spec(form: &str, c: &Classic, limit_damping: bool) -> Result<GranSpec, String> {
    use crate::models::pair::granular::{damping, normal, tangential, Given, MAX_COEFFS};
    let (n, t, d) = match form {
        "hooke" => ("hooke", "linear_nohistory", "mass_velocity"),
        "hooke/history" => ("hooke", "linear_history_classic", "mass_velocity"),
        _ => ("hertz", "mindlin_classic", "viscoelastic"),
    };
    fn named<M>(table: &'static [crate::models::pair::granular::Style<M>], name: &str, form: &str) -> Result<&'static crate::models::pair::granular::Style<M>, String> {
        table.iter().find(|s| s.name == name).ok_or_else(|| format!("fix wall/gran {form} needs the granular model {name}, which dmhs does not have yet"))
    }
    let coeffs = |v: &[f64]| {
        let mut k = [0.0; MAX_COEFFS];
        k[..v.len()].copy_from_slice(v);
        k
    };
    Ok(GranSpec {
        set: true,
        normal: Given { style: named(normal::STYLES, n, form)?, coeffs: coeffs(&[c.kn, c.gamman]) },
        damping: Given { style: named(damping::STYLES, d, form)?, coeffs: coeffs(&[]) },
        tangential: Given { style: named(tangential::STYLES, t, form)?, coeffs: if t == "linear_nohistory" { coeffs(&[c.gammat / c.gamman, c.xmu]) } else { coeffs(&[c.kt, c.gammat / c.gamman, c.xmu]) } },
        limit_damping,
        ..GranSpec::default()
    })
}


/// The contact model of a granular wall (fix wall/gran and wall/gran/region): the `granular`
/// form's sub-models or a classic form, read from `a`.
pub(super) fn parse_model(a: &mut Args, cmd: &Command, syntax: &str, state: &mut State) -> DResult<GranSpec> {
    let first = a.word("the contact model form (granular, hooke, hooke/history or hertz/history)")?;
    let spec = match first.text.as_str() {
        "granular" => GranSpec::parse(a, true)?,
        "hooke" | "hooke/history" | "hertz/history" => {
            let n = a.len_remaining().min(6);
            let c = Classic::from_lammps_words(&a.remaining()[..n], cmd, syntax)?;
            a.skip(n);
            let limit_damping = a.peek().map(|w| w.text == "limit_damping").unwrap_or(false);
            if limit_damping {
                a.skip(1);
            }
            if first.text == "hooke/history" {
                state.messages.push(
                    "WARNING: fix wall/gran hooke/history is LAMMPS 2025's linear_history_classic wall, whose tangential spring lets a sphere resting on a slope creep (as in LAMMPS); `wall/gran granular hooke Kn eta_n0 tangential linear_history Kt x_gt mu damping mass_velocity` holds it elastically"
                        .into(),
                );
            }
            classic_spec(&first.text, &c, limit_damping).map_err(|m| a.error_at(first, m, "not supported"))?
        }
        _ => return Err(a.unknown_keyword(first, &["granular", "hooke", "hooke/history", "hertz/history"])),
    };
    Ok(spec)
}

/// `temperature T` of a granular wall (a number or v_name): the wall's temperature for the heat
/// models, which need it (LAMMPS); without a heat model it is refused.
pub(super) fn parse_temperature(a: &mut Args, k: &Word, model: &GranModel, style: &str) -> DResult<FixValue> {
    if model.heat.is_none() {
        return Err(a.error_at(k, format!("fix {style} `temperature` needs a heat model (`heat radius|area ...` in the granular form)"), "no heat model"));
    }
    let w = a.word("wall temperature (a number or v_name)")?;
    FixValue::parse(w, "wall temperature", false)
}

/// A heat model on a wall needs the wall's temperature.
pub(super) fn check_heat(a: &Args, cmd: &Command, model: &GranModel, temperature: &Option<FixValue>, style: &str) -> DResult<()> {
    if model.heat.is_some() && temperature.is_none() {
        return Err(a.error_at(&cmd.name, format!("fix {style} with a heat model needs the wall temperature: add `temperature T`"), "no wall temperature"));
    }
    Ok(())
}

/// The wall temperature now (None without a heat model), and the atoms' fields checked.
pub(super) fn wall_temperature(temperature: &Option<FixValue>, state: &State, ctx: &mut FixCtx, me: &dyn Fix) -> Result<Option<f64>, RunError> {
    let Some(t) = temperature else { return Ok(None) };
    check_heat_fields(&state.atoms, &format!("fix {} {}", me.id(), me.style())).map_err(|e| RunError::new(state.step, e))?;
    ctx.value(state, me, t)
}

const BIG: f64 = 1.0e20;

enum Motion {
    None,
    Wiggle { axis: usize, amplitude: f64, omega: f64 },
    Shear { axis: usize, v: f64 },
}

pub struct FixWallGran {
    id: String,
    groupbit: u32,
    spec: GranSpec,
    model: GranModel,
    dim: usize,
    lo: f64,
    hi: f64,
    motion: Motion,
    /// Step at which the fix was defined (wiggle phase origin).
    time_origin: i64,
    /// Name of the per-atom history array in `Atoms::extra`.
    array: String,
    /// `temperature T` (heat models)
    temperature: Option<FixValue>,
    /// `contacts`: the per-atom contact array.
    contacts: Option<WallContacts>,
}

/// Columns of the `contacts` array: flag, force (3), contact point (3), radius.
const CONTACT_COLS: usize = 8;

/// The `contacts` per-atom array of fix wall/gran and wall/gran/region (LAMMPS' array_atom,
/// 8 columns): kept in the atoms' extra arrays so it follows the atoms; each force pass
/// clears every owned atom's row, then writes the row of each touching contact (an atom that
/// touches several walls of a region keeps the last one's, as in LAMMPS).
pub(super) struct WallContacts {
    array: String,
}

impl WallContacts {
    /// Registers the array of fix `id`.
    pub(super) fn new(state: &mut State, id: &str, style: &str) -> Self {
        let array = format!("{style}:{id}:contacts");
        state.atoms.extra_array(&array, CONTACT_COLS);
        WallContacts { array }
    }

    /// The array taken out of the atoms, every owned atom's row cleared; give it back with
    /// [`WallContacts::restore`].
    pub(super) fn take_cleared(&self, atoms: &mut crate::engine::atoms::Atoms) -> Vec<f64> {
        let k = atoms.extra_array(&self.array, CONTACT_COLS);
        let mut data = std::mem::take(&mut atoms.extra[k].data);
        data.fill(0.0);
        data
    }

    pub(super) fn restore(&self, atoms: &mut crate::engine::atoms::Atoms, data: Vec<f64>) {
        let k = atoms.extra_array(&self.array, CONTACT_COLS);
        atoms.extra[k].data = data;
    }

    /// One atom's row: touching, the wall's force `f` on it, the contact point `x - del`
    /// (`del` from the wall to the sphere's centre) and its radius.
    #[inline]
    pub(super) fn row(x: &[f64; 3], del: &[f64; 3], f: &[f64; 3], radius: f64) -> [f64; CONTACT_COLS] {
        [1.0, f[0], f[1], f[2], x[0] - del[0], x[1] - del[1], x[2] - del[2], radius]
    }

    /// Drops the array of a fix (None: the fix has none).
    pub(super) fn remove(c: Option<&Self>, state: &mut State) {
        if let Some(c) = c {
            state.atoms.remove_extra(&c.array);
        }
    }

    /// The owned atoms' rows, for dumps and compute reduce (`f_ID[1..8]`), of fix `me`
    /// (an error when it was defined without `contacts`).
    pub(super) fn peratom(c: Option<&Self>, state: &State, me: &dyn Fix) -> Result<crate::models::compute::PerAtom, String> {
        let c = c.ok_or_else(|| format!("fix {} ({}) has per-atom values only with the `contacts` keyword", me.id(), me.style()))?;
        let a = &state.atoms;
        let data = a.find_extra(&c.array).map(|k| a.extra[k].data[..a.nlocal * CONTACT_COLS].to_vec()).unwrap_or_else(|| vec![0.0; a.nlocal * CONTACT_COLS]);
        Ok(crate::models::compute::PerAtom { cols: CONTACT_COLS, data })
    }

    pub(super) fn cols(c: Option<&Self>) -> Option<usize> {
        c.map(|_| CONTACT_COLS)
    }
}

impl FixWallGran {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &mut State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, syntax());
        if !state.atoms.features.sphere {
            return Err(a.error_at(&cmd.name, "fix wall/gran requires atom attributes radius and omega (atom_style sphere)", "no sphere attributes"));
        }
        let spec = parse_model(&mut a, cmd, syntax(), state)?;
        if spec.normal.style.name == "mdr" {
            let w = args.iter().find(|w| w.text == "mdr").unwrap_or(&cmd.name);
            return Err(a.error_at(w, "fix wall/gran cannot use the mdr normal model: LAMMPS' mdr supports only region walls (MDR model currently only supports fix wall/gran/region, not fix wall/gran)", "use fix wall/gran/region"));
        }
        let model = GranModel::build(&spec, true);
        let w = a.word("wall style (xplane, yplane or zplane)")?;
        let dim = match w.text.as_str() {
            "xplane" => 0,
            "yplane" => 1,
            "zplane" => 2,
            "region" => return Err(a.error_at(w, "use fix wall/gran/region for region walls", "see fix wall/gran/region")),
            "zcylinder" => return Err(a.error_at(w, "fix wall/gran zcylinder is not supported (plane walls and fix wall/gran/region only)", "not supported")),
            _ => return Err(a.unknown_keyword(w, &["xplane", "yplane", "zplane"])),
        };
        let bound = |a: &mut Args, what: &str, null: f64| -> DResult<f64> {
            if a.peek().map(|w| w.text == "NULL").unwrap_or(false) {
                a.skip(1);
                Ok(null)
            } else {
                a.f64(what)
            }
        };
        let lo = bound(&mut a, "lo (or NULL)", -BIG)?;
        let hi = bound(&mut a, "hi (or NULL)", BIG)?;
        let axis_of = |a: &mut Args| -> DResult<usize> { a.choice("axis", &["x", "y", "z"]) };
        let mut motion = Motion::None;
        let mut temperature = None;
        let mut contacts = false;
        while let Some(k) = a.peek() {
            a.skip(1);
            match k.text.as_str() {
                "wiggle" => {
                    let axis = axis_of(&mut a)?;
                    let amplitude = a.f64("amplitude")?;
                    let period = a.positive_f64("period")?;
                    motion = Motion::Wiggle { axis, amplitude, omega: 2.0 * std::f64::consts::PI / period };
                }
                "shear" => {
                    let axis = axis_of(&mut a)?;
                    if axis == dim {
                        return Err(a.error_at(a.last().unwrap(), "invalid shear direction for fix wall/gran (along the wall normal)", "normal direction"));
                    }
                    motion = Motion::Shear { axis, v: a.f64("shear velocity")? };
                }
                "temperature" => temperature = Some(parse_temperature(&mut a, k, &model, "wall/gran")?),
                "contacts" => contacts = true,
                _ => return Err(a.unknown_keyword(k, &["wiggle", "shear", "temperature", "contacts"])),
            }
        }
        check_heat(&a, cmd, &model, &temperature, "wall/gran")?;
        let domain = state.domain.as_ref().ok_or_else(|| a.error_at(&cmd.name, "fix wall/gran needs a simulation box", "no box yet"))?;
        if domain.periodic(dim) {
            return Err(a.error_at(w, "cannot use a wall in a periodic dimension", "periodic dimension"));
        }
        let array = format!("wall/gran:{id}");
        state.atoms.extra_array(&array, width(&model));
        let contacts = contacts.then(|| WallContacts::new(state, &id, "wall/gran"));
        Ok(FixWallGran { id, groupbit, spec, model, dim, lo, hi, motion, time_origin: state.step, array, temperature, contacts })
    }

    /// The planes' positions and the wall velocity at the current step.
    fn wall_now(&self, state: &State) -> (f64, f64, [f64; 3]) {
        let (mut wlo, mut whi) = (self.lo, self.hi);
        let mut vwall = [0.0f64; 3];
        match self.motion {
            Motion::Wiggle { axis, amplitude, omega } => {
                let arg = omega * (state.step - self.time_origin) as f64 * state.dt;
                if axis == self.dim {
                    wlo = self.lo + amplitude - amplitude * arg.cos();
                    whi = self.hi + amplitude - amplitude * arg.cos();
                }
                vwall[axis] = amplitude * omega * arg.sin();
            }
            Motion::Shear { axis, v } => vwall[axis] = v,
            Motion::None => {}
        }
        (wlo, whi, vwall)
    }

    fn apply(&mut self, state: &mut State, ctx: &mut FixCtx, update: bool) -> Result<(), RunError> {
        let twall = wall_temperature(&self.temperature, state, ctx, self)?;
        match width(&self.model) {
            3 => self.apply_w::<3>(state, update, twall),
            MAX_HISTORY => self.apply_w::<MAX_HISTORY>(state, update, twall),
            _ => self.apply_w::<WIDEST>(state, update, twall),
        }
    }

    /// `W` history values per atom (the model's, padded with zeros); `twall`: the wall's
    /// temperature when the model conducts heat.
    fn apply_w<const W: usize>(&mut self, state: &mut State, update: bool, twall: Option<f64>) -> Result<(), RunError> {
        let dt = state.dt;
        let (wlo, whi, vwall) = self.wall_now(state);
        let w0 = [0.0f64; 3];
        let k = state.atoms.extra_array(&self.array, W);
        let a = &mut state.atoms;
        let n = a.nlocal;
        let mut hist = std::mem::take(&mut a.extra[k].data);
        // heat: the atoms' temperatures (read) and heat flows (added to), when conducting
        let heat = match (twall, a.field(TEMPERATURE), a.field(HEATFLOW)) {
            (Some(tw), Some(kt), Some(kq)) => Some((tw, kt, kq)),
            _ => None,
        };
        let mut flow = heat.map(|(_, _, kq)| std::mem::take(&mut a.extra[kq].data)).unwrap_or_default();
        // contacts: every owned atom's row is cleared, then the touching ones filled (LAMMPS)
        let mut cdata = self.contacts.as_ref().map(|c| c.take_cleared(a)).unwrap_or_default();
        let nc = if self.contacts.is_some() { n } else { 0 };
        let (c8, _) = cdata[..CONTACT_COLS * nc].as_chunks_mut::<CONTACT_COLS>();
        let temp: &[f64] = heat.map_or(&[], |(_, kt, _)| &a.extra[kt].data[..]);
        // with rigid bodies the body's mass (LAMMPS' mass_rigid)
        let rmass = if state.rigid_mass.is_empty() { &a.rmass[..n] } else { &state.rigid_mass[..n] };
        let (x, v, omega, radius, mask) = (&a.x[..n], &a.v[..n], &a.omega[..n], &a.radius[..n], &a.mask[..n]);
        let (h3, _) = hist[..W * n].as_chunks_mut::<W>();
        let nq = if heat.is_some() { n } else { 0 };
        let windows = (AtomsMut::new(&mut a.f[..n]), AtomsMut::new(&mut a.torque[..n]), AtomsMut::new(h3), AtomsMut::new(&mut flow[..nq]), AtomsMut::new(c8));
        let (dim, groupbit, model) = (self.dim, self.groupbit, &self.model);
        let beyond = model.beyond_contact;
        // atoms are independent: ranges of them may run in parallel (same bits)
        ranges(n, 1024, windows, |range, (mut f, mut torque, mut h3, mut flow, mut c8)| {
            for i in range {
                if mask[i] & groupbit == 0 {
                    continue;
                }
                let xi = x[i][dim];
                let del1 = xi - wlo;
                let del2 = whi - xi;
                // signed distance from the nearer plane; |dx|^2 is just its square (the other
                // components are zero)
                let dist = if del1 < del2 { del1 } else { -del2 };
                let rsq = dist * dist;
                let radi = radius[i];
                let h = &mut h3[i];
                let touching = if beyond { model.wall_touch(rsq, radi, 0.0, h[0] != 0.0) } else { rsq < radi * radi };
                if !touching {
                    // no contact: history zero (written only if it is not, so the many atoms
                    // away from the wall do not dirty their history's cache lines)
                    if h.iter().fold(0, |b, x| b | x.to_bits()) != 0 {
                        *h = [0.0; W];
                    }
                    continue;
                }
                let mut hv = *h;
                if beyond {
                    hv[0] = 1.0;
                }
                let mut dx = [0.0f64; 3];
                dx[dim] = dist;
                let rsq = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
                let c = Contact { del: dx, rsq, radi, radj: 0.0, vi: &v[i], vj: &vwall, omegai: &omega[i], omegaj: &w0, meff: rmass[i] };
                let r = granular_contact(model, &c, true, &mut hv[..model.history_size], update, dt);
                *h = hv;
                for d in 0..3 {
                    f[i][d] += r.f[d];
                    torque[i][d] += r.ti[d];
                }
                if let (Some((tw, _, _)), Some(hm)) = (heat, &model.heat) {
                    flow[i] += contact_heat(model, hm, rsq, radi, 0.0, true, temp[i], tw);
                }
                if nc > 0 {
                    c8[i] = WallContacts::row(&x[i], &dx, &r.f, radi);
                }
            }
        });
        a.extra[k].data = hist;
        if let Some(c) = &self.contacts {
            c.restore(a, cdata);
        }
        if let Some((_, _, kq)) = heat {
            a.extra[kq].data = flow;
        }
        Ok(())
    }
}

/// History values per atom: 3 (as before the models that keep more), the most a pair keeps,
/// or that and a beyond-contact model's touch flag.
fn width(model: &GranModel) -> usize {
    match model.history_size {
        0..=3 => 3,
        4..=MAX_HISTORY => MAX_HISTORY,
        _ => WIDEST,
    }
}

/// The most history values a wall keeps per atom.
const WIDEST: usize = MAX_HISTORY + 1;

impl Fix for FixWallGran {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "wall/gran"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    /// Forces of the current state; the spring is not advanced during setup.
    fn setup(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.apply(state, ctx, false)
    }
    fn post_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.apply(state, ctx, true)
    }
    fn cleanup(&mut self, state: &mut State) {
        state.atoms.remove_extra(&self.array);
        WallContacts::remove(self.contacts.as_ref(), state);
    }
    fn peratom(&self, state: &State) -> Result<crate::models::compute::PerAtom, String> {
        WallContacts::peratom(self.contacts.as_ref(), state, self)
    }
    fn peratom_cols(&self) -> Option<usize> {
        WallContacts::cols(self.contacts.as_ref())
    }
    fn image_planes(&self, state: &State, _equal: &mut dyn FnMut(&str) -> Result<f64, String>) -> Result<Vec<(usize, f64)>, String> {
        let (wlo, whi, _) = self.wall_now(state);
        Ok([wlo, whi].into_iter().filter(|x| x.abs() < 0.5 * BIG).map(|x| (self.dim, x)).collect())
    }
    fn describe(&self) -> String {
        format!("fix {} wall/gran granular {} {}plane {} {}", self.id, self.spec.describe(), ["x", "y", "z"][self.dim], self.lo, self.hi)
    }
}
