//! `fix ID group property/atom name1 name2 ... [ghost yes|no]`: adds per-atom values to the
//! atoms (LAMMPS' fix property/atom), 0 until `set` gives them values:
//!
//! * `temperature`, `heatflow`: the granular heat conduction fields (pair granular `heat`
//!   models, fix heat/flow); the temperature is the one DMHS' models use as well;
//! * `d_NAME`, `i_NAME`: custom per-atom floating-point and integer values (integers kept as
//!   doubles), 0 for now: `set`, compute property/atom and dumps do not read them yet.
//!
//! `ghost yes` makes ghost images carry the custom values (temperature always travels: the heat
//! models read it on neighbours). `mol` gives an atom style without molecule IDs (sphere) the
//! molecule IDs, 0 until set (fix pour and deposit number their molecules); q, rmass and arrays
//! (`d2_`, `i2_`) are refused. `read_data ... fix ID NULL Section` gives the values from a data
//! file section, a line `atom-ID value1 value2 ...` per atom in the order of this fix's names
//! (LAMMPS' read_data_section). Unfixing removes the values.

use super::{Fix, FixHooks};
use crate::engine::fields::{HEATFLOW, TEMPERATURE};
use crate::engine::state::State;
use dmhs_parser::data_file::FixSection;
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};

pub const SYNTAX: &str = "fix ID group property/atom name1 name2 ... [ghost yes|no]  (names: mol temperature heatflow d_NAME i_NAME)";

pub struct FixPropertyAtom {
    id: String,
    groupbit: u32,
    /// The values in the command's order (a data file section's columns).
    columns: Vec<Column>,
}

/// One value of a fix property/atom: the molecule ID, or an extra array this fix made (and
/// whether it holds integers).
enum Column {
    Mol,
    Extra { name: String, int: bool },
}

impl FixPropertyAtom {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &mut State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        // (word, extra array name, carried by ghosts unless `ghost no`)
        let mut wanted: Vec<(&Word, String, bool)> = vec![];
        let mut columns: Vec<Column> = vec![];
        let mut ghost = false;
        let mut wants_mol = false;
        while let Some(w) = a.peek() {
            a.skip(1);
            let t = w.text.as_str();
            let (name, always_ghost) = match t {
                "temperature" => (TEMPERATURE.name.to_string(), true),
                "heatflow" => (HEATFLOW.name.to_string(), false),
                "ghost" => {
                    ghost = a.choice("ghost yes|no", &["yes", "no"])? == 0;
                    continue;
                }
                "mol" => {
                    // molecule IDs for an atom style without them (bodystyle molecule of fix
                    // rigid/small reads them); ghosts always carry them
                    if state.atoms.features.molecule || wants_mol {
                        return Err(a.error_at(w, "fix property/atom mol: the atoms already have molecule IDs", "defined twice"));
                    }
                    wants_mol = true;
                    columns.push(Column::Mol);
                    continue;
                }
                "q" | "rmass" => {
                    return Err(a.error_at(w, format!("fix property/atom {t} is not supported by dmhs"), "not supported").with_help("use an atom style that has it (e.g. atom_style full for mol and q, sphere for rmass)"));
                }
                _ if t.starts_with("d2_") || t.starts_with("i2_") => {
                    return Err(a.error_at(w, format!("per-atom arrays (`{t}`) of fix property/atom are not supported by dmhs"), "not supported").with_help("use one d_NAME or i_NAME per column"));
                }
                _ if (t.starts_with("d_") || t.starts_with("i_")) && t.len() > 2 => {
                    if !t[2..].chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
                        return Err(a.error_at(w, format!("custom per-atom name `{t}` may hold only letters, digits and underscores"), "bad name"));
                    }
                    (t.to_string(), false)
                }
                _ => return Err(a.error_at(w, format!("unknown fix property/atom value `{t}`"), "expected temperature, heatflow, d_NAME or i_NAME")),
            };
            if state.atoms.find_extra(&name).is_some() || wanted.iter().any(|(_, n, _)| *n == name) {
                return Err(a.error_at(w, format!("per-atom `{t}` already exists (another fix property/atom or a DMHS fix made it)"), "defined twice"));
            }
            columns.push(Column::Extra { name: name.clone(), int: t.starts_with("i_") });
            wanted.push((w, name, always_ghost));
        }
        if wanted.is_empty() && !wants_mol {
            return Err(a.missing("a per-atom value name (temperature, heatflow, d_NAME or i_NAME)"));
        }
        // new arrays are added without ghosts; the next run makes them again
        state.atoms.clear_ghosts();
        state.lists_valid = false;
        if wants_mol {
            let n = state.atoms.nlocal;
            state.atoms.features.molecule = true;
            state.atoms.molecule = vec![0; n];
        }
        for (_, name, always_ghost) in wanted {
            state.atoms.extra_field(&name, 1, always_ghost || ghost);
        }
        Ok(FixPropertyAtom { id, groupbit, columns })
    }

    /// The extra arrays this fix made.
    fn extras(&self) -> impl Iterator<Item = &str> {
        self.columns.iter().filter_map(|c| match c {
            Column::Mol => None,
            Column::Extra { name, .. } => Some(name.as_str()),
        })
    }
}

impl Fix for FixPropertyAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "property/atom"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks::default()
    }
    fn cleanup(&mut self, state: &mut State) {
        state.atoms.clear_ghosts();
        state.lists_valid = false;
        for n in self.extras() {
            state.atoms.remove_extra(n);
        }
    }
    /// LAMMPS' FixPropertyAtom::read_data_section: N + 1 values a line (a `#` comment counts
    /// as values, as LAMMPS 22 Jul 2025 reads it), the atom ID (plus the offset) between 1 and the largest atom ID; IDs of no atom
    /// are skipped; integers for mol and i_NAME.
    fn read_data_section(&mut self, state: &mut State, section: &FixSection, id_offset: i64) -> DResult<()> {
        let map = state.atoms.tag_map();
        let max_tag = state.atoms.max_tag();
        // (the extra array, None for the molecule ID; integer values)
        let cols: Vec<(Option<usize>, bool)> = self
            .columns
            .iter()
            .map(|c| match c {
                Column::Mol => Ok((None, true)),
                Column::Extra { name, int } => state.atoms.find_extra(name).map(|k| (Some(k), *int)).ok_or_else(|| Diagnostic::error(format!("fix {} property/atom: its per-atom `{name}` no longer exists", self.id))),
            })
            .collect::<DResult<_>>()?;
        for (span, words) in &section.lines {
            if words.len() != cols.len() + 1 {
                return Err(Diagnostic::at(*span, format!("Incorrect format in {} section of data file: expected an atom ID and {} values", section.name, cols.len()), format!("{} values", words.len())));
            }
            let int = |w: &Word| w.text.parse::<i64>().map_err(|_| Diagnostic::at(w.span, format!("expected an integer in the {} section, found `{}`", section.name, w.text), "not an integer"));
            let tag = int(&words[0])? + id_offset;
            if tag <= 0 || tag > max_tag {
                return Err(Diagnostic::at(words[0].span, format!("Invalid atom ID {tag} in {} section of data file", section.name), "no such atom ID"));
            }
            let Some(i) = map.get(tag) else { continue };
            for (w, &(k, is_int)) in words[1..].iter().zip(&cols) {
                let v = if is_int { int(w)? as f64 } else { w.text.parse::<f64>().map_err(|_| Diagnostic::at(w.span, format!("expected a number in the {} section, found `{}`", section.name, w.text), "not a number"))? };
                match k {
                    None => state.atoms.molecule[i] = v as i64,
                    Some(k) => state.atoms.extra[k].data[i] = v,
                }
            }
        }
        Ok(())
    }
    fn describe(&self) -> String {
        format!("fix {} property/atom {}", self.id, self.extras().collect::<Vec<_>>().join(" "))
    }
}
