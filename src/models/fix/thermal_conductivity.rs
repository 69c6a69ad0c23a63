//! `fix ID group thermal/conductivity N edim Nbin [swap Nswap]`: the Muller-Plathe method
//! (J. Chem. Phys. 106, 6082 (1997)) as LAMMPS' fix thermal/conductivity. The box is cut into
//! Nbin slabs along edim; every N steps, at the end of the step, the Nswap hottest atoms of the
//! group in the bottom slab exchange their kinetic energy with the Nswap coldest in the middle
//! slab (Nbin/2), pair by pair, by reflecting both velocities through the pair's centre-of-mass
//! velocity (momentum kept, atoms of different mass too). f_ID is the energy moved from the
//! middle slab to the bottom one since the fix was defined; the heat flux follows from it.
//! Atoms are ranked in LAMMPS' atom order (ties as LAMMPS breaks them), and on several ranks
//! the pairs are those LAMMPS' global ranking picks.

use super::slab_swaps::{pairs, parse_nbin, parse_nswap, Candidate, Slabs};
use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group thermal/conductivity N edim Nbin [swap Nswap]";

pub struct FixThermalConductivity {
    id: String,
    groupbit: u32,
    nevery: i64,
    edim: usize,
    nbin: usize,
    nswap: usize,
    e_exchange: f64,
}

impl FixThermalConductivity {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let nevery = a.i64_in("N (steps between swaps)", 1, i64::MAX)?;
        let edim = a.choice("edim", &["x", "y", "z"])?;
        let nbin = parse_nbin(&mut a, "thermal/conductivity")?;
        let mut nswap = 1;
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "swap" => nswap = parse_nswap(&mut a)?,
                _ => return Err(a.unknown_keyword(w, &["swap"])),
            }
        }
        Ok(FixThermalConductivity { id, groupbit, nevery, edim, nbin, nswap, e_exchange: 0.0 })
    }
}

impl Fix for FixThermalConductivity {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "thermal/conductivity"
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
        super::slab_swaps::ave_chunk_after("thermal/conductivity", later).into_iter().collect()
    }
    fn end_of_step(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step % self.nevery != 0 {
            return Ok(());
        }
        let Some(slabs) = Slabs::new(state, self.edim, self.nbin) else { return Ok(()) };
        // the hottest atoms of the bottom slab (key -ke) and the coldest of the middle one (ke)
        let [hot, cold] = slabs.candidates(state, self.groupbit, self.nswap, |slab, v, m| {
            let ke = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * (0.5 * m);
            Some(if slab == 0 { -ke } else { ke })
        });
        let mut eswap = 0.0;
        for p in pairs(state, self.nswap, &hot, &cold) {
            let (h, c) = (p.first, p.second);
            let vcm: [f64; 3] = std::array::from_fn(|k| (c.m * c.v[k] + h.m * h.v[k]) / (c.m + h.m));
            let gain = |x: &Candidate| x.m * (vcm[0] * (vcm[0] - x.v[0]) + vcm[1] * (vcm[1] - x.v[1]) + vcm[2] * (vcm[2] - x.v[2]));
            // the cold atom gains what the hot one loses
            eswap += gain(&c);
            eswap -= gain(&h);
            for (local, x) in [(p.second_local, c), (p.first_local, h)] {
                if let Some(i) = local {
                    state.atoms.v[i] = std::array::from_fn(|k| 2.0 * vcm[k] - x.v[k]);
                }
            }
        }
        self.e_exchange += state.units.mvv2e * eswap;
        Ok(())
    }
    fn scalar(&self, _state: &State) -> Option<f64> {
        Some(self.e_exchange)
    }
}
