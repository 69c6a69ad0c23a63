//! What the Muller-Plathe exchanges (fix thermal/conductivity, fix viscosity) share, as LAMMPS
//! does them: the bottom slab and the middle one (Nbin/2) along a direction, each slab's best
//! candidates kept in order on each rank, and the global ranking of LAMMPS' MINLOC reductions
//! that pairs them (lowest key first, ties to the lower rank; a list used up offers BIG, and a
//! swap is skipped when either side has only BIG).

use crate::engine::state::State;
use dmhs_parser::{Args, DResult};

/// What a rank offers when it has no candidate left (LAMMPS' BIG).
pub const BIG: f64 = 1.0e10;

/// Nbin, which must be even (the middle slab is Nbin/2) and above 2, as LAMMPS checks it.
pub fn parse_nbin(a: &mut Args, style: &str) -> DResult<usize> {
    let w = a.peek();
    let nbin = a.i64_in("Nbin (number of slabs)", 3, i64::MAX)? as usize;
    match (nbin % 2, w) {
        (1, Some(w)) => Err(a.error_at(w, format!("fix {style}: Nbin must be even (the middle slab is Nbin/2), got {nbin}"), "odd Nbin")),
        _ => Ok(nbin),
    }
}

/// `swap Nswap` of the two fixes.
pub fn parse_nswap(a: &mut Args) -> DResult<usize> {
    Ok(a.i64_in("Nswap (atom pairs swapped each time)", 1, i64::MAX)? as usize)
}

/// LAMMPS' warning when a fix ave/chunk comes after the exchanging fix `style`: its profile is
/// then sampled right after the swaps.
pub fn ave_chunk_after(style: &str, later: &[Box<dyn super::Fix>]) -> Option<String> {
    later.iter().any(|f| f.style() == "ave/chunk").then(|| format!("Fix {style} comes before fix ave/chunk"))
}

/// One swap candidate: its ranking key (the lowest goes first), velocity, mass and local index.
#[derive(Clone, Copy, Debug)]
pub struct Candidate {
    pub key: f64,
    pub v: [f64; 3],
    pub m: f64,
    pub i: usize,
}

/// Offer `c` to `list`, which keeps the `n` lowest keys in order: it goes after the candidates
/// with a lower key, so before its ties (LAMMPS' insertion).
fn offer(list: &mut Vec<Candidate>, n: usize, c: Candidate) {
    if list.len() == n && c.key >= list[n - 1].key {
        return;
    }
    let at = list.iter().rposition(|e| e.key < c.key).map_or(0, |k| k + 1);
    list.insert(at, c);
    list.truncate(n);
}

/// The two slabs along `dim` of a box cut into `nbin` (the bottom one and the one at nbin/2):
/// which of them holds a coordinate, mapped into a periodic box first.
pub struct Slabs {
    dim: usize,
    lo: f64,
    hi: f64,
    prd: f64,
    periodic: bool,
    bottom: [f64; 2],
    middle: [f64; 2],
}

impl Slabs {
    pub fn new(state: &State, dim: usize, nbin: usize) -> Option<Slabs> {
        let d = state.domain.as_ref()?;
        let (lo, hi) = (d.lo[dim], d.hi[dim]);
        let binsize = (hi - lo) / nbin as f64;
        Some(Slabs {
            dim,
            lo,
            hi,
            prd: d.prd()[dim],
            periodic: d.periodic(dim),
            bottom: [lo, lo + binsize],
            middle: [lo + (nbin / 2) as f64 * binsize, lo + (nbin / 2 + 1) as f64 * binsize],
        })
    }
    /// (in the bottom slab, in the middle slab) for coordinate `x`.
    fn of(&self, mut x: f64) -> (bool, bool) {
        if x < self.lo && self.periodic {
            x += self.prd;
        } else if x >= self.hi && self.periodic {
            x -= self.prd;
        }
        let inside = |s: [f64; 2]| x >= s[0] && x < s[1];
        (inside(self.bottom), inside(self.middle))
    }
    /// The `nswap` best candidates of the group in the bottom slab and in the middle one, the
    /// atoms walked in LAMMPS' order; `key(slab, v, m)` ranks an atom of slab 0 (bottom) or 1
    /// (middle), None leaving it out.
    pub fn candidates(&self, state: &State, groupbit: u32, nswap: usize, key: impl Fn(usize, [f64; 3], f64) -> Option<f64>) -> [Vec<Candidate>; 2] {
        let mut lists = [Vec::with_capacity(nswap + 1), Vec::with_capacity(nswap + 1)];
        let a = &state.atoms;
        for &i in state.lammps_order.indices(a.nlocal).iter() {
            if a.mask[i] & groupbit == 0 {
                continue;
            }
            let slab = match self.of(a.x[i][self.dim]) {
                (true, _) => 0,
                (_, true) => 1,
                _ => continue,
            };
            let (v, m) = (a.v[i], state.mass(i));
            if let Some(key) = key(slab, v, m) {
                offer(&mut lists[slab], nswap, Candidate { key, v, m, i });
            }
        }
        lists
    }
}

/// One exchange: the two candidates and, where this rank owns them, their local indices.
pub struct Pair {
    pub first: Candidate,
    pub first_local: Option<usize>,
    pub second: Candidate,
    pub second_local: Option<usize>,
}

/// Up to `nswap` pairs from every rank's two lists (each at most `nswap` long, in order), in
/// the order LAMMPS' MINLOC loop makes them.
pub fn pairs(state: &State, nswap: usize, first: &[Candidate], second: &[Candidate]) -> Vec<Pair> {
    // every rank's lists (key, v, m per entry, BIG past the end)
    let pack = |list: &[Candidate]| -> Vec<f64> { (0..nswap).flat_map(|k| list.get(k).map_or([BIG, 0.0, 0.0, 0.0, 0.0], |c| [c.key, c.v[0], c.v[1], c.v[2], c.m])).collect() };
    let all = state.allgather_ranks([pack(first), pack(second)].concat());
    let width = 10 * nswap;
    let me = state.decomp.as_ref().filter(|_| state.distributed.is_some()).map_or(0, |d| d.rank());
    let nranks = all.len() / width;
    let entry = |r: usize, list: usize, k: usize| -> Candidate {
        let o = r * width + list * 5 * nswap + 5 * k;
        Candidate { key: all[o], v: [all[o + 1], all[o + 2], all[o + 3]], m: all[o + 4], i: usize::MAX }
    };
    // the rank whose next entry of `list` has the lowest key; None when that key is BIG
    let pick = |next: &[usize], list: usize| -> Option<usize> {
        let key = |r: usize| if next[r] < nswap { entry(r, list, next[r]).key } else { BIG };
        let r = (0..nranks).fold(0, |best, r| if key(r) < key(best) { r } else { best });
        (key(r) != BIG).then_some(r)
    };
    let mut next = [vec![0; nranks], vec![0; nranks]];
    let mut out = Vec::new();
    for _ in 0..nswap {
        let (Some(r1), Some(r2)) = (pick(&next[0], 0), pick(&next[1], 1)) else { continue };
        out.push(Pair {
            first: entry(r1, 0, next[0][r1]),
            first_local: (r1 == me).then(|| first[next[0][r1]].i),
            second: entry(r2, 1, next[1][r2]),
            second_local: (r2 == me).then(|| second[next[1][r2]].i),
        });
        next[0][r1] += 1;
        next[1][r2] += 1;
    }
    out
}
