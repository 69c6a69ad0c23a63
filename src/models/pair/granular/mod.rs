//! `pair_style granular [cutoff]`: per-type-pair contact models composed of one sub-model per
//! kind, as LAMMPS 2025's GranularModel composes them:
//!
//! ```text
//! pair_coeff I J NORMAL coeffs... [damping NAME] [tangential NAME coeffs...]
//!            [rolling NAME coeffs...] [twisting NAME coeffs...] [heat NAME coeffs...]
//!            [limit_damping] [synchronized_verlet] [cutoff value]
//! ```
//!
//! Each kind has its file with a `STYLES` table ([`normal`], [`damping`], [`tangential`],
//! [`rolling`], [`twisting`], [`heat`]): name, coefficients, history values, flags and the
//! constructor of the enum the contact evaluates. The parser, its errors, the syntax line, the
//! history layout and mixing all read the tables. A tangential model is required; damping
//! defaults to viscoelastic (LAMMPS).
//!
//! [`granular_contact`] follows LAMMPS' order of operations: geometry, the contact radius
//! a = sqrt(delta R_eff) (only when a sub-model needs it), F_n from the normal model, the damping
//! prefactor eta_n and F_damp = -eta_n v_n, F_n,tot = F_n + F_damp (`limit_damping` clamps it at
//! 0), F_n,crit from the normal model, F_t from the tangential model, torques -(R - delta/2)
//! (n x F_t) on each sphere (a wall: -R (n x F_t)), then rolling and twisting torques.
//! `synchronized_verlet` (pairs only) takes n half a step back and turns the springs into the
//! full-step tangent plane after their update (LAMMPS 22 Jul 2025).
//!
//! Unset I,J pairs mix from I,I and J,J: the same sub-models, coefficients mixed by each
//! style's rule (geometric means unless the table says otherwise); a mixed pair is not
//! synchronized.
//! The same models serve `fix wall/gran ... granular` ([`GranSpec::parse`] with `wall`).

pub mod damping;
pub mod heat;
pub mod mdr;
pub mod mdr_state;
pub mod normal;
pub mod rolling;
pub mod tangential;
pub mod twisting;

use super::contact::{compute_contacts, Contact, ContactForce, ContactModel, MAX_HISTORY};
use super::gran_hooke_history::{check_setup, rebuild_history, GranTypes};
use super::{PairInput, PairModify, PairOutput, PairSetup, PairStyle, SharedTable, Tally};
use crate::engine::contact_history::ContactHistory;
use crate::engine::atoms::Atoms;
use crate::engine::fields;
use crate::engine::neighbor::{special_level, NEIGH_MASK};
use damping::Damping;
use dmhs_parser::suggest::did_you_mean_help;
use dmhs_parser::{Args, Command, DResult, Word};
use heat::Heat;
use normal::Normal;
use rolling::{Rolling, RollingIn};
use std::sync::OnceLock;
use tangential::{Tangential, TangentialIn};
use twisting::{Twisting, TwistingIn};

pub const SYNTAX: &str = "pair_style granular [cutoff]";

/// Most coefficients of a sub-model.
pub const MAX_COEFFS: usize = 6;
pub type Coeffs = [f64; MAX_COEFFS];

/// A coefficient of a sub-model, for the parser and its messages.
pub struct Coeff {
    pub name: &'static str,
    /// what it is, in error messages (may be empty)
    pub about: &'static str,
    pub range: Range,
}

/// The values a coefficient may take.
#[derive(Clone, Copy, PartialEq)]
pub enum Range {
    Any,
    /// >= 0 (LAMMPS' "Illegal ... model" checks)
    NonNegative,
    /// >= 0, or NULL (read as -1: the model derives it, as LAMMPS' mindlin Kt)
    NonNegativeOrNull,
    /// a Poisson's ratio, in (-1, 0.5]
    Poisson,
    /// > 0
    Positive,
    /// in [lo, hi]
    Closed(f64, f64),
    /// a whole number from lo to hi (LAMMPS truncates the value to an int first)
    Whole(i64, i64),
}

/// What NULL reads as (LAMMPS).
pub const NULL: f64 = -1.0;

impl Coeff {
    pub const fn any(name: &'static str, about: &'static str) -> Coeff {
        Coeff { name, about, range: Range::Any }
    }
    fn what(&self) -> String {
        if self.about.is_empty() { self.name.to_string() } else { format!("{} ({})", self.name, self.about) }
    }
    fn parse(&self, a: &mut Args) -> DResult<f64> {
        let what = self.what();
        match self.range {
            Range::Any => a.f64(&what),
            Range::NonNegative => a.non_negative_f64(&what),
            Range::NonNegativeOrNull => {
                if a.peek().is_some_and(|w| w.text == "NULL") {
                    a.skip(1);
                    return Ok(NULL);
                }
                a.f64_where(&what, ">= 0 or NULL", |x| x >= 0.0)
            }
            Range::Poisson => a.f64_where(&what, "in (-1, 0.5]", |x| x > -1.0 && x <= 0.5),
            Range::Positive => a.f64_where(&what, "> 0", |x| x > 0.0),
            Range::Closed(lo, hi) => a.f64_where(&what, &format!("in [{lo}, {hi}]"), |x| x >= lo && x <= hi),
            Range::Whole(lo, hi) => {
                let alts: Vec<String> = (lo..=hi).map(|k| k.to_string()).collect();
                a.f64_where(&what, &alts.join(" or "), |x| (x as i64) >= lo && (x as i64) <= hi)
            }
        }
    }
}

/// A coefficient that must be >= 0 (LAMMPS' "Illegal ... model" checks).
pub const fn nn(name: &'static str, about: &'static str) -> Coeff {
    Coeff { name, about, range: Range::NonNegative }
}

/// A Poisson's ratio.
pub const fn poisson() -> Coeff {
    Coeff { name: "nu", about: "Poisson's ratio", range: Range::Poisson }
}

/// What LAMMPS checks of a sub-model when it assembles a contact model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flags {
    /// needs the contact radius a = sqrt(delta R_eff) (LAMMPS contact_radius_flag)
    pub contact_radius: bool,
    /// a normal model whose force pulls (LAMMPS cohesive_flag): no limit_damping
    pub cohesive: bool,
    /// refuses a cohesive normal model (LAMMPS allow_cohesion = 0)
    pub no_cohesion: bool,
    /// interacts beyond touching (LAMMPS beyond_contact): a wall keeps the touch flag first
    pub beyond_contact: bool,
    /// a normal model with E and nu (LAMMPS material_properties): mindlin's Kt may be NULL
    pub material: bool,
    /// a tangential model that takes `synchronized_verlet` (LAMMPS allow_synchronization)
    pub synchronizable: bool,
    /// history values (bits, from the model's first) that keep their sign when the pair is
    /// seen from the other side (LAMMPS transfer_history_factor +1)
    pub keep: u64,
    /// kept values that LAMMPS 22 Jul 2025 nevertheless negates when its list moves the pair
    /// to the other atom (rolling and twisting springs: factor -1 there; later LAMMPS versions
    /// keep them)
    pub flip: u64,
}

impl Flags {
    pub const NONE: Flags = Flags { contact_radius: false, cohesive: false, no_cohesion: false, beyond_contact: false, material: false, synchronizable: false, keep: 0, flip: 0 };
}

/// What constructors see besides their coefficients.
pub struct Ctx {
    /// against fix wall/gran's wall (LAMMPS contact_type WALL)
    pub wall: bool,
    /// the coefficients were mixed from two types' (an unset I,J pair)
    pub mixed: bool,
    /// the normal model's name and eta_n0 (empty, 0 while the normal model itself is built)
    pub normal: &'static str,
    pub normal_damp: f64,
    /// the normal model's E and nu (LAMMPS get_emod, get_poiss), if it has them
    pub material: Option<(f64, f64)>,
    /// the tangential model's stiffness and friction coefficient (LAMMPS get_k, get_mu; zero
    /// while it is built)
    pub tangential_k_mu: (f64, f64),
}

/// One row of a kind's table: a sub-model style.
pub struct Style<M: 'static> {
    pub name: &'static str,
    pub coeffs: &'static [Coeff],
    /// history values per contact (LAMMPS size_history)
    pub history: usize,
    pub flags: Flags,
    /// coefficients -> the model the contact evaluates (LAMMPS coeffs_to_local and init)
    pub build: fn(&[f64], &Ctx) -> M,
    /// coefficients of an unset I,J pair from I,I and J,J (LAMMPS mix_coeffs)
    pub mix: fn(&[f64], &[f64]) -> Coeffs,
}

/// LAMMPS' default mixing: geometric means.
pub fn geometric(a: &[f64], b: &[f64]) -> Coeffs {
    std::array::from_fn(|k| (a[k] * b[k]).sqrt())
}

/// A sub-model as given: its table row and coefficients.
pub struct Given<M: 'static> {
    pub style: &'static Style<M>,
    pub coeffs: Coeffs,
}

// (derived Clone/Copy would require M: Copy)
impl<M> Clone for Given<M> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<M> Copy for Given<M> {}

impl<M> Given<M> {
    fn build(&self, ctx: &Ctx) -> M {
        (self.style.build)(&self.coeffs[..self.style.coeffs.len()], ctx)
    }
    /// Same style: mixed coefficients; else None.
    fn mix(&self, other: &Given<M>) -> Option<Given<M>> {
        std::ptr::eq(self.style, other.style).then(|| Given { style: self.style, coeffs: (self.style.mix)(&self.coeffs, &other.coeffs) })
    }
    fn describe(&self) -> String {
        let mut s = self.style.name.to_string();
        for c in &self.coeffs[..self.style.coeffs.len()] {
            s += &format!(" {c}");
        }
        s
    }
}

fn mix_opt<M>(a: &Option<Given<M>>, b: &Option<Given<M>>) -> Option<Option<Given<M>>> {
    match (a, b) {
        (None, None) => Some(None),
        (Some(a), Some(b)) => a.mix(b).map(Some),
        _ => None,
    }
}

/// The names of a table, for messages.
fn names<M>(table: &[Style<M>]) -> Vec<&'static str> {
    table.iter().map(|s| s.name).collect()
}

/// A sub-model as named in the command: the word, and what the checks of
/// [`GranSpec::parse`] need of its style.
#[derive(Clone, Copy)]
struct Named<'a> {
    word: &'a Word,
    name: &'static str,
    history: usize,
    flags: Flags,
}

/// `NAME coeffs...` of one kind, looked up in its table; `set` stores it.
fn parse_sub<'a, M>(a: &mut Args<'a>, table: &'static [Style<M>], kind: &str, set: impl FnOnce(Given<M>)) -> DResult<Named<'a>> {
    let w = a.word(&format!("{kind} model"))?;
    let Some(style) = table.iter().find(|s| s.name == w.text) else {
        let known = names(table);
        let label = if known.is_empty() { format!("dmhs has no {kind} models yet") } else { format!("supported: {}", known.join(", ")) };
        let mut d = a.error_at(w, format!("granular {kind} model `{}` is not supported by dmhs", w.text), label);
        if let Some(h) = did_you_mean_help(&w.text, known.iter().copied()) {
            d.help.insert(0, h);
        }
        return Err(d);
    };
    let mut coeffs = [0.0; MAX_COEFFS];
    for (k, c) in style.coeffs.iter().enumerate() {
        coeffs[k] = c.parse(a)?;
    }
    set(Given { style, coeffs });
    Ok(Named { word: w, name: style.name, history: style.history, flags: style.flags })
}

/// The kinds after the normal model, by keyword.
const KINDS: [&str; 5] = ["damping", "tangential", "rolling", "twisting", "heat"];

/// `NAME c1 c2 | NAME c1 ...` of a table, for syntax lines.
fn table_syntax<M>(table: &[Style<M>]) -> String {
    let alt: Vec<String> = table.iter().map(|s| std::iter::once(s.name).chain(s.coeffs.iter().map(|c| c.name)).collect::<Vec<_>>().join(" ")).collect();
    alt.join(" | ")
}

/// The model words of the syntax line, from the tables.
pub fn model_syntax() -> &'static str {
    static S: OnceLock<String> = OnceLock::new();
    S.get_or_init(|| {
        format!(
            "({}) [damping {}] tangential ({}) [rolling ({})] [twisting ({})] [heat ({})] [limit_damping]",
            table_syntax(normal::STYLES),
            names(damping::STYLES).join("|"),
            table_syntax(tangential::STYLES),
            table_syntax(rolling::STYLES),
            table_syntax(twisting::STYLES),
            table_syntax(heat::STYLES)
        )
    })
}

fn coeff_syntax() -> &'static str {
    static S: OnceLock<String> = OnceLock::new();
    S.get_or_init(|| format!("pair_coeff I J {} [cutoff value]", model_syntax()))
}

/// One type pair's (or a wall's) models as given.
#[derive(Clone, Copy)]
pub struct GranSpec {
    /// given by pair_coeff or a wall (false: mixed from two types, or unset)
    pub set: bool,
    pub normal: Given<Normal>,
    pub damping: Given<Damping>,
    pub tangential: Given<Tangential>,
    pub rolling: Option<Given<Rolling>>,
    pub twisting: Option<Given<Twisting>>,
    pub heat: Option<Given<Heat>>,
    pub limit_damping: bool,
    /// `synchronized_verlet`: the half-step contact normal (pairs only)
    pub synchronized: bool,
    /// `cutoff` keyword (negative: from the radii)
    pub cutoff: f64,
}

impl Default for GranSpec {
    fn default() -> Self {
        let zero = [0.0; MAX_COEFFS];
        GranSpec {
            set: false,
            normal: Given { style: &normal::STYLES[0], coeffs: zero },
            damping: Given { style: damping::default_style(), coeffs: zero },
            tangential: Given { style: &tangential::STYLES[0], coeffs: zero },
            rolling: None,
            twisting: None,
            heat: None,
            limit_damping: false,
            synchronized: false,
            cutoff: -1.0,
        }
    }
}

impl GranSpec {
    /// Parse `NORMAL coeffs [keywords]` (the words after the type ranges; for a wall, up to the
    /// wall style).
    pub fn parse(a: &mut Args, wall: bool) -> DResult<GranSpec> {
        let mut m = GranSpec { set: true, ..GranSpec::default() };
        // the sub-models as named, by kind (for the checks below); a kind given twice: the
        // last one counts (LAMMPS)
        let mut named: [Option<Named>; 6] = [None; 6];
        named[NORMAL] = Some(parse_sub(a, normal::STYLES, "normal", |g| m.normal = g)?);
        let mut limit_word = None;
        let mut sync_word = None;
        let stops: &[&str] = if wall { &["xplane", "yplane", "zplane", "zcylinder", "region"] } else { &[] };
        while let Some(w) = a.peek() {
            if stops.contains(&w.text.as_str()) {
                break;
            }
            a.skip(1);
            let kind = w.text.as_str();
            match kind {
                "damping" => named[DAMPING] = Some(parse_sub(a, damping::STYLES, kind, |g| m.damping = g)?),
                "tangential" => named[TANGENTIAL] = Some(parse_sub(a, tangential::STYLES, kind, |g| m.tangential = g)?),
                "rolling" => named[ROLLING] = Some(parse_sub(a, rolling::STYLES, kind, |g| m.rolling = Some(g))?),
                "twisting" => named[TWISTING] = Some(parse_sub(a, twisting::STYLES, kind, |g| m.twisting = Some(g))?),
                "heat" => named[HEAT] = Some(parse_sub(a, heat::STYLES, kind, |g| m.heat = Some(g))?),
                "limit_damping" => (m.limit_damping, limit_word) = (true, Some(w)),
                "cutoff" if !wall => m.cutoff = a.f64("cutoff")?,
                // LAMMPS' half-step contact normal (examples/granular/in.sync_verlet); walls
                // do not take it (LAMMPS: unknown fix wall/gran keyword)
                "synchronized_verlet" if !wall => (m.synchronized, sync_word) = (true, Some(w)),
                _ => {
                    let mut known = KINDS.to_vec();
                    known.push("limit_damping");
                    if !wall {
                        known.extend(["cutoff", "synchronized_verlet"]);
                    }
                    return Err(a.unknown_keyword(w, &known));
                }
            }
        }
        if named[TANGENTIAL].is_none() {
            return Err(a.missing(&format!("a tangential model (`tangential {}`): LAMMPS requires one", table_syntax(tangential::STYLES))));
        }
        // LAMMPS GranularModel::init's checks, located at the words that named the models
        if let Some(w) = sync_word {
            let name = m.tangential.style.name;
            if !m.tangential.style.flags.synchronizable {
                return Err(a.error_at(w, format!("cannot use synchronized verlet with a non-synchronized tangential model, {name}"), "a tangential model with history"));
            }
        }
        let normal = m.normal.style;
        if normal.flags.cohesive {
            if let Some(w) = limit_word {
                return Err(a.error_at(w, format!("cannot limit damping with a cohesive normal model, {}", normal.name), "cohesive normal model"));
            }
        }
        if m.tangential.style.coeffs.iter().zip(&m.tangential.coeffs).any(|(c, &v)| c.range == Range::NonNegativeOrNull && v == NULL) && !normal.flags.material {
            let w = named[TANGENTIAL].unwrap().word;
            return Err(a.error_at(
                w,
                format!("tangential {} with Kt NULL needs a normal model with material properties (hertz/material, dmt), not {}", w.text, normal.name),
                "Kt NULL without E and nu",
            ));
        }
        // LAMMPS GranSubModDamping*::init: the mdr models go only together
        let damping_is_mdr = m.damping.style.name == "mdr";
        if (normal.name == "mdr") != damping_is_mdr {
            let (w, msg) = match (named[DAMPING], damping_is_mdr) {
                (Some(d), false) => (d.word, "only damping mdr may be used with the mdr normal model".to_string()),
                (Some(d), true) => (d.word, format!("damping mdr can only be used with the mdr normal model, not {}", normal.name)),
                (None, _) => (named[NORMAL].unwrap().word, "the mdr normal model needs `damping mdr 1|2` (the default damping, viscoelastic, does not go with it)".to_string()),
            };
            return Err(a.error_at(w, msg, "mdr goes with mdr"));
        }
        let max_history = if normal.name == "mdr" { mdr::MAX_TOTAL_HISTORY } else { MAX_HISTORY };
        let mut total = 0;
        for n in named.iter().flatten() {
            if n.flags.no_cohesion && normal.flags.cohesive {
                return Err(a.error_at(n.word, format!("cannot use {} model with a cohesive normal model, {}", n.name, normal.name), "cohesive normal model"));
            }
            total += n.history;
            if total > max_history {
                return Err(a.error_at(n.word, format!("these granular models keep {total} history values per contact; dmhs keeps at most {max_history}"), "too much history"));
            }
        }
        Ok(m)
    }

    /// LAMMPS' default mixing: same sub-models, each mixing its coefficients.
    fn mix(a: &GranSpec, b: &GranSpec) -> Option<GranSpec> {
        Some(GranSpec {
            set: false,
            normal: a.normal.mix(&b.normal)?,
            damping: a.damping.mix(&b.damping)?,
            tangential: a.tangential.mix(&b.tangential)?,
            rolling: mix_opt(&a.rolling, &b.rolling)?,
            twisting: mix_opt(&a.twisting, &b.twisting)?,
            heat: mix_opt(&a.heat, &b.heat)?,
            limit_damping: a.limit_damping || b.limit_damping,
            // LAMMPS 22 Jul 2025's mix_coeffs does not carry it: a mixed pair is not synchronized
            synchronized: false,
            cutoff: if a.cutoff >= 0.0 || b.cutoff >= 0.0 { a.cutoff.max(b.cutoff) } else { -1.0 },
        })
    }

    pub fn describe(&self) -> String {
        let mut s = format!("{} damping {} tangential {}", self.normal.describe(), self.damping.describe(), self.tangential.describe());
        for (kind, g) in [("rolling", self.rolling.map(|g| g.describe())), ("twisting", self.twisting.map(|g| g.describe())), ("heat", self.heat.map(|g| g.describe()))] {
            if let Some(g) = g {
                s += &format!(" {kind} {g}");
            }
        }
        if self.limit_damping {
            s += " limit_damping";
        }
        if self.synchronized {
            s += " synchronized_verlet";
        }
        s
    }
}

/// Heat conduction needs per-atom temperatures and heat flows (LAMMPS' init_style checks).
pub fn check_heat_fields(atoms: &Atoms, who: &str) -> Result<(), String> {
    if atoms.field(fields::TEMPERATURE).is_none() || atoms.field(fields::HEATFLOW).is_none() {
        return Err(format!("{who}: a heat model needs per-atom temperature and heatflow: add `fix ID all property/atom temperature heatflow` before the run"));
    }
    Ok(())
}

/// The kinds, in LAMMPS' order (also the order of their values in the contact history).
const NORMAL: usize = 0;
const DAMPING: usize = 1;
const TANGENTIAL: usize = 2;
const ROLLING: usize = 3;
const TWISTING: usize = 4;
const HEAT: usize = 5;

/// One type pair's (or a wall's) contact model as the contact evaluates it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GranModel {
    pub normal: Normal,
    pub damping: Damping,
    pub tangential: Tangential,
    pub rolling: Option<Rolling>,
    pub twisting: Option<Twisting>,
    pub heat: Option<Heat>,
    pub limit_damping: bool,
    /// `synchronized_verlet`: forces along the half-step normal, springs turned to the
    /// full-step one after their update
    pub synchronized: bool,
    /// some sub-model needs the contact radius a
    pub contact_radius: bool,
    /// offsets of each kind's values in the history (normal, damping, tangential, rolling,
    /// twisting, heat: LAMMPS' order), and their total
    pub history_index: [usize; 6],
    pub history_size: usize,
    /// the history values that keep their sign from the other side (bits)
    pub history_keep: u64,
    /// the history values LAMMPS negates when its list moves the pair (bits)
    pub history_flip: u64,
    /// `cutoff` keyword (negative: from the radii)
    pub cutoff: f64,
    /// some sub-model interacts beyond touching (JKR): a contact holds while it was touching
    /// up to the pull-off distance; a wall keeps that flag as its history's first value
    pub beyond_contact: bool,
}

impl GranModel {
    /// Build the sub-models (LAMMPS coeffs_to_local, then init: damping reads the normal model).
    pub fn build(s: &GranSpec, wall: bool) -> GranModel {
        let mixed = !s.set;
        let material = s.normal.style.flags.material.then(|| (s.normal.coeffs[0], s.normal.coeffs[2]));
        let ctx = Ctx { wall, mixed, normal: "", normal_damp: 0.0, material, tangential_k_mu: (0.0, 0.0) };
        let normal = s.normal.build(&ctx);
        let mut ctx = Ctx { normal: s.normal.style.name, normal_damp: s.normal.coeffs[normal::damp_coeff(s.normal.style.name)], ..ctx };
        let tangential = s.tangential.build(&ctx);
        ctx.tangential_k_mu = tangential.k_mu();
        let sizes = [
            s.normal.style.history,
            s.damping.style.history,
            s.tangential.style.history,
            s.rolling.map_or(0, |g| g.style.history),
            s.twisting.map_or(0, |g| g.style.history),
            s.heat.map_or(0, |g| g.style.history),
        ];
        // a wall's beyond-contact touch flag comes first (LAMMPS fix wall/gran: next_index 1)
        let beyond_contact = s.normal.style.flags.beyond_contact;
        let mut history_index = [usize::from(wall && beyond_contact), 0, 0, 0, 0, 0];
        for k in 1..6 {
            history_index[k] = history_index[k - 1] + sizes[k - 1];
        }
        let flags = [Some(s.normal.style.flags), Some(s.damping.style.flags), Some(s.tangential.style.flags), s.rolling.map(|g| g.style.flags), s.twisting.map(|g| g.style.flags), s.heat.map(|g| g.style.flags)];
        let history_keep = flags.iter().zip(history_index).fold(0, |m, (f, at)| m | f.map_or(0, |f| f.keep << at));
        let history_flip = flags.iter().zip(history_index).fold(0, |m, (f, at)| m | f.map_or(0, |f| f.flip << at));
        GranModel {
            normal,
            damping: s.damping.build(&ctx),
            tangential,
            rolling: s.rolling.map(|g| g.build(&ctx)),
            twisting: s.twisting.map(|g| g.build(&ctx)),
            heat: s.heat.map(|g| g.build(&ctx)),
            limit_damping: s.limit_damping,
            synchronized: s.synchronized && !wall,
            contact_radius: flags.iter().flatten().any(|f| f.contact_radius),
            history_index,
            history_size: history_index[HEAT] + sizes[HEAT],
            history_keep,
            history_flip,
            cutoff: s.cutoff,
            beyond_contact,
        }
    }

    /// LAMMPS GranularModel::check_contact against a wall (R_i + 0 and R_eff = R_i for a plane,
    /// or with the wall's curvature radius `radj`): touching, or for JKR a contact that `was`
    /// touching up to the pull-off distance.
    #[inline(always)]
    pub fn wall_touch(&self, rsq: f64, radi: f64, radj: f64, was: bool) -> bool {
        let (radsum, reff) = radsum_reff(radi, radj, true);
        self.normal.touch_with(rsq, radsum, reff, was)
    }
}

/// R_i + R_j (a wall: R_i) and R_eff of a contact (a wall of radius `radj`, 0 for a plane).
#[inline(always)]
fn radsum_reff(radi: f64, radj: f64, wall: bool) -> (f64, f64) {
    if wall {
        (radi, if radj == 0.0 { radi } else { radi * radj / (radi + radj) })
    } else {
        let s = radi + radj;
        (s, radi * radj / s)
    }
}

/// The heat flow into sphere i of a touching contact (LAMMPS calculate_heat after
/// calculate_forces), with the contact radius [`granular_contact`] computes; `tj` is the
/// partner's (or the wall's) temperature.
#[inline]
pub fn contact_heat(m: &GranModel, heat: &Heat, rsq: f64, radi: f64, radj: f64, wall: bool, ti: f64, tj: f64) -> f64 {
    let (radsum, reff) = radsum_reff(radi, radj, wall);
    let delta = radsum - rsq.sqrt();
    heat.flow(m.normal.contact_radius(delta * reff, reff), ti, tj)
}

/// LAMMPS GranularModel::calculate_forces. Returns the force on i, and the torques on i and j.
/// Against a `wall` (fix wall/gran): `del` points from the wall to the sphere, `radj` is 0 for a
/// plane, m_eff is the sphere's mass and the torque lever is its full radius.
#[inline(always)]
pub fn granular_contact(m: &GranModel, g: &Contact, wall: bool, history: &mut [f64], update: bool, dt: f64) -> ContactForce {
    granular_contact_with(m, g, wall, history, update, dt, None)
}

/// [`granular_contact`] with the normal force `fnormal` given (the mdr model computes it from
/// per-atom state first); None: from the normal model.
#[inline(always)]
pub fn granular_contact_with(m: &GranModel, g: &Contact, wall: bool, history: &mut [f64], update: bool, dt: f64, fnormal: Option<f64>) -> ContactForce {
    granular_contact_parts(m, g, wall, history, update, dt, fnormal).0
}

/// The parts of a contact that LAMMPS' pair granular `single` reports besides its force.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ContactParts {
    /// The normal force: the normal model's, damping added, clamped at 0 with limit_damping.
    pub fntot: f64,
    pub rinv: f64,
    /// The tangential force (fs), the rolling "force" (fr) and the twisting torque's magnitude.
    pub fs: [f64; 3],
    pub fr: [f64; 3],
    pub magtortwist: f64,
}

/// [`granular_contact_with`] with the [`ContactParts`] of the same evaluation (inlined into
/// the force loops, which drop them).
#[inline(always)]
pub fn granular_contact_parts(m: &GranModel, g: &Contact, wall: bool, history: &mut [f64], update: bool, dt: f64, fnormal: Option<f64>) -> (ContactForce, ContactParts) {
    let (radi, radj) = (g.radi, g.radj);
    let meff = g.meff;
    let (radsum, reff) = radsum_reff(radi, radj, wall);
    let r = g.rsq.sqrt();
    let rinv = 1.0 / r;
    let delta = radsum - r;
    let nfull = [rinv * g.del[0], rinv * g.del[1], rinv * g.del[2]];
    let vr = [g.vi[0] - g.vj[0], g.vi[1] - g.vj[1], g.vi[2] - g.vj[2]];
    // synchronized_verlet: the normal of the separation half a step back (velocities are at
    // the half step), the full-step one kept for the springs' second turn
    let (nx, full) = if m.synchronized {
        let h = 0.5 * dt;
        let nh = [g.del[0] - h * vr[0], g.del[1] - h * vr[1], g.del[2] - h * vr[2]];
        let s = 1.0 / (nh[0] * nh[0] + nh[1] * nh[1] + nh[2] * nh[2]).sqrt();
        ([nh[0] * s, nh[1] * s, nh[2] * s], Some(&nfull))
    } else {
        (nfull, None)
    };

    // relative velocity: normal and tangential parts
    let vnnr = vr[0] * nx[0] + vr[1] * nx[1] + vr[2] * nx[2];
    let vn = [vnnr * nx[0], vnnr * nx[1], vnnr * nx[2]];
    let vt = [vr[0] - vn[0], vr[1] - vn[1], vr[2] - vn[2]];
    // relative rotational velocity (full radii) and the tangential velocity at the contact
    let wr = [
        radi * g.omegai[0] + radj * g.omegaj[0],
        radi * g.omegai[1] + radj * g.omegaj[1],
        radi * g.omegai[2] + radj * g.omegaj[2],
    ];
    let cr = [wr[1] * nx[2] - wr[2] * nx[1], wr[2] * nx[0] - wr[0] * nx[2], wr[0] * nx[1] - wr[1] * nx[0]];
    let vtr = [vt[0] - cr[0], vt[1] - cr[1], vt[2] - cr[2]];

    // normal force, damping, F_n,crit
    let a = if m.contact_radius { m.normal.contact_radius(delta * reff, reff) } else { 0.0 };
    let fnormal = fnormal.unwrap_or_else(|| m.normal.force(delta, reff, a));
    // damping mdr reads the scale the mdr normal model just stored
    let damp_scale = if matches!(m.damping, Damping::Mdr { .. }) { history[m.history_index[NORMAL] + mdr::DAMP_SCALE] } else { 0.0 };
    let damp_prefactor = m.damping.prefactor(meff, a, fnormal, delta, damp_scale);
    let fdamp = -damp_prefactor * vnnr;
    let mut fntot = fnormal + fdamp;
    if m.limit_damping && fntot < 0.0 {
        fntot = 0.0;
    }
    let fncrit = m.normal.fncrit(fntot, fnormal, reff);

    // tangential force
    let ht = &mut history[m.history_index[TANGENTIAL]..m.history_index[ROLLING]];
    let fs = m.tangential.force(&TangentialIn { nx: &nx, full, vtr: &vtr, fncrit, damp_prefactor, a, update, dt }, ht);
    let mut parts = ContactParts { fntot, rinv, fs, ..ContactParts::default() };

    let f = [fntot * nx[0] + fs[0], fntot * nx[1] + fs[1], fntot * nx[2] + fs[2]];
    // torque direction -(n x F_t), scaled by the lever
    let t = [
        -(nx[1] * fs[2] - nx[2] * fs[1]),
        -(nx[2] * fs[0] - nx[0] * fs[2]),
        -(nx[0] * fs[1] - nx[1] * fs[0]),
    ];
    let mut out = if wall {
        ContactForce { f, ti: [radi * t[0], radi * t[1], radi * t[2]], tj: [0.0; 3] }
    } else {
        let li = radi - 0.5 * delta;
        let lj = radj - 0.5 * delta;
        ContactForce { f, ti: [li * t[0], li * t[1], li * t[2]], tj: [lj * t[0], lj * t[1], lj * t[2]] }
    };

    // rolling and twisting torques (on i; the opposite on j)
    if m.rolling.is_some() || m.twisting.is_some() {
        let relrot = [g.omegai[0] - g.omegaj[0], g.omegai[1] - g.omegaj[1], g.omegai[2] - g.omegaj[2]];
        if let Some(rolling) = &m.rolling {
            let vrl = [
                reff * (relrot[1] * nx[2] - relrot[2] * nx[1]),
                reff * (relrot[2] * nx[0] - relrot[0] * nx[2]),
                reff * (relrot[0] * nx[1] - relrot[1] * nx[0]),
            ];
            let h = &mut history[m.history_index[ROLLING]..m.history_index[TWISTING]];
            let fr = rolling.force(&RollingIn { vrl: &vrl, nx: &nx, full, fncrit, update, dt }, h);
            parts.fr = fr;
            let tr = [reff * (nx[1] * fr[2] - nx[2] * fr[1]), reff * (nx[2] * fr[0] - nx[0] * fr[2]), reff * (nx[0] * fr[1] - nx[1] * fr[0])];
            add_opposite(&mut out, tr, wall);
        }
        if let Some(twisting) = &m.twisting {
            let magtwist = relrot[0] * nx[0] + relrot[1] * nx[1] + relrot[2] * nx[2];
            let h = &mut history[m.history_index[TWISTING]..m.history_index[HEAT]];
            let tangential_damp = m.tangential.xt() * damp_prefactor;
            let mt = twisting.torque(&TwistingIn { magtwist, fncrit, a, tangential_damp, update, dt }, h);
            parts.magtortwist = mt;
            add_opposite(&mut out, [mt * nx[0], mt * nx[1], mt * nx[2]], wall);
        }
    }
    (out, parts)
}

/// LAMMPS FixGranularMDR::setup_pre_force's checks: the mdr model is one model for every
/// type pair (one pair_coeff; a mixed pair would be a second model). Returns its psi_b.
fn mdr_check(models: &SharedTable<GranModel>, ntypes: usize, active: Option<&[bool]>, coeff_calls: usize) -> Result<Option<f64>, String> {
    let mut mdr = None;
    let mut other = false;
    for i in 1..=ntypes {
        for j in i..=ntypes {
            if active.is_some_and(|a| !a[i * (ntypes + 1) + j]) {
                continue;
            }
            match models.get(i, j).normal {
                Normal::Mdr(m) => mdr = Some(m.psi_b),
                _ => other = true,
            }
        }
    }
    if mdr.is_none() {
        return Ok(None);
    }
    if other {
        return Err("pair granular: cannot combine the mdr normal model with a different normal model (LAMMPS)".into());
    }
    if coeff_calls > 1 {
        return Err(format!("pair granular: the mdr model takes one pair_coeff for all type pairs (LAMMPS: cannot currently define multiple MDR normal models in the pairstyle); found {coeff_calls}"));
    }
    Ok(mdr)
}

/// The first `n` bits of `m`, one flag per history value.
fn bits(m: u64, n: usize) -> Vec<bool> {
    (0..n).map(|d| m >> d & 1 != 0).collect()
}

/// A torque added to i and subtracted from j (a wall has no j).
#[inline(always)]
fn add_opposite(out: &mut ContactForce, t: [f64; 3], wall: bool) {
    for (d, td) in t.iter().enumerate() {
        out.ti[d] += td;
        if !wall {
            out.tj[d] -= td;
        }
    }
}

/// The per-type-pair models as a [`ContactModel`], the history values per contact (the most
/// any pair's models keep: LAMMPS' size_history), and whether some pair interacts beyond
/// touching (JKR).
pub struct GranularModels(pub SharedTable<GranModel>, pub usize, pub bool);

impl ContactModel for GranularModels {
    type Params = GranModel;
    const HISTORY: usize = MAX_HISTORY;
    fn history_size(&self) -> usize {
        self.1
    }
    fn beyond_contact(&self) -> bool {
        self.2
    }
    #[inline(always)]
    fn touch(m: &GranModel, rsq: f64, radi: f64, radj: f64, was: bool) -> bool {
        m.normal.touch(rsq, radi, radj, was)
    }
    #[inline(always)]
    fn params(&self, ti: usize, tj: usize) -> &GranModel {
        self.0.get(ti, tj)
    }
    #[inline(always)]
    fn contact(m: &GranModel, c: &Contact, hist: &mut [f64], update: bool, dt: f64) -> ContactForce {
        granular_contact(m, c, false, hist, update, dt)
    }
}

pub struct Granular {
    cut_global: f64,
    coeff: SharedTable<GranSpec>,
    models: GranularModels,
    types: GranTypes,
    history: ContactHistory,
    /// some type pair conducts heat (a `heat` model)
    heat: bool,
    /// pair_coeff commands given (each is one LAMMPS model; mdr allows one)
    coeff_calls: usize,
    /// psi_b of the mdr model, when the pairs use it
    mdr: Option<f64>,
}

impl Granular {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<Granular> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let cut_global = if a.is_empty() { -1.0 } else { a.f64("cutoff")? };
        a.finish()?;
        Ok(Granular {
            cut_global,
            coeff: SharedTable::empty(GranSpec::default()),
            models: GranularModels(SharedTable::empty(GranModel::default()), 0, false),
            types: GranTypes::default(),
            history: ContactHistory::new(0),
            heat: false,
            coeff_calls: 0,
            mdr: None,
        })
    }

    /// Some pair_coeff names the mdr normal model.
    fn uses_mdr(&self) -> bool {
        self.coeff.values().any(|s| s.set && s.normal.style.name == "mdr")
    }

    /// Heat conduction of every contact (LAMMPS' calculate_heat after calculate_forces): Q into
    /// i and -Q into j (owned j only: a pair with a ghost is listed from both sides), in list
    /// order on one thread. A contact is what the force loop counted as one: overlapping (or
    /// flagged touching by a beyond-contact model), of this style's types, not excluded.
    fn heat_pass(&self, input: &PairInput, out: &mut PairOutput) {
        let a = input.atoms;
        let (Some(temp), Some(flow)) = (a.field_values(fields::TEMPERATURE), out.fields.iter_mut().find(|(f, _)| *f == fields::HEATFLOW).map(|(_, v)| v)) else {
            return;
        };
        let (x, radius, typ, nlocal) = (&a.x, &a.radius, &a.typ, a.nlocal);
        let stride = input.ntypes + 1;
        let beyond = self.models.2;
        for (c, chunk) in input.list.chunks.iter().enumerate() {
            for i in chunk.start..chunk.end {
                let k0 = chunk.first_entry(i);
                for (k, &jraw) in chunk.neighbors(i).iter().enumerate() {
                    let j = (jraw & NEIGH_MASK) as usize;
                    let m = self.models.params(typ[i], typ[j]);
                    let Some(heat) = &m.heat else { continue };
                    let del = [x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]];
                    let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
                    let (radi, radj) = (radius[i], radius[j]);
                    let radsum = radi + radj;
                    let touching = if beyond { self.history.chunks[c].touch[k0 + k] != 0 } else { rsq < radsum * radsum };
                    if !touching || input.type_filter.is_some_and(|f| !f[typ[i] * stride + typ[j]]) || input.special_lj[special_level(jraw)] == 0.0 {
                        continue;
                    }
                    let q = contact_heat(m, heat, rsq, radi, radj, false, temp[i], temp[j]);
                    flow[i] += q;
                    if j < nlocal {
                        flow[j] -= q;
                    }
                }
            }
        }
    }
}

impl PairStyle for Granular {
    fn style(&self) -> &str {
        "granular"
    }
    fn contact_stiffness(&self) -> Option<f64> {
        self.coeff.values().filter_map(|s| GranModel::build(s, false).normal.linear_stiffness()).reduce(f64::max)
    }
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = coeff_syntax();
        let m = GranSpec::parse(args, false)?;
        args.finish()?;
        self.coeff_calls += 1;
        self.coeff.grow(ihi.max(jhi)).map_err(|e| args.error_command(e, "too many atom types for this pair style"))?;
        let k = self.coeff.push(m);
        for i in ilo..=ihi {
            for j in jlo.max(i)..=jhi {
                self.coeff.set(i, j, k);
            }
        }
        self.types.set_range(ilo, ihi, jlo, jhi);
        // lay the history store out now (init does it again with the mixed pairs, which use the
        // same sub-models): read_restart checks a file's contacts against it before any run
        let (mut size, mut keep, mut flip) = (0, 0, 0);
        for s in self.coeff.values().filter(|s| s.set) {
            let g = GranModel::build(s, false);
            (size, keep, flip) = (size.max(g.history_size), keep | g.history_keep, flip | g.history_flip);
        }
        self.history.set_flips(bits(flip, size));
        if let Err(e) = self.history.set_layout(bits(keep, size)) {
            return Err(match args.last() {
                Some(w) => args.error_at(w, e, "history size"),
                None => args.missing(&e),
            });
        }
        Ok(())
    }
    fn init_sim(&mut self, setup: &PairSetup) -> Result<(), String> {
        check_setup(setup, self.style())?;
        if self.uses_mdr() && setup.newton_pair {
            return Err("pair granular: the mdr contact model requires `newton off` (LAMMPS: MDR contact model requires Newton off)".into());
        }
        if self.coeff.values().any(|s| s.set && s.heat.is_some()) {
            check_heat_fields(setup.atoms, "pair granular")?;
        }
        self.types.init_radii(setup);
        Ok(())
    }
    fn init(&mut self, ntypes: usize, _modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        self.coeff.grow(ntypes)?;
        self.types.check(ntypes, active, "granular")?;
        let mut models = SharedTable::new(ntypes, GranModel::default())?;
        // one model per distinct spec given, or per distinct pair of specs mixed
        let mut built: std::collections::HashMap<(bool, u32, u32), u32> = std::collections::HashMap::new();
        let (mut size, mut keep, mut flip, mut beyond) = (0, 0u64, 0u64, false);
        self.heat = false;
        for i in 1..=ntypes {
            for j in i..=ntypes {
                if let Some(a) = active {
                    if !a[i * (ntypes + 1) + j] {
                        continue;
                    }
                }
                let c = self.coeff.get(i, j);
                let key = if c.set { (true, self.coeff.index_of(i, j), 0) } else { (false, self.coeff.index_of(i, i), self.coeff.index_of(j, j)) };
                let k = match built.get(&key) {
                    Some(&k) => k,
                    None => {
                        let s = if c.set {
                            *c
                        } else {
                            GranSpec::mix(self.coeff.get(i, i), self.coeff.get(j, j))
                                .ok_or_else(|| format!("pair granular: types {i} and {j} use different models, so the {i} {j} pair cannot be mixed: set it with pair_coeff"))?
                        };
                        let m = GranModel::build(&s, false);
                        (size, keep, flip) = (size.max(m.history_size), keep | m.history_keep, flip | m.history_flip);
                        beyond |= s.normal.style.flags.beyond_contact;
                        self.heat |= m.heat.is_some();
                        let k = models.push(m);
                        built.insert(key, k);
                        k
                    }
                };
                models.set(i, j, k);
            }
        }
        self.mdr = mdr_check(&models, ntypes, active, self.coeff_calls)?;
        self.models = GranularModels(models, size, beyond);
        self.history.set_flips(bits(flip, size));
        self.history.set_layout(bits(keep, size))
    }
    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        let m = self.models.0.get(it, jt);
        if m.cutoff >= 0.0 {
            m.cutoff
        } else if self.cut_global >= 0.0 {
            self.cut_global
        } else {
            // a cohesive contact holds up to the pull-off distance (LAMMPS init_one)
            let r = |t: usize| self.types.maxrad.get(t).copied().unwrap_or(0.0);
            self.types.cutoff(it, jt) + m.normal.pulloff_distance(r(it), r(jt))
        }
    }
    fn size_list(&self) -> bool {
        true
    }
    fn tallies_in_loop(&self) -> bool {
        true
    }
    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally {
        let t = if self.mdr.is_some() { mdr::compute_contacts(&self.models, &mut self.history, input, out).0 } else { compute_contacts(&self.models, input, out, Some(&mut self.history)) };
        if self.heat {
            self.heat_pass(input, out);
        }
        t
    }
    fn rebuilt(&mut self, input: &PairInput, _order: &[usize]) {
        if self.mdr.is_some() {
            // every contact touching at the last evaluation carries on (LAMMPS' fix
            // neigh/history): the radii grow before the next one looks again
            return self.history.rebuilt(input.atoms, input.list, input.sides, |_, _| true);
        }
        if !self.models.2 {
            return rebuild_history(&mut self.history, input);
        }
        // a contact kept over the rebuild was touching: JKR's test with its pull-off distance
        let a = input.atoms;
        let (x, radius, typ, models) = (&a.x, &a.radius, &a.typ, &self.models);
        self.history.rebuilt(a, input.list, input.sides, |i, j| {
            let del = [x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]];
            let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
            models.params(typ[i], typ[j]).normal.touch(rsq, radius[i], radius[j], true)
        });
    }
    fn histories(&mut self) -> Vec<&mut ContactHistory> {
        vec![&mut self.history]
    }
    /// fs (3), |fs|, fr (3), |fr|, the twisting torque, x_i - x_j (3): LAMMPS' svector.
    fn single_extra(&self) -> Option<usize> {
        Some(12)
    }
    /// LAMMPS' PairGranular::single: the contact with its stored history, not advanced (a copy:
    /// LAMMPS 22 Jul 2025 writes a sliding twisting spring back, dmhs leaves the history as the
    /// force loop left it); fpair is the normal force (damping included) over r.
    fn single(&self, input: &PairInput, i: usize, j: usize, rsq: f64, _factor_coul: f64, factor_lj: f64) -> Result<super::Single, String> {
        let mut out = super::Single::default();
        if factor_lj == 0.0 {
            return Ok(out);
        }
        if self.mdr.is_some() {
            return Err("compute pair/local with pair granular's mdr model is not supported (its normal force needs the per-atom state of the step)".into());
        }
        let a = input.atoms;
        let m = self.models.params(a.typ[i], a.typ[j]);
        let hsize = self.models.history_size();
        let mut hist = [0.0; MAX_HISTORY];
        let mut was = false;
        if let Some((touch, values)) = self.history.entry(i, j) {
            was = touch;
            hist[..hsize].copy_from_slice(&values[..hsize]);
        }
        if !m.normal.touch(rsq, a.radius[i], a.radius[j], was) {
            return Ok(out);
        }
        let g = super::contact::contact_of(input, i, j, rsq);
        let (_, p) = granular_contact_parts(m, &g, false, &mut hist[..hsize], false, input.dt, None);
        out.fpair = p.fntot * p.rinv;
        let len = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        out.extra[..12].copy_from_slice(&[p.fs[0], p.fs[1], p.fs[2], len(p.fs), p.fr[0], p.fr[1], p.fr[2], len(p.fr), p.magtortwist, g.del[0], g.del[1], g.del[2]]);
        Ok(out)
    }
    fn atom_fields(&self) -> &'static [crate::engine::fields::Field] {
        if self.uses_mdr() { &crate::engine::fields::MDR_FIELDS } else { &[] }
    }
    fn pre_force(&mut self, state: &mut crate::engine::state::State, setup: bool) -> Result<(), String> {
        match self.mdr {
            Some(psi_b) => mdr_state::pre_force(state, &mut self.history, psi_b, setup),
            None => Ok(()),
        }
    }
    fn ranks_refusal(&self) -> Option<String> {
        self.uses_mdr().then(|| "pair granular with the mdr model".to_string())
    }
    fn mdr_model(&self) -> Option<mdr::Mdr> {
        self.mdr?;
        self.models.0.values().find_map(|m| match m.normal {
            Normal::Mdr(m) => Some(m),
            _ => None,
        })
    }
    fn describe(&self) -> String {
        let mut s = String::from("granular");
        if self.cut_global >= 0.0 {
            s += &format!(" {}", self.cut_global);
        }
        s += &super::pair_lines(self.coeff.n, |i, j| self.coeff.get(i, j).set, |i, j| self.coeff.get(i, j).describe());
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::bonded::test_util::words;
    use dmhs_parser::Span;

    fn parse(line: &str, wall: bool) -> DResult<GranSpec> {
        let w = words(line);
        let mut a = Args::from_words(&w, Span::new(Default::default(), 0, line.len()), "");
        let s = GranSpec::parse(&mut a, wall)?;
        a.finish()?;
        Ok(s)
    }

    fn err(line: &str) -> String {
        match parse(line, false) {
            Ok(_) => panic!("`{line}` was accepted"),
            Err(d) => format!("{} [{}] {}", d.message, d.labels[0].message, d.help.join(" ")),
        }
    }

    #[test]
    fn models_are_read_from_the_tables() {
        let s = parse("hertz/material 1e6 0.5 0.3 damping coeff_restitution tangential linear_history_classic 1000 0.5 0.2 limit_damping cutoff 1.5", false).unwrap();
        assert_eq!(s.describe(), "hertz/material 1000000 0.5 0.3 damping coeff_restitution tangential linear_history_classic 1000 0.5 0.2 limit_damping");
        assert_eq!(s.cutoff, 1.5);
        let m = GranModel::build(&s, false);
        assert!(m.contact_radius && m.limit_damping);
        assert_eq!(m.history_index, [0, 0, 0, 3, 3, 3]);
        // E_eff of two equal spheres is E/(2 (1-nu^2)); against a wall E/(2 (1-nu^2)) as well
        let k = 4.0 / 3.0 * 1e6 / (2.0 * (1.0 - 0.09));
        let (Normal::Hertz { k: kp }, Normal::Hertz { k: kw }) = (m.normal, GranModel::build(&s, true).normal) else { panic!() };
        assert!((kp - k).abs() < 1e-9 * k && (kw - k).abs() < 1e-9 * k);
        // the default damping is viscoelastic; linear_nohistory keeps no history
        let m = GranModel::build(&parse("hooke 10 1 tangential linear_nohistory 0.5 0.1", false).unwrap(), false);
        assert_eq!(m.damping, Damping::Viscoelastic { damp: 1.0 });
        assert_eq!(m.history_index, [0; 6]);
    }

    #[test]
    fn errors_name_what_the_tables_support() {
        // synchronized_verlet: a pair keyword for models with a tangential history (LAMMPS' checks)
        let s = parse("hooke 1e4 0.5 tangential linear_history 8235 0 0.5 damping coeff_restitution synchronized_verlet", false).unwrap();
        assert!(s.synchronized && GranModel::build(&s, false).synchronized && s.describe().ends_with(" synchronized_verlet"));
        let e = err("hooke 1e4 0.5 tangential linear_nohistory 0 0.5 synchronized_verlet");
        assert!(e.contains("cannot use synchronized verlet with a non-synchronized tangential model, linear_nohistory"), "{e}");
        let Err(d) = parse("hooke 1e4 0.5 tangential linear_history 8235 0 0.5 synchronized_verlet", true) else { panic!("a wall took synchronized_verlet") };
        assert!(d.message.contains("unknown keyword `synchronized_verlet`"), "{}", d.message);
        // a mixed pair is not synchronized (LAMMPS 22 Jul 2025's mix_coeffs does not carry it)
        assert!(!GranSpec::mix(&s, &s).unwrap().synchronized);
        let e = err("mdrr 1 2 3 4 5 6 tangential linear_history 1 1 1");
        assert!(e.contains("normal model `mdrr` is not supported") && e.contains("supported: hooke, hertz, hertz/material, dmt, jkr, mdr") && e.contains("did you mean `mdr`"), "{e}");
        // mdr goes with damping mdr only, and 27 history values are allowed with it
        let e = err("mdr 5e6 0.4 1e5 0 0.5 0.2 damping tsuji tangential linear_history 1 1 1");
        assert!(e.contains("only damping mdr may be used with the mdr normal model"), "{e}");
        let m = GranModel::build(&parse("mdr 5e6 0.4 1e5 0 0.5 0.2 damping mdr 2 tangential mindlin_rescale 1 1 1 rolling sds 1 1 1", false).unwrap(), false);
        assert_eq!((m.history_size, m.history_index[TANGENTIAL]), (27 + 4 + 3, 27));
        assert_eq!(m.damping, Damping::Mdr { damp: 0.2, scaled: false });
        // JKR: cohesive; on a wall its touch flag comes first in the history (LAMMPS' layout)
        let e = err("jkr 1e6 0.5 0.3 1 damping coeff_restitution tangential linear_history 1 1 1");
        assert!(e.contains("cannot use coeff_restitution model with a cohesive normal model, jkr"), "{e}");
        let w = words("jkr 1e6 0.5 0.3 1 tangential linear_history 1 1 1 zplane 0 NULL");
        let mut a = Args::from_words(&w, Span::new(Default::default(), 0, 1), "");
        let spec = GranSpec::parse(&mut a, true).unwrap();
        let (wall, pair) = (GranModel::build(&spec, true), GranModel::build(&spec, false));
        assert_eq!((wall.history_size, wall.history_index[TANGENTIAL]), (4, 1));
        assert_eq!((pair.history_size, pair.history_index[TANGENTIAL]), (3, 0));
        let e = err("hooke 1 1 damping tsuij tangential linear_history 1 1 1");
        assert!(e.contains("`tsuij`") && e.contains("coeff_restitution") && e.contains("did you mean `tsuji`"), "{e}");
        let e = err("hooke 1 1 tangential linear_history 1 1 1 rolling sdss 1 1 1");
        assert!(e.contains("rolling model `sdss` is not supported") && e.contains("supported: sds"), "{e}");
        let e = err("hooke 1 1 tangential linear_history 1 1 1 heat areas 1");
        assert!(e.contains("heat model `areas` is not supported") && e.contains("supported: radius, area") && e.contains("did you mean `area`"), "{e}");
        let e = err("hooke 1 1 tangential linear_history 1 1 1 heat radius -1");
        assert!(e.contains("k (conductivity) must be >= 0"), "{e}");
        let e = err("hooke 1 1 tangential linear_history 1 1 1 heat area");
        assert!(e.contains("h (heat transfer coefficient)"), "{e}");
        let m = GranModel::build(&parse("hooke 1 1 tangential linear_history 1 1 1 heat area 2.5", false).unwrap(), false);
        assert!(m.contact_radius && m.heat == Some(heat::Heat::Area { h: 2.5 }));
        // ranges: Poisson's ratio in (-1, 0.5]; Kt NULL only from material properties
        let e = err("hertz/material 1e6 0.5 0.6 tangential linear_history 1 1 1");
        assert!(e.contains("nu (Poisson's ratio) must be in (-1, 0.5], found 0.6"), "{e}");
        let e = err("hertz/material -1e6 0.5 0.3 tangential linear_history 1 1 1");
        assert!(e.contains("E (Young's modulus) must be >= 0"), "{e}");
        let e = err("hertz 1e6 0.5 tangential mindlin NULL 1 1");
        assert!(e.contains("mindlin with Kt NULL needs a normal model with material properties"), "{e}");
        let e = err("hertz 1e6 0.5 tangential mindlin_rescale -2 1 1");
        assert!(e.contains("Kt (NULL: from E and nu) must be >= 0 or NULL"), "{e}");
        let e = err("hertz 1e6 0.5 tangential mindlin 1 1 1 rolling sds 1 1 -1");
        assert!(e.contains("mu_roll (rolling friction coefficient) must be >= 0"), "{e}");
        let e = err("hertz/material 1e6 0.5 tangential linear_history 1 1 1");
        assert!(e.contains("nu (Poisson's ratio)"), "{e}");
        let e = err("hooke 1 -1 tangential linear_history 1 1 1");
        assert!(e.contains("eta_n0 (normal damping) must be >= 0"), "{e}");
        let e = err("hooke 1 1 damping velocity");
        assert!(e.contains("missing a tangential model") && e.contains("linear_history_classic Kt x_gt mu"), "{e}");
        let e = err("hooke 1 1 tangential linear_history 1 1 1 wiggle");
        assert!(e.contains("unknown keyword `wiggle`") && e.contains("cutoff"), "{e}");
        // LAMMPS' checks of cohesive normal models
        let e = err("dmt 1e6 0.5 0.3 1 tangential linear_history 1 1 1 limit_damping");
        assert!(e.contains("cannot limit damping with a cohesive normal model, dmt"), "{e}");
        let e = err("dmt 1e6 0.5 0.3 1 damping tsuji tangential linear_history 1 1 1");
        assert!(e.contains("cannot use tsuji model with a cohesive normal model, dmt"), "{e}");
        // the last damping given counts
        assert!(parse("dmt 1e6 0.5 0.3 1 damping tsuji damping velocity tangential linear_history 1 1 1", false).is_ok());
        // a wall stops at its wall style and has no cutoff
        let w = words("hooke 1 1 tangential linear_history 1 1 1 zplane 0 NULL");
        let mut a = Args::from_words(&w, Span::new(Default::default(), 0, 1), "");
        GranSpec::parse(&mut a, true).unwrap();
        assert_eq!(a.peek().unwrap().text, "zplane");
    }

    #[test]
    fn history_grows_with_the_models() {
        // LAMMPS' order: tangential, rolling, twisting; rescale's 4th value, rolling and
        // twisting keep their sign from the other side
        let s = parse("hertz/material 1e6 0.5 0.3 tangential mindlin_rescale NULL 0.5 0.2 rolling sds 1 2 3 twisting marshall", false).unwrap();
        let m = GranModel::build(&s, false);
        assert_eq!(m.history_index, [0, 0, 0, 4, 7, 10]);
        assert_eq!(m.history_size, 10);
        assert_eq!(m.history_keep, 0b11_1111_1000);
        // Kt NULL: 8 G_eff (pair), 8 G_wall (wall)
        let g = tangential::mix_stiffness_g(1e6, 1e6, 0.3, 0.3);
        assert_eq!(m.tangential.k_mu(), (8.0 * g, 0.2));
        let w = GranModel::build(&s, true);
        assert_eq!(w.tangential.k_mu().0, 8.0 * tangential::mix_stiffness_g_wall(1e6, 0.3));
        assert_eq!(m.twisting, Some(Twisting::Marshall { k_tang: 8.0 * g, mu_tang: 0.2 }));
        let m = GranModel::build(&parse("hooke 1 1 tangential mindlin_classic 1 1 1 twisting sds 1 1 1", false).unwrap(), false);
        assert_eq!((m.history_size, m.history_keep), (6, 0b111_000));
        assert_eq!(m.tangential, Tangential::LinearHistoryClassic { k: 1.0, xt: 1.0, mu: 1.0 });
    }

    #[test]
    fn mixing_follows_each_style() {
        let a = parse("hertz/material 1e6 0.4 0.3 tangential linear_history 100 0.5 0.1", false).unwrap();
        let b = parse("hertz/material 4e6 0.9 0.2 tangential linear_history 400 0.5 0.4", false).unwrap();
        let m = GranSpec::mix(&a, &b).unwrap();
        assert_eq!(m.normal.coeffs[0], normal::mix_stiffness_e(1e6, 4e6, 0.3, 0.2));
        assert_eq!(m.normal.coeffs[1], (0.4f64 * 0.9).sqrt());
        assert_eq!(&m.tangential.coeffs[..3], &[200.0, 0.5, 0.2]);
        // Kn = 4/3 E_eff of the two materials (LAMMPS 2025; measured)
        assert_eq!(GranModel::build(&m, false).normal, Normal::Hertz { k: 4.0 / 3.0 * normal::mix_stiffness_e(1e6, 4e6, 0.3, 0.2) });
        let c = parse("hertz 1e6 0.4 tangential linear_history 100 0.5 0.1", false).unwrap();
        assert!(GranSpec::mix(&a, &c).is_none());
    }
}
