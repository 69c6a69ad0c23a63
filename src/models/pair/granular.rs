//! `pair_style granular [cutoff]` with per-type-pair contact models, as LAMMPS 2025's
//! GranularModel computes them:
//!
//! ```text
//! pair_coeff I J hooke Kn eta_n0 [damping velocity|mass_velocity|viscoelastic|tsuji]
//!            [tangential linear_nohistory x_gt mu | linear_history Kt x_gt mu]
//!            [limit_damping] [cutoff value]
//! ```
//!
//! * F_n = Kn delta + F_damp, F_damp = -eta_n v_n with eta_n = eta_n0 (velocity),
//!   eta_n0 m_eff (mass_velocity), eta_n0 m_eff a (viscoelastic, a = sqrt(delta R_eff), the
//!   default) or eta_n0' sqrt(m_eff Kn) (tsuji, eta_n0' a polynomial of the restitution e);
//!   `limit_damping` clamps F_n at 0. F_n,crit = |F_n|.
//! * linear_history: before the update the spring is rotated into the tangent plane AND
//!   rescaled to its old length (only when its normal part matters: |s.n| Kt > 1e-10 mu F_n,crit);
//!   s += v_tr dt; F_t = -Kt s - x_gt eta_n v_tr, limited to mu F_n,crit with s set back.
//! * linear_nohistory: F_t = -min(mu F_n,crit, x_gt eta_n |v_tr|) v_tr/|v_tr|.
//! * torques -(R - delta/2) (n x F_t) on each sphere (contact-point lever).
//!
//! Unset I,J pairs mix from I,I and J,J (same models, geometric means of the coefficients).
//! Rolling, twisting, heat and the Hertz/DMT/JKR/Mindlin models are not supported.
//! The same contact law serves `fix wall/gran ... granular` (see [`granular_contact`]).

use super::contact::{compute_contacts, Contact, ContactForce, ContactModel};
use super::gran_hooke_history::{check_setup, rebuild_history, GranTypes};
use super::{PairInput, PairModify, PairOutput, PairSetup, PairStyle, Tally, TypeTable};
use crate::engine::contact_history::ContactHistory;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "pair_style granular [cutoff]";
pub const COEFF_SYNTAX: &str = "pair_coeff I J hooke Kn eta_n0 [damping velocity|mass_velocity|viscoelastic|tsuji] [tangential linear_nohistory x_gt mu | linear_history Kt x_gt mu] [limit_damping] [cutoff value]";

#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Damping {
    Velocity,
    MassVelocity,
    #[default]
    Viscoelastic,
    Tsuji,
}

impl Damping {
    pub fn name(self) -> &'static str {
        match self {
            Damping::Velocity => "velocity",
            Damping::MassVelocity => "mass_velocity",
            Damping::Viscoelastic => "viscoelastic",
            Damping::Tsuji => "tsuji",
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Tangential {
    #[default]
    None,
    LinearNoHistory,
    LinearHistory,
}

/// One type pair's contact model (the coefficients as given, and derived values).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GranModel {
    pub set: bool,
    pub kn: f64,
    /// eta_n0 as given
    pub damp_coeff: f64,
    /// the damping model's own coefficient (eta_n0, or the Tsuji polynomial of it)
    pub damp: f64,
    pub damping: Damping,
    pub tangential: Tangential,
    pub kt: f64,
    pub xt: f64,
    pub mu: f64,
    pub limit_damping: bool,
    /// `cutoff` keyword (negative: from the radii)
    pub cutoff: f64,
}

impl GranModel {
    /// Derived coefficients (LAMMPS `coeffs_to_local` and the damping model's `init`).
    fn finish(&mut self) {
        self.damp = match self.damping {
            Damping::Tsuji => {
                let t = self.damp_coeff;
                let mut d = 1.2728 - 4.2783 * t + 11.087 * (t * t);
                d += -22.348 * (t * t * t) + 27.467 * powint(t, 4);
                d += -18.022 * powint(t, 5) + 4.8218 * powint(t, 6);
                d
            }
            _ => self.damp_coeff,
        };
    }

    /// Parse `hooke Kn eta_n0 [keywords]` (the words after the type ranges).
    pub fn parse(a: &mut Args, wall: bool) -> DResult<GranModel> {
        let mut m = GranModel { cutoff: -1.0, ..GranModel::default() };
        let normal = a.word("normal model")?;
        if normal.text != "hooke" {
            return Err(unsupported_model(a, normal, "normal", &["hooke"]));
        }
        m.kn = a.non_negative_f64("Kn")?;
        m.damp_coeff = a.non_negative_f64("eta_n0 (normal damping)")?;
        let stops: &[&str] = if wall { &["xplane", "yplane", "zplane", "zcylinder", "region"] } else { &[] };
        while let Some(w) = a.peek() {
            if stops.contains(&w.text.as_str()) {
                break;
            }
            a.skip(1);
            match w.text.as_str() {
                "damping" => {
                    let d = a.word("damping model")?;
                    m.damping = match d.text.as_str() {
                        "velocity" => Damping::Velocity,
                        "mass_velocity" => Damping::MassVelocity,
                        "viscoelastic" => Damping::Viscoelastic,
                        "tsuji" => Damping::Tsuji,
                        _ => return Err(unsupported_model(a, d, "damping", &["velocity", "mass_velocity", "viscoelastic", "tsuji"])),
                    };
                }
                "tangential" => {
                    let t = a.word("tangential model")?;
                    match t.text.as_str() {
                        "linear_nohistory" => {
                            m.tangential = Tangential::LinearNoHistory;
                            m.xt = a.non_negative_f64("x_gt (tangential damping ratio)")?;
                            m.mu = a.non_negative_f64("mu (friction coefficient)")?;
                        }
                        "linear_history" => {
                            m.tangential = Tangential::LinearHistory;
                            m.kt = a.non_negative_f64("Kt")?;
                            m.xt = a.non_negative_f64("x_gt (tangential damping ratio)")?;
                            m.mu = a.non_negative_f64("mu (friction coefficient)")?;
                        }
                        _ => return Err(unsupported_model(a, t, "tangential", &["linear_nohistory", "linear_history"])),
                    }
                }
                "limit_damping" => m.limit_damping = true,
                "cutoff" if !wall => m.cutoff = a.f64("cutoff")?,
                "rolling" | "twisting" | "heat" | "synchronized" => {
                    return Err(a.error_at(w, format!("granular `{}` models are not supported by dmhs", w.text), "not supported"));
                }
                _ => {
                    let known: &[&str] = if wall { &["damping", "tangential", "limit_damping"] } else { &["damping", "tangential", "limit_damping", "cutoff"] };
                    return Err(a.unknown_keyword(w, known));
                }
            }
        }
        if m.tangential == Tangential::None {
            return Err(a.missing("a tangential model (`tangential linear_history Kt x_gt mu` or `tangential linear_nohistory x_gt mu`): LAMMPS requires one"));
        }
        m.set = true;
        m.finish();
        Ok(m)
    }

    /// LAMMPS' default mixing: same models, geometric means of the coefficients.
    fn mix(a: &GranModel, b: &GranModel) -> Option<GranModel> {
        if a.damping != b.damping || a.tangential != b.tangential {
            return None;
        }
        let g = |x: f64, y: f64| (x * y).sqrt();
        let mut m = GranModel {
            set: false,
            kn: g(a.kn, b.kn),
            damp_coeff: g(a.damp_coeff, b.damp_coeff),
            damp: 0.0,
            damping: a.damping,
            tangential: a.tangential,
            kt: g(a.kt, b.kt),
            xt: g(a.xt, b.xt),
            mu: g(a.mu, b.mu),
            limit_damping: a.limit_damping || b.limit_damping,
            cutoff: if a.cutoff >= 0.0 || b.cutoff >= 0.0 { a.cutoff.max(b.cutoff) } else { -1.0 },
        };
        m.finish();
        Some(m)
    }

    fn describe(&self) -> String {
        let t = match self.tangential {
            Tangential::LinearHistory => format!("tangential linear_history {} {} {}", self.kt, self.xt, self.mu),
            Tangential::LinearNoHistory => format!("tangential linear_nohistory {} {}", self.xt, self.mu),
            Tangential::None => String::new(),
        };
        format!(
            "hooke {} {} damping {} {}{}",
            self.kn,
            self.damp_coeff,
            self.damping.name(),
            t,
            if self.limit_damping { " limit_damping" } else { "" }
        )
    }
}

fn powint(x: f64, n: i32) -> f64 {
    // LAMMPS MathSpecial::powint: binary exponentiation
    let mut yy = x;
    let mut ww = 1.0;
    let mut n = n;
    while n != 0 {
        if n & 1 != 0 {
            ww *= yy;
        }
        n >>= 1;
        yy *= yy;
    }
    ww
}

fn unsupported_model(a: &Args, w: &Word, kind: &str, supported: &[&str]) -> dmhs_parser::Diagnostic {
    a.error_at(w, format!("granular {kind} model `{}` is not supported by dmhs", w.text), format!("supported: {}", supported.join(", ")))
}

/// The geometry of one contact, for pairs and walls.
pub struct GranGeom<'a> {
    /// x_i - x_j (wall: from the wall to the sphere)
    pub dx: [f64; 3],
    pub rsq: f64,
    pub radi: f64,
    /// partner radius (wall: 0 for a plane)
    pub radj: f64,
    pub vi: &'a [f64; 3],
    pub vj: &'a [f64; 3],
    pub omegai: &'a [f64; 3],
    pub omegaj: &'a [f64; 3],
    pub meff: f64,
    pub wall: bool,
}

/// LAMMPS GranularModel::calculate_forces for the supported sub-models. Returns the force on
/// i, and the torques on i and j (a wall's torque lever is the full radius).
#[inline(always)]
pub fn granular_contact(m: &GranModel, g: &GranGeom, history: &mut [f64], update: bool, dt: f64) -> ContactForce {
    let (radi, radj) = (g.radi, g.radj);
    let (radsum, reff) = if g.wall {
        (radi, if radj == 0.0 { radi } else { radi * radj / (radi + radj) })
    } else {
        let s = radi + radj;
        (s, radi * radj / s)
    };
    let r = g.rsq.sqrt();
    let rinv = 1.0 / r;
    let delta = radsum - r;
    let nx = [rinv * g.dx[0], rinv * g.dx[1], rinv * g.dx[2]];

    // relative velocity: normal and tangential parts
    let vr = [g.vi[0] - g.vj[0], g.vi[1] - g.vj[1], g.vi[2] - g.vj[2]];
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

    // normal force
    let fnormal = m.kn * delta;
    let damp_prefactor = match m.damping {
        Damping::Velocity => m.damp,
        Damping::MassVelocity => m.damp * g.meff,
        Damping::Viscoelastic => m.damp * g.meff * (delta * reff).sqrt(),
        Damping::Tsuji => m.damp * (g.meff * fnormal / delta).sqrt(),
    };
    let fdamp = -damp_prefactor * vnnr;
    let mut fntot = fnormal + fdamp;
    if m.limit_damping && fntot < 0.0 {
        fntot = 0.0;
    }
    let fncrit = fntot.abs();

    // tangential force
    let damp = m.xt * damp_prefactor;
    let mut fs;
    match m.tangential {
        Tangential::LinearHistory => {
            let k = m.kt;
            let fscrit = fncrit * m.mu;
            let h = history;
            if update {
                // rotate into the tangent plane, keeping the length, when the normal part matters
                let rsht = h[0] * nx[0] + h[1] * nx[1] + h[2] * nx[2];
                if rsht.abs() * k > 1e-10 * fscrit {
                    let shrmag = len3(h[0], h[1], h[2]);
                    h[0] -= rsht * nx[0];
                    h[1] -= rsht * nx[1];
                    h[2] -= rsht * nx[2];
                    let prjmag = len3(h[0], h[1], h[2]);
                    let scale = if prjmag > 0.0 { shrmag / prjmag } else { 0.0 };
                    h[0] *= scale;
                    h[1] *= scale;
                    h[2] *= scale;
                }
                h[0] += dt * vtr[0];
                h[1] += dt * vtr[1];
                h[2] += dt * vtr[2];
            }
            fs = [-k * h[0], -k * h[1], -k * h[2]];
            fs = [fs[0] - damp * vtr[0], fs[1] - damp * vtr[1], fs[2] - damp * vtr[2]];
            let magfs = len3(fs[0], fs[1], fs[2]);
            if magfs > fscrit {
                let shrmag = len3(h[0], h[1], h[2]);
                if shrmag != 0.0 {
                    let s = fscrit * (1.0 / magfs);
                    let kinv = -1.0 / k;
                    for d in 0..3 {
                        h[d] = s * fs[d];
                        h[d] += damp * vtr[d];
                        h[d] *= kinv;
                        fs[d] *= s;
                    }
                } else {
                    fs = [0.0; 3];
                }
            }
        }
        Tangential::LinearNoHistory | Tangential::None => {
            let vrel = len3(vtr[0], vtr[1], vtr[2]);
            let fscrit = m.mu * fncrit;
            let fsmag = damp * vrel;
            let ft = if vrel != 0.0 { (if fscrit < fsmag { fscrit } else { fsmag }) / vrel } else { 0.0 };
            fs = [-ft * vtr[0], -ft * vtr[1], -ft * vtr[2]];
        }
    }

    let f = [fntot * nx[0] + fs[0], fntot * nx[1] + fs[1], fntot * nx[2] + fs[2]];
    // torque direction -(n x F_t), scaled by the lever
    let t = [
        -(nx[1] * fs[2] - nx[2] * fs[1]),
        -(nx[2] * fs[0] - nx[0] * fs[2]),
        -(nx[0] * fs[1] - nx[1] * fs[0]),
    ];
    if g.wall {
        ContactForce { f, ti: [radi * t[0], radi * t[1], radi * t[2]], tj: [0.0; 3] }
    } else {
        let li = radi - 0.5 * delta;
        let lj = radj - 0.5 * delta;
        ContactForce { f, ti: [li * t[0], li * t[1], li * t[2]], tj: [lj * t[0], lj * t[1], lj * t[2]] }
    }
}

#[inline(always)]
fn len3(a: f64, b: f64, c: f64) -> f64 {
    (a * a + b * b + c * c).sqrt()
}

/// The per-type-pair models as a [`ContactModel`].
pub struct GranularModels(pub TypeTable<GranModel>);

impl ContactModel for GranularModels {
    type Params = GranModel;
    const HISTORY: usize = 3;
    #[inline(always)]
    fn params(&self, ti: usize, tj: usize) -> &GranModel {
        self.0.get(ti, tj)
    }
    #[inline(always)]
    fn contact(m: &GranModel, c: &Contact, hist: &mut [f64], update: bool, dt: f64) -> ContactForce {
        let g = GranGeom {
            dx: c.del,
            rsq: c.rsq,
            radi: c.radi,
            radj: c.radj,
            vi: c.vi,
            vj: c.vj,
            omegai: c.omegai,
            omegaj: c.omegaj,
            meff: c.mi * c.mj / (c.mi + c.mj),
            wall: false,
        };
        granular_contact(m, &g, hist, update, dt)
    }
}

pub struct Granular {
    cut_global: f64,
    coeff: TypeTable<GranModel>,
    models: GranularModels,
    types: GranTypes,
    history: ContactHistory,
}

impl Granular {
    pub fn from_lammps(args: &[Word], cmd: &Command) -> DResult<Granular> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let cut_global = if a.is_empty() { -1.0 } else { a.f64("cutoff")? };
        a.finish()?;
        Ok(Granular {
            cut_global,
            coeff: TypeTable::new(0),
            models: GranularModels(TypeTable::new(0)),
            types: GranTypes::default(),
            history: ContactHistory::new(3),
        })
    }

    fn grow(&mut self, n: usize) {
        if self.coeff.n >= n {
            return;
        }
        let mut t = TypeTable::new(n);
        for i in 1..=self.coeff.n {
            for j in 1..=self.coeff.n {
                t.set(i, j, *self.coeff.get(i, j));
            }
        }
        self.coeff = t;
    }
}

impl PairStyle for Granular {
    fn style(&self) -> &str {
        "granular"
    }
    fn contact_stiffness(&self) -> Option<f64> {
        self.coeff.data.iter().map(|m| m.kn).reduce(f64::max)
    }
    fn coeff(&mut self, ilo: usize, ihi: usize, jlo: usize, jhi: usize, args: &mut Args) -> DResult<()> {
        args.syntax = COEFF_SYNTAX;
        let m = GranModel::parse(args, false)?;
        args.finish()?;
        self.grow(ihi.max(jhi));
        for i in ilo..=ihi {
            for j in jlo.max(i)..=jhi {
                self.coeff.set(i, j, m);
            }
        }
        self.types.set_range(ilo, ihi, jlo, jhi);
        Ok(())
    }
    fn init_sim(&mut self, setup: &PairSetup) -> Result<(), String> {
        check_setup(setup, self.style())?;
        self.types.init_radii(setup);
        Ok(())
    }
    fn init(&mut self, ntypes: usize, _modify: &PairModify, active: Option<&[bool]>) -> Result<(), String> {
        self.grow(ntypes);
        self.types.check(ntypes, active, "granular")?;
        let mut models = TypeTable::new(ntypes);
        for i in 1..=ntypes {
            for j in i..=ntypes {
                if let Some(a) = active {
                    if !a[i * (ntypes + 1) + j] {
                        continue;
                    }
                }
                let c = *self.coeff.get(i, j);
                let m = if c.set {
                    c
                } else {
                    GranModel::mix(self.coeff.get(i, i), self.coeff.get(j, j))
                        .ok_or_else(|| format!("pair granular: types {i} and {j} use different models, so the {i} {j} pair cannot be mixed: set it with pair_coeff"))?
                };
                models.set(i, j, m);
            }
        }
        self.models = GranularModels(models);
        Ok(())
    }
    fn cutoff(&self, it: usize, jt: usize) -> f64 {
        let m = self.models.0.get(it, jt);
        if m.cutoff >= 0.0 {
            m.cutoff
        } else if self.cut_global >= 0.0 {
            self.cut_global
        } else {
            self.types.cutoff(it, jt)
        }
    }
    fn compute(&mut self, input: &PairInput, out: &mut PairOutput) -> Tally {
        compute_contacts(&self.models, input, out, Some(&mut self.history))
    }
    fn rebuilt(&mut self, input: &PairInput, _order: &[usize]) {
        rebuild_history(&mut self.history, input);
    }
    fn histories(&mut self) -> Vec<&mut ContactHistory> {
        vec![&mut self.history]
    }
    fn describe(&self) -> String {
        let mut s = String::from("granular");
        if self.cut_global >= 0.0 {
            s += &format!(" {}", self.cut_global);
        }
        for i in 1..=self.coeff.n {
            for j in i..=self.coeff.n {
                let c = self.coeff.get(i, j);
                if c.set {
                    s += &format!("\n    {i} {j}: {}", c.describe());
                }
            }
        }
        s
    }
}
