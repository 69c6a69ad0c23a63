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
        let mut walls: Vec<(Wall, Option<&Word>)> = Vec::new();
        let mut lattice_units = true;
        while let Some(w) = a.peek() {
            a.skip(1);
            let taken: Vec<(usize, bool)> = walls.iter().map(|(x, _)| (x.dim, x.hi)).collect();
            if let Some(f) = parse_face(&mut a, w, &taken, state, "wall/reflect", SYNTAX)? {
                if domain.periodic(f.dim) {
                    return Err(a.error_at(w, format!("cannot use fix wall/reflect {} in a periodic dimension", w.text), "periodic dimension"));
                }
                walls.push((Wall { dim: f.dim, hi: f.hi, coord: f.coord }, f.constant));
            } else if w.text == "units" {
                lattice_units = a.choice("units", &["box", "lattice"])? == 1;
            } else {
                return Err(a.unknown_keyword(w, &["xlo", "xhi", "ylo", "yhi", "zlo", "zhi", "units"]));
            }
        }
        if walls.is_empty() {
            return Err(a.missing("a wall face"));
        }
        let mut coords: Vec<(usize, &mut FixValue, Option<&Word>)> = walls.iter_mut().map(|(w, c)| (w.dim, &mut w.coord, *c)).collect();
        scale_constants(&a, lattice_units, &mut coords, state)?;
        Ok(FixWallReflect { id, groupbit, walls: walls.into_iter().map(|(w, _)| w).collect() })
    }
}

/// A wall face (`xlo` ... `zhi`) and its coordinate, as the wall fixes read them.
pub struct Face<'a> {
    pub dim: usize,
    pub hi: bool,
    /// EDGE (the box face now), a number or an equal-style variable.
    pub coord: FixValue,
    /// The word of a constant coordinate (scaled by lattice units).
    pub constant: Option<&'a Word>,
}

/// If `w` is a face keyword, read its coordinate; `taken` are the faces defined before.
pub fn parse_face<'a>(a: &mut Args<'a>, w: &'a Word, taken: &[(usize, bool)], state: &State, style: &str, syntax: &str) -> DResult<Option<Face<'a>>> {
    let Some(k) = ["xlo", "xhi", "ylo", "yhi", "zlo", "zhi"].iter().position(|f| *f == w.text) else { return Ok(None) };
    let (dim, hi) = (k / 2, k % 2 == 1);
    if taken.contains(&(dim, hi)) {
        return Err(a.error_at(w, format!("wall {} is defined twice", w.text), "repeated face"));
    }
    if dim == 2 && state.dimension == 2 {
        return Err(a.error_at(w, format!("cannot use fix {style} zlo/zhi in a 2d simulation"), "2d"));
    }
    let domain = state.domain.as_ref().ok_or_else(|| a.error_at(w, format!("fix {style} needs a simulation box"), "no box yet"))?;
    let cw = a.word("wall coordinate")?;
    if cw.text == "EDGE" {
        return Ok(Some(Face { dim, hi, coord: FixValue::Const(if hi { domain.hi[dim] } else { domain.lo[dim] }), constant: None }));
    }
    let coord = FixValue::parse(cw, "wall coordinate", false).map_err(|d| d.with_help(format!("syntax: {syntax}")))?;
    let constant = matches!(coord, FixValue::Const(_)).then_some(cw);
    Ok(Some(Face { dim, hi, coord, constant }))
}

/// Constant coordinates (dimension, value, its word if constant) are in lattice units unless
/// `units box`.
pub fn scale_constants(a: &Args, lattice_units: bool, coords: &mut [(usize, &mut FixValue, Option<&Word>)], state: &State) -> DResult<()> {
    let Some(first) = coords.iter().find_map(|c| c.2) else { return Ok(()) };
    if !lattice_units {
        return Ok(());
    }
    let scale = state.lattice_scale().map_err(|e| a.error_at(first, e, "needs a lattice (or `units box`)"))?;
    for (dim, v, c) in coords.iter_mut() {
        if let (Some(_), FixValue::Const(x)) = (c, &mut **v) {
            *x *= scale[*dim];
        }
    }
    Ok(())
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
    fn init_warnings(&self, others: [&[Box<dyn Fix>]; 2]) -> Vec<String> {
        let rigid = others.iter().any(|fixes| fixes.iter().any(|f| f.rigid_template().is_some()));
        rigid.then(|| "Should not use reflecting walls with rigid bodies".to_string()).into_iter().collect()
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
