//! What LAMMPS' classic example decks (examples/flow, obstacle, friction, crack, indent, melt,
//! min, micelle; docs/validation.md, "LAMMPS MD examples") needed, on decks of our own: fix
//! aveforce (aveforce_flow), fix adapt (adapt_soft, adapt_lj, adapt_diameter), fix deform (deform_erate_volume,
//! deform_wiggle_2d), compute msd/chunk (msd_chunk_chains) and variable atomfile (addforce_atomfile; the thermo table at every printed step against
//! lammps-refs/refs/NAME/thermo.txt and LAMMPS run now, when present), thermo style one's
//! Volume column when the box can change, region IDs with '-'; and the located errors.

use dmhs::deck::{run_text, DeckOptions};

mod thermo_tables;
use thermo_tables::{root, table};

const DECKS: [&str; 9] = ["aveforce_flow", "addforce_atomfile", "adapt_soft", "adapt_lj", "adapt_diameter", "addforce_atom", "deform_erate_volume", "deform_wiggle_2d", "msd_chunk_chains"];

thermo_tables::thermo_table_tests!(DECKS);

fn opts() -> DeckOptions {
    DeckOptions { screen: false, capture_text: true, ..Default::default() }
}

/// A 2D slab of 60 atoms; `boundary` and the lines after it are the test's.
fn deck(boundary: &str, extra: &str) -> String {
    format!(
        "dimension 2\nboundary {boundary}\natom_style atomic\nlattice hex 0.9\nregion box block 0 6 0 5 -0.25 0.25\ncreate_box 1 box\n\
         create_atoms 1 box\nmass 1 1.0\npair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\nfix 2 all enforce2d\n{extra}"
    )
}

/// Each periodic `deck` with `prefix + line` fails with an error located at its last line whose
/// text contains `want`.
fn assert_located_at_last_line(prefix: &str, cases: &[(&str, &str)]) {
    for (line, want) in cases {
        let text = deck("p p p", &format!("{prefix}{line}"));
        let n = text.lines().count();
        let f = run_text("bad.deck", &text, &opts()).err().unwrap_or_else(|| panic!("accepted: {line}"));
        assert!(f.rendered.contains(&format!("bad.deck:{n}:")) && f.rendered.contains(want), "{line}: {}", f.rendered);
    }
}

fn header(text: &str) -> Vec<String> {
    let line = text.lines().find(|l| l.trim_start().starts_with("Step")).expect("a thermo header");
    line.split_whitespace().map(String::from).collect()
}

/// LAMMPS' Thermo::init: style one gains Volume when a face is shrink-wrapped (or a fix such as
/// balance changes the box), custom never does; a later run in a periodic box drops it again.
#[test]
fn thermo_one_prints_volume_when_the_box_can_change() {
    let one = ["Step", "Temp", "E_pair", "E_mol", "TotEng", "Press"];
    for (boundary, extra, volume) in [
        ("p s p", "run 0\n", true),
        ("p m p", "run 0\n", true),
        ("p f p", "run 0\n", false),
        ("p p p", "run 0\n", false),
        ("p p p", "fix b all balance 10 1.1 shift x 5 1.05\nrun 0\n", true),
        ("p s p", "thermo_style custom step temp press\nrun 0\n", false),
    ] {
        let r = run_text("t.deck", &deck(boundary, extra), &opts()).unwrap_or_else(|f| panic!("{boundary} {extra}: {}", f.rendered));
        let h = header(r.sim.out.captured.as_deref().unwrap());
        let mut want: Vec<String> = if extra.contains("custom") { vec!["Step".into(), "Temp".into(), "Press".into()] } else { one.iter().map(|s| s.to_string()).collect() };
        if volume {
            want.push("Volume".into());
        }
        assert_eq!(h, want, "boundary {boundary}, {extra}");
    }
    // the column belongs to the run: a second run after change_box to periodic drops it
    let r = run_text("t.deck", &deck("p s p", "run 0\nchange_box all boundary p p p\nrun 0\n"), &opts()).unwrap();
    let text = r.sim.out.captured.clone().unwrap();
    let last = text.lines().filter(|l| l.trim_start().starts_with("Step")).last().unwrap();
    assert!(!last.contains("Volume"), "{last}");
}

/// The average of the group's forces plus the given component replaces each atom's force;
/// f_ID is the total before averaging; NULL components stay as the pair forces left them.
#[test]
fn aveforce_sets_the_average_force() {
    let shake = "displace_atoms all random 0.05 0.05 0.0 4711 units box\nregion top block INF INF 4.5 INF INF INF\ngroup top region top\n";
    let plain = run_text("t.deck", &deck("p s p", &format!("{shake}run 0\n")), &opts()).unwrap_or_else(|f| panic!("{}", f.rendered));
    let r = run_text("t.deck", &deck("p s p", &format!("{shake}fix 3 top aveforce 0.25 NULL 0.0\nrun 0\n")), &opts()).unwrap_or_else(|f| panic!("{}", f.rendered));
    let sim = &r.sim;
    let a = &sim.state.atoms;
    let bit = sim.state.groups.bit("top").unwrap();
    let top: Vec<usize> = (0..a.nlocal).filter(|&i| a.mask[i] & bit != 0).collect();
    assert!(top.len() > 3);
    let fx = a.f[top[0]][0];
    assert!(top.iter().all(|&i| a.f[i][0] == fx && a.f[i][2] == 0.0));
    let fix = &sim.fixes[sim.find_fix("3").unwrap()];
    let total = fix.vector(&sim.state, 1).unwrap();
    assert!((fx - (total / top.len() as f64 + 0.25)).abs() < 1e-12, "{fx} {total}");
    // y untouched: the same as without the fix (atoms matched by ID)
    let p = &plain.sim.state.atoms;
    for &i in &top {
        let j = (0..p.nlocal).find(|&j| p.tag[j] == a.tag[i]).unwrap();
        assert_eq!(a.f[i][1], p.f[j][1]);
    }
    let spread = top.iter().map(|&i| a.f[i][1]).fold(f64::NEG_INFINITY, f64::max) - top.iter().map(|&i| a.f[i][1]).fold(f64::INFINITY, f64::min);
    assert!(spread > 1e-3, "the displaced atoms' y forces differ ({spread})");
}

#[test]
fn bad_aveforce_is_a_located_error() {
    assert_located_at_last_line("", &[
        ("fix 3 all aveforce 0.0 0.0\n", "fz"),
        ("fix 3 all aveforce 0.0 zero 0.0\n", "fy"),
        ("fix 3 all aveforce 0.0 0.0 0.0 region nowhere\n", "region `nowhere` does not exist"),
        ("fix 3 all aveforce 0.0 0.0 0.0 every 2\n", "unknown keyword `every`"),
    ]);
}

/// fix deform's settings are checked as LAMMPS checks them (tilts need a triclinic box); a
/// second fix deform, or a run that would
/// turn a length negative, stops at the run command.
#[test]
fn bad_deform_is_a_located_error() {
    assert_located_at_last_line("", &[
        ("fix 3 all deform 0 x erate 0.1\n", "N must be in 1"),
        ("fix 3 all deform 1 x stretch 0.1\n", "Illegal fix deform command argument: stretch"),
        ("fix 3 all deform 1 xy erate 0.1\n", "triclinic"),
        ("fix 3 all deform 1 x erate\n", "missing engineering strain rate"),
        ("fix 3 all deform 1 x wiggle 0.1 0\n", "period must be > 0"),
        ("fix 3 all deform 1 x variable len v_rate\n", "Illegal fix deform variable name len"),
        ("fix 3 all deform 1 x volume\n", "volume setting is invalid"),
        ("fix 3 all deform 1 x erate 0.1 remap y\n", "unknown fix deform remap `y`"),
        ("fix 3 all deform 1 x erate 0.1 units metal\n", "metal"),
        ("fix 3 all deform 1 x erate 0.1 every 2\n", "unknown keyword `every`"),
    ]);
    let text = deck("s p p", "fix 3 all deform 1 x erate 0.1\n");
    let f = run_text("bad.deck", &text, &opts()).err().expect("deform on a shrink-wrapped face");
    assert!(f.rendered.contains("shrink-wrapped"), "{}", f.rendered);
    assert_located_at_last_line(
        "",
        &[("fix 3 all deform 1 x erate 0.1\nfix 4 all deform 1 y erate 0.1\nrun 10\n", "More than one fix deform"), ("fix 3 all deform 1 x erate -2.0\nrun 100\n", "Final box dimension due to fix deform is < 0.0")],
    );
}

/// compute msd/chunk needs a compute chunk/atom.
#[test]
fn bad_msd_chunk_is_a_located_error() {
    assert_located_at_last_line("", &[
        ("compute m all msd/chunk\n", "missing chunkID"),
        ("compute m all msd/chunk nope\n", "Chunk/atom compute `nope` does not exist"),
        ("compute t all temp\ncompute m all msd/chunk t\n", "does not use chunk/atom compute"),
        ("compute c all chunk/atom type\ncompute m all msd/chunk c extra\n", "unexpected argument"),
    ]);
}

/// fix addforce's `energy` keyword: an atom-style variable, with variable forces only; its
/// variables checked when the run starts (LAMMPS' init), at the run command.
#[test]
fn bad_addforce_is_a_located_error() {
    assert_located_at_last_line("", &[
        ("fix 3 all addforce 0.1 0.0 0.0 energy v_e
", "Cannot use variable energy with constant force"),
        ("variable f equal 0.1
fix 3 all addforce v_f 0.0 0.0 energy e
", "energy takes v_name"),
        ("fix 3 all addforce 0.1 0.0 0.0 every 0
", "every"),
    ]);
    // checked when the run starts
    assert_located_at_last_line("", &[
        ("fix 3 all addforce v_nothere 0.0 0.0
run 2
", "Variable name for fix addforce does not exist"),
        ("variable f equal 0.1
variable e equal 1.0
fix 3 all addforce v_f 0.0 0.0 energy v_e
run 2
", "energy v_e must be atom-style"),
    ]);
}

/// An atom-style addforce is a trap about the box centre: min_style cg with `energy v_E` and
/// fix_modify energy relaxes the slab into it (refused without `energy`, as LAMMPS). LAMMPS 22
/// Jul 2025 on the same deck prints energies -2.9844107928892 (initial) and -2.99277677662627
/// (final) after 100 iterations and 208 force evaluations; dmhs prints the same text.
#[test]
fn addforce_energy_in_a_minimization() {
    let trap = "variable xc equal 0.5*(xlo+xhi)\nvariable yc equal 0.5*(ylo+yhi)\nvariable fx atom -0.05*(x-v_xc)\n\
        variable fy atom -0.05*(y-v_yc)\nvariable e atom 0.025*((x-v_xc)^2+(y-v_yc)^2)\n";
    let text = deck("p p p", &format!("{trap}fix 3 all addforce v_fx v_fy 0.0\nminimize 0 1e-8 100 1000\n"));
    let f = run_text("bad.deck", &text, &opts()).err().expect("refused");
    assert!(f.rendered.contains("Must use variable energy"), "{}", f.rendered);
    let text = deck("p p p", &format!("{trap}fix 3 all addforce v_fx v_fy 0.0 energy v_e\nfix_modify 3 energy yes\nminimize 0 1e-8 100 1000\n"));
    let r = run_text("min.deck", &text, &opts()).unwrap_or_else(|f| panic!("{}", f.rendered));
    let out = r.sim.out.captured.as_deref().unwrap();
    let lines: Vec<&str> = out.lines().collect();
    let k = lines.iter().position(|l| l.contains("Energy initial, next-to-last, final")).expect("the minimization summary");
    assert_eq!(lines[k + 1].split_whitespace().collect::<Vec<_>>(), ["-2.9844107928892", "-2.9927767766246", "-2.99277677662627"], "{out}");
    assert!(out.contains("Iterations, force evaluations = 100 208"), "{out}");
}

/// After the run, fix adapt's `reset yes` puts the 1 1 and 2 2 prefactors back to 0 and the
/// cross term keeps its last value (reset no, LAMMPS' default): the energy of a `run 0` after
/// the deck, with both fixes gone, is LAMMPS' (0.340219080803117, LAMMPS 22 Jul 2025 on the
/// same deck and lines).
#[test]
fn adapt_resets_only_with_reset_yes() {
    let deck = std::fs::read_to_string(root().join("lammps-refs/decks/in.adapt_soft")).unwrap();
    let text = format!("{deck}unfix 3\nunfix 4\nrun 0\n");
    let r = run_text("adapt.deck", &text, &opts()).unwrap_or_else(|f| panic!("{}", f.rendered));
    let (names, rows) = table(r.sim.out.captured.as_deref().unwrap());
    let pe = rows[0][names.iter().position(|n| n == "PotEng").unwrap()];
    assert!((pe - 0.340219080803117).abs() < 1e-12, "{pe}");
}

/// After adapt_diameter, `reset yes` gives the small spheres back the radii and charges they had
/// when the fix was defined, and their masses LAMMPS' restore factor (under `scale yes` the last
/// scale itself, so the masses grow again rather than return): the sums of a `run 0` after the
/// deck are LAMMPS 22 Jul 2025's on the same deck and lines (normalized by the atom count, lj;
/// the mass sum to its last printed digit, the atoms summed in another order).
#[test]
fn adapt_atom_reset_restores_as_lammps() {
    let deck = std::fs::read_to_string(root().join("lammps-refs/decks/in.adapt_diameter")).unwrap();
    let text = format!("{deck}unfix swell\nunfix lean\nthermo_style custom step c_sums[1] c_sums[2] c_sums[3]\nthermo_modify format float %.15g\nrun 0\n");
    let r = run_text("adapt.deck", &text, &opts()).unwrap_or_else(|f| panic!("{}", f.rendered));
    let (_, rows) = table(r.sim.out.captured.as_deref().unwrap());
    let lammps = [0.432244897959188, 0.823058983356695, 0.199443413729128];
    for (ours, theirs) in rows[0][1..].iter().zip(lammps) {
        assert!((ours - theirs).abs() <= 2e-15 * theirs, "{:?} against LAMMPS' {lammps:?}", &rows[0][1..]);
    }
}

/// LAMMPS adapts diameters only of a dynamic sphere style (`atom_style sphere 1`).
#[test]
fn adapt_diameter_needs_dynamic_radii() {
    let deck = std::fs::read_to_string(root().join("lammps-refs/decks/in.adapt_diameter")).unwrap();
    let text = deck.replacen("atom_style   hybrid sphere 1 charge", "atom_style   hybrid sphere charge", 1);
    assert_ne!(text, deck);
    let f = run_text("adapt.deck", &text, &opts()).err().expect("a static sphere style is refused");
    assert!(f.rendered.contains("atom_style sphere is not dynamic"), "{}", f.rendered);
}

/// write_restart and read_restart keep `atom_style sphere 1` (the flag was taken for a style
/// name: "settings.atom_style `sphere 1` is not an atom style") and the adapted radii.
#[test]
fn restart_keeps_a_dynamic_sphere_style() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("r.restart");
    let write = format!(
        "units lj\natom_style sphere 1\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\nlattice sc 0.5\ncreate_atoms 1 box\n\
         set type 1 diameter 0.8 density 1.0\npair_style zero 1.0\npair_coeff * *\nvariable d equal 0.9\nfix 1 all nve/sphere\n\
         fix g all adapt 1 atom diameter v_d\nrun 0\nwrite_restart {}\n",
        file.display()
    );
    run_text("w.deck", &write, &opts()).unwrap_or_else(|f| panic!("{}", f.rendered));
    let read = format!("read_restart {}\nfix g all adapt 1 atom diameter v_d\nvariable d equal 1.0\nrun 0\n", file.display());
    let r = run_text("r.deck", &read, &opts()).unwrap_or_else(|f| panic!("{}", f.rendered));
    assert_eq!(r.sim.state.atom_style, ["sphere", "1"]);
    let a = &r.sim.state.atoms;
    assert!(a.nlocal > 0 && a.radius[..a.nlocal].iter().all(|&x| x == 0.5), "{:?}", &a.radius[..3]);
}

#[test]
fn bad_adapt_is_a_located_error() {
    let base = "pair_style soft 1.0\npair_coeff * * 1.0\nvariable p equal 2.0\n";
    assert_located_at_last_line(base, &[
        ("fix 3 all adapt 1 kspace v_p\n", "`kspace` is not supported"),
        ("fix 3 all adapt -1 pair soft a * * v_p\n", ">= 0"),
        ("fix 3 all adapt 1 pair soft a * * 2.0\n", "v_name"),
        ("fix 3 all adapt 1 pair soft a * * v_p every 2\n", "unknown keyword `every`"),
        ("fix 3 all adapt 1\n", "missing"),
    ]);
    assert_located_at_last_line(base, &[("fix 3 all adapt 1 atom radius v_p\n", "diameter"), ("fix 3 all adapt 1 atom charge 0.5\n", "v_name")]);
    // what only a run can check: the pair style and its parameter, the atom attributes, the
    // variable's style
    for (line, want) in [
        ("fix 3 all adapt 1 pair lj/cut epsilon * * v_p\nrun 0\n", "lj/cut does not exist"),
        ("fix 3 all adapt 1 pair soft d * * v_p\nrun 0\n", "no parameter `d`"),
        ("fix 3 all adapt 1 atom diameter v_p\nrun 0\n", "requires atom attribute diameter"),
        ("fix 3 all adapt 1 atom charge v_p\nrun 0\n", "requires atom attribute charge"),
        ("variable a atom 2.0*x\nfix 3 all adapt 1 pair soft a * * v_a\nrun 0\n", "Variable a for fix adapt is invalid style"),
        ("fix 3 all adapt 1 pair soft a * * v_nothing\nrun 0\n", "Variable name nothing for fix adapt does not exist"),
    ] {
        let f = run_text("bad.deck", &deck("p p p", &format!("{base}{line}")), &opts()).err().unwrap_or_else(|| panic!("accepted: {line}"));
        assert!(f.rendered.contains(want), "{line}: {}", f.rendered);
    }
}

/// variable atomfile: a file with a bad count, an atom ID beyond the largest, too few lines or a
/// line without a value is an error at the variable command naming the file's line; `next`
/// past the last set deletes the variable (a later v_ use fails).
#[test]
fn atomfile_errors_are_located() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        ("count", "# values\n\nmany\n1 0.5\n", "count.txt:3: expected the number of lines"),
        ("big", "2\n1 0.5\n61 0.5\n", "big.txt:3: Invalid atom ID 61 in variable file"),
        ("short", "3\n1 0.5\n2 0.5\n", "Atomfile variable could not read values"),
        ("novalue", "2\n1 0.5\n2\n", "novalue.txt:3: Invalid atomfile line '2'"),
        ("empty", "# nothing\n", "Atomfile variable could not read values"),
    ];
    for (name, text, want) in cases {
        let file = dir.path().join(format!("{name}.txt"));
        std::fs::write(&file, text).unwrap();
        assert_located_at_last_line("", &[(&format!("variable w atomfile {}", file.display()), want)]);
    }
    let file = dir.path().join("one.txt");
    std::fs::write(&file, "1\n3 0.25\n").unwrap();
    let text = deck("p p p", &format!("variable w atomfile {}\nnext w\nfix 3 all addforce v_w 0.0 0.0\nrun 1\n", file.display()));
    let f = run_text("bad.deck", &text, &opts()).err().expect("the variable is gone after next");
    assert!(f.rendered.contains("Variable name for fix addforce does not exist (v_w)"), "{}", f.rendered);
}
