//! `fix ID group adapt N pair pstyle pparam I J v_name ... [reset yes|no] [scale yes|no]
//! [mass yes|no]`: pair parameters set from equal-style variables at the setup of each run and
//! every N steps before the forces (N = 0: setup only), then back to their values before the
//! run with `reset yes` (LAMMPS' default is no); `scale yes` multiplies the original value instead. As
//! LAMMPS, the pair style then re-derives its mixed and cached values (Pair::reinit). Only
//! `pair` attributes of styles that expose the parameter (soft: a; lj/cut: epsilon, sigma);
//! kspace, atom, bond and angle attributes are located errors.

use super::value::FixValue;
use super::{Fix, FixCtx, FixHooks, MinRole};
use crate::engine::state::{PairParamChange, RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group adapt N pair pstyle pparam I J v_name [pair ...] [reset yes|no] [scale yes|no] [mass yes|no]";

struct Item {
    pstyle: String,
    param: String,
    /// Type pairs i <= j of the I J ranges, as LAMMPS loops them (i, then j >= max(jlo, i)).
    pairs: Vec<(usize, usize)>,
    var: FixValue,
    /// The values at the run's start (LAMMPS' array_orig, taken at init).
    orig: Vec<f64>,
}

pub struct FixAdapt {
    id: String,
    groupbit: u32,
    nevery: i64,
    items: Vec<Item>,
    reset: bool,
    scale: bool,
}

impl FixAdapt {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let nevery = a.i64("N")?;
        if nevery < 0 {
            return Err(a.error_at(&args[0], "fix adapt N must be >= 0", "negative"));
        }
        let (mut items, mut reset, mut scale) = (vec![], false, false);
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "pair" => {
                    let pstyle = a.word("pair style")?.text.clone();
                    let param = a.word("pair parameter")?.text.clone();
                    let (ilo, ihi, jlo, jhi) = crate::models::pair::coeff_type_ranges(&mut a, state.ntypes)?;
                    let vw = a.word("v_name")?;
                    if !vw.text.starts_with("v_") {
                        return Err(a.error_at(vw, "fix adapt takes an equal-style variable here (v_name)", "expected v_name"));
                    }
                    let var = FixValue::parse(vw, "v_name", false)?;
                    let pairs = (ilo..=ihi).flat_map(|i| (jlo.max(i)..=jhi).map(move |j| (i, j))).collect();
                    items.push(Item { pstyle, param, pairs, var, orig: vec![] });
                }
                "kspace" | "atom" | "bond" | "angle" => return Err(a.error_at(w, format!("fix adapt `{}` is not supported (only `pair` attributes)", w.text), "not supported")),
                "reset" => reset = a.yes_no("reset")?,
                "scale" => scale = a.yes_no("scale")?,
                // per-atom masses follow diameters only, which dmhs does not adapt
                "mass" => {
                    a.yes_no("mass")?;
                }
                _ => return Err(a.unknown_keyword(w, &["pair", "reset", "scale", "mass"])),
            }
        }
        if items.is_empty() {
            return Err(a.missing("an attribute (pair pstyle pparam I J v_name)"));
        }
        Ok(FixAdapt { id, groupbit, nevery, items, reset, scale })
    }

    /// LAMMPS' change_settings: every item's variable now, its pairs set (or scaled).
    fn change(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        for k in 0..self.items.len() {
            let value = ctx.value(state, self, &self.items[k].var)?.unwrap_or(0.0);
            let item = &self.items[k];
            for (n, &(i, j)) in item.pairs.iter().enumerate() {
                let v = if self.scale { value * item.orig[n] } else { value };
                state.pair_changes.push(PairParamChange { param: item.param.clone(), i, j, value: v });
            }
        }
        Ok(())
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
    fn init(&mut self, _state: &State, ctx: &FixCtx) -> Result<(), String> {
        let pair = ctx.pair.ok_or("fix adapt: no pair style is defined")?;
        for item in &mut self.items {
            if pair.style() != item.pstyle {
                return Err(format!("fix adapt pair style {} does not exist (the pair style is {})", item.pstyle, pair.style()));
            }
            item.orig = item
                .pairs
                .iter()
                .map(|&(i, j)| pair.adapt_get(&item.param, i, j).ok_or_else(|| format!("fix adapt: pair style {} has no parameter `{}` it can change", item.pstyle, item.param)))
                .collect::<Result<_, _>>()?;
        }
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
        for item in &self.items {
            for (&(i, j), &value) in item.pairs.iter().zip(&item.orig) {
                state.pair_changes.push(PairParamChange { param: item.param.clone(), i, j, value });
            }
        }
    }
}
