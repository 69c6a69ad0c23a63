//! The `lattice` command: a unit cell (primitive vectors a1 a2 a3 and basis atoms), its
//! orientation and origin, and the scale that turns lattice units into box units, computed
//! exactly as LAMMPS' `Lattice` class does (same formulas, same floating-point order), so
//! that `create_atoms` and `units lattice` give LAMMPS' coordinates to the last bit.

// Index loops mirror LAMMPS' formulas term by term (same evaluation order).
#![allow(clippy::needless_range_loop)]

use crate::engine::units::{UnitStyle, Units};
use dmhs_parser::{Args, Command, DResult};

const SYNTAX: &str = "lattice style scale keyword values ... \
(style = none|sc|bcc|fcc|hcp|diamond|sq|sq2|hex|custom; keywords: origin x y z, \
orient x|y|z i j k, spacing dx dy dz, a1|a2|a3 x y z, basis x y z)";

/// Sentinel LAMMPS uses to seed min/max searches.
const BIG: f64 = 1.0e30;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LatticeStyle {
    None,
    Sc,
    Bcc,
    Fcc,
    Hcp,
    Diamond,
    Sq,
    Sq2,
    Hex,
    Custom,
}

const STYLE_NAMES: [&str; 10] = ["none", "sc", "bcc", "fcc", "hcp", "diamond", "sq", "sq2", "hex", "custom"];
const STYLES: [LatticeStyle; 10] = [
    LatticeStyle::None,
    LatticeStyle::Sc,
    LatticeStyle::Bcc,
    LatticeStyle::Fcc,
    LatticeStyle::Hcp,
    LatticeStyle::Diamond,
    LatticeStyle::Sq,
    LatticeStyle::Sq2,
    LatticeStyle::Hex,
    LatticeStyle::Custom,
];

impl LatticeStyle {
    pub fn name(self) -> &'static str {
        STYLE_NAMES[STYLES.iter().position(|s| *s == self).unwrap_or(0)]
    }
    fn is_3d_only(self) -> bool {
        matches!(
            self,
            LatticeStyle::Sc | LatticeStyle::Bcc | LatticeStyle::Fcc | LatticeStyle::Hcp | LatticeStyle::Diamond
        )
    }
    fn is_2d_only(self) -> bool {
        matches!(self, LatticeStyle::Sq | LatticeStyle::Sq2 | LatticeStyle::Hex)
    }
}

/// A lattice as LAMMPS defines it. `xlattice`, `ylattice`, `zlattice` are the spacings used
/// by `units lattice` everywhere (regions, create_atoms single, velocity).
#[derive(Clone, Debug, PartialEq)]
pub struct Lattice {
    pub style: LatticeStyle,
    /// Lattice-to-box scale factor (for `lj` units: derived from the reduced density).
    pub scale: f64,
    pub xlattice: f64,
    pub ylattice: f64,
    pub zlattice: f64,
    /// Basis atoms in fractional unit-cell coordinates (empty for style `none`).
    pub basis: Vec<[f64; 3]>,
    pub origin: [f64; 3],
    /// Orientation vectors of the box x, y, z axes in lattice coordinates.
    pub orient: [[i32; 3]; 3],
    pub a1: [f64; 3],
    pub a2: [f64; 3],
    pub a3: [f64; 3],
    primitive: [[f64; 3]; 3],
    priminv: [[f64; 3]; 3],
    rotaterow: [[f64; 3]; 3],
    rotatecol: [[f64; 3]; 3],
}

fn cross3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl Lattice {
    /// `lattice none spacing`: no basis, only spacings (LAMMPS starts with `none 1.0`).
    pub fn none(spacing: f64) -> Lattice {
        let id = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        Lattice {
            style: LatticeStyle::None,
            scale: 1.0,
            xlattice: spacing,
            ylattice: spacing,
            zlattice: spacing,
            basis: vec![],
            origin: [0.0; 3],
            orient: [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
            a1: id[0],
            a2: id[1],
            a3: id[2],
            primitive: id,
            priminv: id,
            rotaterow: id,
            rotatecol: id,
        }
    }

    pub fn is_none(&self) -> bool {
        self.style == LatticeStyle::None
    }

    pub fn nbasis(&self) -> usize {
        self.basis.len()
    }

    /// The spacings `[xlattice, ylattice, zlattice]`.
    pub fn spacing(&self) -> [f64; 3] {
        [self.xlattice, self.ylattice, self.zlattice]
    }

    /// Parse a `lattice` command. `units` decides the meaning of the scale (reduced density
    /// for `lj`, lattice constant otherwise); `dimension` is 2 or 3.
    pub fn from_lammps(cmd: &Command, units: &Units, dimension: usize) -> DResult<Lattice> {
        let mut a = Args::new(cmd, SYNTAX);
        let style_word = a.peek();
        let style = STYLES[a.choice("lattice style", &STYLE_NAMES)?];
        let style_word = style_word.unwrap();

        if style == LatticeStyle::None {
            let spacing = a.positive_f64("lattice spacing")?;
            a.finish()?;
            return Ok(Lattice::none(spacing));
        }
        if dimension == 2 && style.is_3d_only() {
            return Err(a.error_at(
                style_word,
                format!("lattice style `{}` is incompatible with a 2d simulation", style.name()),
                "3d lattice style",
            ));
        }
        if dimension == 3 && style.is_2d_only() {
            return Err(a.error_at(
                style_word,
                format!("lattice style `{}` is incompatible with a 3d simulation", style.name()),
                "2d lattice style",
            ));
        }
        let mut scale = a.positive_f64("lattice scale")?;

        let mut basis: Vec<[f64; 3]> = match style {
            LatticeStyle::Sc | LatticeStyle::Sq => vec![[0.0, 0.0, 0.0]],
            LatticeStyle::Bcc => vec![[0.0, 0.0, 0.0], [0.5, 0.5, 0.5]],
            LatticeStyle::Fcc => vec![[0.0, 0.0, 0.0], [0.5, 0.5, 0.0], [0.5, 0.0, 0.5], [0.0, 0.5, 0.5]],
            LatticeStyle::Hcp => vec![[0.0, 0.0, 0.0], [0.5, 0.5, 0.0], [0.5, 5.0 / 6.0, 0.5], [0.0, 1.0 / 3.0, 0.5]],
            LatticeStyle::Sq2 | LatticeStyle::Hex => vec![[0.0, 0.0, 0.0], [0.5, 0.5, 0.0]],
            LatticeStyle::Diamond => vec![
                [0.0, 0.0, 0.0],
                [0.0, 0.5, 0.5],
                [0.5, 0.0, 0.5],
                [0.5, 0.5, 0.0],
                [0.25, 0.25, 0.25],
                [0.25, 0.75, 0.75],
                [0.75, 0.25, 0.75],
                [0.75, 0.75, 0.25],
            ],
            LatticeStyle::Custom | LatticeStyle::None => vec![],
        };

        let mut origin = [0.0; 3];
        let mut orient = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
        let mut spacing: Option<[f64; 3]> = None;
        let mut a1 = [1.0, 0.0, 0.0];
        let mut a2 = [0.0, 1.0, 0.0];
        let mut a3 = [0.0, 0.0, 1.0];
        if style == LatticeStyle::Hex {
            a2[1] = 3.0f64.sqrt();
        }
        if style == LatticeStyle::Hcp {
            a2[1] = 3.0f64.sqrt();
            a3[2] = (8.0f64 / 3.0).sqrt();
        }

        const KEYWORDS: [&str; 8] = ["origin", "orient", "spacing", "a1", "a2", "a3", "basis", "triclinic/general"];
        let mut origin_word = None;
        let mut orient_word = None;
        let mut a_word = None;
        let mut basis_words = vec![];
        while let Some(kw) = a.peek() {
            a.skip(1);
            match kw.text.as_str() {
                "origin" => {
                    for (d, what) in ["origin x", "origin y", "origin z"].iter().enumerate() {
                        origin[d] = a.f64_where(what, "in [0, 1)", |x| (0.0..1.0).contains(&x))?;
                    }
                    origin_word = Some(kw);
                }
                "orient" => {
                    let dim = a.choice("orient axis", &["x", "y", "z"])?;
                    for k in 0..3 {
                        orient[dim][k] = a.i64_in("orient component", i32::MIN as i64, i32::MAX as i64)? as i32;
                    }
                    orient_word = Some(kw);
                }
                "spacing" => {
                    let mut s = [0.0; 3];
                    for (d, what) in ["spacing x", "spacing y", "spacing z"].iter().enumerate() {
                        s[d] = a.positive_f64(what)?;
                    }
                    spacing = Some(s);
                }
                "a1" | "a2" | "a3" | "basis" => {
                    if style != LatticeStyle::Custom {
                        return Err(a.error_at(
                            kw,
                            format!("keyword `{}` is only valid for lattice style custom", kw.text),
                            "needs style custom",
                        ));
                    }
                    let mut v = [0.0; 3];
                    if kw.text == "basis" {
                        for (d, what) in ["basis x", "basis y", "basis z"].iter().enumerate() {
                            v[d] = a.f64_where(what, "in [0, 1)", |x| (0.0..1.0).contains(&x))?;
                        }
                        basis.push(v);
                        basis_words.push(kw);
                    } else {
                        for (d, what) in ["x", "y", "z"].iter().enumerate() {
                            v[d] = a.f64(&format!("{} {what}", kw.text))?;
                        }
                        match kw.text.as_str() {
                            "a1" => a1 = v,
                            "a2" => a2 = v,
                            _ => a3 = v,
                        }
                        a_word = Some(kw);
                    }
                }
                "triclinic/general" => {
                    return Err(a.error_at(kw, "lattice triclinic/general is not supported", "not supported"));
                }
                _ => return Err(a.unknown_keyword(kw, &KEYWORDS)),
            }
        }

        // The same validity checks as LAMMPS, in the same order.
        if basis.is_empty() {
            return Err(a.error_at(style_word, "no basis atoms in lattice", "custom lattice without `basis`"));
        }
        let o = orient;
        let odot = |p: [i32; 3], q: [i32; 3]| {
            p[0] as i64 * q[0] as i64 + p[1] as i64 * q[1] as i64 + p[2] as i64 * q[2] as i64
        };
        let at_orient = |msg: &str| match orient_word {
            Some(w) => a.error_at(w, msg.to_string(), "orient vectors"),
            None => a.error_at(style_word, msg.to_string(), "orient vectors"),
        };
        if odot(o[0], o[1]) != 0 || odot(o[1], o[2]) != 0 || odot(o[0], o[2]) != 0 {
            return Err(at_orient("lattice orient vectors are not orthogonal"));
        }
        let xy = [
            o[0][1] as i64 * o[1][2] as i64 - o[0][2] as i64 * o[1][1] as i64,
            o[0][2] as i64 * o[1][0] as i64 - o[0][0] as i64 * o[1][2] as i64,
            o[0][0] as i64 * o[1][1] as i64 - o[0][1] as i64 * o[1][0] as i64,
        ];
        if xy[0] * o[2][0] as i64 + xy[1] * o[2][1] as i64 + xy[2] * o[2][2] as i64 <= 0 {
            return Err(at_orient("lattice orient vectors are not right-handed"));
        }
        let at_a = |msg: &str| match a_word {
            Some(w) => a.error_at(w, msg.to_string(), "primitive vectors"),
            None => a.error_at(style_word, msg.to_string(), "primitive vectors"),
        };
        let len3 = |v: [f64; 3]| dot3(v, v).sqrt();
        if len3(cross3(a1, a2)) == 0.0 || len3(cross3(a2, a3)) == 0.0 || len3(cross3(a1, a3)) == 0.0 {
            return Err(at_a("lattice primitive vectors are collinear"));
        }
        if dimension == 2 {
            if origin[2] != 0.0 {
                let w = origin_word.unwrap_or(style_word);
                return Err(a.error_at(w, "lattice origin z coord must be 0.0 for a 2d simulation", "z must be 0"));
            }
            if a1[2] != 0.0 || a2[2] != 0.0 || a3[0] != 0.0 || a3[1] != 0.0 {
                return Err(at_a("lattice a1/a2/a3 vectors are not compatible with a 2d simulation"));
            }
            if o[0][2] != 0 || o[1][2] != 0 || o[2][0] != 0 || o[2][1] != 0 {
                return Err(at_orient("lattice orient vectors are not compatible with a 2d simulation"));
            }
            if let Some(k) = basis.iter().position(|b| b[2] != 0.0) {
                let w = basis_words.get(k).copied().unwrap_or(style_word);
                return Err(a.error_at(
                    w,
                    "lattice basis atom z coords must be zero for a 2d simulation",
                    "z must be 0",
                ));
            }
        }

        // lj units: the scale argument is a reduced density rho*;
        // scale = (nbasis / (Vprimitive * rho*))^(1/dim).
        if units.style == UnitStyle::Lj {
            let volume = dot3(a1, cross3(a2, a3)).abs();
            scale = (basis.len() as f64 / volume / scale).powf(1.0 / dimension as f64);
        }

        let mut lat = Lattice {
            style,
            scale,
            xlattice: 0.0,
            ylattice: 0.0,
            zlattice: 0.0,
            basis,
            origin,
            orient,
            a1,
            a2,
            a3,
            primitive: [[0.0; 3]; 3],
            priminv: [[0.0; 3]; 3],
            rotaterow: [[0.0; 3]; 3],
            rotatecol: [[0.0; 3]; 3],
        };
        if !lat.setup_transform() {
            return Err(at_a("degenerate lattice primitive vectors"));
        }

        match spacing {
            None => {
                // Spacings = extent of the unit cell's 8 corners in box space (with the
                // spacings still 0 so the origin shift does not enter).
                let mut lo = [BIG; 3];
                let mut hi = [-BIG; 3];
                for corner in 0..8 {
                    let p = [(corner & 1) as f64, ((corner >> 1) & 1) as f64, ((corner >> 2) & 1) as f64];
                    let q = lat.lattice2box(p);
                    for d in 0..3 {
                        lo[d] = if q[d] < lo[d] { q[d] } else { lo[d] };
                        hi[d] = if q[d] > hi[d] { q[d] } else { hi[d] };
                    }
                }
                lat.xlattice = hi[0] - lo[0];
                lat.ylattice = hi[1] - lo[1];
                lat.zlattice = hi[2] - lo[2];
            }
            Some(s) => {
                lat.xlattice = s[0] * lat.scale;
                lat.ylattice = s[1] * lat.scale;
                lat.zlattice = s[2] * lat.scale;
            }
        }
        Ok(lat)
    }

    /// Build the primitive matrix (columns a1 a2 a3), its inverse and the orientation
    /// rotation, as LAMMPS `setup_transform`. False if the primitive vectors are degenerate.
    fn setup_transform(&mut self) -> bool {
        let p = [
            [self.a1[0], self.a2[0], self.a3[0]],
            [self.a1[1], self.a2[1], self.a3[1]],
            [self.a1[2], self.a2[2], self.a3[2]],
        ];
        self.primitive = p;
        let det = p[0][0] * p[1][1] * p[2][2] + p[0][1] * p[1][2] * p[2][0] + p[0][2] * p[1][0] * p[2][1]
            - p[0][0] * p[1][2] * p[2][1]
            - p[0][1] * p[1][0] * p[2][2]
            - p[0][2] * p[1][1] * p[2][0];
        if det == 0.0 {
            return false;
        }
        let mut q = [[0.0; 3]; 3];
        q[0][0] = (p[1][1] * p[2][2] - p[1][2] * p[2][1]) / det;
        q[1][0] = (p[1][2] * p[2][0] - p[1][0] * p[2][2]) / det;
        q[2][0] = (p[1][0] * p[2][1] - p[1][1] * p[2][0]) / det;
        q[0][1] = (p[0][2] * p[2][1] - p[0][1] * p[2][2]) / det;
        q[1][1] = (p[0][0] * p[2][2] - p[0][2] * p[2][0]) / det;
        q[2][1] = (p[0][1] * p[2][0] - p[0][0] * p[2][1]) / det;
        q[0][2] = (p[0][1] * p[1][2] - p[0][2] * p[1][1]) / det;
        q[1][2] = (p[0][2] * p[1][0] - p[0][0] * p[1][2]) / det;
        q[2][2] = (p[0][0] * p[1][1] - p[0][1] * p[1][0]) / det;
        self.priminv = q;
        for r in 0..3 {
            let o = self.orient[r];
            let lensq = o[0] * o[0] + o[1] * o[1] + o[2] * o[2];
            let length = (lensq as f64).sqrt();
            if length == 0.0 {
                return false;
            }
            for c in 0..3 {
                self.rotaterow[r][c] = o[c] as f64 / length;
                self.rotatecol[c][r] = self.rotaterow[r][c];
            }
        }
        true
    }

    /// Lattice coordinates -> box coordinates: `R * scale * P * x + spacing * origin`.
    pub fn lattice2box(&self, x: [f64; 3]) -> [f64; 3] {
        let p = &self.primitive;
        let r = &self.rotaterow;
        let mut x1 = p[0][0] * x[0] + p[0][1] * x[1] + p[0][2] * x[2];
        let mut y1 = p[1][0] * x[0] + p[1][1] * x[1] + p[1][2] * x[2];
        let mut z1 = p[2][0] * x[0] + p[2][1] * x[1] + p[2][2] * x[2];
        x1 *= self.scale;
        y1 *= self.scale;
        z1 *= self.scale;
        let xnew = r[0][0] * x1 + r[0][1] * y1 + r[0][2] * z1;
        let ynew = r[1][0] * x1 + r[1][1] * y1 + r[1][2] * z1;
        let znew = r[2][0] * x1 + r[2][1] * y1 + r[2][2] * z1;
        [
            xnew + self.xlattice * self.origin[0],
            ynew + self.ylattice * self.origin[1],
            znew + self.zlattice * self.origin[2],
        ]
    }

    /// Box coordinates -> lattice coordinates (inverse of [`Lattice::lattice2box`]).
    pub fn box2lattice(&self, x: [f64; 3]) -> [f64; 3] {
        let x0 = x[0] - self.xlattice * self.origin[0];
        let y0 = x[1] - self.ylattice * self.origin[1];
        let z0 = x[2] - self.zlattice * self.origin[2];
        let c = &self.rotatecol;
        let q = &self.priminv;
        let mut x1 = c[0][0] * x0 + c[0][1] * y0 + c[0][2] * z0;
        let mut y1 = c[1][0] * x0 + c[1][1] * y0 + c[1][2] * z0;
        let mut z1 = c[2][0] * x0 + c[2][1] * y0 + c[2][2] * z0;
        x1 /= self.scale;
        y1 /= self.scale;
        z1 /= self.scale;
        [
            q[0][0] * x1 + q[0][1] * y1 + q[0][2] * z1,
            q[1][0] * x1 + q[1][1] * y1 + q[1][2] * z1,
            q[2][0] * x1 + q[2][1] * y1 + q[2][2] * z1,
        ]
    }
}

impl Default for Lattice {
    /// LAMMPS' initial lattice: `lattice none 1.0`.
    fn default() -> Lattice {
        Lattice::none(1.0)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use dmhs_parser::{FileId, Span, Word};

    /// A command from a line of text (words split on spaces, spans into that line).
    pub(crate) fn cmd(line: &str) -> Command {
        let mut words = vec![];
        let mut pos = 0;
        for t in line.split(' ') {
            if !t.is_empty() {
                words.push(Word::new(t, Span::new(FileId(0), pos, pos + t.len())));
            }
            pos += t.len() + 1;
        }
        let name = words.remove(0);
        Command { name, args: words, span: Span::new(FileId(0), 0, line.len()) }
    }

    fn lat(line: &str, units: UnitStyle, dim: usize) -> DResult<Lattice> {
        Lattice::from_lammps(&cmd(line), &Units::new(units), dim)
    }

    #[test]
    fn fcc_lj_spacing_matches_lammps() {
        // LAMMPS: lattice fcc 0.8442 -> spacing 1.6795962 (atom 2 at 0.8397980956912536).
        let l = lat("lattice fcc 0.8442", UnitStyle::Lj, 3).unwrap();
        assert_eq!(l.xlattice, 1.6795961913825073);
        assert_eq!(l.lattice2box([0.5, 0.5, 0.0]), [0.8397980956912536, 0.8397980956912536, 0.0]);
    }

    #[test]
    fn sq_lj_density_gives_dx() {
        // dambreak deck: lattice sq 10000 origin 0.5 0.5 0.0 -> spacing 0.01
        let l = lat("lattice sq 10000 origin 0.5 0.5 0.0", UnitStyle::Lj, 2).unwrap();
        assert_eq!(l.xlattice, 0.01);
        assert_eq!(l.zlattice, 0.01);
        let l = lat("lattice sq 1e-05 origin 0.5 0.5 0.0", UnitStyle::Si, 2).unwrap();
        assert_eq!(l.xlattice, 1e-05);
    }

    #[test]
    fn spacings_match_lammps() {
        // xlat ylat zlat reported by LAMMPS 22 Jul 2025 for each command
        let cases: &[(UnitStyle, usize, &str, [f64; 3])] = &[
            (UnitStyle::Lj, 3, "lattice bcc 1.2", [1.1856311014966876, 1.1856311014966876, 1.1856311014966876]),
            (UnitStyle::Lj, 3, "lattice hcp 0.9", [1.1625835210688116, 2.0136537265335037, 1.898490939991203]),
            (UnitStyle::Lj, 3, "lattice diamond 0.5", [2.5198420997897464, 2.5198420997897464, 2.5198420997897464]),
            (
                UnitStyle::Lj,
                3,
                "lattice fcc 0.8442 orient x 1 1 0 orient y -1 1 0 orient z 0 0 1",
                [2.375307713163338, 2.375307713163338, 1.6795961913825073],
            ),
            (
                UnitStyle::Lj,
                3,
                "lattice fcc 0.8442 orient x 1 1 1 orient y -1 1 0 orient z -1 -1 2",
                [2.9091459396736825, 2.375307713163338, 2.742769095206096],
            ),
            (
                UnitStyle::Si,
                3,
                "lattice hcp 3.2 orient x 1 0 0 orient y 0 1 1 orient z 0 -1 1 origin 0.1 0.2 0.3",
                [3.2, 7.61422531126669, 7.61422531126669],
            ),
            (
                UnitStyle::Lj,
                3,
                "lattice custom 1.3 a1 1 0 0 a2 0.5 0.8 0 a3 0.2 0.3 0.9 basis 0 0 0 basis 0.5 0.25 0.1",
                [2.189611021027544, 1.4168071312531167, 1.159205834661641],
            ),
            (
                UnitStyle::Si,
                3,
                "lattice custom 2.0 a1 1 0 0 a2 0.5 0.8 0 a3 0.2 0.3 0.9 basis 0 0 0 spacing 1 2 3",
                [2.0, 4.0, 6.0],
            ),
            (UnitStyle::Lj, 2, "lattice hex 0.7", [1.2843567252460064, 2.2245711031688638, 1.2843567252460064]),
            (
                UnitStyle::Lj,
                2,
                "lattice sq2 0.9 orient x 1 1 0 orient y -1 1 0",
                [2.1081851067789192, 2.1081851067789192, 1.4907119849998598],
            ),
            (UnitStyle::Cgs, 2, "lattice hex 2.5", [2.5, 4.330127018922193, 2.5]),
            (UnitStyle::Lj, 3, "lattice none 2.5", [2.5, 2.5, 2.5]),
        ];
        for (u, d, line, want) in cases {
            let l = lat(line, *u, *d).unwrap();
            assert_eq!(l.spacing(), *want, "{line}");
        }
    }

    #[test]
    fn rejects_bad_settings() {
        assert!(lat("lattice fcc 0.8 ", UnitStyle::Lj, 2).unwrap_err().message.contains("2d"));
        assert!(lat("lattice sq 1.0 origin 0.5 1.0 0", UnitStyle::Lj, 2).unwrap_err().message.contains("origin y"));
        assert!(lat("lattice sc 1.0 a1 1 0 0", UnitStyle::Lj, 3).unwrap_err().message.contains("custom"));
        assert!(lat("lattice sc 1.0 orient x 1 1 0", UnitStyle::Lj, 3).unwrap_err().message.contains("orthogonal"));
        assert!(lat("lattice sc 1.0 orient x 0 1 0 orient y 1 0 0", UnitStyle::Lj, 3)
            .unwrap_err()
            .message
            .contains("right-handed"));
        assert!(lat("lattice custom 1.0", UnitStyle::Lj, 3).unwrap_err().message.contains("basis"));
        assert!(lat("lattice sc -1", UnitStyle::Lj, 3).is_err());
        assert!(lat("lattice fcc 1.0 orgin 0 0 0", UnitStyle::Lj, 3).unwrap_err().help[0].contains("origin"));
    }
}
