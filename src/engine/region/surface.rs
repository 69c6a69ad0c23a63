//! Wall contacts of a region (LAMMPS' `Region::surface` and the union/intersect overrides): the
//! points of the region's surface closer than a cutoff to a particle, for fix wall/gran/region.
//!
//! A style gives contacts in its own frame; a moving region maps the particle back first and,
//! if it rotates, the contact points forward again (the contact distance `r` is the one of the
//! defining frame, as in LAMMPS). A region with open faces gets the contacts of both sides
//! (LAMMPS calls surface_exterior and surface_interior; one of them finds none except for a
//! particle exactly on a face). Each contact carries the wall velocity at its point (LAMMPS'
//! `velocity_contact`, asked of the region the fix names: a union or intersection has no motion
//! of its own, so its walls are at rest for the contact model even where its sub-regions move).

use super::{Kind, Region, Vec3};

/// One contact: LAMMPS' `Contact` (`r`, `delx dely delz`, `radius`, `iwall`) and the wall's
/// velocity there.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WallContact {
    /// Distance from the particle centre to the surface point.
    pub r: f64,
    /// Particle centre minus surface point.
    pub del: [f64; 3],
    /// Curvature radius of the wall there (0 flat; negative seen from inside, as LAMMPS).
    pub radius: f64,
    /// Which wall of the region: contact history follows a wall by this number.
    pub iwall: usize,
    pub vwall: [f64; 3],
    /// A curved wall that a variable shape moves (LAMMPS `varflag`: sphere, cylinder side).
    pub varflag: bool,
}

impl WallContact {
    /// A contact from the particle at `x` to the surface point `p` (LAMMPS `add_contact`).
    pub fn to_point(x: &Vec3, p: [f64; 3]) -> WallContact {
        let del = [x[0] - p[0], x[1] - p[1], x[2] - p[2]];
        let r = (del[0] * del[0] + del[1] * del[1] + del[2] * del[2]).sqrt();
        WallContact { r, del, ..WallContact::default() }
    }

    /// A flat face `iwall` at distance `delta` along axis `dim`, `sign` towards the particle.
    pub fn face(dim: usize, delta: f64, sign: f64, iwall: usize) -> WallContact {
        let mut del = [0.0; 3];
        del[dim] = if sign > 0.0 { delta } else { -delta };
        WallContact { r: delta, del, radius: 0.0, iwall, ..WallContact::default() }
    }
}

impl Region {
    /// LAMMPS `cmax` and `tmax`: how many contacts a particle can have, and how many it can
    /// touch at once (the size of its contact history).
    pub fn contact_counts(&self) -> (usize, usize) {
        match &self.kind {
            Kind::Shape(s) => s.contact_counts(self.interior),
            Kind::Boolean { subs, .. } => subs.iter().fold((0, 0), |(c, t), s| {
                let (sc, st) = s.contact_counts();
                (c + sc, t + if self.interior { st } else { 1 })
            }),
        }
    }

    /// The style of a region (or sub-region) that has no wall contacts, if any.
    pub fn without_surface(&self) -> Option<&'static str> {
        match &self.kind {
            Kind::Shape(s) => (!s.has_surface()).then_some(self.style),
            Kind::Boolean { subs, .. } => subs.iter().find_map(Region::without_surface),
        }
    }

    /// LAMMPS `Region::surface`: the contacts of the particle at `x` within `cutoff`, into `out`
    /// (cleared first).
    pub fn surface(&self, x: [f64; 3], cutoff: f64, out: &mut Vec<WallContact>) {
        out.clear();
        match &self.kind {
            Kind::Shape(shape) => {
                let xl = Vec3::from(self.motion.inverse(x));
                let open = &self.open_faces;
                if !self.openflag() {
                    if self.interior {
                        shape.surface_interior(&xl, cutoff, open, out);
                    } else {
                        shape.surface_exterior(&xl, cutoff, open, out);
                    }
                } else {
                    // LAMMPS adds the counts of both calls, the interior contacts overwriting
                    // the exterior one from index 0; both find some only for a particle exactly
                    // on a face, where this keeps both
                    shape.surface_interior(&xl, cutoff, open, out);
                    let mut ext = vec![];
                    shape.surface_exterior(&xl, cutoff, open, &mut ext);
                    out.extend(ext);
                }
                let dynamic = self.is_dynamic();
                for c in out.iter_mut() {
                    if self.motion.rotates() {
                        let xs = self.motion.forward([xl[0] - c.del[0], xl[1] - c.del[1], xl[2] - c.del[2]]);
                        c.del = [x[0] - xs[0], x[1] - xs[1], x[2] - xs[2]];
                    }
                    if dynamic {
                        c.vwall = self.wall_velocity(x, c.del, c.varflag);
                    }
                }
            }
            Kind::Boolean { all, subs } => {
                // the sub-regions move themselves; a union or intersection has no frame of its own
                boolean_surface(*all, self.interior, subs, x, cutoff, out);
            }
        }
    }
}

/// Contacts of a union (`all` false) or intersection (`all` true) of the sub-regions' sides:
/// each sub-region's contacts whose point is in every other sub-region (intersection) or in no
/// other closed one (union). `interior` false: the sub-regions' outsides (LAMMPS flips their
/// `side`), the wall numbered by the sub-region; inside, walls are numbered after the walls of
/// the sub-regions before (offset by their cmax).
fn boolean_surface(all: bool, interior: bool, subs: &[Region], x: [f64; 3], cutoff: f64, out: &mut Vec<WallContact>) {
    let flipped: Vec<Region>;
    let subs = if interior {
        subs
    } else {
        flipped = subs.iter().map(|s| Region { interior: !s.interior, ..s.clone() }).collect();
        &flipped
    };
    let mut walloffset = 0;
    let mut own = vec![];
    for (i, sub) in subs.iter().enumerate() {
        sub.surface(x, cutoff, &mut own);
        for c in &own {
            let xs = [x[0] - c.del[0], x[1] - c.del[1], x[2] - c.del[2]];
            let keep = subs.iter().enumerate().filter(|(j, _)| *j != i).all(|(_, other)| match (all, interior) {
                // intersection: in every other one; union: in no other closed one
                (true, true) => other.matches(xs),
                (false, true) => !(other.matches(xs) && !other.openflag()),
                // outside (sides flipped): of a union, in every other flipped one; of an
                // intersection, in no other flipped one
                (false, false) => other.matches(xs),
                (true, false) => !other.matches(xs),
            });
            if keep {
                let iwall = if interior { c.iwall + walloffset } else { i };
                // LAMMPS' velocity_contact is not virtual: fix wall/gran/region asks the union or
                // intersection itself, which never moves (only its sub-regions do), so the wall
                // velocity is zero whatever the sub-region that made the contact
                out.push(WallContact { iwall, vwall: [0.0; 3], ..*c });
            }
        }
        walloffset += sub.contact_counts().0;
    }
}

#[cfg(test)]
mod tests {
    use super::WallContact;
    use crate::engine::region::tests::reg;
    use crate::engine::region::Region;

    /// Contacts of `r` for a particle at `x` of radius 0.5 after the blade turned by 0.1 in one step.
    fn turned(r: &mut Region, regions: &[Region], x: [f64; 3]) -> Vec<WallContact> {
        r.init(regions).unwrap();
        r.prematch(&mut |_| Ok(0.0)).unwrap();
        r.set_velocity(1, 0.5);
        r.prematch(&mut |_| Ok(0.1)).unwrap();
        r.set_velocity(2, 0.5);
        let mut out = vec![];
        r.surface(x, 0.5, &mut out);
        out
    }

    #[test]
    fn walls_of_an_intersect_are_at_rest_though_its_blade_turns() {
        let blade = reg("region b1 block 1 9 4.5 5.5 0 4 side out rotate v_t 5 5 0 0 0 1 units box", None, None, &[]).unwrap();
        let tank = reg("region tank cylinder z 5 5 4.5 0 10 units box", None, None, &[]).unwrap();
        let subs = [tank, blade.clone()];
        let mut mixer = reg("region mixer intersect 2 tank b1 units box", None, None, &subs).unwrap();
        // on the blade's top face, 3 from the axis: the blade alone moves there (omega 0.2)
        let x = [8.0, 5.0, 4.3];
        let own = turned(&mut blade.clone(), &subs, x);
        assert_eq!(own.len(), 1);
        assert!(own[0].vwall[1].abs() > 0.5, "{own:?}");
        // LAMMPS asks the intersect (velocity_contact is not virtual), which has no motion
        let c = turned(&mut mixer, &subs, x);
        assert_eq!(c.len(), 1);
        assert_eq!((c[0].del, c[0].vwall), (own[0].del, [0.0; 3]));
    }
}
