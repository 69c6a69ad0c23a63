//! `fix ID group box/relax keyword value ...`: the box lengths (and on a triclinic box the
//! tilts) as extra degrees of freedom of the minimizer, relaxed towards a target pressure or
//! stress (LAMMPS' FixBoxRelax). Its energy is p_target (V - V0) plus, for a non-hydrostatic
//! target, the strain energy 0.5 Tr(sigma h h^T); its forces are the pressure differences
//! times the areas. The box is dilated about `fixedpoint` from the line search's starting box,
//! the tilts set from their starting values (or scaled with their second length), the atoms
//! (all, or the group's with `dilate partial`) with it in box-fraction coordinates.

use super::box_stress::{strain_trace, Couple};
use super::{Fix, FixCtx, FixHooks, MinExtra};
use crate::engine::domain::Dilation;
use crate::engine::state::State;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group box/relax iso|aniso|tri P | x|y|z|xy|xz|yz P ... [couple none|xyz|xy|yz|xz] [dilate all|partial] [vmax V] [nreset N] [scalexy|scalexz|scaleyz yes|no] [fixedpoint x y z]";

/// How the box moves: one length for all (iso), each length on its own (aniso), the lengths
/// and the tilts (triclinic: a tilt has a target).
#[derive(Clone, Copy, Debug, PartialEq)]
enum PStyle {
    Iso,
    Aniso,
    Triclinic,
}

pub struct FixBoxRelax {
    id: String,
    groupbit: u32,
    pstyle: PStyle,
    pcouple: Couple,
    p_target: [f64; 6],
    p_flag: [bool; 6],
    allremap: bool,
    vmax: f64,
    nreset: i64,
    deviatoric: bool,
    fixedpoint: [f64; 3],
    /// yz, xz, xy follow the length of their second dimension (z, z, y).
    scale: [bool; 3],
    dimension: usize,
    // set by init (LAMMPS' init and compute_sigma)
    pv2e: f64,
    prdinit: [f64; 3],
    vol0: f64,
    h0: [f64; 6],
    p_hydro: f64,
    sigma: [f64; 6],
    /// The box where the line search started (LAMMPS' boxlo0/boxhi0 of min_store).
    lo0: [f64; 3],
    hi0: [f64; 3],
    /// yz, xz, xy there (a triclinic relaxation's).
    tilt0: [f64; 3],
}

impl FixBoxRelax {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let d = state.domain().map_err(|m| a.error_command(format!("fix box/relax: {m}"), "no box"))?;
        let dimension = state.dimension;
        if a.is_empty() {
            return Err(a.missing("a pressure keyword (iso, aniso, tri, x, y, z, xy, xz, yz)"));
        }
        let mut pcouple = Couple::None;
        let mut p_target = [0.0; 6];
        let mut p_flag = [false; 6];
        let mut deviatoric = false;
        let (mut allremap, mut vmax, mut nreset) = (true, 0.0001, 0);
        // a tilt scales with its second length when it is not zero and that dimension periodic
        let [xy, xz, yz] = d.tilts();
        let mut scale = [d.periodic(2) && dimension == 3 && yz != 0.0, d.periodic(2) && dimension == 3 && xz != 0.0, d.periodic(1) && xy != 0.0];
        let mut fixedpoint = [0.5 * (d.lo[0] + d.hi[0]), 0.5 * (d.lo[1] + d.hi[1]), 0.5 * (d.lo[2] + d.hi[2])];
        let mut off_diagonal: Option<&Word> = None;
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                k @ ("iso" | "aniso" | "tri") => {
                    let p = a.f64(&format!("{k} pressure"))?;
                    pcouple = if k == "iso" { Couple::Xyz } else { Couple::None };
                    p_target[..3].fill(p);
                    p_flag[..3].fill(true);
                    if k == "tri" {
                        scale = [false; 3];
                        p_target[3..].fill(0.0);
                        p_flag[3..].fill(true);
                        off_diagonal.get_or_insert(w);
                    }
                    if dimension == 2 {
                        p_target[2] = 0.0;
                        p_flag[2] = false;
                        if k == "tri" {
                            p_target[3] = 0.0;
                            p_target[4] = 0.0;
                            p_flag[3] = false;
                            p_flag[4] = false;
                        }
                    }
                }
                k @ ("x" | "y" | "z" | "yz" | "xz" | "xy") => {
                    let c = ["x", "y", "z", "yz", "xz", "xy"].iter().position(|s| *s == k).unwrap_or(0);
                    p_target[c] = a.f64(&format!("{k} stress"))?;
                    p_flag[c] = true;
                    deviatoric = true;
                    if dimension == 2 && matches!(k, "z" | "yz" | "xz") {
                        return Err(a.error_at(w, format!("fix box/relax {k} is not allowed for a 2d simulation"), "3d only"));
                    }
                    if c >= 3 {
                        scale[c - 3] = false;
                        off_diagonal.get_or_insert(w);
                    }
                }
                "couple" => {
                    pcouple = Couple::parse(&mut a)?;
                }
                "dilate" => allremap = a.choice("dilate", &["all", "partial"])? == 0,
                "vmax" => vmax = a.positive_f64("vmax")?,
                "nreset" => nreset = a.i64_in("nreset", 0, i32::MAX as i64)?,
                k @ ("scaleyz" | "scalexz" | "scalexy") => {
                    let c = ["scaleyz", "scalexz", "scalexy"].iter().position(|s| *s == k).unwrap_or(0);
                    scale[c] = a.logical(k)?;
                }
                "fixedpoint" => {
                    for v in fixedpoint.iter_mut() {
                        *v = a.f64("fixedpoint coordinate")?;
                    }
                }
                _ => {
                    return Err(a.unknown_keyword(w, &["iso", "aniso", "tri", "x", "y", "z", "xy", "xz", "yz", "couple", "dilate", "vmax", "nreset", "scalexy", "scalexz", "scaleyz", "fixedpoint"]));
                }
            }
        }
        let bad = |m: &str| a.error_command(m.to_string(), "fix box/relax");
        if dimension == 2 && pcouple.needs_3d() {
            return Err(bad("invalid fix box/relax command for a 2d simulation: couple yz or xz"));
        }
        let pressure_settings = pcouple.lacks_target(&p_flag, dimension);
        if pressure_settings {
            return Err(bad("invalid fix box/relax pressure settings: a coupled dimension has no target"));
        }
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            if p_flag[k] && !d.periodic(k) {
                return Err(bad(&format!("cannot use fix box/relax with non-periodic {axis} dimension")));
            }
        }
        // a relaxed or scaled tilt needs its second dimension periodic, and not both
        for (c, (name, dim)) in [("yz", 2), ("xz", 2), ("xy", 1)].iter().enumerate() {
            let axis = ["x", "y", "z"][*dim];
            if p_flag[3 + c] && !d.periodic(*dim) {
                return Err(bad(&format!("cannot use fix box/relax {name} with non-periodic {axis} dimension")));
            }
            if scale[c] && !d.periodic(*dim) {
                return Err(bad(&format!("cannot use fix box/relax with {name} tilt factor scaling with a non-periodic {axis} dimension")));
            }
            if p_flag[3 + c] && scale[c] {
                return Err(bad(&format!("cannot use fix box/relax with both {name} relaxation and scaling on the {name} tilt factor")));
            }
        }
        if let (Some(w), false) = (off_diagonal, d.triclinic()) {
            return Err(a.error_at(w, "cannot specify Pxy/Pxz/Pyz in fix box/relax with a non-triclinic box", "a triclinic box (change_box all triclinic)"));
        }
        let same = |i: usize, j: usize| p_target[i] == p_target[j];
        let couple_mismatch = pcouple.mismatch(dimension, same);
        if couple_mismatch {
            return Err(bad("fix box/relax: the coupled dimensions must have the same target pressure"));
        }
        let pstyle = if p_flag[3..].iter().any(|&f| f) {
            PStyle::Triclinic
        } else if pcouple == Couple::Xyz || (dimension == 2 && pcouple == Couple::Xy) {
            PStyle::Iso
        } else {
            PStyle::Aniso
        };
        Ok(FixBoxRelax {
            id,
            groupbit,
            pstyle,
            pcouple,
            p_target,
            p_flag,
            allremap,
            vmax,
            nreset,
            deviatoric,
            fixedpoint,
            scale,
            dimension,
            pv2e: 1.0,
            prdinit: [1.0; 3],
            vol0: 1.0,
            h0: [0.0; 6],
            p_hydro: 0.0,
            sigma: [0.0; 6],
            lo0: d.lo,
            hi0: d.hi,
            tilt0: [yz, xz, xy],
        })
    }

    /// LAMMPS' compute_press_target: the mean of the diagonal targets; a target away from it
    /// makes the relaxation deviatoric.
    fn press_target(&mut self) {
        let n = self.p_flag[..3].iter().filter(|&&f| f).count();
        let mut p = 0.0;
        for k in 0..3 {
            if self.p_flag[k] {
                p += self.p_target[k];
            }
        }
        if n > 0 {
            p /= n as f64;
        }
        self.p_hydro = p;
        for k in 0..3 {
            if self.p_flag[k] && (p - self.p_target[k]).abs() > 1.0e-6 {
                self.deviatoric = true;
            }
        }
        if self.pstyle == PStyle::Triclinic && (3..6).any(|k| self.p_flag[k] && self.p_target[k].abs() > 1.0e-6) {
            self.deviatoric = true;
        }
    }

    /// The reference box is the current one (LAMMPS' xprdinit.. and vol0), and with a
    /// deviatoric target sigma = V0 h0^-1 P_dev h0^-T (LAMMPS' compute_sigma).
    fn reference(&mut self, state: &State) -> Result<(), String> {
        let d = state.domain()?;
        let prd = d.prd();
        self.prdinit = [prd[0], prd[1], if self.dimension == 2 { 1.0 } else { prd[2] }];
        self.vol0 = self.prdinit[0] * self.prdinit[1] * self.prdinit[2];
        if !self.deviatoric {
            return Ok(());
        }
        let hinv = d.h_inv();
        let m = [[hinv[0], hinv[5], hinv[4]], [0.0, hinv[1], hinv[3]], [0.0, 0.0, hinv[2]]];
        let mut p = [[0.0; 3]; 3];
        for k in 0..3 {
            if self.p_flag[k] {
                p[k][k] = self.p_target[k] - self.p_hydro;
            }
        }
        p[1][2] = self.p_target[3];
        p[2][1] = self.p_target[3];
        p[0][2] = self.p_target[4];
        p[2][0] = self.p_target[4];
        p[0][1] = self.p_target[5];
        p[1][0] = self.p_target[5];
        // the target as the system's deviatoric stress at stationarity, P h^-T diag(h)
        p[1][1] -= p[1][2] * hinv[3] * self.h0[1];
        p[0][1] -= p[0][2] * hinv[3] * self.h0[1];
        p[1][0] = p[0][1];
        p[0][0] -= p[0][1] * hinv[5] * self.h0[0] + p[0][2] * hinv[4] * self.h0[0];
        let mut t = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                t[i][j] = m[i][0] * p[0][j] + m[i][1] * p[1][j] + m[i][2] * p[2][j];
            }
        }
        let mut s = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                s[i][j] = (t[i][0] * m[j][0] + t[i][1] * m[j][1] + t[i][2] * m[j][2]) * self.vol0;
            }
        }
        self.sigma = [s[0][0], s[1][1], s[2][2], s[1][2], s[0][2], s[0][1]];
        Ok(())
    }

    /// The pressure LAMMPS' box/relax measures (compute pressure ... virial: the virial
    /// alone), the diagonal coupled as `couple` says, then (triclinic) yz, xz, xy.
    fn p_current(&self, state: &State, virial: &[f64; 6]) -> Result<[f64; 6], String> {
        let d = state.domain()?;
        let p = d.prd();
        let nktv2p = state.units.nktv2p;
        let three = self.dimension == 3;
        let inv = if three { 1.0 / (p[0] * p[1] * p[2]) } else { 1.0 / (p[0] * p[1]) };
        let pc = if self.pstyle == PStyle::Iso {
            let s = if three { (virial[0] + virial[1] + virial[2]) / 3.0 * inv * nktv2p } else { (virial[0] + virial[1]) / 2.0 * inv * nktv2p };
            [s; 3]
        } else {
            let z = if three { virial[2] * inv * nktv2p } else { 0.0 };
            self.pcouple.apply([virial[0] * inv * nktv2p, virial[1] * inv * nktv2p, z])
        };
        let mut p6 = [pc[0], pc[1], pc[2], 0.0, 0.0, 0.0];
        if self.pstyle == PStyle::Triclinic {
            // the virial's xy xz yz in the box's yz xz xy order (2d: xy only)
            for (k, v) in [(3, 5), (4, 4), (5, 3)] {
                p6[k] = if three || k == 5 { virial[v] * inv * nktv2p } else { 0.0 };
            }
        }
        if p6.iter().any(|v| !v.is_finite()) {
            return Err("fix box/relax: non-numeric pressure - simulation unstable".into());
        }
        Ok(p6)
    }

    /// LAMMPS' min_energy: the energy of the box degrees of freedom and their forces, from
    /// the virial of the last force evaluation.
    fn energy(&self, state: &State, virial: &[f64; 6], fextra: &mut [f64]) -> Result<f64, String> {
        let pc = self.p_current(state, virial)?;
        let d = state.domain()?;
        let prd = d.prd();
        let (pv2e, vol0) = (self.pv2e, self.vol0);
        let mut eng;
        if self.pstyle == PStyle::Iso {
            let scale = prd[0] / self.prdinit[0];
            if self.dimension == 3 {
                eng = pv2e * self.p_target[0] * (scale * scale * scale - 1.0) * vol0;
                fextra[0] = pv2e * (pc[0] - self.p_target[0]) * 3.0 * scale * scale * vol0;
            } else {
                eng = pv2e * self.p_target[0] * (scale * scale - 1.0) * vol0;
                fextra[0] = pv2e * (pc[0] - self.p_target[0]) * 2.0 * scale * vol0;
            }
        } else {
            fextra[..3].fill(0.0);
            let mut s = [1.0; 3];
            for k in 0..3 {
                if self.p_flag[k] {
                    s[k] = prd[k] / self.prdinit[k];
                }
            }
            let scalevol = s[0] * s[1] * s[2];
            eng = pv2e * self.p_hydro * (scalevol - 1.0) * vol0;
            if self.p_flag[0] {
                fextra[0] = pv2e * (pc[0] - self.p_hydro) * s[1] * s[2] * vol0;
            }
            if self.p_flag[1] {
                fextra[1] = pv2e * (pc[1] - self.p_hydro) * s[0] * s[2] * vol0;
            }
            if self.p_flag[2] {
                fextra[2] = pv2e * (pc[2] - self.p_hydro) * s[0] * s[1] * vol0;
            }
            let [x0, y0, z0] = self.prdinit;
            let triclinic = self.pstyle == PStyle::Triclinic;
            if triclinic {
                // the shear stress times the face the tilt moves and the length it is measured in
                fextra[3..6].fill(0.0);
                if self.p_flag[3] {
                    fextra[3] = pv2e * pc[3] * s[1] * y0 * s[0] * x0 * y0;
                }
                if self.p_flag[4] {
                    fextra[4] = pv2e * pc[4] * s[0] * x0 * s[1] * y0 * x0;
                }
                if self.p_flag[5] {
                    fextra[5] = pv2e * pc[5] * s[0] * x0 * s[2] * z0 * x0;
                }
            }
            if self.deviatoric {
                let h = d.h();
                let fdev = self.deviatoric_force(&h);
                for k in 0..3 {
                    if self.p_flag[k] {
                        fextra[k] -= fdev[k] * self.prdinit[k];
                    }
                }
                if triclinic {
                    // yz is measured in y, xz and xy in x
                    for (k, len) in [(3, y0), (4, x0), (5, x0)] {
                        if self.p_flag[k] {
                            fextra[k] -= fdev[k] * len;
                        }
                    }
                }
                eng += self.strain_energy(&h);
            }
        }
        Ok(eng)
    }

    /// LAMMPS' compute_strain_energy: 0.5 Tr(sigma h h^T) in energy units.
    fn strain_energy(&self, h: &[f64; 6]) -> f64 {
        let s = &self.sigma;
        if self.dimension == 3 {
            return strain_trace(s, h) * self.pv2e;
        }
        let (d0, d1) = (s[0] * (h[0] * h[0] + h[5] * h[5]) + s[5] * h[1] * h[5], s[5] * h[5] * h[1] + s[1] * h[1] * h[1]);
        0.5 * (d0 + d1 + 0.0) * self.pv2e
    }

    /// LAMMPS' compute_deviatoric: h sigma in h's layout (the deviatoric force on the lengths
    /// and tilts).
    fn deviatoric_force(&self, h: &[f64; 6]) -> [f64; 6] {
        let (s, pv2e) = (&self.sigma, self.pv2e);
        if self.dimension == 3 {
            [
                pv2e * (h[0] * s[0] + h[5] * s[5] + h[4] * s[4]),
                pv2e * (h[1] * s[1] + h[3] * s[3]),
                pv2e * (h[2] * s[2]),
                pv2e * (h[1] * s[3] + h[3] * s[2]),
                pv2e * (h[0] * s[4] + h[5] * s[3] + h[4] * s[2]),
                pv2e * (h[0] * s[5] + h[5] * s[1] + h[4] * s[3]),
            ]
        } else {
            [pv2e * (h[0] * s[0] + h[5] * s[5]), pv2e * (h[1] * s[1]), 0.0, 0.0, 0.0, pv2e * (h[0] * s[5] + h[5] * s[1])]
        }
    }
}

impl MinExtra for FixBoxRelax {
    fn min_dof(&self) -> usize {
        match self.pstyle {
            PStyle::Iso => 1,
            PStyle::Aniso => 3,
            PStyle::Triclinic => 6,
        }
    }
    fn min_energy(&mut self, state: &State, virial: &[f64; 6], fextra: &mut [f64]) -> Result<f64, String> {
        self.energy(state, virial, fextra)
    }
    fn min_store(&mut self, state: &State) -> Result<(), String> {
        let d = state.domain()?;
        (self.lo0, self.hi0) = (d.lo, d.hi);
        if self.pstyle == PStyle::Triclinic {
            let [xy, xz, yz] = d.tilts();
            self.tilt0 = [yz, xz, xy];
        }
        Ok(())
    }
    /// The box of the line search's start dilated by alpha hextra (fractions of the reference
    /// lengths), the tilts scaled or moved, the atoms with it (LAMMPS' min_step and remap).
    fn min_step(&mut self, state: &mut State, alpha: f64, hextra: &[f64]) -> Result<(), String> {
        let mut ds = [0.0; 6];
        match self.pstyle {
            PStyle::Iso => ds[..3].fill(alpha * hextra[0]),
            PStyle::Aniso | PStyle::Triclinic => {
                for k in 0..hextra.len() {
                    if self.p_flag[k] {
                        ds[k] = alpha * hextra[k];
                    }
                }
            }
        }
        let d = state.domain.as_mut().ok_or("fix box/relax: no box")?;
        let old = d.clone();
        let prd = old.prd();
        for k in 0..3 {
            if self.p_flag[k] {
                let (lo0, hi0) = (self.lo0[k], self.hi0[k]);
                d.lo[k] = lo0 + (lo0 - self.fixedpoint[k]) / prd[k] * ds[k] * self.h0[k];
                d.hi[k] = hi0 + (hi0 - self.fixedpoint[k]) / prd[k] * ds[k] * self.h0[k];
                if d.lo[k] >= d.hi[k] {
                    return Err("fix box/relax generated a negative box length".into());
                }
            }
        }
        if let Some(t) = d.tilt.as_mut() {
            let [syz, sxz, sxy] = self.scale;
            let h0 = &self.h0;
            if syz {
                t[2] = (d.hi[2] - d.lo[2]) * h0[3] / h0[2];
            }
            if sxz {
                t[1] = (d.hi[2] - d.lo[2]) * h0[4] / h0[2];
            }
            if sxy {
                t[0] = (d.hi[1] - d.lo[1]) * h0[5] / h0[1];
            }
            let [x0, y0, _] = self.prdinit;
            // yz from its start by a fraction of y, xz and xy by fractions of x
            for (k, slot, len) in [(3, 2, y0), (4, 1, x0), (5, 0, x0)] {
                if self.p_flag[k] {
                    t[slot] = self.tilt0[k - 3] + ds[k] * len;
                }
            }
        }
        // the atoms (all, or the group's with dilate partial; ghosts too, as LAMMPS) follow
        let dilation = Dilation::new(&old, d);
        let atoms = &mut state.atoms;
        for (x, &mask) in atoms.x.iter_mut().zip(&atoms.mask) {
            if self.allremap || mask & self.groupbit != 0 {
                dilation.apply(x);
            }
        }
        Ok(())
    }
    fn max_alpha(&self, hextra: &[f64]) -> f64 {
        let min = |a: f64, b: f64| if a < b { a } else { b };
        match self.pstyle {
            PStyle::Iso => self.vmax / hextra[0].abs(),
            PStyle::Aniso | PStyle::Triclinic => {
                let mut alpha = 1.0;
                for k in 0..hextra.len() {
                    if self.p_flag[k] {
                        alpha = min(alpha, self.vmax / hextra[k].abs());
                    }
                }
                alpha
            }
        }
    }
    fn min_reset_ref(&mut self, state: &State, begin: i64) -> Result<bool, String> {
        if self.deviatoric && self.nreset > 0 && (state.step - begin) % self.nreset == 0 {
            self.reference(state)?;
            return Ok(true);
        }
        Ok(false)
    }
}

impl Fix for FixBoxRelax {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "box/relax"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks::default()
    }
    fn changes_box(&self) -> bool {
        true
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        self.pv2e = 1.0 / state.units.nktv2p;
        self.h0 = state.domain()?.h();
        self.press_target();
        self.reference(state)
    }
    fn min_extra(&mut self) -> Option<&mut dyn MinExtra> {
        Some(self)
    }
    /// f_ID: the energy of the box degrees of freedom (0 at step 0), from the force field's
    /// virial of the last evaluation.
    fn scalar(&self, state: &State) -> Option<f64> {
        if state.step == 0 {
            return Some(0.0);
        }
        let mut f = [0.0; 6];
        Some(self.energy(state, &state.energies.virial, &mut f).unwrap_or(f64::NAN))
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
}
