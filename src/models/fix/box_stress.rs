//! What the box-changing pressure fixes share (fix npt/nph and fix box/relax, LAMMPS' FixNH and
//! FixBoxRelax): the coupling of the diagonal pressures and the strain energy of a deviatoric
//! target.

use crate::engine::domain::Dilation;
use crate::engine::state::State;
use dmhs_parser::{Args, DResult};

/// `couple`: which diagonal pressures are averaged into one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Couple {
    None,
    Xyz,
    Xy,
    Yz,
    Xz,
}

impl Couple {
    /// `couple none|xyz|xy|yz|xz`.
    pub fn parse(a: &mut Args) -> DResult<Couple> {
        Ok([Couple::Xyz, Couple::Xy, Couple::Yz, Couple::Xz, Couple::None][a.choice("couple", &["xyz", "xy", "yz", "xz", "none"])?])
    }
    /// The pressures with the coupled ones replaced by their mean (LAMMPS' couple()).
    pub fn apply(self, t: [f64; 3]) -> [f64; 3] {
        match self {
            Couple::Xyz => [1.0 / 3.0 * (t[0] + t[1] + t[2]); 3],
            Couple::Xy => {
                let ave = 0.5 * (t[0] + t[1]);
                [ave, ave, t[2]]
            }
            Couple::Yz => {
                let ave = 0.5 * (t[1] + t[2]);
                [t[0], ave, ave]
            }
            Couple::Xz => {
                let ave = 0.5 * (t[0] + t[2]);
                [ave, t[1], ave]
            }
            Couple::None => t,
        }
    }
    /// A coupled dimension without a pressure target (z only in 3D for xyz).
    pub fn lacks_target(self, p_flag: &[bool], dimension: usize) -> bool {
        match self {
            Couple::Xyz => !p_flag[0] || !p_flag[1] || (dimension == 3 && !p_flag[2]),
            Couple::Xy => !p_flag[0] || !p_flag[1],
            Couple::Yz => !p_flag[1] || !p_flag[2],
            Couple::Xz => !p_flag[0] || !p_flag[2],
            Couple::None => false,
        }
    }
    /// Coupled dimensions whose settings differ (`same(i, j)`: those of i and j agree).
    pub fn mismatch(self, dimension: usize, same: impl Fn(usize, usize) -> bool) -> bool {
        match self {
            Couple::Xyz if dimension == 3 => !same(0, 1) || !same(0, 2),
            Couple::Xyz | Couple::Xy => !same(0, 1),
            Couple::Yz => !same(1, 2),
            Couple::Xz => !same(0, 2),
            Couple::None => false,
        }
    }
    /// couple yz and xz need a third dimension.
    pub fn needs_3d(self) -> bool {
        matches!(self, Couple::Yz | Couple::Xz)
    }
}

/// 0.5 Tr(sigma h h^T) for the box matrix h and sigma, both upper triangles in Voigt order
/// (xx yy zz yz xz xy), in pressure x volume units (LAMMPS' compute_strain_energy before the
/// unit conversion).
pub fn strain_trace(s: &[f64; 6], h: &[f64; 6]) -> f64 {
    let d0 = s[0] * (h[0] * h[0] + h[5] * h[5] + h[4] * h[4]) + s[5] * (h[1] * h[5] + h[3] * h[4]) + s[4] * (h[2] * h[4]);
    let d1 = s[5] * (h[5] * h[1] + h[4] * h[3]) + s[1] * (h[1] * h[1] + h[3] * h[3]) + s[3] * (h[2] * h[3]);
    let d2 = s[4] * (h[4] * h[2]) + s[3] * (h[3] * h[2]) + s[2] * (h[2] * h[2]);
    0.5 * (d0 + d1 + d2)
}

/// A flip of a triclinic box (LAMMPS' pre_exchange of fix deform and the barostats): the new
/// tilts `[xy, xz, yz]`, each atom's image flags carried over by the flips `[m, n, p]` (xy,
/// xz, yz: LAMMPS' image_flip, before the remap), the atom remapped into the new box and moved
/// through box fractions once more (LAMMPS migrates them in lamda coordinates).
pub fn flip_box(state: &mut State, tilts: [f64; 3], [m, n, p]: [i32; 3]) -> Result<(), String> {
    let dom = state.domain.as_mut().ok_or("no simulation box")?;
    dom.tilt = Some(tilts);
    let a = &mut state.atoms;
    for i in 0..a.nlocal {
        let img = &mut a.image[i];
        img[1] -= p * img[2];
        img[0] -= m * img[1] + n * img[2];
        dom.remap(&mut a.x[i], img);
        a.x[i] = dom.lamda2x(dom.x2lamda(a.x[i]));
    }
    Ok(())
}

/// The largest tilt a barostat's step may leave, in lengths of the tilt's first dimension.
const TILTMAX: f64 = 1.5;

/// A barostat's half step of the box (LAMMPS' remap): `shear` (the tilts' own barostat, on
/// `h` = [lx ly lz yz xz xy] holding the old lengths, as LAMMPS' domain->h until the box is
/// set) before and after; each length k with `scale[k] = Some((fixed point, factor))` scaled
/// about its fixed point, a triclinic box's tilts that `tilt_scale` (yz, xz, xy) names scaled
/// with the length of their second dimension (y for xy, z for xz and yz; None: a triclinic box
/// is refused); then the atoms (all, or the group `dilate`'s) moved with the box in box
/// fractions (x2lamda, new box, lamda2x). Returns the dilation, for other points that follow
/// the box (rigid bodies' centres).
pub fn dilate_box(state: &mut State, scale: [Option<(f64, f64)>; 3], tilt_scale: Option<[bool; 3]>, shear: Option<&dyn Fn(&mut [f64; 6])>, dilate: Option<u32>) -> Result<Dilation, String> {
    let dom = state.domain.as_mut().ok_or("no simulation box")?;
    if dom.triclinic() && tilt_scale.is_none() {
        return Err("a barostat of rigid bodies on a triclinic box (LAMMPS: does not yet allow triclinic box)".into());
    }
    let old = dom.clone();
    let mut h = old.h();
    if let Some(f) = shear {
        f(&mut h);
    }
    let [syz, sxz, sxy] = tilt_scale.unwrap_or([false; 3]);
    for k in 0..3 {
        if let Some((fixed, expfac)) = scale[k] {
            let (oldlo, oldhi) = (dom.lo[k], dom.hi[k]);
            dom.lo[k] = (oldlo - fixed) * expfac + fixed;
            dom.hi[k] = (oldhi - fixed) * expfac + fixed;
            // xy follows y, xz and yz follow z, when their scaling is on
            if k == 1 && sxy {
                h[5] *= expfac;
            }
            if k == 2 {
                if sxz {
                    h[4] *= expfac;
                }
                if syz {
                    h[3] *= expfac;
                }
            }
        }
    }
    if let Some(f) = shear {
        f(&mut h);
    }
    if let Some(t) = dom.tilt.as_mut() {
        *t = [h[5], h[4], h[3]];
    }
    let prd = dom.prd();
    if (0..3).any(|k| !(prd[k] > 0.0) || !prd[k].is_finite()) {
        return Err(format!("the box length became {prd:?} - simulation unstable"));
    }
    // LAMMPS' TILTMAX: a tilt may not pass 1.5 box lengths in one step
    let [xy, xz, yz] = dom.tilts();
    let beyond = |t: f64, len: f64| t < -TILTMAX * len || t > TILTMAX * len;
    if beyond(yz, prd[1]) || beyond(xz, prd[0]) || beyond(xy, prd[0]) {
        return Err("has tilted box too far in one step - periodic cell is too far from equilibrium state".into());
    }
    let dilation = Dilation::new(&old, dom);
    let a = &mut state.atoms;
    for i in 0..a.nlocal {
        if dilate.is_none_or(|bit| a.mask[i] & bit != 0) {
            dilation.apply(&mut a.x[i]);
        }
    }
    Ok(dilation)
}
