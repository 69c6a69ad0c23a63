//! Follow-on errors in keep-going mode (`dmhs check`): when a command that defines something
//! (a style, a fix, a region, a variable, the box, ...) is refused, a later command that fails
//! only because that definition is missing is not a second mistake of the user. Such errors
//! are kept apart as notes that point at the refused definition.

use crate::span::Span;

/// What a refused command would have defined.
#[derive(Clone, Debug, PartialEq)]
enum Key {
    /// `pair`, `bond`, `angle`, `dihedral`, `improper`: its `X_style`.
    Style(String),
    /// A fix, compute, region, group, dump or variable with its ID or name.
    Named(&'static str, String),
    /// The simulation box (create_box, read_data, read_restart).
    Box,
    /// The lattice.
    Lattice,
}

/// The definitions refused so far, each with where its command was.
#[derive(Default)]
pub struct Refused {
    keys: Vec<(Key, Span)>,
}

/// What `words` (a command's words, name first) defines.
fn defined_by(words: &[&str]) -> Vec<Key> {
    let id = |k: usize| words.get(k).map(|s| s.to_string());
    let named = |kind: &'static str, k: usize| id(k).map(|n| Key::Named(kind, n)).into_iter().collect();
    match words.first().copied() {
        Some(s) if s.ends_with("_style") && ["pair_style", "bond_style", "angle_style", "dihedral_style", "improper_style"].contains(&s) => {
            vec![Key::Style(s.trim_end_matches("_style").to_string())]
        }
        Some("fix") => named("fix", 1),
        Some("compute") => named("compute", 1),
        Some("region") => named("region", 1),
        Some("dump") => named("dump", 1),
        Some("variable") => named("variable", 1),
        // `group all ...` cannot undefine the group all
        Some("group") if words.get(1) != Some(&"all") => named("group", 1),
        Some("create_box" | "read_data" | "read_restart") => vec![Key::Box],
        Some("lattice") => vec![Key::Lattice],
        _ => vec![],
    }
}

/// Whether a failure of the command `words` (its text before substitution in `raw`) with
/// `message` follows from the refused definition `key`.
fn follows(key: &Key, words: &[&str], raw: &str, message: &str) -> bool {
    let cmd = words.first().copied().unwrap_or("");
    let args = words.get(1..).unwrap_or(&[]);
    // `v_n` or `c_n[1]` in the command or its message, but not `v_nn`
    let mentions = |prefix: &str, id: &str| [raw, message].iter().any(|t| names(t, &format!("{prefix}{id}")));
    match key {
        Key::Style(kind) => {
            cmd == format!("{kind}_coeff") || cmd == format!("{kind}_modify") || message.contains(&format!("{kind}_style")) || message.contains(&format!("no {kind} style"))
        }
        Key::Named(kind, id) => match *kind {
            "fix" => mentions("f_", id) || (["unfix", "fix_modify"].contains(&cmd) && args.first() == Some(&id.as_str())),
            "compute" => mentions("c_", id) || (["uncompute", "compute_modify"].contains(&cmd) && args.first() == Some(&id.as_str())),
            "dump" => ["undump", "dump_modify"].contains(&cmd) && args.first() == Some(&id.as_str()),
            "variable" => mentions("v_", id) || raw.contains(&format!("${{{id}}}")) || (id.len() == 1 && raw.contains(&format!("${id}"))),
            // a region or group is named by an argument of the command using it
            _ => args.iter().any(|a| a == id) && message.contains(id.as_str()),
        },
        Key::Box => message.contains("before the simulation box is defined"),
        Key::Lattice => message.contains("lattice"),
    }
}

/// Whether `text` holds `name` as a whole word (not inside a longer name).
fn names(text: &str, name: &str) -> bool {
    let word = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_');
    text.match_indices(name).any(|(at, _)| !word(text[..at].chars().last()) && !word(text[at + name.len()..].chars().next()))
}

impl Refused {
    /// Records what a refused command would have defined.
    pub fn refuse(&mut self, words: &[&str], at: Span) {
        for k in defined_by(words) {
            self.keys.push((k, at));
        }
    }

    /// The refused definition a failure of `words` follows from, if any.
    pub fn cause(&self, words: &[&str], raw: &str, message: &str) -> Option<Span> {
        self.keys.iter().find(|(k, _)| follows(k, words, raw, message)).map(|(_, s)| *s)
    }

    /// A definition made later (e.g. a second, valid `pair_style`) ends the excuse.
    pub fn defined(&mut self, words: &[&str]) {
        let keys = defined_by(words);
        self.keys.retain(|(k, _)| !keys.contains(k));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::span::FileId;

    #[test]
    fn follow_ons_of_refused_definitions() {
        let at = Span::new(FileId(0), 0, 1);
        let mut r = Refused::default();
        r.refuse(&["pair_style", "lj/cutt", "2.5"], at);
        r.refuse(&["region", "box", "blok", "0", "1"], at);
        r.refuse(&["variable", "n", "equal", "1+"], at);
        r.refuse(&["fix", "1", "all", "nvee"], at);
        assert!(r.cause(&["pair_coeff", "1", "1", "1", "1"], "pair_coeff 1 1 1 1", "pair_coeff used before pair_style").is_some());
        assert!(r.cause(&["create_box", "1", "box"], "create_box 1 box", "region box is not defined").is_some());
        assert!(r.cause(&["print", "x"], "print $(v_n+1)", "variable n is not defined").is_some());
        assert!(r.cause(&["print", "x"], "print ${n}", "variable n is not defined").is_some());
        assert!(r.cause(&["thermo_style", "custom", "f_1"], "thermo_style custom f_1", "no fix with ID 1").is_some());
        // unrelated errors stay errors
        assert!(r.cause(&["mass", "1", "abc"], "mass 1 abc", "expected a number, found `abc`").is_none());
        assert!(r.cause(&["print", "x"], "print $(v_nn+1)", "variable nn is not defined").is_none());
        assert!(r.cause(&["thermo_style", "custom", "f_10"], "thermo_style custom f_10", "no fix with ID 10").is_none());
        r.defined(&["pair_style", "lj/cut", "2.5"]);
        assert!(r.cause(&["pair_coeff", "1", "1", "x"], "pair_coeff 1 1 x", "expected a number").is_none());
    }
}
