//! `fix ID group recenter x|NULL|INIT y|NULL|INIT z|NULL|INIT [shift group2] [units
//! box|lattice|fraction]`: before each step's integration, every atom of group2 (default the
//! fix's group) is moved by the difference between the target and the group's centre of mass
//! (unwrapped), so the centre stays at the target, as LAMMPS' fix recenter. INIT targets the
//! centre at the start of each run; NULL leaves a direction alone; `fraction` targets are
//! fractions of the box. f_ID is the distance moved in the last step, f_ID[1..3] the shift
//! (extensive, as LAMMPS'). Define it after the integrators (it acts in their hook, in order).

use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group recenter x|NULL|INIT y|NULL|INIT z|NULL|INIT [shift group2] [units box|lattice|fraction]";

#[derive(Clone, Copy)]
enum Target {
    At(f64),
    Null,
    Init,
}

#[derive(Clone, Copy, PartialEq)]
enum Scale {
    Box,
    Lattice,
    Fraction,
}

pub struct FixRecenter {
    id: String,
    groupbit: u32,
    /// The atoms moved.
    shift_bit: u32,
    target: [Target; 3],
    scale: Scale,
    /// The centre at the start of the run (INIT targets).
    init: [f64; 3],
    shift: [f64; 3],
    distance: f64,
}

impl FixRecenter {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let mut target = [Target::Null; 3];
        for (d, t) in target.iter_mut().enumerate() {
            let what = ["x", "y", "z"][d];
            *t = match a.peek().map(|w| w.text.as_str()) {
                Some("NULL") => Target::Null,
                Some("INIT") => Target::Init,
                _ => Target::At(a.f64(what)?),
            };
            if !matches!(t, Target::At(_)) {
                a.skip(1);
            }
        }
        let (mut shift_bit, mut scale) = (groupbit, Scale::Lattice);
        while let Some(k) = a.peek() {
            a.skip(1);
            match k.text.as_str() {
                "shift" => {
                    let g = a.word("group ID")?;
                    shift_bit = state.groups.bit(&g.text).ok_or_else(|| a.error_at(g, format!("Could not find fix recenter group ID {}", g.text), "an existing group"))?;
                }
                "units" => scale = [Scale::Box, Scale::Lattice, Scale::Fraction][a.choice("units", &["box", "lattice", "fraction"])?],
                _ => return Err(a.unknown_keyword(k, &["shift", "units"])),
            }
        }
        if scale == Scale::Lattice {
            let l = state.lattice_scale().map_err(|e| a.error_at(&cmd.name, e, "units lattice needs a lattice"))?;
            for (t, s) in target.iter_mut().zip(l) {
                if let Target::At(x) = t {
                    *x *= s;
                }
            }
        }
        if state.group_count(groupbit) == 0 {
            return Err(a.error_at(&cmd.name, "Fix recenter group has no atoms", "a group with atoms"));
        }
        Ok(FixRecenter { id, groupbit, shift_bit, target, scale, init: [0.0; 3], shift: [0.0; 3], distance: 0.0 })
    }
}

impl Fix for FixRecenter {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "recenter"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { initial_integrate: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        if self.target.iter().any(|t| matches!(t, Target::Init)) {
            self.init = state.group_xcm(self.groupbit).0;
        }
        Ok(())
    }
    fn initial_integrate(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        let (lo, hi) = state.domain.as_ref().map_or(([0.0; 3], [0.0; 3]), |d| (d.lo, d.hi));
        let xcm = state.group_xcm(self.groupbit).0;
        for d in 0..3 {
            self.shift[d] = match self.target[d] {
                Target::Null => 0.0,
                Target::Init => self.init[d] - xcm[d],
                Target::At(x) if self.scale == Scale::Fraction => lo[d] + x * (hi[d] - lo[d]) - xcm[d],
                Target::At(x) => x - xcm[d],
            };
        }
        let s = self.shift;
        self.distance = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
        let a = &mut state.atoms;
        for i in (0..a.nlocal).filter(|&i| a.mask[i] & self.shift_bit != 0) {
            for d in 0..3 {
                a.x[i][d] += s[d];
            }
        }
        Ok(())
    }
    fn scalar(&self, _state: &State) -> Option<f64> {
        Some(self.distance)
    }
    fn size_vector(&self) -> usize {
        3
    }
    fn vector(&self, _state: &State, i: usize) -> Option<f64> {
        (1..=3).contains(&i).then(|| self.shift[i - 1])
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
}
