//! `fix ID group halt N attribute operator avalue [error hard|soft|continue] [message yes|no]
//! [universe no]`: every N steps, compare an attribute with a value and stop the run when the
//! comparison holds, as LAMMPS' fix halt. Attributes: `bondmax` (the longest bond), `tlimit`
//! (seconds since the run's loop started), `v_name` (an equal-style variable). `error hard`
//! stops the deck with an error; `soft` ends this run after the current step (its output
//! included) and makes later `run` and `minimize` commands do nothing, as LAMMPS' expired
//! timer; `continue` ends this run only. The group is ignored, as in LAMMPS.

use super::{Fix, FixCtx, FixDef, FixHooks, MinRole};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, DResult};

pub const SYNTAX: &str = "fix ID group halt N bondmax|tlimit|v_name OP avalue [error hard|soft|continue] [message yes|no] [universe no]  (OP: < <= > >= == != |^)";

const OPERATORS: [&str; 7] = ["<", "<=", ">", ">=", "==", "!=", "|^"];

enum Attribute {
    BondMax,
    TimeLimit,
    Variable(String),
}

#[derive(Clone, Copy, PartialEq)]
enum OnHalt {
    Hard,
    Soft,
    Continue,
}

pub struct FixHalt {
    id: String,
    groupbit: u32,
    every: i64,
    attribute: Attribute,
    /// Index into [`OPERATORS`].
    operator: usize,
    value: f64,
    on_halt: OnHalt,
    message: bool,
    /// When this run's loop started (the clock of `tlimit`).
    started: Option<std::time::Instant>,
}

impl FixHalt {
    pub fn from_lammps(d: FixDef) -> DResult<Self> {
        let mut a = Args::from_words(d.args, d.cmd.span, SYNTAX);
        let every = a.i64_in("N", 1, i64::MAX)?;
        let w = a.word("attribute")?;
        let attribute = match w.text.as_str() {
            "bondmax" => Attribute::BondMax,
            "tlimit" => Attribute::TimeLimit,
            "diskfree" => return Err(a.error_at(w, "fix halt diskfree is not supported by dmhs", "bondmax, tlimit or v_name")),
            t => match t.strip_prefix("v_") {
                Some(name) if !name.is_empty() => Attribute::Variable(name.to_string()),
                _ => return Err(a.error_at(w, format!("Invalid fix halt attribute {t}"), "bondmax, tlimit or v_name")),
            },
        };
        let operator = a.choice("operator", &OPERATORS)?;
        let value = a.f64("avalue")?;
        let (mut on_halt, mut message) = (OnHalt::Soft, true);
        while let Some(k) = a.peek() {
            a.skip(1);
            match k.text.as_str() {
                "error" => on_halt = [OnHalt::Hard, OnHalt::Soft, OnHalt::Continue][a.choice("error", &["hard", "soft", "continue"])?],
                "message" => message = a.yes_no("message")?,
                "universe" => {
                    if a.yes_no("universe")? {
                        return Err(a.error_at(k, "fix halt universe yes needs multiple partitions, which dmhs does not run", "universe no"));
                    }
                }
                "path" => return Err(a.error_at(k, "fix halt path is only used with diskfree, which dmhs does not support", "error, message or universe")),
                _ => return Err(a.unknown_keyword(k, &["error", "message", "universe"])),
            }
        }
        Ok(FixHalt { id: d.id, groupbit: d.groupbit, every, attribute, operator, value, on_halt, message, started: None })
    }

    /// Whether the condition holds for `x` (LAMMPS' comparisons; `|^` is exclusive or of
    /// "non-zero").
    fn met(&self, x: f64) -> bool {
        let v = self.value;
        match self.operator {
            0 => x < v,
            1 => x <= v,
            2 => x > v,
            3 => x >= v,
            4 => x == v,
            5 => x != v,
            _ => (x == 0.0) != (v == 0.0),
        }
    }
}

/// The longest bond of the system (minimum image), over the ranks: bonds that are on (type
/// > 0), listed by an owner of their first atom.
fn bondmax(state: &State) -> Result<f64, String> {
    let a = &state.atoms;
    let dom = state.domain()?;
    let map = a.tag_map();
    let mut max = 0.0f64;
    for b in state.topo.bonds.iter().filter(|b| b.typ > 0 && !b.off) {
        let (Some(i), Some(j)) = (map.get(b.atoms[0]), map.get(b.atoms[1])) else { continue };
        if i >= a.nlocal {
            continue;
        }
        let mut d = [a.x[i][0] - a.x[j][0], a.x[i][1] - a.x[j][1], a.x[i][2] - a.x[j][2]];
        dom.minimum_image(&mut d);
        max = max.max(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
    let mut m = [max];
    state.max_ranks(&mut m);
    Ok(m[0].sqrt())
}

impl Fix for FixHalt {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "halt"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { end_of_step: true, ..FixHooks::default() }
    }
    fn min_role(&self) -> MinRole {
        MinRole::Refused(format!("fix halt {} during minimize is not supported by dmhs (it checks during run only)", self.id))
    }
    fn setup(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.started = Some(std::time::Instant::now());
        if let Attribute::Variable(name) = &self.attribute {
            let ok = ctx.eval(state, self, |_, ev| Ok(ev.variables().style(name).map(|_| ev.variables().is_equal_style(name))))?;
            match ok {
                None => return Err(RunError::new(state.step, format!("fix halt {}: Could not find fix halt variable name {name}", self.id))),
                Some(false) => return Err(RunError::new(state.step, format!("fix halt {}: Fix halt variable {name} is not equal-style variable", self.id))),
                Some(true) => {}
            }
        }
        Ok(())
    }
    fn wants_energy(&self, step: i64) -> bool {
        matches!(self.attribute, Attribute::Variable(_)) && step % self.every == 0
    }
    fn end_of_step(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step % self.every != 0 {
            return Ok(());
        }
        let x = match &self.attribute {
            Attribute::BondMax => bondmax(state).map_err(|e| RunError::new(state.step, format!("fix halt {}: {e}", self.id)))?,
            Attribute::TimeLimit => {
                // the same clock on every rank: the slowest one's
                let mut t = [self.started.map_or(0.0, |t| t.elapsed().as_secs_f64())];
                state.max_ranks(&mut t);
                t[0]
            }
            Attribute::Variable(name) => {
                let name = name.clone();
                ctx.equal(state, self, &name).map_err(|e| RunError::new(state.step, format!("fix halt {}: variable `{name}`: {e}", self.id)))?
            }
        };
        if !self.met(x) {
            return Ok(());
        }
        let text = format!("Fix halt condition for fix-id {} met on step {} with value {}", self.id, state.step, dmhs_parser::numfmt::shortest(x));
        if self.on_halt == OnHalt::Hard {
            return Err(RunError::new(state.step, text));
        }
        if self.message {
            state.messages.push(text);
        }
        state.halted = true;
        Ok(())
    }
    fn post_run(&mut self, state: &mut State) {
        if self.on_halt == OnHalt::Continue {
            state.halted = false;
        }
    }
}
