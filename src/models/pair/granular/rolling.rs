//! Rolling sub-models of `pair_style granular` (LAMMPS gran_sub_mod_rolling.cpp): a resistance
//! to the rolling velocity v_rl = R_eff (omega_i - omega_j) x n, giving a torque R_eff n x F_r
//! (LAMMPS' `sds` has a spring of 3 history values). dmhs has none yet: the table is empty, and
//! `rolling NAME` is refused with a located error.

use super::Style;

/// No rolling model is supported yet (an empty enum: the contact's rolling branch compiles away).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Rolling {}

/// The rolling models dmhs supports.
pub static STYLES: &[Style<Rolling>] = &[];

/// What a rolling model reads of the contact.
pub struct RollingIn<'a> {
    /// rolling velocity R_eff (omega_i - omega_j) x n
    pub vrl: &'a [f64; 3],
    pub nx: &'a [f64; 3],
    pub fncrit: f64,
    pub update: bool,
    pub dt: f64,
}

impl Rolling {
    /// F_r (the torque on i is R_eff n x F_r); `h` is this model's history.
    #[inline(always)]
    pub fn force(&self, _r: &RollingIn, _h: &mut [f64]) -> [f64; 3] {
        match *self {}
    }
}
