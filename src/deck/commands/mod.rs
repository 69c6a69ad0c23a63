//! The engine side of the input script: every supported LAMMPS command, parsed from its words
//! into changes of the [`Simulation`]. Flow control (variable, if, jump, include, print, ...)
//! is the interpreter's (parser crate); everything else arrives here through [`Host`].

pub(crate) mod atoms_cmds;
mod box_cmds;
mod change_box;
mod displace;
mod forcefield;
mod min_cmds;
mod modify_cmds;
mod output_cmds;
mod replicate;
mod rerun_cmds;
mod run_cmds;
mod settings;
mod topology_cmds;

pub(crate) use settings::features_of;

use crate::sim::Simulation;
use dmhs_parser::{Command, DResult, Diagnostic, Host, SourceMap};

type Handler = fn(&mut Simulation, &Command, &mut SourceMap) -> DResult<()>;

/// Every command the engine implements, with its handler.
const COMMANDS: &[(&str, Handler)] = &[
    ("units", settings::units),
    ("clear", settings::clear),
    ("dimension", settings::dimension),
    ("boundary", settings::boundary),
    ("atom_style", settings::atom_style),
    ("atom_modify", settings::atom_modify),
    ("newton", settings::newton),
    ("processors", settings::processors),
    ("timestep", settings::timestep),
    ("neighbor", settings::neighbor),
    ("neigh_modify", settings::neigh_modify),
    ("comm_modify", settings::comm_modify),
    ("comm_style", settings::comm_style),
    ("balance", settings::balance),
    ("special_bonds", settings::special_bonds),
    ("log", settings::log),
    ("dmhs/stability", settings::dmhs_stability),
    ("lattice", box_cmds::lattice),
    ("region", box_cmds::region),
    ("create_box", box_cmds::create_box),
    ("create_atoms", box_cmds::create_atoms),
    ("delete_atoms", box_cmds::delete_atoms),
    ("displace_atoms", displace::displace_atoms),
    ("change_box", change_box::change_box),
    ("replicate", replicate::replicate),
    ("read_data", box_cmds::read_data),
    ("create_bonds", topology_cmds::create_bonds),
    ("delete_bonds", topology_cmds::delete_bonds),
    ("molecule", crate::deck::molecule::molecule),
    ("write_data", box_cmds::write_data),
    ("mass", atoms_cmds::mass),
    ("set", atoms_cmds::set),
    ("group", atoms_cmds::group),
    ("velocity", atoms_cmds::velocity),
    ("pair_style", forcefield::pair_style),
    ("pair_coeff", forcefield::pair_coeff),
    ("pair_modify", forcefield::pair_modify),
    ("bond_style", forcefield::bond_style),
    ("bond_coeff", forcefield::bond_coeff),
    ("angle_style", forcefield::angle_style),
    ("angle_coeff", forcefield::angle_coeff),
    ("dihedral_style", forcefield::dihedral_style),
    ("dihedral_coeff", forcefield::dihedral_coeff),
    ("fix", modify_cmds::fix),
    ("unfix", modify_cmds::unfix),
    ("compute", modify_cmds::compute),
    ("uncompute", modify_cmds::uncompute),
    ("compute_modify", modify_cmds::compute_modify),
    ("fix_modify", modify_cmds::fix_modify),
    ("thermo", output_cmds::thermo),
    ("thermo_style", output_cmds::thermo_style),
    ("thermo_modify", output_cmds::thermo_modify),
    ("dump", output_cmds::dump),
    ("undump", output_cmds::undump),
    ("dump_modify", output_cmds::dump_modify),
    ("write_dump", output_cmds::write_dump),
    ("run", run_cmds::run),
    ("run_style", run_cmds::run_style),
    ("minimize", min_cmds::minimize),
    ("min_style", min_cmds::min_style),
    ("min_modify", min_cmds::min_modify),
    ("reset_timestep", run_cmds::reset_timestep),
    ("read_dump", rerun_cmds::read_dump),
    ("rerun", rerun_cmds::rerun),
    ("write_restart", crate::deck::restart::write_restart),
    ("read_restart", crate::deck::restart::read_restart),
];

/// Commands that define the force field (replayed by read_restart).
const FORCE_FIELD: &[&str] = &[
    "pair_style",
    "pair_coeff",
    "pair_modify",
    "bond_style",
    "bond_coeff",
    "angle_style",
    "angle_coeff",
    "dihedral_style",
    "dihedral_coeff",
    "special_bonds",
];

/// Names of the supported commands (for `dmhs check` and docs).
pub fn supported_commands() -> impl Iterator<Item = &'static str> {
    COMMANDS.iter().map(|(n, _)| *n)
}

impl Host for Simulation {
    fn execute(&mut self, cmd: &Command, sources: &mut SourceMap) -> DResult<()> {
        if let Some(log) = self.command_log.as_mut() {
            let mut words = vec![cmd.name.text.clone()];
            words.extend(cmd.args.iter().map(|w| w.text.clone()));
            log.push(words);
        }
        match COMMANDS.iter().find(|(n, _)| *n == cmd.name()) {
            Some((_, handler)) => {
                handler(self, cmd, sources)?;
                if FORCE_FIELD.contains(&cmd.name()) {
                    // kept for write_restart, which stores the force field as its commands
                    let mut words = vec![cmd.name.text.clone()];
                    words.extend(cmd.args.iter().map(|w| w.text.clone()));
                    self.ff_commands.push(words);
                }
                Ok(())
            }
            None => Err(Diagnostic::at(cmd.name.span, format!("command `{}` is not supported by dmhs", cmd.name()), "not supported")),
        }
    }
    fn print(&mut self, text: &str) {
        self.out.print(text);
    }
    fn run_halted(&self) -> bool {
        self.state.halted
    }
    fn echo(&mut self, text: &str, screen: bool, log: bool) {
        self.out.print_to(text, screen, log);
    }
    fn supports_command(&self, name: &str) -> bool {
        COMMANDS.iter().any(|(n, _)| *n == name)
    }
    fn atom_ids(&mut self) -> (Vec<i64>, i64) {
        let a = &self.state.atoms;
        let mut max = [a.tag[..a.nlocal].iter().copied().max().unwrap_or(0) as f64];
        self.state.max_ranks(&mut max);
        (a.tag[..a.nlocal].to_vec(), max[0] as i64)
    }
}

impl Simulation {
    /// Execute one command (used for the coefficient sections of data files).
    pub fn execute_command(&mut self, cmd: &Command, sources: &mut SourceMap) -> DResult<()> {
        Host::execute(self, cmd, sources)
    }
}

/// Error unless the simulation box exists.
pub(crate) fn need_box(sim: &Simulation, cmd: &Command) -> DResult<()> {
    if sim.state.domain.is_none() {
        return Err(Diagnostic::at(cmd.name.span, format!("{} used before the simulation box is defined", cmd.name()), "no box yet")
            .with_help("define the box first with create_box or read_data"));
    }
    Ok(())
}

/// Error if the simulation box exists already.
pub(crate) fn before_box(sim: &Simulation, cmd: &Command) -> DResult<()> {
    if sim.state.domain.is_some() {
        return Err(Diagnostic::at(cmd.name.span, format!("{} must be used before the simulation box is defined", cmd.name()), "box already defined"));
    }
    Ok(())
}

/// Test helper: run a deck of plain commands (one per line, no `$` substitution or quotes).
#[cfg(test)]
pub(crate) fn run_plain(sim: &mut Simulation, text: &str) -> DResult<()> {
    use dmhs_parser::{FileId, Span, Word};
    let mut sources = SourceMap::new();
    let id = sources.add("test", text);
    let mut offset = 0usize;
    for line in text.split_inclusive('\n') {
        let body = line.split('#').next().unwrap();
        let mut words = vec![];
        let mut pos = 0;
        for w in body.split_whitespace() {
            let at = body[pos..].find(w).unwrap() + pos;
            pos = at + w.len();
            words.push(Word::new(w, Span::new(id, offset + at, offset + at + w.len())));
        }
        offset += line.len();
        if words.is_empty() {
            continue;
        }
        let span = words[0].span.to(words.last().unwrap().span);
        let cmd = Command { name: words.remove(0), args: words, span };
        sim.execute(&cmd, &mut sources).map_err(|d| {
            eprintln!("{}", d.render(&sources));
            d
        })?;
    }
    let _ = FileId(0);
    Ok(())
}
#[cfg(test)]
mod tests;
