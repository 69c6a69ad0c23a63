//! Errors for style names that dmhs does not implement: a LAMMPS style we lack is named as
//! such; an unknown name gets a "did you mean".

use dmhs_parser::commands::{is_lammps_style, StyleKind};
use dmhs_parser::suggest::did_you_mean_help;
use dmhs_parser::{Diagnostic, Word};

fn kind_of(category: &str) -> Option<StyleKind> {
    Some(match category {
        "pair" => StyleKind::Pair,
        "bond" => StyleKind::Bond,
        "angle" => StyleKind::Angle,
        "dihedral" => StyleKind::Dihedral,
        "improper" => StyleKind::Improper,
        "fix" => StyleKind::Fix,
        "compute" => StyleKind::Compute,
        "atom_style" => StyleKind::Atom,
        "region" => StyleKind::Region,
        "dump" => StyleKind::Dump,
        _ => return None,
    })
}

/// Styles LAMMPS has removed (LAMMPS 22 Jul 2025 refuses them too), and what replaces them.
const REMOVED: &[(&str, &str, &str)] = &[
    ("fix", "ave/spatial", "use `compute ID group chunk/atom bin/1d|bin/2d|bin/3d ...` and `fix ID group ave/chunk Nevery Nrepeat Nfreq chunkID value ...` (LAMMPS' examples/KAPPA and VISCOSITY decks do so now)"),
    ("fix", "ave/spatial/sphere", "use `compute ID group chunk/atom bin/sphere ...` and `fix ID group ave/chunk ...`"),
];

/// The error for `category` style `name` that is not in `supported`.
pub fn unsupported_style(category: &str, word: &Word, name: &str, supported: &[&str]) -> Diagnostic {
    if let Some((_, _, instead)) = REMOVED.iter().find(|(c, n, _)| *c == category && *n == name) {
        return Diagnostic::at(word.span, format!("{category} style `{name}` was removed from LAMMPS (\"This {category} style is no longer available\")"), "removed style").with_help(*instead);
    }
    let known = kind_of(category).map(|k| is_lammps_style(k, name)).unwrap_or(false);
    let mut d = if known {
        Diagnostic::at(word.span, format!("{category} style `{name}` is a LAMMPS style that dmhs does not support"), "not supported by dmhs")
    } else {
        let mut d = Diagnostic::at(word.span, format!("unknown {category} style `{name}`"), format!("not a {category} style"));
        if let Some(h) = did_you_mean_help(name, supported.iter().copied()) {
            d = d.with_help(h);
        }
        d
    };
    d = d.with_help(format!("supported {category} styles: {}", supported.join(", ")));
    d
}
