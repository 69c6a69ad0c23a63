//! `displace_atoms group move|ramp|random|rotate ... [units box|lattice]`, as LAMMPS'
//! DisplaceAtoms: each style's arithmetic in LAMMPS' order, then every owned atom is remapped
//! into a periodic box with its image flags updated.

use super::need_box;
use super::atoms_cmds::{equal_or_atom_variable, SetValue};
use crate::engine::random_park::RanPark;
use crate::sim::Simulation;
use dmhs_parser::{Args, Command, DResult, Diagnostic, SourceMap, Word};

const SYNTAX: &str = "displace_atoms group-ID move dx dy dz (numbers or v_name) | ramp ddim dlo dhi dim clo chi | random dx dy dz seed | rotate Px Py Pz Rx Ry Rz theta  [units box|lattice]";

/// How many arguments each style takes before its keywords.
const STYLES: &[(&str, usize)] = &[("move", 3), ("ramp", 6), ("random", 4), ("rotate", 7)];

pub fn displace_atoms(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    let mut a = Args::new(cmd, SYNTAX);
    let gw = a.word("group ID")?;
    let bit = sim.state.groups.bit(&gw.text).ok_or_else(|| a.error_at(gw, format!("group `{}` does not exist", gw.text), "unknown group"))?;
    let sw = a.peek();
    let style = a.choice("displacement style", &STYLES.iter().map(|s| s.0).collect::<Vec<_>>())?;
    let sw = sw.unwrap();
    // the keywords follow the style's arguments (LAMMPS reads them first: units scale them)
    let params: &[Word] = a.remaining().get(..STYLES[style].1).ok_or_else(|| Diagnostic::at(cmd.span, format!("displace_atoms {} needs {} arguments", sw.text, STYLES[style].1), "too few arguments").with_help(format!("syntax: {SYNTAX}")))?;
    a.skip(params.len());
    let lattice_units = a.units_keyword_only()?;
    let scale = match lattice_units {
        true => sim.state.lattice_scale().map_err(|e| a.error_at(sw, e, "needs a lattice"))?,
        false => [1.0; 3],
    };
    let mut p = Args::from_words(params, cmd.span, SYNTAX);
    let dim = sim.state.dimension;
    sim.state.atoms.clear_ghosts();
    let members: Vec<usize> = (0..sim.state.atoms.nlocal).filter(|&i| sim.state.atoms.mask[i] & bit != 0).collect();
    if STYLES[style].0 == "move" {
        // one direction after the other, each variable evaluated on the positions the earlier
        // directions moved (LAMMPS); in 2d the z word is not read at all
        for (k, w) in params.iter().enumerate().take(dim) {
            let step = move_step(sim, w, ["dx", "dy", "dz"][k])?;
            let x = &mut sim.state.atoms.x;
            for &i in &members {
                x[i][k] += scale[k] * step.at(i);
            }
        }
    }
    let at = &mut sim.state.atoms;
    match STYLES[style].0 {
        "move" => {}
        "ramp" => {
            let ddim = p.choice("ddim", &["x", "y", "z"])?;
            let (dlo, dhi) = (scale[ddim] * p.f64("dlo")?, scale[ddim] * p.f64("dhi")?);
            let cdim = p.choice("dim", &["x", "y", "z"])?;
            let (clo, chi) = (scale[cdim] * p.f64("clo")?, scale[cdim] * p.f64("chi")?);
            if dim == 2 && ddim == 2 {
                return Err(p.error_at(&params[0], "displace_atoms ramp cannot displace along z in 2d", "z in 2d"));
            }
            for &i in &members {
                let fraction = ((at.x[i][cdim] - clo) / (chi - clo)).max(0.0).min(1.0);
                at.x[i][ddim] += dlo + fraction * (dhi - dlo);
            }
        }
        "random" => {
            let d = [scale[0] * p.f64("dx")?, scale[1] * p.f64("dy")?, scale[2] * p.f64("dz")?];
            check_z(dim, d[2], &params[2], "displace atoms")?;
            let seed = p.i64_in("seed", 1, i32::MAX as i64)? as i32;
            // reseeded from the seed and each atom's position: independent of atom order
            let mut rng = RanPark::new(seed);
            for &i in &members {
                rng.reset_coord(seed, at.x[i]);
                for k in 0..3 {
                    at.x[i][k] += d[k] * 2.0 * (rng.uniform() - 0.5);
                }
            }
        }
        _ => {
            let point = [scale[0] * p.f64("Px")?, scale[1] * p.f64("Py")?, scale[2] * p.f64("Pz")?];
            let axis = [p.f64("Rx")?, p.f64("Ry")?, p.f64("Rz")?];
            let theta = p.f64("theta")?;
            if dim == 2 && (axis[0] != 0.0 || axis[1] != 0.0) {
                return Err(p.error_at(&params[3], "invalid displace_atoms rotate axis for 2d: it must be (0,0,Rz)", "axis not along z"));
            }
            let len = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
            if len == 0.0 {
                return Err(p.error_at(&params[3], "zero length rotation vector with displace_atoms", "zero axis"));
            }
            let r = [axis[0] / len, axis[1] / len, axis[2] / len];
            let angle = std::f64::consts::PI * theta / 180.0;
            let (cosine, sine) = (angle.cos(), angle.sin());
            let dom = sim.state.domain.as_ref().unwrap();
            for &i in &members {
                // rotate the unwrapped position; its image flags restart at 0
                let x = dom.unmap(at.x[i], at.image[i]);
                at.image[i] = [0; 3];
                let (c, disp) = crate::engine::quat::rotate_about_axis(&point, &r, &x, sine, cosine);
                at.x[i] = [point[0] + c[0] + disp[0], point[1] + c[1] + disp[1], x[2]];
                if dim == 3 {
                    at.x[i][2] = point[2] + c[2] + disp[2];
                }
            }
        }
    }
    let mut d = sim.state.domain.clone().unwrap();
    for &i in &members {
        if !at.x[i].iter().all(|c| c.is_finite()) {
            return Err(Diagnostic::at(cmd.span, format!("displace_atoms moves atom {} to a non-finite position {:?}", at.tag[i], at.x[i]), "non-finite position"));
        }
    }
    // LAMMPS remaps every owned atom back into a periodic box, updating image flags, and
    // shrink-wraps the box around them
    crate::engine::boundary::remap_and_migrate(&mut d, sim.state.box_initial.as_ref(), at);
    sim.state.domain = Some(d);
    sim.state.lists_valid = false;
    Ok(())
}

/// One direction's displacement of `move`, unscaled: a number, or `v_name` of an equal-style
/// variable (one value) or an atom-style one (a value per owned atom).
fn move_step(sim: &mut Simulation, w: &Word, what: &str) -> DResult<SetValue> {
    match w.text.starts_with("v_") {
        true => equal_or_atom_variable(sim, w, "displace_atoms"),
        false => Args::from_words(std::slice::from_ref(w), w.span, SYNTAX).f64(what).map(SetValue::One),
    }
}

/// LAMMPS refuses a z displacement in 2d.
fn check_z(dim: usize, dz: f64, w: &Word, what: &str) -> DResult<()> {
    match dim == 2 && dz != 0.0 {
        true => Err(Diagnostic::at(w.span, format!("must not {what} in z-direction with 2d system"), "nonzero dz in 2d")),
        false => Ok(()),
    }
}
