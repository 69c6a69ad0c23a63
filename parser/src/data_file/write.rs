//! Writing a data file in the layout of LAMMPS' `write_data`.

use std::fmt::Write as _;

use super::*;

/// The first line LAMMPS' `write_data` writes:
/// `LAMMPS data file via write_data, version VERSION, timestep = N, units = UNITS`.
pub fn write_data_title(version: &str, timestep: i64, units: &str) -> String {
    format!("LAMMPS data file via write_data, version {version}, timestep = {timestep}, units = {units}")
}

/// A float the way `{fmt}`'s `{}` writes it (as LAMMPS' `write_data` writes coordinates and
/// velocities): the shortest digits that read back to the same number, in fixed notation for
/// decimal exponents -4..=15 and otherwise as `d.ddde+XX` (at least two exponent digits).
pub fn format_float(x: f64) -> String {
    if x.is_nan() {
        return "nan".into();
    }
    if x.is_infinite() {
        return if x < 0.0 { "-inf".into() } else { "inf".into() };
    }
    if x == 0.0 {
        return if x.is_sign_negative() { "-0".into() } else { "0".into() };
    }
    // Rust's `{:e}` gives the shortest round-trip digits: `-1.2345e-7`
    let e = format!("{:e}", x);
    let (mant, exp) = e.split_once('e').unwrap_or((&e, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let neg = mant.starts_with('-');
    let digits: String = mant.chars().filter(|c| c.is_ascii_digit()).collect();
    let mut out = String::new();
    if neg {
        out.push('-');
    }
    if !(-4..16).contains(&exp) {
        out.push_str(&digits[..1]);
        if digits.len() > 1 {
            out.push('.');
            out.push_str(&digits[1..]);
        }
        let _ = write!(out, "e{}{:02}", if exp < 0 { '-' } else { '+' }, exp.abs());
    } else if exp >= 0 {
        let int_len = exp as usize + 1;
        if digits.len() <= int_len {
            out.push_str(&digits);
            out.push_str(&"0".repeat(int_len - digits.len()));
        } else {
            out.push_str(&digits[..int_len]);
            out.push('.');
            out.push_str(&digits[int_len..]);
        }
    } else {
        out.push_str("0.");
        out.push_str(&"0".repeat((-exp - 1) as usize));
        out.push_str(&digits);
    }
    out
}

impl DataFile {
    /// The file in LAMMPS' `write_data` layout: title, counts, box, type labels, Masses,
    /// coefficient sections with their `# style`, `Atoms # style` with image flags, Velocities,
    /// Bonds, Angles, Dihedrals, Impropers. Counts are the lengths of the vectors; topology
    /// lines are numbered from 1 as LAMMPS numbers them.
    pub fn write(&self, layout: &AtomLayout) -> String {
        let h = &self.header;
        let mut s = String::new();
        let _ = writeln!(s, "{}\n", self.title);
        let _ = writeln!(s, "{} atoms\n{} atom types", self.atoms.len(), h.atom_types);
        let counts = [
            (TypeKind::Bond, self.bonds.len()),
            (TypeKind::Angle, self.angles.len()),
            (TypeKind::Dihedral, self.dihedrals.len()),
            (TypeKind::Improper, self.impropers.len()),
        ];
        for (k, n) in counts {
            if layout.allows(k) && (n > 0 || h.types(k) > 0) {
                let _ = writeln!(s, "{n} {}s\n{} {} types", k.name(), h.types(k), k.name());
            }
        }
        s.push('\n');
        for (d, axis) in ["x", "y", "z"].iter().enumerate() {
            let _ = writeln!(s, "{} {} {axis}lo {axis}hi", format_float(h.boxlo[d]), format_float(h.boxhi[d]));
        }
        if let Some(t) = h.tilt {
            let _ = writeln!(s, "{} {} {} xy xz yz", format_float(t[0]), format_float(t[1]), format_float(t[2]));
        }
        for k in TypeKind::ALL {
            let labels = self.type_labels.of(k);
            if !labels.is_empty() {
                let _ = writeln!(s, "\n{} Type Labels\n", k.title());
                for (i, l) in labels.iter().enumerate() {
                    let _ = writeln!(s, "{} {}", i + 1, l.text);
                }
            }
        }
        if !self.masses.is_empty() {
            s.push_str("\nMasses\n\n");
            for m in &self.masses {
                let _ = writeln!(s, "{} {}", m.atom_type, format_float(m.mass));
            }
        }
        for sec in &self.coeffs {
            match (&sec.style, sec.kind.has_style_comment()) {
                (Some(st), true) => {
                    let _ = writeln!(s, "\n{} # {}\n", sec.kind.section_name(), st.text);
                }
                _ => {
                    let _ = writeln!(s, "\n{}\n", sec.kind.section_name());
                }
            }
            for l in &sec.lines {
                let mut parts: Vec<String> = l.types.iter().map(|t| t.to_string()).collect();
                parts.extend(l.args.iter().map(|w| w.text.clone()));
                let _ = writeln!(s, "{}", parts.join(" "));
            }
        }
        if !self.atoms.is_empty() {
            let _ = writeln!(s, "\nAtoms # {}\n", layout.style);
            for a in &self.atoms {
                let mut parts: Vec<String> = vec![];
                for c in &layout.atoms {
                    parts.push(match c {
                        C::Id => a.id.to_string(),
                        C::Type => a.atom_type.to_string(),
                        C::Molecule => a.molecule.to_string(),
                        _ => format_float(a.get(*c).unwrap_or(0.0)),
                    });
                }
                let _ = writeln!(s, "{} {} {} {}", parts.join(" "), a.image[0], a.image[1], a.image[2]);
            }
        }
        if let Some(vels) = &self.velocities {
            if !vels.is_empty() {
                s.push_str("\nVelocities\n\n");
                for v in vels {
                    let parts: Vec<String> = layout
                        .velocities
                        .iter()
                        .map(|c| if *c == C::Id { v.id.to_string() } else { format_float(v.get(*c).unwrap_or(0.0)) })
                        .collect();
                    let _ = writeln!(s, "{}", parts.join(" "));
                }
            }
        }
        write_topology(&mut s, "Bonds", &self.bonds);
        write_topology(&mut s, "Angles", &self.angles);
        write_topology(&mut s, "Dihedrals", &self.dihedrals);
        write_topology(&mut s, "Impropers", &self.impropers);
        s
    }
}

fn write_topology<const N: usize>(s: &mut String, name: &str, lines: &[TopoLine<N>]) {
    if lines.is_empty() {
        return;
    }
    let _ = writeln!(s, "\n{name}\n");
    for (i, l) in lines.iter().enumerate() {
        let _ = write!(s, "{} {}", i + 1, l.topo_type);
        for a in &l.atoms {
            let _ = write!(s, " {a}");
        }
        s.push('\n');
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_are_written_like_fmt() {
        // values observed in LAMMPS 22 Jul 2025 write_data output
        let cases = [
            (0.30000000000000004, "0.30000000000000004"),
            (1e-5, "1e-05"),
            (1e-4, "0.0001"),
            (0.0001234567, "0.0001234567"),
            (1e15, "1000000000000000"),
            (1e16, "1e+16"),
            (1234567890123456.8, "1234567890123456.8"),
            (12345678901234567.0, "1.2345678901234568e+16"),
            (1e300, "1e+300"),
            (2.5e-310, "2.5e-310"),
            (-0.0, "-0"),
            (0.0, "0"),
            (-1e20, "-1e+20"),
            (12.149999999999999, "12.149999999999999"),
            (-3.0374999999999996, "-3.0374999999999996"),
            (3.906121284557794e-16, "3.906121284557794e-16"),
        ];
        for (x, s) in cases {
            assert_eq!(format_float(x), s, "{x:e}");
            assert_eq!(s.parse::<f64>().unwrap().to_bits(), x.to_bits());
        }
    }
}
