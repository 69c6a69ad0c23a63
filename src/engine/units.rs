//! Unit systems: the conversion constants LAMMPS uses (only lj, si and cgs are supported).

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnitStyle {
    Lj,
    Si,
    Cgs,
}

/// Constants of a unit system, named as in LAMMPS' `Force` class.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Units {
    pub style: UnitStyle,
    /// Boltzmann constant (energy/temperature).
    pub boltz: f64,
    /// mass*velocity^2 -> energy.
    pub mvv2e: f64,
    /// force*time/mass -> velocity.
    pub ftm2v: f64,
    /// N kB T / V -> pressure.
    pub nktv2p: f64,
    /// Default timestep.
    pub dt: f64,
    /// Default neighbour skin.
    pub skin: f64,
}

impl Units {
    pub fn new(style: UnitStyle) -> Units {
        match style {
            UnitStyle::Lj => Units { style, boltz: 1.0, mvv2e: 1.0, ftm2v: 1.0, nktv2p: 1.0, dt: 0.005, skin: 0.3 },
            UnitStyle::Si => Units { style, boltz: 1.3806504e-23, mvv2e: 1.0, ftm2v: 1.0, nktv2p: 1.0, dt: 1.0e-8, skin: 0.001 },
            UnitStyle::Cgs => Units { style, boltz: 1.3806504e-16, mvv2e: 1.0, ftm2v: 1.0, nktv2p: 1.0, dt: 1.0e-8, skin: 0.1 },
        }
    }
    pub fn name(&self) -> &'static str {
        match self.style {
            UnitStyle::Lj => "lj",
            UnitStyle::Si => "si",
            UnitStyle::Cgs => "cgs",
        }
    }
}

impl Default for Units {
    fn default() -> Units {
        Units::new(UnitStyle::Lj)
    }
}
