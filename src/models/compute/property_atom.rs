//! `compute ID group property/atom name1 name2 ...`: per-atom attributes (0 outside the group).

use super::{property::Field, Compute, PerAtom};
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "compute ID group property/atom input1 input2 ...  (id mol type mass x y z xu ix vx fx q radius rho esph ...)";

pub struct ComputePropertyAtom {
    id: String,
    groupbit: u32,
    fields: Vec<Field>,
}

impl ComputePropertyAtom {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, world: &World) -> DResult<Self> {
        let a = Args::from_words(args, cmd.span, SYNTAX);
        if args.is_empty() {
            return Err(a.missing("an attribute name"));
        }
        let mut fields = Vec::new();
        for w in args {
            let f = Field::parse(&w.text).ok_or_else(|| a.error_at(w, format!("unknown per-atom attribute `{}`", w.text), "not an attribute"))?;
            f.check(world.state).map_err(|e| a.error_at(w, e, "not available"))?;
            fields.push(f);
        }
        Ok(ComputePropertyAtom { id, groupbit, fields })
    }
}

impl Compute for ComputePropertyAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "property/atom"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn peratom_cols(&self) -> Option<usize> {
        Some(self.fields.len())
    }
    fn peratom(&self, w: &World) -> Result<PerAtom, String> {
        let n = w.state.atoms.nlocal;
        let cols = self.fields.len();
        let mut data = vec![0.0; n * cols];
        for i in 0..n {
            if w.state.atoms.mask[i] & self.groupbit != 0 {
                for (c, f) in self.fields.iter().enumerate() {
                    data[i * cols + c] = f.value(w.state, i);
                }
            }
        }
        Ok(PerAtom { cols, data })
    }
}
