//! `fix ID group viscosity N vdim pdim Nbin [swap Nswap] [vtarget V|INF]`: the Muller-Plathe
//! method for the shear viscosity (Phys. Rev. E 59, 4894 (1999)) as LAMMPS' fix viscosity. The
//! box is cut into Nbin slabs along pdim; every N steps, at the end of the step, the Nswap atoms
//! of the group in the bottom slab whose vdim velocity is closest to +vtarget (at least 0; INF:
//! the fastest) exchange that momentum component with the Nswap atoms of the middle slab
//! (Nbin/2) closest to -vtarget, pair by pair, by reflecting both through the pair's centre-of-
//! mass velocity (atoms of different mass too). f_ID is the momentum so moved since the fix was
//! defined (negative: from the bottom slab to the middle one, as LAMMPS signs it). Atoms are
//! ranked in LAMMPS' atom order, and on several ranks the pairs are those LAMMPS' global ranking
//! picks.

use super::slab_swaps::{pairs, parse_nbin, parse_nswap, Slabs, BIG};
use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::args::word_f64;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group viscosity N vdim pdim Nbin [swap Nswap] [vtarget V|INF]";

pub struct FixViscosity {
    id: String,
    groupbit: u32,
    nevery: i64,
    vdim: usize,
    pdim: usize,
    nbin: usize,
    nswap: usize,
    vtarget: f64,
    p_exchange: f64,
}

impl FixViscosity {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let nevery = a.i64_in("N (steps between swaps)", 1, i64::MAX)?;
        let vdim = a.choice("vdim (the velocity component swapped)", &["x", "y", "z"])?;
        let pdim = a.choice("pdim (the direction of the slabs)", &["x", "y", "z"])?;
        let nbin = parse_nbin(&mut a, "viscosity")?;
        let (mut nswap, mut vtarget) = (1, BIG);
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "swap" => nswap = parse_nswap(&mut a)?,
                "vtarget" => {
                    let v = a.word("vtarget (a positive velocity or INF)")?;
                    vtarget = if v.text == "INF" { BIG } else { word_f64(&v, "vtarget")? };
                    if vtarget <= 0.0 {
                        return Err(a.error_at(&v, "Fix viscosity vtarget value must be positive", "not positive"));
                    }
                }
                _ => return Err(a.unknown_keyword(w, &["swap", "vtarget"])),
            }
        }
        Ok(FixViscosity { id, groupbit, nevery, vdim, pdim, nbin, nswap, vtarget, p_exchange: 0.0 })
    }
}

impl Fix for FixViscosity {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "viscosity"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { end_of_step: true, ..FixHooks::default() }
    }
    fn global_freq(&self) -> i64 {
        self.nevery
    }
    fn init_warnings(&self, [_, later]: [&[Box<dyn Fix>]; 2]) -> Vec<String> {
        super::slab_swaps::ave_chunk_after("viscosity", later).into_iter().collect()
    }
    fn end_of_step(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step % self.nevery != 0 {
            return Ok(());
        }
        let Some(slabs) = Slabs::new(state, self.pdim, self.nbin) else { return Ok(()) };
        let (vd, vt) = (self.vdim, self.vtarget);
        // the bottom slab's atoms moving along +vdim closest to +vtarget, the middle slab's
        // moving along -vdim closest to -vtarget
        let [pos, neg] = slabs.candidates(state, self.groupbit, self.nswap, |slab, v, _| match slab {
            0 => (v[vd] >= 0.0).then(|| (v[vd] - vt).abs()),
            _ => (v[vd] <= 0.0).then(|| (v[vd] + vt).abs()),
        });
        let mut pswap = 0.0;
        for p in pairs(state, self.nswap, &pos, &neg) {
            let (q, n) = (p.first, p.second);
            let vcm = (n.m * n.v[vd] + q.m * q.v[vd]) / (n.m + q.m);
            pswap += q.m * (vcm - q.v[vd]) - n.m * (vcm - n.v[vd]);
            for (local, x) in [(p.second_local, n), (p.first_local, q)] {
                if let Some(i) = local {
                    state.atoms.v[i][vd] = 2.0 * vcm - x.v[vd];
                }
            }
        }
        self.p_exchange += pswap;
        Ok(())
    }
    fn scalar(&self, _state: &State) -> Option<f64> {
        Some(self.p_exchange)
    }
}
