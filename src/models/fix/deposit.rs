//! `fix ID group deposit N type M seed keyword values ...`: insert one atom or one molecule every
//! M steps, N in all, into a region, as LAMMPS' fix deposit. Keywords: `region ID` (required),
//! `mol template-ID` (then `type` is an offset added to the template's types), `molfrac 1.0`,
//! `id max|next`, `global lo hi`, `local lo hi delta`, `near R`, `attempt Q`, `rate V`,
//! `vx lo hi`, `vy lo hi`, `vz lo hi`, `orient rx ry rz`, `units lattice|box`,
//! `gaussian xmid ymid zmid sigma`, `target tx ty tz`, `rigid fix-ID` (each molecule a body of
//! that rigid/small fix, made from the same template: LAMMPS' set_molecule). `shake`, `var`/`set`
//! and templates of several molecules are refused.
//!
//! Everything random comes from LAMMPS' Park-Miller stream (`seed`, 30 numbers discarded) in
//! LAMMPS' order of draws, so the inserted atoms are LAMMPS' own: per attempt a position in the
//! region's bounding box until one is inside the region (or a Gaussian one), a height above the
//! highest (nearby) atom for `global`/`local`, for a molecule a random axis and angle, then, if
//! no present atom is within `near` of any new one, the velocity. The `f_ID` scalar is the number
//! inserted.

use super::{Fix, FixCtx, FixDef, FixHooks};
use crate::engine::atoms::NewAtom;
use crate::engine::molecule::{Molecule, RigidInsert};
use crate::engine::quat::{axisangle_to_quat, norm3, quat_to_mat};
use crate::engine::random_park::RanPark;
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, DResult};

const SYNTAX: &str = "fix ID group deposit N type M seed region ID [mol template-ID] [molfrac 1.0] [id max|next] [global lo hi] [local lo hi delta] [near R] [attempt Q] [rate V] [vx lo hi] [vy lo hi] [vz lo hi] [orient rx ry rz] [units lattice|box] [gaussian xmid ymid zmid sigma] [target tx ty tz] [rigid fix-ID]";

/// Where a new particle's height comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Height {
    /// From the region.
    Region,
    /// `global lo hi`: lo..hi above the highest atom.
    Global { lo: f64, hi: f64 },
    /// `local lo hi delta`: lo..hi above the highest atom within `delta` laterally.
    Local { lo: f64, hi: f64, deltasq: f64 },
}

pub struct FixDeposit {
    id: String,
    groupbit: u32,
    ninsert: i64,
    ntype: usize,
    nfreq: i64,
    region: String,
    /// The region's bounding box.
    lo: [f64; 3],
    hi: [f64; 3],
    mol: Option<Molecule>,
    /// `rigid fix-ID`: the rigid fix that makes each inserted molecule a body.
    rigid: Option<String>,
    id_next: bool,
    height: Height,
    nearsq: f64,
    maxattempt: i64,
    rate: Option<f64>,
    vel: [(f64, f64); 3],
    orient: Option<[f64; 3]>,
    gaussian: Option<([f64; 3], f64)>,
    target: Option<[f64; 3]>,
    random: RanPark,
    nfirst: i64,
    next: Option<i64>,
    ninserted: i64,
    maxtag: i64,
    maxmol: i64,
    warned: bool,
}

impl FixDeposit {
    pub fn from_lammps(d: FixDef, state: &mut State) -> DResult<Self> {
        let cmd = d.cmd;
        let mut a = Args::from_words(d.args, cmd.span, SYNTAX);
        let ninsert = a.i64_in("number of insertions N", 0, i64::from(i32::MAX))?;
        let type_word = a.peek();
        let ntype = a.i64_in("atom type", 0, state.ntypes as i64)?;
        let nfreq = a.i64_in("insertion interval M", 1, i64::from(i32::MAX))?;
        let seed = a.i64_in("random seed (> 0)", 1, i64::from(i32::MAX))? as i32;
        let dimension = state.dimension;
        let mut region = None;
        let mut mol: Option<Molecule> = None;
        let mut id_next = false;
        let mut height = Height::Region;
        let mut near = 0.0;
        let mut maxattempt = 10;
        let mut rate = None;
        let mut vel = [(0.0, 0.0); 3];
        let mut orient = None;
        let mut lattice_units = true;
        let mut gaussian = None;
        let mut target = None;
        let mut rigid = None;
        const KEYWORDS: [&str; 17] = ["region", "mol", "molfrac", "id", "global", "local", "near", "attempt", "rate", "vx", "vy", "vz", "orient", "units", "gaussian", "target", "rigid"];
        while let Some(k) = a.peek() {
            a.skip(1);
            match k.text.as_str() {
                "region" => {
                    let w = a.word("region ID")?;
                    let r = state.regions.iter().find(|r| r.id == w.text).ok_or_else(|| a.error_at(w, format!("region ID `{}` for fix deposit does not exist", w.text), "unknown region"))?;
                    let Some(ext) = r.extent() else {
                        return Err(a.error_at(w, "fix deposit region does not support a bounding box (side out, or an infinite shape)", "no bounding box"));
                    };
                    if r.is_dynamic() {
                        return Err(a.error_at(w, "fix deposit region cannot be dynamic (move, rotate or a variable shape)", "dynamic region"));
                    }
                    region = Some((w, r.id.clone(), ext));
                }
                "mol" => {
                    let w = a.word("molecule template ID")?;
                    let m = state.molecules.iter().find(|m| m.id == w.text).ok_or_else(|| a.error_at(w, format!("molecule template ID `{}` for fix deposit does not exist", w.text), "unknown template"))?;
                    if m.typ.is_none() {
                        return Err(a.error_at(w, "fix deposit molecule must have atom types (a Types section)", "template without types"));
                    }
                    m.check_types(state).map_err(|e| a.error_at(w, e, "type out of range"))?;
                    mol = Some(m.clone());
                }
                "molfrac" => {
                    if mol.is_none() {
                        return Err(a.error_at(k, "fix deposit molfrac needs `mol` before it", "no molecule template yet"));
                    }
                    // one molecule per template: the one fraction must be 1
                    let f = a.f64("molecule fraction")?;
                    if (f - 1.0).abs() > 1e-6 {
                        return Err(a.error_at(a.last().unwrap(), "fix deposit molfrac: the fractions must add up to 1 (the template holds one molecule)", "must be 1.0"));
                    }
                }
                "id" => id_next = a.choice("id mode", &["max", "next"])? == 1,
                "global" => height = Height::Global { lo: a.f64("lo")?, hi: a.f64("hi")? },
                "local" => {
                    let (lo, hi) = (a.f64("lo")?, a.f64("hi")?);
                    let delta = a.f64("delta")?;
                    height = Height::Local { lo, hi, deltasq: delta * delta };
                }
                "near" => near = a.f64("near distance")?,
                "attempt" => maxattempt = a.i64("number of attempts")?,
                "rate" => rate = Some(a.f64("rate")?),
                "vx" => vel[0] = (a.f64("vxlo")?, a.f64("vxhi")?),
                "vy" => vel[1] = (a.f64("vylo")?, a.f64("vyhi")?),
                "vz" => vel[2] = (a.f64("vzlo")?, a.f64("vzhi")?),
                "orient" => {
                    let r = [a.f64("rx")?, a.f64("ry")?, a.f64("rz")?];
                    if (dimension == 2 && (r[0] != 0.0 || r[1] != 0.0)) || r == [0.0; 3] {
                        return Err(a.error_at(a.last().unwrap(), "illegal fix deposit orient settings (a nonzero axis; along z in 2d)", "invalid axis"));
                    }
                    orient = Some(r);
                }
                "units" => lattice_units = a.choice("units", &["lattice", "box"])? == 0,
                "gaussian" => {
                    let c = [a.f64("xmid")?, a.f64("ymid")?, a.f64("zmid")?];
                    gaussian = Some((c, a.f64("sigma")?));
                }
                "target" => target = Some([a.f64("tx")?, a.f64("ty")?, a.f64("tz")?]),
                "rigid" => rigid = Some(a.word("rigid fix ID")?),
                "shake" | "var" | "set" => {
                    return Err(a.error_at(k, format!("fix deposit `{}` is not supported", k.text), "not supported"));
                }
                _ => return Err(a.unknown_keyword(k, &KEYWORDS)),
            }
        }
        if let (Some(w), None) = (rigid, &mol) {
            return Err(a.error_at(w, "cannot use fix deposit rigid and not molecule", "needs `mol TEMPLATE`"));
        }
        if let Some(m) = &mol {
            let maxt = m.max_type() as i64;
            if ntype + maxt <= 0 || ntype + maxt > state.ntypes as i64 {
                return Err(a.error_at(type_word.unwrap(), format!("invalid atom type in fix deposit mol: the offset {ntype} plus the template's largest type {maxt} is outside 1..{}", state.ntypes), "type out of range"));
            }
        } else if ntype < 1 {
            return Err(a.error_at(type_word.unwrap(), format!("invalid atom type {ntype} in fix deposit command"), "expected 1 or more"));
        }
        let Some((rword, region, (lo, hi))) = region else { return Err(a.missing("region ID (fix deposit needs `region ID`)")) };
        let domain = state.domain.as_ref().ok_or_else(|| a.error_at(&cmd.name, "fix deposit needs a simulation box", "no box yet"))?;
        if (0..3).any(|k| lo[k] < domain.lo[k] || hi[k] > domain.hi[k]) {
            return Err(a.error_at(rword, "deposition region extends outside simulation box", "outside the box"));
        }
        // lengths and velocities in lattice spacings unless `units box`, as LAMMPS scales them
        let scale = match (&state.lattice, lattice_units) {
            (Some(l), true) => [l.xlattice, l.ylattice, l.zlattice],
            _ => [1.0; 3],
        };
        let up = if dimension == 2 { scale[1] } else { scale[2] };
        height = match height {
            Height::Region => Height::Region,
            Height::Global { lo, hi } => Height::Global { lo: lo * up, hi: hi * up },
            Height::Local { lo, hi, deltasq } => Height::Local { lo: lo * up, hi: hi * up, deltasq: deltasq * (scale[0] * scale[0]) },
        };
        let rate = rate.map(|r| r * up);
        let nearsq = near * near * (scale[0] * scale[0]);
        for k in 0..3 {
            vel[k] = (vel[k].0 * scale[k], vel[k].1 * scale[k]);
        }
        let gaussian = gaussian.map(|(c, s)| ([c[0] * scale[0], c[1] * scale[1], c[2] * scale[2]], s * scale[0]));
        let target = target.map(|t| [t[0] * scale[0], t[1] * scale[1], t[2] * scale[2]]);
        let mut random = RanPark::new(seed);
        // LAMMPS discards the first 30 numbers (nearby seeds would give correlated first positions)
        for _ in 0..30 {
            random.uniform();
        }
        let (maxtag, maxmol) = if id_next { max_ids(state, mol.is_some()) } else { (0, 0) };
        let next = state.step + 1;
        Ok(FixDeposit {
            id: d.id,
            groupbit: d.groupbit,
            ninsert,
            ntype: ntype as usize,
            nfreq,
            region,
            lo,
            hi,
            mol,
            rigid: rigid.map(|w| w.text.clone()),
            id_next,
            height,
            nearsq,
            maxattempt,
            rate,
            vel,
            orient,
            gaussian,
            target,
            random,
            nfirst: next - nfreq,
            next: (ninsert > 0).then_some(next),
            ninserted: 0,
            maxtag,
            maxmol,
            warned: false,
        })
    }

    /// A position in the region: uniform in its bounding box, or Gaussian, until inside.
    fn position(&mut self, state: &State) -> Result<[f64; 3], String> {
        let r = state.regions.iter().find(|r| r.id == self.region).ok_or_else(|| format!("region ID {} for fix deposit does not exist", self.region))?;
        loop {
            let c = match self.gaussian {
                None => {
                    let x = self.lo[0] + self.random.uniform() * (self.hi[0] - self.lo[0]);
                    let y = self.lo[1] + self.random.uniform() * (self.hi[1] - self.lo[1]);
                    let z = self.lo[2] + self.random.uniform() * (self.hi[2] - self.lo[2]);
                    [x, y, z]
                }
                Some((mid, sigma)) => {
                    let x = mid[0] + self.random.gaussian() * sigma;
                    let y = mid[1] + self.random.gaussian() * sigma;
                    let z = mid[2] + self.random.gaussian() * sigma;
                    [x, y, z]
                }
            };
            if r.matches(c) {
                return Ok(c);
            }
        }
    }
}

/// The largest atom ID, and the largest molecule ID when molecules are inserted.
fn max_ids(state: &State, molecules: bool) -> (i64, i64) {
    let (maxtag, maxmol) = state.max_ids();
    (maxtag, if molecules { maxmol } else { 0 })
}

impl Fix for FixDeposit {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "deposit"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { pre_exchange: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, ctx: &FixCtx) -> Result<(), String> {
        if !state.regions.iter().any(|r| r.id == self.region) {
            return Err(format!("region ID {} for fix deposit does not exist", self.region));
        }
        if let (Some(id), Some(m)) = (&self.rigid, &self.mol) {
            super::check_rigid_insert(ctx, "deposit", id, &m.id)?;
        }
        Ok(())
    }
    /// LAMMPS `setup_pre_exchange`: the next insertion step on the fix's own schedule.
    /// Also LAMMPS' warning (from its `init`) when `near` is below the separation of finite-size
    /// particles, present or inserted.
    fn setup(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        if state.atoms.features.sphere {
            let a = &state.atoms;
            let maxrad = a.radius[..a.nlocal].iter().copied().fold(0.0, f64::max);
            let insert = match &self.mol {
                Some(m) => m.radius.as_ref().map(|r| r.iter().copied().fold(0.0, f64::max)).unwrap_or(0.5),
                None => 0.5,
            };
            let separation = (2.0 * insert).max(maxrad + insert);
            if self.nearsq.sqrt() < separation {
                state.messages.push(format!("WARNING: Fix deposit near setting < possible overlap separation {separation}"));
            }
        }
        self.next = (self.ninserted < self.ninsert).then(|| self.nfirst + (state.step - self.nfirst) / self.nfreq * self.nfreq + self.nfreq);
        Ok(())
    }
    fn next_reneighbor(&self) -> Option<i64> {
        self.next
    }
    /// LAMMPS `extract("radius")`: 0.5 for the inserted type (one atom), else the largest
    /// radius of the template's atoms of that type (0.5 without Diameters), so that granular
    /// cutoffs, and with them the neighbour cutoff and LAMMPS' sort bins, cover molecules that
    /// do not exist yet.
    fn insert_radius(&self, itype: usize) -> f64 {
        let Some(m) = &self.mol else { return if itype == self.ntype { 0.5 } else { 0.0 } };
        let Some(types) = &m.typ else { return 0.0 };
        types
            .iter()
            .enumerate()
            .filter(|&(_, &t)| t + self.ntype == itype)
            .map(|(k, _)| m.radius.as_ref().map_or(0.5, |r| r[k]))
            .fold(0.0, f64::max)
    }
    fn scalar(&self, _state: &State) -> Option<f64> {
        Some(self.ninserted as f64)
    }
    fn pre_exchange(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        if self.next != Some(state.step) {
            return Ok(());
        }
        let step = state.step;
        let err = |m: String| RunError::new(step, m);
        let Some(domain) = state.domain.clone() else { return Ok(()) };
        state.atoms.clear_ghosts();
        let offset = self.rate.map(|r| (state.step - self.nfirst) as f64 * state.dt * r).unwrap_or(0.0);
        if !self.id_next {
            (self.maxtag, self.maxmol) = max_ids(state, self.mol.is_some());
        }
        let dimension = state.dimension;
        let vertical = dimension - 1;
        let mut inserted = None;
        let mut attempt = 0;
        while attempt < self.maxattempt {
            attempt += 1;
            let mut coord = self.position(state).map_err(err)?;
            coord[vertical] += offset;
            if let Height::Global { lo, hi } | Height::Local { lo, hi, .. } = self.height {
                let a = &state.atoms;
                let mut max = domain.lo[vertical];
                for i in 0..a.nlocal {
                    if let Height::Local { deltasq, .. } = self.height {
                        let mut del = [coord[0] - a.x[i][0], coord[1] - a.x[i][1], 0.0];
                        domain.minimum_image(&mut del);
                        let rsq = if dimension == 2 { del[0] * del[0] } else { del[0] * del[0] + del[1] * del[1] };
                        if rsq > deltasq {
                            continue;
                        }
                    }
                    if a.x[i][vertical] > max {
                        max = a.x[i][vertical];
                    }
                }
                // the highest atom of every rank (all ranks draw the same coordinates)
                let mut top = [max];
                state.max_ranks(&mut top);
                coord[vertical] = top[0] + lo + self.random.uniform() * (hi - lo);
            }
            // the new atoms: one, or the molecule turned about its centre and wrapped
            let mut quat = [1.0, 0.0, 0.0, 0.0];
            let placed: Vec<([f64; 3], [i32; 3])> = match &self.mol {
                None => vec![(coord, [0; 3])],
                Some(m) => {
                    // one molecule per template: LAMMPS' molfrac draw picks it
                    self.random.uniform();
                    let mut r = match self.orient {
                        _ if dimension == 2 => [0.0, 0.0, 1.0],
                        Some(r) => r,
                        None => [self.random.uniform() - 0.5, self.random.uniform() - 0.5, self.random.uniform() - 0.5],
                    };
                    let theta = self.random.uniform() * std::f64::consts::TAU;
                    norm3(&mut r);
                    quat = axisangle_to_quat(&r, theta);
                    m.place(&quat_to_mat(&quat), coord, &domain)
                }
            };
            let a = &state.atoms;
            let crowded = placed.iter().any(|(p, _)| {
                (0..a.nlocal).any(|i| {
                    let mut del = [p[0] - a.x[i][0], p[1] - a.x[i][1], p[2] - a.x[i][2]];
                    domain.minimum_image(&mut del);
                    del[0] * del[0] + del[1] * del[1] + del[2] * del[2] < self.nearsq
                })
            });
            if state.any_ranks(crowded) {
                continue;
            }
            let mut v = [0.0; 3];
            for k in 0..3 {
                v[k] = self.vel[k].0 + self.random.uniform() * (self.vel[k].1 - self.vel[k].0);
            }
            if let Some(t) = self.target {
                let speed = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                let del = [t[0] - coord[0], t[1] - coord[1], t[2] - coord[2]];
                let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
                if rsq > 0.0 {
                    let rinv = (1.0 / rsq).sqrt();
                    v = [del[0] * rinv * speed, del[1] * rinv * speed, del[2] * rinv * speed];
                }
            }
            let keep: Vec<bool> = placed.iter().map(|(x, _)| domain.takes_inserted(*x)).collect();
            let first = state.atoms.nlocal;
            match &self.mol {
                None => {
                    if keep[0] && state.owns_point(&coord) {
                        let mut atom = NewAtom::at(self.maxtag + 1, self.ntype, coord);
                        atom.v = v;
                        state.atoms.push(&atom);
                    }
                }
                Some(m) => {
                    if keep.iter().any(|&k| !k) {
                        return Err(err(format!("fix deposit: molecule atom outside the box (at step {step}); dmhs inserts whole molecules only")));
                    }
                    // on ranks the owner of the centre takes the whole molecule; the rebuild that
                    // follows sends its atoms on to their own sub-domains
                    if state.owns_point(&coord) {
                        m.push_copy(state, &placed, self.maxtag, self.maxmol, self.ntype, v);
                    } else {
                        m.push_topology(state, self.maxtag);
                    }
                    if m.has_topology() {
                        state.special_dirty = true;
                    }
                    if let Some(fix_id) = &self.rigid {
                        state.rigid_inserts.push(RigidInsert { fix_id: fix_id.clone(), tagprev: self.maxtag, mol: self.maxmol + m.nmolecules(), xgeom: coord, vcm: v, quat });
                    }
                }
            }
            for i in first..state.atoms.nlocal {
                state.atoms.mask[i] = 1 | self.groupbit;
            }
            inserted = Some(placed.len() as i64);
            break;
        }
        match inserted {
            Some(n) => {
                self.ninserted += 1;
                self.maxtag += n;
                if let Some(m) = &self.mol {
                    self.maxmol += m.nmolecules();
                }
                state.lists_valid = false;
            }
            None if !self.warned => {
                state.messages.push("WARNING: One or more particle depositions were unsuccessful".into());
                self.warned = true;
            }
            None => {}
        }
        self.next = (self.ninserted < self.ninsert).then_some(state.step + self.nfreq);
        Ok(())
    }
    fn describe(&self) -> String {
        let what = match &self.mol {
            Some(m) => format!("molecule {}", m.id),
            None => format!("atom of type {}", self.ntype),
        };
        format!("fix {} deposit: {} insertions of one {what}, every {} steps, in region {}", self.id, self.ninsert, self.nfreq, self.region)
    }
}
