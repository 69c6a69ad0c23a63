//! Regression tests for issue 15 (reliability): decks that made dmhs panic, abort or hang are
//! refused with a located error (file:line:col) and the deck-error exit code 2, or run. Each
//! deck lives in tests/decks/reliability/. Set DMHS_BIN to run them against another build.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bin() -> PathBuf {
    std::env::var_os("DMHS_BIN").map(PathBuf::from).unwrap_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_dmhs")))
}

/// Runs dmhs on one thread under a limit of 2 GB of address space and 60 s, so that an
/// allocation per possible atom ID or an endless loop fails the test instead of the machine.
fn dmhs(args: &[&str], dir: &Path) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg("ulimit -v 2000000; exec timeout 60 \"$0\" \"$@\" -threads 1")
        .arg(bin())
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

fn text(o: &Output) -> String {
    format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr))
}

fn deck(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/decks/reliability").join(name).to_string_lossy().into_owned()
}

/// Runs `dmhs sub args` in a fresh folder; asserts the exit code (124: it hung), that nothing
/// panicked, and that every `expect` text appears. Returns the output.
fn expect(sub: &str, args: &[&str], code: i32, expect: &[&str]) -> String {
    let tmp = tempfile::tempdir().unwrap();
    let mut all = vec![sub];
    all.extend_from_slice(args);
    let o = dmhs(&all, tmp.path());
    let t = text(&o);
    assert!(!t.contains("panicked") && !t.contains("RUST_BACKTRACE"), "panic for {all:?}:\n{t}");
    assert_eq!(o.status.code(), Some(code), "exit code for {all:?}:\n{t}");
    for e in expect {
        assert!(t.contains(e), "`{e}` missing for {all:?}:\n{t}");
    }
    t
}

/// Item 1: every SPH pair style needs the SPH atom attributes; with the default atom style the
/// run (and `dmhs check`) stops at set-up, pointing at the pair_style line.
#[test]
fn sph_pair_styles_refuse_a_non_sph_atom_style() {
    let d = deck("in.sph_atomic");
    for (style, coeffs) in [
        ("sph/taitwater", "1000 10 1 1.5"),
        ("sph/taitwater/morris", "1000 10 1 1.5"),
        ("sph/heatconduction", "1 1.5"),
        ("sph/rhosum 1", "1.5"),
        ("dmhs/heatconduction", "1 1.5"),
        ("dmhs/sph/diffusion", "1 1.5"),
    ] {
        let name = style.split(' ').next().unwrap();
        let msg = format!("pair {name} requires atom attributes rho, drho, esph, desph, cv (atom_style sph, or hybrid with sph)");
        for sub in ["run", "check"] {
            let t = expect(sub, &[&d, "-var", "style", style, "-var", "coeffs", coeffs, "-log", "none"], 2, &[&msg, "in.sph_atomic:12:1", "defined here"]);
            assert!(t.contains("in.sph_atomic:14:1") && t.contains("checked before this run"), "{t}");
        }
    }
}

/// Item 2: widths and precisions of C formats are limited to 4096 wherever a deck gives one.
#[test]
fn huge_printf_precisions_are_located_errors() {
    let too_large = "is too large: dmhs formats numbers with a precision of at most 4096";
    expect("run", &[&deck("in.format_immediate"), "-log", "none"], 2, &["precision 70000 in format `%.70000f`", too_large, "in.format_immediate:2:18"]);
    expect("run", &[&deck("in.format_variable"), "-log", "none"], 2, &["precision 70000 in format `%.70000g`", too_large, "in.format_variable:3:21"]);
    expect("run", &[&deck("in.format_dump"), "-log", "none"], 2, &["precision 70000 in format `%.70000e`", too_large, "in.format_dump:8:28"]);
    for fmt in ["%.70000f", "%.65536g", "%.99999999999999999999e"] {
        expect("run", &[&deck("in.format_thermo"), "-var", "fmt", fmt, "-log", "none"], 2, &[&format!("precision {} in format `{fmt}`", &fmt[2..fmt.len() - 1]), too_large, "in.format_thermo:8:28"]);
    }
    expect("run", &[&deck("in.format_thermo"), "-var", "fmt", "%99999999999.2f", "-log", "none"], 2, &["width 99999999999 in format", "a width of at most 4096"]);
    // at the limit the number is printed
    let t = expect("run", &[&deck("in.format_thermo"), "-var", "fmt", "%.4096f", "-log", "none"], 0, &[]);
    assert!(t.contains(&format!("0.{}", "0".repeat(4096))), "{t}");
}

/// Item 3: atom IDs up to 2^31 - 1 need no table with an entry per possible ID (atom map,
/// special lists, contact history); larger IDs are refused at the data file's line.
#[test]
fn huge_atom_ids_use_a_hash_map_or_are_refused() {
    // data files are read from the working directory, as in LAMMPS: give their full paths
    let t = expect("run", &[&deck("in.huge_ids"), "-var", "data", &deck("ids_sparse.data"), "-log", "none"], 0, &["Loop time of", "for 20 steps with 3 atoms"]);
    assert!(t.contains("vx of 2147483647: "), "{t}");
    expect("run", &[&deck("in.huge_ids_gran"), "-var", "data", &deck("ids_sparse_gran.data"), "-log", "none"], 0, &["for 20 steps with 2 atoms", "omega z of 7: -0.198049"]);
    for (data, id) in [("ids_2pow31.data", "2147483648"), ("ids_1e11.data", "100000000000"), ("ids_2pow63.data", "9223372036854775807")] {
        let msg = format!("invalid atom ID {id}: atom IDs must be at most 2147483647");
        for sub in ["run", "check"] {
            expect(sub, &[&deck("in.huge_ids"), "-var", "data", &deck(data), "-log", "none"], 2, &[&msg, &format!("{data}:20:1")]);
        }
    }
}

/// Item 4: periodic boxes of 1e30..1e308 with an atom near a face run; an extent that
/// overflows a double is an error that names the region and the cutoff.
#[test]
fn huge_boxes_bin_without_overflow() {
    for l in ["1e30", "1e100", "1e308"] {
        expect("run", &[&deck("in.big_box"), "-var", "L", l, "-log", "none"], 0, &["for 10 steps with 3 atoms", "pe -0.2553180274"]);
    }
    expect(
        "run",
        &[&deck("in.huge_extent"), "-log", "none"],
        1,
        &["the region to bin for neighbours, the box and its atoms widened by the cutoff 2.8 (pair cutoff + skin), (-1e+308, -1.8, -1.8) to (1e+308, 3.8, 3.8), is too large", "in.huge_extent:16:1"],
    );
    // a box whose length overflows is refused where it is made
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("in.box"), "region b block -1e308 1e308 0 1 0 1\ncreate_box 1 b\n").unwrap();
    let o = dmhs(&["run", "in.box", "-log", "none"], tmp.path());
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("the box length 1e+308 - (-1e+308) overflows a double in x") && text(&o).contains("in.box:2:14"), "{}", text(&o));
}

/// Item 5: a restart file's bad field is refused at its place in the file (file:line:col),
/// with the read_restart command as the second place; the atom types of the issue.
#[test]
fn restart_file_errors_point_into_the_file() {
    let tmp = tempfile::tempdir().unwrap();
    let write = "units lj\nregion b block 0 4 0 4 0 4\ncreate_box 2 b\ncreate_atoms 1 single 1 1 1\ncreate_atoms 2 single 2 1 1\nmass * 1\nwrite_restart r.json\n";
    std::fs::write(tmp.path().join("in.write"), write).unwrap();
    assert_eq!(dmhs(&["run", "in.write", "-log", "none"], tmp.path()).status.code(), Some(0));
    let good = std::fs::read_to_string(tmp.path().join("r.json")).unwrap();
    let line = good.lines().position(|l| l.contains("\"type\": [1,2]")).unwrap() + 1;
    std::fs::write(tmp.path().join("in.read"), "read_restart bad.json\nrun 0\n").unwrap();
    for t in ["0", "-1", "3", "4294967296"] {
        std::fs::write(tmp.path().join("bad.json"), good.replace("\"type\": [1,2]", &format!("\"type\": [1,{t}]"))).unwrap();
        let o = dmhs(&["run", "in.read", "-log", "none"], tmp.path());
        let t2 = text(&o);
        assert_eq!(o.status.code(), Some(2), "{t2}");
        assert!(t2.contains(&format!("atoms.type[1] (atom 2) is {t}, outside 1..=2")), "{t2}");
        assert!(t2.contains(&format!("bad.json:{line}:16")) && t2.contains("in.read:1:14"), "{t2}");
    }
    // a value of the wrong kind: where the JSON parser stopped
    std::fs::write(tmp.path().join("bad.json"), good.replace("\"type\": [1,2]", "\"type\": [1,2.5]")).unwrap();
    let t2 = text(&dmhs(&["run", "in.read", "-log", "none"], tmp.path()));
    assert!(t2.contains("invalid type: floating point `2.5`") && t2.contains(&format!("bad.json:{line}:18")), "{t2}");
}

/// Item 6: atoms far outside a periodic box (x = 1e100, a box 1e-300 thick; from a data file,
/// create_atoms single ... remap yes, displace_atoms) are wrapped at once (the steps of one box
/// length never ended); a non-finite position is a located error.
#[test]
fn far_atoms_are_wrapped_in_constant_time() {
    expect(
        "run",
        &[&deck("in.far_atoms"), "-var", "data", &deck("far.data"), "-log", "none"],
        0,
        &["atom 1: 4 5 5 image 2147483647", "atom 2: 5 6 5 image -2147483648 2", "atom 3: 6 4 3", "for 0 steps with 3 atoms"],
    );
    let t = expect("run", &[&deck("in.thin_box"), "-log", "none"], 0, &["z = "]);
    let z: f64 = t.lines().find_map(|l| l.strip_prefix("z = ")).unwrap().trim().parse().unwrap();
    assert!((0.0..1e-300).contains(&z), "{t}");
    expect("run", &[&deck("in.nonfinite_create"), "-log", "none"], 2, &["create_atoms single: the point [inf, ", "is not finite", "in.nonfinite_create:6:31"]);
    expect("run", &[&deck("in.nonfinite_displace"), "-log", "none"], 2, &["displace_atoms moves atom 1 to a non-finite position [1.0, 1.0, inf]", "in.nonfinite_displace:9:1"]);
}

/// Item 7: `-v NAME VALUE` is LAMMPS' short form of `-var` (it printed the version and exited
/// without running); `-h` is the help and `-version` the version.
#[test]
fn dash_v_defines_a_variable() {
    let small = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/decks/in.small_lj").to_string_lossy().into_owned();
    let t = expect("-in", &[&small, "-v", "nsteps", "3", "-log", "none"], 0, &["for 3 steps with 256 atoms"]);
    assert!(!t.contains("for 50 steps"), "{t}");
    expect("-h", &[], 0, &["usage:", "-var NAME VALUE...", "short form -v"]);
    expect("-version", &[], 0, &[&format!("dmhs {}", env!("CARGO_PKG_VERSION"))]);
}

/// Item 8: the log of a failed deck ends with the error text the screen (stderr) showed, as
/// LAMMPS' log ends with its ERROR line: a run that fails, a deck error, a set-up error.
#[test]
fn the_log_ends_with_the_error() {
    let decks = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/decks");
    for (d, code) in [(decks.join("in.lost_atoms"), 1), (decks.join("in.errors"), 2), (decks.join("reliability/in.missing_mass"), 2)] {
        let tmp = tempfile::tempdir().unwrap();
        let o = dmhs(&["run", d.to_str().unwrap(), "-log", "out.log"], tmp.path());
        assert_eq!(o.status.code(), Some(code), "{}", text(&o));
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        assert!(err.starts_with("error: "), "{err}");
        let log = std::fs::read_to_string(tmp.path().join("out.log")).unwrap();
        assert!(log.trim_end().ends_with(err.trim_end()), "log of {}:\n{log}\n--- stderr:\n{err}", d.display());
        // and the screen text before it is in the log too
        assert!(log.starts_with("dmhs "), "{log}");
    }
}

/// Item 9: a deck mistake found by the checks before a run is a deck error (exit 2) under
/// `run` as under `check`, with the same message.
#[test]
fn a_setup_error_is_exit_2_under_run_and_check() {
    let msg = "mass of atom type 2 is not set (use the mass command or a Masses section)";
    for sub in ["run", "check"] {
        let t = expect(sub, &[&deck("in.missing_mass"), "-log", "none"], 2, &[msg, "in.missing_mass:11:1"]);
        assert!(!t.contains("run stopped at step"), "{t}");
    }
}

/// Item 9: a command that would allocate more than the machine has is refused before it
/// allocates, in well under a second, saying how much it needs and how much there is.
#[cfg(target_os = "linux")]
#[test]
fn commands_that_need_more_memory_than_the_machine_are_refused_at_once() {
    // the most atoms create_atoms makes (2^31 sites or random atoms) need 259-272 GiB: refused on
    // a machine with less (and the test's ulimit of 2 GB would fail an attempt)
    let avail: f64 = std::fs::read_to_string("/proc/meminfo").unwrap().lines().find(|l| l.starts_with("MemAvailable:")).and_then(|l| l.split_whitespace().nth(1)?.parse().ok()).unwrap();
    if avail * 1024.0 < 2.5e11 {
        let t0 = std::time::Instant::now();
        expect("run", &[&deck("in.huge_create"), "-log", "none"], 2, &["in.huge_create:9:", "create_atoms would make about 2.147e9 atoms: this would need about 272.0 GiB of memory (2.147e9 atoms x 136 bytes)"]);
        expect("run", &[&deck("in.huge_create"), "-var", "style", "box", "-log", "none"], 2, &["create_atoms would make about 2.048e9 atoms: this would need about 2", "GiB of memory (2.048e9 atoms x 136 bytes)"]);
        assert!(t0.elapsed().as_secs_f64() < 2.0, "{:?}", t0.elapsed());
    }
    // bins of a histogram by the billion (a fuzz case: `compute rdf 4294967296` aborted on the
    // failed allocation of its first evaluation; counts above 2^31 - 1 are now out of range, as
    // in LAMMPS)
    if avail * 1024.0 < 6.0e10 {
        expect("check", &[&deck("in.huge_bins"), "-log", "none"], 2, &[
            "error: this would need about 59.6 GiB of memory (compute rdf: 2000000000 bins x 4 doubles)",
            "in.huge_bins:8:19",
            "error: this would need about 59.6 GiB of memory (fix ave/histo: 2000000000 bins x 4 doubles)",
            "in.huge_bins:9:37",
            "error: this would need about 2.91e4 TiB of memory (compute temp/profile: 1.0000e15 bins x 4 doubles)",
            "in.huge_bins:10:53",
        ]);
    }
}

/// `dmhs check` of a broken deck prints its errors and a closing count, not the half-built
/// set-up ("pair: none", "thermo every 0 steps"); a command that fails only because an earlier
/// definition was refused (pair_coeff after a misspelt pair_style, a group of a refused region,
/// unfix of a refused fix) is a note pointing at that error, not another error.
#[test]
fn check_of_a_broken_deck_prints_errors_and_their_count() {
    let d = deck("in.check_errors");
    let t = expect("check", &[&d], 2, &["unknown pair style `lj/cutt`", "unknown keyword `blok`", "unknown fix style `nvee`", "expected a number for temperature, found `abc`"]);
    assert!(t.trim_end().ends_with("4 errors"), "{t}");
    assert_eq!(t.matches("error: ").count(), 4, "{t}");
    for (line, msg, cause) in [(13, "pair_coeff used before pair_style", 12), (15, "region `wall` does not exist", 14), (17, "fix `1` does not exist", 16)] {
        assert!(t.contains(&format!("in.check_errors:{line}:")) && t.contains(&format!("{msg} (follows from the error at line {cause})")), "{t}");
    }
    for setup in ["pair: none", "thermo every", "models:", "is valid"] {
        assert!(!t.contains(setup), "`{setup}` after errors:\n{t}");
    }
    let t = expect("check", &[&deck("in.check_one_error")], 2, &["expected a number for mass, found `abc`", "in.check_one_error:5:16"]);
    assert!(t.trim_end().ends_with("1 error") && !t.contains("box:"), "{t}");
    // a valid deck still gets the set-up summary
    let small = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/decks/in.small_lj").to_string_lossy().into_owned();
    expect("check", &[&small], 0, &["pair lj/cut 2.5", "thermo every 10 steps", "is valid"]);
}

/// Found by tests/fuzz.rs: a box long in one dimension only (4 x 4 x 2^31 lattice units) runs;
/// the neighbour grid, its margins included, stays bounded (it was 2^24 bins times 7 x 7
/// margin bins, a 3 GB allocation that aborted).
#[test]
fn long_thin_boxes_run() {
    expect("run", &[&deck("in.long_box"), "-log", "none"], 0, &["for 5 steps with 2 atoms", "pe -0.2004681042"]);
    expect("check", &[&deck("in.long_box")], 0, &["is valid"]);
}

/// Found by tests/fuzz.rs: more atom types than dmhs' per-type tables hold are refused where
/// they are given, in create_box and in a data file's header (a 16 GB allocation aborted).
#[test]
fn absurd_type_counts_are_refused() {
    for sub in ["run", "check"] {
        expect(sub, &[&deck("in.many_types"), "-log", "none"], 2, &["number of atom types must be in 1..=4096, found 2147483647", "in.many_types:6:14"]);
        let data = deck("many_types.data");
        expect(sub, &[&deck("in.many_types_data"), "-var", "data", &data, "-log", "none"], 2, &["too many atom types: 2147483647; dmhs accepts at most 4096", "many_types.data:4:1"]);
        // found by tests/fuzz.rs (seed 44): read_data's extra bond types were not bounded
        let t = expect(sub, &[&deck("in.extra_types"), "-var", "data", &deck("one_bond.data"), "-log", "none"], 2, &["number of extra bond types must be in 0..=4096, found 2147483647", "in.extra_types:6:"]);
        assert!(!t.contains("memory allocation"), "{t}");
    }
}

/// Found by tests/fuzz.rs (seed 77): a fix wall/gran/region defined again with its ID replaced
/// the old fix, whose cleanup then removed the new one's history array (same name): a panic at
/// setup. The old fix is now removed first, as LAMMPS' Modify::add_fix deletes it.
#[test]
fn a_fix_defined_twice_keeps_its_per_atom_arrays() {
    for sub in ["run", "check"] {
        expect(sub, &[&deck("in.wall_gran_region_twice"), "-log", "none"], 0, &[]);
    }
}

/// Found by tests/fuzz.rs: `create_box 4000` in a pair granular deck needed 13.7 GB (a 350-byte
/// model per type pair) and aborted under the 2 GB limit. One model per distinct pair_coeff runs
/// in a few hundred MB; a style whose plain table does not fit (lj/cut: 48 bytes a pair) is
/// refused at its pair_style line.
#[test]
fn thousands_of_types_run_or_are_refused_at_the_pair_style() {
    let d = deck("in.types_4096");
    for sub in ["run", "check"] {
        let t = expect(sub, &[&d, "-log", "none"], 0, &[]);
        if sub == "run" {
            assert!(t.contains("for 20 steps with 2 atoms"), "{t}");
        }
    }
    let tmp = tempfile::tempdir().unwrap();
    let o = dmhs(&["-in", &d, "-var", "style", "lj", "-log", "none"], tmp.path());
    let t = text(&o);
    assert!(!t.contains("panicked") && !t.contains("RUST_BACKTRACE"), "{t}");
    match o.status.code() {
        Some(0) => assert!(t.contains("for 20 steps with 2 atoms"), "{t}"),
        Some(2) => assert!(t.contains("a pair style's table of (N+1)^2 = 16785409 type pairs") && t.contains("in.types_4096:"), "{t}"),
        c => panic!("exit {c:?}:\n{t}"),
    }
}

/// Found by tests/fuzz.rs: 100,400 atoms in a strip of a periodic box 1e19 long. Bins grow only
/// along the long dimension; with the bins of every dimension grown the strip was one bin and
/// each neighbour build O(N^2) (over 60 s).
#[test]
fn a_strip_in_a_huge_box_keeps_fine_bins() {
    expect("run", &[&deck("in.sparse_strip"), "-log", "none"], 0, &["for 2 steps with 100400 atoms"]);
}

/// A neighbour skin that reaches every atom: the list (3.2 GB for 40,000 atoms) is more than the
/// 2 GB the test allows, and the run stops with a located error naming the cutoff instead of
/// aborting in the allocator (found by the fuzz test: a mutated dam-break skin of 100).
#[test]
fn a_neighbour_list_larger_than_memory_is_an_error() {
    expect("-in", &[&deck("in.huge_skin"), "-log", "none"], 1, &["the neighbour list does not fit in memory", "the neighbour cutoff 1001 (pair cutoff + skin)", "in.huge_skin:16:1"]);
}
