//! `fix ID group gravity magnitude vector x y z | chute angle | spherical phi theta`:
//! f += m * g (acceleration `magnitude` along the normalised direction, LAMMPS' arithmetic).
//! `disable`: no force on the atoms (nor energy); the acceleration is still evaluated every
//! step for the fixes that read it (a rigid fix's `gravity` keyword).

use super::value::FixValue;
use super::{Fix, FixCtx, FixHooks, ThermoTally};
use crate::engine::par::{ranges, AtomsMut};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group gravity magnitude vector x y z | chute angle | spherical phi theta [disable]";

/// What a fix gravity applies: the acceleration magnitude (None when a variable gives it) along
/// the unit direction `dir`, and the acceleration vector of the last force step (LAMMPS' gvec).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gravity {
    pub magnitude: Option<f64>,
    pub dir: [f64; 3],
    pub acc: [f64; 3],
}

pub struct FixGravity {
    id: String,
    groupbit: u32,
    magnitude: FixValue,
    dir: [f64; 3],
    /// The acceleration vector of the last force step.
    acc: [f64; 3],
    /// `disable`: the atoms get no force.
    disable: bool,
    /// Energy only (LAMMPS: no virial).
    tally: ThermoTally,
}

impl FixGravity {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let w = a.word("magnitude")?;
        let magnitude = FixValue::parse(w, "magnitude", false).map_err(|d| d.with_help(format!("syntax: {SYNTAX}")))?;
        let deg = std::f64::consts::PI / 180.0;
        let three_d = state.dimension == 3;
        let dir = match a.choice("direction style", &["vector", "chute", "spherical"])? {
            0 => {
                let (x, y, z) = (a.f64("x")?, a.f64("y")?, a.f64("z")?);
                if three_d {
                    let len = (x * x + y * y + z * z).sqrt();
                    [x / len, y / len, z / len]
                } else {
                    let len = (x * x + y * y).sqrt();
                    [x / len, y / len, 0.0]
                }
            }
            1 => {
                let angle = a.f64("angle")?;
                let (phi, theta) = (0.0, 180.0 - angle);
                angles(phi, theta, deg, three_d)
            }
            _ => {
                let (phi, theta) = (a.f64("phi")?, a.f64("theta")?);
                angles(phi, theta, deg, three_d)
            }
        };
        if !dir.iter().all(|v| v.is_finite()) {
            return Err(a.error_at(&args[1], "gravity direction has zero length", "zero vector"));
        }
        let mut disable = false;
        while let Some(w) = a.peek() {
            if w.text != "disable" {
                return Err(a.unknown_keyword(w, &["disable"]));
            }
            a.skip(1);
            disable = true;
        }
        // LAMMPS sets the acceleration at init already (a rigid fix may read it before this
        // fix's first post_force)
        let acc = match magnitude {
            FixValue::Const(g) => [g * dir[0], g * dir[1], g * dir[2]],
            _ => [0.0; 3],
        };
        Ok(FixGravity { id, groupbit, magnitude, dir, acc, disable, tally: ThermoTally::default() })
    }
}

fn angles(phi: f64, theta: f64, deg: f64, three_d: bool) -> [f64; 3] {
    if three_d {
        [(deg * theta).sin() * (deg * phi).cos(), (deg * theta).sin() * (deg * phi).sin(), (deg * theta).cos()]
    } else {
        [(deg * theta).sin(), (deg * theta).cos(), 0.0]
    }
}

impl Fix for FixGravity {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "gravity"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    fn post_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        let g = ctx.value(state, self, &self.magnitude)?.unwrap_or(0.0);
        let acc = [g * self.dir[0], g * self.dir[1], g * self.dir[2]];
        self.acc = acc;
        if self.disable {
            return Ok(());
        }
        let per_atom = state.atoms.features.per_atom_mass();
        let a = &mut state.atoms;
        let n = a.nlocal;
        let (mask, typ, rmass, type_mass, groupbit) = (&a.mask[..n], &a.typ[..n], &a.rmass, &state.type_mass, self.groupbit);
        // atoms are independent: ranges in parallel (the energy is summed in `scalar`)
        ranges(n, 4096, AtomsMut::new(&mut a.f[..n]), |r, mut f| {
            let f = f.slice(r.clone());
            for (k, i) in r.enumerate() {
                if mask[i] & groupbit != 0 {
                    let m = if per_atom { rmass[i] } else { type_mass[typ[i]] };
                    f[k][0] += m * acc[0];
                    f[k][1] += m * acc[1];
                    f[k][2] += m * acc[2];
                }
            }
        });
        Ok(())
    }
    /// LAMMPS' egrav = -sum m (g . x) over the group, with the acceleration of the last force
    /// step, summed here in atom order (what LAMMPS sums in post_force: positions, masses and
    /// the group do not change between the force step and the end of the step, when thermo and
    /// variables read it).
    fn scalar(&self, state: &State) -> Option<f64> {
        if self.disable {
            return Some(0.0);
        }
        let a = &state.atoms;
        let per_atom = a.features.per_atom_mass();
        let [xacc, yacc, zacc] = self.acc;
        let mut egrav = 0.0;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit != 0 {
                let m = if per_atom { a.rmass[i] } else { state.type_mass[a.typ[i]] };
                let x = a.x[i];
                egrav -= m * (xacc * x[0] + yacc * x[1] + zacc * x[2]);
            }
        }
        // every rank's atoms
        Some(state.summed_over_ranks(egrav))
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
    fn gravity(&self) -> Option<Gravity> {
        let magnitude = match self.magnitude {
            FixValue::Const(g) => Some(g),
            _ => None,
        };
        Some(Gravity { magnitude, dir: self.dir, acc: self.acc })
    }
}
