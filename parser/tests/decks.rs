//! Good and bad decks under tests/decks/.
//!
//! * good/*.in run without error and put on the screen exactly what LAMMPS 22 Jul 2025 prints
//!   for them (good/*.in.out, made with `lmp -in good/x.in [-var ...]` from parser/). A
//!   `# vars: NAME VALUE ...` line gives the `-var` overrides.
//! * bad/*.in each carry `# expect: LINE:COL message` lines, one per diagnostic the deck must
//!   produce (location of the primary label, and text the message contains), and
//!   `# also: text` lines that must appear somewhere in the rendered diagnostics.

mod common;

use common::TestHost;
use dmhs_parser::interp::{Exit, Interpreter};
use std::path::PathBuf;

/// The decks of a folder, as paths relative to the package root (the tests' working directory).
fn decks(folder: &str) -> Vec<String> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/decks").join(folder);
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".in"))
        .map(|n| format!("tests/decks/{folder}/{n}"))
        .collect();
    names.sort();
    names
}

fn header_values<'a>(text: &'a str, key: &str) -> Vec<&'a str> {
    text.lines().filter_map(|l| l.strip_prefix(key)).map(str::trim).collect()
}

#[test]
fn good_decks_print_what_lammps_prints() {
    let mut failures = vec![];
    for path in decks("good") {
        let text = std::fs::read_to_string(&path).unwrap();
        let mut host = TestHost::new();
        for line in header_values(&text, "# vars:") {
            let w: Vec<&str> = line.split_whitespace().collect();
            for pair in w.chunks(2) {
                host.vars.define_index(pair[0], vec![pair[1].to_string()]);
            }
        }
        let mut interp = Interpreter::new();
        match interp.run_file(&path, &mut host) {
            Err(ds) => failures.push(format!("{path}: {}", common::render(&interp, &ds))),
            Ok(out) => {
                let expected = std::fs::read_to_string(format!("{path}.out")).unwrap();
                if host.screen != expected {
                    failures.push(format!("{path}: screen differs\n--- ours\n{}--- lammps\n{}", host.screen, expected));
                }
                let quits = text.lines().any(|l| l.trim() == "quit");
                if quits != (out.exit == Exit::Quit(0)) {
                    failures.push(format!("{path}: exit {:?}", out.exit));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn bad_decks_report_the_expected_diagnostics() {
    let mut failures = vec![];
    for path in decks("bad") {
        let text = std::fs::read_to_string(&path).unwrap();
        let expects: Vec<(String, &str)> = header_values(&text, "# expect:")
            .into_iter()
            .map(|e| {
                let (loc, msg) = e.split_once(' ').unwrap();
                (format!("{path}:{loc}"), msg)
            })
            .collect();
        assert!(!expects.is_empty(), "{path} has no # expect line");
        let mut host = TestHost { unsupported: vec!["minimize"], ..TestHost::new() };
        let mut interp = Interpreter::new();
        let ds = match interp.run_file(&path, &mut host) {
            Ok(_) => {
                failures.push(format!("{path}: ran without error"));
                continue;
            }
            Err(ds) => ds,
        };
        let rendered = common::render(&interp, &ds);
        if std::env::var_os("DMHS_SHOW_DIAGNOSTICS").is_some() {
            println!("{rendered}");
        }
        let located: Vec<(String, &str)> =
            ds.iter().map(|d| (d.primary_span().map(|s| interp.sources().location(s)).unwrap_or_default(), d.message.as_str())).collect();
        if ds.len() != expects.len() {
            failures.push(format!("{path}: {} diagnostics, {} expected\n{rendered}", ds.len(), expects.len()));
        }
        for (loc, msg) in &expects {
            if !located.iter().any(|(l, m)| l == loc && m.contains(msg)) {
                failures.push(format!("{path}: no diagnostic `{msg}` at {loc}\n{rendered}"));
            }
        }
        for also in header_values(&text, "# also:") {
            if !rendered.contains(also) {
                failures.push(format!("{path}: rendered diagnostics lack `{also}`\n{rendered}"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}
