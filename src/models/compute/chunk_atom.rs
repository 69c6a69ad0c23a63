//! `compute ID group chunk/atom style args [keyword value ...]`: assigns each atom a chunk ID
//! from 1 to Nchunk (0: in no chunk), as LAMMPS' compute chunk/atom (compute_chunk_atom.cpp).
//! Styles `bin/1d`, `bin/2d`, `bin/3d` (spatial bins), `type` and `molecule`; keywords
//! `region`, `nchunk once|every`, `limit N max|exact`, `ids once|nfreq|every`, `compress`,
//! `discard`, `bound`, `units box|lattice|reduced`. The per-atom vector is the chunk ID (dumps,
//! compute reduce); the scalar is Nchunk. fix ave/chunk reads the chunks through
//! [`ComputeChunkAtom::setup_chunks`] and [`ComputeChunkAtom::ichunk`].
//!
//! Chunk IDs are computed when asked, from the current state; what LAMMPS keeps between calls
//! (Nchunk with `nchunk once`, the IDs with `ids once`) is taken when a run starts and kept by
//! atom ID. dmhs boxes never change size, so bins are set up once unless `compress` or
//! `nchunk every` asks otherwise (LAMMPS' default for a static box).

use super::{Compute, PerAtom};
use crate::engine::state::State;
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};
use std::collections::{BTreeMap, HashMap};

pub const SYNTAX: &str = "compute ID group chunk/atom bin/1d|bin/2d|bin/3d|type|molecule [dim origin delta ...] [region R] [nchunk once|every] [limit N max|exact] [ids once|nfreq|every] [compress yes|no] [discard yes|no|mixed] [bound x|y|z lo hi] [units box|lattice|reduced]";

/// Where a bin grid starts along one dimension (LAMMPS' originflag).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Origin {
    Lower,
    Center,
    Upper,
    Coord(f64),
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Discard {
    No,
    Mixed,
    Yes,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Ids {
    Once,
    Nfreq,
    Every,
}

#[derive(Clone, Debug)]
enum Style {
    /// `ndim` bins along dimensions `dim[..ndim]`.
    Bins { ndim: usize, dim: [usize; 3], origin: [Origin; 3], delta: [f64; 3], invdelta: [f64; 3] },
    Type,
    Molecule,
}

/// The chunks of one setup (LAMMPS' setup_chunks): their number, the bin grid and coordinates,
/// the volume of a bin, and the original IDs of compressed chunks.
#[derive(Clone, Debug, Default)]
pub struct Chunks {
    pub nchunk: usize,
    /// Coordinates per chunk: the number of bin dimensions (0 without bins).
    pub ncoord: usize,
    offset: [f64; 3],
    nlayers: [usize; 3],
    /// Bin centres, `ncoord` values per original chunk ID (bins only).
    pub coord: Vec<[f64; 3]>,
    /// Volume of one chunk (the box volume for styles without bins).
    pub volume: f64,
    /// With `compress yes`: the populated original IDs in ascending order (chunk k is
    /// `chunk_id[k - 1]`), and the map back.
    pub chunk_id: Vec<i64>,
    hash: BTreeMap<i64, usize>,
}

pub struct ComputeChunkAtom {
    id: String,
    groupbit: u32,
    style: Style,
    region: Option<String>,
    nchunk_once: bool,
    limit: usize,
    limit_exact: bool,
    limit_first: bool,
    pub ids: Ids,
    pub compress: bool,
    discard: Discard,
    /// `bound`: the low and high limits per dimension (None: the box edge).
    min: [Option<f64>; 3],
    max: [Option<f64>; 3],
    reduced: bool,
    /// Chunks kept with `nchunk once`, from the first run.
    fixed: Option<Chunks>,
    /// Chunk IDs by atom ID kept with `ids once`, from the first run.
    stored: Option<HashMap<i64, usize>>,
}

/// One dimension of a bin style: `dim origin delta`.
fn read_dim<'a>(a: &mut Args<'a>, dimension: usize) -> DResult<(usize, Origin, f64, &'a Word)> {
    let w = a.peek();
    let d = a.choice("dimension", &["x", "y", "z"])?;
    if d == 2 && dimension == 2 {
        return Err(a.error_at(w.expect("read"), "cannot bin along z in a 2d model", "2d"));
    }
    let ow = a.word("origin (lower, center, upper or a coordinate)")?;
    let origin = match ow.text.as_str() {
        "lower" => Origin::Lower,
        "center" => Origin::Center,
        "upper" => Origin::Upper,
        _ => Origin::Coord(dmhs_parser::args::word_f64(ow, "origin")?),
    };
    let dw = a.peek();
    let delta = a.f64("bin width delta")?;
    Ok((d, origin, delta, dw.expect("read")))
}

impl ComputeChunkAtom {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        let state = w.state;
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let dimension = state.domain.as_ref().map_or(3, |d| d.dimension);
        let sw = a.word("chunk style")?;
        let style = match sw.text.as_str() {
            "bin/1d" | "bin/2d" | "bin/3d" => {
                let ndim = (sw.text.as_bytes()[4] - b'0') as usize;
                let (mut dim, mut origin, mut delta) = ([0; 3], [Origin::Lower; 3], [0.0; 3]);
                for m in 0..ndim {
                    let (d, o, del, dw) = read_dim(&mut a, dimension)?;
                    if del <= 0.0 {
                        return Err(a.error_at(dw, "the bin width must be positive", "delta > 0"));
                    }
                    if dim[..m].contains(&d) {
                        return Err(a.error_at(sw, format!("compute chunk/atom {}: the dimensions must differ", sw.text), "same dimension twice"));
                    }
                    (dim[m], origin[m], delta[m]) = (d, o, del);
                }
                Style::Bins { ndim, dim, origin, delta, invdelta: [0.0; 3] }
            }
            "type" => Style::Type,
            "molecule" => {
                if !state.atoms.features.molecule {
                    return Err(a.error_at(sw, "compute chunk/atom molecule needs an atom style with molecule IDs", "no molecule IDs"));
                }
                Style::Molecule
            }
            "bin/sphere" | "bin/cylinder" => return Err(a.error_at(sw, format!("compute chunk/atom {} is not supported yet (supported: bin/1d, bin/2d, bin/3d, type, molecule)", sw.text), "not supported")),
            t if t.starts_with("c_") || t.starts_with("f_") || t.starts_with("v_") => {
                return Err(a.error_at(sw, "compute chunk/atom with chunk IDs from a compute, fix or variable is not supported yet (supported: bin/1d, bin/2d, bin/3d, type, molecule)", "not supported"))
            }
            _ => return Err(a.unknown_keyword(sw, &["bin/1d", "bin/2d", "bin/3d", "type", "molecule"])),
        };
        let binflag = matches!(style, Style::Bins { .. });
        let mut c = ComputeChunkAtom {
            id,
            groupbit,
            style,
            region: None,
            nchunk_once: false,
            limit: 0,
            limit_exact: false,
            limit_first: false,
            ids: Ids::Every,
            compress: false,
            discard: if binflag { Discard::Mixed } else { Discard::Yes },
            min: [None; 3],
            max: [None; 3],
            reduced: false,
            fixed: None,
            stored: None,
        };
        let (mut nchunk_set, mut discard_w, mut lattice) = (None, None, true);
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "region" => {
                    let r = a.word("region ID")?;
                    if !state.regions.iter().any(|reg| reg.id == r.text) {
                        return Err(a.error_at(r, format!("region `{}` for compute chunk/atom does not exist", r.text), "unknown region"));
                    }
                    c.region = Some(r.text.clone());
                }
                "nchunk" => nchunk_set = Some(a.choice("nchunk", &["once", "every"])? == 0),
                "limit" => {
                    c.limit = a.usize_min("limit", 0)?;
                    if c.limit > 0 {
                        c.limit_first = !c.compress;
                        c.limit_exact = a.choice("limit style", &["max", "exact"])? == 1;
                    }
                }
                "ids" => c.ids = [Ids::Once, Ids::Nfreq, Ids::Every][a.choice("ids", &["once", "nfreq", "every"])?],
                "compress" => c.compress = a.yes_no("compress")?,
                "discard" => {
                    discard_w = Some(w);
                    c.discard = [Discard::Mixed, Discard::No, Discard::Yes][a.choice("discard", &["mixed", "no", "yes"])?];
                }
                "bound" => {
                    let d = a.choice("dimension", &["x", "y", "z"])?;
                    let lo = a.word("lower bound (lower or a coordinate)")?;
                    c.min[d] = if lo.text == "lower" { None } else { Some(dmhs_parser::args::word_f64(lo, "lower bound")?) };
                    let hi = a.word("upper bound (upper or a coordinate)")?;
                    c.max[d] = if hi.text == "upper" { None } else { Some(dmhs_parser::args::word_f64(hi, "upper bound")?) };
                }
                "units" => match a.choice("units", &["box", "lattice", "reduced"])? {
                    0 => lattice = false,
                    1 => lattice = true,
                    _ => (lattice, c.reduced) = (false, true),
                },
                "pbc" => return Err(a.error_at(w, "compute chunk/atom pbc is for bin/sphere and bin/cylinder, which are not supported yet", "not supported")),
                _ => return Err(a.unknown_keyword(w, &["region", "nchunk", "limit", "ids", "compress", "discard", "bound", "units"])),
            }
        }
        if !binflag && c.discard == Discard::Mixed {
            return Err(a.error_at(discard_w.expect("discard was given"), "compute chunk/atom without bins cannot use discard mixed", "mixed"));
        }
        // LAMMPS' defaults; a static box (dmhs boxes always are) makes bins `nchunk once`
        c.nchunk_once = match nchunk_set {
            Some(once) => once,
            None => !c.compress && (binflag || matches!(c.style, Style::Type) || (matches!(c.style, Style::Molecule) && c.region.is_none())),
        };
        if c.ids == Ids::Once && !c.nchunk_once {
            return Err(a.error_at(sw, "compute chunk/atom ids once needs nchunk once", "nchunk every"));
        }
        // lengths in lattice spacings become box lengths (the bounds as LAMMPS scales them:
        // by the dimension of the m-th bin direction)
        if let Style::Bins { ndim, dim, origin, delta, invdelta } = &mut c.style {
            let scale = if lattice { state.lattice_scale().map_err(|e| a.error_at(sw, e, "lattice"))? } else { [1.0; 3] };
            for m in 0..*ndim {
                let s = scale[dim[m]];
                delta[m] *= s;
                invdelta[m] = 1.0 / delta[m];
                if let Origin::Coord(o) = &mut origin[m] {
                    *o *= s;
                }
                if let Some(v) = &mut c.min[m] {
                    *v *= s;
                }
                if let Some(v) = &mut c.max[m] {
                    *v *= s;
                }
            }
        }
        Ok(c)
    }

    /// Whether atoms of this compute are binned (styles bin/*).
    pub fn ncoord(&self) -> usize {
        match self.style {
            Style::Bins { ndim, .. } => ndim,
            _ => 0,
        }
    }

    /// The chunks now (LAMMPS' setup_chunks): kept ones with `nchunk once`.
    pub fn setup_chunks(&self, state: &State) -> Result<Chunks, String> {
        match &self.fixed {
            Some(c) => Ok(c.clone()),
            None => self.new_chunks(state),
        }
    }

    fn new_chunks(&self, state: &State) -> Result<Chunks, String> {
        let dom = state.domain()?;
        let mut ch = Chunks::default();
        let prd = dom.prd();
        let mut volume = prd[0] * prd[1];
        if dom.dimension == 3 {
            volume *= prd[2];
        }
        if let Style::Bins { ndim, dim, origin, delta, invdelta } = &self.style {
            let (lo_box, hi_box) = if self.reduced { ([0.0; 3], [1.0; 3]) } else { (dom.lo, dom.hi) };
            let mut nbins = 1;
            for m in 0..*ndim {
                let d = dim[m];
                let binlo = self.min[d].unwrap_or(lo_box[d]);
                let binhi = self.max[d].unwrap_or(hi_box[d]);
                let o = match origin[m] {
                    Origin::Lower => binlo,
                    Origin::Upper => binhi,
                    Origin::Center => 0.5 * (binlo + binhi),
                    Origin::Coord(c) => c,
                };
                // the bin edges just below binlo and just above binhi
                let lo = if o < binlo {
                    o + ((binlo - o) * invdelta[m]) as i32 as f64 * delta[m]
                } else {
                    let lo = o - ((o - binlo) * invdelta[m]) as i32 as f64 * delta[m];
                    if lo > binlo { lo - delta[m] } else { lo }
                };
                let hi = if o < binhi {
                    let hi = o + ((binhi - o) * invdelta[m]) as i32 as f64 * delta[m];
                    if hi < binhi { hi + delta[m] } else { hi }
                } else {
                    o - ((o - binhi) * invdelta[m]) as i32 as f64 * delta[m]
                };
                if lo > hi {
                    return Err(format!("compute chunk/atom {}: invalid bin bounds", self.id));
                }
                ch.offset[m] = lo;
                ch.nlayers[m] = ((hi - lo) * invdelta[m] + 0.5) as i32 as usize;
                nbins *= ch.nlayers[m];
            }
            if nbins > 100_000_000 {
                return Err(format!("compute chunk/atom {}: {nbins} bins is too many", self.id));
            }
            let centre = |m: usize, i: usize| ch.offset[m] + (i as f64 + 0.5) * delta[m];
            let n = ch.nlayers;
            for i in 0..n[0] {
                for j in 0..if *ndim > 1 { n[1] } else { 1 } {
                    for k in 0..if *ndim > 2 { n[2] } else { 1 } {
                        ch.coord.push([centre(0, i), if *ndim > 1 { centre(1, j) } else { 0.0 }, if *ndim > 2 { centre(2, k) } else { 0.0 }]);
                    }
                }
            }
            ch.nchunk = nbins;
            ch.ncoord = *ndim;
            for m in 0..*ndim {
                volume *= delta[m] / if self.reduced { 1.0 } else { prd[dim[m]] };
            }
        }
        ch.volume = volume;
        let (ichunk, exclude) = self.assign(state, &ch)?;
        match self.style {
            Style::Type => ch.nchunk = state.ntypes,
            Style::Molecule => {
                let hi = (0..ichunk.len()).filter(|&i| !exclude[i]).map(|i| ichunk[i]).max().unwrap_or(-1);
                // the largest molecule ID of every rank
                let mut hi = [hi as f64];
                state.max_ranks(&mut hi);
                ch.nchunk = (hi[0] as i64).max(1) as usize;
            }
            Style::Bins { .. } => {}
        }
        let binflag = matches!(self.style, Style::Bins { .. });
        let limit = |n: usize| if self.limit_exact { self.limit } else { n.min(self.limit) };
        if self.limit > 0 && !binflag {
            if !self.compress {
                ch.nchunk = limit(ch.nchunk);
            } else if self.limit_first {
                ch.nchunk = ch.nchunk.min(self.limit);
            }
        }
        if self.compress {
            // the IDs present on every rank, ascending
            let ids: Vec<f64> = (0..ichunk.len()).filter(|&i| !exclude[i]).map(|i| ichunk[i] as f64).collect();
            ch.hash = state.allgather_ranks(ids).into_iter().map(|id| (id as i64, 0)).collect();
            ch.nchunk = ch.hash.len();
            for (k, (orig, v)) in ch.hash.iter_mut().enumerate() {
                *v = k + 1;
                ch.chunk_id.push(*orig);
            }
            if self.limit > 0 && !binflag {
                ch.nchunk = limit(ch.nchunk);
            }
        }
        Ok(ch)
    }

    /// Raw chunk IDs of the owned atoms (LAMMPS' assign_chunk_ids) and which atoms are left out
    /// (not in the group or region; for bins, the discard rule).
    fn assign(&self, state: &State, ch: &Chunks) -> Result<(Vec<i64>, Vec<bool>), String> {
        let a = &state.atoms;
        let n = a.nlocal;
        let region = match &self.region {
            Some(r) => Some(state.regions.iter().find(|reg| &reg.id == r).ok_or_else(|| format!("region `{r}` for compute chunk/atom {} does not exist", self.id))?),
            None => None,
        };
        let mut exclude: Vec<bool> = (0..n).map(|i| a.mask[i] & self.groupbit == 0 || region.is_some_and(|r| !r.matches(a.x[i]))).collect();
        let mut ichunk = vec![0i64; n];
        match &self.style {
            Style::Type => (0..n).filter(|&i| !exclude[i]).for_each(|i| ichunk[i] = a.typ[i] as i64),
            Style::Molecule => (0..n).filter(|&i| !exclude[i]).for_each(|i| ichunk[i] = a.molecule[i] as i32 as i64),
            Style::Bins { ndim, dim, invdelta, .. } => {
                let dom = state.domain()?;
                let prd = dom.prd();
                if dom.triclinic() && !self.reduced {
                    return Err(format!("Compute chunk/atom {} for triclinic boxes requires units reduced", self.id));
                }
                for i in 0..n {
                    if exclude[i] {
                        continue;
                    }
                    let mut ibin = 0i64;
                    // LAMMPS' reduced coordinates: box fractions (x2lamda, tilts included)
                    let l = self.reduced.then(|| dom.x2lamda(a.x[i]));
                    for m in 0..*ndim {
                        let d = dim[m];
                        let (mut x, lo, hi, p) = match l {
                            Some(l) => (l[d], 0.0, 1.0, 1.0),
                            None => (a.x[i][d], dom.lo[d], dom.hi[d], prd[d]),
                        };
                        if dom.periodic(d) {
                            if x < lo {
                                x += p;
                            }
                            if x >= hi {
                                x -= p;
                            }
                        }
                        let mut b = ((x - ch.offset[m]) * invdelta[m]) as i32 as i64;
                        if x < ch.offset[m] {
                            b -= 1;
                        }
                        let top = ch.nlayers[m] as i64 - 1;
                        let clamp_lo = self.discard == Discard::No || (self.discard == Discard::Mixed && self.min[d].is_none());
                        let clamp_hi = self.discard == Discard::No || (self.discard == Discard::Mixed && self.max[d].is_none());
                        if clamp_lo {
                            b = b.max(0);
                        }
                        if clamp_hi {
                            b = b.min(top);
                        }
                        if b < 0 || b > top {
                            exclude[i] = true;
                            break;
                        }
                        ibin = ibin * ch.nlayers[m] as i64 + b;
                    }
                    if !exclude[i] {
                        ichunk[i] = ibin + 1;
                    }
                }
            }
        }
        Ok((ichunk, exclude))
    }

    /// Chunk IDs (1..=Nchunk, 0: none) of the owned atoms for `ch` (LAMMPS' compute_ichunk):
    /// kept ones with `ids once`.
    pub fn ichunk(&self, state: &State, ch: &Chunks) -> Result<Vec<usize>, String> {
        let a = &state.atoms;
        if let Some(map) = &self.stored {
            return Ok((0..a.nlocal).map(|i| map.get(&a.tag[i]).copied().unwrap_or(0)).collect());
        }
        let (raw, mut exclude) = self.assign(state, ch)?;
        let binflag = matches!(self.style, Style::Bins { .. });
        let n = ch.nchunk as i64;
        let mut out = vec![0usize; raw.len()];
        for i in 0..raw.len() {
            if exclude[i] {
                continue;
            }
            let id = if self.compress {
                match ch.hash.get(&raw[i]) {
                    Some(&k) => k as i64,
                    None if !binflag && self.discard == Discard::No => n,
                    None => 0,
                }
            } else if (raw[i] < 1 || raw[i] > n) && self.discard == Discard::No {
                n
            } else {
                raw[i]
            };
            // (a compressed ID beyond `limit` has no chunk either)
            if id < 1 || id > n {
                exclude[i] = true;
            } else {
                out[i] = id as usize;
            }
        }
        Ok(out)
    }
}

impl Compute for ComputeChunkAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "chunk/atom"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn setup(&mut self, w: &World) {
        // errors (no box yet) leave the chunks to be made when asked, which reports them
        if self.nchunk_once && self.fixed.is_none() {
            self.fixed = self.new_chunks(w.state).ok();
        }
        if self.ids == Ids::Once && self.stored.is_none() {
            if let Some(ch) = &self.fixed {
                if let Ok(ids) = self.ichunk(w.state, ch) {
                    self.stored = Some(w.state.values_by_id(|i| ids[i]));
                }
            }
        }
    }
    fn scalar(&self, w: &World) -> Result<f64, String> {
        Ok(self.setup_chunks(w.state)?.nchunk as f64)
    }
    fn peratom_cols(&self) -> Option<usize> {
        Some(1)
    }
    fn peratom(&self, w: &World) -> Result<PerAtom, String> {
        let ch = self.setup_chunks(w.state)?;
        Ok(PerAtom { cols: 1, data: self.ichunk(w.state, &ch)?.into_iter().map(|c| c as f64).collect() })
    }
    fn as_chunk(&self) -> Option<&ComputeChunkAtom> {
        Some(self)
    }
}
