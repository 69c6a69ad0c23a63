//! The reference decks of the project go through the interpreter unmodified, and give the
//! commands and the echo that LAMMPS 22 Jul 2025 gives for them (`lmp -echo screen -var nsteps 0`,
//! screen output stored next to the decks).

mod common;

use common::{render, TestHost};
use dmhs_parser::interp::{Exit, Interpreter};
use std::path::{Path, PathBuf};

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/decks/reference")
}

fn read(name: &str) -> String {
    std::fs::read_to_string(dir().join(name)).unwrap()
}

/// Run a deck with `-var` overrides and echo to the screen, as the stored LAMMPS runs were made.
fn run_deck(name: &str, vars: &[(&str, &str)]) -> TestHost {
    let mut host = TestHost::new();
    for (n, v) in vars {
        host.vars.define_index(n, vec![v.to_string()]);
    }
    let mut interp = Interpreter::new();
    interp.set_echo(true, false);
    let path = dir().join(name);
    let out = interp.run_file(path.to_str().unwrap(), &mut host).unwrap_or_else(|ds| panic!("{}", render(&interp, &ds)));
    assert_eq!(out.exit, Exit::EndOfInput);
    assert!(out.errors.is_empty());
    host
}

/// Every line we echo appears, in order, in what LAMMPS printed.
fn assert_echo_subsequence(ours: &str, lammps: &str) {
    let theirs: Vec<&str> = lammps.lines().collect();
    let mut k = 0;
    for line in ours.lines() {
        match theirs[k..].iter().position(|t| *t == line) {
            Some(p) => k += p + 1,
            None => panic!("echoed line not in LAMMPS output (in order): {line:?}"),
        }
    }
}

#[test]
fn stored_copies_are_the_shared_reference_decks() {
    let shared = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/reference/lammps-decks");
    for name in ["in.dambreak2d", "in.poiseuille2d"] {
        if let Ok(text) = std::fs::read_to_string(shared.join(name)) {
            assert_eq!(text, read(name), "{name} differs from shared/reference");
        }
    }
}

#[test]
fn dambreak_gives_the_commands_lammps_runs() {
    let host = run_deck("in.dambreak2d", &[("nsteps", "0")]);
    let expected: Vec<String> = read("in.dambreak2d.commands").lines().map(String::from).collect();
    assert_eq!(host.command_lines(), expected);
    // the immediate variables, printed with %.20g as LAMMPS prints them
    let region = &host.executed[6];
    assert_eq!(
        region.arg_strs(),
        ["box", "block", "-0.035000000000000003331", "3.2550000000000003375", "-0.035000000000000003331", "1.8", "-0.0050000000000000001041", "0.0050000000000000001041", "units", "box"]
    );
    assert_echo_subsequence(&host.screen, &read("in.dambreak2d.lmp-screen"));
}

#[test]
fn dambreak_takes_the_then_branch_with_rhosum() {
    let host = run_deck("in.dambreak2d", &[("nsteps", "0"), ("rhosum", "1")]);
    let lines = host.command_lines();
    let k = lines.iter().position(|l| l.starts_with("pair_style")).unwrap();
    assert_eq!(
        &lines[k..k + 3],
        [
            "pair_style hybrid/overlay sph/rhosum 1 sph/taitwater",
            "pair_coeff * * sph/taitwater 1000 20 0.1 0.03",
            "pair_coeff 1 1 sph/rhosum 0.03"
        ]
    );
    assert_echo_subsequence(&host.screen, &read("in.dambreak2d.rhosum1.lmp-screen"));
}

#[test]
fn poiseuille_gives_the_commands_lammps_runs() {
    let host = run_deck("in.poiseuille2d", &[("nsteps", "0")]);
    let expected: Vec<String> = read("in.poiseuille2d.commands").lines().map(String::from).collect();
    assert_eq!(host.command_lines(), expected);
    assert_echo_subsequence(&host.screen, &read("in.poiseuille2d.lmp-screen"));
}

#[test]
fn default_step_count_comes_from_the_index_variable() {
    let host = run_deck("in.poiseuille2d", &[]);
    assert_eq!(host.command_lines().last().unwrap(), "run 1000");
}

#[test]
fn word_spans_point_at_what_was_written() {
    let mut host = TestHost::new();
    let mut interp = Interpreter::new();
    let path = dir().join("in.dambreak2d");
    interp.run_file(path.to_str().unwrap(), &mut host).unwrap();
    let sm = interp.sources();
    let region = &host.executed[6];
    assert_eq!(sm.snippet(region.args[2].span), "$(-3.5*v_dx)");
    assert_eq!(sm.snippet(region.args[5].span), "${H}");
    assert!(sm.location(region.args[2].span).ends_with("in.dambreak2d:23:24"));
    // a command from a quoted `if` branch points into the quotes
    let pc = host.executed.iter().find(|c| c.name() == "pair_coeff").unwrap();
    assert_eq!(sm.snippet(pc.args[2].span), "${rho0}");
    assert!(sm.location(pc.name.span).ends_with("in.dambreak2d:45:4"), "{}", sm.location(pc.name.span));
}
