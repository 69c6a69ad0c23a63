//! The names of every LAMMPS command and of every style per category, and the diagnostics
//! that tell a misspelled name ("unknown command") from a real LAMMPS name that dmhs does not
//! implement.
//!
//! The names are data (lammps_names/*.txt): the styles of the installed LAMMPS 22 Jul 2025
//! (`lammps().available_styles(category)`, `lmp -h`), the commands of `Input::execute_command`,
//! and the command and style lists of the LAMMPS manual for packages that build lacks.
//! Accelerated variants (`/omp`, `/opt`, `/kk`, `/gpu`, `/intel`) are recognised by suffix.

use crate::ast::Word;
use crate::diag::Diagnostic;
use crate::suggest::did_you_mean;
use std::sync::OnceLock;

/// A category of LAMMPS styles.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StyleKind {
    Atom,
    Pair,
    Bond,
    Angle,
    Dihedral,
    Improper,
    KSpace,
    Fix,
    Compute,
    Region,
    Dump,
    /// `run_style`
    Integrate,
    /// `min_style`
    Minimize,
}

impl StyleKind {
    pub const ALL: [StyleKind; 13] = [
        StyleKind::Atom,
        StyleKind::Pair,
        StyleKind::Bond,
        StyleKind::Angle,
        StyleKind::Dihedral,
        StyleKind::Improper,
        StyleKind::KSpace,
        StyleKind::Fix,
        StyleKind::Compute,
        StyleKind::Region,
        StyleKind::Dump,
        StyleKind::Integrate,
        StyleKind::Minimize,
    ];

    /// The command that names a style of this kind.
    pub fn command(self) -> &'static str {
        match self {
            StyleKind::Atom => "atom_style",
            StyleKind::Pair => "pair_style",
            StyleKind::Bond => "bond_style",
            StyleKind::Angle => "angle_style",
            StyleKind::Dihedral => "dihedral_style",
            StyleKind::Improper => "improper_style",
            StyleKind::KSpace => "kspace_style",
            StyleKind::Fix => "fix",
            StyleKind::Compute => "compute",
            StyleKind::Region => "region",
            StyleKind::Dump => "dump",
            StyleKind::Integrate => "run_style",
            StyleKind::Minimize => "min_style",
        }
    }

    /// The kind in words, for messages ("pair style", "fix style").
    pub fn noun(self) -> &'static str {
        match self {
            StyleKind::Atom => "atom style",
            StyleKind::Pair => "pair style",
            StyleKind::Bond => "bond style",
            StyleKind::Angle => "angle style",
            StyleKind::Dihedral => "dihedral style",
            StyleKind::Improper => "improper style",
            StyleKind::KSpace => "kspace style",
            StyleKind::Fix => "fix style",
            StyleKind::Compute => "compute style",
            StyleKind::Region => "region style",
            StyleKind::Dump => "dump style",
            StyleKind::Integrate => "run style",
            StyleKind::Minimize => "min style",
        }
    }

    fn data(self) -> &'static str {
        match self {
            StyleKind::Atom => include_str!("lammps_names/atom.txt"),
            StyleKind::Pair => include_str!("lammps_names/pair.txt"),
            StyleKind::Bond => include_str!("lammps_names/bond.txt"),
            StyleKind::Angle => include_str!("lammps_names/angle.txt"),
            StyleKind::Dihedral => include_str!("lammps_names/dihedral.txt"),
            StyleKind::Improper => include_str!("lammps_names/improper.txt"),
            StyleKind::KSpace => include_str!("lammps_names/kspace.txt"),
            StyleKind::Fix => include_str!("lammps_names/fix.txt"),
            StyleKind::Compute => include_str!("lammps_names/compute.txt"),
            StyleKind::Region => include_str!("lammps_names/region.txt"),
            StyleKind::Dump => include_str!("lammps_names/dump.txt"),
            StyleKind::Integrate => include_str!("lammps_names/integrate.txt"),
            StyleKind::Minimize => include_str!("lammps_names/minimize.txt"),
        }
    }

    fn index(self) -> usize {
        StyleKind::ALL.iter().position(|k| *k == self).unwrap_or(0)
    }
}

/// The names of a data file: one per line, `#` lines are comments; sorted for binary search.
fn parse_names(data: &'static str) -> Vec<&'static str> {
    let mut v: Vec<&'static str> =
        data.lines().map(str::trim).filter(|l| !l.is_empty() && !l.starts_with('#')).collect();
    v.sort_unstable();
    v.dedup();
    v
}

/// Every LAMMPS input-script command name, sorted.
pub fn lammps_commands() -> &'static [&'static str] {
    static NAMES: OnceLock<Vec<&'static str>> = OnceLock::new();
    NAMES.get_or_init(|| parse_names(include_str!("lammps_names/commands.txt")))
}

/// Every LAMMPS style name of a kind (without accelerator suffixes), sorted.
pub fn lammps_styles(kind: StyleKind) -> &'static [&'static str] {
    static NAMES: OnceLock<Vec<Vec<&'static str>>> = OnceLock::new();
    let all = NAMES.get_or_init(|| StyleKind::ALL.iter().map(|k| parse_names(k.data())).collect());
    &all[kind.index()]
}

/// True if `name` is a LAMMPS command (in any package).
pub fn is_lammps_command(name: &str) -> bool {
    lammps_commands().binary_search(&name).is_ok()
}

const ACCELERATOR_SUFFIXES: [&str; 7] = ["/kk/device", "/kk/host", "/kk", "/gpu", "/intel", "/omp", "/opt"];

/// `name` without an accelerator suffix (`lj/cut/omp` -> `lj/cut`).
pub fn strip_accelerator_suffix(name: &str) -> &str {
    ACCELERATOR_SUFFIXES.iter().find_map(|s| name.strip_suffix(s)).unwrap_or(name)
}

/// True if `name` is a LAMMPS style of this kind, possibly with an accelerator suffix.
pub fn is_lammps_style(kind: StyleKind, name: &str) -> bool {
    let names = lammps_styles(kind);
    names.binary_search(&name).is_ok() || names.binary_search(&strip_accelerator_suffix(name)).is_ok()
}

/// A close name, preferring one dmhs supports.
fn suggestion<'a>(name: &str, supported: &[&'a str], lammps: &'static [&'static str]) -> Option<&'a str> {
    did_you_mean(name, supported.iter().copied()).or_else(|| did_you_mean(name, lammps.iter().copied()))
}

/// The diagnostic for a command name dmhs cannot run: a LAMMPS command it does not
/// implement, or an unknown name with a did-you-mean over `supported` and all LAMMPS names.
pub fn unknown_command(word: &Word, supported: &[&str]) -> Diagnostic {
    let name = word.text.as_str();
    if is_lammps_command(name) {
        return Diagnostic::at(word.span, format!("`{name}` is a LAMMPS command that dmhs does not support"), "not supported by dmhs")
            .with_help("remove it, or run this input in LAMMPS");
    }
    let mut d = Diagnostic::at(word.span, format!("unknown command `{name}`"), "not a LAMMPS command");
    if let Some(s) = suggestion(name, supported, lammps_commands()) {
        d = d.with_help(format!("did you mean `{s}`?"));
    }
    d
}

/// The diagnostic for a style dmhs cannot build (`word` is the style name): a LAMMPS style it
/// does not implement ("`fix npt` is a LAMMPS style that dmhs does not support"), or an unknown
/// name with a did-you-mean. `supported` lists the styles of this kind dmhs has.
pub fn unknown_style(kind: StyleKind, word: &Word, supported: &[&str]) -> Diagnostic {
    let name = word.text.as_str();
    let cmd = kind.command();
    let list = || format!("dmhs supports these {}s: {}", kind.noun(), supported.join(", "));
    if is_lammps_style(kind, name) {
        let mut d = Diagnostic::at(word.span, format!("`{cmd} {name}` is a LAMMPS style that dmhs does not support"), "not supported by dmhs");
        let base = strip_accelerator_suffix(name);
        if base != name && supported.contains(&base) {
            d = d.with_help(format!("dmhs supports `{cmd} {base}`; accelerator suffixes are not needed"));
        } else if !supported.is_empty() {
            d = d.with_help(list());
        }
        return d;
    }
    let mut d = Diagnostic::at(word.span, format!("unknown {} `{name}`", kind.noun()), format!("not a LAMMPS {}", kind.noun()));
    if let Some(s) = suggestion(name, supported, lammps_styles(kind)) {
        d = d.with_help(format!("did you mean `{s}`?"));
    } else if !supported.is_empty() {
        d = d.with_help(list());
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::span::Span;

    fn w(s: &str) -> Word {
        Word::new(s, Span::default())
    }

    #[test]
    fn command_names() {
        for c in ["pair_style", "run", "fix", "variable", "read_data", "create_atoms", "reset_atoms", "kim", "labelmap", "temper"] {
            assert!(is_lammps_command(c), "{c}");
        }
        assert!(!is_lammps_command("pair_stlye"));
        assert!(!is_lammps_command("sph/taitwater"));
    }

    #[test]
    fn style_names() {
        assert!(is_lammps_style(StyleKind::Pair, "sph/taitwater/morris"));
        assert!(is_lammps_style(StyleKind::Pair, "lj/cut/omp"));
        assert!(is_lammps_style(StyleKind::Pair, "lj/cut/kk"));
        assert!(is_lammps_style(StyleKind::Fix, "sph/stationary"));
        assert!(is_lammps_style(StyleKind::Fix, "npt"));
        assert!(is_lammps_style(StyleKind::Compute, "property/atom"));
        assert!(is_lammps_style(StyleKind::Bond, "bpm/rotational"));
        assert!(is_lammps_style(StyleKind::Atom, "sph"));
        assert!(is_lammps_style(StyleKind::Region, "block"));
        assert!(is_lammps_style(StyleKind::Dump, "custom"));
        assert!(is_lammps_style(StyleKind::KSpace, "pppm"));
        assert!(!is_lammps_style(StyleKind::Region, "cube"));
        assert!(lammps_styles(StyleKind::Pair).len() > 250);
        assert!(lammps_styles(StyleKind::Fix).iter().all(|s| !s.ends_with("/omp")));
    }

    #[test]
    fn unknown_vs_unsupported() {
        let d = unknown_command(&w("pair_stlye"), &["pair_style", "units"]);
        assert_eq!(d.message, "unknown command `pair_stlye`");
        assert_eq!(d.help, vec!["did you mean `pair_style`?"]);
        let d = unknown_command(&w("minimize"), &["run"]);
        assert_eq!(d.message, "`minimize` is a LAMMPS command that dmhs does not support");
        let d = unknown_style(StyleKind::Fix, &w("npt"), &["nve", "sph"]);
        assert_eq!(d.message, "`fix npt` is a LAMMPS style that dmhs does not support");
        assert_eq!(d.help, vec!["dmhs supports these fix styles: nve, sph"]);
        let d = unknown_style(StyleKind::Pair, &w("sph/taitwatr"), &["sph/taitwater"]);
        assert_eq!(d.message, "unknown pair style `sph/taitwatr`");
        assert_eq!(d.help, vec!["did you mean `sph/taitwater`?"]);
        let d = unknown_style(StyleKind::Pair, &w("sph/taitwater/gpu"), &["sph/taitwater"]);
        assert!(d.help[0].contains("accelerator suffixes"));
    }
}
