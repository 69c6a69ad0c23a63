//! `fix ID group spring tether K x y z R0` and `fix ID group spring couple group2 K x y z R0`:
//! a spring on the group's centre of mass, to a point (tether) or to the centre of mass of a
//! second group (couple), as LAMMPS' fix spring; x, y or z NULL leaves that direction free.
//! The force is spread over the atoms by mass. f_ID is the spring energy, f_ID[1..4] the force
//! on the group and its signed magnitude.

use super::{Fix, FixCtx, FixHooks, ThermoTally};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group spring tether K x y z R0 | couple group2 K x y z R0";

const SMALL: f64 = 1.0e-10;

pub struct FixSpring {
    id: String,
    groupbit: u32,
    /// The second group (couple), by name (looked up again at each run, as LAMMPS' init).
    group2: Option<(String, u32)>,
    k: f64,
    /// Centre or offset; None: that direction is free.
    c: [Option<f64>; 3],
    r0: f64,
    espring: f64,
    ftotal: [f64; 4],
    /// Energy only (LAMMPS: no virial).
    tally: ThermoTally,
}

impl FixSpring {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let couple = a.choice("spring style", &["tether", "couple"])? == 1;
        let group2 = if couple {
            let w = a.word("group2")?;
            let bit = state.groups.bit(&w.text).ok_or_else(|| a.error_at(w, format!("fix spring couple group `{}` does not exist", w.text), "unknown group"))?;
            if bit == groupbit {
                return Err(a.error_at(w, "the two groups of fix spring couple cannot be the same", "same group"));
            }
            Some((w.text.clone(), bit))
        } else {
            None
        };
        let k = a.f64("K")?;
        let mut c = [None; 3];
        for (d, what) in ["x", "y", "z"].iter().enumerate() {
            let w = a.peek().ok_or_else(|| a.missing(what))?;
            if w.text == "NULL" {
                a.skip(1);
            } else {
                c[d] = Some(a.f64(what)?);
            }
        }
        let r0 = a.f64_where("R0", ">= 0", |r| r >= 0.0)?;
        a.finish()?;
        Ok(FixSpring { id, groupbit, group2, k, c, r0, espring: 0.0, ftotal: [0.0; 4], tally: ThermoTally::default() })
    }
}

impl Fix for FixSpring {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "spring"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    /// LAMMPS applies it while minimizing (its energy counts only with fix_modify energy).
    fn min_role(&self) -> super::MinRole {
        super::MinRole::PostForce
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        if let Some((name, bit)) = self.group2.as_mut() {
            *bit = state.groups.bit(name).ok_or_else(|| format!("fix spring couple group `{name}` does not exist"))?;
        }
        Ok(())
    }
    fn post_force(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        let (xcm, masstotal) = state.group_xcm(self.groupbit);
        let (xcm2, masstotal2) = match self.group2 {
            Some((_, bit)) => state.group_xcm(bit),
            None => ([0.0; 3], 0.0),
        };
        let mut d = [0.0; 3];
        for k in 0..3 {
            d[k] = match (self.c[k], self.group2.is_some()) {
                (None, _) => 0.0,
                (Some(c), false) => xcm[k] - c,
                (Some(c), true) => xcm2[k] - xcm[k] - c,
            };
        }
        let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(SMALL);
        let dr = r - self.r0;
        let mut f = [self.k * d[0] * dr / r, self.k * d[1] * dr / r, self.k * d[2] * dr / r];
        // tether: the force on the group pulls it back; couple: group 1 is pulled towards group 2
        let sign = if self.group2.is_some() { 1.0 } else { -1.0 };
        self.ftotal = [sign * f[0], sign * f[1], sign * f[2], (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt()];
        if dr < 0.0 {
            self.ftotal[3] = -self.ftotal[3];
        }
        self.espring = 0.5 * self.k * dr * dr;
        let f2 = [f[0] / masstotal2, f[1] / masstotal2, f[2] / masstotal2];
        for v in &mut f {
            *v /= masstotal;
        }
        let bit2 = self.group2.as_ref().map_or(0, |g| g.1);
        for i in 0..state.atoms.nlocal {
            let mask = state.atoms.mask[i];
            if mask & (self.groupbit | bit2) == 0 {
                continue;
            }
            let m = state.mass(i);
            let fi = &mut state.atoms.f[i];
            if mask & self.groupbit != 0 {
                if bit2 == 0 {
                    fi[0] -= f[0] * m;
                    fi[1] -= f[1] * m;
                    fi[2] -= f[2] * m;
                } else {
                    fi[0] += f[0] * m;
                    fi[1] += f[1] * m;
                    fi[2] += f[2] * m;
                }
            }
            if mask & bit2 != 0 {
                fi[0] -= f2[0] * m;
                fi[1] -= f2[1] * m;
                fi[2] -= f2[2] * m;
            }
        }
        Ok(())
    }
    fn scalar(&self, _state: &State) -> Option<f64> {
        Some(self.espring)
    }
    fn vector(&self, _state: &State, i: usize) -> Option<f64> {
        (1..=4).contains(&i).then(|| self.ftotal[i - 1])
    }
    fn size_vector(&self) -> usize {
        4
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
