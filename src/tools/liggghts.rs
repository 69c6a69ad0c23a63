//! LIGGGHTS 3.8 (Debian's `liggghts`) as a second reference engine for granular decks:
//! a LAMMPS/dmhs deck is translated to LIGGGHTS syntax, run, and its per-atom forces after the
//! setup of the first run and its final state are read back in the lammps-refs table format.
//!
//! The deck is first executed by dmhs in check mode (nothing runs), so variables, loops and
//! `$(...)` are already expanded; the translator sees the flat command stream. It handles the
//! granular subset: `atom_style sphere`, box and atom creation, `set`, groups, velocities,
//! `pair_style gran/hooke/history | gran/hooke | granular` (hooke, linear_history or
//! linear_nohistory, damping mass_velocity or velocity), `fix nve/sphere`, `nve`, `gravity`,
//! `wall/gran granular` planes, `neighbor`, `neigh_modify`, `timestep`, `thermo`, `run`.
//! Anything else is refused with a message naming the command.
//!
//! Mapping (see dem-contact-formulas.md): LIGGGHTS `pair_style gran model hooke/stiffness
//! tangential history` with `fix property/global kn kt gamman gammat coefficientFriction
//! peratomtypepair` (absolute_damping off: the damping coefficients are multiplied by m_eff,
//! exactly LAMMPS' gamma_n, gamma_t); `newton off`, `communicate single vel yes`; a wall plane
//! is `fix wall/gran model hooke/stiffness tangential history primitive type 1 zplane z` and
//! takes the type-1 coefficients, which must equal the deck's wall coefficients.
//! The two engines' normal forces agree; their tangential models coincide for sticking
//! contacts without rotation (LIGGGHTS does not damp a sliding contact and uses R - delta/2
//! as the lever and in the rolling velocity).
//!
//! For crosscheck runs the neighbour lists are rebuilt every step in LIGGGHTS
//! (`neigh_modify every 1 delay 0 check no` before the first run): LIGGGHTS 3.8 does not start
//! a contact that forms between two list builds from a zero tangential spring (observed: a
//! sphere resting on a wall meets a falling one and the new contact starts with a spring of the
//! size of the resting sphere's wall spring); with a rebuild every step it agrees with LAMMPS and
//! dmhs to round-off. Timing runs (bench) keep the deck's own settings.

use crate::tools::crosscheck::AtomTable;
use crate::deck::{run_file, DeckOptions};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The LIGGGHTS executable: `$DMHS_LIGGGHTS`, else `liggghts` on the PATH.
pub fn find_liggghts() -> Result<PathBuf, String> {
    if let Ok(p) = std::env::var("DMHS_LIGGGHTS") {
        let p = PathBuf::from(p);
        return if p.exists() { Ok(p) } else { Err(format!("DMHS_LIGGGHTS={} does not exist", p.display())) };
    }
    let path = std::env::var_os("PATH").unwrap_or_default();
    for dir in std::env::split_paths(&path) {
        let c = dir.join("liggghts");
        if c.is_file() {
            return Ok(c);
        }
    }
    Err("LIGGGHTS not found: install it (`apt-get install -y liggghts`) or set DMHS_LIGGGHTS to the executable".to_string())
}

/// Contact coefficients in LIGGGHTS' terms.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Coeffs {
    kn: f64,
    kt: f64,
    gamman: f64,
    gammat: f64,
    mu: f64,
    /// damping multiplied by m_eff (false: absolute, `damping velocity`)
    mass_scaled: bool,
    history: bool,
    limit: bool,
}

fn num(w: &str) -> Result<f64, String> {
    w.parse::<f64>().map_err(|_| format!("`{w}` is not a number"))
}

/// `hooke Kn eta [damping X] [tangential ...] [limit_damping]` words of pair granular or
/// wall/gran granular, up to a wall keyword.
fn granular_coeffs(w: &[String]) -> Result<(Coeffs, usize), String> {
    if w.first().map(|s| s.as_str()) != Some("hooke") {
        return Err("only the hooke normal model translates to LIGGGHTS".into());
    }
    let kn = num(w.get(1).ok_or("missing Kn")?)?;
    let eta = num(w.get(2).ok_or("missing eta_n0")?)?;
    let mut c = Coeffs { kn, kt: 0.0, gamman: eta, gammat: 0.0, mu: 0.0, mass_scaled: false, history: true, limit: false };
    let mut damping = "viscoelastic";
    let mut xgt = 0.0;
    let mut k = 3;
    while k < w.len() {
        match w[k].as_str() {
            "damping" => {
                damping = match w.get(k + 1).map(|s| s.as_str()) {
                    Some("mass_velocity") => "mass_velocity",
                    Some("velocity") => "velocity",
                    other => return Err(format!("damping {other:?} has no LIGGGHTS equivalent (use mass_velocity or velocity)")),
                };
                k += 2;
            }
            "tangential" => match w.get(k + 1).map(|s| s.as_str()) {
                Some("linear_history") => {
                    c.kt = num(w.get(k + 2).ok_or("missing Kt")?)?;
                    xgt = num(w.get(k + 3).ok_or("missing x_gt")?)?;
                    c.mu = num(w.get(k + 4).ok_or("missing mu")?)?;
                    k += 5;
                }
                Some("linear_nohistory") => {
                    c.history = false;
                    xgt = num(w.get(k + 2).ok_or("missing x_gt")?)?;
                    c.mu = num(w.get(k + 3).ok_or("missing mu")?)?;
                    k += 4;
                }
                other => return Err(format!("tangential {other:?} has no LIGGGHTS equivalent")),
            },
            "limit_damping" => {
                c.limit = true;
                k += 1;
            }
            "xplane" | "yplane" | "zplane" => break,
            other => return Err(format!("granular keyword `{other}` has no LIGGGHTS equivalent")),
        }
    }
    if damping == "viscoelastic" {
        return Err("the default damping (viscoelastic) has no LIGGGHTS hooke equivalent: add `damping mass_velocity`".into());
    }
    c.mass_scaled = damping == "mass_velocity";
    c.gammat = xgt * eta;
    Ok((c, k))
}

/// `gran/hooke/history Kn Kt gn gt mu dampflag [limit_damping]` (or gran/hooke).
fn classic_coeffs(w: &[String], history: bool) -> Result<Coeffs, String> {
    if w.len() < 6 {
        return Err("too few arguments".into());
    }
    let kn = num(&w[0])?;
    let kt = if w[1] == "NULL" { kn * 2.0 / 7.0 } else { num(&w[1])? };
    let gamman = num(&w[2])?;
    let mut gammat = if w[3] == "NULL" { 0.5 * gamman } else { num(&w[3])? };
    let mu = num(&w[4])?;
    if w[5] == "0" {
        gammat = 0.0;
    }
    Ok(Coeffs { kn, kt, gamman, gammat, mu, mass_scaled: true, history, limit: w.get(6).map(|s| s == "limit_damping").unwrap_or(false) })
}

/// Join words into a LIGGGHTS line (quoting words with spaces).
fn line(words: &[String]) -> String {
    words.iter().map(|w| if w.contains(char::is_whitespace) { format!("\"{w}\"") } else { w.clone() }).collect::<Vec<_>>().join(" ")
}

/// The LIGGGHTS input for a deck. With `out` set, per-atom forces are dumped after a `run 0`
/// before the first run (`out/forces0.dump`) and the final state at the end (`out/final.dump`).
pub fn translate(deck: &Path, vars: &[(String, Vec<String>)], out: Option<&Path>) -> Result<String, String> {
    let dir = deck.parent().filter(|p| !p.as_os_str().is_empty()).map(Path::to_path_buf).unwrap_or_else(|| PathBuf::from("."));
    let opts = DeckOptions { vars: vars.to_vec(), base_dir: Some(dir), check_only: true, record_commands: true, ..Default::default() };
    let run = run_file(deck, &opts).map_err(|f| f.rendered)?;
    if let Some(e) = run.check_errors.first() {
        return Err(format!("the deck has errors (dmhs check): {}", e.message));
    }
    let ntypes = run.sim.state.ntypes;
    let commands = run.sim.command_log.unwrap_or_default();
    let mut t = String::from("# translated from a dmhs/LAMMPS deck by dmhs (src/liggghts.rs)\n");
    let mut pair: Option<Coeffs> = None;
    let mut pair_style: Option<String> = None;
    let mut first_run = true;
    let table = |name: &str, v: f64| {
        let vals = vec![format!("{v:?}"); ntypes * ntypes].join(" ");
        format!("fix dmhs_{name} all property/global {name} peratomtypepair {ntypes} {vals}\n")
    };
    let pair_lines = |c: &Coeffs| -> String {
        let mut s = String::new();
        s += &table("kn", c.kn);
        s += &table("kt", c.kt);
        if c.mass_scaled {
            s += &table("gamman", c.gamman);
            s += &table("gammat", c.gammat);
        } else {
            s += &table("gamman_abs", c.gamman);
            s += &table("gammat_abs", c.gammat);
        }
        s += &table("coefficientFriction", c.mu);
        s
    };
    let model = |c: &Coeffs| -> String {
        let mut m = format!("model hooke/stiffness tangential {}", if c.history { "history" } else { "no_history" });
        if !c.mass_scaled {
            m += " absolute_damping on";
        }
        if c.limit {
            m += " limitForce on";
        }
        if c.gammat == 0.0 {
            m += " tangential_damping off";
        }
        m
    };
    for w in &commands {
        let name = w[0].as_str();
        let args = &w[1..];
        let why = |why: &str| format!("`{}` cannot be translated to LIGGGHTS: {why}", line(w));
        let refuse = |w: &str| Err(why(w));
        match name {
            "set" if args.iter().any(|a| a == "omega") => return refuse("LIGGGHTS' set has no omega keyword"),
            "units" | "dimension" | "boundary" | "lattice" | "region" | "create_box" | "create_atoms" | "mass" | "group" | "velocity"
            | "displace_atoms" | "delete_atoms" | "neighbor" | "timestep" | "set" | "thermo" | "unfix" | "reset_timestep" | "read_data" => {
                t += &line(w);
                t.push('\n');
            }
            "atom_style" => {
                if args.len() != 1 || args[0] != "sphere" {
                    return refuse("only atom_style sphere (LIGGGHTS granular) is translated");
                }
                t += "atom_style granular\natom_modify map array\nnewton off\n";
            }
            "atom_modify" | "newton" | "processors" | "thermo_modify" | "compute" | "uncompute" | "dump" | "dump_modify" | "undump" | "write_data" | "write_restart" => {}
            "thermo_style" => t += "thermo_style custom step atoms ke\n",
            "comm_modify" => {
                if args.windows(2).any(|p| p[0] == "vel" && p[1] == "yes") {
                    t += "communicate single vel yes\n";
                }
            }
            "neigh_modify" => {
                if args.iter().any(|a| a == "exclude") {
                    return refuse("neighbour exclusions are not translated");
                }
                t += &line(w);
                t.push('\n');
            }
            "pair_style" => match args.first().map(|s| s.as_str()) {
                Some("gran/hooke/history") | Some("gran/hooke") => {
                    let c = classic_coeffs(&args[1..], args[0] == "gran/hooke/history").map_err(|e| why(&e))?;
                    t += &pair_lines(&c);
                    t += &format!("pair_style gran {}\n", model(&c));
                    pair = Some(c);
                    pair_style = Some(args[0].clone());
                }
                Some("granular") => {
                    if args.len() > 1 {
                        return refuse("a global cutoff is not translated");
                    }
                    pair_style = Some("granular".into());
                    pair = None;
                }
                _ => return refuse("only gran/hooke, gran/hooke/history and granular are translated"),
            },
            "pair_coeff" => {
                if args.len() < 2 || args[0] != "*" || args[1] != "*" {
                    return refuse("only `pair_coeff * *` (one set of coefficients for all types) is translated");
                }
                if pair_style.as_deref() == Some("granular") {
                    let (c, used) = granular_coeffs(&args[2..]).map_err(|e| why(&e))?;
                    if used != args.len() - 2 {
                        return refuse("unexpected words after the granular model");
                    }
                    t += &pair_lines(&c);
                    t += &format!("pair_style gran {}\n", model(&c));
                    pair = Some(c);
                }
                t += "pair_coeff * *\n";
            }
            "fix" => {
                let style = args.get(2).map(|s| s.as_str()).unwrap_or("");
                match style {
                    "nve" | "nve/sphere" | "gravity" | "setforce" | "addforce" | "viscous" | "enforce2d" => {
                        t += &line(w);
                        t.push('\n');
                    }
                    "wall/gran" => {
                        if args.get(3).map(|s| s.as_str()) != Some("granular") {
                            return refuse("only the `granular` form of fix wall/gran is translated");
                        }
                        let (c, used) = granular_coeffs(&args[4..]).map_err(|e| why(&e))?;
                        let p = pair.ok_or_else(|| format!("`{}`: define the pair style before the wall", line(w)))?;
                        if c != p {
                            return refuse("the wall coefficients must equal the pair coefficients (LIGGGHTS takes them from atom type 1)");
                        }
                        let rest = &args[4 + used..];
                        if rest.len() != 3 {
                            return refuse("only a plane with lo and hi (and no wiggle/shear) is translated");
                        }
                        for (k, bound) in rest[1..].iter().enumerate() {
                            if bound != "NULL" {
                                t += &format!("fix {}_{k} {} wall/gran {} primitive type 1 {} {bound}\n", args[0], args[1], model(&c), rest[0]);
                            }
                        }
                    }
                    _ => return refuse("this fix style is not translated"),
                }
            }
            "run" => {
                if first_run {
                    first_run = false;
                    if let Some(out) = out {
                        // LIGGGHTS 3.8 does not start a contact that forms between two list builds
                        // from a zero spring; rebuilt every step it agrees with LAMMPS and dmhs
                        t += "neigh_modify every 1 delay 0 check no\n";
                        t += &format!(
                            "dump dmhs_f0 all custom 1 {} id type fx fy fz tqx tqy tqz\n\
                             dump_modify dmhs_f0 sort id format \"%d %d %.17g %.17g %.17g %.17g %.17g %.17g\"\nrun 0\nundump dmhs_f0\n",
                            out.join("forces0.dump").display()
                        );
                    }
                }
                t += &line(w);
                t.push('\n');
            }
            _ => return refuse("this command is not translated"),
        }
    }
    if let Some(out) = out {
        t += &format!(
            "dump dmhs_fin all custom 1 {} id type xu yu zu vx vy vz omegax omegay omegaz\n\
             dump_modify dmhs_fin sort id format \"%d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"\nrun 0\n",
            out.join("final.dump").display()
        );
    }
    Ok(t)
}

/// Run LIGGGHTS on an input text with the deck's folder as working directory.
fn run_input(deck: &Path, input: &str, tmp: &Path) -> Result<String, String> {
    run_input_measured(deck, input, tmp).map(|(text, _)| text)
}

/// `run_input`, with the peak memory of the LIGGGHTS process.
fn run_input_measured(deck: &Path, input: &str, tmp: &Path) -> Result<(String, Option<u64>), String> {
    let exe = find_liggghts()?;
    let file = tmp.join("in.liggghts");
    std::fs::write(&file, input).map_err(|e| format!("cannot write {}: {e}", file.display()))?;
    if let Ok(keep) = std::env::var("DMHS_LIGGGHTS_KEEP") {
        // for debugging a translation: keep a copy of the input
        let _ = std::fs::write(keep, input);
    }
    let dir = deck.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let mut cmd = Command::new(&exe);
    cmd.current_dir(dir).arg("-in").arg(&file).arg("-log").arg("none").arg("-echo").arg("none").env("OMP_NUM_THREADS", "1");
    let name = exe.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let o = crate::tools::measure::run_measured(&mut cmd, &name, std::time::Duration::from_millis(50)).map_err(|e| format!("cannot run {}: {e}", exe.display()))?;
    if !o.status.success() || o.stdout.contains("ERROR") {
        let err: Vec<&str> = o.stdout.lines().filter(|l| l.contains("ERROR")).collect();
        return Err(format!("LIGGGHTS failed on {} (exit {}): {}\n{}", deck.display(), o.status.code().unwrap_or(-1), err.join("\n"), o.stderr));
    }
    Ok((o.stdout, o.peak_bytes))
}

/// Read a `dump custom` file with a sorted, single-snapshot ATOMS section into a table.
fn read_dump(path: &Path, columns: &[&str]) -> Result<AtomTable, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    // the last snapshot
    let at = text.rfind("ITEM: ATOMS").ok_or_else(|| format!("{}: no ATOMS section", path.display()))?;
    let mut lines = text[at..].lines();
    lines.next();
    let mut table = format!("# id type {}\n", columns.join(" "));
    for l in lines {
        if l.starts_with("ITEM:") {
            break;
        }
        table += l.trim();
        table.push('\n');
    }
    AtomTable::parse(&table).map_err(|e| format!("{}: {e}", path.display()))
}

/// Run a deck in LIGGGHTS; write `forces0.txt` and `final.txt` (lammps-refs format) to `out`.
pub fn run_driver(deck: &Path, vars: &[(String, Vec<String>)], out: &Path) -> Result<(), String> {
    let input = translate(deck, vars, Some(out))?;
    run_input(deck, &input, out)?;
    let f0 = read_dump(&out.join("forces0.dump"), &["fx", "fy", "fz", "tqx", "tqy", "tqz"])?;
    let fin = read_dump(&out.join("final.dump"), &["xu", "yu", "zu", "vx", "vy", "vz", "omegax", "omegay", "omegaz"])?;
    std::fs::write(out.join("forces0.txt"), f0.to_text()).map_err(|e| e.to_string())?;
    std::fs::write(out.join("final.txt"), fin.to_text()).map_err(|e| e.to_string())?;
    Ok(())
}

/// Time a deck in LIGGGHTS (serial): (seconds of the last run's loop, steps, atoms).
pub fn time_liggghts(deck: &Path, vars: &[(String, Vec<String>)]) -> Result<crate::tools::lammps::RunTiming, String> {
    let input = translate(deck, vars, None)?;
    let tmp = tempfile::tempdir().map_err(|e| e.to_string())?;
    let (text, peak_bytes) = run_input_measured(deck, &input, tmp.path())?;
    let (seconds, steps, atoms) = crate::tools::lammps::parse_loop_time(&text).ok_or_else(|| format!("no `Loop time` line in LIGGGHTS output for {}", deck.display()))?;
    Ok(crate::tools::lammps::RunTiming { seconds, steps, atoms, peak_bytes })
}
