//! `run N ... every M c1 c2 ...`: the segments, their ramps, setups and summaries, the commands
//! between them, and how it meets fix halt, as LAMMPS 22 Jul 2025 does (the lines below are
//! LAMMPS' own output of the same decks).

use dmhs::deck::{run_text, DeckOptions};

mod common;

const LJ: &str = "units lj\natom_style atomic\nlattice fcc 0.8442\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
    velocity all create 3.0 87287 loop geom\npair_style lj/cut 2.5\npair_coeff 1 1 1.0 1.0 2.5\nfix 1 all nve\n";

fn screen(deck: &str) -> String {
    let opts = DeckOptions { screen: false, capture_text: true, ..Default::default() };
    let run = run_text("every.deck", deck, &opts).unwrap_or_else(|f| panic!("{}", f.rendered));
    run.sim.out.captured.clone().unwrap()
}

/// Three runs: 25 steps in segments of 10 with two commands after each (the last segment is 5
/// steps; each segment ramps ramp(0,1) over itself); 40 upto with pre and post no in segments
/// of 7 (one setup banner, thermo header each segment); 10 steps with start/stop (the ramp over
/// 0..100) in segments of 5. LAMMPS prints the same lines and thermo rows.
#[test]
fn segments_as_lammps() {
    let deck = format!(
        "{LJ}fix 2 all temp/berendsen 3.0 1.0 0.5\nvariable r equal ramp(0,1)\nthermo_style custom step temp pe v_r\nthermo_modify format float %.10g\nthermo 10\n\
         run 25 every 10 \"print 'now $(step) r=${{r}}'\" \"print second\"\nrun 40 upto pre no post no every 7 NULL\nrun 10 start 0 stop 100 every 5 \"print 'x $(step) $r'\"\n"
    );
    let text = screen(&deck);
    let printed: Vec<&str> = text.lines().filter(|l| l.starts_with("now ") || l.starts_with("second") || l.starts_with("x ")).collect();
    assert_eq!(printed, ["now 10 r=1", "second", "now 20 r=1", "second", "now 25 r=1", "second", "x 45 0.45", "x 50 0.5"]);
    let rows: Vec<&str> = text.lines().filter(|l| l.starts_with("        ")).map(|l| l.trim()).collect();
    // LAMMPS' thermo rows (step, temp, pe, ramp) of the upto run and the last one
    for want in [
        "25  1.637175286 -4.805485387 0",
        "30  1.681416807 -4.833554134 0.7142857143",
        "32  1.698205672 -4.876572128 1",
        "39  1.618519719 -4.736952946 1",
        "40  1.595250298 -4.710290046 1",
        "40  1.595250298 -4.710290046 0.4",
        "50  1.757511532 -4.890997892 0.5",
    ] {
        assert!(rows.contains(&want), "no row `{want}` in:\n{}", rows.join("\n"));
    }
    // banners: 3 segments of the first run, 1 of the upto run (pre no), 2 of the last
    assert_eq!(text.matches("Setting up Verlet run").count(), 6);
}

/// A fix halt ending the runs stops the segments: LAMMPS prints after 5, after 10, the halt at
/// 13, after 13 (the commands of the segment the halt cut short), and nothing more.
#[test]
fn halt_stops_the_segments() {
    let deck = format!("{LJ}variable s equal step\nfix h all halt 1 v_s >= 13 error soft\nrun 40 every 5 \"print 'after $(step)'\"\nprint \"end $(step)\"\n");
    let text = screen(&deck);
    let lines: Vec<&str> = text.lines().filter(|l| l.starts_with("after") || l.starts_with("end") || l.starts_with("Fix halt")).collect();
    assert_eq!(lines, ["after 5", "after 10", "Fix halt condition for fix-id h met on step 13 with value 13", "after 13", "end 13"]);
}

#[test]
fn bad_every_is_located() {
    for (run, want) in [
        ("run 10 every 0 NULL", "every M must be an integer > 0"),
        ("run 10 every 5", "missing commands"),
        ("run 10 every", "missing M"),
        ("run ten every 5 NULL", "run N must be an integer"),
        ("run 10\nrun 5 upto every 2 NULL", "Invalid run command upto value: 5. Must be >= 10"),
        ("run 10 every 5 \"bogus_command 1\"", "bogus_command"),
    ] {
        let deck = format!("{LJ}{run}\n");
        let f = run_text("bad.deck", &deck, &Default::default()).err().unwrap_or_else(|| panic!("accepted: {run}"));
        assert!(f.rendered.contains("bad.deck:") && f.rendered.contains(want), "{run}: {}", f.rendered);
    }
}
