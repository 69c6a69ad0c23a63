//! Flat walls with a potential: `fix ID group wall/STYLE face coord params... cutoff ... [units
//! box|lattice] [fld no] [pbc yes|no]` (LAMMPS' FixWall; face: xlo xhi ylo yhi zlo zhi; coord:
//! EDGE, a number or v_name). The potentials are one file each (wall_lj93.rs, wall_lj126.rs,
//! wall_lj1043.rs, wall_harmonic.rs, wall_morse.rs) and are shared with fix wall/region.
//! f_ID is the wall energy, f_ID[k] the force on wall k.

use super::value::FixValue;
use super::wall_reflect::{parse_face, scale_constants};
use super::{Fix, FixCtx, FixHooks, ThermoTally};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

/// A wall potential of the particle-surface distance `r` (LAMMPS' per-style formulas, in their
/// floating-point order).
pub trait WallPotential: Send + Sync {
    /// The force magnitude (positive: pushing the particle away) and the energy, shifted to
    /// zero at the cutoff as LAMMPS does.
    fn force_energy(&self, r: f64) -> (f64, f64);
    /// LAMMPS' fix wall/lj1043 skips particles on or behind its wall (and takes the cutoff
    /// itself) where the other flat walls stop with an error.
    fn skips_behind(&self) -> bool {
        false
    }
}

/// LAMMPS' MathSpecial::powint (binary exponentiation; negative n: its reciprocal).
pub fn powint(x: f64, n: i32) -> f64 {
    if n == 0 {
        return 1.0;
    }
    if x == 0.0 {
        return 0.0;
    }
    let (mut nn, mut ww, mut yy) = (n.unsigned_abs(), x, 1.0);
    while nn != 0 {
        if nn & 1 != 0 {
            yy *= ww;
        }
        nn >>= 1;
        ww *= ww;
    }
    if n > 0 {
        yy
    } else {
        1.0 / yy
    }
}

/// libm's pow with an integer exponent (LAMMPS' `pow(x, 9.0)`).
pub fn pow(x: f64, n: i32) -> f64 {
    x.powf(n as f64)
}

/// The parameters of one wall: epsilon, alpha (morse only), sigma and the cutoff, and which
/// power function the style's coefficients use.
#[derive(Clone, Copy, Debug)]
pub struct Params {
    pub epsilon: f64,
    pub alpha: f64,
    pub sigma: f64,
    pub cutoff: f64,
    pub pow: fn(f64, i32) -> f64,
}

/// A wall style: its name, the names of its parameters before the cutoff, and the potential.
pub struct Style {
    pub name: &'static str,
    pub params: &'static [&'static str],
    pub build: fn(&Params) -> Box<dyn WallPotential>,
    /// The power function of the flat fix (LAMMPS' fix wall/* and fix wall/region differ).
    pub flat_pow: fn(f64, i32) -> f64,
}

/// The flat wall styles; fix wall/region takes the same potentials by name.
pub const STYLES: &[Style] = &[
    Style { name: "lj93", params: &["epsilon", "sigma"], build: |p| Box::new(super::wall_lj93::Lj93::new(p)), flat_pow: pow },
    Style { name: "lj126", params: &["epsilon", "sigma"], build: |p| Box::new(super::wall_lj126::Lj126::new(p)), flat_pow: powint },
    Style { name: "lj1043", params: &["epsilon", "sigma"], build: |p| Box::new(super::wall_lj1043::Lj1043::new(p)), flat_pow: pow },
    Style { name: "harmonic", params: &["epsilon", "sigma"], build: |p| Box::new(super::wall_harmonic::Harmonic::new(p)), flat_pow: powint },
    Style { name: "morse", params: &["D0", "alpha", "r0"], build: |p| Box::new(super::wall_morse::Morse::new(p)), flat_pow: powint },
];

/// Read a style's parameters and the cutoff (> 0) into [`Params`].
pub fn parse_params(a: &mut Args, style: &Style, pow: fn(f64, i32) -> f64) -> DResult<Params> {
    let mut v = [0.0; 3];
    for (k, name) in style.params.iter().enumerate() {
        v[k] = a.f64(name)?;
    }
    let cutoff = a.f64_where("cutoff", "> 0", |c| c > 0.0)?;
    let (epsilon, alpha, sigma) = if style.params.len() == 3 { (v[0], v[1], v[2]) } else { (v[0], 0.0, v[1]) };
    Ok(Params { epsilon, alpha, sigma, cutoff, pow })
}

fn syntax(style: &Style) -> String {
    format!("fix ID group wall/{} face coord {} cutoff [face ...] [units box|lattice] [fld no] [pbc yes|no]  (face: xlo xhi ylo yhi zlo zhi; coord: EDGE, number, v_name)", style.name, style.params.join(" "))
}

struct Wall {
    dim: usize,
    hi: bool,
    coord: FixValue,
    cutoff: f64,
    pot: Box<dyn WallPotential>,
}

pub struct FixWall {
    id: String,
    style: String,
    groupbit: u32,
    walls: Vec<Wall>,
    /// Scale of v_ coordinates: the lattice spacings unless `units box` (LAMMPS scales
    /// variable walls too).
    vscale: [f64; 3],
    /// Energy, then the force on each wall.
    ewall: Vec<f64>,
    tally: ThermoTally,
}

impl FixWall {
    pub fn from_lammps(id: String, groupbit: u32, style: &Word, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let name = style.text.trim_start_matches("wall/");
        let st = STYLES.iter().find(|s| s.name == name).expect("registered wall style");
        let syn = syntax(st);
        let fix_style = style.text.as_str();
        let mut a = Args::from_words(args, cmd.span, &syn);
        let domain = state.domain.as_ref().ok_or_else(|| a.error_at(&cmd.name, format!("fix {fix_style} needs a simulation box"), "no box yet"))?;
        let mut walls: Vec<(Wall, Option<&Word>, &Word)> = Vec::new();
        let (mut lattice_units, mut pbc) = (true, false);
        while let Some(w) = a.peek() {
            a.skip(1);
            let taken: Vec<(usize, bool)> = walls.iter().map(|(x, _, _)| (x.dim, x.hi)).collect();
            if let Some(f) = parse_face(&mut a, w, &taken, state, fix_style, &syn)? {
                let p = parse_params(&mut a, st, st.flat_pow)?;
                walls.push((Wall { dim: f.dim, hi: f.hi, coord: f.coord, cutoff: p.cutoff, pot: (st.build)(&p) }, f.constant, w));
            } else if w.text == "units" {
                lattice_units = a.choice("units", &["box", "lattice"])? == 1;
            } else if w.text == "pbc" {
                pbc = a.yes_no("pbc")?;
            } else if w.text == "fld" {
                let at = a.peek();
                if a.yes_no("fld")? {
                    return Err(a.error_at(at.unwrap_or(w), "fix wall `fld yes` (walls before the pair forces, for the FLD package) is not supported", "fld no"));
                }
            } else {
                return Err(a.unknown_keyword(w, &["xlo", "xhi", "ylo", "yhi", "zlo", "zhi", "units", "fld", "pbc"]));
            }
        }
        if walls.is_empty() {
            return Err(a.missing("a wall face"));
        }
        if !pbc {
            if let Some((_, _, w)) = walls.iter().find(|(x, _, _)| domain.periodic(x.dim)) {
                return Err(a.error_at(w, format!("cannot use fix {fix_style} {} in a periodic dimension (without `pbc yes`)", w.text), "periodic dimension"));
            }
        }
        let mut coords: Vec<(usize, &mut FixValue, Option<&Word>)> = walls.iter_mut().map(|(w, c, _)| (w.dim, &mut w.coord, *c)).collect();
        scale_constants(&a, lattice_units, &mut coords, state)?;
        let vscale = if lattice_units { state.lattice_scale().map_err(|e| a.error_at(&cmd.name, e, "needs a lattice (or `units box`)"))? } else { [1.0; 3] };
        let n = walls.len();
        Ok(FixWall { id, style: style.text.clone(), groupbit, walls: walls.into_iter().map(|(w, _, _)| w).collect(), vscale, ewall: vec![0.0; n + 1], tally: ThermoTally::new(true) })
    }
}

impl Fix for FixWall {
    /// LAMMPS applies it while minimizing (its energy counts only with fix_modify energy).
    fn min_role(&self) -> super::MinRole {
        super::MinRole::PostForce
    }
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        &self.style
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    fn post_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.ewall.fill(0.0);
        self.tally.v_init();
        for m in 0..self.walls.len() {
            let mut coord = ctx.value(state, self, &self.walls[m].coord)?.unwrap_or(0.0);
            let w = &self.walls[m];
            if matches!(w.coord, FixValue::Variable(_)) {
                coord *= self.vscale[w.dim];
            }
            let (dim, side) = (w.dim, if w.hi { 1.0 } else { -1.0 });
            let skips = w.pot.skips_behind();
            let a = &mut state.atoms;
            let mut on = None;
            for i in 0..a.nlocal {
                if a.mask[i] & self.groupbit == 0 {
                    continue;
                }
                let delta = if w.hi { coord - a.x[i][dim] } else { a.x[i][dim] - coord };
                if skips {
                    if delta <= 0.0 || delta > w.cutoff {
                        continue;
                    }
                } else {
                    if delta >= w.cutoff {
                        continue;
                    }
                    if delta <= 0.0 {
                        on = Some(a.tag[i]);
                        continue;
                    }
                }
                let (f, e) = w.pot.force_energy(delta);
                let fwall = side * f;
                a.f[i][dim] -= fwall;
                self.ewall[0] += e;
                self.ewall[m + 1] += fwall;
                self.tally.v_tally_n(dim, if w.hi { fwall * delta } else { -fwall * delta });
            }
            if let Some(tag) = on {
                return Err(RunError::new(state.step, format!("fix {} {}: particle {tag} is on or inside the wall surface", self.style, self.id)));
            }
        }
        Ok(())
    }
    fn scalar(&self, state: &State) -> Option<f64> {
        Some(state.summed_over_ranks(self.ewall[0]))
    }
    fn vector(&self, state: &State, i: usize) -> Option<f64> {
        (1..=self.walls.len()).contains(&i).then(|| state.summed_over_ranks(self.ewall[i]))
    }
    fn size_vector(&self) -> usize {
        self.walls.len()
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
    fn thermo_tally(&self) -> Option<&ThermoTally> {
        Some(&self.tally)
    }
    fn thermo_tally_mut(&mut self) -> Option<&mut ThermoTally> {
        Some(&mut self.tally)
    }
}
