//! `fix ID group nvt|npt|nph keyword values ...`: Nose-Hoover chain thermostat and
//! Martyna-Tobias-Klein barostat with velocity-Verlet (LAMMPS' FixNH, same operations and
//! order; on a triclinic box the lengths are barostatted and the tilts follow them, flipping
//! past 0.6 box lengths). A step: the barostat's chain and the thermostat's chain for half a
//! step (velocities scaled), the pressure measured, the box velocity and the velocity scaling by
//! it, the NVE half kick, half the box change, the drift, the other half of the box change;
//! after the forces: the second kick, the velocity scaling, the new temperature and pressure,
//! the box velocity, then the chains' second halves. fix nvt thermostats with the temperature
//! of its group; npt and nph measure the temperature of group all (LAMMPS' `ID_temp all
//! temp`) and the pressure from it and the virial (`ID_press all pressure ID_temp`), and
//! dilate every atom (or a `dilate` group) with the box. Defaults as LAMMPS: chains of 3, one
//! loop, mtk yes, no drag, the box centre fixed. The scalar is the energy of the chains and the
//! barostat.
//!
//! `fix ID group nvt/sllod temp ... [psllod yes|no]`: fix nvt for a box that fix deform
//! changes with `remap v` (NEMD shear and elongation), as LAMMPS 22 Jul 2025's FixNVTSllod:
//! its own temperature is a compute temp/deform (the box's streaming velocity taken away), the
//! chain is 1 long unless `tchain` says otherwise, and where fix nvt scales the thermal
//! velocities the SLLOD step also subtracts dt/2 (h_rate h_inv) v_thermal (p-SLLOD: of the
//! whole velocity).

use super::box_stress::{dilate_box, flip_box, strain_trace, Couple};
use super::thermostat::{run_fraction, GroupTemp};
use super::{Fix, FixCtx, FixHooks};
use crate::models::compute::pressure::{scalar_pressure, tensor_pressure};
use crate::models::compute::temp_bias;
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX_SLLOD: &str = "fix ID group nvt/sllod temp Tstart Tstop Tdamp [psllod yes|no] [tchain N] [tloop N] [drag factor]";
pub const SYNTAX_NVT: &str = "fix ID group nvt temp Tstart Tstop Tdamp [tchain N] [tloop N] [drag factor] [mtk yes|no]";
pub const SYNTAX_NPT: &str = "fix ID group npt temp Tstart Tstop Tdamp iso|aniso|x|y|z Pstart Pstop Pdamp ... [couple none|xyz|xy|yz|xz] [tchain N] [pchain N] [tloop N] [ploop N] [mtk yes|no] [drag f] [dilate all|group-ID] [nreset N] [fixedpoint x y z] [scalexy|scalexz|scaleyz|flip yes|no]";
pub const SYNTAX_NPH: &str = "fix ID group nph iso|aniso|x|y|z Pstart Pstop Pdamp ... [couple none|xyz|xy|yz|xz] [ptemp T] [pchain N] [ploop N] [mtk yes|no] [drag f] [dilate all|group-ID] [nreset N] [fixedpoint x y z] [scalexy|scalexz|scaleyz|flip yes|no]";

/// How the box lengths move: together (ISO: `iso`, `couple xyz`, or `couple xy` in 2D) or each
/// on its own (ANISO). LAMMPS' third style (tilts, on a triclinic box) is not supported yet.
#[derive(Clone, Copy, Debug, PartialEq)]
enum PStyle {
    Iso,
    Aniso,
    /// A tilt is barostatted too (6 degrees of freedom).
    Triclinic,
}

/// A Nose-Hoover chain of `m` links (the velocity array has one extra zero link, as LAMMPS').
#[derive(Clone, Debug)]
struct Chain {
    eta: Vec<f64>,
    eta_dot: Vec<f64>,
    eta_dotdot: Vec<f64>,
    eta_mass: Vec<f64>,
}

impl Chain {
    fn new(m: usize) -> Chain {
        Chain { eta: vec![0.0; m], eta_dot: vec![0.0; m + 1], eta_dotdot: vec![0.0; m], eta_mass: vec![0.0; m] }
    }
    fn len(&self) -> usize {
        self.eta.len()
    }
    /// Half a step of the chain (LAMMPS' nhc_temp_integrate and nhc_press_integrate): `nc`
    /// loops, each moving the links from the last to the first, scaling the driven velocities
    /// by exp(-dt/2 eta_dot_1) through `scale` (which returns their kinetic energy after), and
    /// moving the links back. `ke`: the driven kinetic energy now, `target` its target, `kt`
    /// the other links' target, `drag` the drag factor.
    fn half_step(&mut self, dt: f64, nc: i64, drag: f64, ke: f64, target: f64, kt: f64, mut scale: impl FnMut(f64) -> Result<f64, RunError>) -> Result<(), RunError> {
        let (dthalf, dt4, dt8) = (0.5 * dt, 0.25 * dt, 0.125 * dt);
        let m = self.len();
        let first_force = |c: &Chain, ke: f64| if c.eta_mass[0] > 0.0 { (ke - target) / c.eta_mass[0] } else { 0.0 };
        self.eta_dotdot[0] = first_force(self, ke);
        let ncfac = 1.0 / nc as f64;
        for _ in 0..nc {
            for ich in (1..m).rev() {
                let expfac = (-ncfac * dt8 * self.eta_dot[ich + 1]).exp();
                self.eta_dot[ich] *= expfac;
                self.eta_dot[ich] += self.eta_dotdot[ich] * ncfac * dt4;
                self.eta_dot[ich] *= drag;
                self.eta_dot[ich] *= expfac;
            }
            let expfac = (-ncfac * dt8 * self.eta_dot[1]).exp();
            self.eta_dot[0] *= expfac;
            self.eta_dot[0] += self.eta_dotdot[0] * ncfac * dt4;
            self.eta_dot[0] *= drag;
            self.eta_dot[0] *= expfac;

            let ke = scale((-ncfac * dthalf * self.eta_dot[0]).exp())?;
            self.eta_dotdot[0] = first_force(self, ke);
            for ich in 0..m {
                self.eta[ich] += ncfac * dthalf * self.eta_dot[ich];
            }

            self.eta_dot[0] *= expfac;
            self.eta_dot[0] += self.eta_dotdot[0] * ncfac * dt4;
            self.eta_dot[0] *= expfac;
            for ich in 1..m {
                let expfac = (-ncfac * dt8 * self.eta_dot[ich + 1]).exp();
                self.eta_dot[ich] *= expfac;
                self.eta_dotdot[ich] = (self.eta_mass[ich - 1] * self.eta_dot[ich - 1] * self.eta_dot[ich - 1] - kt) / self.eta_mass[ich];
                self.eta_dot[ich] += self.eta_dotdot[ich] * ncfac * dt4;
                self.eta_dot[ich] *= expfac;
            }
        }
        Ok(())
    }
    /// The forces on links 2.. at the start of a run, from the link before each.
    fn set_link_forces(&mut self, kt: f64) {
        for ich in 1..self.len() {
            self.eta_dotdot[ich] = (self.eta_mass[ich - 1] * self.eta_dot[ich - 1] * self.eta_dot[ich - 1] - kt) / self.eta_mass[ich];
        }
    }
}

/// The barostat: box velocities, their masses and chain, and the reference box.
#[derive(Clone, Debug)]
struct Barostat {
    pstyle: PStyle,
    pcouple: Couple,
    p_start: [f64; 3],
    p_stop: [f64; 3],
    p_freq: [f64; 3],
    p_flag: [bool; 3],
    deviatoric: bool,
    nc_pchain: i64,
    mtk: bool,
    /// None: every atom dilates with the box; Some(bit): the atoms of that group.
    dilate: Option<u32>,
    nreset_h0: i64,
    fixedpoint: [f64; 3],
    /// Whether the tilts yz, xz, xy scale with the box (scaleyz, scalexz, scalexy).
    tilt_scale: [bool; 3],
    /// The tilts' own barostat (`tri`, `xy`, `xz`, `yz`).
    shear: Option<TiltBaro>,
    /// Whether a tilt past half a box length (and DELTAFLIP) flips at a rebuild.
    flips: bool,
    p_temp: Option<f64>,
    chain: Chain,
    // state
    p_target: [f64; 3],
    p_hydro: f64,
    p_current: [f64; 3],
    /// The temperature compute's kinetic tensor at the last measurement (LAMMPS'
    /// temperature->vector, read by the MTK term of ANISO).
    mvv_current: [f64; 6],
    omega: [f64; 3],
    omega_dot: [f64; 3],
    omega_mass: [f64; 3],
    /// The reference temperature of the masses (LAMMPS' t0; 0 until the first setup).
    t0: f64,
    /// The reference volume and inverse box (0: until the first run).
    vol0: f64,
    h0_inv: [f64; 6],
    sigma: [f64; 6],
    fdev: [f64; 6],
    mtk_term1: f64,
    mtk_term2: f64,
    pdrag_factor: f64,
    p_freq_max: f64,
    pdim: usize,
}

/// The barostat of a triclinic box's tilts, index 0 yz, 1 xz, 2 xy (LAMMPS' Voigt 3, 4, 5):
/// the off-diagonal pressures' targets, box velocities and masses.
#[derive(Clone, Debug, Default)]
struct TiltBaro {
    p_start: [f64; 3],
    p_stop: [f64; 3],
    p_freq: [f64; 3],
    p_flag: [bool; 3],
    p_target: [f64; 3],
    p_current: [f64; 3],
    omega: [f64; 3],
    omega_dot: [f64; 3],
    omega_mass: [f64; 3],
}

impl TiltBaro {
    /// sum m omega_dot^2 over the barostatted tilts.
    fn kinetic(&self, omega_dot: &[f64; 3]) -> f64 {
        (0..3).filter(|&j| self.p_flag[j]).fold(0.0, |ke, j| ke + self.omega_mass[j] * omega_dot[j] * omega_dot[j])
    }
    fn count(&self) -> usize {
        self.p_flag.iter().filter(|&&f| f).count()
    }
    /// LAMMPS' off-diagonal half of remap (h_dot = omega_dot h, upper triangular, in the order
    /// xz, yz, xy, xz that keeps it time-symmetric), on `h` = [lx ly lz yz xz xy] with the box's
    /// old lengths; `omega_dot0` the diagonal box velocities.
    fn half_shear(&self, h: &mut [f64; 6], omega_dot0: [f64; 3], dto: f64) {
        let (dto2, dto4, dto8) = (dto / 2.0, dto / 4.0, dto / 8.0);
        let w = &self.omega_dot;
        let xz = |h: &mut [f64; 6]| {
            let expfac = (dto8 * omega_dot0[0]).exp();
            h[4] *= expfac;
            h[4] += dto4 * (w[2] * h[3] + w[1] * h[2]);
            h[4] *= expfac;
        };
        if self.p_flag[1] {
            xz(h);
        }
        if self.p_flag[0] {
            let expfac = (dto4 * omega_dot0[1]).exp();
            h[3] *= expfac;
            h[3] += dto2 * (w[0] * h[2]);
            h[3] *= expfac;
        }
        if self.p_flag[2] {
            let expfac = (dto4 * omega_dot0[0]).exp();
            h[5] *= expfac;
            h[5] += dto2 * (w[2] * h[1]);
            h[5] *= expfac;
        }
        if self.p_flag[1] {
            xz(h);
        }
    }
}

pub struct FixNh {
    id: String,
    groupbit: u32,
    style: &'static str,
    dimension: usize,
    /// Thermostat: (Tstart, Tstop, 1/Tdamp); None for nph.
    tstat: Option<(f64, f64, f64)>,
    mtchain: usize,
    nc_tchain: i64,
    drag: f64,
    temp: GroupTemp,
    chain: Chain,
    t_target: f64,
    ke_target: f64,
    t_current: f64,
    tdof: f64,
    tdrag_factor: f64,
    baro: Option<Barostat>,
    /// fix nvt/sllod: Some(psllod).
    sllod: Option<bool>,
}

const BAROSTAT_KEYS: [&str; 19] = ["iso", "aniso", "tri", "x", "y", "z", "xy", "yz", "xz", "couple", "dilate", "pchain", "ploop", "nreset", "fixedpoint", "ptemp", "scalexy", "scalexz", "scaleyz"];

impl FixNh {
    pub fn from_lammps(id: String, groupbit: u32, style: &Word, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let (style, syntax) = match style.text.as_str() {
            "npt" => ("npt", SYNTAX_NPT),
            "nph" => ("nph", SYNTAX_NPH),
            "nvt/sllod" => ("nvt/sllod", SYNTAX_SLLOD),
            _ => ("nvt", SYNTAX_NVT),
        };
        let is_sllod = style == "nvt/sllod";
        let mut psllod = false;
        let mut tchain_given = false;
        let mut a = Args::from_words(args, cmd.span, syntax);
        let dimension = state.dimension;
        let mut tstat: Option<(f64, f64, f64)> = None;
        let (mut mtchain, mut mpchain, mut nc_tchain, mut nc_pchain, mut drag, mut mtk) = (3usize, 3usize, 1i64, 1i64, 0.0, true);
        let mut pcouple = Couple::None;
        let (mut p_start, mut p_stop, mut p_period, mut p_flag) = ([0.0; 3], [0.0; 3], [0.0; 3], [false; 3]);
        let mut deviatoric = false;
        let mut dilate = None;
        let mut nreset_h0 = 0;
        let mut p_temp = None;
        // yz, xz, xy: LAMMPS scales a tilt with its box length when it is not 0 and the length's
        // dimension is periodic
        let now = state.domain().map_err(|m| a.error_command(format!("fix {style}: {m}"), "no box"))?;
        let [xy0, xz0, yz0] = now.tilts();
        let mut scale = [now.periodic(2) && dimension == 3 && yz0 != 0.0, now.periodic(2) && dimension == 3 && xz0 != 0.0, now.periodic(1) && xy0 != 0.0];
        let mut flip = true;
        // the tilts' barostat: yz, xz, xy
        let (mut t_start, mut t_stop, mut t_period, mut t_flag) = ([0.0; 3], [0.0; 3], [0.0; 3], [false; 3]);
        let mut fixedpoint = None;
        let mut first_pressure: Option<&Word> = None;
        if a.is_empty() {
            return Err(a.missing(if style == "nph" { "a pressure keyword (iso, aniso, x, y, z)" } else { "the keyword `temp`" }));
        }
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "temp" => {
                    let t0w = a.peek();
                    let t0 = a.f64("Tstart")?;
                    let t1 = a.f64("Tstop")?;
                    if t0 <= 0.0 || t1 <= 0.0 {
                        return Err(a.error_at(t0w.unwrap_or(w), format!("target temperature for fix {style} must be > 0.0"), "Tstart and Tstop must be positive"));
                    }
                    let period = a.positive_f64("Tdamp")?;
                    tstat = Some((t0, t1, 1.0 / period));
                }
                k @ ("iso" | "aniso") => {
                    let (p0, p1, period) = (a.f64("Pstart")?, a.f64("Pstop")?, a.positive_f64("Pdamp")?);
                    pcouple = if k == "iso" { Couple::Xyz } else { Couple::None };
                    let n = if dimension == 2 { 2 } else { 3 };
                    p_start = [p0, p0, if n == 3 { p0 } else { 0.0 }];
                    p_stop = [p1, p1, if n == 3 { p1 } else { 0.0 }];
                    p_period = [period, period, if n == 3 { period } else { 0.0 }];
                    p_flag = [true, true, n == 3];
                    first_pressure.get_or_insert(w);
                }
                k @ ("x" | "y" | "z") => {
                    let c = ["x", "y", "z"].iter().position(|s| *s == k).unwrap_or(0);
                    if dimension == 2 && c == 2 {
                        return Err(a.error_at(w, format!("invalid fix {style} command for a 2d simulation: z"), "3d only"));
                    }
                    p_start[c] = a.f64("Pstart")?;
                    p_stop[c] = a.f64("Pstop")?;
                    p_period[c] = a.positive_f64("Pdamp")?;
                    p_flag[c] = true;
                    deviatoric = true;
                    first_pressure.get_or_insert(w);
                }
                "tri" => {
                    let (p0, p1, period) = (a.f64("Pstart")?, a.f64("Pstop")?, a.positive_f64("Pdamp")?);
                    pcouple = Couple::None;
                    scale = [false; 3];
                    let n = if dimension == 2 { 2 } else { 3 };
                    p_start = [p0, p0, if n == 3 { p0 } else { 0.0 }];
                    p_stop = [p1, p1, if n == 3 { p1 } else { 0.0 }];
                    p_period = [period, period, if n == 3 { period } else { 0.0 }];
                    p_flag = [true, true, n == 3];
                    // the tilts' targets are 0; in 2d only xy
                    for j in 0..3 {
                        let on = dimension == 3 || j == 2;
                        (t_start[j], t_stop[j], t_period[j], t_flag[j]) = (0.0, 0.0, if on { period } else { 0.0 }, on);
                    }
                    first_pressure.get_or_insert(w);
                }
                k @ ("xy" | "xz" | "yz") => {
                    let j = ["yz", "xz", "xy"].iter().position(|s| *s == k).unwrap_or(0);
                    if dimension == 2 && j < 2 {
                        return Err(a.error_at(w, format!("invalid fix {style} command for a 2d simulation: {k}"), "3d only"));
                    }
                    t_start[j] = a.f64("Pstart")?;
                    t_stop[j] = a.f64("Pstop")?;
                    t_period[j] = a.positive_f64("Pdamp")?;
                    t_flag[j] = true;
                    scale[j] = false;
                    deviatoric = true;
                    first_pressure.get_or_insert(w);
                }
                "couple" => {
                    pcouple = Couple::parse(&mut a)?;
                }
                "drag" => drag = a.non_negative_f64("drag factor")?,
                "ptemp" => p_temp = Some(a.positive_f64("ptemp")?),
                "dilate" => {
                    let g = a.word("dilate group (all or a group ID)")?;
                    if g.text != "all" {
                        dilate = Some(state.groups.bit(&g.text).ok_or_else(|| a.error_at(g, format!("fix {style} dilate group ID {} does not exist", g.text), "all or an existing group"))?);
                    } else {
                        dilate = None;
                    }
                }
                "tchain" => {
                    mtchain = a.i64_in("tchain (chain length)", 1, 10_000)? as usize;
                    tchain_given = true;
                }
                "psllod" if is_sllod => psllod = a.logical("psllod")?,
                "pchain" => mpchain = a.i64_in("pchain (chain length)", 0, 10_000)? as usize,
                // LAMMPS takes any count; a bound keeps a typo from hanging the run
                "tloop" => nc_tchain = a.i64_in("tloop (sub-cycles)", 0, 10_000)?,
                "ploop" => nc_pchain = a.i64_in("ploop (sub-cycles)", 0, 10_000)?,
                "mtk" => mtk = a.logical("mtk")?,
                "nreset" => nreset_h0 = a.i64_in("nreset", 0, i32::MAX as i64)?,
                k @ ("scaleyz" | "scalexz" | "scalexy") => {
                    let c = ["scaleyz", "scalexz", "scalexy"].iter().position(|s| *s == k).unwrap_or(0);
                    scale[c] = a.logical(k)?;
                }
                // box flips happen to tilted boxes only
                "flip" => flip = a.logical("flip")?,
                // read by fix nvt/sphere and nph/sphere; the point-particle styles ignore it
                "disc" => {}
                "fixedpoint" => fixedpoint = Some([a.f64("fixedpoint x")?, a.f64("fixedpoint y")?, a.f64("fixedpoint z")?]),
                "update" => return Err(a.error_at(w, format!("fix {style} update dipole: dmhs' atoms carry no dipoles"), "not supported")),
                _ => return Err(a.unknown_keyword(w, &["temp", "iso", "aniso", "x", "y", "z", "couple", "drag", "ptemp", "dilate", "tchain", "pchain", "tloop", "ploop", "mtk", "nreset", "scalexy", "scalexz", "scaleyz", "flip", "fixedpoint", "disc"])),
            }
        }
        let bad = |m: String| a.error_command(m, format!("fix {style}"));
        let pstat = p_flag.iter().any(|&f| f) || t_flag.iter().any(|&f| f);
        match style {
            "nvt" | "nvt/sllod" if tstat.is_none() => return Err(a.error_at(&args[0], format!("fix {style} needs temperature control: `temp Tstart Tstop Tdamp`"), "no `temp` keyword")),
            "nvt" | "nvt/sllod" if pstat => {
                let hint = if is_sllod { "" } else { " (use fix npt)" };
                return Err(a.error_at(first_pressure.unwrap_or(&args[0]), format!("pressure control cannot be used with fix {style}{hint}"), format!("not with fix {style}")));
            }
            "npt" if tstat.is_none() => return Err(bad("temperature control must be used with fix npt: `temp Tstart Tstop Tdamp`".into())),
            "npt" | "nph" if !pstat => return Err(bad(format!("pressure control must be used with fix {style}: iso, aniso, x, y or z"))),
            "nph" if tstat.is_some() => return Err(bad("temperature control cannot be used with fix nph (use fix npt)".into())),
            _ => {}
        }
        if style == "nvt" || is_sllod {
            if let Some(w) = args.iter().find(|w| BAROSTAT_KEYS.contains(&w.text.as_str()) && w.text != "x" && w.text != "y" && w.text != "z") {
                let hint = if is_sllod { "" } else { " (use fix npt)" };
                return Err(a.error_at(w, format!("`{}` is a barostat keyword; fix {style} has no barostat{hint}", w.text), format!("not with fix {style}")));
            }
        }
        // LAMMPS' FixNVTSllod: a chain of 1 unless tchain is given
        if is_sllod && !tchain_given {
            mtchain = 1;
        }
        if tstat.is_some() && p_temp.is_some() {
            return Err(bad(format!("thermostat in fix {style} is incompatible with the ptemp keyword")));
        }
        let d = now;
        if dimension == 2 && pcouple.needs_3d() {
            return Err(bad(format!("invalid fix {style} command for a 2d simulation: couple yz or xz")));
        }
        if dimension == 2 && (scale[0] || scale[1]) {
            return Err(bad(format!("invalid fix {style} command for a 2d simulation: scaleyz or scalexz")));
        }
        let missing = pcouple.lacks_target(&p_flag, dimension);
        if missing {
            return Err(bad(format!("invalid fix {style} command pressure settings: a coupled dimension has no pressure target")));
        }
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            if p_flag[k] && !d.periodic(k) {
                return Err(bad(format!("cannot use fix {style} on a non-periodic dimension ({axis})")));
            }
        }
        for (c, (name, dim)) in [("yz", 2), ("xz", 2), ("xy", 1)].iter().enumerate() {
            if scale[c] && !d.periodic(*dim) {
                return Err(bad(format!("cannot use fix {style} with {name} scaling when {} is a non-periodic dimension", ["x", "y", "z"][*dim])));
            }
            if t_flag[c] && !d.periodic(*dim) {
                return Err(bad(format!("cannot use fix {style} on a 2nd non-periodic dimension ({name} needs {} periodic)", ["x", "y", "z"][*dim])));
            }
            if t_flag[c] && scale[c] {
                return Err(bad(format!("cannot use fix {style} with both {name} dynamics and {name} scaling")));
            }
        }
        if t_flag.iter().any(|&f| f) && !d.triclinic() {
            return Err(bad(format!("can not specify Pxy/Pxz/Pyz in fix {style} with non-triclinic box")).with_help("make the box triclinic first: change_box all triclinic"));
        }
        let same = |i: usize, j: usize| p_start[i] == p_start[j] && p_stop[i] == p_stop[j] && p_period[i] == p_period[j];
        let mismatch = pcouple.mismatch(dimension, same);
        if mismatch {
            return Err(bad(format!("invalid fix {style} pressure settings: the coupled dimensions need the same Pstart, Pstop and Pdamp")));
        }
        let shear = t_flag.iter().any(|&f| f).then(|| TiltBaro {
            p_start: t_start,
            p_stop: t_stop,
            p_freq: [0, 1, 2].map(|j| if t_flag[j] { 1.0 / t_period[j] } else { 0.0 }),
            p_flag: t_flag,
            ..TiltBaro::default()
        });
        let baro = pstat.then(|| {
            let pstyle = if shear.is_some() {
                PStyle::Triclinic
            } else if pcouple == Couple::Xyz || (dimension == 2 && pcouple == Couple::Xy) {
                PStyle::Iso
            } else {
                PStyle::Aniso
            };
            let p_freq = [0, 1, 2].map(|k| if p_flag[k] { 1.0 / p_period[k] } else { 0.0 });
            Barostat {
                pstyle,
                pcouple,
                p_start,
                p_stop,
                p_freq,
                p_flag,
                deviatoric,
                nc_pchain,
                mtk,
                dilate,
                nreset_h0,
                fixedpoint: fixedpoint.unwrap_or([0.5 * (d.lo[0] + d.hi[0]), 0.5 * (d.lo[1] + d.hi[1]), 0.5 * (d.lo[2] + d.hi[2])]),
                tilt_scale: scale,
                // LAMMPS flips a box whose tilts it changes or that was tilted when the fix
                // was defined
                flips: flip && (shear.is_some() || xy0 != 0.0 || xz0 != 0.0 || yz0 != 0.0),
                shear,
                p_temp,
                chain: Chain::new(mpchain),
                p_target: [0.0; 3],
                p_hydro: 0.0,
                p_current: [0.0; 3],
                mvv_current: [0.0; 6],
                omega: [0.0; 3],
                omega_dot: [0.0; 3],
                omega_mass: [0.0; 3],
                t0: 0.0,
                vol0: 0.0,
                h0_inv: [0.0; 6],
                sigma: [0.0; 6],
                fdev: [0.0; 6],
                mtk_term1: 0.0,
                mtk_term2: 0.0,
                pdrag_factor: 1.0,
                p_freq_max: 0.0,
                pdim: p_flag.iter().filter(|&&f| f).count(),
            }
        });
        // nvt: the temperature of its group; npt, nph: of group all (their compute ID_temp);
        // nvt/sllod: temp/deform of its group
        let temp_group = if style == "nvt" || is_sllod { groupbit } else { 1 };
        let mut temp = GroupTemp::new(temp_group);
        if is_sllod {
            temp.spec.bias = temp_bias::Bias::Deform;
        }
        Ok(FixNh {
            id,
            groupbit,
            style,
            dimension,
            tstat,
            mtchain,
            nc_tchain,
            drag,
            temp,
            chain: Chain::new(if tstat.is_some() { mtchain } else { 0 }),
            t_target: 0.0,
            ke_target: 0.0,
            t_current: 0.0,
            tdof: 0.0,
            tdrag_factor: 1.0,
            baro,
            sllod: is_sllod.then_some(psllod),
        })
    }

    fn t_freq(&self) -> f64 {
        self.tstat.map_or(0.0, |t| t.2)
    }

    fn compute_temp_target(&mut self, state: &State) {
        if let Some((t_start, t_stop, _)) = self.tstat {
            let delta = run_fraction(state);
            self.t_target = t_start + delta * (t_stop - t_start);
            self.ke_target = self.tdof * state.units.boltz * self.t_target;
        }
    }

    /// Half step of the thermostat's chain; scales the group's velocities (LAMMPS'
    /// nhc_temp_integrate). The chain's masses follow the target, so it keeps its frequency.
    fn nhc_temp_integrate(&mut self, state: &mut State) -> Result<(), RunError> {
        let boltz = state.units.boltz;
        let t_freq = self.t_freq();
        let (t_target, tdof, groupbit) = (self.t_target, self.tdof, self.groupbit);
        let c = &mut self.chain;
        c.eta_mass[0] = tdof * boltz * t_target / (t_freq * t_freq);
        for ich in 1..c.len() {
            c.eta_mass[ich] = boltz * t_target / (t_freq * t_freq);
        }
        let ke = tdof * boltz * self.t_current;
        let (temp, t_current, sllod) = (&mut self.temp, &mut self.t_current, self.sllod);
        c.half_step(state.dt, self.nc_tchain, self.tdrag_factor, ke, self.ke_target, boltz * t_target, |factor| {
            match sllod {
                Some(psllod) => sllod_v_temp(temp, state, groupbit, factor, psllod)?,
                None => temp.scale(state, groupbit, factor)?,
            }
            // the temperature scales with the velocities; LAMMPS does not recompute it
            *t_current *= factor * factor;
            Ok(tdof * boltz * *t_current)
        })
    }

    /// v += dtf/m f for the group (LAMMPS' nve_v).
    fn nve_v(&self, state: &mut State) {
        let dtf = 0.5 * state.dt * state.units.ftm2v;
        let per_atom = state.atoms.features.per_atom_mass();
        let type_mass = &state.type_mass;
        let a = &mut state.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit != 0 {
                let m = if per_atom { a.rmass[i] } else { type_mass[a.typ[i]] };
                super::kick(&mut a.v[i], dtf / m, &a.f[i]);
            }
        }
    }

    /// x += dt v for the group (LAMMPS' nve_x).
    fn nve_x(&self, state: &mut State) {
        let dtv = state.dt;
        let a = &mut state.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit != 0 {
                super::drift(&mut a.x[i], dtv, &a.v[i]);
            }
        }
    }

    /// The pressure of group all's temperature and the virial (LAMMPS' compute pressure: the
    /// scalar for ISO, the tensor otherwise), coupled as `couple` says.
    fn measure_pressure(&mut self, state: &State, ctx: &mut FixCtx) -> Result<(), RunError> {
        let virial = ctx.eval(state, &*self, |w, _| Ok(w.virial()))?;
        let volume = self.volume(state)?;
        let (boltz, nktv2p) = (state.units.boltz, state.units.nktv2p);
        let Some(pstyle) = self.baro.as_ref().map(|b| b.pstyle) else { return Ok(()) };
        if pstyle == PStyle::Iso {
            let t = self.temp.compute(state)?;
            let p = scalar_pressure(self.dimension, self.temp.dof * boltz * t, &virial, volume, nktv2p);
            let b = self.baro.as_mut().expect("a barostat");
            b.p_current = [p; 3];
        } else {
            let ke = self.temp.spec.tensor(state).map_err(|e| RunError::new(state.step, e))?;
            let t = tensor_pressure(&ke, &virial, volume, nktv2p);
            let b = self.baro.as_mut().expect("a barostat");
            b.mvv_current = ke;
            b.p_current = b.pcouple.apply([t[0], t[1], t[2]]);
            // LAMMPS' couple(): the tensor's xy xz yz to Voigt yz xz xy
            if let Some(s) = b.shear.as_mut() {
                s.p_current = [t[5], t[4], t[3]];
            }
        }
        let b = self.baro.as_ref().expect("a barostat");
        if b.p_current.iter().chain(b.shear.iter().flat_map(|s| s.p_current.iter())).any(|p| !p.is_finite()) {
            return Err(RunError::new(state.step, format!("fix {} {}: non-numeric pressure - simulation unstable", self.style, self.id)));
        }
        Ok(())
    }

    /// Velocities scaled by the box velocity, twice by exp(-dt/4 (omega_dot + mtk_term2))
    /// (LAMMPS' nh_v_press), the temperature compute's bias removed around it.
    fn nh_v_press(&self, state: &mut State) -> Result<(), RunError> {
        let b = self.baro.as_ref().expect("a barostat");
        let dt4 = 0.25 * state.dt;
        let factor = [0, 1, 2].map(|k| (-dt4 * (b.omega_dot[k] + b.mtk_term2)).exp());
        let dthalf = 0.5 * state.dt;
        let shear = b.shear.as_ref().map(|s| s.omega_dot);
        let bias = self.temp.spec.field(state, self.groupbit).map_err(|e| RunError::new(state.step, e))?;
        let a = &mut state.atoms;
        let n = a.nlocal;
        if let Some(bias) = &bias {
            temp_bias::remove(&mut a.v[..n], &a.mask[..n], self.groupbit, bias);
        }
        for (v, _) in a.v[..n].iter_mut().zip(&a.mask[..n]).filter(|(_, &m)| m & self.groupbit != 0) {
            for k in 0..3 {
                v[k] *= factor[k];
            }
            // the tilts' box velocities (yz, xz, xy) shear the velocities between the scalings
            if let Some(w) = shear {
                v[0] += -dthalf * (v[1] * w[2] + v[2] * w[1]);
                v[1] += -dthalf * v[2] * w[0];
            }
            for k in 0..3 {
                v[k] *= factor[k];
            }
        }
        if let Some(bias) = &bias {
            temp_bias::restore(&mut a.v[..n], &a.mask[..n], self.groupbit, bias);
        }
        Ok(())
    }

    /// Half a step of the box: each barostatted length scaled by exp(dt/2 omega_dot) about the
    /// fixed point, the atoms (all, or the dilate group's) with it in box fractions (LAMMPS'
    /// remap).
    fn remap(&mut self, state: &mut State) -> Result<(), RunError> {
        let dto = 0.5 * state.dt;
        let b = self.baro.as_mut().expect("a barostat");
        for k in 0..3 {
            b.omega[k] += dto * b.omega_dot[k];
        }
        if let Some(t) = b.shear.as_mut() {
            for j in 0..3 {
                t.omega[j] += dto * t.omega_dot[j];
            }
        }
        let scale = std::array::from_fn(|k| b.p_flag[k].then(|| (b.fixedpoint[k], (dto * b.omega_dot[k]).exp())));
        let omega_dot0 = b.omega_dot;
        let half = b.shear.as_ref().map(|t| move |h: &mut [f64; 6]| t.half_shear(h, omega_dot0, dto));
        dilate_box(state, scale, Some(b.tilt_scale), half.as_ref().map(|f| f as &dyn Fn(&mut [f64; 6])), b.dilate).map_err(|e| RunError::new(state.step, format!("fix {} {}: {e}", self.style, self.id)))?;
        Ok(())
    }

    /// Half step of the barostat's chain; scales the box velocities (LAMMPS'
    /// nhc_press_integrate). Its first link's target is kT, or kT per length under ANISO.
    fn nhc_press_integrate(&mut self, state: &State) -> Result<(), RunError> {
        let kt = state.units.boltz * self.t_target;
        let b = self.baro.as_mut().expect("a barostat");
        let pdof = b.pdim + b.shear.as_ref().map_or(0, |s| s.count());
        let target = if b.pstyle == PStyle::Iso { kt } else { pdof as f64 * kt };
        let (p_flag, omega_mass) = (b.p_flag, b.omega_mass);
        let kinetic = |omega_dot: &[f64; 3]| (0..3).filter(|&i| p_flag[i]).fold(0.0, |ke, i| ke + omega_mass[i] * omega_dot[i] * omega_dot[i]);
        let shear = b.shear.clone();
        let mut tilt_dot = shear.as_ref().map_or([0.0; 3], |s| s.omega_dot);
        let ke = kinetic(&b.omega_dot) + shear.as_ref().map_or(0.0, |s| s.kinetic(&tilt_dot));
        let omega_dot = &mut b.omega_dot;
        b.chain.half_step(state.dt, b.nc_pchain, b.pdrag_factor, ke, target, kt, |factor| {
            for i in 0..3 {
                if p_flag[i] {
                    omega_dot[i] *= factor;
                }
            }
            if let Some(s) = &shear {
                for j in (0..3).filter(|&j| s.p_flag[j]) {
                    tilt_dot[j] *= factor;
                }
            }
            Ok(kinetic(omega_dot) + shear.as_ref().map_or(0.0, |s| s.kinetic(&tilt_dot)))
        })?;
        if let Some(s) = b.shear.as_mut() {
            s.omega_dot = tilt_dot;
        }
        Ok(())
    }

    /// The targets ramped over the run and their mean; with a deviatoric target, sigma
    /// (LAMMPS' compute_press_target and compute_sigma).
    fn compute_press_target(&mut self, state: &State) -> Result<(), RunError> {
        let delta = run_fraction(state);
        let begin = state.run_window.map_or(state.step, |w| w.0);
        let volume = self.volume(state)?;
        let h_inv = state.domain().map_err(|e| RunError::new(state.step, e))?.h_inv();
        let b = self.baro.as_mut().expect("a barostat");
        b.p_hydro = 0.0;
        for i in 0..3 {
            if b.p_flag[i] {
                b.p_target[i] = b.p_start[i] + delta * (b.p_stop[i] - b.p_start[i]);
                b.p_hydro += b.p_target[i];
            }
        }
        if b.pdim > 0 {
            b.p_hydro /= b.pdim as f64;
        }
        if let Some(s) = b.shear.as_mut() {
            for j in (0..3).filter(|&j| s.p_flag[j]) {
                s.p_target[j] = s.p_start[j] + delta * (s.p_stop[j] - s.p_start[j]);
            }
        }
        if b.deviatoric {
            if b.nreset_h0 > 0 && (state.step - begin) % b.nreset_h0 == 0 {
                b.vol0 = volume;
                b.h0_inv = h_inv;
            }
            b.compute_sigma();
        }
        Ok(())
    }

    /// Volume in 3D, area in 2D.
    fn volume(&self, state: &State) -> Result<f64, RunError> {
        Ok(state.domain().map_err(|e| RunError::new(state.step, e))?.volume())
    }

    /// Half step of the box velocities from the pressure difference (LAMMPS' nh_omega_dot).
    fn nh_omega_dot(&mut self, state: &State) -> Result<(), RunError> {
        let volume = self.volume(state)?;
        let h = state.domain().map_err(|e| RunError::new(state.step, e))?.h();
        let (boltz, nktv2p, dthalf) = (state.units.boltz, state.units.nktv2p, 0.5 * state.dt);
        let natoms = state.natoms();
        let (tdof, t_current) = (self.tdof, self.t_current);
        let b = self.baro.as_mut().expect("a barostat");
        if b.deviatoric {
            b.compute_deviatoric(&h);
        }
        let nd = (b.pdim * natoms) as f64;
        b.mtk_term1 = 0.0;
        if b.mtk {
            if b.pstyle == PStyle::Iso {
                b.mtk_term1 = tdof * boltz * t_current;
                b.mtk_term1 /= nd;
            } else {
                for i in 0..3 {
                    if b.p_flag[i] {
                        b.mtk_term1 += b.mvv_current[i];
                    }
                }
                b.mtk_term1 /= nd;
            }
        }
        for i in 0..3 {
            if b.p_flag[i] {
                let mut f_omega = (b.p_current[i] - b.p_hydro) * volume / (b.omega_mass[i] * nktv2p) + b.mtk_term1 / b.omega_mass[i];
                if b.deviatoric {
                    f_omega -= b.fdev[i] / (b.omega_mass[i] * nktv2p);
                }
                b.omega_dot[i] += f_omega * dthalf;
                b.omega_dot[i] *= b.pdrag_factor;
            }
        }
        b.mtk_term2 = 0.0;
        if b.mtk {
            for i in 0..3 {
                if b.p_flag[i] {
                    b.mtk_term2 += b.omega_dot[i];
                }
            }
            if b.pdim > 0 {
                b.mtk_term2 /= nd;
            }
        }
        let (fdev, deviatoric, pdrag) = (b.fdev, b.deviatoric, b.pdrag_factor);
        if let Some(s) = b.shear.as_mut() {
            for j in (0..3).filter(|&j| s.p_flag[j]) {
                let mut f_omega = s.p_current[j] * volume / (s.omega_mass[j] * nktv2p);
                if deviatoric {
                    f_omega -= fdev[3 + j] / (s.omega_mass[j] * nktv2p);
                }
                s.omega_dot[j] += f_omega * dthalf;
                s.omega_dot[j] *= pdrag;
            }
        }
        Ok(())
    }

    /// The barostat's energy terms (LAMMPS' compute_scalar, pressure part).
    fn barostat_energy(&self, state: &State) -> f64 {
        let Some(b) = &self.baro else { return 0.0 };
        let kt = state.units.boltz * self.t_target;
        let volume = self.volume(state).unwrap_or(f64::NAN);
        let nktv2p = state.units.nktv2p;
        let mut energy = 0.0;
        let mut lkt_press = 0.0;
        for i in 0..3 {
            if b.p_flag[i] {
                energy += 0.5 * b.omega_dot[i] * b.omega_dot[i] * b.omega_mass[i] + b.p_hydro * (volume - b.vol0) / (b.pdim as f64 * nktv2p);
                lkt_press += kt;
            }
        }
        if let Some(s) = &b.shear {
            for j in (0..3).filter(|&j| s.p_flag[j]) {
                energy += 0.5 * s.omega_dot[j] * s.omega_dot[j] * s.omega_mass[j];
                lkt_press += kt;
            }
        }
        let c = &b.chain;
        if c.len() > 0 {
            energy += lkt_press * c.eta[0] + 0.5 * c.eta_mass[0] * c.eta_dot[0] * c.eta_dot[0];
            for ich in 1..c.len() {
                energy += kt * c.eta[ich] + 0.5 * c.eta_mass[ich] * c.eta_dot[ich] * c.eta_dot[ich];
            }
        }
        if b.deviatoric {
            let h = state.domain().map(|d| d.h()).unwrap_or([f64::NAN; 6]);
            energy += b.strain_energy(&h, nktv2p);
        }
        energy
    }

    /// The vector LAMMPS' compute_vector lists: eta, eta_dot, omega, omega_dot, etap,
    /// etap_dot, then the energies of each (PE_eta, KE_eta_dot, PE_omega, KE_omega_dot,
    /// PE_etap, KE_etap_dot, PE_strain).
    fn vector_values(&self, state: &State) -> Vec<f64> {
        let mut out = Vec::new();
        let n_omega = |b: &Barostat| if b.pstyle == PStyle::Iso { 1 } else { 3 };
        if self.tstat.is_some() {
            out.extend_from_slice(&self.chain.eta);
            out.extend_from_slice(&self.chain.eta_dot[..self.mtchain]);
        }
        if let Some(b) = &self.baro {
            // TRICLINIC: six box velocities, the tilts' in Voigt order (yz, xz, xy)
            let tilt = b.shear.as_ref();
            out.extend_from_slice(&b.omega[..n_omega(b)]);
            out.extend(tilt.iter().flat_map(|s| s.omega));
            out.extend_from_slice(&b.omega_dot[..n_omega(b)]);
            out.extend(tilt.iter().flat_map(|s| s.omega_dot));
            out.extend_from_slice(&b.chain.eta);
            out.extend_from_slice(&b.chain.eta_dot[..b.chain.len()]);
        }
        let kt = state.units.boltz * self.t_target;
        let nktv2p = state.units.nktv2p;
        let volume = self.volume(state).unwrap_or(f64::NAN);
        if self.tstat.is_some() {
            let c = &self.chain;
            for ich in 0..c.len() {
                out.push(if ich == 0 { self.ke_target * c.eta[0] } else { kt * c.eta[ich] });
            }
            for ich in 0..c.len() {
                out.push(0.5 * c.eta_mass[ich] * c.eta_dot[ich] * c.eta_dot[ich]);
            }
        }
        if let Some(b) = &self.baro {
            let pdim = b.pdim as f64;
            if b.pstyle == PStyle::Iso {
                out.push(b.p_hydro * (volume - b.vol0) / nktv2p);
                out.push(pdim * 0.5 * b.omega_dot[0] * b.omega_dot[0] * b.omega_mass[0]);
            } else {
                for i in 0..3 {
                    out.push(if b.p_flag[i] { b.p_hydro * (volume - b.vol0) / (pdim * nktv2p) } else { 0.0 });
                }
                if b.shear.is_some() {
                    out.extend([0.0; 3]);
                }
                for i in 0..3 {
                    out.push(if b.p_flag[i] { 0.5 * b.omega_dot[i] * b.omega_dot[i] * b.omega_mass[i] } else { 0.0 });
                }
                if let Some(s) = &b.shear {
                    out.extend((0..3).map(|j| if s.p_flag[j] { 0.5 * s.omega_dot[j] * s.omega_dot[j] * s.omega_mass[j] } else { 0.0 }));
                }
            }
            let c = &b.chain;
            for ich in 0..c.len() {
                out.push(kt * c.eta[ich]);
            }
            for ich in 0..c.len() {
                out.push(0.5 * c.eta_mass[ich] * c.eta_dot[ich] * c.eta_dot[ich]);
            }
            if b.deviatoric {
                let h = state.domain().map(|d| d.h()).unwrap_or([f64::NAN; 6]);
                out.push(b.strain_energy(&h, nktv2p));
            }
        }
        out
    }
}

impl Barostat {
    /// sigma = vol0 h0^-1 (P_target - p_hydro) h0^-T, upper triangle in Voigt order (LAMMPS'
    /// compute_sigma; the tilt targets are 0 on an orthogonal box).
    fn compute_sigma(&mut self) {
        let (h, v0) = (&self.h0_inv, self.vol0);
        let ph = self.p_hydro;
        let t = self.shear.as_ref().map_or([0.0; 3], |s| s.p_target);
        let pt = [self.p_target[0], self.p_target[1], self.p_target[2], t[0], t[1], t[2]];
        self.sigma = [
            v0 * (h[0] * ((pt[0] - ph) * h[0] + pt[5] * h[5] + pt[4] * h[4]) + h[5] * (pt[5] * h[0] + (pt[1] - ph) * h[5] + pt[3] * h[4]) + h[4] * (pt[4] * h[0] + pt[3] * h[5] + (pt[2] - ph) * h[4])),
            v0 * (h[1] * ((pt[1] - ph) * h[1] + pt[3] * h[3]) + h[3] * (pt[3] * h[1] + (pt[2] - ph) * h[3])),
            v0 * (h[2] * ((pt[2] - ph) * h[2])),
            v0 * (h[1] * (pt[3] * h[2]) + h[3] * ((pt[2] - ph) * h[2])),
            v0 * (h[0] * (pt[4] * h[2]) + h[5] * (pt[3] * h[2]) + h[4] * ((pt[2] - ph) * h[2])),
            v0 * (h[0] * (pt[5] * h[1] + pt[4] * h[3]) + h[5] * ((pt[1] - ph) * h[1] + pt[3] * h[3]) + h[4] * (pt[3] * h[1] + (pt[2] - ph) * h[3])),
        ];
    }

    /// The deviatoric force h sigma h^T on the box (LAMMPS' compute_deviatoric).
    fn compute_deviatoric(&mut self, h: &[f64; 6]) {
        let s = &self.sigma;
        self.fdev = [
            h[0] * (s[0] * h[0] + s[5] * h[5] + s[4] * h[4]) + h[5] * (s[5] * h[0] + s[1] * h[5] + s[3] * h[4]) + h[4] * (s[4] * h[0] + s[3] * h[5] + s[2] * h[4]),
            h[1] * (s[1] * h[1] + s[3] * h[3]) + h[3] * (s[3] * h[1] + s[2] * h[3]),
            h[2] * (s[2] * h[2]),
            h[1] * (s[3] * h[2]) + h[3] * (s[2] * h[2]),
            h[0] * (s[4] * h[2]) + h[5] * (s[3] * h[2]) + h[4] * (s[2] * h[2]),
            h[0] * (s[5] * h[1] + s[4] * h[3]) + h[5] * (s[1] * h[1] + s[3] * h[3]) + h[4] * (s[3] * h[1] + s[2] * h[3]),
        ];
    }

    /// 0.5 Tr(sigma h h^T) in energy units (LAMMPS' compute_strain_energy).
    fn strain_energy(&self, h: &[f64; 6], nktv2p: f64) -> f64 {
        strain_trace(&self.sigma, h) / nktv2p
    }
}

/// LAMMPS' FixNVTSllod::nh_v_temp: each atom of the group loses its bias (the stream of
/// temp/deform), is scaled by the chain's `factor` less dt/2 (h_rate h_inv) of its thermal
/// velocity (p-SLLOD: of its whole velocity, taken before the bias) and gets its bias back.
fn sllod_v_temp(temp: &GroupTemp, state: &mut State, groupbit: u32, factor: f64, psllod: bool) -> Result<(), RunError> {
    let step = state.step;
    let bias = temp.spec.field(state, groupbit).map_err(|e| RunError::new(step, e))?;
    let d = state.domain().map_err(|e| RunError::new(step, e))?;
    let h_two = crate::engine::domain::shape_product(&d.rate.h_rate, &d.h_inv());
    let dthalf = 0.5 * state.dt;
    let a = &mut state.atoms;
    for i in (0..a.nlocal).filter(|&i| a.mask[i] & groupbit != 0) {
        let b = bias.as_ref().map_or([0.0; 3], |b| b[i]);
        let v = &mut a.v[i];
        let unbias = |v: &mut [f64; 3]| (0..3).for_each(|k| v[k] -= b[k]);
        if !psllod {
            unbias(v);
        }
        let vdelu = [h_two[0] * v[0] + h_two[5] * v[1] + h_two[4] * v[2], h_two[1] * v[1] + h_two[3] * v[2], h_two[2] * v[2]];
        if psllod {
            unbias(v);
        }
        for k in 0..3 {
            v[k] = v[k] * factor - dthalf * vdelu[k];
            v[k] += b[k];
        }
    }
    Ok(())
}

impl Fix for FixNh {
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
        let flips = self.baro.as_ref().is_some_and(|b| b.flips);
        FixHooks { initial_integrate: true, final_integrate: true, pre_exchange: flips, ..FixHooks::default() }
    }
    /// LAMMPS' FixNH::pre_exchange at a rebuild: a tilt past half its box length by DELTAFLIP
    /// (0.1, so that a tilt oscillating about the half does not flip back and forth) flips,
    /// yz first (it moves xz by xy), then xz and xy, each along a periodic dimension.
    fn pre_exchange(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        const DELTAFLIP: f64 = 0.1;
        let d = state.domain().map_err(|e| RunError::new(state.step, e))?;
        let Some([mut xy, mut xz, mut yz]) = d.tilt else { return Ok(()) };
        let prd = d.prd();
        let (xtiltmax, ytiltmax) = ((0.5 + DELTAFLIP) * prd[0], (0.5 + DELTAFLIP) * prd[1]);
        let (mut m, mut n, mut p) = (0, 0, 0);
        if d.periodic(1) {
            if yz < -ytiltmax {
                yz += prd[1];
                xz += xy;
                p = 1;
            } else if yz >= ytiltmax {
                yz -= prd[1];
                xz -= xy;
                p = -1;
            }
        }
        if d.periodic(0) {
            // xz, then xy, each by one x length
            let back = |t: &mut f64, flag: &mut i32| {
                if *t < -xtiltmax {
                    *t += prd[0];
                    *flag = 1;
                } else if *t >= xtiltmax {
                    *t -= prd[0];
                    *flag = -1;
                }
            };
            back(&mut xz, &mut n);
            back(&mut xy, &mut m);
        }
        if m == 0 && n == 0 && p == 0 {
            return Ok(());
        }
        flip_box(state, [xy, xz, yz], [m, n, p]).map_err(|e| RunError::new(state.step, format!("fix {} {}: {e}", self.style, self.id)))
    }
    fn couples_energy(&self) -> bool {
        true
    }
    fn changes_box(&self) -> bool {
        self.baro.is_some()
    }
    /// The barostat reads the virial every step (LAMMPS' pressure->addstep(ntimestep+1)).
    fn wants_energy(&self, _step: i64) -> bool {
        self.baro.is_some()
    }
    fn modify_temp(&mut self, spec: crate::models::compute::temp_bias::TempSpec) -> Result<(), String> {
        self.temp.replace(spec);
        Ok(())
    }
    fn init(&mut self, state: &State, ctx: &FixCtx) -> Result<(), String> {
        self.temp.count_dof(state, ctx);
        if self.sllod.is_some() {
            if self.temp.spec.bias == temp_bias::Bias::None {
                return Err("Temperature for fix nvt/sllod does not have a bias".into());
            }
            match ctx.other_fixes().find(|f| f.style() == "deform") {
                None => return Err("Using fix nvt/sllod with no fix deform defined".into()),
                Some(f) if f.deform_remap() != Some(super::deform::Remap::V) => {
                    return Err(format!("Using fix nvt/sllod with inconsistent fix deform remap option: fix {} must remap v (the velocities of atoms crossing the box)", f.id()));
                }
                Some(_) => {}
            }
        }
        self.tdrag_factor = 1.0 - (state.dt * self.t_freq() * self.drag / self.nc_tchain as f64);
        let (style, drag) = (self.style, self.drag);
        let Some(b) = self.baro.as_mut() else { return Ok(()) };
        if let Some(f) = ctx.other_fixes().find(|f| f.style() == "deform") {
            return Err(format!("fix {style} with fix deform {}: dmhs does not combine a barostat with fix deform", f.id()));
        }
        if let Some(f) = ctx.other_fixes().find(|f| f.rigid_body_mass(state).is_some()) {
            return Err(format!("fix {style} with fix {} ({}): dmhs' barostats do not move rigid bodies with the box", f.id(), f.style()));
        }
        b.p_freq_max = b.p_freq.iter().chain(b.shear.iter().flat_map(|s| s.p_freq.iter())).fold(0.0, |m: f64, &f| m.max(f));
        b.pdrag_factor = 1.0 - (state.dt * b.p_freq_max * drag / b.nc_pchain as f64);
        if b.vol0 == 0.0 {
            let d = state.domain()?;
            b.vol0 = d.volume();
            b.h0_inv = d.h_inv();
        }
        Ok(())
    }
    /// The drag factors depend on dt (LAMMPS' FixNH::reset_dt).
    fn reset_dt(&mut self, state: &State) -> Result<(), String> {
        self.tdrag_factor = 1.0 - (state.dt * self.t_freq() * self.drag / self.nc_tchain as f64);
        if let Some(b) = self.baro.as_mut() {
            b.pdrag_factor = 1.0 - (state.dt * b.p_freq_max * self.drag / b.nc_pchain as f64);
        }
        Ok(())
    }
    fn setup(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.t_current = self.temp.compute(state)?;
        self.tdof = self.temp.dof;
        if self.tstat.is_some() {
            self.compute_temp_target(state);
        } else if let Some(b) = self.baro.as_mut() {
            // the masses' reference temperature: ptemp, or the temperature at the first run
            if b.t0 == 0.0 {
                b.t0 = match b.p_temp {
                    Some(t) => t,
                    None if self.t_current < 1.0e-6 => {
                        return Err(RunError::new(state.step, format!("fix {} {}: current temperature too close to zero, consider using the ptemp keyword", self.style, self.id)));
                    }
                    None => self.t_current,
                };
            }
            self.t_target = b.t0;
        }
        let boltz = state.units.boltz;
        if self.baro.is_some() {
            self.compute_press_target(state)?;
            self.measure_pressure(state, ctx)?;
        }
        if let Some((_, _, t_freq)) = self.tstat {
            let f2 = t_freq * t_freq;
            let c = &mut self.chain;
            c.eta_mass[0] = self.tdof * boltz * self.t_target / f2;
            for ich in 1..c.len() {
                c.eta_mass[ich] = boltz * self.t_target / f2;
            }
            c.set_link_forces(boltz * self.t_target);
        }
        let natoms = state.natoms();
        if let Some(b) = self.baro.as_mut() {
            let kt = boltz * self.t_target;
            let nkt = (natoms + 1) as f64 * kt;
            for i in 0..3 {
                if b.p_flag[i] {
                    b.omega_mass[i] = nkt / (b.p_freq[i] * b.p_freq[i]);
                }
            }
            if let Some(s) = b.shear.as_mut() {
                for j in (0..3).filter(|&j| s.p_flag[j]) {
                    s.omega_mass[j] = nkt / (s.p_freq[j] * s.p_freq[j]);
                }
            }
            let c = &mut b.chain;
            if c.len() > 0 {
                let f2 = b.p_freq_max * b.p_freq_max;
                for ich in 0..c.len() {
                    c.eta_mass[ich] = boltz * self.t_target / f2;
                }
                c.set_link_forces(kt);
            }
        }
        Ok(())
    }
    fn initial_integrate(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if self.baro.as_ref().is_some_and(|b| b.chain.len() > 0) {
            self.nhc_press_integrate(state)?;
        }
        if self.tstat.is_some() {
            self.compute_temp_target(state);
            self.nhc_temp_integrate(state)?;
        }
        // the velocities changed: the pressure again (t_current keeps the chain's scaled value)
        if self.baro.is_some() {
            self.measure_pressure(state, ctx)?;
            self.compute_press_target(state)?;
            self.nh_omega_dot(state)?;
            self.nh_v_press(state)?;
        }
        self.nve_v(state);
        if self.baro.is_some() {
            self.remap(state)?;
        }
        self.nve_x(state);
        if self.baro.is_some() {
            self.remap(state)?;
        }
        Ok(())
    }
    fn final_integrate(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.nve_v(state);
        if self.baro.is_some() {
            self.nh_v_press(state)?;
        }
        self.t_current = self.temp.compute(state)?;
        self.tdof = self.temp.dof;
        if self.baro.is_some() {
            self.measure_pressure(state, ctx)?;
            self.nh_omega_dot(state)?;
        }
        if self.tstat.is_some() {
            self.nhc_temp_integrate(state)?;
        }
        if self.baro.as_ref().is_some_and(|b| b.chain.len() > 0) {
            self.nhc_press_integrate(state)?;
        }
        Ok(())
    }
    /// The chains' and the barostat's energy: L kT eta_1 + sum_k>1 kT eta_k + sum 0.5 Q_k
    /// eta_dot_k^2, plus 0.5 W omega_dot^2 + P (V - V0) per barostatted length, the barostat
    /// chain's terms and the strain energy.
    fn scalar(&self, state: &State) -> Option<f64> {
        let kt = state.units.boltz * self.t_target;
        let mut energy = 0.0;
        if self.tstat.is_some() {
            let c = &self.chain;
            energy += self.ke_target * c.eta[0] + 0.5 * c.eta_mass[0] * c.eta_dot[0] * c.eta_dot[0];
            for ich in 1..c.len() {
                energy += kt * c.eta[ich] + 0.5 * c.eta_mass[ich] * c.eta_dot[ich] * c.eta_dot[ich];
            }
        }
        Some(energy + self.barostat_energy(state))
    }
    fn size_vector(&self) -> usize {
        let t = if self.tstat.is_some() { 4 * self.mtchain } else { 0 };
        let p = self.baro.as_ref().map_or(0, |b| {
            let n = match b.pstyle {
                PStyle::Iso => 1,
                PStyle::Aniso => 3,
                PStyle::Triclinic => 6,
            };
            4 * n + 4 * b.chain.len() + usize::from(b.deviatoric)
        });
        t + p
    }
    fn vector(&self, state: &State, i: usize) -> Option<f64> {
        self.vector_values(state).get(i.checked_sub(1)?).copied()
    }
    fn extensive(&self, index: Option<usize>) -> bool {
        index.is_none()
    }
    /// LAMMPS' FixNH::pack_restart_data: tstat_flag, the chain length, eta, eta_dot;
    /// pstat_flag, omega (6), omega_dot (6), vol0, t0, the barostat chain's length, etap,
    /// etap_dot, deviatoric_flag and h0_inv (6) when set.
    fn write_restart(&self) -> Option<Vec<f64>> {
        let mut list = vec![];
        if self.tstat.is_some() {
            let m = self.mtchain;
            list.extend([1.0, m as f64]);
            list.extend_from_slice(&self.chain.eta[..m]);
            list.extend_from_slice(&self.chain.eta_dot[..m]);
        } else {
            list.push(0.0);
        }
        match &self.baro {
            None => list.push(0.0),
            Some(b) => {
                list.push(1.0);
                let tilt = b.shear.clone().unwrap_or_default();
                list.extend_from_slice(&b.omega);
                list.extend_from_slice(&tilt.omega);
                list.extend_from_slice(&b.omega_dot);
                list.extend_from_slice(&tilt.omega_dot);
                list.extend([b.vol0, b.t0, b.chain.len() as f64]);
                list.extend_from_slice(&b.chain.eta);
                list.extend_from_slice(&b.chain.eta_dot[..b.chain.len()]);
                list.push(if b.deviatoric { 1.0 } else { 0.0 });
                if b.deviatoric {
                    list.extend_from_slice(&b.h0_inv);
                }
            }
        }
        Some(list)
    }
    /// LAMMPS' FixNH::restart: each chain only when its length is this fix's.
    fn restart(&mut self, list: &[f64]) {
        let mut it = list.iter().copied();
        let mut next = || it.next();
        let Some(tflag) = next() else { return };
        if tflag != 0.0 {
            let Some(m) = next() else { return };
            let m = m as usize;
            let values: Vec<f64> = (0..2 * m).filter_map(|_| next()).collect();
            if self.tstat.is_some() && m == self.mtchain && values.len() == 2 * m {
                self.chain.eta[..m].copy_from_slice(&values[..m]);
                self.chain.eta_dot[..m].copy_from_slice(&values[m..]);
            }
        }
        let Some(pflag) = next() else { return };
        if pflag == 0.0 {
            return;
        }
        let head: Vec<f64> = (0..15).filter_map(|_| next()).collect();
        if head.len() < 15 {
            return;
        }
        let m = head[14] as usize;
        let chain: Vec<f64> = (0..2 * m).filter_map(|_| next()).collect();
        let dev = next();
        let h0_inv: Vec<f64> = if dev.is_some_and(|d| d != 0.0) { (0..6).filter_map(|_| next()).collect() } else { vec![] };
        let Some(b) = self.baro.as_mut() else { return };
        b.omega.copy_from_slice(&head[0..3]);
        b.omega_dot.copy_from_slice(&head[6..9]);
        if let Some(s) = b.shear.as_mut() {
            s.omega.copy_from_slice(&head[3..6]);
            s.omega_dot.copy_from_slice(&head[9..12]);
        }
        (b.vol0, b.t0) = (head[12], head[13]);
        if m == b.chain.len() && chain.len() == 2 * m {
            b.chain.eta.copy_from_slice(&chain[..m]);
            b.chain.eta_dot[..m].copy_from_slice(&chain[m..]);
        }
        if h0_inv.len() == 6 {
            b.h0_inv.copy_from_slice(&h0_inv);
        }
    }
}
