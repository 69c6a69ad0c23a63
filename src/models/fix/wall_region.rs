//! `fix ID group wall/region regionID style args cutoff`: the surface of a region as a wall
//! acting along the surface normal on the particles inside it (or outside, `side out`), with
//! the potentials of the flat walls (lj93, lj126, lj1043, harmonic, morse: wall_flat.rs) or
//! colloid (wall_colloid.rs, atom_style sphere), as LAMMPS' FixWallRegion.
//!
//! Each step every group atom must be matched by the region; each of its contacts closer than
//! the cutoff ([`Region::surface`]) adds the force along the contact direction. An atom the
//! region does not match, or one on the surface (colloid: within its radius), stops the run as
//! LAMMPS' "Particle outside surface of region used in fix wall/region".
//! f_ID is the energy, f_ID[1..3] the total force on the wall.

use super::wall_colloid::Colloid;
use super::wall_flat::{parse_params, powint, WallPotential, STYLES};
use super::wall_gran_region::NameOnly;
use super::{Fix, FixCtx, FixHooks, ThermoTally};
use crate::engine::region::{Region, WallContact};
use crate::engine::state::{RunError, State};
use dmhs_parser::{Args, Command, DResult, Word};

pub const SYNTAX: &str = "fix ID group wall/region region-ID style args cutoff  (style: lj93|lj126|lj1043|colloid|harmonic epsilon sigma, morse D0 alpha r0)";

enum Potential {
    Point(Box<dyn WallPotential>),
    Colloid(Colloid),
}

pub struct FixWallRegion {
    id: String,
    groupbit: u32,
    style: String,
    region_id: String,
    /// The fix's copy of the region (its motion state), as fix wall/gran/region.
    region: Region,
    pot: Potential,
    cutoff: f64,
    /// Energy, then the force on the wall (x, y, z).
    ewall: [f64; 4],
    contacts: Vec<WallContact>,
    tally: ThermoTally,
}

impl FixWallRegion {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &State) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        let rw = a.word("region ID")?;
        let Some(region) = state.regions.iter().find(|r| r.id == rw.text) else {
            return Err(a.error_at(rw, format!("region {} for fix wall/region does not exist", rw.text), "unknown region"));
        };
        if let Some(style) = region.without_surface() {
            return Err(a.error_at(rw, format!("fix wall/region does not support region style {style} yet (block, cylinder, cone, sphere, union and intersect)"), "not supported"));
        }
        let sw = a.word("wall style")?;
        let (pot, cutoff) = if sw.text == "colloid" {
            if !state.atoms.features.sphere {
                return Err(a.error_at(sw, "fix wall/region colloid requires atom attribute radius (atom_style sphere)", "no radius"));
            }
            let epsilon = a.f64("epsilon")?;
            let sigma = a.f64("sigma")?;
            let cutoff = a.f64_where("cutoff", "> 0", |c| c > 0.0)?;
            (Potential::Colloid(Colloid::new(epsilon, sigma, cutoff)), cutoff)
        } else {
            let Some(st) = STYLES.iter().find(|s| s.name == sw.text) else {
                return Err(a.error_at(sw, format!("unknown fix wall/region style `{}`", sw.text), "expected one of: lj93, lj126, lj1043, colloid, harmonic, morse"));
            };
            let p = parse_params(&mut a, st, powint)?;
            (Potential::Point((st.build)(&p)), p.cutoff)
        };
        a.finish()?;
        Ok(FixWallRegion { id, groupbit, style: sw.text.clone(), region_id: rw.text.clone(), region: region.clone(), pot, cutoff, ewall: [0.0; 4], contacts: vec![], tally: ThermoTally::new(true) })
    }
}

impl Fix for FixWallRegion {
    /// LAMMPS applies it while minimizing (its energy counts only with fix_modify energy).
    fn min_role(&self) -> super::MinRole {
        super::MinRole::PostForce
    }
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "wall/region"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, _ctx: &FixCtx) -> Result<(), String> {
        if matches!(self.pot, Potential::Colloid(_)) {
            let a = &state.atoms;
            if (0..a.nlocal).any(|i| a.mask[i] & self.groupbit != 0 && a.radius[i] == 0.0) {
                return Err(format!("fix {} wall/region colloid requires only extended particles (radius > 0)", self.id));
            }
        }
        Ok(())
    }
    /// The region as it is now (LAMMPS looks it up again at init); its motion starts afresh.
    fn setup_pre_force(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        let now = state.regions.iter().find(|r| r.id == self.region_id).ok_or_else(|| RunError::new(state.step, format!("region {} for fix wall/region does not exist", self.region_id)))?;
        if now.serial != self.region.serial {
            self.region = now.clone();
        }
        self.region.init(&state.regions).map_err(|e| RunError::new(state.step, e))
    }
    fn post_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        let step = state.step;
        if self.region.is_dynamic() {
            let me: &dyn Fix = &NameOnly(&self.id);
            self.region.prematch(&mut |name| ctx.equal(state, me, name)).map_err(|e| RunError::new(step, format!("fix {} region {}: {e}", self.id, self.region_id)))?;
        }
        self.ewall = [0.0; 4];
        self.tally.v_init();
        let a = &mut state.atoms;
        let mut outside = None;
        for i in 0..a.nlocal {
            if a.mask[i] & self.groupbit == 0 {
                continue;
            }
            if !self.region.matches(a.x[i]) {
                outside = Some(a.tag[i]);
                continue;
            }
            let tooclose = if matches!(self.pot, Potential::Colloid(_)) { a.radius[i] } else { 0.0 };
            self.region.surface(a.x[i], self.cutoff, &mut self.contacts);
            for c in &self.contacts {
                if c.r <= tooclose {
                    outside = Some(a.tag[i]);
                    continue;
                }
                let rinv = 1.0 / c.r;
                let (fwall, eng) = match &self.pot {
                    Potential::Point(p) => p.force_energy(c.r),
                    Potential::Colloid(p) => p.force_energy(c.r, a.radius[i]),
                };
                let fx = fwall * c.del[0] * rinv;
                let fy = fwall * c.del[1] * rinv;
                let fz = fwall * c.del[2] * rinv;
                a.f[i][0] += fx;
                a.f[i][1] += fy;
                a.f[i][2] += fz;
                self.ewall[1] -= fx;
                self.ewall[2] -= fy;
                self.ewall[3] -= fz;
                self.ewall[0] += eng;
                let d = c.del;
                self.tally.v_tally([fx * d[0], fy * d[1], fz * d[2], fx * d[1], fx * d[2], fy * d[2]]);
            }
        }
        match outside {
            Some(tag) => Err(RunError::new(step, format!("fix {} wall/region {}: particle {tag} is outside the surface of region {} (or on it): LAMMPS' \"Particle outside surface of region used in fix wall/region\"", self.id, self.style, self.region_id))),
            None => Ok(()),
        }
    }
    fn scalar(&self, state: &State) -> Option<f64> {
        Some(state.summed_over_ranks(self.ewall[0]))
    }
    fn vector(&self, state: &State, i: usize) -> Option<f64> {
        (1..=3).contains(&i).then(|| state.summed_over_ranks(self.ewall[i]))
    }
    fn size_vector(&self) -> usize {
        3
    }
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }
    fn thermo_tally(&self) -> Option<&ThermoTally> {
        Some(&self.tally)
    }
    fn thermo_tally_mut(&mut self) -> Option<&mut ThermoTally> {
        Some(&mut self.tally)
    }
    fn describe(&self) -> String {
        format!("fix {} wall/region {} {}", self.id, self.region_id, self.style)
    }
}
