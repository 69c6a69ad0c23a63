//! `compute ID group centro/atom fcc|bcc|N [axes no]`: the centro-symmetry parameter of each
//! atom of the group, as LAMMPS' compute centro/atom (Kelchner, Plimpton, Hamilton 1998): of the
//! atom's N nearest neighbours within the pair cutoff (N = 12 for fcc, 8 for bcc), the sum of
//! the N/2 smallest |R_j + R_k|^2 over the pairs j, k of them (R the vectors from the atom).
//! 0 outside the group and for an atom with fewer than N neighbours. Neighbours come from the
//! pair style's list (LAMMPS' occasional full list holds the same pairs: special pairs of weight
//! 0 left out); the smallest values are summed in increasing order, LAMMPS in the order its
//! selection leaves them, so the two differ by round-off. `axes yes` is refused.

use super::{Compute, PerAtom};
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult};

const SYNTAX: &str = "compute ID group centro/atom fcc|bcc|N [axes no]";

pub struct ComputeCentroAtom {
    id: String,
    groupbit: u32,
    /// Nearest neighbours considered (even).
    nnn: usize,
}

impl ComputeCentroAtom {
    pub fn from_lammps(id: String, groupbit: u32, args: &[dmhs_parser::Word], cmd: &Command) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let w = a.word("lattice (fcc, bcc or a neighbour count)")?;
        let nnn = match w.text.as_str() {
            "fcc" => 12,
            "bcc" => 8,
            t => match t.parse::<i64>() {
                Ok(n) if n > 0 && n % 2 == 0 => n as usize,
                Ok(_) => return Err(a.error_at(w, "Illegal neighbor value for compute centro/atom command", "a positive even count")),
                Err(_) => return Err(a.error_at(w, format!("Illegal compute centro/atom lattice {t}"), "fcc, bcc or an even count")),
            },
        };
        while let Some(k) = a.peek() {
            a.skip(1);
            match k.text.as_str() {
                "axes" => {
                    if a.yes_no("axes")? {
                        return Err(a.error_at(k, "compute centro/atom axes yes is not supported by dmhs", "axes no"));
                    }
                }
                _ => return Err(a.unknown_keyword(k, &["axes"])),
            }
        }
        Ok(ComputeCentroAtom { id, groupbit, nnn })
    }
}

impl Compute for ComputeCentroAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "centro/atom"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn peratom_cols(&self) -> Option<usize> {
        Some(1)
    }
    fn peratom(&self, w: &World) -> Result<PerAtom, String> {
        let s = w.state;
        if s.neighbor.cutforce <= 0.0 {
            return Err(format!("compute centro/atom {} requires a pair style be defined", self.id));
        }
        super::need_lists(s, self)?;
        let at = &s.atoms;
        let cutsq = s.neighbor.cutforce * s.neighbor.cutforce;
        // every neighbour within the cutoff of each group atom: (rsq, atom)
        let mut near: Vec<Vec<(f64, usize)>> = vec![Vec::new(); at.nlocal];
        super::group_pairs(s, self.groupbit, u32::MAX, |i, j, rsq, count_i, count_j, _| {
            if rsq < cutsq {
                if count_i {
                    near[i].push((rsq, j));
                }
                if count_j {
                    near[j].push((rsq, i));
                }
            }
        });
        let (nnn, nhalf) = (self.nnn, self.nnn / 2);
        let mut pairs = Vec::with_capacity(nnn * (nnn - 1) / 2);
        let data = near
            .iter_mut()
            .enumerate()
            .map(|(i, list)| {
                if at.mask[i] & self.groupbit == 0 || list.len() < nnn {
                    return 0.0;
                }
                list.select_nth_unstable_by(nnn - 1, |p, q| p.0.total_cmp(&q.0));
                let xi = at.x[i];
                pairs.clear();
                for (k, &(_, j)) in list[..nnn].iter().enumerate() {
                    for &(_, l) in &list[k + 1..nnn] {
                        let d: [f64; 3] = std::array::from_fn(|c| at.x[j][c] + at.x[l][c] - 2.0 * xi[c]);
                        pairs.push(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                    }
                }
                pairs.sort_unstable_by(f64::total_cmp);
                pairs[..nhalf].iter().sum()
            })
            .collect();
        Ok(PerAtom { cols: 1, data })
    }
}
