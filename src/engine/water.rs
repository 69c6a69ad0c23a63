//! The water field of the paper's cleaning model (Eqs 26-27): every particle carries a water
//! mass `w_i`; its concentration is the closure `c_i = w_i rho_i / m_i` (Eq 27 solved for c),
//! with `rho_i` the SPH density and `m_i` the per-type mass (the mass SPH pair styles use).
//!
//! The water mass is the stored variable because it is what Eq 26 conserves: the pair terms of
//! `dmhs/sph/diffusion` are antisymmetric in w, so the sum of w over particles that all
//! integrate it is constant to round-off, whatever their densities do. Storage: extra per-atom
//! arrays (sorted, deleted and restarted with the atoms); `dmhs/water` is carried by ghosts
//! (pair styles read neighbours' concentrations), its rate `dmhs/dwater` is owned-only and is
//! zeroed before every force pass like `desph`.

use crate::engine::atoms::Atoms;
use crate::engine::fields::{Field, WATER, WATER_RATE};

/// Register the water arrays (no-op if present). Removes ghosts if it has to add an array.
pub fn ensure_fields(atoms: &mut Atoms) {
    if atoms.field(WATER).is_none() || atoms.field(WATER_RATE).is_none() {
        atoms.clear_ghosts();
        atoms.add_field(WATER);
        atoms.add_field(WATER_RATE);
    }
}

/// Concentration c = w rho / m of atom `i` (owned or ghost) given its water mass.
#[inline(always)]
pub fn conc_of(w: f64, rho: f64, m: f64) -> f64 {
    w * rho / m
}

/// The water masses of all atoms (owned, then ghosts), if the field exists.
pub fn water(atoms: &Atoms) -> Option<&[f64]> {
    atoms.field_values(WATER)
}

/// Concentration of owned atom `i` (0 without a water field or a density).
pub fn conc(atoms: &Atoms, type_mass: &[f64], i: usize) -> f64 {
    match water(atoms) {
        Some(w) if atoms.features.sph => {
            let m = type_mass.get(atoms.typ[i]).copied().unwrap_or(0.0);
            if m > 0.0 { conc_of(w[i], atoms.rho[i], m) } else { 0.0 }
        }
        _ => 0.0,
    }
}

/// Value of a field for owned atom `i` (0 if no model registered it).
pub fn field_value(atoms: &Atoms, f: Field, i: usize) -> f64 {
    atoms.field_values(f).map(|v| v[i]).unwrap_or(0.0)
}

/// `set ... dmhs/conc c` (w = c m / rho, with the current density and type mass) or
/// `set ... dmhs/water w`, on the selected owned atoms. Errors name the atom that cannot take it.
pub fn set(atoms: &mut Atoms, type_mass: &[f64], mass_set: &[bool], selected: &[bool], keyword: &str, value: &dyn Fn(usize) -> f64) -> Result<(), String> {
    if !atoms.features.sph {
        return Err(format!("set {keyword} needs an atom style with SPH attributes (the concentration closure c = w rho/m uses the SPH density)"));
    }
    ensure_fields(atoms);
    let k = atoms.add_field(WATER);
    for (i, _) in selected.iter().enumerate().take(atoms.nlocal).filter(|(_, &s)| s) {
        let w = if keyword == "dmhs/conc" {
            let t = atoms.typ[i];
            if !mass_set.get(t).copied().unwrap_or(false) {
                return Err(format!("set dmhs/conc: the mass of atom type {t} is not set yet (w = c m/rho needs it: give `mass` first)"));
            }
            if atoms.rho[i] <= 0.0 {
                return Err(format!("set dmhs/conc: atom {} has density {} (w = c m/rho needs rho > 0: set sph/rho first)", atoms.tag[i], atoms.rho[i]));
            }
            value(i) * type_mass[t] / atoms.rho[i]
        } else {
            value(i)
        };
        atoms.extra[k].data[i] = w;
    }
    Ok(())
}

/// Volume of a particle of radius r: 4/3 pi r^3 in 3D, pi r^2 per unit depth in 2D.
pub fn volume_of_radius(r: f64, dim: usize) -> f64 {
    if dim == 3 { 4.0 / 3.0 * std::f64::consts::PI * r * r * r } else { std::f64::consts::PI * r * r }
}

/// Inverse of [`volume_of_radius`].
pub fn radius_of_volume(v: f64, dim: usize) -> f64 {
    if dim == 3 { (3.0 * v / (4.0 * std::f64::consts::PI)).cbrt() } else { (v / std::f64::consts::PI).sqrt() }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::atoms::{AtomFeatures, NewAtom};

    #[test]
    fn set_conc_uses_the_closure() {
        let mut a = Atoms::new(AtomFeatures { sph: true, ..Default::default() });
        let mut n = NewAtom::at(1, 1, [0.0; 3]);
        n.rho = 1800.0;
        a.push(&n);
        let mass = [0.0, 2.0];
        set(&mut a, &mass, &[false, true], &[true], "dmhs/conc", &|_| 0.3).unwrap();
        assert_eq!(water(&a).unwrap()[0], 0.3 * 2.0 / 1800.0);
        assert!((conc(&a, &mass, 0) - 0.3).abs() < 1e-15);
        assert!(set(&mut a, &mass, &[false, false], &[true], "dmhs/conc", &|_| 0.3).unwrap_err().contains("mass of atom type 1"));
        set(&mut a, &mass, &[false, false], &[true], "dmhs/water", &|_| 5.0).unwrap();
        assert_eq!(water(&a).unwrap()[0], 5.0);
    }

    #[test]
    fn radius_and_volume_are_inverse() {
        for dim in [2, 3] {
            let r = 2.35e-5;
            assert!((radius_of_volume(volume_of_radius(r, dim), dim) - r).abs() < 1e-18);
        }
        assert!((volume_of_radius(1.0, 3) - 4.18879020478639).abs() < 1e-12);
    }
}
