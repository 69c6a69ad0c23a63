//! `fix ID group pour N type seed keyword values ...`: insert N granular particles over the
//! run into a block or z-cylinder region, a batch every `nfreq` steps, as LAMMPS' fix pour.
//! Keywords: `region ID` (required), `diam one D | range Dlo Dhi | poly N D1 P1 ...`,
//! `dens lo hi`, `vol fraction Nattempt`, `rate v`, `vel vxlo vxhi vylo vyhi vz` (2D: `vxlo
//! vxhi vy`), `id max|next`, `ignore`, `mol TEMPLATE` (copies of a molecule template, types
//! offset by `type`, turned at random about z in 2D, about a random axis in 3D, LAMMPS' draws),
//! `molfrac 1` and `rigid FIXID` (each copy a body of that fix rigid/small, made from the
//! template: LAMMPS' set_molecule). `shake` and templates of several molecules are refused.
//!
//! Positions, radii, densities and velocities come from LAMMPS' Park-Miller stream in LAMMPS'
//! order of draws, so the inserted particles are LAMMPS' own: after 30 discarded numbers, per
//! particle a height (biased
//! so that insertion is uniform in time), a radius, trial positions until one overlaps nothing
//! inserted or present, the lateral velocities and the density. The vertical velocity is the
//! one the particle would have reached falling from the top of the region.
//!
//! nfreq is the time to fall through the region: solve zhi + vz t + g t^2/2 = zlo + rate t.
//! The number per batch fills `fraction` of the region volume with the largest particle
//! (a region thinner than 1 in y counts as 1 thick in 3D, for quasi-2D decks).

use super::{Fix, FixCtx, FixDef, FixHooks};
use crate::engine::atoms::NewAtom;
use crate::engine::molecule::RigidInsert;
use crate::engine::quat::{axisangle_to_quat, norm3, quat_to_mat};
use crate::engine::random_park::RanPark;
use crate::engine::region::Simple;
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, DResult};
use std::f64::consts::PI;

const SYNTAX: &str = "fix ID group pour N type seed region ID [mol TEMPLATE [molfrac 1] [rigid FIXID]] [diam one D | diam range Dlo Dhi | diam poly N D1 P1 ...] [dens lo hi] [vol fraction Nattempt] [rate v] [vel vxlo vxhi vylo vyhi vz (2D: vxlo vxhi vy)] [id max|next] [ignore]";

/// How LAMMPS tells the gravity direction is the insertion axis (-z in 3D, -y in 2D).
const EPSILON: f64 = 0.001;

/// Particle sizes to draw from.
#[derive(Clone, Debug, PartialEq)]
enum Diameters {
    One(f64),
    /// Radii uniform in lo..hi.
    Range(f64, f64),
    /// (radius, fraction) pairs.
    Poly(Vec<(f64, f64)>),
}

impl Diameters {
    fn max_radius(&self) -> f64 {
        match self {
            Diameters::One(r) => *r,
            Diameters::Range(_, hi) => *hi,
            Diameters::Poly(p) => p.iter().map(|&(r, _)| r).fold(0.0, f64::max),
        }
    }
    /// LAMMPS `radius_sample`: no draw for one size, one draw otherwise.
    fn sample(&self, random: &mut RanPark) -> f64 {
        match self {
            Diameters::One(r) => *r,
            Diameters::Range(lo, hi) => lo + random.uniform() * (hi - lo),
            Diameters::Poly(p) => {
                let value = random.uniform();
                let (mut i, mut sum) = (0, 0.0);
                while sum < value && i < p.len() {
                    sum += p[i].1;
                    i += 1;
                }
                p[i.max(1) - 1].0
            }
        }
    }
}

/// The insertion region: a block, or a cylinder along z.
#[derive(Clone, Copy, Debug)]
enum Volume {
    Block { lo: [f64; 3], hi: [f64; 3] },
    Cylinder { xc: f64, yc: f64, rc: f64, zlo: f64, zhi: f64 },
}

pub struct FixPour {
    id: String,
    groupbit: u32,
    ninsert: i64,
    ntype: usize,
    volume: Volume,
    diam: Diameters,
    radius_max: f64,
    density: (f64, f64),
    maxattempt: i64,
    rate: f64,
    /// vxlo, vxhi, vylo, vyhi, and the vertical speed (vz in 3D, vy in 2D).
    vel: [f64; 5],
    /// IDs continue from the largest ID at creation (`id next`) instead of at each insertion.
    id_next: bool,
    random: RanPark,
    /// -g (negative), the acceleration along the insertion axis when the fix was made.
    grav: f64,
    /// Time to fall through the region (LAMMPS' t at init).
    fall_time: f64,
    /// Steps between batches, set at init from the run's timestep (0 before the first run).
    nfreq: i64,
    nper: i64,
    nfirst: i64,
    next: Option<i64>,
    /// The insertion line was printed (LAMMPS prints it at the first init only).
    announced: bool,
    ninserted: i64,
    maxtag: i64,
    dimension: usize,
    /// `mol`: the template inserted, and the rigid fix that makes each copy a body.
    mol: Option<(crate::engine::molecule::Molecule, Option<String>)>,
    maxmol: i64,
}

impl FixPour {
    pub fn from_lammps(d: FixDef, state: &mut State) -> DResult<Self> {
        let cmd = d.cmd;
        let mut a = Args::from_words(d.args, cmd.span, SYNTAX);
        if !state.atoms.features.sphere {
            return Err(a.error_at(&cmd.name, "fix pour requires atom attributes radius and rmass (atom_style sphere)", "no sphere attributes"));
        }
        let ninsert = a.i64_in("number of particles to insert N", 0, i64::from(i32::MAX))?;
        // 0 is allowed with `mol` (an offset added to the template's types)
        let type_word = a.peek().cloned();
        let ntype = a.i64_in("atom type", 0, state.ntypes as i64)? as usize;
        let seed = a.i64_in("random seed (> 0)", 1, i64::from(i32::MAX))? as i32;
        let dimension = state.dimension;
        let mut region = None;
        let mut diam = Diameters::One(0.5);
        let (mut density, mut volfrac, mut maxattempt, mut rate) = ((1.0, 1.0), 0.25, 50, 0.0);
        let mut vel = [0.0; 5];
        let mut id_next = false;
        let mut mol: Option<(crate::engine::molecule::Molecule, Option<String>)> = None;
        let mut rigid = None;
        while let Some(k) = a.peek() {
            a.skip(1);
            match k.text.as_str() {
                "region" => {
                    let w = a.word("region ID")?;
                    let r = state.regions.iter().find(|r| r.id == w.text).ok_or_else(|| a.error_at(w, format!("fix pour region `{}` does not exist", w.text), "unknown region"))?;
                    if r.is_dynamic() {
                        return Err(a.error_at(w, "fix pour region cannot be dynamic (move, rotate or a variable shape)", "dynamic region"));
                    }
                    region = Some((w, r.simple()));
                }
                "diam" => {
                    diam = match a.choice("diameter style", &["one", "range", "poly"])? {
                        0 => Diameters::One(0.5 * a.positive_f64("diameter")?),
                        1 => {
                            let (lo, hi) = (0.5 * a.positive_f64("lowest diameter")?, 0.5 * a.positive_f64("highest diameter")?);
                            if lo > hi {
                                return Err(a.error_at(a.last().unwrap(), "fix pour diam range: the lowest diameter is above the highest", "below the lowest"));
                            }
                            Diameters::Range(lo, hi)
                        }
                        _ => {
                            let n = a.usize_min("number of diameters", 1)?;
                            let mut p = Vec::with_capacity(n.min(1024));
                            for _ in 0..n {
                                let r = 0.5 * a.positive_f64("diameter")?;
                                let f = a.non_negative_f64("fraction")?;
                                p.push((r, f));
                            }
                            let sum: f64 = p.iter().map(|&(_, f)| f).sum();
                            if (sum - 1.0).abs() > 1e-10 {
                                return Err(a.error_at(a.last().unwrap(), format!("fix pour polydisperse fractions sum to {sum}, not 1"), "fractions must sum to 1"));
                            }
                            Diameters::Poly(p)
                        }
                    }
                }
                "dens" => {
                    density = (a.f64("lowest density")?, a.f64("highest density")?);
                    if density.0 > density.1 {
                        return Err(a.error_at(a.last().unwrap(), "fix pour dens: the lowest density is above the highest", "below the lowest"));
                    }
                }
                "vol" => {
                    volfrac = a.positive_f64("volume fraction")?;
                    maxattempt = a.i64_in("insertion attempts per particle", 0, i64::from(i32::MAX))?;
                }
                "rate" => rate = a.f64("rate")?,
                "vel" => {
                    if dimension == 3 {
                        vel = [a.f64("vxlo")?, a.f64("vxhi")?, a.f64("vylo")?, a.f64("vyhi")?, a.f64("vz")?];
                    } else {
                        let (lo, hi) = (a.f64("vxlo")?, a.f64("vxhi")?);
                        vel = [lo, hi, 0.0, 0.0, a.f64("vy")?];
                    }
                    if vel[0] > vel[1] || vel[2] > vel[3] {
                        return Err(a.error_at(a.last().unwrap(), "fix pour vel: a lower velocity bound is above its upper bound", "bounds out of order"));
                    }
                }
                "id" => id_next = a.choice("id mode", &["max", "next"])? == 1,
                // lines and triangles, which `ignore` skips in the overlap test, do not exist in dmhs
                "ignore" => {}
                "mol" => {
                    let w = a.word("molecule template ID")?;
                    let m = state.molecules.iter().find(|m| m.id == w.text).ok_or_else(|| a.error_at(w, format!("molecule template `{}` for fix pour does not exist", w.text), "unknown template"))?;
                    if m.typ.is_none() {
                        return Err(a.error_at(w, "fix pour molecule must have atom types", "no Types section"));
                    }
                    if ntype + m.max_type() > state.ntypes {
                        return Err(a.error_at(w, format!("fix pour mol: type {} + the template's types exceed the {} atom types", ntype, state.ntypes), "invalid atom type"));
                    }
                    if m.has_topology() {
                        return Err(a.error_at(w, "fix pour of molecules with bonds, angles or dihedrals is not supported", "not supported"));
                    }
                    mol = Some((m.clone().with_radius(), None));
                }
                "molfrac" => {
                    if mol.is_none() {
                        return Err(a.error_at(k, "fix pour molfrac needs `mol TEMPLATE` before it", "no template"));
                    }
                    let f = a.f64("molecule fraction")?;
                    if (f - 1.0).abs() > 1e-6 {
                        return Err(a.error_at(a.last().unwrap(), "fix pour molfrac of a one-molecule template must be 1", "fractions must sum to 1"));
                    }
                }
                "rigid" => rigid = Some(a.word("rigid fix ID")?),
                "shake" => {
                    return Err(a.error_at(k, "fix pour `shake` is not supported", "not supported"));
                }
                _ => return Err(a.unknown_keyword(k, &["region", "diam", "dens", "vol", "rate", "vel", "id", "ignore", "mol", "molfrac", "rigid"])),
            }
        }
        if ntype == 0 && mol.is_none() {
            let w = type_word.unwrap();
            return Err(a.error_at(&w, "fix pour atom type 0 needs `mol TEMPLATE` (an offset of the template's types)", "expected a type from 1"));
        }
        if let Some(w) = rigid {
            let Some((_, r)) = mol.as_mut() else { return Err(a.error_at(w, "fix pour rigid needs `mol TEMPLATE`", "not molecule insertion")) };
            let f = d.fixes.iter().find(|f| f.id() == w.text).ok_or_else(|| a.error_at(w, format!("fix pour rigid fix `{}` does not exist", w.text), "unknown fix"))?;
            if f.rigid_template().is_none() {
                return Err(a.error_at(w, format!("fix pour rigid: fix `{}` is {}, not rigid/small", w.text, f.style()), "not rigid/small"));
            }
            *r = Some(w.text.clone());
        }
        let Some((rword, shape)) = region else { return Err(a.missing("region ID (fix pour needs `region ID`)")) };
        let domain = state.domain.as_ref().ok_or_else(|| a.error_at(&cmd.name, "fix pour needs a simulation box", "no box yet"))?;
        let (blo, bhi) = (domain.lo, domain.hi);
        let volume = match shape {
            Some(Simple::Block { lo, hi }) => {
                if (0..3).any(|k| lo[k] < blo[k] || hi[k] > bhi[k]) {
                    return Err(a.error_at(rword, "fix pour: the insertion region extends outside the simulation box", "outside the box"));
                }
                Volume::Block { lo, hi }
            }
            Some(Simple::Cylinder { axis, center, radius, lo, hi }) => {
                if axis != 2 {
                    return Err(a.error_at(rword, "fix pour needs a z-axis cylinder region", "not along z"));
                }
                if dimension == 2 {
                    return Err(a.error_at(rword, "fix pour needs a block region in 2D", "a cylinder"));
                }
                let (xc, yc) = (center[0], center[1]);
                if xc - radius < blo[0] || xc + radius > bhi[0] || yc - radius < blo[1] || yc + radius > bhi[1] || lo < blo[2] || hi > bhi[2] {
                    return Err(a.error_at(rword, "fix pour: the insertion region extends outside the simulation box", "outside the box"));
                }
                Volume::Cylinder { xc, yc, rc: radius, zlo: lo, zhi: hi }
            }
            None => return Err(a.error_at(rword, "fix pour needs a block or cylinder region (side in, not open)", "not a block or cylinder")),
        };
        let gravity = d.fixes.iter().find_map(|f| f.gravity()).ok_or_else(|| a.error_at(&cmd.name, "fix pour needs a fix gravity defined before it", "no fix gravity"))?;
        let magnitude = gravity.magnitude.ok_or_else(|| a.error_at(&cmd.name, "fix pour needs a fix gravity of constant magnitude (not a variable)", "variable gravity"))?;
        check_direction(gravity.dir, dimension).map_err(|m| a.error_at(&cmd.name, m, "gravity direction"))?;
        let grav = -magnitude * state.units.ftm2v;

        // with molecules the particle is the template's bounding circle or sphere
        let radius_max = match &mol {
            Some((m, _)) => m.molradius,
            None => diam.max_radius(),
        };
        let (v_rel, delta) = match volume {
            Volume::Block { lo, hi } if dimension == 2 => (vel[4] - rate, hi[1] - lo[1]),
            Volume::Block { lo, hi } => (vel[4] - rate, hi[2] - lo[2]),
            Volume::Cylinder { zlo, zhi, .. } => (vel[4] - rate, zhi - zlo),
        };
        // the fall time; nfreq follows from it at init, with the timestep of the run (LAMMPS
        // computes it there, so a `timestep` after the fix counts)
        let fall_time = (-v_rel - (v_rel * v_rel - 2.0 * grav * delta).sqrt()) / grav;
        let region_volume = match volume {
            Volume::Block { lo, hi } if dimension == 3 => (hi[0] - lo[0]) * (hi[1] - lo[1]).max(1.0) * (hi[2] - lo[2]),
            Volume::Block { lo, hi } => (hi[0] - lo[0]) * (hi[1] - lo[1]),
            Volume::Cylinder { rc, zlo, zhi, .. } => PI * rc * rc * (zhi - zlo),
        };
        let one = |r: f64| if dimension == 3 { 4.0 / 3.0 * PI * r * r * r } else { PI * r * r };
        let volume_one = match &diam {
            Diameters::Poly(p) if mol.is_none() => p.iter().map(|&(r, f)| one(r) * f).sum(),
            _ => one(radius_max),
        };
        let nper = (volfrac * region_volume / volume_one) as i32 as i64;
        if nper <= 0 {
            return Err(a.error_at(&cmd.name, "fix pour inserts 0 particles per batch: raise the volume fraction or the region, or lower the diameter", "insertion count 0"));
        }
        let nfirst = state.step + 1;
        let maxtag = if id_next { state.atoms.max_tag() } else { 0 };
        let maxmol = if id_next { state.atoms.max_molecule() } else { 0 };
        // LAMMPS discards the first 30 numbers (nearby seeds would give correlated first positions)
        let mut random = RanPark::new(seed);
        for _ in 0..30 {
            random.uniform();
        }
        Ok(FixPour {
            id: d.id,
            groupbit: d.groupbit,
            ninsert,
            ntype,
            volume,
            diam,
            radius_max,
            density,
            maxattempt,
            rate,
            vel,
            id_next,
            random,
            grav,
            fall_time,
            nfreq: 0,
            nper,
            nfirst,
            next: None,
            announced: false,
            ninserted: 0,
            maxtag,
            dimension,
            mol,
            maxmol,
        })
    }

    /// The vertical (3D z, 2D y) bounds of the region at this step (it moves at `rate`).
    fn current_bounds(&self, step: i64, dt: f64) -> (f64, f64) {
        let (lo, hi) = match self.volume {
            Volume::Block { lo, hi } => (lo[self.dimension - 1], hi[self.dimension - 1]),
            Volume::Cylinder { zlo, zhi, .. } => (zlo, zhi),
        };
        let shift = (step - self.nfirst) as f64 * dt * self.rate;
        (lo + shift, hi + shift)
    }

    /// A trial position at height `h` (LAMMPS `xyz_random`).
    fn trial_position(&mut self, h: f64) -> [f64; 3] {
        match self.volume {
            Volume::Block { lo, hi } if self.dimension == 3 => {
                let x = lo[0] + self.random.uniform() * (hi[0] - lo[0]);
                let y = lo[1] + self.random.uniform() * (hi[1] - lo[1]);
                [x, y, h]
            }
            Volume::Block { lo, hi } => [lo[0] + self.random.uniform() * (hi[0] - lo[0]), h, 0.0],
            Volume::Cylinder { xc, yc, rc, .. } => loop {
                let r1 = self.random.uniform() - 0.5;
                let r2 = self.random.uniform() - 0.5;
                if r1 * r1 + r2 * r2 < 0.25 {
                    break [xc + 2.0 * r1 * rc, yc + 2.0 * r2 * rc, h];
                }
            },
        }
    }

    /// Whether an atom at `x` with radius `r` could touch a particle inserted now (LAMMPS
    /// `overlap`, periodic images included).
    fn could_overlap(&self, x: [f64; 3], r: f64, (lo_c, hi_c): (f64, f64), domain: &crate::engine::domain::Domain) -> bool {
        let delta = r + self.radius_max;
        let outside = |d: usize, v: f64, lo: f64, hi: f64| outside(domain, d, v, lo, hi);
        match self.volume {
            Volume::Block { lo, hi } if self.dimension == 3 => {
                !(outside(0, x[0], lo[0] - delta, hi[0] + delta) || outside(1, x[1], lo[1] - delta, hi[1] + delta) || outside(2, x[2], lo_c - delta, hi_c + delta))
            }
            Volume::Block { lo, hi } => !(outside(0, x[0], lo[0] - delta, hi[0] + delta) || outside(1, x[1], lo_c - delta, hi_c + delta)),
            Volume::Cylinder { xc, yc, rc, .. } => {
                let mut del = [x[0] - xc, x[1] - yc, 0.0];
                domain.minimum_image(&mut del);
                let rr = rc + delta;
                del[0] * del[0] + del[1] * del[1] <= rr * rr && !outside(2, x[2], lo_c - delta, hi_c + delta)
            }
        }
    }
}

/// LAMMPS' `FixPour::outside`: is `v` outside `lo..hi` along `d`, where in a periodic
/// dimension the interval may wrap around the box.
fn outside(domain: &crate::engine::domain::Domain, d: usize, v: f64, lo: f64, hi: f64) -> bool {
    let regular = v < lo || v > hi;
    let mut pbc = true;
    if domain.periodic(d) {
        let (blo, bhi, prd) = (domain.lo[d], domain.hi[d], domain.prd()[d]);
        if (lo < blo && hi > bhi) || (hi - lo) > prd {
            pbc = false;
        } else if lo < blo {
            pbc = v > hi && v < lo + prd;
        } else if hi > bhi {
            pbc = v < lo && v > hi - prd;
        }
    }
    pbc && regular
}

/// Every rank's `points` (position, radius), joined (a distributed run; otherwise `points`).
fn gather_points(state: &State, points: Vec<([f64; 3], f64)>) -> Vec<([f64; 3], f64)> {
    if state.distributed.is_none() {
        return points;
    }
    let flat = points.iter().flat_map(|&(x, r)| [x[0], x[1], x[2], r]).collect();
    state.allgather_ranks(flat).chunks_exact(4).map(|c| ([c[0], c[1], c[2]], c[3])).collect()
}

/// Gravity must point along -z (3D) or -y (2D), or particles would not fall through the region.
fn check_direction(dir: [f64; 3], dimension: usize) -> Result<(), String> {
    let want = if dimension == 3 { [0.0, 0.0, -1.0] } else { [0.0, -1.0, 0.0] };
    if (0..3).any(|k| (dir[k] - want[k]).abs() > EPSILON) {
        return Err(format!("fix pour needs gravity along {} (found direction {:?})", if dimension == 3 { "-z in 3D" } else { "-y in 2D" }, dir));
    }
    Ok(())
}

impl Fix for FixPour {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "pour"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { pre_exchange: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, ctx: &FixCtx) -> Result<(), String> {
        let g = ctx.other_fixes().find_map(|f| f.gravity()).ok_or("fix pour needs a fix gravity")?;
        check_direction(g.dir, state.dimension)?;
        if g.magnitude.map(|m| -m * state.units.ftm2v) != Some(self.grav) {
            return Err("the gravity changed since fix pour was defined".into());
        }
        // as LAMMPS 22 Jul 2025's init: the interval from this run's timestep, and the next
        // batch on the run's first step (every run restarts the schedule; nfirst, the origin
        // of the region's motion, stays)
        let nfreq = (self.fall_time / state.dt + 0.5) as i32 as i64;
        if nfreq <= 0 {
            return Err(format!("fix pour: the fall time through the region ({}) is below half a time step", self.fall_time));
        }
        self.nfreq = nfreq;
        self.next = (self.ninserted < self.ninsert).then_some(state.step + 1);
        if let Some((m, Some(id))) = &self.mol {
            super::check_rigid_insert(ctx, "pour", id, &m.id)?;
        }
        Ok(())
    }
    fn setup_pre_force(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        if !self.announced {
            self.announced = true;
            let nfinal = state.step + 1 + (self.ninsert - 1).max(0) / self.nper * self.nfreq;
            state.messages.push(format!("Particle insertion: {} every {} steps, {} by step {nfinal}", self.nper, self.nfreq, self.ninsert));
        }
        Ok(())
    }
    fn reset_dt(&mut self, _state: &State) -> Result<(), String> {
        match self.announced {
            true => Err("Cannot change timestep with fix pour".into()),
            false => Ok(()),
        }
    }
    fn next_reneighbor(&self) -> Option<i64> {
        self.next
    }
    fn insert_radius(&self, itype: usize) -> f64 {
        match &self.mol {
            // the largest radius among the template's atoms of that type (LAMMPS' extract)
            Some((m, _)) => {
                let typ = m.typ.as_deref().unwrap_or(&[]);
                (0..m.natoms()).filter(|&k| typ.get(k).map(|t| t + self.ntype) == Some(itype)).map(|k| m.radius.as_ref().map_or(0.5, |r| r[k])).fold(0.0, f64::max)
            }
            None if itype == self.ntype => self.radius_max,
            None => 0.0,
        }
    }
    fn pre_exchange(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        if self.next != Some(state.step) {
            return Ok(());
        }
        let Some(domain) = state.domain.clone() else { return Ok(()) };
        state.atoms.clear_ghosts();
        if !self.id_next {
            (self.maxtag, self.maxmol) = state.max_ids();
        }
        let nnew = self.nper.min(self.ninsert - self.ninserted);
        let bounds = self.current_bounds(state.step, state.dt);
        let (lo_c, hi_c) = bounds;
        let a = &state.atoms;
        // (x, radius) of every particle a new one must not overlap: present ones near the
        // region (on every rank of a distributed run, so that all ranks draw and place the
        // same particles), then each one inserted
        let near: Vec<([f64; 3], f64)> = (0..a.nlocal).filter(|&i| self.could_overlap(a.x[i], a.radius[i], bounds, &domain)).map(|i| (a.x[i], a.radius[i])).collect();
        let mut near = gather_points(state, near);
        let nprevious = near.len();
        let maxiter = nnew * self.maxattempt;
        let (mut attempt, mut nsuccess) = (0, 0);
        let vertical = self.dimension - 1;
        while nsuccess < nnew {
            let rn = self.random.uniform();
            let h = hi_c - rn * rn * (hi_c - lo_c);
            let radius = if self.mol.is_none() { self.diam.sample(&mut self.random) } else { 0.0 };
            // the particle's atoms (wrapped, with images and radii), and a molecule's rotation
            let mut placed: Option<(Vec<([f64; 3], [i32; 3], f64)>, [f64; 3], [f64; 4])> = None;
            while attempt < maxiter {
                attempt += 1;
                let x = self.trial_position(h);
                let (atoms, quat) = match &self.mol {
                    None => (vec![(x, [0; 3], radius)], [1.0, 0.0, 0.0, 0.0]),
                    Some((m, _)) => {
                        // the template draw (one template: always the first), then the rotation
                        self.random.uniform();
                        let mut r = [0.0, 0.0, 1.0];
                        if self.dimension == 3 {
                            r = [self.random.uniform() - 0.5, self.random.uniform() - 0.5, self.random.uniform() - 0.5];
                        }
                        let theta = self.random.uniform() * 2.0 * PI;
                        norm3(&mut r);
                        let quat = axisangle_to_quat(&r, theta);
                        let rot = quat_to_mat(&quat);
                        let radii = (0..m.natoms()).map(|k| m.radius.as_ref().map_or(0.5, |r| r[k]));
                        (m.place(&rot, x, &domain).into_iter().zip(radii).map(|((p, img), r)| (p, img, r)).collect(), quat)
                    }
                };
                let clear = atoms.iter().all(|&(p, _, radius)| {
                    near.iter().all(|&(y, ry)| {
                        let mut del = [p[0] - y[0], p[1] - y[1], p[2] - y[2]];
                        domain.minimum_image(&mut del);
                        let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
                        let radsum = radius + ry;
                        rsq > radsum * radsum
                    })
                });
                if clear {
                    placed = Some((atoms, x, quat));
                    break;
                }
            }
            let Some((atoms, x, quat)) = placed else { break };
            nsuccess += 1;
            near.extend(atoms.iter().map(|&(p, _, r)| (p, r)));
            let [vxlo, vxhi, vylo, vyhi, vfall] = self.vel;
            let mut v = [0.0; 3];
            v[0] = vxlo + self.random.uniform() * (vxhi - vxlo);
            if self.dimension == 3 {
                v[1] = vylo + self.random.uniform() * (vyhi - vylo);
            }
            v[vertical] = -(vfall * vfall + 2.0 * self.grav * (x[vertical] - hi_c)).sqrt();
            match &self.mol {
                None => {
                    let dens = self.density.0 + self.random.uniform() * (self.density.1 - self.density.0);
                    if domain.takes_inserted(x) && state.owns_point(&x) {
                        let mut atom = NewAtom::at(self.maxtag + 1, self.ntype, x);
                        atom.v = v;
                        atom.radius = radius;
                        atom.rmass = 4.0 * PI / 3.0 * radius * radius * radius * dens;
                        state.atoms.push(&atom);
                        let n = state.atoms.nlocal - 1;
                        state.atoms.mask[n] = 1 | self.groupbit;
                    }
                    self.maxtag += 1;
                }
                Some((m, rigid)) => {
                    if !atoms.iter().all(|&(p, _, _)| domain.takes_inserted(p)) {
                        return Err(RunError::new(state.step, format!("fix {} pour: a molecule would be inserted partly outside the box, which dmhs does not support", self.id)));
                    }
                    // on ranks the owner of the centre takes the whole molecule; the rebuild that
                    // follows sends its atoms on to their own sub-domains
                    if state.owns_point(&x) {
                        let at: Vec<([f64; 3], [i32; 3])> = atoms.iter().map(|&(p, img, _)| (p, img)).collect();
                        let new = m.push_copy(state, &at, self.maxtag, self.maxmol, self.ntype, v);
                        for n in new {
                            state.atoms.mask[n] = 1 | self.groupbit;
                        }
                    }
                    if let Some(fix_id) = rigid {
                        state.rigid_inserts.push(RigidInsert { fix_id: fix_id.clone(), tagprev: self.maxtag, mol: self.maxmol + m.nmolecules(), xgeom: x, vcm: v, quat });
                    }
                    self.maxtag += m.natoms() as i64;
                    if state.atoms.features.molecule {
                        self.maxmol += 1;
                    }
                }
            }
        }
        let natom = self.mol.as_ref().map_or(1, |(m, _)| m.natoms());
        let inserted = ((near.len() - nprevious) / natom) as i64;
        self.ninserted += inserted;
        if inserted < nnew {
            state.messages.push("WARNING: Fewer insertions than requested".into());
        }
        if inserted > 0 {
            state.lists_valid = false;
        }
        self.next = (self.ninserted < self.ninsert).then_some(state.step + self.nfreq);
        Ok(())
    }
    fn describe(&self) -> String {
        match self.nfreq {
            0 => format!("fix {} pour: {} particles of type {}, {} per batch (interval set when a run starts)", self.id, self.ninsert, self.ntype, self.nper),
            n => format!("fix {} pour: {} particles of type {}, {} every {n} steps", self.id, self.ninsert, self.ntype, self.nper),
        }
    }
}
