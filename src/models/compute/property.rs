//! Per-atom quantities by their LAMMPS names, shared by `compute property/atom`,
//! `compute reduce`, `dump custom` and atom references in expressions (`x[12]`).

use crate::engine::state::State;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    Id,
    Mol,
    Proc,
    Type,
    Mass,
    X(usize),
    Xs(usize),
    Xu(usize),
    Image(usize),
    V(usize),
    F(usize),
    Q,
    Radius,
    Diameter,
    Omega(usize),
    Torque(usize),
    /// Orientation component w, i, j, k (`quatw` ...; atom_style bpm/sphere).
    Quat(usize),
    Rho,
    Drho,
    Esph,
    Desph,
    Cv,
    Vest(usize),
    /// Water concentration c = w rho/m, water mass w, and its rate (dmhs/sph/diffusion).
    Conc,
    Water,
    DWater,
    /// Per-atom temperature and heat flow (fix property/atom temperature heatflow).
    Temperature,
    HeatFlow,
    /// A named per-atom value a model keeps (`d_psi` of pair granular mdr).
    Extra(crate::engine::fields::Field),
}

impl Field {
    /// Parse a LAMMPS per-atom keyword.
    pub fn parse(name: &str) -> Option<Field> {
        let axis = |c: &str| match c {
            "x" => Some(0),
            "y" => Some(1),
            "z" => Some(2),
            _ => None,
        };
        Some(match name {
            "id" => Field::Id,
            "mol" => Field::Mol,
            "proc" => Field::Proc,
            "type" => Field::Type,
            "mass" => Field::Mass,
            "x" | "y" | "z" => Field::X(axis(name)?),
            "xs" | "ys" | "zs" => Field::Xs(axis(&name[..1])?),
            "xu" | "yu" | "zu" => Field::Xu(axis(&name[..1])?),
            "ix" | "iy" | "iz" => Field::Image(axis(&name[1..])?),
            "vx" | "vy" | "vz" => Field::V(axis(&name[1..])?),
            "fx" | "fy" | "fz" => Field::F(axis(&name[1..])?),
            "q" => Field::Q,
            "radius" => Field::Radius,
            "diameter" => Field::Diameter,
            "omegax" | "omegay" | "omegaz" => Field::Omega(axis(&name[5..])?),
            "tqx" | "tqy" | "tqz" => Field::Torque(axis(&name[2..])?),
            "quatw" => Field::Quat(0),
            "quati" => Field::Quat(1),
            "quatj" => Field::Quat(2),
            "quatk" => Field::Quat(3),
            "rho" => Field::Rho,
            "drho" => Field::Drho,
            "esph" => Field::Esph,
            "desph" => Field::Desph,
            "cv" => Field::Cv,
            "vxest" | "vyest" | "vzest" => Field::Vest(axis(&name[1..2])?),
            "conc" => Field::Conc,
            "water" => Field::Water,
            "dwater" => Field::DWater,
            "temperature" => Field::Temperature,
            "heatflow" => Field::HeatFlow,
            _ => Field::Extra(*crate::engine::fields::MDR_FIELDS.iter().find(|f| f.name == name)?),
        })
    }

    /// Whether the atom style has this quantity (an error message if not).
    pub fn check(&self, state: &State) -> Result<(), String> {
        let ft = state.atoms.features;
        let (ok, what) = match self {
            Field::Mol => (ft.molecule, "molecule IDs"),
            Field::Q => (ft.charge, "charges"),
            Field::Radius | Field::Diameter | Field::Omega(_) | Field::Torque(_) => (ft.sphere, "sphere attributes (atom_style sphere)"),
            Field::Quat(_) => (ft.quat, "orientations (atom_style bpm/sphere)"),
            Field::Rho | Field::Drho | Field::Esph | Field::Desph | Field::Cv | Field::Vest(_) => (ft.sph, "SPH attributes (atom_style sph)"),
            Field::Conc | Field::Water | Field::DWater => (state.atoms.field(crate::engine::fields::WATER).is_some(), "water field (define fix dmhs/diffusion or set ... dmhs/conc first)"),
            Field::Temperature => (state.atoms.field(crate::engine::fields::TEMPERATURE).is_some(), "temperature (define fix property/atom temperature first)"),
            Field::HeatFlow => (state.atoms.field(crate::engine::fields::HEATFLOW).is_some(), "heatflow (define fix property/atom heatflow first)"),
            Field::Extra(f) => (state.atoms.field(*f).is_some(), "such per-atom value (pair granular mdr makes it at its pair_coeff)"),
            _ => (true, ""),
        };
        if ok { Ok(()) } else { Err(format!("this atom style has no {what}")) }
    }

    /// True if the value is an integer (for dump formats).
    pub fn is_int(&self) -> bool {
        matches!(self, Field::Id | Field::Mol | Field::Proc | Field::Type | Field::Image(_))
    }

    /// Value for owned atom `i` (the field must pass `check`).
    #[inline]
    pub fn value(&self, state: &State, i: usize) -> f64 {
        let a = &state.atoms;
        match *self {
            Field::Id => a.tag[i] as f64,
            Field::Mol => a.molecule[i] as f64,
            Field::Proc => 0.0,
            Field::Type => a.typ[i] as f64,
            Field::Mass => state.mass(i),
            Field::X(d) => a.x[i][d],
            Field::Xs(d) => {
                let dom = state.domain.as_ref().unwrap();
                if dom.triclinic() {
                    return dom.x2lamda(a.x[i])[d];
                }
                (a.x[i][d] - dom.lo[d]) / (dom.hi[d] - dom.lo[d])
            }
            Field::Xu(d) => {
                let dom = state.domain.as_ref().unwrap();
                if dom.triclinic() {
                    // LAMMPS' dump custom adds the image terms one by one (Domain::unmap sums
                    // them first)
                    let (h, m) = (dom.h(), a.image[i].map(|k| k as f64));
                    return match d {
                        0 => a.x[i][0] + h[0] * m[0] + h[5] * m[1] + h[4] * m[2],
                        1 => a.x[i][1] + h[1] * m[1] + h[3] * m[2],
                        _ => a.x[i][2] + h[2] * m[2],
                    };
                }
                a.x[i][d] + a.image[i][d] as f64 * (dom.hi[d] - dom.lo[d])
            }
            Field::Image(d) => a.image[i][d] as f64,
            Field::V(d) => a.v[i][d],
            Field::F(d) => a.f[i][d],
            Field::Q => a.q[i],
            Field::Radius => a.radius[i],
            Field::Diameter => 2.0 * a.radius[i],
            Field::Omega(d) => a.omega[i][d],
            Field::Torque(d) => a.torque[i][d],
            Field::Quat(d) => a.quat[i][d],
            Field::Rho => a.rho[i],
            Field::Drho => a.drho[i],
            Field::Esph => a.esph[i],
            Field::Desph => a.desph[i],
            Field::Cv => a.cv[i],
            Field::Vest(d) => a.vest[i][d],
            Field::Conc => crate::engine::water::conc(a, &state.type_mass, i),
            Field::Water => crate::engine::water::field_value(a, crate::engine::fields::WATER, i),
            Field::DWater => crate::engine::water::field_value(a, crate::engine::fields::WATER_RATE, i),
            Field::Temperature => crate::engine::water::field_value(a, crate::engine::fields::TEMPERATURE, i),
            Field::HeatFlow => crate::engine::water::field_value(a, crate::engine::fields::HEATFLOW, i),
            Field::Extra(f) => crate::engine::water::field_value(a, f, i),
        }
    }
}
