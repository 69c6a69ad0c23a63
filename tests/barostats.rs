//! Barostats (fix npt, fix nph: LAMMPS' FixNH with pressure control) against LAMMPS: every
//! column of the thermo tables of the lammps-refs decks npt_* and nph_* (temperature, pressure
//! and its tensor, box lengths, the fix's energy f_ID and vector f_ID[i]) at every printed step,
//! against lammps-refs/refs/NAME/thermo.txt (and LAMMPS run now, when present). The per-atom
//! state after each run is compared by tests/lammps_parity.rs. And the refusals: bad barostat
//! commands are located errors.

mod thermo_tables;
use thermo_tables::{root, table};

/// iso with a pressure ramp; aniso with drag and chains of other lengths over two runs;
/// deviatoric nph with nreset, fixedpoint, ploop, ptemp; 2D nph coupled xy with a dilate group
/// and mtk no; bead-spring chains (bond virial) thermostatted with temp/com.
const DECKS: [&str; 5] = ["npt_iso", "npt_aniso", "nph_deviatoric", "nph_2d", "npt_chains_com"];

thermo_tables::thermo_table_tests!(DECKS);

/// The box follows the barostat: under a higher target pressure the liquid is denser. The
/// npt_iso deck at P 0.5 -> 1.0 against the same deck at 0.1 -> 0.1: a smaller volume at the end.
#[test]
fn higher_pressure_gives_a_smaller_box() {
    let deck = std::fs::read_to_string(root().join("lammps-refs/decks/in.npt_iso")).unwrap();
    let low = deck.replace("iso 0.5 1.0 1.0", "iso 0.1 0.1 1.0");
    assert_ne!(low, deck);
    let opts = dmhs::deck::DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let volume = |name: &str, text: &str| {
        let run = dmhs::deck::run_text(name, text, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
        let (names, rows) = table(run.sim.out.captured.as_deref().unwrap());
        let v = names.iter().position(|c| c == "Volume").unwrap();
        rows.last().unwrap()[v]
    };
    let (v_high, v_low) = (volume("npt_high", &deck), volume("npt_low", &low));
    println!("volume after 400 steps: P 0.5->1.0 {v_high}, P 0.1 {v_low}");
    assert!(v_high < v_low, "{v_high} !< {v_low}");
}

/// Bad barostat commands give located errors (`dmhs check` on the npt_iso deck, edited).
#[test]
fn barostat_errors_are_located() {
    let base = std::fs::read_to_string(root().join("lammps-refs/decks/in.npt_iso")).unwrap();
    let fix = "fix          1 all npt temp 1.2 1.2 0.5 iso 0.5 1.0 1.0";
    for (to, want) in [
        ("fix 1 all npt iso 0.5 0.5 1.0", "temperature control must be used with fix npt"),
        ("fix 1 all npt temp 1.2 1.2 0.5", "pressure control must be used with fix npt"),
        ("fix 1 all nph temp 1.2 1.2 0.5 iso 1 1 1", "temperature control cannot be used with fix nph"),
        ("fix 1 all nph iso 1 1 0.0", "Pdamp"),
        ("fix 1 all nph iso 1 1", "Pdamp"),
        ("fix 1 all nph tri 1 1 1", "triclinic"),
        ("fix 1 all nph xy 0 0 1", "triclinic"),
        ("fix 1 all nph x 1 1 1 couple xy", "coupled dimension has no pressure target"),
        ("fix 1 all nph x 1 1 1 y 2 2 1 couple xy", "the same Pstart"),
        ("fix 1 all nph iso 1 1 1 dilate nogroup", "dilate group ID nogroup does not exist"),
        ("fix 1 all nph iso 1 1 1 couple xzy", "couple"),
        ("fix 1 all nph iso 1 1 1 ptemp 0", "ptemp"),
        ("fix 1 all npt temp 1 1 1 iso 1 1 1 ptemp 1", "incompatible with the ptemp keyword"),
        ("fix 1 all nph iso 1 1 1 update dipole", "dipoles"),
        ("fix 1 all nph iso 1 1 1 wobble 1", "unknown keyword `wobble`"),
        ("fix 1 all nvt temp 1 1 1 dilate all", "barostat keyword"),
        ("change_box all boundary p p f\nfix 1 all nph iso 1 1 1", "non-periodic dimension (z)"),
        ("change_box all boundary p f p\nfix 1 all nph x 1 1 1 scalexy yes", "xy scaling when y is a non-periodic dimension"),
    ] {
        let deck = base.replacen(fix, to, 1);
        assert_ne!(deck, base);
        let tmp = tempfile::tempdir().unwrap();
        let path = tmp.path().join("in.baro");
        std::fs::write(&path, &deck).unwrap();
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_dmhs")).arg("check").arg(&path).current_dir(tmp.path()).output().unwrap();
        let out = format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
        assert_eq!(o.status.code(), Some(2), "{to}: {out}");
        assert!(out.contains(want) && out.contains("in.baro:"), "{to}: expected `{want}`:\n{out}");
    }
}

/// A barostat cannot share the box with fix deform, nor move rigid bodies: refused when the run
/// starts, naming both fixes; nph on a liquid at rest needs ptemp.
#[test]
fn barostat_run_refusals() {
    let base = std::fs::read_to_string(root().join("lammps-refs/decks/in.npt_iso")).unwrap();
    let fix = "fix          1 all npt temp 1.2 1.2 0.5 iso 0.5 1.0 1.0";
    let opts = dmhs::deck::DeckOptions { screen: false, capture_text: true, ..Default::default() };
    for (to, want) in [
        (format!("{fix}\nfix 2 all deform 1 x erate 0.01"), "with fix deform 2"),
        ("velocity all set 0 0 0\nfix 1 all nph iso 1 1 1".to_string(), "consider using the ptemp keyword"),
    ] {
        let deck = base.replacen(fix, &to, 1);
        let err = dmhs::deck::run_text("in.refuse", &deck, &opts).err().expect("a run error");
        assert!(err.rendered.contains(want), "{to}: expected `{want}`:\n{}", err.rendered);
    }
}
