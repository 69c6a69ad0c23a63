//! `compute ID group rdf Nbin [itype jtype ...] [cutoff Rc]`: radial distribution functions g(r)
//! and coordination numbers of type pairs, from the neighbour list, as LAMMPS' compute rdf: a
//! global array of Nbin rows, column 1 the bin centres, then g(r) and coord(r) per type-pair
//! set. Read it with `fix ave/time ... c_ID[*] mode vector`.

use super::Compute;
use crate::engine::neighbor::{special_level, NEIGH_MASK};
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "compute ID group rdf Nbin [itype jtype ...] [cutoff Rc]";

pub struct ComputeRdf {
    id: String,
    groupbit: u32,
    nbin: usize,
    /// Type ranges (ilo, ihi, jlo, jhi) of each histogram.
    pairs: Vec<(usize, usize, usize, usize)>,
    cutoff: Option<f64>,
}

impl ComputeRdf {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let nbin_word = a.peek().cloned();
        let nbin = a.usize_min("Nbin", 1)?;
        let ntypes = w.state.ntypes;
        let mut pairs = Vec::new();
        let mut cutoff = None;
        while let Some(k) = a.peek() {
            if k.text == "cutoff" {
                a.skip(1);
                let c = a.f64("cutoff Rc")?;
                cutoff = (c > 0.0).then_some(c);
                continue;
            }
            if a.len_remaining() < 2 || a.remaining()[1].text == "cutoff" {
                return Err(a.error_at(k, "compute rdf takes type pairs: itype jtype", "a type without its partner"));
            }
            let (ilo, ihi) = a.type_range("itype", ntypes)?;
            let (jlo, jhi) = a.type_range("jtype", ntypes)?;
            pairs.push((ilo, ihi, jlo, jhi));
        }
        if pairs.is_empty() {
            pairs.push((1, ntypes, 1, ntypes));
        }
        let rdf = ComputeRdf { id, groupbit, nbin, pairs, cutoff };
        // each evaluation holds a histogram per pair and the output array
        let doubles = nbin as f64 * (rdf.pairs.len() + rdf.cols()) as f64;
        crate::engine::memory::check_fits(doubles * 8.0, &format!("compute rdf: {nbin} bins x {} doubles", rdf.pairs.len() + rdf.cols()))
            .map_err(|m| a.error_at(nbin_word.as_ref().expect("Nbin was read"), m, "too many bins"))?;
        Ok(rdf)
    }

    fn cols(&self) -> usize {
        1 + 2 * self.pairs.len()
    }
}

impl Compute for ComputeRdf {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "rdf"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn array_cols(&self) -> Option<usize> {
        Some(self.cols())
    }
    fn array(&self, w: &World) -> Result<Vec<Vec<f64>>, String> {
        let s = w.state;
        super::need_lists(s, self)?;
        let nb = &s.neighbor;
        let skin = s.neigh_settings.skin;
        let cut = match self.cutoff {
            Some(c) => {
                if c + skin > nb.cutneighmax {
                    return Err(format!("compute rdf {}: the cutoff {c} plus the skin exceeds the ghost atom range {} (pair cutoff + skin)", self.id, nb.cutneighmax));
                }
                c
            }
            None if nb.cutforce > 0.0 => nb.cutforce,
            None => return Err(format!("compute rdf {} needs a pair style or a cutoff", self.id)),
        };
        let nbin = self.nbin;
        let delr = cut / nbin as f64;
        let delrinv = 1.0 / delr;
        let at = &s.atoms;
        let ntypes = s.ntypes;
        let npairs = self.pairs.len();
        // which histograms a type pair feeds (LAMMPS' rdfpair/nrdfpair)
        let mut feeds: Vec<Vec<usize>> = vec![Vec::new(); (ntypes + 1) * (ntypes + 1)];
        for (m, &(ilo, ihi, jlo, jhi)) in self.pairs.iter().enumerate() {
            for i in ilo..=ihi {
                for j in jlo..=jhi {
                    feeds[i * (ntypes + 1) + j].push(m);
                }
            }
        }
        // atoms of each type in the group, and the normalisation counts
        let mut counts = vec![0.0; ntypes + 1];
        for i in 0..at.nlocal {
            if at.mask[i] & self.groupbit != 0 {
                counts[at.typ[i]] += 1.0;
            }
        }
        // every rank's atoms (counts below 2^53 are exact as doubles)
        s.sum_ranks(&mut counts);
        let typecount: Vec<usize> = counts.iter().map(|&c| c as usize).collect();
        let (mut icount, mut jcount, mut dup) = (vec![0usize; npairs], vec![0usize; npairs], vec![0usize; npairs]);
        for (m, &(ilo, ihi, jlo, jhi)) in self.pairs.iter().enumerate() {
            icount[m] = (ilo..=ihi).map(|t| typecount[t]).sum();
            jcount[m] = (jlo..=jhi).map(|t| typecount[t]).sum();
            dup[m] = (ilo..=ihi).filter(|t| (jlo..=jhi).contains(t)).map(|t| typecount[t]).sum();
        }

        // a pair of owned atoms is listed once and counted from both ends; a pair with a ghost
        // is listed by each owned end (LAMMPS' newton off), so counted once per listing (on
        // several ranks, by each owner: the histograms are then summed over the ranks)
        let mut hist = vec![vec![0.0f64; nbin]; npairs];
        let (lj, coul) = (s.special_bonds.lj, s.special_bonds.coul);
        for chunk in &nb.list.chunks {
            for i in chunk.start..chunk.end {
                if at.mask[i] & self.groupbit == 0 {
                    continue;
                }
                let (xi, itype) = (at.x[i], at.typ[i]);
                for &e in chunk.neighbors(i) {
                    let level = special_level(e);
                    if lj[level] == 0.0 && coul[level] == 0.0 {
                        continue;
                    }
                    let j = (e & NEIGH_MASK) as usize;
                    if at.mask[j] & self.groupbit == 0 {
                        continue;
                    }
                    let jtype = at.typ[j];
                    let (fi, fj) = (&feeds[itype * (ntypes + 1) + jtype], &feeds[jtype * (ntypes + 1) + itype]);
                    if fi.is_empty() && fj.is_empty() {
                        continue;
                    }
                    let (dx, dy, dz) = (xi[0] - at.x[j][0], xi[1] - at.x[j][1], xi[2] - at.x[j][2]);
                    let r = (dx * dx + dy * dy + dz * dz).sqrt();
                    let ibin = (r * delrinv) as usize;
                    if ibin >= nbin {
                        continue;
                    }
                    for &m in fi {
                        hist[m][ibin] += 1.0;
                    }
                    if j < at.nlocal {
                        for &m in fj {
                            hist[m][ibin] += 1.0;
                        }
                    }
                }
            }
        }

        let mut flat: Vec<f64> = hist.concat();
        s.sum_ranks(&mut flat);
        let hist: Vec<&[f64]> = flat.chunks_exact(nbin).collect();

        let d = s.domain.as_ref().ok_or("no simulation box")?;
        let prd = d.prd();
        let three_d = s.dimension == 3;
        let constant = if three_d { 4.0 * std::f64::consts::PI / (3.0 * prd[0] * prd[1] * prd[2]) } else { std::f64::consts::PI / (prd[0] * prd[1]) };
        let mut out = vec![vec![0.0; self.cols()]; nbin];
        for (ibin, row) in out.iter_mut().enumerate() {
            row[0] = (ibin as f64 + 0.5) * delr;
        }
        for m in 0..npairs {
            let normfac = if icount[m] > 0 { jcount[m] as f64 - dup[m] as f64 / icount[m] as f64 } else { 0.0 };
            let mut ncoord = 0.0;
            for ibin in 0..nbin {
                let rlower = ibin as f64 * delr;
                let rupper = (ibin + 1) as f64 * delr;
                let vfrac = if three_d { constant * (rupper * rupper * rupper - rlower * rlower * rlower) } else { constant * (rupper * rupper - rlower * rlower) };
                let gr = if vfrac * normfac != 0.0 { hist[m][ibin] / (vfrac * normfac * icount[m] as f64) } else { 0.0 };
                if icount[m] != 0 {
                    ncoord += gr * vfrac * normfac;
                }
                out[ibin][1 + 2 * m] = gr;
                out[ibin][2 + 2 * m] = ncoord;
            }
        }
        Ok(out)
    }
}
