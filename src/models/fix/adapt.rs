//! `fix ID group adapt N pair pstyle pparam I J v_name ... atom diameter|diameter/disc|charge
//! v_name ... [reset yes|no] [scale yes|no] [mass yes|no]`: pair parameters and the group's
//! diameters or charges set from equal-style variables at the setup of each run and every N
//! steps before the forces (N = 0: setup only), as LAMMPS' FixAdapt::change_settings.
//!
//! * pair: the style's parameter for the type pairs (soft: a; lj/cut: epsilon, sigma), `scale
//!   yes` multiplying the value at the run's start; the style then re-derives its mixed and
//!   cached values (Pair::reinit). `reset yes` (LAMMPS' default is no) restores the values of
//!   the run's start after it.
//! * atom diameter: every group atom (ghosts too) gets radius value/2, or with `scale yes` its
//!   radius times value over the value of the last change (1 at each run's start); with `mass
//!   yes` (the default) its mass follows at constant density (r^3, r^2 for diameter/disc).
//!   atom charge: the charge, or scaled the same way. `reset yes` gives the group's atoms back
//!   the radius (mass with it) or charge they had when the fix was defined (an atom added later:
//!   when the fix first saw it), as LAMMPS' restore_settings, whose mass factor under `scale yes`
//!   is the last scale itself.
//!
//! kspace, bond and angle attributes are located errors.

use super::{Fix, FixCtx, FixHooks, MinRole};
use crate::engine::state::{PairParamChange, RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};
use std::collections::HashMap;

pub const SYNTAX: &str = "fix ID group adapt N pair pstyle pparam I J v_name | atom diameter|diameter/disc|charge v_name ... [reset yes|no] [scale yes|no] [mass yes|no]";

/// What an item changes.
enum Target {
    Pair {
        pstyle: String,
        param: String,
        /// Type pairs i <= j of the I J ranges, as LAMMPS loops them (i, then j >= max(jlo, i)).
        pairs: Vec<(usize, usize)>,
        /// The values at the run's start (LAMMPS' array_orig, taken at init).
        orig: Vec<f64>,
    },
    /// atom diameter (`disc`: diameter/disc, mass as r^2)
    Diameter { disc: bool },
    Charge,
}

struct Item {
    target: Target,
    /// the equal-style variable
    var: String,
}

pub struct FixAdapt {
    id: String,
    groupbit: u32,
    nevery: i64,
    items: Vec<Item>,
    reset: bool,
    scale: bool,
    mass: bool,
    /// The value of the last diameter and charge change under `scale yes` (LAMMPS'
    /// previous_diam_scale, previous_chg_scale; 1 at each run's init: LAMMPS 22 Jul 2025 writes
    /// them to restart files, yet a run after read_restart starts again from 1, measured).
    previous_diam: f64,
    previous_chg: f64,
    /// With `reset yes`: each atom's radius and charge when the fix was defined (0 outside the
    /// group, as LAMMPS' store fix), by atom ID.
    stored_radius: HashMap<i64, f64>,
    stored_q: HashMap<i64, f64>,
}

impl FixAdapt {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let nevery = a.i64("N")?;
        if nevery < 0 {
            return Err(a.error_at(&args[0], "fix adapt N must be >= 0", "negative"));
        }
        let (mut items, mut reset, mut scale, mut mass) = (vec![], false, false, true);
        let variable = |a: &mut Args| -> DResult<String> {
            let vw = a.word("v_name")?;
            match vw.text.strip_prefix("v_") {
                Some(name) => Ok(name.to_string()),
                None => Err(a.error_at(vw, format!("fix adapt takes an equal-style variable here (v_name), not {}", vw.text), "expected v_name")),
            }
        };
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "pair" => {
                    let pstyle = a.word("pair style")?.text.clone();
                    let param = a.word("pair parameter")?.text.clone();
                    let (ilo, ihi, jlo, jhi) = crate::models::pair::coeff_type_ranges(&mut a, state.ntypes)?;
                    let var = variable(&mut a)?;
                    let pairs = (ilo..=ihi).flat_map(|i| (jlo.max(i)..=jhi).map(move |j| (i, j))).collect();
                    items.push(Item { target: Target::Pair { pstyle, param, pairs, orig: vec![] }, var });
                }
                "atom" => {
                    let target = match a.choice("per-atom property", &["diameter", "diameter/disc", "charge"])? {
                        0 => Target::Diameter { disc: false },
                        1 => Target::Diameter { disc: true },
                        _ => Target::Charge,
                    };
                    items.push(Item { target, var: variable(&mut a)? });
                }
                "kspace" | "bond" | "angle" => return Err(a.error_at(w, format!("fix adapt `{}` is not supported (pair and atom attributes only)", w.text), "not supported")),
                "reset" => reset = a.yes_no("reset")?,
                "scale" => scale = a.yes_no("scale")?,
                "mass" => mass = a.yes_no("mass")?,
                _ => return Err(a.unknown_keyword(w, &["pair", "atom", "reset", "scale", "mass"])),
            }
        }
        if items.is_empty() {
            return Err(a.missing("an attribute (pair pstyle pparam I J v_name, or atom diameter|charge v_name)"));
        }
        let mut fix = FixAdapt { id, groupbit, nevery, items, reset, scale, mass, previous_diam: 1.0, previous_chg: 1.0, stored_radius: HashMap::new(), stored_q: HashMap::new() };
        // LAMMPS' post_constructor: the values reset yes restores, stored when the fix is made
        if reset {
            let at = &state.atoms;
            let group = |k: usize, v: f64| if at.mask[k] & groupbit != 0 { v } else { 0.0 };
            if fix.diameter().is_some() && at.features.sphere {
                fix.stored_radius = (0..at.nlocal).map(|k| (at.tag[k], group(k, at.radius[k]))).collect();
            }
            if fix.charges() && at.features.charge {
                fix.stored_q = (0..at.nlocal).map(|k| (at.tag[k], group(k, at.q[k]))).collect();
            }
        }
        Ok(fix)
    }

    /// `Some(disc)` when an item adapts diameters.
    fn diameter(&self) -> Option<bool> {
        self.items.iter().find_map(|it| match it.target {
            Target::Diameter { disc } => Some(disc),
            _ => None,
        })
    }
    fn charges(&self) -> bool {
        self.items.iter().any(|it| matches!(it.target, Target::Charge))
    }

    /// The equal-style variable `name` now (LAMMPS' checks: it exists, it is equal-style).
    fn equal(&self, state: &State, ctx: &mut FixCtx, name: &str) -> Result<f64, RunError> {
        let style = ctx.eval(state, self, |_, ev| Ok(ev.variables().style(name).map(str::to_string)))?;
        match style.as_deref() {
            None => Err(RunError::new(state.step, format!("Variable name {name} for fix adapt does not exist"))),
            Some("atom" | "vector" | "atomfile") => Err(RunError::new(state.step, format!("Variable {name} for fix adapt is invalid style"))),
            Some(_) => ctx.equal(state, self, name).map_err(|e| RunError::new(state.step, format!("fix adapt {}: variable `{name}`: {e}", self.id))),
        }
    }

    /// LAMMPS' change_settings: every item's variable now, then its pairs or the group's atoms
    /// (owned and ghosts) set or scaled.
    fn change(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.remember_new_atoms(state);
        for k in 0..self.items.len() {
            let value = self.equal(state, ctx, &self.items[k].var)?;
            let (scale, bit) = (self.scale, self.groupbit);
            match &self.items[k].target {
                Target::Pair { param, pairs, orig, .. } => {
                    for (n, &(i, j)) in pairs.iter().enumerate() {
                        let v = if scale { value * orig[n] } else { value };
                        state.pair_changes.push(PairParamChange { param: param.clone(), i, j, value: v });
                    }
                }
                &Target::Diameter { disc } => {
                    let at = &mut state.atoms;
                    let mut factor = value / self.previous_diam;
                    for i in 0..at.nall() {
                        if at.mask[i] & bit == 0 {
                            continue;
                        }
                        if self.mass {
                            if !scale {
                                factor = 0.5 * value / at.radius[i];
                            }
                            at.rmass[i] *= if disc { factor * factor } else { factor * factor * factor };
                        }
                        at.radius[i] = if scale { at.radius[i] * factor } else { 0.5 * value };
                    }
                    if scale {
                        self.previous_diam = value;
                    }
                }
                Target::Charge => {
                    let at = &mut state.atoms;
                    let factor = value / self.previous_chg;
                    for i in 0..at.nall() {
                        if at.mask[i] & bit != 0 {
                            at.q[i] = if scale { at.q[i] * factor } else { value };
                        }
                    }
                    if scale {
                        self.previous_chg = value;
                    }
                }
            }
        }
        Ok(())
    }

    /// With `reset yes`: atoms added since (pour, deposit, create_atoms) keep the radius and
    /// charge they have when the fix first sees them (LAMMPS' set_arrays at their creation).
    fn remember_new_atoms(&mut self, state: &State) {
        if !self.reset {
            return;
        }
        let at = &state.atoms;
        for k in 0..at.nlocal {
            if self.diameter().is_some() && at.features.sphere {
                self.stored_radius.entry(at.tag[k]).or_insert(at.radius[k]);
            }
            if self.charges() && at.features.charge {
                self.stored_q.entry(at.tag[k]).or_insert(at.q[k]);
            }
        }
    }
}

impl Fix for FixAdapt {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "adapt"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { pre_force: true, ..FixHooks::default() }
    }
    /// LAMMPS' minimizer calls setup_pre_force and post_run, which change the parameters;
    /// dmhs' minimize does not, so it refuses the fix.
    fn min_role(&self) -> MinRole {
        MinRole::Refused(format!("fix {} (adapt) is not supported in minimize", self.id))
    }
    fn init(&mut self, state: &State, ctx: &FixCtx) -> Result<(), String> {
        let f = &state.atoms.features;
        for item in &mut self.items {
            match &mut item.target {
                Target::Pair { pstyle, param, pairs, orig } => {
                    let pair = ctx.pair.ok_or("fix adapt: no pair style is defined")?;
                    if pair.style() != pstyle {
                        return Err(format!("fix adapt pair style {pstyle} does not exist (the pair style is {})", pair.style()));
                    }
                    *orig = pairs
                        .iter()
                        .map(|&(i, j)| pair.adapt_get(param, i, j).ok_or_else(|| format!("fix adapt: pair style {pstyle} has no parameter `{param}` it can change")))
                        .collect::<Result<_, _>>()?;
                }
                Target::Diameter { disc } => {
                    if state.groups.bit_is_dynamic(self.groupbit) {
                        return Err(format!("Cannot use dynamic group with fix adapt atom (fix {})", self.id));
                    }
                    if !f.sphere {
                        return Err("Fix adapt requires atom attribute diameter (atom_style sphere)".into());
                    }
                    if *disc && state.dimension != 2 {
                        return Err("Fix adapt requires 2d simulation (atom diameter/disc)".into());
                    }
                    if !state.radius_dynamic() {
                        return Err("Fix adapt changes atom radii but atom_style sphere is not dynamic (use atom_style sphere 1)".into());
                    }
                }
                Target::Charge => {
                    if state.groups.bit_is_dynamic(self.groupbit) {
                        return Err(format!("Cannot use dynamic group with fix adapt atom (fix {})", self.id));
                    }
                    if !f.charge {
                        return Err("Fix adapt requires atom attribute charge".into());
                    }
                }
            }
        }
        self.previous_diam = 1.0;
        self.previous_chg = 1.0;
        Ok(())
    }
    fn setup_pre_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.change(state, ctx)
    }
    fn pre_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if self.nevery == 0 || state.step % self.nevery != 0 {
            return Ok(());
        }
        self.change(state, ctx)
    }
    fn post_run(&mut self, state: &mut State) {
        if !self.reset {
            return;
        }
        self.remember_new_atoms(state);
        for item in &self.items {
            match &item.target {
                Target::Pair { param, pairs, orig, .. } => {
                    for (&(i, j), &value) in pairs.iter().zip(orig) {
                        state.pair_changes.push(PairParamChange { param: param.clone(), i, j, value });
                    }
                }
                // as LAMMPS' restore_settings: each atom item restores both (so a deck with two
                // restores twice)
                Target::Diameter { .. } | Target::Charge => self.restore_atoms(state),
            }
        }
    }
}

impl FixAdapt {
    /// LAMMPS' restore_settings for atoms: owned group atoms back to the stored radius (the
    /// mass scaled by the stored over the current radius, or under `scale yes` by the last
    /// scale, as LAMMPS) and charge.
    fn restore_atoms(&self, state: &mut State) {
        let bit = self.groupbit;
        let at = &mut state.atoms;
        if let Some(disc) = self.diameter().filter(|_| at.features.sphere) {
            for i in 0..at.nlocal {
                let Some(&stored) = self.stored_radius.get(&at.tag[i]).filter(|_| at.mask[i] & bit != 0) else { continue };
                if self.mass {
                    let factor = if self.scale { self.previous_diam } else { stored / at.radius[i] };
                    at.rmass[i] *= if disc { factor * factor } else { factor * factor * factor };
                }
                at.radius[i] = stored;
            }
        }
        if self.charges() && at.features.charge {
            for i in 0..at.nlocal {
                if let Some(&stored) = self.stored_q.get(&at.tag[i]).filter(|_| at.mask[i] & bit != 0) {
                    at.q[i] = stored;
                }
            }
        }
    }
}
