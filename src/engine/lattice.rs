//! The `lattice` command: a unit cell (primitive vectors a1 a2 a3 and basis atoms), its
//! orientation and origin, and the scale that turns lattice units into box units, computed
//! exactly as LAMMPS' `Lattice` class does (same formulas, same floating-point order), so
//! that `create_atoms` and `units lattice` give LAMMPS' coordinates to the last bit.

use crate::engine::units::{UnitStyle, Units};
use dmhs_parser::{Args, Command, DResult};
use nalgebra::{Matrix3, RowVector3, Vector3};

type Vec3 = Vector3<f64>;

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
    pub basis: Vec<Vec3>,
    pub origin: Vec3,
    /// Orientation vectors of the box x, y, z axes in lattice coordinates.
    pub orient: [[i32; 3]; 3],
    pub a1: Vec3,
    pub a2: Vec3,
    pub a3: Vec3,
    /// Columns a1 a2 a3: unit-cell coordinates -> unscaled lattice vectors.
    primitive: Matrix3<f64>,
    priminv: Matrix3<f64>,
    /// Rows: the unit orient vectors (LAMMPS `rotaterow`; its transpose is `rotatecol`).
    rotate: Matrix3<f64>,
}

impl Lattice {
    /// `lattice none spacing`: no basis, only spacings (LAMMPS starts with `none 1.0`).
    pub fn none(spacing: f64) -> Lattice {
        let id = Matrix3::identity();
        Lattice {
            style: LatticeStyle::None,
            scale: 1.0,
            xlattice: spacing,
            ylattice: spacing,
            zlattice: spacing,
            basis: vec![],
            origin: Vec3::zeros(),
            orient: [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
            a1: Vec3::x(),
            a2: Vec3::y(),
            a3: Vec3::z(),
            primitive: id,
            priminv: id,
            rotate: id,
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

        let basis: Vec<[f64; 3]> = match style {
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
        let mut basis: Vec<Vec3> = basis.into_iter().map(Vec3::from).collect();

        let mut origin = Vec3::zeros();
        let mut orient = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
        let mut spacing: Option<[f64; 3]> = None;
        let mut a1 = Vec3::x();
        let mut a2 = Vec3::y();
        let mut a3 = Vec3::z();
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
                    for c in &mut orient[dim] {
                        *c = a.i64_in("orient component", i32::MIN as i64, i32::MAX as i64)? as i32;
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
                    let mut v = Vec3::zeros();
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
        // integer algebra, as LAMMPS
        let o = orient.map(|r| Vector3::from(r.map(i64::from)));
        let at_orient = |msg: &str| match orient_word {
            Some(w) => a.error_at(w, msg.to_string(), "orient vectors"),
            None => a.error_at(style_word, msg.to_string(), "orient vectors"),
        };
        if o[0].dot(&o[1]) != 0 || o[1].dot(&o[2]) != 0 || o[0].dot(&o[2]) != 0 {
            return Err(at_orient("lattice orient vectors are not orthogonal"));
        }
        if o[0].cross(&o[1]).dot(&o[2]) <= 0 {
            return Err(at_orient("lattice orient vectors are not right-handed"));
        }
        let at_a = |msg: &str| match a_word {
            Some(w) => a.error_at(w, msg.to_string(), "primitive vectors"),
            None => a.error_at(style_word, msg.to_string(), "primitive vectors"),
        };
        if a1.cross(&a2).norm() == 0.0 || a2.cross(&a3).norm() == 0.0 || a1.cross(&a3).norm() == 0.0 {
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
            if orient[0][2] != 0 || orient[1][2] != 0 || orient[2][0] != 0 || orient[2][1] != 0 {
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
            let volume = a1.dot(&a2.cross(&a3)).abs();
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
            primitive: Matrix3::zeros(),
            priminv: Matrix3::zeros(),
            rotate: Matrix3::zeros(),
        };
        if !lat.setup_transform() {
            return Err(at_a("degenerate lattice primitive vectors"));
        }

        match spacing {
            None => {
                // Spacings = extent of the unit cell's 8 corners in box space (with the
                // spacings still 0 so the origin shift does not enter).
                let mut lo = Vec3::repeat(BIG);
                let mut hi = Vec3::repeat(-BIG);
                for corner in 0..8 {
                    let p = Vec3::new((corner & 1) as f64, ((corner >> 1) & 1) as f64, ((corner >> 2) & 1) as f64);
                    let q = lat.lattice2box(p);
                    // LAMMPS' MIN/MAX (ties keep the old value)
                    lo = lo.zip_map(&q, |l, q| if q < l { q } else { l });
                    hi = hi.zip_map(&q, |h, q| if q > h { q } else { h });
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
        let prim = Matrix3::from_columns(&[self.a1, self.a2, self.a3]);
        let p = |i: usize, j: usize| prim[(i, j)];
        // LAMMPS' determinant and cofactor inverse term by term: nalgebra's `determinant` and
        // `try_inverse` group the products differently and round differently.
        let det = p(0, 0) * p(1, 1) * p(2, 2) + p(0, 1) * p(1, 2) * p(2, 0) + p(0, 2) * p(1, 0) * p(2, 1)
            - p(0, 0) * p(1, 2) * p(2, 1)
            - p(0, 1) * p(1, 0) * p(2, 2)
            - p(0, 2) * p(1, 1) * p(2, 0);
        if det == 0.0 {
            return false;
        }
        self.primitive = prim;
        self.priminv = Matrix3::new(
            (p(1, 1) * p(2, 2) - p(1, 2) * p(2, 1)) / det,
            (p(0, 2) * p(2, 1) - p(0, 1) * p(2, 2)) / det,
            (p(0, 1) * p(1, 2) - p(0, 2) * p(1, 1)) / det,
            (p(1, 2) * p(2, 0) - p(1, 0) * p(2, 2)) / det,
            (p(0, 0) * p(2, 2) - p(0, 2) * p(2, 0)) / det,
            (p(0, 2) * p(1, 0) - p(0, 0) * p(1, 2)) / det,
            (p(1, 0) * p(2, 1) - p(1, 1) * p(2, 0)) / det,
            (p(0, 1) * p(2, 0) - p(0, 0) * p(2, 1)) / det,
            (p(0, 0) * p(1, 1) - p(0, 1) * p(1, 0)) / det,
        );
        let mut rows = [RowVector3::zeros(); 3];
        for (row, o) in rows.iter_mut().zip(self.orient) {
            // the squared length in int arithmetic, as LAMMPS
            let lensq = o[0] * o[0] + o[1] * o[1] + o[2] * o[2];
            let length = (lensq as f64).sqrt();
            if length == 0.0 {
                return false;
            }
            *row = RowVector3::new(o[0] as f64, o[1] as f64, o[2] as f64) / length;
        }
        self.rotate = Matrix3::from_rows(&rows);
        true
    }

    // nalgebra's 3x3 matrix-vector product sums each row x, y, z in order, as LAMMPS' loops.

    /// Lattice coordinates -> box coordinates: `R (scale P x) + spacing * origin`.
    pub fn lattice2box(&self, x: Vec3) -> Vec3 {
        let v = self.rotate * (self.primitive * x * self.scale);
        v + Vec3::from(self.spacing()).component_mul(&self.origin)
    }

    /// Box coordinates -> lattice coordinates (inverse of [`Lattice::lattice2box`]).
    pub fn box2lattice(&self, x: Vec3) -> Vec3 {
        let v = x - Vec3::from(self.spacing()).component_mul(&self.origin);
        self.priminv * (self.rotate.transpose() * v / self.scale)
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
        assert_eq!(l.lattice2box(Vec3::new(0.5, 0.5, 0.0)), Vec3::new(0.8397980956912536, 0.8397980956912536, 0.0));
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
