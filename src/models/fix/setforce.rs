//! `fix ID group setforce fx fy fz [region R]`: sets force components, each a constant, an
//! equal- or atom-style variable, or NULL (left alone); f_ID[1..3] is the force before it was set.

use super::value::FixValue;
use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group setforce fx|NULL fy|NULL fz|NULL [region region-ID]";

pub struct FixSetForce {
    id: String,
    groupbit: u32,
    value: [FixValue; 3],
    /// Looked up by ID each time, so that `region ID delete` and a new definition are seen.
    region: Option<String>,
    foriginal: [f64; 3],
}

/// `region ID` keyword of a fix: the region's ID, which must exist now.
pub fn find_region(a: &mut Args, state: &State) -> DResult<String> {
    let w = a.word("region ID")?;
    match state.regions.iter().any(|r| r.id == w.text) {
        true => Ok(w.text.clone()),
        false => Err(a.error_at(w, format!("region `{}` does not exist", w.text), "unknown region")),
    }
}

/// The region a fix names, at run time (LAMMPS checks it when a run starts).
pub fn region_now<'a>(regions: &'a [crate::engine::region::Region], step: i64, fix: &str, id: &Option<String>) -> Result<Option<&'a crate::engine::region::Region>, RunError> {
    match id {
        None => Ok(None),
        Some(id) => regions.iter().find(|r| &r.id == id).map(Some).ok_or_else(|| RunError::new(step, format!("region {id} for fix {fix} does not exist"))),
    }
}

/// `fx fy fz [region R]` of fix setforce and fix aveforce: each a constant, v_name or NULL.
pub fn parse_components(args: &[Word], cmd: &Command, syntax: &'static str, state: &State) -> DResult<([FixValue; 3], Option<String>)> {
    let mut a = Args::from_words(args, cmd.span, syntax);
    let mut value = [FixValue::Null, FixValue::Null, FixValue::Null];
    for (k, what) in ["fx", "fy", "fz"].iter().enumerate() {
        let w = a.word(what)?;
        value[k] = FixValue::parse(w, what, true).map_err(|d| d.with_help(format!("syntax: {syntax}")))?;
    }
    Ok((value, region_keyword(&mut a, state)?))
}

/// The trailing `[region R]` of a fix whose only keyword it is.
pub fn region_keyword(a: &mut Args, state: &State) -> DResult<Option<String>> {
    let mut region = None;
    while let Some(w) = a.peek() {
        a.skip(1);
        match w.text.as_str() {
            "region" => region = Some(find_region(a, state)?),
            _ => return Err(a.unknown_keyword(w, &["region"])),
        }
    }
    Ok(region)
}

impl FixSetForce {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let (value, region) = parse_components(args, cmd, SYNTAX, state)?;
        Ok(FixSetForce { id, groupbit, value, region, foriginal: [0.0; 3] })
    }
}

impl Fix for FixSetForce {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "setforce"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    /// LAMMPS refuses a non-zero or variable force in a minimization (no energy goes with it).
    fn min_role(&self) -> super::MinRole {
        match self.value.iter().all(|v| matches!(v, FixValue::Null | FixValue::Const(0.0))) {
            true => super::MinRole::PostForce,
            false => super::MinRole::Refused(format!("fix {} (setforce): cannot use non-zero forces in an energy minimization (LAMMPS' rule; use 0.0 or NULL)", self.id)),
        }
    }
    fn post_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        let [vx, vy, vz] = [0, 1, 2].map(|k| ctx.value_per_atom(state, self, &self.value[k]));
        let fv = [vx?, vy?, vz?];
        let region = region_now(&state.regions, state.step, &self.id, &self.region)?;
        let a = &mut state.atoms;
        self.foriginal = [0.0; 3];
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            if let Some(r) = region {
                if !r.matches(a.x[i]) {
                    continue;
                }
            }
            let f = &mut a.f[i];
            for k in 0..3 {
                self.foriginal[k] += f[k];
                if let Some(v) = fv[k].at(i) {
                    f[k] = v;
                }
            }
        }
        Ok(())
    }
    fn vector(&self, state: &State, i: usize) -> Option<f64> {
        (1..=3).contains(&i).then(|| state.summed_over_ranks(self.foriginal[i - 1]))
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
}
