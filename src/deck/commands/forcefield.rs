//! Force-field definitions: pair_style, pair_coeff, pair_modify, and the bonded styles and
//! their coefficients.

use super::need_box;
use crate::models::pair::{new_pair_style, MixRule};
use crate::sim::Simulation;
use dmhs_parser::{Args, Command, DResult, Diagnostic, SourceMap, Word};

pub fn pair_style(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let a = Args::new(cmd, "pair_style style args");
    let Some(name) = cmd.args.first() else { return Err(a.missing("a pair style")) };
    if name.text == "none" {
        sim.pair = None;
        sim.pair_span = None;
        return Ok(());
    }
    let mut pair = new_pair_style(name, &cmd.args[1..], cmd)?;
    // LAMMPS keeps the style when the same one is named again (only its settings change): its
    // contact histories, restored by read_restart or built by a run, carry on
    if let Some(old) = sim.pair.as_mut().filter(|old| old.style() == pair.style() && old.sub_styles() == pair.sub_styles()) {
        for (from, to) in old.histories().into_iter().zip(pair.histories()) {
            to.carry(from.records());
        }
    }
    sim.pair = Some(pair);
    sim.pair_span = Some(cmd.span);
    sim.state.lists_valid = false;
    Ok(())
}

/// `pair_coeff I J` with both as plain numbers and I > J is reordered, as LAMMPS does.
fn ordered_type_words(cmd: &Command) -> Vec<Word> {
    let mut args = cmd.args.clone();
    if args.len() >= 2 {
        if let (Ok(i), Ok(j)) = (args[0].text.parse::<usize>(), args[1].text.parse::<usize>()) {
            if i > j {
                args.swap(0, 1);
            }
        }
    }
    args
}

pub fn pair_coeff(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    let syntax = "pair_coeff I J args  (I, J: type or range n*m)";
    let args = ordered_type_words(cmd);
    let mut a = Args::from_words(&args, cmd.span, syntax);
    let ntypes = sim.state.ntypes;
    let Some(pair) = sim.pair.as_mut() else {
        return Err(Diagnostic::at(cmd.name.span, "pair_coeff used before pair_style", "no pair style yet").with_help("define the pair style first, e.g. `pair_style lj/cut 2.5`"));
    };
    let (ilo, ihi) = a.type_range("atom type I", ntypes)?;
    let (jlo, jhi) = a.type_range("atom type J", ntypes)?;
    if !(ilo..=ihi).any(|i| jhi >= jlo.max(i)) {
        return Err(Diagnostic::at(cmd.args[0].span.to(cmd.args[1].span), "pair_coeff sets no type pair (each pair needs I <= J)", "no I <= J pair in these ranges"));
    }
    pair.coeff(ilo, ihi, jlo, jhi, &mut a)?;
    // the per-atom values a style keeps exist from here on (LAMMPS: its fix property/atom)
    crate::models::pair::granular::mdr_state::ensure_fields_for(pair.atom_fields(), &mut sim.state.atoms);
    sim.state.lists_valid = false;
    Ok(())
}

pub fn pair_modify(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let mut a = Args::new(cmd, "pair_modify [pair M [k]] keyword value ...  (shift yes|no, mix geometric|arithmetic|sixthpower, tail no)");
    let Some(pair) = sim.pair.as_mut() else {
        return Err(Diagnostic::at(cmd.name.span, "pair_modify used before pair_style", "no pair style yet"));
    };
    if a.is_empty() {
        return Err(a.missing("a keyword"));
    }
    // `pair M [k]` first: the keywords that follow change that hybrid sub-style alone;
    // otherwise the style's settings and every sub-style's own
    let sub = match a.peek() {
        Some(w) if w.text == "pair" => {
            a.skip(1);
            Some(pair.sub_modify(&mut a, &sim.pair_modify)?)
        }
        _ => None,
    };
    let (mut mix, mut shift) = (None, None);
    while let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            "shift" => shift = Some(a.yes_no("shift")?),
            "mix" => {
                mix = Some(match a.choice("mixing rule", &["geometric", "arithmetic", "sixthpower"])? {
                    0 => MixRule::Geometric,
                    1 => MixRule::Arithmetic,
                    _ => MixRule::SixthPower,
                })
            }
            "tail" => {
                if a.yes_no("tail")? {
                    return Err(a.error_at(a.last().unwrap(), "pair_modify tail yes (long-range corrections) is not supported yet", "use no"));
                }
            }
            "pair" => return Err(a.error_at(w, "pair_modify pair must be the first keyword", "move it first")),
            "special" | "compute/tally" | "compute" | "table" | "table/disp" | "tabinner" | "tabinner/disp" | "nofdotr" | "neigh/trim" => {
                return Err(a.error_at(w, format!("pair_modify {} is not supported yet", w.text), "not supported"));
            }
            _ => return Err(a.unknown_keyword(w, &["pair", "shift", "mix", "tail"])),
        }
    }
    let mut apply = |m: &mut crate::models::pair::PairModify| {
        if let Some(mix) = mix {
            m.mix = mix;
        }
        if let Some(shift) = shift {
            m.shift = shift;
        }
    };
    match sub {
        Some(m) => apply(m),
        None => {
            apply(&mut sim.pair_modify);
            pair.each_sub_modify(&mut apply);
        }
    }
    Ok(())
}

/// Shared parsing of `bond_style`, `angle_style`, `dihedral_style`.
fn style_name<'a>(cmd: &'a Command, what: &str, supported: &[&str], allowed: bool) -> DResult<Option<&'a Word>> {
    let a = Args::new(cmd, "");
    let Some(name) = cmd.args.first() else { return Err(a.missing(&format!("a {what} style"))) };
    if !allowed {
        let styles = if what == "bond" { "bond, angle, molecular, full" } else if what == "angle" { "angle, molecular, full" } else { "molecular, full" };
        return Err(Diagnostic::at(cmd.name.span, format!("{what}_style needs an atom style with {what}s ({styles}, or a hybrid with one of them)"), "atom style has no such interactions"));
    }
    if name.text == "none" {
        return Ok(None);
    }
    if !supported.contains(&name.text.as_str()) {
        return Err(crate::models::styles::unsupported_style(what, name, &name.text, supported));
    }
    Ok(Some(name))
}

pub fn bond_style(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let names: Vec<&str> = crate::models::bonded::bond_style_names().collect();
    match style_name(cmd, "bond", &names, sim.state.atoms.features.bonds)? {
        None => sim.bond_style = None,
        Some(w) => {
            let mut s = crate::models::bonded::new_bond_style(&w.text).unwrap();
            s.settings(&mut Args::from_words(&cmd.args[1..], cmd.span, "bond_style style args"))?;
            if let Some(sl) = s.as_bpm().and_then(|b| b.shared().store_local.as_ref()) {
                bpm_store_local(sim, sl)?;
            }
            if s.as_bpm().is_some_and(|b| b.shared().volume) {
                // registered now so that a restart file's volumes find their arrays
                for field in crate::models::bonded::bpm::VOLUMES {
                    sim.state.atoms.add_field(field);
                }
            }
            sim.bond_style = Some(s);
        }
    }
    Ok(())
}

/// `store/local FIXID N values...` of a BPM bond style: the fix STORE/LOCAL that collects the
/// broken bonds (LAMMPS creates it unless a fix of that ID exists), and the reference positions
/// for x/ref, y/ref, z/ref (the positions now).
fn bpm_store_local(sim: &mut Simulation, sl: &crate::models::bonded::bpm::StoreLocal) -> DResult<()> {
    use crate::models::bonded::bpm::{LocalValue, X_REF};
    match sim.fixes.iter_mut().find(|f| f.id() == sl.fix_id) {
        Some(f) => {
            if f.as_store_local().is_none() {
                return Err(Diagnostic::at(sl.span, format!("Incorrect fix style matched, not STORE/LOCAL: {}", f.style()), "fix ID of another style"));
            }
        }
        None => {
            let all = sim.state.groups.bit("all").unwrap_or(1);
            sim.fixes.push(Box::new(crate::models::fix::store_local::FixStoreLocal::new(sl.fix_id.clone(), all, sl.every, sl.values.len())));
        }
    }
    if sl.values.iter().any(|v| matches!(v, LocalValue::XRef(_))) {
        let a = &mut sim.state.atoms;
        if a.nall() > a.nlocal {
            a.clear_ghosts();
            sim.state.lists_valid = false;
        }
        for (d, field) in X_REF.into_iter().enumerate() {
            let k = a.add_field(field);
            for i in 0..a.nlocal {
                a.extra[k].data[i] = a.x[i][d];
            }
        }
    }
    Ok(())
}

pub fn angle_style(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let names: Vec<&str> = crate::models::bonded::angle_style_names().collect();
    match style_name(cmd, "angle", &names, sim.state.atoms.features.angles)? {
        None => sim.angle_style = None,
        Some(w) => {
            let mut s = crate::models::bonded::new_angle_style(&w.text).unwrap();
            s.settings(&mut Args::from_words(&cmd.args[1..], cmd.span, "angle_style style args"))?;
            sim.angle_style = Some(s);
        }
    }
    Ok(())
}

pub fn dihedral_style(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let names: Vec<&str> = crate::models::bonded::dihedral_style_names().collect();
    match style_name(cmd, "dihedral", &names, sim.state.atoms.features.dihedrals)? {
        None => sim.dihedral_style = None,
        Some(w) => {
            let mut s = crate::models::bonded::new_dihedral_style(&w.text).unwrap();
            s.settings(&mut Args::from_words(&cmd.args[1..], cmd.span, "dihedral_style style args"))?;
            sim.dihedral_style = Some(s);
        }
    }
    Ok(())
}

/// `bond_coeff`/`angle_coeff`/`dihedral_coeff N args`: the type range and the style.
fn coeff_prelude<'a>(sim: &Simulation, cmd: &'a Command, what: &str, ntypes: usize, has_style: bool) -> DResult<(usize, usize, Args<'a>)> {
    need_box(sim, cmd)?;
    if !has_style {
        return Err(Diagnostic::at(cmd.name.span, format!("{what}_coeff used before {what}_style"), format!("no {what} style yet")));
    }
    if ntypes == 0 {
        return Err(Diagnostic::at(cmd.name.span, format!("{what}_coeff with no {what} types (set {what}/types in create_box or the data file)"), format!("0 {what} types")));
    }
    let mut a = Args::new(cmd, "");
    let (lo, hi) = a.type_range(&format!("{what} type"), ntypes)?;
    Ok((lo, hi, a))
}

pub fn bond_coeff(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let n = sim.state.topo.nbondtypes;
    let (lo, hi, mut a) = coeff_prelude(sim, cmd, "bond", n, sim.bond_style.is_some())?;
    let s = sim.bond_style.as_mut().unwrap();
    s.set_types(n);
    s.coeff(lo, hi, &mut a)
}

pub fn angle_coeff(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let n = sim.state.topo.nangletypes;
    let (lo, hi, mut a) = coeff_prelude(sim, cmd, "angle", n, sim.angle_style.is_some())?;
    let s = sim.angle_style.as_mut().unwrap();
    s.set_types(n);
    s.coeff(lo, hi, &mut a)
}

pub fn dihedral_coeff(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    let n = sim.state.topo.ndihedraltypes;
    let (lo, hi, mut a) = coeff_prelude(sim, cmd, "dihedral", n, sim.dihedral_style.is_some())?;
    let s = sim.dihedral_style.as_mut().unwrap();
    s.set_types(n);
    s.coeff(lo, hi, &mut a)
}
