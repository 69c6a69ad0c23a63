//! Energy and virial tallies of a force evaluation.

/// Energies and virial from one force evaluation (only filled when asked for).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tally {
    pub evdwl: f64,
    pub ecoul: f64,
    /// xx, yy, zz, xy, xz, yz
    pub virial: [f64; 6],
}

impl Tally {
    pub fn add(&mut self, o: &Tally) {
        self.evdwl += o.evdwl;
        self.ecoul += o.ecoul;
        for k in 0..6 {
            self.virial[k] += o.virial[k];
        }
    }
}

/// Sum tallies in chunk order (deterministic).
pub fn sum_tallies(parts: &[Tally]) -> Tally {
    let mut t = Tally::default();
    for p in parts {
        t.add(p);
    }
    t
}

