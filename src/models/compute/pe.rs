//! `compute ID all pe [pair] [bond] [angle] [dihedral]`: potential energy of the last force
//! evaluation that tallied energies.

use super::Compute;
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "compute ID all pe [pair] [bond] [angle] [dihedral] [improper] [kspace] [fix]";

pub struct ComputePe {
    id: String,
    pair: bool,
    bond: bool,
    angle: bool,
    dihedral: bool,
    /// Fix energies under `fix_modify energy yes`.
    fix: bool,
}

impl ComputePe {
    pub fn new(id: String) -> Self {
        ComputePe { id, pair: true, bond: true, angle: true, dihedral: true, fix: true }
    }
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        if groupbit != 1 {
            return Err(a.error_at(&cmd.args[1], "compute pe must use group all", "must be `all`"));
        }
        if a.is_empty() {
            return Ok(Self::new(id));
        }
        let mut c = ComputePe { id, pair: false, bond: false, angle: false, dihedral: false, fix: false };
        while !a.is_empty() {
            match a.choice("energy term", &["pair", "bond", "angle", "dihedral", "improper", "kspace", "fix"])? {
                0 => c.pair = true,
                1 => c.bond = true,
                2 => c.angle = true,
                3 => c.dihedral = true,
                6 => c.fix = true,
                _ => {}
            }
        }
        Ok(c)
    }
}

impl Compute for ComputePe {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "pe"
    }
    fn groupbit(&self) -> u32 {
        1
    }
    fn scalar(&self, w: &World) -> Result<f64, String> {
        let e = &w.state.energies;
        let mut s = 0.0;
        if self.pair {
            s += e.pair.evdwl + e.pair.ecoul;
        }
        if self.bond {
            s += e.ebond;
        }
        if self.angle {
            s += e.eangle;
        }
        if self.dihedral {
            s += e.edihed;
        }
        if self.fix {
            if let Some(f) = w.fix_energy() {
                s += f;
            }
        }
        Ok(s)
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
}
