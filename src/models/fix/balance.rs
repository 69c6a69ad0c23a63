//! `fix ID group balance Nfreq thresh style args ... [keywords]`: LAMMPS' periodic load
//! balancing of MPI sub-domains. dmhs runs one process (with threads), so there is nothing to
//! balance: the fix is accepted (its arguments checked for shape) and does nothing; `dmhs check`
//! says so.

use super::{Fix, FixHooks};
use crate::engine::state::State;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group balance Nfreq thresh shift|rcb args ... [keyword value ...]";

pub struct FixBalance {
    id: String,
    groupbit: u32,
}

impl FixBalance {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &mut State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        a.i64_in("Nfreq", 0, i64::MAX)?;
        a.f64_where("thresh", "thresh >= 1.0", |t| t >= 1.0)?;
        a.choice("balance style", &["shift", "rcb"])?;
        state.messages.push(format!("note: fix {id} balance does nothing: dmhs runs one process, which has nothing to balance"));
        Ok(FixBalance { id, groupbit })
    }
}

impl Fix for FixBalance {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "balance"
    }
    fn changes_box(&self) -> bool {
        true
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks::default()
    }
}
