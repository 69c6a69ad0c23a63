//! `fix ID group thermal/conductivity N edim Nbin [swap Nswap]`: the Muller-Plathe method
//! (J. Chem. Phys. 106, 6082 (1997)) as LAMMPS' fix thermal/conductivity. The box is cut into
//! Nbin slabs along edim; every N steps, at the end of the step, the Nswap hottest atoms of the
//! group in the bottom slab exchange their kinetic energy with the Nswap coldest in the middle
//! slab (Nbin/2), pair by pair, by reflecting both velocities through the pair's centre-of-mass
//! velocity (momentum kept, atoms of different mass too). f_ID is the energy moved from the
//! middle slab to the bottom one since the fix was defined; the heat flux follows from it.
//! Atoms are ranked in LAMMPS' atom order (ties as LAMMPS breaks them), and on several ranks
//! the pairs are those LAMMPS' global ranking picks.

use super::{Fix, FixCtx, FixHooks};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group thermal/conductivity N edim Nbin [swap Nswap]";

/// The kinetic energy a rank offers when it has no atom left to swap (LAMMPS' BIG).
const BIG: f64 = 1.0e10;

pub struct FixThermalConductivity {
    id: String,
    groupbit: u32,
    nevery: i64,
    edim: usize,
    nbin: usize,
    nswap: usize,
    e_exchange: f64,
}

/// One swap candidate: its kinetic energy, velocity, mass and local index.
#[derive(Clone, Copy)]
struct Candidate {
    ke: f64,
    v: [f64; 3],
    m: f64,
    i: usize,
}

/// Offer `c` to `list`, which keeps the `n` best ordered by `ahead` (x ranks ahead of y): it
/// goes after the candidates strictly ahead of it, so before its ties (LAMMPS' insertion).
fn offer(list: &mut Vec<Candidate>, n: usize, c: Candidate, ahead: impl Fn(f64, f64) -> bool) {
    if list.len() == n && !ahead(c.ke, list[n - 1].ke) {
        return;
    }
    let at = list.iter().rposition(|e| ahead(e.ke, c.ke)).map_or(0, |k| k + 1);
    list.insert(at, c);
    list.truncate(n);
}

impl FixThermalConductivity {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let nevery = a.i64_in("N (steps between swaps)", 1, i64::MAX)?;
        let edim = a.choice("edim", &["x", "y", "z"])?;
        let w = a.peek();
        let nbin = a.i64_in("Nbin (number of slabs)", 3, i64::MAX)? as usize;
        if nbin % 2 != 0 {
            let w = w.expect("read above");
            return Err(a.error_at(w, format!("fix thermal/conductivity: Nbin must be even (the middle slab is Nbin/2), got {nbin}"), "odd Nbin"));
        }
        let mut nswap = 1;
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "swap" => nswap = a.i64_in("Nswap (atom pairs swapped each time)", 1, i64::MAX)? as usize,
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
    fn end_of_step(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.step % self.nevery != 0 {
            return Ok(());
        }
        let Some(d) = state.domain.as_ref() else { return Ok(()) };
        let e = self.edim;
        let (boxlo, boxhi, prd, periodic) = (d.lo[e], d.hi[e], d.prd()[e], d.periodic(e));
        let binsize = (boxhi - boxlo) / self.nbin as f64;
        let (lo_lo, lo_hi) = (boxlo, boxlo + binsize);
        let (hi_lo, hi_hi) = (boxlo + (self.nbin / 2) as f64 * binsize, boxlo + (self.nbin / 2 + 1) as f64 * binsize);
        // the hottest atoms of the bottom slab and the coldest of the middle one, in order
        let (mut hot, mut cold) = (Vec::with_capacity(self.nswap + 1), Vec::with_capacity(self.nswap + 1));
        let a = &state.atoms;
        for &i in state.lammps_order.indices(a.nlocal).iter() {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            let mut coord = a.x[i][e];
            if coord < boxlo && periodic {
                coord += prd;
            } else if coord >= boxhi && periodic {
                coord -= prd;
            }
            let (v, m) = (a.v[i], state.mass(i));
            let ke = || (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * (0.5 * m);
            if coord >= lo_lo && coord < lo_hi {
                offer(&mut hot, self.nswap, Candidate { ke: ke(), v, m, i }, |x, y| x > y);
            }
            if coord >= hi_lo && coord < hi_hi {
                offer(&mut cold, self.nswap, Candidate { ke: ke(), v, m, i }, |x, y| x < y);
            }
        }
        // every rank's lists (ke, v, m per entry, BIG past the end), so that each rank walks the
        // global ranking as LAMMPS' MINLOC reductions do, ties to the lower rank
        let width = 10 * self.nswap;
        let nswap = self.nswap;
        let pack = |list: &[Candidate]| -> Vec<f64> { (0..nswap).flat_map(|k| list.get(k).map_or([BIG, 0.0, 0.0, 0.0, 0.0], |c| [c.ke, c.v[0], c.v[1], c.v[2], c.m])).collect() };
        let all = state.allgather_ranks([pack(&hot), pack(&cold)].concat());
        let me = state.decomp.as_ref().filter(|_| state.distributed.is_some()).map_or(0, |d| d.rank());
        let nranks = all.len() / width;
        let entry = |r: usize, cold_list: bool, k: usize| -> Candidate {
            let o = r * width + if cold_list { 5 * self.nswap } else { 0 } + 5 * k;
            Candidate { ke: all[o], v: [all[o + 1], all[o + 2], all[o + 3]], m: all[o + 4], i: usize::MAX }
        };
        // the rank whose next entry is hottest (hot lists) or coldest (cold lists), None when
        // every list is used up
        let pick = |next: &[usize], cold_list: bool| -> Option<usize> {
            let key = |r: usize| match (next[r] < nswap).then(|| entry(r, cold_list, next[r]).ke) {
                None | Some(BIG) => BIG,
                Some(ke) if cold_list => ke,
                Some(ke) => -ke,
            };
            let r = (0..nranks).fold(0, |best, r| if key(r) < key(best) { r } else { best });
            (key(r) != BIG).then_some(r)
        };
        let (mut next_hot, mut next_cold) = (vec![0; nranks], vec![0; nranks]);
        let mut eswap = 0.0;
        let a = &mut state.atoms;
        for _ in 0..self.nswap {
            let (Some(rh), Some(rc)) = (pick(&next_hot, false), pick(&next_cold, true)) else { continue };
            let (h, c) = (entry(rh, false, next_hot[rh]), entry(rc, true, next_cold[rc]));
            let (hot_local, cold_local) = ((rh == me).then(|| hot[next_hot[rh]].i), (rc == me).then(|| cold[next_cold[rc]].i));
            next_hot[rh] += 1;
            next_cold[rc] += 1;
            let vcm: [f64; 3] = std::array::from_fn(|k| (c.m * c.v[k] + h.m * h.v[k]) / (c.m + h.m));
            let gain = |x: &Candidate| x.m * (vcm[0] * (vcm[0] - x.v[0]) + vcm[1] * (vcm[1] - x.v[1]) + vcm[2] * (vcm[2] - x.v[2]));
            // the cold atom gains what the hot one loses
            eswap += gain(&c);
            eswap -= gain(&h);
            for (local, x) in [(cold_local, c), (hot_local, h)] {
                if let Some(i) = local {
                    a.v[i] = std::array::from_fn(|k| 2.0 * vcm[k] - x.v[k]);
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
