//! thermo, thermo_style, thermo_modify, dump, undump, dump_modify.

use super::need_box;
use crate::output::dump::Dump;
use crate::sim::Simulation;
use crate::output::thermo::{parse_column, parse_columns, LineStyle, STYLE_MULTI, STYLE_ONE, STYLE_YAML};
use dmhs_parser::{Args, Command, DResult, SourceMap};

pub fn thermo(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "thermo N | v_name");
    let w = a.word("N")?;
    // the variable is looked up when a run starts (LAMMPS' Output::init)
    if let Some(name) = w.text.strip_prefix("v_") {
        let name = name.to_string();
        a.finish()?;
        sim.thermo.every = 0;
        sim.thermo.every_var = Some(name);
        return Ok(());
    }
    let n = dmhs_parser::args::word_i64(w, "N").map_err(|d| d.with_help("syntax: thermo N | v_name"))?;
    if n < 0 {
        return Err(a.error_at(w, "thermo N must be >= 0", "negative"));
    }
    a.finish()?;
    sim.thermo.every = n;
    sim.thermo.every_var = None;
    Ok(())
}

pub fn thermo_style(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "thermo_style one | multi | yaml | custom keyword1 keyword2 ...");
    let style = a.choice("thermo style", &["one", "custom", "multi", "yaml"])?;
    // LAMMPS makes a new Thermo: every thermo_modify setting (norm, formats, lost, flush, temp,
    // press, line, colname) returns to its default; `thermo N` stays
    if sim.thermo.modified {
        sim.out.print("WARNING: New thermo_style command, previous thermo_modify settings will be lost");
    }
    let old = std::mem::take(&mut sim.thermo);
    sim.thermo = crate::output::thermo::Thermo { every: old.every, every_var: old.every_var, next: old.next, ..Default::default() };
    match style {
        1 => {
            if a.is_empty() {
                return Err(a.missing("at least one keyword"));
            }
            let mut cols = vec![];
            while let Some(w) = a.peek() {
                a.skip(1);
                let c = parse_column(&w.text).map_err(|e| {
                    let mut d = a.error_at(w, e, "not a thermo keyword");
                    if let Some(h) = dmhs_parser::suggest::did_you_mean_help(&w.text, crate::output::thermo::KEYWORDS.iter().map(|(k, _)| *k)) {
                        d = d.with_help(h);
                    }
                    d
                })?;
                cols.push(c);
            }
            sim.thermo.columns = cols;
            sim.thermo.custom = true;
        }
        // one, multi, yaml: LAMMPS' keyword list of the style
        _ => {
            a.finish()?;
            sim.thermo.columns = parse_columns([STYLE_ONE, STYLE_ONE, STYLE_MULTI, STYLE_YAML][style]).unwrap();
            sim.thermo.custom = false;
        }
    }
    sim.thermo.line = [LineStyle::One, LineStyle::One, LineStyle::Multi, LineStyle::Yaml][style];
    // and the warnings notice, as in LAMMPS
    sim.out.warnings.noticed = false;
    Ok(())
}

pub fn thermo_modify(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "thermo_modify keyword value ...  (norm yes|no, format line|int|float|N|none str, lost error|warn|ignore, warn ignore|always|reset|default|N, flush yes|no, temp ID, press ID)");
    if a.is_empty() {
        return Err(a.missing("a keyword"));
    }
    sim.thermo.modified = true;
    while let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            "norm" => sim.thermo.norm = Some(a.yes_no("norm")?),
            "flush" => sim.thermo.flush = a.yes_no("flush")?,
            "lost" => {
                let k = a.choice("lost", &["error", "warn", "ignore"])?;
                sim.thermo.lost_ignore = k != 0;
                sim.thermo.lost_warn = k == 1;
            }
            "lost/bond" => {
                a.choice("lost/bond", &["error", "warn", "ignore"])?;
            }
            "warn" => {
                let w = &mut sim.out.warnings;
                match a.peek().map(|v| v.text.as_str()) {
                    Some(k @ ("ignore" | "always" | "reset" | "default")) => {
                        a.skip(1);
                        match k {
                            "ignore" => w.max = -1,
                            "always" => w.max = 0,
                            "reset" => (w.count, w.noticed) = (0, false),
                            _ => (w.count, w.noticed, w.max) = (0, false, 100),
                        }
                    }
                    _ => w.max = a.i64_in("warn", i32::MIN as i64, i32::MAX as i64).map_err(|d| d.with_help("thermo_modify warn ignore|always|reset|default|N"))?,
                }
            }
            "format" => {
                let which = a.word("format kind")?;
                match which.text.as_str() {
                    "none" => {
                        sim.thermo.format_line = None;
                        sim.thermo.format_int = None;
                        sim.thermo.format_float = None;
                        sim.thermo.format_column.clear();
                    }
                    "line" => sim.thermo.format_line = Some(a.printf_line("format string")?),
                    "int" => sim.thermo.format_int = Some(a.printf_format("format string")?.to_string()),
                    "float" => sim.thermo.format_float = Some(a.printf_format("format string")?.to_string()),
                    n => {
                        let cols = column_range(&sim.thermo, n).ok_or_else(|| a.error_at(which, format!("Invalid thermo_modify format argument: {n}"), format!("line, int, float, none, a column 1..{} (or N*M, or negative from the end) or a keyword of the style", initial_columns(&sim.thermo))))?;
                        let f = a.printf_format("format string")?.to_string();
                        for k in cols {
                            sim.thermo.format_column.retain(|(c, _)| *c != k + 1);
                            sim.thermo.format_column.push((k + 1, f.clone()));
                        }
                    }
                }
            }
            "colname" => {
                let which = a.word("column (a number or keyword) or `default`")?;
                if which.text == "default" {
                    for c in &mut sim.thermo.columns {
                        c.label = parse_column(&c.word).map(|d| d.label).unwrap_or_else(|_| c.word.clone());
                    }
                } else {
                    let k = column_range(&sim.thermo, &which.text).filter(|r| r.len() == 1).map(|r| r[0]);
                    let k = k.ok_or_else(|| a.error_at(which, format!("Invalid thermo_modify colname argument: {}", which.text), format!("a column 1..{} (negative from the end) or a keyword of the style", initial_columns(&sim.thermo))))?;
                    sim.thermo.columns[k].label = a.word("column name")?.text.clone();
                }
            }
            "temp" => {
                let idw = a.word("temperature compute ID")?;
                let found = {
                    let world = sim.world();
                    world.compute(&idw.text).map(|c| (c.dof(&world).is_some(), c.groupbit() == 1))
                };
                let Some((is_temp, group_all)) = found else {
                    return Err(a.error_at(idw, format!("could not find thermo_modify temperature compute `{}`", idw.text), "unknown compute"));
                };
                if !is_temp {
                    return Err(a.error_at(idw, format!("thermo_modify temperature ID `{}` does not compute temperature", idw.text), "not a temperature"));
                }
                if !group_all {
                    sim.out.print("WARNING: Temperature for thermo pressure is not for group all");
                }
                // the pressure thermo uses (or thermo_press) takes the same temperature, as LAMMPS
                let press_id = sim.thermo.press_id.clone();
                if let Some(p) = sim.computes.iter_mut().find(|c| c.id() == press_id) {
                    p.reset_temperature(&idw.text);
                }
                sim.thermo.temp_id = idw.text.clone();
            }
            "press" => {
                let idw = a.word("pressure compute ID")?;
                match sim.computes.iter().find(|c| c.id() == idw.text) {
                    None => return Err(a.error_at(idw, format!("could not find thermo_modify pressure compute `{}`", idw.text), "unknown compute")),
                    Some(c) if c.style() != "pressure" => return Err(a.error_at(idw, format!("thermo_modify pressure ID `{}` does not compute pressure", idw.text), "not a pressure")),
                    Some(_) => sim.thermo.press_id = idw.text.clone(),
                }
            }
            "line" => sim.thermo.line = [LineStyle::One, LineStyle::Multi, LineStyle::Yaml][a.choice("line", &["one", "multi", "yaml"])?],
            "every" => {
                return Err(a.error_at(w, format!("thermo_modify {} is not supported yet", w.text), "not supported"));
            }
            _ => return Err(a.unknown_keyword(w, &["norm", "format", "lost", "lost/bond", "warn", "flush", "temp", "press", "line", "colname"])),
        }
    }
    Ok(())
}

pub fn dump(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    let d = Dump::from_lammps(cmd, &sim.world(), sim.base_dir.as_deref())?;
    if sim.dumps.iter().any(|x| x.id == d.id) {
        return Err(dmhs_parser::Diagnostic::at(cmd.args[0].span, format!("reuse of dump ID `{}`", d.id), "already defined"));
    }
    if let Some(note) = d.picture.as_ref().and_then(|p| p.movie_note(&d.id)) {
        sim.out.print(&note);
    }
    sim.dumps.push(d);
    Ok(())
}

pub fn undump(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "undump ID");
    let w = a.word("dump ID")?;
    a.finish()?;
    let k = crate::output::dump::find(&sim.dumps, w).ok_or_else(|| a.error_at(w, format!("dump `{}` does not exist", w.text), "unknown dump"))?;
    sim.dumps.remove(k);
    Ok(())
}

pub fn dump_modify(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "dump_modify ID keyword value ...  (sort id|off, format line|int|float|N str, every N, first yes|no, image yes|no, append yes|no, element E1 .. EN (xyz), time yes|no (xyz))");
    let w = a.word("dump ID")?;
    let k = crate::output::dump::find(&sim.dumps, w).ok_or_else(|| a.error_at(w, format!("dump `{}` does not exist", w.text), "unknown dump"))?;
    if a.is_empty() {
        return Err(a.missing("a keyword"));
    }
    let ntypes = sim.state.ntypes;
    sim.dumps[k].modify(&mut a, ntypes)
}

/// `write_dump group-ID style file args ... [modify keyword value ...]` (LAMMPS' WriteDump): a
/// dump `WRITE_DUMP` of the same style with N = 1 is made, given the dump_modify keywords after
/// `modify`, written once at the current step and dropped.
pub fn write_dump(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    let a = Args::new(cmd, "write_dump group-ID style file args ... [modify keyword value ...]");
    if cmd.args.len() < 3 {
        return Err(a.missing("group-ID, dump style and file name"));
    }
    let style = &cmd.args[1];
    if style.text == "movie" {
        return Err(a.error_at(style, "dump style movie cannot be used with write_dump", "not a one-shot style"));
    }
    let split = cmd.args.iter().position(|w| w.text == "modify").unwrap_or(cmd.args.len());
    let word = |text: &str, at: &dmhs_parser::Word| dmhs_parser::Word { text: text.to_string(), span: at.span, quoted: false };
    let mut args = vec![word("WRITE_DUMP", &cmd.name), cmd.args[0].clone(), style.clone(), word("1", style)];
    // LAMMPS skips `noinit` (it only silences its warning about a write before the first run)
    args.extend(cmd.args[2..split].iter().filter(|w| w.text != "noinit").cloned());
    let dcmd = Command { name: word("dump", &cmd.name), args, span: cmd.span };
    let mut d = Dump::from_lammps(&dcmd, &sim.world(), sim.base_dir.as_deref())?;
    if split < cmd.args.len() {
        let mut margs = vec![word("WRITE_DUMP", &cmd.args[split])];
        margs.extend(cmd.args[split + 1..].iter().cloned());
        let mcmd = Command { name: word("dump_modify", &cmd.args[split]), args: margs, span: cmd.span };
        let mut m = Args::new(&mcmd, "write_dump ... modify keyword value ...  (dump_modify keywords)");
        m.word("dump ID")?;
        if m.is_empty() {
            return Err(m.missing("a dump_modify keyword after `modify`"));
        }
        d.modify(&mut m, sim.state.ntypes)?;
    }
    // `dmhs check` writes no file (the atoms are not those of a run)
    if sim.state.check_only {
        return Ok(());
    }
    let world = crate::models::world::World { state: &sim.state, computes: &sim.computes, fixes: crate::models::world::FixesView::all(&sim.fixes), bond: sim.bond_style.as_deref(), pair: sim.pair.as_deref() };
    let mut ev = crate::sim::eval::Eval { world, thermo: &sim.thermo, variables: &mut sim.variables, cpu: sim.last_loop_seconds };
    d.write(&world, &mut ev).map_err(|e| a.error_at(&cmd.args[2], e, "while writing"))
}

/// The columns the thermo style gave (without the Volume a run adds).
fn initial_columns(t: &crate::output::thermo::Thermo) -> usize {
    t.columns.len() - usize::from(t.volume_added)
}

/// The 0-based columns `key` names for thermo_modify format and colname (LAMMPS' key2col and
/// bounds): a number from 1 (negative: from the end), N*M, or a keyword of the style (its last
/// column with that keyword).
fn column_range(t: &crate::output::thermo::Thermo, key: &str) -> Option<Vec<usize>> {
    let n = initial_columns(t) as i64;
    if let Some((lo, hi)) = key.split_once('*') {
        let lo = if lo.is_empty() { 1 } else { lo.parse::<i64>().ok()? };
        let hi = if hi.is_empty() { n } else { hi.parse::<i64>().ok()? };
        return (1 <= lo && lo <= hi && hi <= n).then(|| (lo - 1..hi).map(|k| k as usize).collect());
    }
    let k = match key.parse::<i64>() {
        Ok(k) if k < 0 => n + k,
        Ok(k) => k - 1,
        Err(_) => t.columns[..n as usize].iter().rposition(|c| c.word == key)? as i64,
    };
    (0..n).contains(&k).then(|| vec![k as usize])
}
