//! Twisting sub-models of `pair_style granular` (LAMMPS gran_sub_mod_twisting.cpp): a torque
//! about the normal from the relative spin (omega_i - omega_j).n (LAMMPS' `marshall` and `sds`
//! keep 1 history value). dmhs has none yet: the table is empty, and `twisting NAME` is refused
//! with a located error.

use super::Style;

/// No twisting model is supported yet (an empty enum: the contact's twisting branch compiles away).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Twisting {}

/// The twisting models dmhs supports.
pub static STYLES: &[Style<Twisting>] = &[];

/// What a twisting model reads of the contact.
pub struct TwistingIn {
    /// relative spin about the normal, (omega_i - omega_j).n
    pub magtwist: f64,
    pub fncrit: f64,
    /// contact radius
    pub a: f64,
    /// the tangential damping x_gt eta_n
    pub tangential_damp: f64,
    pub update: bool,
    pub dt: f64,
}

impl Twisting {
    /// The twisting torque about n on i; `h` is this model's history.
    #[inline(always)]
    pub fn torque(&self, _t: &TwistingIn, _h: &mut [f64]) -> f64 {
        match *self {}
    }
}
