//! Per-atom properties: mass, set, group, velocity.

use super::need_box;
use crate::sim::Simulation;
use dmhs_parser::args::{word_f64, word_i64};
use dmhs_parser::{Args, Command, DResult, Diagnostic, SourceMap, Word};

pub fn mass(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    let mut a = Args::new(cmd, "mass I value  (I: type or range n*m)");
    // styles with per-atom masses only have no per-type ones (a hybrid with sph, bond, ...
    // has both, as LAMMPS')
    let styles = &sim.state.atom_style;
    if styles.iter().all(|s| matches!(s.as_str(), "sphere" | "bpm/sphere")) {
        let name = if styles.len() > 1 { "hybrid".to_string() } else { styles.join(" ") };
        return Err(a.error_command(format!("Cannot set per-type atom mass for atom style {name}"), "per-atom masses: set ... mass or density"));
    }
    let (lo, hi) = a.type_range("atom type", sim.state.ntypes)?;
    let m = a.positive_f64("mass")?;
    a.finish()?;
    for t in lo..=hi {
        sim.state.type_mass[t] = m;
        sim.state.mass_set[t] = true;
    }
    Ok(())
}

/// Parse an ID or type list element: `n`, `n*m`, `*`, `n*`, `*m` or `n:m[:k]`, within `lo..=hi`.
fn id_range(w: &Word, max: i64) -> DResult<Vec<(i64, i64, i64)>> {
    let t = w.text.as_str();
    let bad = || Diagnostic::at(w.span, format!("invalid range `{t}`"), "expected n, n*m or n:m:k");
    if t.contains(':') {
        let parts: Vec<&str> = t.split(':').collect();
        if parts.len() < 2 || parts.len() > 3 {
            return Err(bad());
        }
        let p = |s: &str| s.parse::<i64>().map_err(|_| bad());
        let (a, b) = (p(parts[0])?, p(parts[1])?);
        let k = if parts.len() == 3 { p(parts[2])? } else { 1 };
        if k <= 0 || a > b {
            return Err(bad());
        }
        return Ok(vec![(a, b, k)]);
    }
    match t.find('*') {
        None => {
            let n = word_i64(w, "an ID")?;
            Ok(vec![(n, n, 1)])
        }
        Some(k) => {
            let lo = if k == 0 { 1 } else { t[..k].parse().map_err(|_| bad())? };
            let hi = if k + 1 == t.len() { max } else { t[k + 1..].parse().map_err(|_| bad())? };
            Ok(vec![(lo, hi, 1)])
        }
    }
}

/// Which owned atoms a `group`/`set` selection of `type`, `id` or `molecule` values picks.
fn select_by_value(sim: &Simulation, a: &mut Args, values: impl Fn(usize) -> i64, max: i64) -> DResult<Vec<bool>> {
    let n = sim.state.atoms.nlocal;
    let ops = ["<", "<=", ">", ">=", "==", "!=", "<>"];
    if let Some(w) = a.peek() {
        if let Some(k) = ops.iter().position(|o| *o == w.text) {
            a.skip(1);
            let v1 = word_i64(a.word("value")?, "value")?;
            let v2 = if k == 6 { word_i64(a.word("upper value")?, "upper value")? } else { 0 };
            return Ok((0..n)
                .map(|i| {
                    let x = values(i);
                    match k {
                        0 => x < v1,
                        1 => x <= v1,
                        2 => x > v1,
                        3 => x >= v1,
                        4 => x == v1,
                        5 => x != v1,
                        _ => x >= v1 && x <= v2,
                    }
                })
                .collect());
        }
    }
    if a.is_empty() {
        return Err(a.missing("a value or range"));
    }
    let mut ranges = vec![];
    while let Some(w) = a.peek() {
        a.skip(1);
        ranges.extend(id_range(w, max)?);
    }
    Ok((0..n).map(|i| {
        let x = values(i);
        ranges.iter().any(|&(lo, hi, k)| x >= lo && x <= hi && (x - lo) % k == 0)
    }).collect())
}

pub fn group(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    if cmd.args.get(1).is_some_and(|w| w.text == "region") {
        super::box_cmds::region_now(sim, cmd, "region")?;
    }
    let syntax = "group ID style args  (style: type, id, molecule (values, ranges or <, <=, >, >=, ==, !=, <> v1 v2), region ID, subtract/union/intersect G1 G2 ..., delete, clear, empty)";
    let mut a = Args::new(cmd, syntax);
    let idw = a.word("group ID")?;
    let style = a.word("group style")?;
    if style.text == "delete" {
        a.finish()?;
        let k = sim.state.groups.find(&idw.text).ok_or_else(|| a.error_at(idw, format!("group `{}` does not exist", idw.text), "unknown group"))?;
        if k == 0 {
            return Err(a.error_at(idw, "cannot delete group all", "not allowed"));
        }
        if sim.fixes.iter().any(|f| f.groupbit() == 1 << k) || sim.computes.iter().any(|c| c.groupbit() == 1 << k) {
            return Err(a.error_at(idw, format!("cannot delete group `{}` while a fix or compute uses it", idw.text), "in use"));
        }
        for m in &mut sim.state.atoms.mask {
            *m &= !(1 << k);
        }
        drop_dynamic(sim, k);
        sim.state.groups.delete(k);
        return Ok(());
    }
    need_box(sim, cmd)?;
    if style.text == "dynamic" || style.text == "static" {
        return group_dynamic(sim, &mut a, idw, style);
    }
    if idw.text == "all" {
        return Err(a.error_at(idw, "group all cannot be changed", "reserved group"));
    }
    let k = sim.state.groups.find_or_create(&idw.text).map_err(|e| a.error_at(idw, e, "too many groups"))?;
    let bit = 1u32 << k;
    sim.state.atoms.clear_ghosts();
    let n = sim.state.atoms.nlocal;
    let sel: Vec<bool> = match style.text.as_str() {
        "type" => {
            let at = &sim.state.atoms;
            let typ = at.typ.clone();
            select_by_value(sim, &mut a, |i| typ[i] as i64, sim.state.ntypes as i64)?
        }
        "id" => {
            let tag = sim.state.atoms.tag.clone();
            let max = sim.state.atoms.max_tag();
            select_by_value(sim, &mut a, |i| tag[i], max)?
        }
        "molecule" => {
            if !sim.state.atoms.features.molecule {
                return Err(a.error_at(style, "group molecule needs an atom style with molecule IDs", "no molecule IDs"));
            }
            let mol = sim.state.atoms.molecule.clone();
            let max = mol.iter().copied().max().unwrap_or(0);
            select_by_value(sim, &mut a, |i| mol[i], max)?
        }
        "region" => {
            let w = a.word("region ID")?;
            a.finish()?;
            let r = sim.state.regions.iter().find(|r| r.id == w.text).ok_or_else(|| a.error_at(w, format!("region `{}` does not exist", w.text), "unknown region"))?;
            (0..n).map(|i| r.matches(sim.state.atoms.x[i])).collect()
        }
        "subtract" | "union" | "intersect" => {
            let mut bits = vec![];
            while let Some(w) = a.peek() {
                a.skip(1);
                let b = sim.state.groups.bit(&w.text).ok_or_else(|| a.error_at(w, format!("group `{}` does not exist", w.text), "unknown group"))?;
                // LAMMPS refuses: a dynamic group's members change during a run
                if sim.state.groups.bit_is_dynamic(b) {
                    return Err(a.error_at(w, format!("Cannot {} groups using a dynamic group (`{}`)", style.text, w.text), "dynamic group"));
                }
                bits.push(b);
            }
            let need = if style.text == "union" { 1 } else { 2 };
            if bits.len() < need {
                return Err(a.missing(&format!("at least {need} group IDs")));
            }
            let m = &sim.state.atoms.mask;
            (0..n)
                .map(|i| match style.text.as_str() {
                    "subtract" => m[i] & bits[0] != 0 && bits[1..].iter().all(|b| m[i] & b == 0),
                    "union" => bits.iter().any(|b| m[i] & b != 0),
                    _ => bits.iter().all(|b| m[i] & b != 0),
                })
                .collect()
        }
        "variable" => {
            // the atoms whose value is not zero (LAMMPS)
            let w = a.word("atom-style variable name")?;
            a.finish()?;
            atom_variable_values(sim, w, &w.text, "group")?.iter().map(|&v| v != 0.0).collect()
        }
        "clear" => {
            a.finish()?;
            for m in &mut sim.state.atoms.mask {
                *m &= !bit;
            }
            vec![false; n]
        }
        "empty" => {
            a.finish()?;
            vec![false; n]
        }
        other => {
            let known = ["type", "id", "molecule", "region", "variable", "subtract", "union", "intersect", "delete", "clear", "empty", "dynamic", "static"];
            let msg = if ["include"].contains(&other) {
                format!("group style `{other}` is a LAMMPS style that dmhs does not support yet")
            } else {
                format!("unknown group style `{other}`")
            };
            let mut d = a.error_at(style, msg, "not a supported group style");
            if let Some(h) = dmhs_parser::suggest::did_you_mean_help(other, known) {
                d = d.with_help(h);
            }
            return Err(d);
        }
    };
    for i in 0..n {
        if sel[i] {
            sim.state.atoms.mask[i] |= bit;
        }
    }
    let count = sim.state.group_count(bit);
    sim.out.print(&format!("{count} atoms in group {}", idw.text));
    Ok(())
}

/// Remove the internal fix of dynamic group `k`, if it has one.
fn drop_dynamic(sim: &mut Simulation, k: usize) {
    if sim.state.groups.is_dynamic(k) {
        let name = format!("GROUP_{}", sim.state.groups.names().find(|&(j, _)| j == k).map(|(_, n)| n).unwrap_or_default());
        if let Some(j) = sim.find_fix(&name) {
            let mut f = sim.fixes.remove(j);
            f.cleanup(&mut sim.state);
        }
        sim.state.groups.set_dynamic(k, false);
    }
}

/// `group ID dynamic parent [region R] [var V] [every N]` (an internal fix GROUP_ID, added
/// last, recomputes the members at setup and every N steps) and `group ID static`.
fn group_dynamic(sim: &mut Simulation, a: &mut Args, idw: &Word, style: &Word) -> DResult<()> {
    if style.text == "static" {
        a.finish()?;
        let k = sim.state.groups.find_or_create(&idw.text).map_err(|e| a.error_at(idw, e, "too many groups"))?;
        drop_dynamic(sim, k);
        let count = sim.state.group_count(1 << k);
        sim.out.print(&format!("{count} atoms in group {}", idw.text));
        return Ok(());
    }
    let pw = a.word("parent group ID")?;
    if a.is_empty() {
        return Err(a.missing("a keyword (region, var, property or every): LAMMPS needs at least one"));
    }
    if pw.text == idw.text {
        return Err(a.error_at(pw, "Group dynamic cannot reference itself", "the group itself"));
    }
    let parent = sim.state.groups.bit(&pw.text).ok_or_else(|| a.error_at(pw, format!("Group dynamic parent group `{}` does not exist", pw.text), "unknown group"))?;
    if idw.text == "all" {
        return Err(a.error_at(idw, "Group all cannot be made dynamic", "reserved group"));
    }
    let (mut region, mut var, mut property, mut every) = (None, None, None, 1);
    while let Some(kw) = a.peek() {
        a.skip(1);
        match kw.text.as_str() {
            "region" => {
                let w = a.word("region ID")?;
                if !sim.state.regions.iter().any(|r| r.id == w.text) {
                    return Err(a.error_at(w, format!("Region {} for dynamic group {} does not exist", w.text, idw.text), "unknown region"));
                }
                region = Some(w.text.clone());
            }
            "var" => {
                let w = a.word("variable name")?;
                match sim.variables.style(&w.text) {
                    None => return Err(a.error_at(w, format!("Variable '{}' for dynamic group {} does not exist", w.text, idw.text), "unknown variable")),
                    Some("atom" | "atomfile") => {}
                    Some(s) => return Err(a.error_at(w, format!("Variable {} for dynamic group {} is invalid style ({s}; an atom-style variable is needed)", w.text, idw.text), "not atom-style")),
                }
                var = Some(w.text.clone());
            }
            "every" => {
                let w = a.word("every N")?;
                every = word_i64(w, "every N")?;
                if every <= 0 {
                    return Err(a.error_at(w, format!("Illegal every value {every} for dynamic group {}", idw.text), "must be > 0"));
                }
            }
            "property" => {
                let w = a.word("custom per-atom property name")?;
                if crate::models::fix::group_dynamic::find_custom(&sim.state.atoms, &w.text).is_none() {
                    return Err(a.error_at(w, format!("Custom per-atom vector {} for group dynamic does not exist (a fix property/atom i_{0} or d_{0} defines one)", w.text), "unknown property"));
                }
                property = Some(w.text.clone());
            }
            _ => return Err(a.unknown_keyword(kw, &["region", "var", "property", "every"])),
        }
    }
    let k = sim.state.groups.find_or_create(&idw.text).map_err(|e| a.error_at(idw, e, "too many groups"))?;
    drop_dynamic(sim, k);
    sim.state.groups.set_dynamic(k, true);
    sim.fixes.push(Box::new(crate::models::fix::group_dynamic::FixGroup::new(&idw.text, parent, 1 << k, region, var, property, every)));
    sim.out.print(&format!("dynamic group {} defined", idw.text));
    Ok(())
}

pub fn set(sim: &mut Simulation, cmd: &Command, _: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    if cmd.args.first().is_some_and(|w| w.text == "region") {
        super::box_cmds::region_now(sim, cmd, "region")?;
    }
    let syntax = "set atom|type|mol|group|region ID keyword value ...  (type, type/fraction, type/ratio, type/subset, mass, diameter, density, charge, image, x, y, z, vx, vy, vz, mol, omega, quat, quat/random, sph/rho, sph/e, sph/cv, dmhs/conc, dmhs/water, temperature; a number may be v_name of an atom-style variable)";
    let mut a = Args::new(cmd, syntax);
    sim.state.atoms.clear_ghosts();
    let n = sim.state.atoms.nlocal;
    let style = a.choice("selection style", &["atom", "type", "mol", "group", "region"])?;
    let idw = a.word("ID or range")?;
    let sel: Vec<bool> = match style {
        0 | 1 | 2 => {
            let (vals, max): (Vec<i64>, i64) = match style {
                0 => (sim.state.atoms.tag.clone(), sim.state.atoms.max_tag()),
                1 => (sim.state.atoms.typ.iter().map(|&t| t as i64).collect(), sim.state.ntypes as i64),
                _ => {
                    if !sim.state.atoms.features.molecule {
                        return Err(a.error_at(idw, "set mol needs an atom style with molecule IDs", "no molecule IDs"));
                    }
                    let m = sim.state.atoms.molecule.clone();
                    let max = m.iter().copied().max().unwrap_or(0);
                    (m, max)
                }
            };
            let ranges = id_range(idw, max)?;
            (0..n).map(|i| ranges.iter().any(|&(lo, hi, k)| vals[i] >= lo && vals[i] <= hi && (vals[i] - lo) % k == 0)).collect()
        }
        3 => {
            let bit = sim.state.groups.bit(&idw.text).ok_or_else(|| a.error_at(idw, format!("group `{}` does not exist", idw.text), "unknown group"))?;
            (0..n).map(|i| sim.state.atoms.mask[i] & bit != 0).collect()
        }
        _ => {
            let r = sim.state.regions.iter().find(|r| r.id == idw.text).ok_or_else(|| a.error_at(idw, format!("region `{}` does not exist", idw.text), "unknown region"))?;
            (0..n).map(|i| r.matches(sim.state.atoms.x[i])).collect()
        }
    };
    if a.is_empty() {
        return Err(a.missing("a keyword"));
    }
    let count = sel.iter().filter(|&&s| s).count();
    // each selected atom in local order, with LAMMPS' check of its value (error->one)
    let each = |at: &mut crate::engine::atoms::Atoms, v: &SetValue, w: &Word, ok: &dyn Fn(f64) -> bool, why: &str, f: &mut dyn FnMut(&mut crate::engine::atoms::Atoms, usize, f64)| -> DResult<()> {
        // a number is checked even when no atom is selected (LAMMPS checks it as it reads it)
        if let SetValue::One(x) = v {
            if !ok(*x) {
                return Err(set_value_error(w, v, 0, *x, why));
            }
        }
        for i in 0..n {
            if sel[i] {
                let x = v.at(i);
                if !ok(x) {
                    return Err(set_value_error(w, v, at.tag[i], x, why));
                }
                f(at, i, x);
            }
        }
        Ok(())
    };
    let any = |_: f64| true;
    while let Some(kw) = a.peek() {
        a.skip(1);
        let ft = sim.state.atoms.features;
        let need = |ok: bool, what: &str| -> DResult<()> {
            if ok { Ok(()) } else { Err(Diagnostic::at(kw.span, format!("set {} needs an atom style with {what}", kw.text), "not available in this atom style")) }
        };
        let mut made = count;
        match kw.text.as_str() {
            "type" => {
                let ntypes = sim.state.ntypes;
                let (w, v) = if is_var(&a) {
                    set_value(sim, &mut a, "atom type", syntax)?
                } else {
                    let t = a.i64_in("atom type", 1, ntypes as i64)?;
                    (a.last().unwrap(), SetValue::One(t as f64))
                };
                // LAMMPS truncates a variable's value to an integer type
                each(&mut sim.state.atoms, &v, w, &|x| (1..=ntypes as i64).contains(&(x as i32 as i64)), "Invalid atom type in set command", &mut |at, i, x| at.typ[i] = x as i32 as usize)?;
            }
            "type/fraction" | "type/ratio" | "type/subset" => {
                let t = a.i64_in("atom type", 1, sim.state.ntypes as i64)? as usize;
                let how = match kw.text.as_str() {
                    "type/fraction" => TypeRandom::Fraction(a.f64_where("fraction", "between 0 and 1", |f| (0.0..=1.0).contains(&f))?),
                    "type/ratio" => TypeRandom::Ratio(a.f64_where("ratio", "between 0 and 1", |f| (0.0..=1.0).contains(&f))?),
                    _ => {
                        let nw = a.word("number of atoms")?;
                        let m = word_i64(nw, "number of atoms")?;
                        if m < 0 || m as usize > count {
                            return Err(a.error_at(nw, format!("Set type/subset value {m} exceeds eligible atoms ({count} selected)"), format!("expected 0..={count}")));
                        }
                        TypeRandom::Subset(m as usize)
                    }
                };
                let seed = a.i64_in("random seed", 1, if matches!(how, TypeRandom::Fraction(_)) { i32::MAX as i64 } else { 900_000_000 })? as i32;
                let order = sim.state.lammps_order.indices(n);
                made = set_type_random(&mut sim.state.atoms, &order, &sel, t, how, seed);
            }
            "mass" => {
                need(ft.per_atom_mass(), "per-atom masses (sphere)")?;
                let (w, v) = set_value(sim, &mut a, "mass", syntax)?;
                // LAMMPS: a number must be > 0, a variable's value >= 0
                let ok: &dyn Fn(f64) -> bool = if v.is_var() { &|m| m >= 0.0 } else { &|m| m > 0.0 };
                each(&mut sim.state.atoms, &v, w, ok, "Invalid mass in set command", &mut |at, i, m| at.rmass[i] = m)?;
            }
            "diameter" => {
                need(ft.sphere, "radii (sphere)")?;
                let (w, v) = set_value(sim, &mut a, "diameter", syntax)?;
                // the mass stays: LAMMPS' set diameter changes only the radius
                each(&mut sim.state.atoms, &v, w, &|d| d >= 0.0, "Invalid diameter in set command", &mut |at, i, d| at.radius[i] = 0.5 * d)?;
            }
            "density" | "density/disc" => {
                need(ft.sphere, "radii (sphere)")?;
                let disc = kw.text == "density/disc";
                if disc && sim.state.dimension != 2 {
                    return Err(a.error_at(kw, "Set density/disc requires 2d simulation", "3d simulation"));
                }
                let (w, v) = set_value(sim, &mut a, "density", syntax)?;
                // a sphere (disc) of radius > 0 gets its volume (area) times the density; a point
                // particle gets the density itself as its mass (LAMMPS)
                each(&mut sim.state.atoms, &v, w, &|rho| rho > 0.0, "Invalid density in set command", &mut |at, i, rho| {
                    let r = at.radius[i];
                    at.rmass[i] = if r > 0.0 {
                        if disc { std::f64::consts::PI * r * r * rho } else { 4.0 * std::f64::consts::PI / 3.0 * r * r * r * rho }
                    } else {
                        rho
                    };
                })?;
            }
            "charge" => {
                need(ft.charge, "charges")?;
                let (w, v) = set_value(sim, &mut a, "charge", syntax)?;
                each(&mut sim.state.atoms, &v, w, &any, "", &mut |at, i, q| at.q[i] = q)?;
            }
            "mol" => {
                need(ft.molecule, "molecule IDs")?;
                let (w, v) = if is_var(&a) {
                    set_value(sim, &mut a, "molecule ID", syntax)?
                } else {
                    let m = a.i64("molecule ID")?;
                    (a.last().unwrap(), SetValue::One(m as f64))
                };
                each(&mut sim.state.atoms, &v, w, &|m| m as i64 >= 0, "Invalid molecule ID in set command", &mut |at, i, m| at.molecule[i] = m as i64)?;
            }
            "image" => {
                let mut img: [Option<(&Word, SetValue)>; 3] = [None, None, None];
                for (d, slot) in img.iter_mut().enumerate() {
                    let what = ["ix", "iy", "iz"][d];
                    let periodic = sim.state.domain.as_ref().is_some_and(|dom| dom.periodic(d));
                    match a.peek() {
                        Some(w) if w.text == "NULL" => a.skip(1),
                        Some(w) if w.text.starts_with("v_") => {
                            if !periodic {
                                return Err(a.error_at(w, "Cannot set variable image flag for non-periodic dimension", "non-periodic dimension"));
                            }
                            *slot = Some(set_value(sim, &mut a, what, syntax)?);
                        }
                        _ => {
                            let w = a.word(what)?;
                            let f = word_i64(w, "image flag")?;
                            if f != 0 && !periodic {
                                return Err(a.error_at(w, "Cannot set non-zero image flag for non-periodic dimension", "non-periodic dimension"));
                            }
                            *slot = Some((w, SetValue::One(f as f64)));
                        }
                    }
                }
                for (d, slot) in img.iter().enumerate() {
                    if let Some((w, v)) = slot {
                        // a variable's value is truncated to an integer flag
                        each(&mut sim.state.atoms, v, w, &any, "", &mut |at, i, f| at.image[i][d] = f as i32)?;
                    }
                }
            }
            "x" | "y" | "z" | "vx" | "vy" | "vz" => {
                let (w, v) = set_value(sim, &mut a, &kw.text, syntax)?;
                let d = match &kw.text[kw.text.len() - 1..] {
                    "x" => 0,
                    "y" => 1,
                    _ => 2,
                };
                let vel = kw.text.starts_with('v');
                each(&mut sim.state.atoms, &v, w, &any, "", &mut |at, i, x| if vel { at.v[i][d] = x } else { at.x[i][d] = x })?;
            }
            "omega" => {
                need(ft.sphere, "angular velocities (sphere)")?;
                let vals = [set_value(sim, &mut a, "wx", syntax)?, set_value(sim, &mut a, "wy", syntax)?, set_value(sim, &mut a, "wz", syntax)?];
                for (d, (w, v)) in vals.iter().enumerate() {
                    each(&mut sim.state.atoms, v, w, &any, "", &mut |at, i, x| at.omega[i][d] = x)?;
                }
            }
            "quat" => {
                need(ft.quat, "orientations (bpm/sphere)")?;
                let dim = sim.state.domain.as_ref().map_or(3, |d| d.dimension);
                let names = ["a", "b", "c", "theta"];
                let mut vals = Vec::with_capacity(4);
                for (k, name) in names.iter().enumerate() {
                    let (w, v) = set_value(sim, &mut a, name, syntax)?;
                    if let (SetValue::One(x), true) = (&v, k < 2 && dim == 2) {
                        if *x != 0.0 {
                            return Err(a.error_at(w, "Cannot set quaternion with xy components for 2d system", "must be 0 in 2d"));
                        }
                    }
                    vals.push((w, v));
                }
                let at = &mut sim.state.atoms;
                for i in (0..n).filter(|&i| sel[i]) {
                    let [x, y, z, theta] = [0, 1, 2, 3].map(|k| vals[k].1.at(i));
                    if dim == 2 && (x != 0.0 || y != 0.0) {
                        return Err(set_value_error(vals[0].0, &vals[0].1, at.tag[i], x, "Cannot set quaternion with xy components for 2d system"));
                    }
                    // LAMMPS: the half angle, the axis scaled by its sine, then normalised
                    let half = std::f64::consts::FRAC_PI_2 * theta / 180.0;
                    let s = half.sin();
                    let mut q = [half.cos(), x * s, y * s, z * s];
                    crate::engine::quat::qnormalize(&mut q);
                    at.quat[i] = q;
                }
            }
            "quat/random" => {
                need(ft.quat, "orientations (bpm/sphere)")?;
                let seed = a.i64_in("random number seed", 1, i32::MAX as i64)? as i32;
                let three_d = sim.state.domain.as_ref().map_or(3, |d| d.dimension) == 3;
                let at = &mut sim.state.atoms;
                let mut r = crate::engine::random_park::RanPark::new(1);
                let pi = std::f64::consts::PI;
                // LAMMPS' generator reseeded by the seed and each atom's position
                for i in (0..n).filter(|&i| sel[i]) {
                    r.reset_coord(seed, at.x[i]);
                    at.quat[i] = if three_d {
                        let s = r.uniform();
                        let (t1, t2) = ((1.0 - s).sqrt(), s.sqrt());
                        let theta1 = 2.0 * pi * r.uniform();
                        let theta2 = 2.0 * pi * r.uniform();
                        [theta2.cos() * t2, theta1.sin() * t1, theta1.cos() * t1, theta2.sin() * t2]
                    } else {
                        let theta2 = pi * r.uniform();
                        [theta2.cos(), 0.0, 0.0, theta2.sin()]
                    };
                }
            }
            "sph/rho" | "sph/e" | "sph/cv" => {
                need(ft.sph, "SPH attributes (sph)")?;
                let (w, v) = set_value(sim, &mut a, &kw.text, syntax)?;
                let which = kw.text.clone();
                each(&mut sim.state.atoms, &v, w, &any, "", &mut |at, i, x| match which.as_str() {
                    "sph/rho" => at.rho[i] = x,
                    "sph/e" => at.esph[i] = x,
                    _ => at.cv[i] = x,
                })?;
            }
            "dmhs/conc" | "dmhs/water" => {
                let (_, v) = set_value(sim, &mut a, &kw.text, syntax)?;
                let st = &mut sim.state;
                crate::engine::water::set(&mut st.atoms, &st.type_mass, &st.mass_set, &sel, &kw.text, &|i| v.at(i)).map_err(|e| Diagnostic::at(kw.span, e, "cannot set the water field"))?;
            }
            "temperature" => {
                let Some(k) = sim.state.atoms.field(crate::engine::fields::TEMPERATURE) else {
                    return Err(Diagnostic::at(kw.span, "set temperature needs per-atom temperatures", "no temperature").with_help("define `fix ID all property/atom temperature` first"));
                };
                let (w, v) = set_value(sim, &mut a, "temperature", syntax)?;
                each(&mut sim.state.atoms, &v, w, &|t| t >= 0.0, "Invalid temperature in set command", &mut |at, i, t| at.extra[k].data[i] = t)?;
            }
            custom if (custom.starts_with("i_") || custom.starts_with("d_")) && custom.len() > 2 => {
                // LAMMPS: a fix property/atom value; an integer one truncates a variable's value
                let Some(k) = sim.state.atoms.find_extra(custom) else {
                    return Err(a.error_at(kw, format!("Set keyword or custom property {custom} does not exist"), "no such custom value").with_help(format!("define it first: fix ID all property/atom {custom}")));
                };
                let int = custom.starts_with("i_");
                let (w, v) = if int && !is_var(&a) {
                    let m = a.i64("integer value")?;
                    (a.last().unwrap(), SetValue::One(m as f64))
                } else {
                    set_value(sim, &mut a, custom, syntax)?
                };
                each(&mut sim.state.atoms, &v, w, &|_| true, "", &mut |at, i, x| at.extra[k].data[i] = if int { x.trunc() } else { x })?;
            }
            other => {
                let known = ["type", "type/fraction", "type/ratio", "type/subset", "mass", "diameter", "density", "density/disc", "charge", "mol", "image", "x", "y", "z", "vx", "vy", "vz", "omega", "quat", "quat/random", "sph/rho", "sph/e", "sph/cv", "dmhs/conc", "dmhs/water", "temperature", "i_NAME", "d_NAME"];
                let mut d = a.error_at(kw, format!("set keyword `{other}` is not supported"), "unknown or unsupported keyword");
                if let Some(h) = dmhs_parser::suggest::did_you_mean_help(other, known) {
                    d = d.with_help(h);
                }
                return Err(d);
            }
        }
        sim.out.print(&format!("Setting atom values ...\n  {made} settings made for {}", kw.text));
    }
    sim.state.lists_valid = false;
    Ok(())
}

/// A numeric `set` value: one number, or an atom-style variable's value for each owned atom.
/// A value given as a number (or an equal-style variable) or as an atom-style variable's values
/// over the owned atoms.
pub(crate) enum SetValue {
    One(f64),
    PerAtom(Vec<f64>),
}

impl SetValue {
    pub(crate) fn at(&self, i: usize) -> f64 {
        match self {
            SetValue::One(x) => *x,
            SetValue::PerAtom(v) => v[i],
        }
    }
    fn is_var(&self) -> bool {
        matches!(self, SetValue::PerAtom(_))
    }
}

/// Whether the next word is `v_name`.
fn is_var(a: &Args) -> bool {
    a.peek().is_some_and(|w| w.text.starts_with("v_"))
}

/// The next `set` value: a number, or `v_name` of an atom-style variable evaluated now over
/// every owned atom (LAMMPS' Set::varparse, then compute_atom on group all, with the values
/// the earlier keywords of the same command have set).
fn set_value<'c>(sim: &mut Simulation, a: &mut Args<'c>, what: &str, syntax: &str) -> DResult<(&'c Word, SetValue)> {
    let w = a.word(what)?;
    let Some(name) = w.text.strip_prefix("v_") else {
        return word_f64(w, what).map(|x| (w, SetValue::One(x))).map_err(|d| d.with_help(format!("syntax: {syntax}")));
    };
    let v = atom_variable_values(sim, w, name, "set command")?;
    Ok((w, SetValue::PerAtom(v)))
}

/// The values of atom-style variable `name` (named at `w`) over every owned atom, for command
/// `what` (set, group): LAMMPS' errors for a missing variable or another style.
pub(crate) fn atom_variable_values(sim: &mut Simulation, w: &Word, name: &str, what: &str) -> DResult<Vec<f64>> {
    match sim.variables.style(name) {
        Some("atom" | "atomfile") => {}
        None => return Err(Diagnostic::at(w.span, format!("Variable name {} for {what} does not exist", w.text), "no such variable").with_help(format!("define it first: variable {name} atom FORMULA"))),
        Some(style) => {
            return Err(Diagnostic::at(w.span, format!("Variable {} for {what} is invalid style", w.text), format!("an {style}-style variable")).with_help(format!("{what} takes atom-style variables only (as LAMMPS)")))
        }
    }
    let world = crate::models::world::World { state: &sim.state, computes: &sim.computes, fixes: crate::models::world::FixesView::all(&sim.fixes), bond: sim.bond_style.as_deref(), pair: sim.pair.as_deref() };
    let mut ev = crate::sim::eval::Eval { world, thermo: &sim.thermo, variables: &mut sim.variables, cpu: sim.last_loop_seconds };
    crate::models::atom_formula::atom_variable_drawing(name, &world, &mut ev, Some(&mut sim.random_atom)).map_err(|e| Diagnostic::at(w.span, e, "while evaluating this variable"))
}

/// The value of `v_name` at `w` for command `what` (velocity set, displace_atoms): an
/// equal-style variable's value or an atom-style one's values over the owned atoms, with
/// LAMMPS' errors for a missing variable or another style.
pub(crate) fn equal_or_atom_variable(sim: &mut Simulation, w: &Word, what: &str) -> DResult<SetValue> {
    let name = &w.text[2..];
    match sim.variables.style(name) {
        None => Err(Diagnostic::at(w.span, format!("Variable name for {what} does not exist: {}", w.text), "no such variable")),
        Some("atom" | "atomfile") => Ok(SetValue::PerAtom(atom_variable_values(sim, w, name, what)?)),
        Some("equal" | "internal" | "timer" | "python") => {
            dmhs_parser::variables::compute_equal(sim, name).map(SetValue::One).map_err(|e| Diagnostic::at(w.span, e, "while evaluating this variable"))
        }
        Some(style) => Err(Diagnostic::at(w.span, format!("Variable for {what} is invalid style: {} is {style}-style", w.text), "an equal- or atom-style variable is needed")),
    }
}

/// LAMMPS' error for a value it refuses, at the value's word (and the atom, for a variable).
fn set_value_error(w: &Word, v: &SetValue, tag: i64, x: f64, why: &str) -> Diagnostic {
    let label = if v.is_var() { format!("{x} for atom {tag}") } else { "out of range".into() };
    Diagnostic::at(w.span, why, label)
}

/// How `set ... type/fraction|type/ratio|type/subset` picks the atoms that change type.
#[derive(Clone, Copy)]
enum TypeRandom {
    /// each atom with probability f, from a generator reseeded by the seed and its position
    Fraction(f64),
    /// floor(f * eligible) atoms exactly
    Ratio(f64),
    /// N atoms exactly
    Subset(usize),
}

/// Change the type of the atoms `how` picks among the selected ones (`sel`) to `t`, as LAMMPS'
/// set does: the exact counts by `RanMars::select_subset` over the selected atoms in LAMMPS'
/// local order (`order`). Returns the number changed.
fn set_type_random(at: &mut crate::engine::atoms::Atoms, order: &[usize], sel: &[bool], t: usize, how: TypeRandom, seed: i32) -> usize {
    let eligible: Vec<usize> = order.iter().copied().filter(|&i| sel[i]).collect();
    let pick: Vec<bool> = match how {
        TypeRandom::Fraction(f) => {
            let mut r = crate::engine::random_park::RanPark::new(1);
            eligible
                .iter()
                .map(|&i| {
                    r.reset_coord(seed, at.x[i]);
                    r.uniform() < f
                })
                .collect()
        }
        TypeRandom::Ratio(_) | TypeRandom::Subset(_) => {
            let target = match how {
                // LAMMPS truncates fraction * count to an integer
                TypeRandom::Ratio(f) => (f * eligible.len() as f64) as usize,
                TypeRandom::Subset(m) => m,
                TypeRandom::Fraction(_) => unreachable!(),
            };
            crate::engine::random_mars::RanMars::new(seed).select_subset(target, eligible.len())
        }
    };
    let mut made = 0;
    for (&i, _) in eligible.iter().zip(&pick).filter(|(_, &p)| p) {
        at.typ[i] = t;
        made += 1;
    }
    made
}

pub fn velocity(sim: &mut Simulation, cmd: &Command, sources: &mut SourceMap) -> DResult<()> {
    need_box(sim, cmd)?;
    crate::deck::velocity::velocity_command(sim, cmd, sources)
}
