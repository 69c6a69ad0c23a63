//! Variable tests. Expected strings were printed by LAMMPS 22 Jul 2025 (`lmp`) for the same
//! commands, unless a comment says otherwise.

use super::*;
use crate::expr::evaluate;
use crate::numfmt::format_g;
use crate::span::FileId;
use crate::test_context::TestContext;

/// Words of a command line (split at blanks, with byte spans).
fn words(line: &str) -> Vec<Word> {
    let mut out = vec![];
    let mut pos = 0;
    for t in line.split(' ') {
        if !t.is_empty() {
            out.push(Word::new(t, Span::new(FileId(0), pos, pos + t.len())));
        }
        pos += t.len() + 1;
    }
    out
}

fn var(ctx: &mut TestContext, line: &str) {
    ctx.vars.command(&words(line)).unwrap_or_else(|d| panic!("variable {line}: {d}"));
}

fn var_err(ctx: &mut TestContext, line: &str) -> Diagnostic {
    match ctx.vars.command(&words(line)) {
        Ok(()) => panic!("variable {line}: expected an error"),
        Err(d) => d,
    }
}

fn get(ctx: &mut TestContext, name: &str) -> String {
    retrieve(ctx, name).unwrap().unwrap_or_else(|| panic!("{name} is undefined"))
}

/// `$(...)` as LAMMPS prints it.
fn imm(ctx: &mut TestContext, text: &str) -> String {
    format_g(evaluate(text, ctx).unwrap(), 20)
}

/// in.dambreak2d and in.poiseuille2d from the reference decks: `${x}` is replaced by the
/// text of x before the command runs (done by hand here), `$(...)` is computed.
#[test]
fn reference_decks() {
    let mut c = TestContext::new();
    var(&mut c, "nsteps index 1000");
    var(&mut c, "rhosum index 0");
    var(&mut c, "dx equal 0.01");
    let dx = get(&mut c, "dx");
    var(&mut c, &format!("h equal 3.0*{dx}"));
    var(&mut c, "rho0 equal 1000.0");
    var(&mut c, "c equal 20.0");
    var(&mut c, "alpha equal 0.1");
    let (h, cc) = (get(&mut c, "h"), get(&mut c, "c"));
    var(&mut c, &format!("dt equal 0.1*{h}/{cc}"));
    var(&mut c, "W equal 3.22");
    var(&mut c, "H equal 1.8");
    let d1 = [imm(&mut c, "-3.5*v_dx"), imm(&mut c, "v_W+3.5*v_dx"), get(&mut c, "H"), imm(&mut c, "-0.5*v_dx"), imm(&mut c, "0.5*v_dx")];
    assert_eq!(d1, ["-0.035000000000000003331", "3.2550000000000003375", "1.8", "-0.0050000000000000001041", "0.0050000000000000001041"]);
    let d2 = [imm(&mut c, "1.0/(v_dx*v_dx)"), imm(&mut c, "-3.0*v_dx"), imm(&mut c, "v_W+3.0*v_dx"), get(&mut c, "W"), imm(&mut c, "v_H+1")];
    assert_eq!(d2, ["10000", "-0.02999999999999999889", "3.25", "3.22", "2.7999999999999998224"]);
    let d3 = [
        imm(&mut c, "v_rho0*v_dx*v_dx"),
        get(&mut c, "rho0"),
        get(&mut c, "c"),
        get(&mut c, "alpha"),
        get(&mut c, "h"),
        imm(&mut c, "0.3*v_h"),
        get(&mut c, "dt"),
        get(&mut c, "nsteps"),
    ];
    assert_eq!(d3, ["0.10000000000000000555", "1000", "20", "0.1", "0.03", "0.00899999999999999932", "0.00015", "1000"]);
    let rhosum = get(&mut c, "rhosum");
    assert!(!crate::expr::evaluate_boolean(&format!("{rhosum} == 1"), &mut c).unwrap());

    let mut c = TestContext::new();
    var(&mut c, "nsteps index 1000");
    var(&mut c, "dx equal 1.0e-5");
    let dx = get(&mut c, "dx");
    var(&mut c, &format!("h equal 2.6*{dx}"));
    var(&mut c, "rho0 equal 1000.0");
    var(&mut c, "mu equal 1.0e-3");
    var(&mut c, "c equal 1.0e-3");
    var(&mut c, "F equal 2.0e-4");
    var(&mut c, "dt equal 1.0e-5");
    var(&mut c, &format!("L equal 100*{dx}"));
    let p1 = [get(&mut c, "L"), imm(&mut c, "-3.0*v_dx"), imm(&mut c, "v_L+3.0*v_dx"), imm(&mut c, "-0.5*v_dx"), imm(&mut c, "0.5*v_dx"), get(&mut c, "dx")];
    assert_eq!(p1, ["0.001", "-3.0000000000000004148e-05", "0.0010300000000000000995", "-5.000000000000000409e-06", "5.000000000000000409e-06", "1e-05"]);
    let p2 = [
        imm(&mut c, "v_rho0*v_dx*v_dx"),
        get(&mut c, "rho0"),
        get(&mut c, "c"),
        get(&mut c, "mu"),
        get(&mut c, "h"),
        get(&mut c, "F"),
        imm(&mut c, "0.2*v_h"),
        get(&mut c, "dt"),
    ];
    assert_eq!(p2, ["1.0000000000000000871e-07", "1000", "0.001", "0.001", "2.6e-05", "0.0002", "5.2000000000000001882e-06", "1e-05"]);
}

#[test]
fn values_as_text_and_numbers() {
    let mut c = TestContext::new();
    var(&mut c, "p1 equal 1/3");
    var(&mut c, "p2 equal v_p1*3");
    // v_p1 reads the 15-digit text of p1
    assert_eq!(get(&mut c, "p2"), "0.999999999999999");
    assert_eq!(imm(&mut c, "v_p2"), "0.9999999999999990008");
    assert_eq!(get(&mut c, "p1"), "0.333333333333333");
    // compute_equal is the formula at full precision
    assert_eq!(compute_equal(&mut c, "p1").unwrap(), 1.0 / 3.0);
    // internal: the value itself
    var(&mut c, "ii internal 2.5");
    var(&mut c, "ie equal v_ii+1");
    assert_eq!(get(&mut c, "ie"), "3.5");
    c.vars.set_internal("ii", 1.0 / 3.0);
    assert_eq!(compute_equal(&mut c, "ie").unwrap(), 1.0 / 3.0 + 1.0);
    assert_eq!(get(&mut c, "ii"), "0.333333333333333");
    // strings and index values that are numbers
    var(&mut c, "n string 12.5");
    var(&mut c, "o equal v_n*2");
    assert_eq!(get(&mut c, "o"), "25");
    var(&mut c, "n2 index 1e3");
    var(&mut c, "o2 equal v_n2*2");
    assert_eq!(get(&mut c, "o2"), "2000");
    var(&mut c, "n8 string +5");
    var(&mut c, "o8 equal v_n8*2");
    assert_eq!(get(&mut c, "o8"), "10");
    var(&mut c, "lp loop 3");
    var(&mut c, "ol equal v_lp+0.5");
    assert_eq!(get(&mut c, "ol"), "1.5");
    // formulas of several words are joined
    var(&mut c, "a equal 1 + 2");
    assert_eq!(get(&mut c, "a"), "3");
    // -0 and tiny values print as 0
    var(&mut c, "z equal 0*-1");
    assert_eq!(get(&mut c, "z"), "0");
}

#[test]
fn non_numeric_and_circular_references() {
    let mut c = TestContext::new();
    for (value, style) in [("12.5abc", "string"), ("0x10", "string"), ("inf", "string"), ("x", "index")] {
        var(&mut c, &format!("n {style} {value}"));
        var(&mut c, "o equal v_n*2");
        assert_eq!(retrieve(&mut c, "o").unwrap_err(), "Variable n: Non-numeric variable value in variable formula");
        var(&mut c, "n delete");
    }
    // NaN prints as -nan, which is not a number either
    var(&mut c, "nan equal (-1)^0.5");
    assert_eq!(get(&mut c, "nan"), "-nan");
    var(&mut c, "o equal v_nan");
    assert_eq!(retrieve(&mut c, "o").unwrap_err(), "Variable nan: Non-numeric variable value in variable formula");

    var(&mut c, "c1 equal v_c2+1");
    var(&mut c, "c2 equal v_c1+1");
    var(&mut c, "cs equal v_cs");
    assert_eq!(evaluate("v_c1", &mut c).unwrap_err().message, "Variable c1: has a circular dependency");
    assert_eq!(evaluate("v_cs", &mut c).unwrap_err().message, "Variable cs: has a circular dependency");
    assert_eq!(retrieve(&mut c, "cs").unwrap_err(), "Variable cs: has a circular dependency");
    // the flags are cleared after an error
    var(&mut c, "cs equal 4");
    assert_eq!(get(&mut c, "cs"), "4");

    // the innermost variable names the error
    var(&mut c, "b equal 1/0");
    var(&mut c, "a equal v_b+1");
    assert_eq!(retrieve(&mut c, "a").unwrap_err(), "Variable b: Divide by 0 in variable formula");
    assert_eq!(compute_equal(&mut c, "b").unwrap_err(), "Variable b: Divide by 0 in variable formula");
    let e = evaluate("2*v_a", &mut c).unwrap_err();
    assert_eq!((e.message.as_str(), e.offset, e.len), ("Variable b: Divide by 0 in variable formula", 2, 3));
    // bare LAMMPS messages stay bare
    var(&mut c, "u equal v_nope");
    assert_eq!(retrieve(&mut c, "u").unwrap_err(), "Invalid variable reference v_nope in variable formula");
    var(&mut c, "k equal foo");
    assert_eq!(retrieve(&mut c, "k").unwrap_err(), "Variable k: Invalid thermo keyword 'foo' in variable formula");
    var(&mut c, "e equal 2*3");
    assert_eq!(evaluate("v_e[1]", &mut c).unwrap_err().message, "Variable e: Mismatched variable in variable formula");
    var(&mut c, "an atom x");
    assert_eq!(evaluate("v_an", &mut c).unwrap_err().message, "Variable an: Atom-style variable in equal-style variable formula");
    assert_eq!(retrieve(&mut c, "an").unwrap(), None);
    assert_eq!(retrieve(&mut c, "nope").unwrap(), None);
}

#[test]
fn format_and_getenv() {
    let mut c = TestContext::new();
    var(&mut c, "e equal 2*3");
    var(&mut c, "f format e %10.4f");
    assert_eq!(get(&mut c, "f"), "    6.0000");
    var(&mut c, "ii internal 2");
    var(&mut c, "fi format ii %.2f");
    assert_eq!(get(&mut c, "fi"), "2.00");
    // a format variable is replaced by a new definition
    var(&mut c, "fi format ii %.3e");
    assert_eq!(get(&mut c, "fi"), "2.000e+00");
    var(&mut c, "e1 equal 1/3");
    var(&mut c, "f1 format e1 %.3f");
    assert_eq!(get(&mut c, "f1"), "0.333");
    var(&mut c, "e1 equal 2/3");
    var(&mut c, "f1 format e1 %.5f");
    assert_eq!(get(&mut c, "f1"), "0.66667");
    // LAMMPS keeps at most 63 characters
    var(&mut c, "pi equal PI");
    var(&mut c, "fp format pi %.300f");
    assert_eq!(get(&mut c, "fp"), "3.1415926535897931159979634685441851615905761718750000000000000");
    var(&mut c, "e delete");
    assert_eq!(retrieve(&mut c, "f").unwrap_err(), "Variable f: format variable e does not exist");
    assert_eq!(
        var_err(&mut c, "g format nope %.3f").message,
        "Variable g: format variable nope does not exist"
    );
    var(&mut c, "s string 2");
    assert_eq!(var_err(&mut c, "g format s %.3f").message, "Variable g: format variable s has incompatible style");
    for bad in ["%+.3e", "%#.3g", "x=%.3f", "%.3f_units", "%d"] {
        assert_eq!(var_err(&mut c, &format!("g format pi {bad}")).message, "Incorrect conversion in format string", "{bad}");
    }
    std::env::set_var("DMHS_TEST_GETENV", "hello");
    var(&mut c, "g getenv DMHS_TEST_GETENV");
    assert_eq!(get(&mut c, "g"), "hello");
    var(&mut c, "g getenv DMHS_TEST_NOT_SET_ANYWHERE");
    assert_eq!(get(&mut c, "g"), "");
}

#[test]
fn loops_indexes_and_next() {
    let mut c = TestContext::new();
    var(&mut c, "n index x y z");
    var(&mut c, "n index q");
    assert_eq!(get(&mut c, "n"), "x");
    assert!(!c.vars.next(&words("n")).unwrap());
    assert_eq!(get(&mut c, "n"), "y");
    var(&mut c, "lp loop 3 pad");
    assert_eq!(get(&mut c, "lp"), "1");
    c.vars.next(&words("lp")).unwrap();
    assert_eq!(get(&mut c, "lp"), "2");
    var(&mut c, "l2 loop 8 12 pad");
    assert_eq!(get(&mut c, "l2"), "08");
    var(&mut c, "l3 loop 5 12");
    assert_eq!(get(&mut c, "l3"), "5");
    var(&mut c, "l4 loop 0 3");
    assert_eq!(get(&mut c, "l4"), "0");
    var(&mut c, "l5 loop -1 2");
    assert_eq!(get(&mut c, "l5"), "-1");
    var(&mut c, "l9 loop 10 pad");
    assert_eq!(get(&mut c, "l9"), "01");
    var(&mut c, "l8 loop 0 0");
    assert_eq!(get(&mut c, "l8"), "0");
    // an existing loop is not redefined
    var(&mut c, "l9 loop 2 pad extra");
    assert_eq!(get(&mut c, "l9"), "01");

    // next: each mention advances once; exhausted variables are deleted
    var(&mut c, "b index x y");
    var(&mut c, "cc index p q r");
    assert!(!c.vars.next(&words("b cc")).unwrap());
    assert_eq!((get(&mut c, "b"), get(&mut c, "cc")), ("y".into(), "q".into()));
    assert!(c.vars.next(&words("b cc")).unwrap());
    assert!(!c.vars.exists("b"));
    assert_eq!(get(&mut c, "cc"), "r");
    var(&mut c, "b index again");
    assert_eq!(get(&mut c, "b"), "again");
    var(&mut c, "idx index a b c");
    c.vars.next(&words("idx idx")).unwrap();
    assert_eq!(get(&mut c, "idx"), "c");
    var(&mut c, "l loop 2");
    assert!(!c.vars.next(&words("l")).unwrap());
    assert_eq!(get(&mut c, "l"), "2");
    assert!(c.vars.next(&words("l")).unwrap());
    assert!(!c.vars.exists("l"));

    // -var on the command line wins over the script's index
    let mut c = TestContext::new();
    c.vars.define_index("T", vec!["300".into(), "400".into()]);
    var(&mut c, "T index 1.0");
    assert_eq!(get(&mut c, "T"), "300");
    assert_eq!(var_err(&mut c, "T equal 5").message, "Cannot redefine variable T with a different style");
    assert_eq!(c.vars.names(), ["T"]);
}

#[test]
fn next_errors() {
    let mut c = TestContext::new();
    var(&mut c, "a equal 1");
    var(&mut c, "b index 1 2");
    var(&mut c, "d loop 2");
    var(&mut c, "i internal 1");
    let err = |c: &mut TestContext, line: &str| c.vars.next(&words(line)).unwrap_err();
    assert_eq!(err(&mut c, "").message, "Illegal next command: missing argument(s)");
    let d = err(&mut c, "nope");
    assert_eq!(d.message, "Invalid variable 'nope' in next command");
    assert_eq!(d.primary_span(), Some(Span::new(FileId(0), 0, 4)));
    assert_eq!(err(&mut c, "a").message, "Variable a has invalid style equal for next command");
    assert_eq!(err(&mut c, "i").message, "Variable i has invalid style internal for next command");
    assert_eq!(err(&mut c, "b d").message, "All variables in next command must have same style");
}

#[test]
fn redefinition_rules() {
    let mut c = TestContext::new();
    var(&mut c, "a equal 1");
    var(&mut c, "a equal 2");
    assert_eq!(get(&mut c, "a"), "2");
    // index and loop are ignored when the name exists, whatever its style
    var(&mut c, "a index 1");
    var(&mut c, "a loop 3");
    assert_eq!(get(&mut c, "a"), "2");
    assert_eq!(var_err(&mut c, "a string x").message, "Cannot redefine variable a with a different style");
    assert_eq!(var_err(&mut c, "a internal 3").message, "Cannot redefine variable a with a different style");
    var(&mut c, "s string x");
    var(&mut c, "s string y");
    assert_eq!(get(&mut c, "s"), "y");
    assert_eq!(var_err(&mut c, "s equal 1").message, "Cannot redefine variable s with a different style");
    var(&mut c, "i internal 3.5");
    var(&mut c, "i internal 4.5");
    assert_eq!(imm(&mut c, "v_i*2"), "9");
    var(&mut c, "s delete");
    var(&mut c, "s delete");
    var(&mut c, "s equal 7");
    assert_eq!(get(&mut c, "s"), "7");
    var(&mut c, "9x equal 1");
    assert_eq!(get(&mut c, "9x"), "1");
    assert_eq!(c.vars.names(), ["a", "i", "s", "9x"]);
    assert_eq!(c.vars.style("i"), Some("internal"));
    assert!(c.vars.is_equal_style("s") && !c.vars.is_equal_style("nope"));
    var(&mut c, "at atom x+2 y");
    assert_eq!(c.vars.formula("at"), Some("x+2 y"));
}

#[test]
fn command_errors() {
    let mut c = TestContext::new();
    let cases: &[(&str, &str)] = &[
        ("a", "Illegal variable command: missing argument(s)"),
        ("a foo", "Unknown variable style: foo"),
        ("a equal", "Illegal variable equal command: missing argument(s)"),
        ("x index", "Illegal variable index command: missing argument(s)"),
        ("c string x y", "Illegal variable command: expected 3 arguments but found 4"),
        ("g getenv", "Illegal variable command: expected 3 arguments but found 2"),
        ("e format", "Illegal variable command: expected 4 arguments but found 2"),
        ("d loop", "Illegal variable loop command: missing argument(s)"),
        ("d loop 0", "Invalid variable loop argument: 0"),
        ("d loop -1", "Invalid variable loop argument: -1"),
        ("d loop 3 2", "Illegal variable loop command: 3 > 2"),
        ("d loop -3 -1", "Illegal variable loop command: -3 > -1"),
        ("d loop 3 2 pad", "Illegal variable loop command: 3 > 2"),
        ("d loop 1 2 3", "Illegal variable loop command: too many arguments"),
        ("d loop 2 pad extra", "Illegal variable loop command: too many arguments"),
        ("d loop 2 x", "Expected integer parameter instead of 'x' in input script or data file"),
        ("d loop 1.5", "Expected integer parameter instead of '1.5' in input script or data file"),
        ("d loop 3 pad pad", "Expected integer parameter instead of 'pad' in input script or data file"),
        ("e internal abc", "Expected floating point parameter instead of 'abc' in input script or data file"),
        ("e internal 1e400", "Floating point number 1e400 in input script or data file is out of range"),
        ("a-b equal 1", "Variable name 'a-b' must have only letters, numbers, or underscores"),
        ("a.b index 1", "Variable name 'a.b' must have only letters, numbers, or underscores"),
        ("a-b loop 2", "Variable name 'a-b' must have only letters, numbers, or underscores"),
        ("a delete extra", "Illegal variable delete command: expected 2 arguments but found 3"),
    ];
    for &(line, msg) in cases {
        assert_eq!(var_err(&mut c, line).message, msg, "{line}");
    }
    assert!(c.vars.names().is_empty());
    // located: the offending word is underlined, with the syntax as help
    let d = var_err(&mut c, "a equl 1");
    assert_eq!(d.primary_span(), Some(Span::new(FileId(0), 2, 6)));
    assert_eq!(d.help[0], "did you mean `equal`?");
    let d = var_err(&mut c, "c string x y z");
    assert_eq!(d.primary_span(), Some(Span::new(FileId(0), 11, 14)));
    let d = var_err(&mut c, "u universe 1 2");
    assert_eq!(d.message, "variable style `universe` is not supported by dmhs");
}
