//! `fix ID group wall/reflect face coord ... [units box|lattice]`: atoms that cross a wall
//! plane are mirrored back and their normal velocity flips (after the position update).

use super::value::FixValue;
use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group wall/reflect face coord [face coord ...] [units box|lattice]  (face: xlo xhi ylo yhi zlo zhi; coord: EDGE, number, v_name)";

struct Wall {
    dim: usize,
    hi: bool,
    coord: FixValue,
}

pub struct FixWallReflect {
    id: String,
    groupbit: u32,
    walls: Vec<Wall>,
}

impl FixWallReflect {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let domain = state.domain.as_ref().ok_or_else(|| a.error_at(&cmd.name, "fix wall/reflect needs a simulation box", "no box yet"))?;
        let faces = ["xlo", "xhi", "ylo", "yhi", "zlo", "zhi"];
        let mut walls: Vec<(Wall, Option<&Word>)> = Vec::new();
        let mut lattice_units = true;
        while let Some(w) = a.peek() {
            a.skip(1);
            if let Some(k) = faces.iter().position(|f| *f == w.text) {
                let (dim, hi) = (k / 2, k % 2 == 1);
                if walls.iter().any(|(x, _)| x.dim == dim && x.hi == hi) {
                    return Err(a.error_at(w, format!("wall {} is defined twice", w.text), "repeated face"));
                }
                if domain.periodic(dim) {
                    return Err(a.error_at(w, format!("cannot use fix wall/reflect {} in a periodic dimension", w.text), "periodic dimension"));
                }
                if dim == 2 && state.dimension == 2 {
                    return Err(a.error_at(w, "cannot use fix wall/reflect zlo/zhi in a 2d simulation", "2d"));
                }
                let cw = a.word("wall coordinate")?;
                let (coord, constant) = if cw.text == "EDGE" {
                    (FixValue::Const(if hi { domain.hi[dim] } else { domain.lo[dim] }), None)
                } else {
                    let v = FixValue::parse(cw, "wall coordinate", false).map_err(|d| d.with_help(format!("syntax: {SYNTAX}")))?;
                    let c = matches!(v, FixValue::Const(_)).then_some(cw);
                    (v, c)
                };
                walls.push((Wall { dim, hi, coord }, constant));
            } else if w.text == "units" {
                lattice_units = a.choice("units", &["box", "lattice"])? == 1;
            } else {
                return Err(a.unknown_keyword(w, &["xlo", "xhi", "ylo", "yhi", "zlo", "zhi", "units"]));
            }
        }
        if walls.is_empty() {
            return Err(a.missing("a wall face"));
        }
        // constant coordinates are in lattice units by default
        if lattice_units && walls.iter().any(|(_, c)| c.is_some()) {
            let scale = state.lattice_scale().map_err(|e| a.error_at(walls.iter().find_map(|(_, c)| *c).unwrap(), e, "needs a lattice (or `units box`)"))?;
            for (wall, c) in &mut walls {
                if c.is_some() {
                    if let FixValue::Const(x) = &mut wall.coord {
                        *x *= scale[wall.dim];
                    }
                }
            }
        }
        Ok(FixWallReflect { id, groupbit, walls: walls.into_iter().map(|(w, _)| w).collect() })
    }
}

impl Fix for FixWallReflect {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "wall/reflect"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_integrate: true, ..FixHooks::default() }
    }
    fn image_planes(&self, _state: &State, equal: &mut dyn FnMut(&str) -> Result<f64, String>) -> Result<Vec<(usize, f64)>, String> {
        let mut planes = vec![];
        for w in &self.walls {
            if let Some(c) = w.coord.eval(equal)? {
                planes.push((w.dim, c));
            }
        }
        Ok(planes)
    }
    fn post_integrate(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        for w in &self.walls {
            let coord = ctx.value(state, self, &w.coord)?.unwrap_or(0.0);
            let a = &mut state.atoms;
            let d = w.dim;
            for i in 0..a.nlocal {
                if a.mask[i] & self.groupbit == 0 {
                    continue;
                }
                let x = a.x[i][d];
                if !w.hi && x < coord {
                    a.x[i][d] = coord + (coord - x);
                    a.v[i][d] = -a.v[i][d];
                } else if w.hi && x > coord {
                    a.x[i][d] = coord - (x - coord);
                    a.v[i][d] = -a.v[i][d];
                }
            }
        }
        Ok(())
    }
}
