//! The `velocity` command (create, set, scale, ramp, zero) as pure functions over atom
//! arrays, computing what LAMMPS' `Velocity` class computes in the same floating-point
//! order: the same random streams (`loop all` by atom ID, `loop geom` by position hash,
//! `loop local`), the same momentum and angular-momentum removal and the same rescaling
//! by the group temperature (LAMMPS `compute temp`).
//!
//! Arrays must be in LAMMPS' local atom order (creation order before the first run), since
//! the group sums (mass, momentum, temperature) are accumulated in that order.

// Index loops mirror LAMMPS' formulas term by term (same evaluation order).
#![allow(clippy::needless_range_loop)]

use crate::engine::domain::Periods;
use crate::engine::group_rotation::{remove_rotation, GroupRotation};
use crate::engine::lattice::Lattice;
use crate::engine::random_park::RanPark;
use dmhs_parser::{Args, Command, DResult, Diagnostic, Span, Word};

const SYNTAX: &str = "velocity group-ID style args keyword value ... \
(styles: create T seed | set vx vy vz | scale T | ramp vdim vlo vhi dim clo chi | zero linear|angular; \
keywords: dist uniform|gaussian, sum yes|no, mom yes|no, rot yes|no, temp compute-ID, bias yes|no, \
loop all|local|geom, units box|lattice)";

/// Warm-up draws for `loop local` (LAMMPS `WARMUP`).
const WARMUP: usize = 100;
/// How `velocity create` walks the atoms to draw random numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LoopMode {
    /// One stream over atom IDs 1..N (independent of the number of ranks).
    All,
    /// One stream over local atoms (seed + rank; rank 0 here).
    Local,
    /// A stream per atom seeded from its coordinates.
    Geom,
}

#[derive(Clone, Debug, PartialEq)]
pub struct VelocityOptions {
    pub gaussian: bool,
    pub sum: bool,
    pub mom: bool,
    pub rot: bool,
    /// Compute ID given with `temp` (default: a `compute temp` over the group).
    pub temp: Option<String>,
    /// `bias yes`: remove the `temp` compute's velocity bias before create/scale, restore after.
    pub bias: bool,
    pub loop_mode: LoopMode,
    pub lattice_units: bool,
}

impl Default for VelocityOptions {
    fn default() -> VelocityOptions {
        VelocityOptions {
            gaussian: false,
            sum: false,
            mom: true,
            rot: false,
            temp: None,
            bias: false,
            loop_mode: LoopMode::All,
            lattice_units: true,
        }
    }
}

/// One component of `velocity set`: NULL (left unchanged), a number (in box units), or a
/// variable `v_name`, which the command evaluates before it applies (equal-style: one value;
/// atom-style: one per local atom; LAMMPS scales neither by the lattice).
#[derive(Clone, Debug, PartialEq)]
pub enum SetArg {
    Null,
    Value(f64),
    PerAtom(Vec<f64>),
    Variable(Word),
}

/// A velocity style with its arguments already converted to box units.
#[derive(Clone, Debug, PartialEq)]
pub enum VelocityStyle {
    Create {
        temp: f64,
        seed: i32,
    },
    Set {
        v: [SetArg; 3],
    },
    Scale {
        temp: f64,
    },
    Ramp {
        vdim: usize,
        vlo: f64,
        vhi: f64,
        cdim: usize,
        clo: f64,
        chi: f64,
    },
    Zero {
        angular: bool,
    },
}

/// A parsed `velocity` command.
#[derive(Clone, Debug, PartialEq)]
pub struct Velocity {
    pub group: String,
    pub style: VelocityStyle,
    pub opts: VelocityOptions,
    pub span: Span,
}

/// The per-atom data the velocity styles read. All slices have one entry per local atom.
pub struct VelocityAtoms<'a> {
    /// Atom IDs (LAMMPS tags).
    pub ids: &'a [i64],
    pub x: &'a [[f64; 3]],
    /// Image flags (for unwrapped coordinates in `rot`/`zero angular`).
    pub image: &'a [[i32; 3]],
    /// Per-atom mass (the type mass, or the per-atom mass for atom styles that have one).
    pub mass: &'a [f64],
    /// Group membership.
    pub selected: &'a [bool],
}

/// Global settings the velocity styles need.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VelocityEnv {
    pub dimension: usize,
    pub boltz: f64,
    pub mvv2e: f64,
    /// Box lengths (for unwrapping with image flags).
    pub periods: Periods,
    /// Degrees of freedom of a `compute temp` over the group (see [`default_dof`]).
    pub dof: f64,
}

/// The temperature compute given with `temp ID`: the temperature of velocities `v` as it
/// measures it, and its velocity bias (LAMMPS' compute_scalar, remove_bias_all,
/// reapply_bias_all). Without one, velocity measures a `compute temp` over its group.
pub trait VelocityTemp {
    fn temperature(&mut self, v: &[[f64; 3]]) -> Result<f64, String>;
    /// The bias of each atom for velocities `v` (zero outside the compute's group).
    fn bias(&mut self, v: &[[f64; 3]]) -> Result<Vec<[f64; 3]>, String>;
    /// Reset the components the bias owns after new thermal velocities (temp/partial: 0).
    fn reapply(&mut self, v: &mut [[f64; 3]]);
}

fn add_field(v: &mut [[f64; 3]], field: &[[f64; 3]], sign: f64) {
    for (vi, b) in v.iter_mut().zip(field) {
        for k in 0..3 {
            if sign > 0.0 {
                vi[k] += b[k];
            } else {
                vi[k] -= b[k];
            }
        }
    }
}

/// Degrees of freedom of a default `compute temp` over `count` atoms: `dim * count - dim`
/// (LAMMPS' `extra_dof` = dimension, no fix-removed dof).
pub fn default_dof(count: usize, dimension: usize) -> f64 {
    let natoms = count as f64;
    let mut dof = dimension as f64 * natoms;
    dof -= dimension as f64;
    dof
}

/// Group temperature as LAMMPS `compute temp` computes it: `sum(m v^2) * mvv2e / (dof kB)`.
pub fn temperature(v: &[[f64; 3]], mass: &[f64], selected: &[bool], dof: f64, boltz: f64, mvv2e: f64) -> f64 {
    let mut t = 0.0;
    for i in 0..v.len() {
        if selected[i] {
            t += (v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]) * mass[i];
        }
    }
    let tfactor = if dof > 0.0 { mvv2e / (dof * boltz) } else { 0.0 };
    t * tfactor
}

/// Scale the group's velocities from temperature `t_old` to `t_new` (LAMMPS `rescale`).
pub fn rescale(v: &mut [[f64; 3]], selected: &[bool], t_old: f64, t_new: f64) -> Result<(), String> {
    if t_old == 0.0 {
        return Err("attempting to rescale a 0.0 temperature".into());
    }
    let factor = (t_new / t_old).sqrt();
    for (vi, _) in v.iter_mut().zip(selected).filter(|(_, &s)| s) {
        vi[0] *= factor;
        vi[1] *= factor;
        vi[2] *= factor;
    }
    Ok(())
}

/// Total mass of the group (LAMMPS `Group::mass`).
fn group_mass(mass: &[f64], selected: &[bool]) -> f64 {
    let mut m = 0.0;
    for i in 0..mass.len() {
        if selected[i] {
            m += mass[i];
        }
    }
    m
}

/// Remove the centre-of-mass velocity of the group (LAMMPS `zero_momentum`).
pub fn zero_momentum(v: &mut [[f64; 3]], mass: &[f64], selected: &[bool]) -> Result<(), String> {
    if !selected.iter().any(|&s| s) {
        return Err("cannot zero momentum of no atoms".into());
    }
    let masstotal = group_mass(mass, selected);
    let mut p = [0.0; 3];
    for i in 0..v.len() {
        if selected[i] {
            p[0] += v[i][0] * mass[i];
            p[1] += v[i][1] * mass[i];
            p[2] += v[i][2] * mass[i];
        }
    }
    let mut vcm = p;
    if masstotal > 0.0 {
        for c in &mut vcm {
            *c /= masstotal;
        }
    }
    for i in 0..v.len() {
        if selected[i] {
            v[i][0] -= vcm[0];
            v[i][1] -= vcm[1];
            v[i][2] -= vcm[2];
        }
    }
    Ok(())
}

/// Remove the angular velocity of the group about its centre of mass (LAMMPS
/// `zero_rotation`: `v_i -= omega x r_i` with unwrapped positions).
pub fn zero_rotation(v: &mut [[f64; 3]], atoms: &VelocityAtoms, periods: Periods) -> Result<(), String> {
    let r = GroupRotation::of(v, atoms.x, atoms.image, atoms.mass, atoms.selected, periods, &mut |_| {}).ok_or("cannot zero momentum of no atoms")?;
    let (cm, w) = (r.cm, r.omega()?);
    let (x, image, sel) = (atoms.x, atoms.image, atoms.selected);
    for i in 0..v.len() {
        if sel[i] {
            remove_rotation(&mut v[i], periods.unmap(x[i], image[i]), cm, w);
        }
    }
    Ok(())
}

/// The three random components for one atom (uniform in [-0.5, 0.5) or Gaussian).
fn triple(random: &mut RanPark, gaussian: bool) -> [f64; 3] {
    if gaussian {
        [random.gaussian(), random.gaussian(), random.gaussian()]
    } else {
        [random.uniform() - 0.5, random.uniform() - 0.5, random.uniform() - 0.5]
    }
}

/// `velocity G create T seed`: random velocities, momentum/rotation removal, rescale to `t`.
pub fn create(
    v: &mut [[f64; 3]],
    atoms: &VelocityAtoms,
    env: &VelocityEnv,
    t_desired: f64,
    seed: i32,
    opts: &VelocityOptions,
    mut tc: Option<&mut dyn VelocityTemp>,
) -> Result<(), String> {
    if seed <= 0 {
        return Err(format!("illegal velocity create seed {seed}"));
    }
    let n = v.len();
    let sel = atoms.selected;
    let vhold: Option<Vec<[f64; 3]>> = if opts.sum { Some(v.to_vec()) } else { None };
    // bias yes: the compute's bias comes off first and back after the rescale
    let bias = match (&mut tc, opts.bias) {
        (Some(tc), true) => {
            tc.temperature(v)?;
            let b = tc.bias(v)?;
            add_field(v, &b, -1.0);
            Some(b)
        }
        _ => None,
    };
    let assign = |v: &mut [[f64; 3]], i: usize, r: [f64; 3]| {
        let factor = 1.0 / atoms.mass[i].sqrt();
        v[i][0] = r[0] * factor;
        v[i][1] = r[1] * factor;
        v[i][2] = if env.dimension == 3 { r[2] * factor } else { 0.0 };
    };
    match opts.loop_mode {
        LoopMode::All => {
            // IDs must be exactly 1..N; draw for every ID, assign to those in the group.
            let natoms = n;
            let mut index = vec![usize::MAX; natoms + 1];
            for (i, &id) in atoms.ids.iter().enumerate() {
                if id < 1 || id as usize > natoms || index[id as usize] != usize::MAX {
                    return Err("atom IDs must be consecutive for velocity create loop all".into());
                }
                index[id as usize] = i;
            }
            if natoms > i32::MAX as usize {
                return Err("too big a problem to use velocity create loop all".into());
            }
            let mut random = RanPark::new(seed);
            for id in 1..=natoms {
                let r = triple(&mut random, opts.gaussian);
                let m = index[id];
                if sel[m] {
                    assign(v, m, r);
                }
            }
        }
        LoopMode::Local => {
            let mut random = RanPark::new(seed);
            for _ in 0..WARMUP {
                random.uniform();
            }
            for i in 0..n {
                if sel[i] {
                    let r = triple(&mut random, opts.gaussian);
                    assign(v, i, r);
                }
            }
        }
        LoopMode::Geom => {
            let mut random = RanPark::new(1);
            for i in 0..n {
                if sel[i] {
                    random.reset_coord(seed, atoms.x[i]);
                    let r = triple(&mut random, opts.gaussian);
                    assign(v, i, r);
                }
            }
        }
    }
    if opts.mom {
        zero_momentum(v, atoms.mass, sel)?;
    }
    if opts.rot {
        zero_rotation(v, atoms, env.periods)?;
    }
    // with a bias the new thermal velocities are measured by a compute temp over the group
    let t = match (&mut tc, &bias) {
        (Some(tc), None) => tc.temperature(v)?,
        _ => temperature(v, atoms.mass, sel, env.dof, env.boltz, env.mvv2e),
    };
    rescale(v, sel, t, t_desired)?;
    if let (Some(tc), Some(b)) = (&mut tc, &bias) {
        tc.reapply(v);
        add_field(v, b, 1.0);
    }
    if let Some(old) = vhold {
        for i in 0..n {
            if sel[i] {
                v[i][0] += old[i][0];
                v[i][1] += old[i][1];
                v[i][2] += old[i][2];
            }
        }
    }
    Ok(())
}

/// `velocity G set vx vy vz`, the components evaluated (NULL: unchanged), as LAMMPS' order.
pub fn set(v: &mut [[f64; 3]], selected: &[bool], value: &[SetArg; 3], sum: bool) -> Result<(), String> {
    for (i, (vi, _)) in v.iter_mut().zip(selected).enumerate().filter(|(_, (_, &s))| s) {
        for d in 0..3 {
            let c = match &value[d] {
                SetArg::Null => continue,
                SetArg::Value(c) => *c,
                SetArg::PerAtom(p) => p[i],
                SetArg::Variable(w) => return Err(format!("velocity set: variable {} was not evaluated", w.text)),
            };
            if sum {
                vi[d] += c;
            } else {
                vi[d] = c;
            }
        }
    }
    Ok(())
}

/// `velocity G ramp`: component `vdim` ramps from `vlo` to `vhi` as coordinate `cdim`
/// goes from `clo` to `chi` (clamped outside).
#[allow(clippy::too_many_arguments)]
pub fn ramp(
    v: &mut [[f64; 3]],
    x: &[[f64; 3]],
    selected: &[bool],
    vdim: usize,
    vlo: f64,
    vhi: f64,
    cdim: usize,
    clo: f64,
    chi: f64,
    sum: bool,
) {
    for i in 0..v.len() {
        if selected[i] {
            let mut fraction = (x[i][cdim] - clo) / (chi - clo);
            fraction = if fraction > 0.0 { fraction } else { 0.0 };
            fraction = if fraction < 1.0 { fraction } else { 1.0 };
            let vramp = vlo + fraction * (vhi - vlo);
            if sum {
                v[i][vdim] += vramp;
            } else {
                v[i][vdim] = vramp;
            }
        }
    }
}

impl Velocity {
    /// Parse a `velocity` command. `lattice` gives the spacings for `units lattice` (the
    /// default); without a lattice LAMMPS' initial `lattice none 1.0` is used.
    pub fn from_lammps(cmd: &Command, dimension: usize, lattice: Option<&Lattice>) -> DResult<Velocity> {
        let mut a = Args::new(cmd, SYNTAX);
        let group = a.str("group ID")?.to_string();
        let style_word = a.word("velocity style")?;
        const STYLES: [&str; 5] = ["create", "set", "scale", "ramp", "zero"];
        let nargs = match style_word.text.as_str() {
            "create" => 2,
            "set" => 3,
            "scale" => 1,
            "ramp" => 6,
            "zero" => 1,
            _ => return Err(a.unknown_keyword(style_word, &STYLES)),
        };
        if a.len_remaining() < nargs {
            a.skip(a.len_remaining());
            return Err(a.missing(&format!("{nargs} arguments of velocity {}", style_word.text)));
        }
        let sargs: &[Word] = &a.remaining()[..nargs];
        a.skip(nargs);

        let mut opts = VelocityOptions::default();
        const KEYWORDS: [&str; 9] = ["dist", "sum", "mom", "rot", "temp", "bias", "loop", "rigid", "units"];
        while let Some(kw) = a.peek() {
            a.skip(1);
            match kw.text.as_str() {
                "dist" => opts.gaussian = a.choice("dist", &["uniform", "gaussian"])? == 1,
                "sum" => opts.sum = a.logical("sum")?,
                "mom" => opts.mom = a.logical("mom")?,
                "rot" => opts.rot = a.logical("rot")?,
                "temp" => opts.temp = Some(a.str("temperature compute ID")?.to_string()),
                "loop" => {
                    opts.loop_mode = [LoopMode::All, LoopMode::Local, LoopMode::Geom]
                        [a.choice("loop", &["all", "local", "geom"])?];
                }
                "units" => opts.lattice_units = a.choice("units", &["lattice", "box"])? == 0,
                "bias" => opts.bias = a.logical("bias")?,
                "rigid" => {
                    return Err(a.error_at(
                        kw,
                        format!("velocity keyword `{}` is not supported", kw.text),
                        "not supported",
                    ));
                }
                _ => return Err(a.unknown_keyword(kw, &KEYWORDS)),
            }
        }
        let none = Lattice::none(1.0);
        let lat = lattice.unwrap_or(&none);
        let scale = if opts.lattice_units { lat.spacing() } else { [1.0; 3] };
        let num = |w: &Word, what: &str| -> DResult<f64> {
            if w.text.starts_with("v_") {
                return Err(a.error_at(
                    w,
                    "variables in velocity arguments are not supported",
                    "variable not supported",
                ));
            }
            dmhs_parser::args::word_f64(w, what).map_err(|d| d.with_help(format!("syntax: {SYNTAX}")))
        };
        let dim_of = |w: &Word, names: [&str; 3], what: &str| -> DResult<usize> {
            names.iter().position(|n| *n == w.text).ok_or_else(|| {
                a.error_at(
                    w,
                    format!("expected {} for {what}, found `{}`", names.join(" or "), w.text),
                    "invalid dimension",
                )
            })
        };

        let style = match style_word.text.as_str() {
            "create" => {
                let temp = num(&sargs[0], "temperature")?;
                let seed = dmhs_parser::args::word_i64(&sargs[1], "seed")
                    .map_err(|d| d.with_help(format!("syntax: {SYNTAX}")))?;
                if seed <= 0 || seed > i32::MAX as i64 {
                    return Err(a.error_at(
                        &sargs[1],
                        format!("velocity create seed must be a positive integer, found {seed}"),
                        "invalid seed",
                    ));
                }
                VelocityStyle::Create { temp, seed: seed as i32 }
            }
            "set" => {
                let mut v = [SetArg::Null, SetArg::Null, SetArg::Null];
                for d in 0..3 {
                    let w = &sargs[d];
                    v[d] = if w.text == "NULL" {
                        SetArg::Null
                    } else if w.text.starts_with("v_") {
                        SetArg::Variable(w.clone())
                    } else {
                        SetArg::Value(num(w, ["vx", "vy", "vz"][d])? * scale[d])
                    };
                }
                match &v[2] {
                    SetArg::Value(z) if dimension == 2 && *z != 0.0 => {
                        return Err(a.error_at(&sargs[2], "cannot set a non-zero z velocity in a 2d simulation", "must be 0 or NULL"));
                    }
                    SetArg::Variable(w) if dimension == 2 => {
                        return Err(a.error_at(w, "Cannot set variable z velocity for 2d simulation", "must be 0 or NULL"));
                    }
                    _ => {}
                }
                VelocityStyle::Set { v }
            }
            "scale" => VelocityStyle::Scale { temp: num(&sargs[0], "temperature")? },
            "ramp" => {
                let vdim = dim_of(&sargs[0], ["vx", "vy", "vz"], "the ramped velocity component")?;
                if vdim == 2 && dimension == 2 {
                    return Err(a.error_at(&sargs[0], "velocity ramp in z for a 2d simulation", "no z velocity in 2d"));
                }
                let vlo = scale[vdim] * num(&sargs[1], "vlo")?;
                let vhi = scale[vdim] * num(&sargs[2], "vhi")?;
                let cdim = dim_of(&sargs[3], ["x", "y", "z"], "the ramp coordinate")?;
                let clo = scale[cdim] * num(&sargs[4], "clo")?;
                let chi = scale[cdim] * num(&sargs[5], "chi")?;
                VelocityStyle::Ramp { vdim, vlo, vhi, cdim, clo, chi }
            }
            _ => {
                let k = match sargs[0].text.as_str() {
                    "linear" => false,
                    "angular" => true,
                    _ => {
                        return Err(a.error_at(
                            &sargs[0],
                            format!("expected linear or angular, found `{}`", sargs[0].text),
                            "invalid",
                        ))
                    }
                };
                VelocityStyle::Zero { angular: k }
            }
        };
        Ok(Velocity { group, style, opts, span: cmd.span })
    }

    /// Apply the command to the atoms (`v` has one entry per local atom).
    pub fn apply(&self, v: &mut [[f64; 3]], atoms: &VelocityAtoms, env: &VelocityEnv, tc: Option<&mut dyn VelocityTemp>) -> DResult<()> {
        let located = |msg: String| Diagnostic::at(self.span, msg, "in this velocity command");
        if v.is_empty() {
            return Err(located("velocity command with no atoms existing".into()));
        }
        match &self.style {
            VelocityStyle::Create { temp, seed } => create(v, atoms, env, *temp, *seed, &self.opts, tc).map_err(located),
            VelocityStyle::Set { v: value } => set(v, atoms.selected, value, self.opts.sum).map_err(located),
            VelocityStyle::Scale { temp } => match tc {
                None => {
                    let t = temperature(v, atoms.mass, atoms.selected, env.dof, env.boltz, env.mvv2e);
                    rescale(v, atoms.selected, t, *temp).map_err(located)
                }
                Some(tc) => {
                    let t = tc.temperature(v).map_err(located)?;
                    let bias = if self.opts.bias { Some(tc.bias(v).map_err(located)?) } else { None };
                    if let Some(b) = &bias {
                        add_field(v, b, -1.0);
                    }
                    rescale(v, atoms.selected, t, *temp).map_err(located)?;
                    if let Some(b) = &bias {
                        add_field(v, b, 1.0);
                    }
                    Ok(())
                }
            },
            VelocityStyle::Ramp { vdim, vlo, vhi, cdim, clo, chi } => {
                ramp(v, atoms.x, atoms.selected, *vdim, *vlo, *vhi, *cdim, *clo, *chi, self.opts.sum);
                Ok(())
            }
            VelocityStyle::Zero { angular: false } => zero_momentum(v, atoms.mass, atoms.selected).map_err(located),
            VelocityStyle::Zero { angular: true } => zero_rotation(v, atoms, env.periods).map_err(located),
        }
    }
}


#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::lattice::tests::cmd;

    use crate::deck::create_atoms::tests::run_deck_state;

    /// A small system built from a deck with the geometry code, masses per type.
    struct Sys {
        ids: Vec<i64>,
        x: Vec<[f64; 3]>,
        image: Vec<[i32; 3]>,
        types: Vec<usize>,
        mass_of_type: Vec<f64>,
        v: Vec<[f64; 3]>,
        dim: usize,
        lattice: Option<Lattice>,
        periods: Periods,
    }

    fn setup(deck: &str, mass_of_type: &[f64]) -> Sys {
        let st = run_deck_state(deck).unwrap();
        let n = st.atoms.len();
        Sys {
            ids: (1..=n as i64).collect(),
            x: st.atoms.iter().map(|a| a.0).collect(),
            image: vec![[0; 3]; n],
            types: st.atoms.iter().map(|a| a.1).collect(),
            mass_of_type: mass_of_type.to_vec(),
            v: vec![[0.0; 3]; n],
            dim: st.dim,
            lattice: st.lattice.clone(),
            periods: st.boxed.unwrap().domain.periods(),
        }
    }

    impl Sys {
        fn run(&mut self, line: &str, selected: &[bool], boltz: f64) {
            let vc = Velocity::from_lammps(&cmd(line), self.dim, self.lattice.as_ref()).unwrap();
            let mass: Vec<f64> = self.types.iter().map(|&t| self.mass_of_type[t - 1]).collect();
            let count = selected.iter().filter(|&&s| s).count();
            let env = VelocityEnv {
                dimension: self.dim,
                boltz,
                mvv2e: 1.0,
                periods: self.periods,
                dof: default_dof(count, self.dim),
            };
            let atoms = VelocityAtoms { ids: &self.ids, x: &self.x, image: &self.image, mass: &mass, selected };
            vc.apply(&mut self.v, &atoms, &env, None).unwrap();
        }
    }

    /// FNV-1a over (id, vx, vy, vz) in ID order, as computed from LAMMPS' arrays.
    fn vdigest(v: &[[f64; 3]]) -> u64 {
        let mut h: u64 = 0xcbf29ce484222325;
        for (i, vi) in v.iter().enumerate() {
            let mut bytes = (i as u64 + 1).to_le_bytes().to_vec();
            for c in vi {
                bytes.extend(c.to_le_bytes());
            }
            for b in bytes {
                h = (h ^ b as u64).wrapping_mul(0x100000001b3);
            }
        }
        h
    }

    fn check(sys: &Sys, fnv: u64, first: [f64; 3], last: [f64; 3]) {
        assert_eq!(sys.v[0], first);
        assert_eq!(*sys.v.last().unwrap(), last);
        assert_eq!(vdigest(&sys.v), fnv, "velocities differ from LAMMPS");
    }

    // Fixtures: LAMMPS 22 Jul 2025, one rank, velocities by atom ID via extract_atom.
    const FCC: &str =
        "units lj\nlattice fcc 0.8442\nregion box block 0 4 0 4 0 4\ncreate_box 2 box\ncreate_atoms 1 box";

    #[test]
    fn create_loop_all_matches_lammps() {
        let mut s = setup(FCC, &[1.0, 2.5]);
        let all = vec![true; s.v.len()];
        s.run("velocity all create 1.44 87287 loop all", &all, 1.0);
        check(
            &s,
            0xaae6b0b81d88fc6c,
            [0.7636644414798337, 0.13749169671269937, 0.12291516694674864],
            [-1.9014474094324572, 1.4044056352956336, -0.06702550884163075],
        );
    }

    #[test]
    fn create_loop_geom_matches_lammps() {
        let mut s = setup(FCC, &[1.0, 2.5]);
        let all = vec![true; s.v.len()];
        s.run("velocity all create 1.44 87287 loop geom", &all, 1.0);
        check(
            &s,
            0x65d9163c5fd52576,
            [-0.24713448553592715, -0.6350688564395275, -1.919458527294104],
            [0.7999121704500977, 0.7132452754988785, 0.0028891130290597754],
        );
    }

    #[test]
    fn create_loop_local_gaussian_matches_lammps() {
        let mut s = setup(FCC, &[1.0, 2.5]);
        let all = vec![true; s.v.len()];
        s.run("velocity all create 1.44 87287 loop local dist gaussian", &all, 1.0);
        check(
            &s,
            0x6e8ca7391ecc1205,
            [-0.9414795367546245, 0.34932141157555585, 0.22423584171285557],
            [2.123447654526178, -0.7927886220809687, 0.08466587030137063],
        );
    }

    #[test]
    fn create_gaussian_with_rotation_removal_matches_lammps() {
        let mut s = setup(FCC, &[1.0, 2.5]);
        let all = vec![true; s.v.len()];
        s.run("velocity all create 3.0 4928459 dist gaussian rot yes", &all, 1.0);
        check(
            &s,
            0xd6d6d824cbc0b92f,
            [3.2605312623446663, 2.7669967343976483, -0.6742780422126298],
            [-0.23935238670948894, 3.400661656244253, 2.785110455101111],
        );
    }

    #[test]
    fn group_sum_set_ramp_zero_scale_match_lammps() {
        // region half block 0 2 INF INF INF INF (lattice units) -> type 2, group heavy = type 2
        let mut s = setup(FCC, &[1.0, 2.5]);
        let xhalf = 2.0 * s.lattice.as_ref().unwrap().xlattice;
        for i in 0..s.x.len() {
            if s.x[i][0] >= 0.0 && s.x[i][0] <= xhalf {
                s.types[i] = 2;
            }
        }
        let all = vec![true; s.v.len()];
        let heavy: Vec<bool> = s.types.iter().map(|&t| t == 2).collect();
        s.run("velocity all set 0.1 NULL -0.2 units box", &all, 1.0);
        s.run("velocity heavy create 0.5 111 sum yes mom yes loop geom", &heavy, 1.0);
        s.run("velocity all ramp vy -1 1 x 0 4", &all, 1.0);
        s.run("velocity heavy zero angular", &heavy, 1.0);
        s.run("velocity all scale 2.0", &all, 1.0);
        check(
            &s,
            0xbfe4171991957c5a,
            [-0.5857128857110735, -2.2537155593198785, 0.7110136996741213],
            [0.15243948677511895, 1.2801839070189693, -0.3048789735502379],
        );
    }

    const SQ: &str = "units lj\ndimension 2\nboundary p f p\nlattice sq 0.8 origin 0.5 0.5 0
        region box block 0 10 0 8 -0.5 0.5\ncreate_box 1 box\ncreate_atoms 1 box";

    #[test]
    fn create_2d_geom_rot_matches_lammps() {
        let mut s = setup(SQ, &[1.5]);
        let all = vec![true; s.v.len()];
        s.run("velocity all create 1.0 5551 loop geom rot yes", &all, 1.0);
        check(
            &s,
            0x5bea8349dc97d6e7,
            [0.8423029742173763, -1.25436155884036, 0.0],
            [1.4058164804675557, 0.7722597428932924, 0.0],
        );
    }

    #[test]
    fn create_2d_gaussian_matches_lammps() {
        let mut s = setup(SQ, &[1.5]);
        let all = vec![true; s.v.len()];
        s.run("velocity all create 0.7 5551 dist gaussian", &all, 1.0);
        check(
            &s,
            0xeac767a5a965fb36,
            [0.3472749226454524, -0.10662045532648447, 0.0],
            [-0.1242486516055515, 0.17171814765212431, 0.0],
        );
    }

    #[test]
    fn create_si_2d_rot_uses_principal_axes_like_lammps() {
        // tiny inertia tensor (det < 1e-6): LAMMPS takes the Jacobi path in Group::omega
        let deck = "dimension 2\nunits si\nboundary p f p
            region box block 0 0.001 -3.0000000000000004148e-05 0.0010300000000000000995 -5.000000000000000409e-06 5.000000000000000409e-06 units box
            create_box 2 box
            lattice sq 1e-05 origin 0.5 0.5 0.0
            region fluid block 0 0.0002 0 0.0001 EDGE EDGE units box
            create_atoms 1 region fluid";
        let mut s = setup(deck, &[1e-07, 1e-07]);
        let all = vec![true; s.v.len()];
        // LAMMPS 2025 si units: boltz = 1.3806504e-23 (CODATA 2006), as extract_global reports.
        s.run("velocity all create 300.0 2024 rot yes", &all, 1.3806504e-23);
        check(
            &s,
            0xe677945040be9221,
            [-3.297903715754887e-07, -2.0888165093586095e-07, 0.0],
            [1.8096673489764607e-07, -3.351593491649347e-08, 0.0],
        );
    }

    #[test]
    fn parses_styles_and_keywords() {
        let v = Velocity::from_lammps(&cmd("velocity all create 1.44 87287 loop geom dist gaussian mom no"), 3, None)
            .unwrap();
        assert_eq!(v.style, VelocityStyle::Create { temp: 1.44, seed: 87287 });
        assert!(v.opts.gaussian && !v.opts.mom && v.opts.loop_mode == LoopMode::Geom);
        let e = Velocity::from_lammps(&cmd("velocity all create 1.0 -3"), 3, None).unwrap_err();
        assert!(e.message.contains("seed"));
        let e = Velocity::from_lammps(&cmd("velocity all set 0 0 1"), 2, None).unwrap_err();
        assert!(e.message.contains("2d"));
        let e = Velocity::from_lammps(&cmd("velocity all creat 1 1"), 3, None).unwrap_err();
        assert!(e.help[0].contains("create"), "{:?}", e.help);
    }
}
