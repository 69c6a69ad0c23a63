//! `fix ID group wall/lj93 face coord epsilon sigma cutoff ... [units box|lattice] [pbc yes|no]`:
//! flat walls with the 9-3 Lennard-Jones potential E = eps [2/15 (sigma/r)^9 - (sigma/r)^3],
//! shifted to zero at the cutoff, as LAMMPS' fix wall/lj93 (face: xlo xhi ylo yhi zlo zhi;
//! coord: EDGE, a number or v_name). f_ID is the wall energy, f_ID[k] the force on wall k.

use super::value::FixValue;
use super::wall_reflect::{parse_face, scale_constants};
use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group wall/lj93 face coord epsilon sigma cutoff [face ...] [units box|lattice] [pbc yes|no]  (face: xlo xhi ylo yhi zlo zhi; coord: EDGE, number, v_name)";

struct Wall {
    dim: usize,
    hi: bool,
    coord: FixValue,
    cutoff: f64,
    coeff: [f64; 4],
    offset: f64,
}

pub struct FixWallLj93 {
    id: String,
    groupbit: u32,
    walls: Vec<Wall>,
    /// Energy, then the force on each wall.
    ewall: Vec<f64>,
}

impl Wall {
    /// LAMMPS' precompute: the force and energy prefactors and the energy at the cutoff.
    fn new(dim: usize, hi: bool, coord: FixValue, epsilon: f64, sigma: f64, cutoff: f64) -> Wall {
        let coeff = [6.0 / 5.0 * epsilon * sigma.powf(9.0), 3.0 * epsilon * sigma.powf(3.0), 2.0 / 15.0 * epsilon * sigma.powf(9.0), epsilon * sigma.powf(3.0)];
        let rinv = 1.0 / cutoff;
        let r2inv = rinv * rinv;
        let r4inv = r2inv * r2inv;
        let offset = coeff[2] * r4inv * r4inv * rinv - coeff[3] * r2inv * rinv;
        Wall { dim, hi, coord, cutoff, coeff, offset }
    }
}

impl FixWallLj93 {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let domain = state.domain.as_ref().ok_or_else(|| a.error_at(&cmd.name, "fix wall/lj93 needs a simulation box", "no box yet"))?;
        let mut walls: Vec<(Wall, Option<&Word>, &Word)> = Vec::new();
        let (mut lattice_units, mut pbc) = (true, false);
        while let Some(w) = a.peek() {
            a.skip(1);
            let taken: Vec<(usize, bool)> = walls.iter().map(|(x, _, _)| (x.dim, x.hi)).collect();
            if let Some(f) = parse_face(&mut a, w, &taken, state, "wall/lj93", SYNTAX)? {
                let epsilon = a.f64("epsilon")?;
                let sigma = a.f64("sigma")?;
                let cutoff = a.f64_where("cutoff", "> 0", |c| c > 0.0)?;
                walls.push((Wall::new(f.dim, f.hi, f.coord, epsilon, sigma, cutoff), f.constant, w));
            } else if w.text == "units" {
                lattice_units = a.choice("units", &["box", "lattice"])? == 1;
            } else if w.text == "pbc" {
                pbc = a.yes_no("pbc")?;
            } else {
                return Err(a.unknown_keyword(w, &["xlo", "xhi", "ylo", "yhi", "zlo", "zhi", "units", "pbc"]));
            }
        }
        if walls.is_empty() {
            return Err(a.missing("a wall face"));
        }
        if !pbc {
            if let Some((_, _, w)) = walls.iter().find(|(x, _, _)| domain.periodic(x.dim)) {
                return Err(a.error_at(w, format!("cannot use fix wall/lj93 {} in a periodic dimension (without `pbc yes`)", w.text), "periodic dimension"));
            }
        }
        let mut coords: Vec<(usize, &mut FixValue, Option<&Word>)> = walls.iter_mut().map(|(w, c, _)| (w.dim, &mut w.coord, *c)).collect();
        scale_constants(&a, lattice_units, &mut coords, state)?;
        let n = walls.len();
        Ok(FixWallLj93 { id, groupbit, walls: walls.into_iter().map(|(w, _, _)| w).collect(), ewall: vec![0.0; n + 1] })
    }
}

impl Fix for FixWallLj93 {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "wall/lj93"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    fn post_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.ewall.fill(0.0);
        for m in 0..self.walls.len() {
            let coord = ctx.value(state, self, &self.walls[m].coord)?.unwrap_or(0.0);
            let w = &self.walls[m];
            let (dim, side) = (w.dim, if w.hi { 1.0 } else { -1.0 });
            let a = &mut state.atoms;
            let mut on = None;
            for i in 0..a.nlocal {
                if a.mask[i] & self.groupbit == 0 {
                    continue;
                }
                let delta = if w.hi { coord - a.x[i][dim] } else { a.x[i][dim] - coord };
                if delta >= w.cutoff {
                    continue;
                }
                if delta <= 0.0 {
                    on = Some(a.tag[i]);
                    continue;
                }
                let rinv = 1.0 / delta;
                let r2inv = rinv * rinv;
                let r4inv = r2inv * r2inv;
                let r10inv = r4inv * r4inv * r2inv;
                let fwall = side * (w.coeff[0] * r10inv - w.coeff[1] * r4inv);
                a.f[i][dim] -= fwall;
                self.ewall[0] += w.coeff[2] * r4inv * r4inv * rinv - w.coeff[3] * r2inv * rinv - w.offset;
                self.ewall[m + 1] += fwall;
            }
            if let Some(tag) = on {
                return Err(RunError::new(state.step, format!("fix wall/lj93 {}: particle {tag} is on or inside the wall surface", self.id)));
            }
        }
        Ok(())
    }
    fn scalar(&self, _state: &State) -> Option<f64> {
        Some(self.ewall[0])
    }
    fn vector(&self, _state: &State, i: usize) -> Option<f64> {
        (1..=self.walls.len()).contains(&i).then(|| self.ewall[i])
    }
    fn size_vector(&self) -> usize {
        self.walls.len()
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
}
