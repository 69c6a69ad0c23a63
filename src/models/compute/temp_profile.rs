//! `compute ID group temp/profile xflag yflag zflag x|y|z|xy|yz|xz|xyz N... [out tensor]`: the
//! temperature after each spatial bin's mean velocity (of the flagged components) is taken away,
//! as LAMMPS' compute_temp_profile.cpp: bins evenly over the box, periodic coordinates folded
//! in; dof = dim N - extra - fixes' dof - (flagged components x bins); the vector is the kinetic
//! tensor of the thermal velocities; thermostats given it with `fix_modify temp` remove and
//! restore the bias. `out bin` (the per-bin array) is refused.

use super::temp_bias::{Bias, ComputeTempBias, Profile};
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

const SYNTAX: &str = "compute ID group temp/profile xflag yflag zflag x|y|z|xy|yz|xz|xyz Nx|Ny|Nz ... [out tensor]";

pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<ComputeTempBias> {
    let mut a = Args::from_words(args, cmd.span, SYNTAX);
    let mut flags = [false; 3];
    for (k, name) in ["xflag", "yflag", "zflag"].iter().enumerate() {
        flags[k] = a.i64_in(name, 0, 1)? == 1;
    }
    let two_d = w.state.dimension == 2;
    if flags[2] && two_d {
        return Err(a.error_at(&args[2], "Compute temp/profile cannot use vz for 2d systems", "must be 0 in 2d"));
    }
    const BINSTYLES: [&str; 7] = ["x", "y", "z", "xy", "yz", "xz", "xyz"];
    let style_word = a.peek().cloned();
    let style = BINSTYLES[a.choice("bin style", &BINSTYLES)?];
    if style.contains('z') && two_d {
        return Err(a.error_at(style_word.as_ref().expect("read above"), "Compute temp/profile cannot bin z for 2d systems", "no z bins in 2d"));
    }
    let mut nbin = [1usize; 3];
    for c in style.chars() {
        let k = (c as u8 - b'x') as usize;
        nbin[k] = a.usize_min(&format!("N{c}"), 1)?;
    }
    // the bins' velocity sums and counts (4 doubles each)
    let bins = nbin.iter().map(|&n| n as f64).product::<f64>();
    crate::engine::memory::check_fits(bins * 4.0 * 8.0, &format!("compute temp/profile: {bins:.4e} bins x 4 doubles"))
        .map_err(|m| a.error_at(a.last().expect("a bin count was read"), m, "too many bins"))?;
    while let Some(k) = a.peek() {
        a.skip(1);
        match k.text.as_str() {
            "out" => {
                if a.choice("out", &["tensor", "bin"])? == 1 {
                    return Err(a.error_at(a.last().expect("read"), "compute temp/profile out bin (the per-bin array) is not supported by dmhs", "use out tensor"));
                }
            }
            _ => return Err(a.unknown_keyword(k, &["out"])),
        }
    }
    Ok(ComputeTempBias::new(id, "temp/profile", groupbit, Bias::Profile(Profile { flags, nbin })))
}
