//! C-printf-compatible number formatting used in LAMMPS-style output.

use dmhs_parser::numfmt::format_g;

/// `%g` (6 significant digits).
pub fn g(x: f64) -> String {
    format_g(x, 6)
}

/// `{:.6g}` as LAMMPS' `Loop time of` line uses it.
pub fn g6(x: f64) -> String {
    format_g(x, 6)
}

/// `%.8g`, as LAMMPS prints box and lattice values.
pub fn g8(x: f64) -> String {
    format_g(x, 8)
}
