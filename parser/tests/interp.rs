//! Interpreter behaviour through its public API (the decks in tests/decks cover the rest).

mod common;

use common::{run, TestHost};
use dmhs_parser::interp::{Exit, Interpreter};

fn temp_dir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("dmhs-parser-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn commands_reach_the_host_with_words_and_spans() {
    let mut host = TestHost::new();
    let mut interp = Interpreter::new();
    let src = "units lj\nfix 1 all print 10 \"step $(2*3)\" # c\n";
    interp.run_source("in.t", src, &mut host).unwrap();
    assert_eq!(host.command_lines(), ["units lj", "fix 1 all print 10 step $(2*3)"]);
    let fix = &host.executed[1];
    let sm = interp.sources();
    assert!(fix.args[4].quoted);
    assert_eq!(sm.snippet(fix.args[4].span), "\"step $(2*3)\"");
    assert_eq!(sm.snippet(fix.span), "fix 1 all print 10 \"step $(2*3)\"");
}

#[test]
fn exhausted_next_skips_the_next_jump_even_later_in_the_file() {
    let mut host = TestHost::new();
    let src = "variable a index 1\nlabel top\nprint a=$a\nnext a\nprint between\njump SELF top\nprint end\n";
    run("in.t", src, &mut host).unwrap();
    assert_eq!(host.screen, "a=1\nbetween\nend\n");
}

#[test]
fn command_line_index_value_wins() {
    let mut host = TestHost::new();
    host.vars.define_index("T", vec!["300".into(), "400".into()]);
    let src = "variable T index 1.0\nlabel l\nprint T=$T\nnext T\njump SELF l\n";
    run("in.t", src, &mut host).unwrap();
    assert_eq!(host.screen, "T=300\nT=400\n");
}

#[test]
fn quit_inside_if_stops_everything() {
    let mut host = TestHost::new();
    let out = run("in.t", "if \"1 > 0\" then \"quit 3\" \"print no\"\nprint no\n", &mut host).unwrap();
    assert_eq!(out.exit, Exit::Quit(3));
    assert_eq!(host.screen, "");
}

#[test]
fn keep_going_records_errors_and_continues() {
    let mut host = TestHost { fail_on: Some("run"), ..TestHost::new() };
    let mut interp = Interpreter::new();
    interp.set_keep_going(true);
    let src = "units lj\npair_stlye lj/cut 2.5\nprint ${nope}\nrun 10\ntimestep 0.1\n";
    let out = interp.run_source("in.t", src, &mut host).unwrap();
    let msgs: Vec<&str> = out.errors.iter().map(|d| d.message.as_str()).collect();
    assert_eq!(msgs, ["unknown command `pair_stlye`", "undefined variable `nope`", "`run` failed in the test host"]);
    assert_eq!(host.command_lines(), ["units lj", "timestep 0.1"]);
}

#[test]
fn keep_going_stops_a_loop_that_fails_every_pass() {
    let mut host = TestHost::new();
    let mut interp = Interpreter::new();
    interp.set_keep_going(true);
    let errors = interp.run_source("in.t", "label l\nprint ${nope}\njump SELF l\n", &mut host).unwrap_err();
    assert!(errors.last().unwrap().message.contains("too many errors"));
}

#[test]
fn without_keep_going_nothing_runs_when_the_prepass_finds_problems() {
    let mut host = TestHost::new();
    let err = run("in.t", "units lj\ntimestpe 0.1\nrun 10\n", &mut host).unwrap_err();
    assert!(err.contains("unknown command `timestpe`") && err.contains("did you mean `timestep`?"), "{err}");
    assert!(host.executed.is_empty());
}

#[test]
fn unsupported_command_in_an_if_branch_is_reported_when_it_runs() {
    let mut host = TestHost { unsupported: vec!["minimize"], ..TestHost::new() };
    let src = "if \"0 > 1\" then \"minimize 0 0 1 1\"\nprint ok\nif \"1 > 0\" then \"minimize 0 0 1 1\"\n";
    let err = run("in.t", src, &mut host).unwrap_err();
    assert_eq!(host.screen, "ok\n");
    assert!(err.contains("`minimize` is a LAMMPS command that dmhs does not support"), "{err}");
    assert!(err.contains("--> in.t:3:18"), "{err}");
}

#[test]
fn include_and_jump_to_files() {
    let dir = temp_dir("include");
    let inc = dir.join("inc.in");
    let other = dir.join("other.in");
    std::fs::write(&inc, "print \"in include\"\nvariable z equal 5\n").unwrap();
    std::fs::write(&other, "print skipped\nlabel here\nprint \"in other z=$z\"\n").unwrap();
    let src = format!("include {}\njump {} here\nprint never\n", inc.display(), other.display());
    let mut host = TestHost::new();
    run("in.t", &src, &mut host).unwrap();
    assert_eq!(host.screen, "in include\nin other z=5\n");
}

#[test]
fn include_nesting_is_limited() {
    let dir = temp_dir("nest");
    let f = dir.join("self.in");
    std::fs::write(&f, format!("include {}\n", f.display())).unwrap();
    let mut host = TestHost::new();
    let err = run("in.t", &format!("include {}\n", f.display()), &mut host).unwrap_err();
    assert!(err.contains("too many nested input files"), "{err}");
}

#[test]
fn print_to_file_and_append() {
    let dir = temp_dir("print");
    let f = dir.join("out.txt");
    let src = format!(
        "variable x equal 2\nprint \"first $x\" file {p} screen no\nprint 'second ${{x}}' append {p}\n",
        p = f.display()
    );
    let mut host = TestHost::new();
    run("in.t", &src, &mut host).unwrap();
    assert_eq!(std::fs::read_to_string(&f).unwrap(), "first 2\nsecond 2\n");
    assert_eq!(host.screen, "second 2\n");
}

#[test]
fn partition_with_one_partition() {
    let mut host = TestHost::new();
    run("in.t", "partition yes 1 print \"yes # x\" # c\npartition no 1 print no\npartition yes * print star\n", &mut host).unwrap();
    assert_eq!(host.screen, "yes # x\nstar\n");
}

#[test]
fn execute_line_runs_one_command() {
    let mut host = TestHost::new();
    let mut interp = Interpreter::new();
    interp.execute_line("variable n equal 4", &mut host).unwrap();
    interp.execute_line("run ${n}", &mut host).unwrap();
    assert_eq!(host.command_lines(), ["run 4"]);
    let err = interp.execute_line("jump SELF", &mut host).unwrap_err();
    assert!(err[0].message.contains("needs an input file"));
}

#[test]
fn non_ascii_is_warned_once_and_replaced() {
    let mut host = TestHost::new();
    run("in.t", "print \u{201C}a b\u{201D}\nprint x\u{00A0}screen no\nprint \u{2212}1\n", &mut host).unwrap();
    assert_eq!(host.screen.matches("warning: non-ASCII").count(), 1);
    assert!(host.screen.ends_with("a b\n-1\n"), "{}", host.screen);
}

#[test]
fn shell_and_python_are_refused_even_in_branches() {
    let mut host = TestHost::new();
    let err = run("in.t", "if \"1 > 0\" then \"shell rm -rf x\"\n", &mut host).unwrap_err();
    assert!(err.contains("`shell` is not supported for safety"), "{err}");
}

#[test]
fn check_source_reports_without_running() {
    let host = TestHost::new();
    let mut interp = Interpreter::new();
    let ds = interp.check_source("in.t", "units lj\nfix 1 all nve\npair_stlye x\nprint 'a\n", &host);
    let msgs: Vec<&str> = ds.iter().map(|d| d.message.as_str()).collect();
    assert_eq!(msgs, ["unknown command `pair_stlye`", "unmatched single quote"]);
}
