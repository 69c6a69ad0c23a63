//! `fix ID group indent K sphere|cylinder|plane ... [side in|out] [units box|lattice]`: an
//! indenter pushing atoms with F(r) = -K (r - R)^2 (sphere: centre x y z, radius R; cylinder:
//! axis dim c1 c2, radius R; plane: dim pos lo|hi), as LAMMPS' fix indent. Geometry values may
//! be equal-style variables (evaluated every step, in box units). f_ID is the indenter energy,
//! f_ID[1..3] the force on the indenter.

use super::value::FixValue;
use super::{Fix, FixCtx, FixHooks, ThermoTally};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group indent K sphere x y z R | cylinder dim c1 c2 R | plane dim pos lo|hi [side in|out] [units box|lattice]";

enum Shape {
    Sphere { c: [FixValue; 3], r: FixValue },
    /// Axis along `dim`; `c` are the other two coordinates in x, y, z order.
    Cylinder { dim: usize, c: [FixValue; 2], r: FixValue },
    /// `side` +1 (hi: pushes atoms below the plane) or -1 (lo).
    Plane { dim: usize, pos: FixValue, side: f64 },
}

pub struct FixIndent {
    id: String,
    groupbit: u32,
    k: f64,
    k3: f64,
    shape: Shape,
    outside: bool,
    /// Energy, then the force on the indenter.
    indenter: [f64; 4],
    /// Energy only (LAMMPS: no virial).
    tally: ThermoTally,
}

fn dim_of(a: &mut Args) -> DResult<usize> {
    a.choice("axis", &["x", "y", "z"])
}

impl FixIndent {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let k = a.f64("K")?;
        let mut shape = None;
        let (mut outside, mut lattice_units) = (true, true);
        let value = |a: &mut Args, what: &str| -> DResult<FixValue> {
            let w = a.word(what)?;
            FixValue::parse(w, what, false).map_err(|d| d.with_help(format!("syntax: {SYNTAX}")))
        };
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "sphere" => {
                    let c = [value(&mut a, "x")?, value(&mut a, "y")?, value(&mut a, "z")?];
                    shape = Some(Shape::Sphere { c, r: value(&mut a, "R")? });
                }
                "cylinder" => {
                    let dim = dim_of(&mut a)?;
                    let c = [value(&mut a, "c1")?, value(&mut a, "c2")?];
                    shape = Some(Shape::Cylinder { dim, c, r: value(&mut a, "R")? });
                }
                "plane" => {
                    let dim = dim_of(&mut a)?;
                    let pos = value(&mut a, "pos")?;
                    let side = if a.choice("side of the plane", &["lo", "hi"])? == 1 { 1.0 } else { -1.0 };
                    shape = Some(Shape::Plane { dim, pos, side });
                }
                "side" => outside = a.choice("side", &["in", "out"])? == 1,
                "units" => lattice_units = a.choice("units", &["box", "lattice"])? == 1,
                _ => return Err(a.unknown_keyword(w, &["sphere", "cylinder", "plane", "side", "units"])),
            }
        }
        let mut shape = shape.ok_or_else(|| a.missing("an indenter shape (sphere, cylinder or plane)"))?;
        // constant geometry is in lattice units by default; the radius scales with x
        let s = if lattice_units { state.lattice_scale().map_err(|e| a.error_at(&cmd.name, e, "needs a lattice (or `units box`)"))? } else { [1.0; 3] };
        let scale = |v: &mut FixValue, f: f64| {
            if let FixValue::Const(x) = v {
                *x *= f;
            }
        };
        match &mut shape {
            Shape::Sphere { c, r } => {
                for d in 0..3 {
                    scale(&mut c[d], s[d]);
                }
                scale(r, s[0]);
            }
            Shape::Cylinder { dim, c, r } => {
                let others: Vec<usize> = (0..3).filter(|d| d != dim).collect();
                scale(&mut c[0], s[others[0]]);
                scale(&mut c[1], s[others[1]]);
                scale(r, s[0]);
            }
            Shape::Plane { dim, pos, .. } => scale(pos, s[*dim]),
        }
        Ok(FixIndent { id, groupbit, k, k3: k / 3.0, shape, outside, indenter: [0.0; 4], tally: ThermoTally::default() })
    }

    /// Force on atoms around a centre (sphere) or an axis (cylinder: `axis` is zeroed).
    fn radial(&mut self, state: &mut State, ctr: [f64; 3], radius: f64, axis: Option<usize>) -> Result<(), RunError> {
        let d = state.domain.as_ref().ok_or_else(|| RunError::new(state.step, "no box"))?;
        let mut ctr = ctr;
        d.remap(&mut ctr, &mut [0; 3]);
        let a = &mut state.atoms;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            let mut del = [a.x[i][0] - ctr[0], a.x[i][1] - ctr[1], a.x[i][2] - ctr[2]];
            if let Some(ax) = axis {
                del[ax] = 0.0;
            }
            d.minimum_image(&mut del);
            let r = (del[0] * del[0] + del[1] * del[1] + del[2] * del[2]).sqrt();
            let (dr, fmag) = if self.outside {
                let dr = r - radius;
                (dr, self.k * dr * dr)
            } else {
                let dr = radius - r;
                (dr, -self.k * dr * dr)
            };
            if dr >= 0.0 {
                continue;
            }
            let fx = del[0] * fmag / r;
            let fy = del[1] * fmag / r;
            let fz = del[2] * fmag / r;
            a.f[i][0] += fx;
            a.f[i][1] += fy;
            a.f[i][2] += fz;
            self.indenter[0] -= self.k3 * dr * dr * dr;
            self.indenter[1] -= fx;
            self.indenter[2] -= fy;
            self.indenter[3] -= fz;
        }
        Ok(())
    }
}

impl Fix for FixIndent {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "indent"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    /// LAMMPS' min_setup and min_post_force are its post_force; with `fix_modify energy yes`
    /// the indenter energy is part of the minimized energy (examples/indent/in.indent.min).
    fn min_role(&self) -> super::MinRole {
        super::MinRole::PostForce
    }
    fn post_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.indenter = [0.0; 4];
        let mut val = |v: &FixValue, me: &Self, state: &State| ctx.value(state, me, v).map(|x| x.unwrap_or(0.0));
        match &self.shape {
            Shape::Sphere { c, r } => {
                let ctr = [val(&c[0], self, state)?, val(&c[1], self, state)?, val(&c[2], self, state)?];
                let radius = val(r, self, state)?;
                self.radial(state, ctr, radius, None)
            }
            Shape::Cylinder { dim, c, r } => {
                let dim = *dim;
                // the coordinate along the axis only needs to lie near the box for the remap
                let lo = state.domain.as_ref().map_or(0.0, |d| d.lo[dim]);
                let (c0, c1) = (val(&c[0], self, state)?, val(&c[1], self, state)?);
                let ctr = match dim {
                    0 => [lo, c0, c1],
                    1 => [c0, lo, c1],
                    _ => [c0, c1, lo],
                };
                let radius = val(r, self, state)?;
                self.radial(state, ctr, radius, Some(dim))
            }
            Shape::Plane { dim, pos, side } => {
                let (dim, side) = (*dim, *side);
                let plane = val(pos, self, state)?;
                let a = &mut state.atoms;
                for i in 0..a.nlocal {
                    if a.mask[i] & self.groupbit == 0 {
                        continue;
                    }
                    let dr = side * (plane - a.x[i][dim]);
                    if dr >= 0.0 {
                        continue;
                    }
                    let fatom = -side * self.k * dr * dr;
                    a.f[i][dim] += fatom;
                    self.indenter[0] -= self.k3 * dr * dr * dr;
                    self.indenter[dim + 1] -= fatom;
                }
                Ok(())
            }
        }
    }
    fn scalar(&self, state: &State) -> Option<f64> {
        Some(state.summed_over_ranks(self.indenter[0]))
    }
    fn vector(&self, state: &State, i: usize) -> Option<f64> {
        (1..=3).contains(&i).then(|| state.summed_over_ranks(self.indenter[i]))
    }
    fn size_vector(&self) -> usize {
        3
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
