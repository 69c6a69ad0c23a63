//! Global settings: units, dimension, boundary, atom_style, newton, timestep, neighbor, ...

use super::before_box;
use crate::engine::atoms::{AtomFeatures, Atoms};
use crate::engine::domain::BoundaryKind;
use crate::sim::Simulation;
use crate::engine::special::SpecialBonds;
use crate::engine::units::{UnitStyle, Units};
use dmhs_parser::{Args, Command, DResult, Diagnostic, SourceMap, Word};

pub fn units(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    before_box(sim, cmd)?;
    let mut a = Args::new(cmd, "units lj|si|cgs");
    let w = a.word("unit style")?;
    let style = match w.text.as_str() {
        "lj" => UnitStyle::Lj,
        "si" => UnitStyle::Si,
        "cgs" => UnitStyle::Cgs,
        "real" | "metal" | "electron" | "micro" | "nano" => {
            return Err(a.error_at(w, format!("units {} is a LAMMPS unit style that dmhs does not support yet", w.text), "supported: lj, si, cgs"))
        }
        _ => {
            a.skip(0);
            return Err(a.error_at(w, format!("unknown unit style `{}`", w.text), "expected lj, si or cgs"));
        }
    };
    a.finish()?;
    let old = sim.state.units;
    sim.state.units = Units::new(style);
    // defaults that follow the unit style unless the user set them
    if !sim.state.dt_set {
        sim.state.dt = sim.state.units.dt;
    }
    if sim.state.neigh_settings.skin == old.skin {
        sim.state.neigh_settings.skin = sim.state.units.skin;
    }
    Ok(())
}

pub fn dimension(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    before_box(sim, cmd)?;
    let mut a = Args::new(cmd, "dimension 2|3");
    sim.state.dimension = a.i64_in("dimension", 2, 3)? as usize;
    a.finish()?;
    if sim.state.dimension == 2 {
        sim.state.boundary[2] = [BoundaryKind::Periodic; 2];
    }
    Ok(())
}

pub fn boundary(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    before_box(sim, cmd)?;
    let syntax = "boundary x y z  (each p, f, s, m or a pair like fs)";
    let mut a = Args::new(cmd, syntax);
    for what in ["x boundary", "y boundary", "z boundary"] {
        a.word(what)?;
    }
    a.finish()?;
    sim.state.boundary = parse_boundary(&cmd.args[..3], sim.state.dimension)?;
    Ok(())
}

/// The three words of `boundary x y z` (each p, f, s, m or a pair such as fs).
pub(super) fn parse_boundary(words: &[Word], dim: usize) -> DResult<[[BoundaryKind; 2]; 3]> {
    let letter = |c: char| match c {
        'p' => Some(BoundaryKind::Periodic),
        'f' => Some(BoundaryKind::Fixed),
        's' => Some(BoundaryKind::Shrink),
        'm' => Some(BoundaryKind::ShrinkMin),
        _ => None,
    };
    let mut b = [[BoundaryKind::Periodic; 2]; 3];
    for (d, w) in words.iter().enumerate() {
        let chars: Vec<char> = w.text.chars().collect();
        let pair = match chars.as_slice() {
            [c] => letter(*c).map(|k| [k, k]),
            [c1, c2] => letter(*c1).zip(letter(*c2)).map(|(k1, k2)| [k1, k2]),
            _ => None,
        };
        let Some(pair) = pair else {
            return Err(Diagnostic::at(w.span, format!("invalid boundary `{}`", w.text), "expected p, f, s, m or a pair of f/s/m"));
        };
        if (pair[0] == BoundaryKind::Periodic) != (pair[1] == BoundaryKind::Periodic) {
            return Err(Diagnostic::at(w.span, "both faces must be periodic or neither", "mixed periodic boundary"));
        }
        b[d] = pair;
    }
    if dim == 2 && b[2][0] != BoundaryKind::Periodic {
        return Err(Diagnostic::at(words[2].span, "a 2d simulation must be periodic in z", "must be p"));
    }
    Ok(b)
}

/// The atom styles dmhs implements (LAMMPS names).
pub const ATOM_STYLES: &[&str] = &["atomic", "bond", "angle", "molecular", "full", "charge", "sphere", "bpm/sphere", "sph", "hybrid"];

/// Features of an atom style given as words (`hybrid a b ...` included).
pub fn features_of(styles: &[&str]) -> Result<AtomFeatures, String> {
    let mut f = AtomFeatures::default();
    for &s in styles {
        match s {
            "atomic" => {}
            "bond" => {
                f.molecule = true;
                f.bonds = true;
            }
            "angle" => {
                f.molecule = true;
                f.bonds = true;
                f.angles = true;
            }
            "molecular" => {
                f.molecule = true;
                f.bonds = true;
                f.angles = true;
                f.dihedrals = true;
            }
            "full" => {
                f.molecule = true;
                f.charge = true;
                f.bonds = true;
                f.angles = true;
                f.dihedrals = true;
            }
            "charge" => f.charge = true,
            "sphere" => f.sphere = true,
            // LAMMPS' AtomVecBPMSphere: molecular (bonds only) finite-size spheres with orientations
            "bpm/sphere" => {
                f.molecule = true;
                f.bonds = true;
                f.sphere = true;
                f.quat = true;
            }
            "sph" => f.sph = true,
            other => return Err(other.to_string()),
        }
    }
    Ok(f)
}

pub fn atom_style(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    before_box(sim, cmd)?;
    let syntax = "atom_style atomic|bond|angle|molecular|full|charge|sphere|bpm/sphere|sph|hybrid style1 style2 ...";
    let a = Args::new(cmd, syntax);
    let Some(first) = cmd.args.first() else { return Err(a.missing("an atom style")) };
    let mut names: Vec<&str> = vec![];
    if first.text == "hybrid" {
        let subs = &cmd.args[1..];
        if subs.is_empty() {
            return Err(a.missing("the sub-styles of atom_style hybrid"));
        }
        for w in subs {
            if w.text == "hybrid" {
                return Err(a.error_at(w, "atom_style hybrid cannot contain hybrid", "not allowed"));
            }
            // `sphere 0|1` takes an optional flag (1: dynamic radius, which LAMMPS then sends to
            // ghosts at every step; dmhs always does)
            if (w.text == "0" || w.text == "1") && matches!(names.last(), Some(&("sphere" | "bpm/sphere"))) {
                continue;
            }
            if !ATOM_STYLES.contains(&w.text.as_str()) {
                return Err(crate::models::styles::unsupported_style("atom_style", w, &w.text, ATOM_STYLES));
            }
            names.push(&w.text);
        }
    } else {
        if !ATOM_STYLES.contains(&first.text.as_str()) {
            return Err(crate::models::styles::unsupported_style("atom_style", first, &first.text, ATOM_STYLES));
        }
        names.push(&first.text);
        let rest = &cmd.args[1..];
        let takes_flag = first.text == "sphere" || first.text == "bpm/sphere";
        let ok_extra = takes_flag && rest.len() == 1 && (rest[0].text == "0" || rest[0].text == "1");
        if !rest.is_empty() && !ok_extra {
            return Err(a.error_at(&rest[0], format!("unexpected argument `{}`", rest[0].text), "not expected here"));
        }
    }
    let features = features_of(&names).unwrap();
    sim.state.atom_style = cmd.args.iter().map(|w| w.text.clone()).filter(|t| t != "0").collect();
    sim.state.atoms = Atoms::new(features);
    Ok(())
}

pub fn atom_modify(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let syntax = "atom_modify keyword value ...  (map array|hash|yes, sort Nfreq binsize, id yes, first group)";
    let mut a = Args::new(cmd, syntax);
    if a.is_empty() {
        return Err(a.missing("a keyword"));
    }
    while let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            "map" => {
                a.choice("map style", &["array", "hash", "yes"])?;
            }
            // dmhs sorts its own atoms at every rebuild; the setting gives LAMMPS' order, which
            // fixes that draw random numbers per atom follow (engine/lammps_order.rs)
            "sort" => {
                if sim.state.lammps_order.first.is_some() {
                    return Err(a.error_at(w, "atom_modify sort and first options cannot be used together", "first GROUP already set"));
                }
                sim.state.lammps_order.sortfreq = a.i64_in("sort frequency", 0, i64::MAX)?;
                sim.state.lammps_order.binsize = a.non_negative_f64("sort bin size")?;
            }
            "id" => {
                if !a.yes_no("id")? {
                    return Err(a.error_at(a.last().unwrap(), "atom_modify id no is not supported (atoms always have IDs)", "use yes"));
                }
            }
            // LAMMPS keeps the group's atoms first in its local order, and stops sorting
            "first" => {
                let g = a.word("group ID")?;
                if g.text == "all" {
                    sim.state.lammps_order.first = None;
                } else {
                    sim.state.lammps_order.first = Some(g.text.clone());
                    sim.state.lammps_order.sortfreq = 0;
                }
            }
            _ => return Err(a.unknown_keyword(w, &["map", "sort", "id", "first"])),
        }
    }
    Ok(())
}

pub fn newton(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "newton on|off [on|off]");
    let pair = a.on_off("newton pair setting")?;
    let bond = if a.is_empty() { pair } else { a.on_off("newton bond setting")? };
    a.finish()?;
    // results do not depend on these (see docs/commands.md); they are recorded for check output
    sim.state.newton_pair = pair;
    sim.state.newton_bond = bond;
    Ok(())
}

/// `processors Px Py Pz [grid onelevel|twolevel Nc Cx Cy Cz|custom infile] [map
/// cart|cart/reorder|xyz|xzy|yxz|yzx|zxy|zyx] [file outfile]`: the processor grid of a run on
/// several ranks (src/engine/procmap.rs). Before the box, as LAMMPS requires: the grid is chosen
/// for the box as it is made (`State::grid_areas`); the ranks are laid out at each run's start.
pub fn processors(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    use crate::engine::procmap::{layout, read_custom, GridStyle, MapStyle, ProcSettings};
    // LAMMPS sets the grid when it makes the box: "Processors command after simulation box is defined"
    super::before_box(sim, cmd)?;
    let ranks = sim.nranks();
    const SYNTAX: &str = "processors Px Py Pz [grid onelevel|twolevel Nc Cx Cy Cz|custom infile] [map cart|cart/reorder|xyz|xzy|yxz|yzx|zxy|zyx] [file outfile]  (each P * or a count; their product the number of ranks)";
    let mut a = Args::new(cmd, SYNTAX);
    let mut settings = ProcSettings::default();
    let counts = |a: &mut Args, names: [&str; 3]| -> DResult<[Option<usize>; 3]> {
        let mut user = [None; 3];
        for (d, what) in names.into_iter().enumerate() {
            let w = a.word(what)?;
            if w.text != "*" {
                let n: usize = w.text.parse().ok().filter(|&n| n > 0).ok_or_else(|| a.error_at(w, format!("{what} must be * or a positive count, not `{}`", w.text), "expected * or a count"))?;
                user[d] = Some(n);
            }
        }
        Ok(user)
    };
    settings.user = counts(&mut a, ["Px", "Py", "Pz"])?;
    while let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            "grid" => {
                let g = a.word("grid style")?;
                settings.grid = match g.text.as_str() {
                    "onelevel" => GridStyle::OneLevel,
                    "twolevel" => {
                        let ncores = a.i64_in("Nc (cores per node)", 1, i32::MAX as i64)? as usize;
                        let user_cores = counts(&mut a, ["Cx", "Cy", "Cz"])?;
                        if user_cores.iter().all(|c| c.is_some()) && user_cores.iter().map(|c| c.unwrap()).product::<usize>() != ncores {
                            return Err(a.error_at(g, format!("Cx Cy Cz must multiply to Nc = {ncores}"), "cores per node"));
                        }
                        GridStyle::TwoLevel { ncores, user_cores }
                    }
                    "numa" => return Err(a.error_at(g, "processors grid numa is not supported: LAMMPS places its NUMA domains by a machine detection dmhs does not reproduce; grid twolevel Nc * * * with the cores per node gives each node a contiguous block the same way", "use grid twolevel")),
                    "custom" => {
                        let fw = a.word("infile")?;
                        let path = sim.path(&fw.text);
                        let text = std::fs::read_to_string(&path).map_err(|e| a.error_at(fw, format!("cannot open processors custom file `{}`: {e}", path.display()), "this file"))?;
                        let (procs, places) = read_custom(&text).map_err(|(line, e)| a.error_at(fw, format!("processors custom grid file {}:{line}: {e}", path.display()), "this file"))?;
                        GridStyle::Custom { procs, places }
                    }
                    _ => return Err(a.error_at(g, format!("unknown grid style `{}`", g.text), "expected onelevel, twolevel, numa or custom")),
                };
            }
            "map" => {
                let m = a.word("map style")?;
                settings.map = MapStyle::parse(&m.text).ok_or_else(|| a.error_at(m, format!("unknown map style `{}`", m.text), "expected cart, cart/reorder, xyz, xzy, yxz, yzx, zxy or zyx"))?;
            }
            "file" => settings.file = Some(a.word("outfile")?.text.clone()),
            "part" => return Err(a.error_at(w, "processors part links the grids of several partitions (the -partition switch), which dmhs does not run", "one partition")),
            _ => return Err(a.unknown_keyword(w, &["grid", "map", "part", "file"])),
        }
    }
    // the counts checked against the ranks this run has
    if let Err(e) = layout(ranks, &settings, [1.0; 3], sim.state.dimension) {
        return Err(a.error_at(&cmd.args[0], format!("{e} (dmhs runs on {ranks} rank{})", if ranks == 1 { "" } else { "s" }), "a grid of the ranks"));
    }
    if ranks == 1 {
        // one rank: the grid is 1 by 1 by 1 whatever the box (a run on ranks writes it when it
        // lays them out)
        if let Some(f) = &settings.file {
            let path = sim.path(f);
            let text = crate::engine::procmap::Layout::cartesian([1; 3]).file_text(&[crate::engine::comm::host_name()]);
            crate::output::log::write_atomic(&path, text.as_bytes()).map_err(|e| a.error_at(cmd.args.last().unwrap_or(&cmd.name), format!("Cannot open processors output file {}: {e}", path.display()), "outfile"))?;
        }
    }
    sim.state.procs = settings;
    Ok(())
}

/// `comm_style brick|tiled`: how MPI sub-domains are shaped; one process has one.
pub fn comm_style(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "comm_style brick|tiled");
    a.choice("comm_style", &["brick", "tiled"])?;
    a.finish()?;
    let _ = sim;
    Ok(())
}

/// `balance thresh style args ... [keywords]`: LAMMPS' load balancing of MPI sub-domains. One
/// process has nothing to balance; a run on several ranks balances by itself (a note says so).
pub fn balance(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "balance thresh x|y|z|shift|rcb args ... [keyword value ...]");
    a.f64_where("thresh", "thresh >= 1.0", |t| t >= 1.0)?;
    a.choice("balance style", &["x", "y", "z", "shift", "rcb"])?;
    sim.out.print(if sim.nranks() > 1 {
        "note: balance does nothing now: a run on several ranks balances its sub-domains at its start and whenever one rank owns 1.2x the mean at a rebuild"
    } else {
        "note: balance does nothing: dmhs runs one process, which has nothing to balance"
    });
    Ok(())
}

pub fn timestep(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "timestep dt");
    let dt = a.f64("dt")?;
    a.finish()?;
    let old = (sim.state.atime, sim.state.atimestep, sim.state.dt);
    sim.state.atime = sim.state.time();
    sim.state.atimestep = sim.state.step;
    sim.state.dt = dt;
    for f in &mut sim.fixes {
        if let Err(e) = f.reset_dt(&sim.state) {
            (sim.state.atime, sim.state.atimestep, sim.state.dt) = old;
            return Err(a.error_at(&cmd.name, e, "a fix depends on the timestep"));
        }
    }
    sim.state.dt_set = true;
    Ok(())
}

pub fn neighbor(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "neighbor skin bin|nsq|multi");
    let skin = a.non_negative_f64("skin")?;
    let multi = a.choice("neighbor style", &["bin", "nsq", "multi"])? == 2;
    a.finish()?;
    sim.state.neigh_settings.skin = skin;
    sim.state.neigh_settings.multi = multi;
    sim.state.lists_valid = false;
    Ok(())
}

pub fn neigh_modify(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let syntax = "neigh_modify keyword value ...  (every N, delay N, check yes|no, once yes|no, one N, page N, binsize x, exclude type|group|molecule/intra|molecule/inter|none ...)";
    let mut a = Args::new(cmd, syntax);
    if a.is_empty() {
        return Err(a.missing("a keyword"));
    }
    let keys = ["every", "delay", "check", "once", "one", "page", "binsize", "exclude", "cluster"];
    let ntypes = sim.state.ntypes;
    while let Some(w) = a.peek() {
        a.skip(1);
        let s = &mut sim.state.neigh_settings;
        match w.text.as_str() {
            "every" => s.every = a.i64_in("every", 1, i64::MAX)?,
            "delay" => s.delay = a.i64_in("delay", 0, i64::MAX)?,
            "check" => s.check = a.yes_no("check")?,
            "once" => s.once = a.yes_no("once")?,
            "cluster" => {
                a.yes_no("cluster")?;
            }
            // list storage grows as needed: the limits are accepted and not needed
            "one" | "page" => {
                a.i64_in(&w.text, 1, i64::MAX)?;
            }
            "binsize" => s.binsize = a.f64("binsize")?,
            "exclude" => {
                let kind = a.choice("exclusion kind", &["type", "group", "molecule/intra", "molecule/inter", "molecule", "none"])?;
                match kind {
                    0 => {
                        if ntypes == 0 {
                            return Err(a.error_at(w, "neigh_modify exclude type needs the box (atom types) to be defined", "no box yet"));
                        }
                        let t1 = a.i64_in("type 1", 1, ntypes as i64)? as usize;
                        let t2 = a.i64_in("type 2", 1, ntypes as i64)? as usize;
                        sim.state.neigh_settings.exclusions.types.push((t1, t2));
                    }
                    1 => {
                        let g1 = group_bit(&mut a, &sim.state.groups)?;
                        let g2 = group_bit(&mut a, &sim.state.groups)?;
                        sim.state.neigh_settings.exclusions.groups.push((g1, g2));
                    }
                    2..=4 => {
                        if !sim.state.atoms.features.molecule {
                            return Err(a.error_at(w, "neigh_modify exclude molecule needs an atom style with molecule IDs", "no molecule IDs"));
                        }
                        let g = group_bit(&mut a, &sim.state.groups)?;
                        // plain `molecule` is the old name of molecule/intra
                        sim.state.neigh_settings.exclusions.molecule.push((g, kind != 3));
                    }
                    _ => sim.state.neigh_settings.exclusions = Default::default(),
                }
            }
            _ => return Err(a.unknown_keyword(w, &keys)),
        }
    }
    sim.state.lists_valid = false;
    Ok(())
}

fn group_bit(a: &mut Args, groups: &crate::engine::groups::Groups) -> DResult<u32> {
    let w = a.word("group ID")?;
    groups.bit(&w.text).ok_or_else(|| a.error_at(w, format!("group `{}` does not exist", w.text), "unknown group"))
}

pub fn comm_modify(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "comm_modify keyword value ...  (vel yes|no, cutoff x, cutoff/multi type x, reduce/multi, mode single|multi, group G)");
    if a.is_empty() {
        return Err(a.missing("a keyword"));
    }
    while let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            "vel" => sim.state.comm_vel = a.yes_no("vel")?,
            // a serial run's ghosts are made for the list cutoff; a distributed run's reach
            // at least this far
            "cutoff" => sim.state.comm_cutoff = a.non_negative_f64("cutoff")?,
            // ghost cutoffs by type and the ghost group only shape MPI communication: one
            // process makes the ghosts its lists need
            "mode" => {
                if a.choice("mode", &["single", "multi", "multi/old"])? == 1 && !sim.state.neigh_settings.multi {
                    return Err(a.error_at(a.last().unwrap(), "cannot use comm mode `multi` without `multi` style neighbor lists (neighbor skin multi), as LAMMPS", "needs neighbor multi"));
                }
            }
            "cutoff/multi" | "cutoff/multi/old" => {
                a.word("type range")?;
                a.non_negative_f64("cutoff")?;
            }
            "reduce/multi" => {}
            "group" => {
                let g = a.word("group ID")?;
                if sim.state.groups.find(&g.text).is_none() {
                    return Err(a.error_at(g, format!("comm_modify group `{}` does not exist", g.text), "unknown group"));
                }
            }
            _ => return Err(a.unknown_keyword(w, &["vel", "cutoff", "cutoff/multi", "reduce/multi", "mode", "group"])),
        }
    }
    Ok(())
}

pub fn special_bonds(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "");
    sim.state.special_bonds = SpecialBonds::parse(&mut a)?;
    // LAMMPS rebuilds its special lists when the weights change
    sim.state.special_frozen = false;
    sim.state.lists_valid = false;
    Ok(())
}

pub fn log(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "log file|none [append]");
    let w = a.word("file name")?;
    let append = if a.is_empty() { false } else { a.choice("keyword", &["append"]).map(|_| true)? };
    a.finish()?;
    let path = if w.text == "none" { None } else { Some(sim.path(&w.text)) };
    // `dmhs check` opens no log file
    if sim.state.check_only {
        return Ok(());
    }
    sim.out.set_log(path.as_deref(), append).map_err(|e| a.error_at(w, format!("cannot open log file `{}`: {e}", w.text), "cannot open"))
}

/// `dmhs/stability keyword value ...` (dmhs extension): the run-time guards of
/// src/stability.rs. Keywords: `rho LO HI` (allowed SPH density as factors of rho0, default
/// 0 2: positive and at most twice rho0), `every N` (check every N steps, default 1), `off`, `on`.
pub fn dmhs_stability(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "dmhs/stability [rho LO HI] [every N] [on|off]");
    if a.is_empty() {
        return Err(a.missing("a keyword"));
    }
    while let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            "rho" => {
                let lo = a.non_negative_f64("LO (factor of rho0)")?;
                let hi = a.f64_where("HI (factor of rho0)", "> LO", |x| x > lo)?;
                sim.guard.rho_lo = lo;
                sim.guard.rho_hi = hi;
            }
            "every" => sim.guard.every = a.i64_in("every", 1, i64::MAX)?,
            "off" => sim.guard.enabled = false,
            "on" => sim.guard.enabled = true,
            _ => return Err(a.unknown_keyword(w, &["rho", "every", "on", "off"])),
        }
    }
    Ok(())
}

/// `clear`: atoms, box, styles, fixes, computes, groups, regions and settings back to a new
/// simulation's, as LAMMPS' clear (a new LAMMPS instance inside the same input); the variables
/// (and atom-style random()'s generator), the log and screen, and the deck's options (base
/// folder, crosscheck capture, check mode, stability guard) stay.
pub fn clear(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    Args::new(cmd, "clear").finish()?;
    if sim.state.decomp.is_some() {
        return Err(Diagnostic::at(cmd.span, "clear is not supported on several ranks (mpiexec) yet", "not under mpiexec"));
    }
    let mut fresh = Simulation::new();
    std::mem::swap(&mut fresh.variables, &mut sim.variables);
    std::mem::swap(&mut fresh.random_atom, &mut sim.random_atom);
    std::mem::swap(&mut fresh.out, &mut sim.out);
    std::mem::swap(&mut fresh.command_log, &mut sim.command_log);
    std::mem::swap(&mut fresh.capture_setup, &mut sim.capture_setup);
    std::mem::swap(&mut fresh.capture_checkpoints, &mut sim.capture_checkpoints);
    std::mem::swap(&mut fresh.guard, &mut sim.guard);
    fresh.base_dir = sim.base_dir.take();
    fresh.want_capture = sim.want_capture;
    fresh.capture_first_step = sim.capture_first_step;
    fresh.state.check_only = sim.state.check_only;
    fresh.checked_runs = sim.checked_runs;
    fresh.runtime_failed = sim.runtime_failed;
    fresh.cancel = sim.cancel.clone();
    *sim = fresh;
    Ok(())
}
