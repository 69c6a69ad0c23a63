//! `fix ID group wall/gran/region MODEL ... region R-ID`: the surface of a region as a frictional
//! granular wall, with the contact models of fix wall/gran ([`super::wall_gran::parse_model`]:
//! the `granular` form or the classic `hooke|hooke/history|hertz/history` forms), as LAMMPS
//! 2025's FixWallGranRegion.
//!
//! Each step (and at setup, without advancing the springs) a moving region evaluates its
//! variables and infers its velocities ([`Region::prematch`], [`Region::set_velocity`]); every
//! atom the region matches gets the region's contacts within its radius ([`Region::surface`]),
//! each a wall of radius `contact.radius` (the wall's curvature: the effective radius of Hertz
//! contacts) moving with the region's velocity at the contact point.
//!
//! Contact history is kept per atom and per wall number (`iwall`), as LAMMPS' `ncontact`,
//! `walls` and `history_many`, in an extra per-atom array that follows the atom: a contact that
//! persists keeps its spring, a new one starts at zero, a broken one is removed by moving the
//! last over it; LAMMPS' `c2r` map from contacts to history slots is reproduced as LAMMPS fills
//! it (`update_contacts`). The history survives `region ID delete` and a new definition of the
//! region (LAMMPS keeps its arrays then and only resets the region's motion).
//!
//! `contacts` gives LAMMPS' per-atom array (f_ID[1..8], as fix wall/gran's: touching, the
//! wall's force, the contact point, the radius; [`WallContacts`]). An atom touching several of
//! the region's walls reports the last contact in the region's order (LAMMPS overwrites the
//! row for each); the forces of all of them act.
//!
//! As in LAMMPS 2025, the fix acts on every atom whatever its group (its group test reads
//! `(!mask[i]) & groupbit`); `dmhs check` warns when the group is not `all`.

use super::value::FixValue;
use super::wall_gran::{check_heat, parse_model, parse_temperature, syntax as wall_syntax, wall_temperature, WallContacts};
use crate::engine::fields::{HEATFLOW, TEMPERATURE};
use super::{Fix, FixCtx, FixHooks};
use crate::engine::region::{Region, WallContact};
use crate::engine::state::{RunError, State};
use crate::models::pair::contact::Contact;
use crate::models::pair::granular::normal::Normal;
use crate::models::pair::granular::mdr_state::{self, MdrArrays};
use crate::models::pair::granular::{contact_heat, granular_contact_with, mdr, GranModel, GranSpec};
use dmhs_parser::{Args, Command, DResult, Word};

fn syntax() -> String {
    wall_syntax().replace("wall/gran ", "wall/gran/region ").replace(" xplane|yplane|zplane lo hi [wiggle x|y|z A period | shear x|y|z v]", " region region-ID")
}

pub struct FixWallGranRegion {
    id: String,
    groupbit: u32,
    spec: GranSpec,
    model: GranModel,
    region_id: String,
    /// The fix's copy of the region: it holds the motion state (LAMMPS keeps a pointer and
    /// notices a new region of the same ID when a run starts).
    region: Region,
    /// LAMMPS `tmax`: touching contacts per atom; the history array has room for `slots`.
    tmax: usize,
    slots: usize,
    /// Name of the per-atom history array in `Atoms::extra`.
    array: String,
    /// Scratch: the current atom's contacts, and LAMMPS' c2r.
    contacts: Vec<WallContact>,
    c2r: Vec<usize>,
    /// `temperature T` (heat models)
    temperature: Option<FixValue>,
    /// `contacts`: the per-atom contact array.
    contact_array: Option<WallContacts>,
}

impl FixWallGranRegion {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, state: &mut State) -> DResult<Self> {
        let syn = syntax();
        let mut a = Args::from_words(args, cmd.span, &syn);
        if !state.atoms.features.sphere {
            return Err(a.error_at(&cmd.name, "fix wall/gran/region requires atom attributes radius and omega (atom_style sphere)", "no sphere attributes"));
        }
        let spec = parse_model(&mut a, cmd, &syn, state)?;
        let model = GranModel::build(&spec, true);
        let w = a.word("`region` and a region ID")?;
        if w.text != "region" {
            return Err(a.error_at(w, format!("expected `region region-ID`, found `{}`", w.text), "expected region"));
        }
        let rw = a.word("region ID")?;
        let Some(region) = state.regions.iter().find(|r| r.id == rw.text) else {
            return Err(a.error_at(rw, format!("region {} for fix wall/gran/region does not exist", rw.text), "unknown region"));
        };
        if let Some(style) = region.without_surface() {
            return Err(a.error_at(rw, format!("fix wall/gran/region does not support region style {style} yet (block, cylinder, cone, sphere, union and intersect)"), "not supported"));
        }
        let mut temperature = None;
        let mut contacts = false;
        while let Some(k) = a.peek() {
            a.skip(1);
            match k.text.as_str() {
                "temperature" => temperature = Some(parse_temperature(&mut a, k, &model, "wall/gran/region")?),
                "contacts" => contacts = true,
                _ => return Err(a.unknown_keyword(k, &["temperature", "contacts"])),
            }
        }
        check_heat(&a, cmd, &model, &temperature, "wall/gran/region")?;
        if groupbit != 1 {
            state.messages.push(format!("WARNING: fix {id} wall/gran/region acts on all atoms, not only group members: LAMMPS 2025 ignores its group (it tests `(!mask[i]) & groupbit`), and so does dmhs"));
        }
        let region = region.clone();
        let tmax = region.contact_counts().1;
        let array = format!("wall/gran/region:{id}");
        let contact_array = contacts.then(|| WallContacts::new(state, &id, "wall/gran/region"));
        let mut fix = FixWallGranRegion { id, groupbit, spec, model, region_id: rw.text.clone(), region, tmax, slots: 0, array, contacts: vec![], c2r: vec![], temperature, contact_array };
        fix.reserve(state, tmax);
        Ok(fix)
    }

    /// History values per contact (LAMMPS `size_history`); 0: no history kept.
    fn width(&self) -> usize {
        self.model.history_size
    }

    /// Per-atom layout: count, `slots` wall numbers, `slots` histories.
    fn stride(&self, slots: usize) -> usize {
        1 + slots * (1 + self.width())
    }

    /// Make room for `tmax` contacts per atom, keeping the histories.
    fn reserve(&mut self, state: &mut State, tmax: usize) {
        if self.width() == 0 || tmax <= self.slots {
            return;
        }
        let (old, new) = (self.slots, tmax);
        let (so, sn, w) = (self.stride(old), self.stride(new), self.width());
        let atoms = &mut state.atoms;
        let n = atoms.nlocal;
        let data = match atoms.find_extra(&self.array) {
            Some(k) => {
                let d = std::mem::take(&mut atoms.extra[k].data);
                let mut out = vec![0.0; n * sn];
                for i in 0..n {
                    let (src, dst) = (&d[i * so..(i + 1) * so], &mut out[i * sn..(i + 1) * sn]);
                    dst[0] = src[0];
                    dst[1..1 + old].copy_from_slice(&src[1..1 + old]);
                    dst[1 + new..1 + new + old * w].copy_from_slice(&src[1 + old..]);
                }
                atoms.remove_extra(&self.array);
                out
            }
            None => vec![0.0; n * sn],
        };
        let k = atoms.extra_array(&self.array, sn);
        atoms.extra[k].data = data;
        self.slots = new;
    }

    fn apply(&mut self, state: &mut State, ctx: &mut FixCtx, update: bool) -> Result<(), RunError> {
        let step = state.step;
        let dynamic = self.region.is_dynamic();
        if dynamic {
            let region = &mut self.region;
            let me: &dyn Fix = &NameOnly(&self.id);
            region.prematch(&mut |name| ctx.equal(state, me, name)).map_err(|e| RunError::new(step, format!("fix {} region {}: {e}", self.id, self.region_id)))?;
            region.set_velocity(step, state.dt);
        }
        let twall = wall_temperature(&self.temperature, state, ctx, &NameOnly(&self.id))?;
        let (w, slots, tmax) = (self.width(), self.slots, self.tmax);
        let stride = self.stride(slots);
        let dt = state.dt;
        let kx = state.atoms.find_extra(&self.array);
        let a = &mut state.atoms;
        // with rigid bodies the body's mass (LAMMPS' mass_rigid)
        let rigid_mass = &state.rigid_mass;
        let n = a.nlocal;
        let mut hist = kx.map(|k| std::mem::take(&mut a.extra[k].data)).unwrap_or_default();
        // heat: the atoms' temperatures (read) and heat flows (added to), when conducting
        let heat = match (twall, a.field(TEMPERATURE), a.field(HEATFLOW)) {
            (Some(tw), Some(kt), Some(kq)) => Some((tw, kt, kq)),
            _ => None,
        };
        let mut flow = heat.map(|(_, _, kq)| std::mem::take(&mut a.extra[kq].data)).unwrap_or_default();
        // contacts: every owned atom's row is cleared, then each touching contact's written
        let mut cdata = self.contact_array.as_ref().map(|c| c.take_cleared(a)).unwrap_or_default();
        let cols = WallContacts::cols(self.contact_array.as_ref()).unwrap_or(0);
        // the mdr model reads and adds to the atoms' mdr values
        let mut mdr_io = match self.model.normal {
            Normal::Mdr(_) => Some(MdrArrays::take(a).map_err(|e| RunError::new(step, format!("fix {}: {e}", self.id)))?),
            _ => None,
        };
        let w0 = [0.0f64; 3];
        let mut result = Ok(());
        for i in 0..n {
            if !self.region.matches(a.x[i]) {
                continue;
            }
            let radi = a.radius[i];
            // LAMMPS widens the search by the pull-off distance against R_j = 0, which is 0:
            // a JKR contact with a region wall ends where it stops touching
            self.region.surface(a.x[i], radi + self.model.normal.pulloff_distance(radi, 0.0), &mut self.contacts);
            let nc = self.contacts.len();
            if nc > tmax {
                result = Err(RunError::new(step, format!("too many wall/gran/region contacts for one particle (atom {}: {nc}, at most {tmax})", a.tag[i])));
                break;
            }
            let h = if w > 0 { &mut hist[i * stride..(i + 1) * stride] } else { &mut [][..] };
            if w > 0 && !track_contacts(h, slots, w, tmax, &self.contacts, &mut self.c2r) {
                continue;
            }
            for ic in 0..nc {
                let c = self.contacts[ic];
                let rsq = c.r * c.r;
                let slot = if w > 0 { 1 + slots + self.c2r[ic] * w } else { 0 };
                let beyond = self.model.beyond_contact;
                if !self.model.wall_touch(rsq, radi, c.radius, beyond && h[slot] != 0.0) {
                    if w > 0 {
                        h[slot..slot + w].fill(0.0);
                    }
                    continue;
                }
                if beyond {
                    h[slot] = 1.0;
                }
                let vwall = if dynamic { c.vwall } else { w0 };
                let mi = if rigid_mass.is_empty() { a.rmass[i] } else { rigid_mass[i] };
                let g = Contact { del: c.del, rsq, radi, radj: c.radius, vi: &a.v[i], vj: &vwall, omegai: &a.omega[i], omegaj: &w0, meff: mi };
                let hs = if w > 0 { &mut h[slot..slot + w] } else { &mut [][..] };
                let fnormal = match (&self.model.normal, mdr_io.as_mut()) {
                    (Normal::Mdr(m), Some(io)) => {
                        let at = io.atom(i, a.tag[i], radi);
                        let rinv = 1.0 / c.r;
                        let nx = [rinv * c.del[0], rinv * c.del[1], rinv * c.del[2]];
                        Some(mdr::normal_force(m, [&at, &at], [i, i], true, radi - c.r, &nx, mi, &mut hs[..mdr::HISTORY], update, &mut io.sums()).f)
                    }
                    _ => None,
                };
                let r = granular_contact_with(&self.model, &g, true, hs, update, dt, fnormal);
                for d in 0..3 {
                    a.f[i][d] += r.f[d];
                    a.torque[i][d] += r.ti[d];
                }
                if let (Some((tw, kt, _)), Some(hm)) = (heat, &self.model.heat) {
                    flow[i] += contact_heat(&self.model, hm, rsq, radi, c.radius, true, a.extra[kt].data[i], tw);
                }
                if cols > 0 {
                    cdata[i * cols..(i + 1) * cols].copy_from_slice(&WallContacts::row(&a.x[i], &c.del, &r.f, radi));
                }
            }
        }
        if let Some(c) = &self.contact_array {
            c.restore(a, cdata);
        }
        if let Some(k) = kx {
            a.extra[k].data = hist;
        }
        if let Some((_, _, kq)) = heat {
            a.extra[kq].data = flow;
        }
        if let Some(io) = mdr_io {
            io.restore(a);
        }
        result
    }

    /// LAMMPS FixGranularMDR::update_fix_gran_wall, for this wall with the mdr model: after the
    /// pair style's mdr pass (new radii, mean surface displacements of the pairs), each atom's
    /// contacts with the wall (at its new radius) are tracked as the force pass will track them
    /// and add their overlap increments to the atom's mean surface displacement; then the
    /// ghosts get it.
    fn mdr_pre_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        let step = state.step;
        if self.region.is_dynamic() {
            let me: &dyn Fix = &NameOnly(&self.id);
            self.region.prematch(&mut |name| ctx.equal(state, me, name)).map_err(|e| RunError::new(step, format!("fix {} region {}: {e}", self.id, self.region_id)))?;
        }
        let (w, slots, tmax) = (self.width(), self.slots, self.tmax);
        let stride = self.stride(slots);
        let a = &mut state.atoms;
        let Some(kx) = a.find_extra(&self.array) else { return Ok(()) };
        let mut hist = std::mem::take(&mut a.extra[kx].data);
        let mut result = Ok(());
        for i in 0..a.nlocal {
            if !self.region.matches(a.x[i]) {
                continue;
            }
            self.region.surface(a.x[i], a.radius[i], &mut self.contacts);
            if self.contacts.len() > tmax {
                result = Err(RunError::new(step, format!("too many wall/gran/region contacts for one particle (atom {}: {}, at most {tmax})", a.tag[i], self.contacts.len())));
                break;
            }
            let h = &mut hist[i * stride..(i + 1) * stride];
            if !track_contacts(h, slots, w, tmax, &self.contacts, &mut self.c2r) {
                continue;
            }
            for (ic, c) in self.contacts.iter().enumerate() {
                let slot = 1 + slots + self.c2r[ic] * w;
                let delta = a.radius[i] - c.r;
                if let Err(e) = mdr_state::wall_surface_displacement(a, i, delta, &h[slot..slot + w]) {
                    result = Err(RunError::new(step, e));
                }
            }
        }
        a.extra[kx].data = hist;
        result?;
        let kd = a.field(crate::engine::fields::MDR_DDELTA_BAR).ok_or_else(|| RunError::new(step, "pair granular mdr: the per-atom value d_ddelta_bar is missing"))?;
        mdr_state::forward(a, kd);
        Ok(())
    }
}

/// LAMMPS FixGranularMDR::setup_pre_force's checks of a region wall with the mdr model: pair
/// granular uses mdr too, with the same material (E, nu, Y, psi_b and damping coefficient).
fn check_mdr_wall(wall: &mdr::Mdr, pair: Option<mdr::Mdr>) -> Result<(), String> {
    let Some(p) = pair else {
        return Err("the mdr normal model on a region wall needs pair_style granular with the mdr model (LAMMPS: Must specify MDR normal model with pair granular)".into());
    };
    for (what, a, b) in [("Young's modulus", p.e, wall.e), ("Poisson's ratio", p.nu, wall.nu), ("Yield stress", p.y, wall.y), ("Bulk response trigger", p.psi_b, wall.psi_b), ("Damping", p.damp, wall.damp)] {
        if a != b {
            return Err(format!("{what} in pair style, {a}, does not agree with value {b} in fix gran/wall/region (LAMMPS' mdr model)"));
        }
    }
    Ok(())
}

/// The history of atom `i` (`h`: count, wall numbers, histories) follows its contacts now, and
/// `c2r` maps each contact to its history slot (LAMMPS' post_force before the contacts: one
/// contact handled at once, more by `update_contacts`). False when the atom touches nothing.
fn track_contacts(h: &mut [f64], slots: usize, w: usize, tmax: usize, contacts: &[WallContact], c2r: &mut Vec<usize>) -> bool {
    if contacts.is_empty() {
        h[0] = 0.0;
        return false;
    }
    c2r.clear();
    c2r.resize(tmax.max(1), 0);
    let count = h[0] as usize;
    let iwall = contacts[0].iwall;
    if contacts.len() == 1 && count == 0 {
        h[0] = 1.0;
        h[1] = iwall as f64;
        h[1 + slots..1 + slots + w].fill(0.0);
    } else if contacts.len() > 1 || count > 1 || h[1] as usize != iwall {
        update_contacts(h, slots, w, contacts, c2r);
    }
    true
}

/// LAMMPS `update_contacts`: drop the remembered walls the atom no longer touches (the last
/// moved over each), add the new ones with zero history, and map each contact to its history
/// slot in `c2r` exactly as LAMMPS fills it (`c2r[slot] = contact` for remembered walls).
fn update_contacts(h: &mut [f64], slots: usize, w: usize, contacts: &[WallContact], c2r: &mut [usize]) {
    let hist = 1 + slots;
    let mut count = h[0] as usize;
    let mut iold = 0;
    while iold < count {
        let wall = h[1 + iold] as usize;
        if !contacts.iter().any(|c| c.iwall == wall) {
            let ilast = count - 1;
            h.copy_within(hist + ilast * w..hist + (ilast + 1) * w, hist + iold * w);
            h[1 + iold] = h[1 + ilast];
            count -= 1;
        } else {
            iold += 1;
        }
    }
    let nold = count;
    for (inew, c) in contacts.iter().enumerate() {
        match (0..nold).find(|&m| h[1 + m] as usize == c.iwall) {
            Some(m) => c2r[m] = inew,
            None => {
                c2r[count] = inew;
                h[hist + count * w..hist + (count + 1) * w].fill(0.0);
                h[1 + count] = c.iwall as f64;
                count += 1;
            }
        }
    }
    h[0] = count as f64;
}

/// The fix as the `running` fix of an expression (only its ID is read), while its region is
/// borrowed mutably.
pub(super) struct NameOnly<'a>(pub(super) &'a str);

impl Fix for NameOnly<'_> {
    fn id(&self) -> &str {
        self.0
    }
    fn style(&self) -> &str {
        "wall/gran/region"
    }
    fn groupbit(&self) -> u32 {
        0
    }
    fn hooks(&self) -> FixHooks {
        FixHooks::default()
    }
}

impl Fix for FixWallGranRegion {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "wall/gran/region"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn hooks(&self) -> FixHooks {
        FixHooks { post_force: true, mdr_pre_force: matches!(self.model.normal, Normal::Mdr(_)), ..FixHooks::default() }
    }
    fn init(&mut self, state: &State, ctx: &FixCtx) -> Result<(), String> {
        if let Normal::Mdr(wall) = self.model.normal {
            check_mdr_wall(&wall, ctx.pair.and_then(|p| p.mdr_model()))?;
        }
        let now = state.regions.iter().find(|r| r.id == self.region_id).ok_or_else(|| format!("region {} for fix wall/gran/region does not exist", self.region_id))?;
        if let Some(style) = now.without_surface() {
            return Err(format!("region style {style} has no wall contacts"));
        }
        let mut check = now.clone();
        check.init(&state.regions)
    }
    /// A region deleted and defined again is taken, its motion reset (LAMMPS' warning); the
    /// sub-regions of a union or intersection are looked up again.
    fn setup_pre_force(&mut self, state: &mut State, _ctx: &mut FixCtx) -> Result<(), RunError> {
        let now = state.regions.iter().find(|r| r.id == self.region_id).ok_or_else(|| RunError::new(state.step, format!("region {} for fix wall/gran/region does not exist", self.region_id)))?;
        if now.serial != self.region.serial {
            self.region = now.clone();
            self.region.reset_vel();
            state.messages.push(format!("WARNING: Region properties for region {} changed between runs, resetting its motion", self.region_id));
        }
        self.region.init(&state.regions).map_err(|e| RunError::new(state.step, e))?;
        self.tmax = self.region.contact_counts().1;
        let tmax = self.tmax;
        self.reserve(state, tmax);
        Ok(())
    }
    /// Forces of the current state; the springs are not advanced during setup.
    fn setup(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.apply(state, ctx, false)
    }
    fn post_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        self.apply(state, ctx, true)
    }
    fn mdr_pre_force(&mut self, state: &mut State, ctx: &mut FixCtx) -> Result<(), RunError> {
        FixWallGranRegion::mdr_pre_force(self, state, ctx)
    }
    fn cleanup(&mut self, state: &mut State) {
        state.atoms.remove_extra(&self.array);
        WallContacts::remove(self.contact_array.as_ref(), state);
    }
    fn peratom(&self, state: &State) -> Result<crate::models::compute::PerAtom, String> {
        WallContacts::peratom(self.contact_array.as_ref(), state, self)
    }
    fn peratom_cols(&self) -> Option<usize> {
        WallContacts::cols(self.contact_array.as_ref())
    }
    fn describe(&self) -> String {
        format!("fix {} wall/gran/region granular {} region {}", self.id, self.spec.describe(), self.region_id)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn contact(iwall: usize) -> WallContact {
        WallContact { iwall, ..WallContact::default() }
    }

    #[test]
    fn history_follows_walls_as_lammps() {
        // 3 slots, 1 value each: walls 4 and 0 remembered with springs 40 and 10
        let mut h = vec![2.0, 4.0, 0.0, 0.0, 40.0, 10.0, 0.0];
        let mut c2r = vec![9; 3];
        // now touching walls 0, 2, 4 (in that contact order)
        update_contacts(&mut h, 3, 1, &[contact(0), contact(2), contact(4)], &mut c2r);
        assert_eq!(h, vec![3.0, 4.0, 0.0, 2.0, 40.0, 10.0, 0.0]);
        // LAMMPS: c2r[slot] = contact for remembered walls, c2r[new slot] = contact for new ones
        assert_eq!(c2r, vec![2, 0, 1]);
        // wall 4 breaks: the last slot (wall 2) moves over it
        update_contacts(&mut h, 3, 1, &[contact(0), contact(2)], &mut c2r);
        assert_eq!(&h[..4], &[2.0, 2.0, 0.0, 2.0]);
        assert_eq!(&h[4..6], &[0.0, 10.0]);
    }
}
