//! The `region` command: geometric regions with LAMMPS' exact point tests (surface points are
//! inside), `side in|out`, `units lattice|box` scaling, `open` faces and the bounding box
//! ("extent") that `create_atoms` uses to narrow its lattice loop.
//!
//! This file holds what every style shares (ID, keywords, INF/EDGE bounds, `match`) and the
//! registry `STYLES`; each style is one file with its parsing, its `inside` test, its extent
//! and its tests. To add a style: write `name.rs` with a `pub const STYLE: Style` and a type
//! that implements [`Shape`], then add `mod name;` and one line to `STYLES` (its syntax then
//! shows in the help line and its name in "did you mean").
//!
//! A style sees points in its own frame only: LAMMPS' `move`/`rotate` keywords map a point back
//! through the inverse displacement and rotation before the style's test (`Region::match`), so
//! they belong in [`Region`] (motion.rs), not in the styles. Granular walls
//! (`fix wall/gran/region`) ask a region for the points of its surface within a cutoff of a
//! particle ([`Region::surface`], surface.rs): the styles give them in their own frame
//! ([`Shape::surface_interior`], [`Shape::surface_exterior`]) and the region moves them back.

mod block;
mod boolean;
mod cone;
mod cylinder;
mod ellipsoid;
mod motion;
mod surface;
mod plane;
mod prism;
mod sphere;

use crate::engine::domain::Domain;
use crate::engine::lattice::Lattice;
use dmhs_parser::{Args, Command, DResult, Diagnostic, Word};
pub use motion::ShapeFrame;
use nalgebra::Vector3;
use std::fmt::Debug;
use std::sync::Arc;

pub type Vec3 = Vector3<f64>;

pub use surface::WallContact;

/// What LAMMPS substitutes for `INF` bounds.
const BIG: f64 = 1.0e20;

/// The geometry of one region style, in box units.
pub trait Shape: Debug + Send + Sync {
    /// LAMMPS `inside()`: the bare shape test, surface points included.
    fn inside(&self, x: &Vec3) -> bool;
    /// Bounding box `(lo, hi)` of the interior (LAMMPS `bboxflag`, `extent_*`), if finite.
    fn extent(&self) -> Option<(Vec3, Vec3)>;
    /// Whether `open` applies: union and intersect have no faces of their own.
    fn has_faces(&self) -> bool {
        true
    }
    /// The parameters of a block or cylinder, for commands that accept only those (fix pour).
    fn simple(&self) -> Option<Simple> {
        None
    }
    /// A prism's lower and upper bounds and tilts `[xy, xz, yz]` (create_box makes a
    /// triclinic box of it).
    fn prism(&self) -> Option<([f64; 3], [f64; 3], [f64; 3])> {
        None
    }
    /// Union and intersect: whether all sub-regions must match, and the sub-regions (taken into
    /// the [`Region`], which keeps their motion state).
    fn boolean(&self) -> Option<(bool, Vec<Region>)> {
        None
    }
    /// Whether the style gives wall contacts (LAMMPS' surface_interior/exterior).
    fn has_surface(&self) -> bool {
        false
    }
    /// LAMMPS `surface_interior`: contacts with the inner side of the faces that are not open,
    /// for a point at most `cutoff` away (none if the point is outside).
    fn surface_interior(&self, _x: &Vec3, _cutoff: f64, _open: &[bool; 6], _out: &mut Vec<WallContact>) {}
    /// LAMMPS `surface_exterior`: the one nearest point of the outer side, if closer than `cutoff`.
    fn surface_exterior(&self, _x: &Vec3, _cutoff: f64, _open: &[bool; 6], _out: &mut Vec<WallContact>) {}
    /// LAMMPS `cmax` (contacts a point can have) and `tmax` (touching contacts, by side).
    fn contact_counts(&self, _interior: bool) -> (usize, usize) {
        (0, 0)
    }
    /// Where a change of the shape moves its wall (LAMMPS' `set_velocity_shape`: sphere and
    /// cylinder, whose curved contacts have `varflag`); None for the other styles.
    fn shape_frame(&self) -> Option<ShapeFrame> {
        None
    }
}

/// A block or a cylinder by its parameters, in box units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Simple {
    Block { lo: [f64; 3], hi: [f64; 3] },
    /// `center` is a point on the axis (its axial component is 0); `lo..hi` along the axis.
    Cylinder { axis: usize, center: [f64; 3], radius: f64, lo: f64, hi: f64 },
}

/// A registered style: its syntax (for the help line), how many shape words it takes, and its
/// parser. The count comes first because the keywords after the shape words set its scale.
#[derive(Clone, Copy)]
pub struct Style {
    syntax: &'static str,
    /// The shape words that may be equal-style variables `v_name` (LAMMPS 22 Jul 2025).
    vars: &'static [usize],
    /// May read a count word first (`union N ...`); the style name is given for messages.
    nargs: fn(&mut Args, &str) -> DResult<usize>,
    parse: fn(&ShapeArgs) -> DResult<Box<dyn Shape>>,
}

/// LAMMPS `point_on_line_segment`: the point of segment `a`-`b` nearest to `c`.
pub(crate) fn point_on_segment(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]) -> [f64; 3] {
    let ba = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let ca = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let t = (ca[0] * ba[0] + ca[1] * ba[1] + ca[2] * ba[2]) / (ba[0] * ba[0] + ba[1] * ba[1] + ba[2] * ba[2]);
    if t <= 0.0 {
        *a
    } else if t >= 1.0 {
        *b
    } else {
        [a[0] + t * ba[0], a[1] + t * ba[1], a[2] + t * ba[2]]
    }
}

/// `nargs` of a style with a fixed number of shape words.
fn fixed<const N: usize>(_: &mut Args, _: &str) -> DResult<usize> {
    Ok(N)
}

/// The region styles dmhs implements, in the order the help line lists them.
const STYLES: &[(&str, Style)] = &[
    ("block", block::STYLE),
    ("sphere", sphere::STYLE),
    ("cylinder", cylinder::STYLE),
    ("cone", cone::STYLE),
    ("ellipsoid", ellipsoid::STYLE),
    ("prism", prism::STYLE),
    ("plane", plane::STYLE),
    ("union", boolean::UNION),
    ("intersect", boolean::INTERSECT),
];

/// LAMMPS region styles that dmhs lacks: named as unsupported (checked after `STYLES`).
const LAMMPS_ONLY: &[&str] = &["grid"];

/// Names of the supported styles.
pub fn style_names() -> impl Iterator<Item = &'static str> {
    STYLES.iter().map(|(n, _)| *n)
}

fn syntax() -> String {
    let styles: Vec<&str> = STYLES.iter().map(|(_, s)| s.syntax).collect();
    format!(
        "region ID style args keyword value ... | region ID delete (styles: {}; keywords: side in|out, units lattice|box, open face, move v_x|NULL v_y|NULL v_z|NULL, rotate v_theta Px Py Pz Rx Ry Rz)",
        styles.join(" | ")
    )
}

/// What a style's parser gets: its shape words, the scale of `units`, the box (for INF/EDGE)
/// and the regions defined so far; errors point at the words through `args`.
pub struct ShapeArgs<'a> {
    args: &'a Args<'a>,
    /// The current value of each shape word that is a variable (None for the others).
    values: &'a [Option<f64>],
    style: &'a str,
    words: &'a [Word],
    /// Lattice spacings under `units lattice`, ones under `units box`.
    scale: Vec3,
    domain: Option<&'a Domain>,
    /// Faces given with `open` (1-based) and the word that named each.
    open: &'a [(&'a Word, usize)],
    existing: &'a [Region],
}

impl ShapeArgs<'_> {
    pub fn error(&self, w: &Word, message: impl Into<String>, label: impl Into<String>) -> Diagnostic {
        self.args.error_at(w, message, label)
    }

    /// Shape word `k` as a number (in the units of the command, not scaled).
    pub fn num(&self, k: usize, what: &str) -> DResult<f64> {
        let w = &self.words[k];
        if w.text.starts_with("v_") {
            return match self.values.get(k).copied().flatten() {
                Some(v) => Ok(v),
                None => Err(self
                    .error(w, format!("region {} takes a number for {what}, not a variable (found `{}`)", self.style, w.text), "variable not allowed here")
                    .with_help(format!("syntax: {}", self.args.syntax))),
            };
        }
        dmhs_parser::args::word_f64(w, what).map_err(|d| d.with_help(format!("syntax: {}", self.args.syntax)))
    }

    /// Shape word `k` times the scale of dimension `dim`.
    pub fn scaled(&self, k: usize, dim: usize, what: &str) -> DResult<f64> {
        Ok(self.scale[dim] * self.num(k, what)?)
    }

    /// Shape words `k..k + 3` as a scaled point or vector.
    pub fn point(&self, k: usize, what: [&str; 3]) -> DResult<Vec3> {
        Ok(Vec3::new(self.scaled(k, 0, what[0])?, self.scaled(k + 1, 1, what[1])?, self.scaled(k + 2, 2, what[2])?))
    }

    /// Shape word `k` as a bound along `dim`: INF (+-1e20), EDGE (the box face) or a scaled number.
    pub fn bound(&self, k: usize, dim: usize, upper: bool, what: &str) -> DResult<f64> {
        let w = &self.words[k];
        if w.text == "INF" || w.text == "EDGE" {
            let Some(d) = self.domain else {
                return Err(self.error(w, format!("cannot use region {} when the box does not exist", w.text), "no box yet"));
            };
            return Ok(match (w.text.as_str(), upper) {
                ("INF", false) => -BIG,
                ("INF", true) => BIG,
                (_, false) => d.lo[dim],
                (_, true) => d.hi[dim],
            });
        }
        self.scaled(k, dim, what)
    }

    /// The first six shape words as `xlo xhi ylo yhi zlo zhi` (block and prism).
    pub fn box_bounds(&self) -> DResult<(Vec3, Vec3)> {
        let mut lo = Vec3::zeros();
        let mut hi = Vec3::zeros();
        for d in 0..3 {
            lo[d] = self.bound(2 * d, d, false, ["xlo", "ylo", "zlo"][d])?;
            hi[d] = self.bound(2 * d + 1, d, true, ["xhi", "yhi", "zhi"][d])?;
        }
        Ok((lo, hi))
    }
}

/// What a region is: one style's shape, or a union/intersection of sub-regions (copies that
/// keep their own motion state, looked up again by ID before each run as LAMMPS does).
#[derive(Clone, Debug)]
enum Kind {
    Shape(Arc<dyn Shape>),
    Boolean { all: bool, subs: Vec<Region> },
}

/// A shape with variable parameters (LAMMPS `varshape`): what rebuilding it from its words
/// takes, each time the variables are evaluated (LAMMPS' `shape_update`).
#[derive(Debug)]
struct ShapeVars {
    cmd: Command,
    style: &'static str,
    /// The shape words are `cmd.args[2..2 + nshape]` (styles with variables take no count word).
    nshape: usize,
    /// The variable of each shape word that is one.
    names: Vec<Option<String>>,
    scale: Vec3,
    /// The box when the region was defined (EDGE bounds stay where they were).
    domain: Option<Domain>,
    open: Vec<usize>,
}

impl ShapeVars {
    /// The shape with the shape words' variables at `values`.
    fn build(&self, values: &[Option<f64>]) -> DResult<Box<dyn Shape>> {
        let style = STYLES.iter().find(|(n, _)| *n == self.style).map(|(_, s)| *s).expect("a registered style");
        let syntax = syntax();
        let args = Args::new(&self.cmd, &syntax);
        let words = &self.cmd.args[2..2 + self.nshape];
        let open: Vec<(&Word, usize)> = self.open.iter().map(|&f| (&words[0], f)).collect();
        (style.parse)(&ShapeArgs { args: &args, values, style: self.style, words, scale: self.scale, domain: self.domain.as_ref(), open: &open, existing: &[] })
    }

    /// The variables' values now.
    fn values(&self, equal: &mut dyn FnMut(&str) -> Result<f64, String>) -> Result<Vec<Option<f64>>, String> {
        self.names.iter().map(|n| n.as_deref().map(&mut *equal).transpose()).collect()
    }
}

#[derive(Clone, Debug)]
pub struct Region {
    pub id: String,
    pub style: &'static str,
    kind: Kind,
    /// `side in` (true, the default) or `side out`.
    pub interior: bool,
    /// Faces listed with the `open` keyword (1-based in the command, 0-based here).
    pub open_faces: [bool; 6],
    /// Which `region` command made it: a region deleted and defined again is another region.
    pub serial: u64,
    /// `move` and `rotate`, the current displacement and angle, and the velocities inferred
    /// from them (motion.rs).
    motion: motion::Motion,
    /// Shape words that are variables, if any.
    shape_vars: Option<Arc<ShapeVars>>,
    /// How the variable shape's wall moves this step (sphere and cylinder; motion.rs).
    shape_velocity: Option<motion::ShapeVelocity>,
}

static SERIAL: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

impl Region {
    /// LAMMPS `Region::match`: is `x` in the region, honouring `side`. A moving region maps `x`
    /// back to where it was defined first. A region with any `open` face matches every point (as
    /// in LAMMPS, where open faces only matter for wall contacts). A union or intersection asks
    /// its sub-regions (each with its own motion and open faces).
    pub fn matches(&self, x: [f64; 3]) -> bool {
        match &self.kind {
            Kind::Shape(shape) => {
                let xl = self.motion.inverse(x);
                if self.openflag() {
                    return true;
                }
                shape.inside(&Vec3::from(xl)) == self.interior
            }
            Kind::Boolean { all, subs } => {
                let inside = if *all { subs.iter().all(|r| r.matches(x)) } else { subs.iter().any(|r| r.matches(x)) };
                inside == self.interior
            }
        }
    }

    /// LAMMPS `openflag`: some face was given with `open` (union and intersect have none).
    pub fn openflag(&self) -> bool {
        matches!(self.kind, Kind::Shape(_)) && self.open_faces.contains(&true)
    }

    /// [`Shape::prism`] of this region.
    pub fn prism(&self) -> Option<([f64; 3], [f64; 3], [f64; 3])> {
        match &self.kind {
            Kind::Shape(shape) => shape.prism(),
            Kind::Boolean { .. } => None,
        }
    }

    /// The block or cylinder this region is, if it is one (`side in`, no open faces, still).
    pub fn simple(&self) -> Option<Simple> {
        if !self.interior || self.open_faces.contains(&true) || self.is_dynamic() {
            return None;
        }
        match &self.kind {
            Kind::Shape(shape) => shape.simple(),
            Kind::Boolean { .. } => None,
        }
    }

    /// The bounding box LAMMPS uses (`bboxflag` and `extent_*`): interior regions of finite shapes.
    pub fn extent(&self) -> Option<([f64; 3], [f64; 3])> {
        if !self.interior {
            return None;
        }
        match &self.kind {
            Kind::Shape(shape) => shape.extent().map(|(lo, hi)| (lo.into(), hi.into())),
            Kind::Boolean { all, subs } => boolean::extent(*all, subs),
        }
    }

    /// Parse a `region` command. `domain` is needed for `EDGE`/`INF` bounds; `lattice` gives
    /// the spacings for `units lattice` (the default; without a lattice command LAMMPS uses
    /// its initial `lattice none 1.0`); `existing` holds the regions defined so far (for
    /// union/intersect and ID reuse); `equal` evaluates the equal-style variables of shape
    /// words `v_name` (LAMMPS evaluates them when the region is defined, and again at each use).
    pub fn from_lammps(
        cmd: &Command,
        domain: Option<&Domain>,
        lattice: Option<&Lattice>,
        existing: &[Region],
        equal: &mut dyn FnMut(&str) -> Result<f64, String>,
    ) -> DResult<Region> {
        let syntax = syntax();
        let mut a = Args::new(cmd, &syntax);
        let id_word = a.word("region ID")?;
        let id = id_word.text.clone();
        // LAMMPS checks no characters in region IDs (`lo-fixed` in examples/friction)
        if id.is_empty() {
            return Err(a.error_at(id_word, "empty region ID", "invalid ID"));
        }
        let style_word = a.word("region style")?;
        if style_word.text == "delete" {
            return Err(a.error_at(style_word, "`region ID delete` removes a region (handled by the region command)", "delete"));
        }
        if existing.iter().any(|r| r.id == id) {
            return Err(a.error_at(id_word, format!("reuse of region ID `{id}`"), "already defined"));
        }
        let Some(&(name, style)) = STYLES.iter().find(|(n, _)| *n == style_word.text) else {
            if LAMMPS_ONLY.contains(&style_word.text.as_str()) {
                return Err(a.error_at(
                    style_word,
                    format!("region style `{}` is not supported", style_word.text),
                    "not supported",
                ));
            }
            return Err(a.unknown_keyword(style_word, &style_names().collect::<Vec<_>>()));
        };
        let nshape = (style.nargs)(&mut a, name)?;
        if a.len_remaining() < nshape {
            a.skip(a.len_remaining());
            return Err(a.missing(&format!("{nshape} arguments of region {name}")));
        }
        let words = &a.remaining()[..nshape];
        a.skip(nshape);
        // the shape words that are variables: their values now
        let mut names: Vec<Option<String>> = vec![None; nshape];
        for (k, w) in words.iter().enumerate() {
            if let Some(var) = w.text.strip_prefix("v_").filter(|_| style.vars.contains(&k)) {
                names[k] = Some(var.to_string());
            }
        }
        let mut values = vec![None; nshape];
        for (k, var) in names.iter().enumerate() {
            if let Some(var) = var {
                let v = equal(var).map_err(|e| a.error_at(&words[k], format!("Variable {var} for region {name}: {e}"), "equal-style variable"))?;
                values[k] = Some(v);
            }
        }

        // Keywords come first in LAMMPS (they set the scale the shape arguments use).
        let mut interior = true;
        let mut lattice_units = true;
        let mut open_faces = [false; 6];
        const KEYWORDS: [&str; 5] = ["side", "units", "open", "move", "rotate"];
        let mut open: Vec<(&Word, usize)> = vec![];
        let mut moving = motion::Motion::default();
        let mut dynamic_word = None;
        while let Some(kw) = a.peek() {
            a.skip(1);
            match kw.text.as_str() {
                "side" => interior = a.choice("side", &["in", "out"])? == 0,
                "units" => lattice_units = a.choice("units", &["lattice", "box"])? == 0,
                "open" => {
                    let face = a.i64_in("open face", 1, 6)? as usize;
                    open_faces[face - 1] = true;
                    open.push((a.last().unwrap(), face));
                }
                "move" => {
                    moving.parse_move(&mut a)?;
                    dynamic_word = Some(kw);
                }
                "rotate" => {
                    moving.parse_rotate(&mut a)?;
                    dynamic_word = Some(kw);
                }
                _ => return Err(a.unknown_keyword(kw, &KEYWORDS)),
            }
        }
        let spacing = lattice.map_or(Lattice::default().spacing(), Lattice::spacing);
        let scale = if lattice_units { Vec3::from(spacing) } else { Vec3::repeat(1.0) };
        if let (Some(kw), "union" | "intersect") = (dynamic_word, name) {
            return Err(a.error_at(kw, format!("region {name} cannot be dynamic (its sub-regions may move)"), "not allowed here"));
        }
        moving.scale_point(&scale);
        let shape = (style.parse)(&ShapeArgs { args: &a, values: &values, style: name, words, scale, domain, open: &open, existing })?;
        let kind = match shape.boolean() {
            Some((all, subs)) => Kind::Boolean { all, subs },
            None => Kind::Shape(shape.into()),
        };
        let shape_vars = names.iter().any(Option::is_some).then(|| {
            let open = open.iter().map(|(_, f)| *f).collect();
            Arc::new(ShapeVars { cmd: cmd.clone(), style: name, nshape, names, scale, domain: domain.cloned(), open })
        });
        let serial = SERIAL.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Ok(Region { id, style: name, kind, interior, open_faces, serial, motion: moving, shape_vars, shape_velocity: None })
    }

    /// Whether some shape word is a variable (LAMMPS `varshape`).
    pub fn varshape(&self) -> bool {
        self.shape_vars.is_some()
    }

    /// LAMMPS `shape_update`: the shape rebuilt with its variables' values now.
    fn shape_update(&mut self, equal: &mut dyn FnMut(&str) -> Result<f64, String>) -> Result<(), String> {
        let Some(sv) = &self.shape_vars else { return Ok(()) };
        let values = sv.values(equal)?;
        let shape = sv.build(&values).map_err(|d| format!("Variable evaluation in region gave bad value: {}", d.message))?;
        self.kind = Kind::Shape(shape.into());
        Ok(())
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::engine::domain::BoundaryKind;
    use crate::engine::lattice::tests::cmd;

    pub(crate) fn boxed(lo: [f64; 3], hi: [f64; 3]) -> Domain {
        Domain::new(3, lo, hi, [[BoundaryKind::Periodic; 2]; 3])
    }

    pub(crate) fn reg(line: &str, d: Option<&Domain>, l: Option<&Lattice>, ex: &[Region]) -> DResult<Region> {
        Region::from_lammps(&cmd(line), d, l, ex, &mut |n| Err(format!("variable {n} is not defined in this test")))
    }

    #[test]
    fn edge_and_inf_need_a_box() {
        let e = reg("region w block 0 1 0 1 EDGE EDGE units box", None, None, &[]).unwrap_err();
        assert!(e.message.contains("box does not exist"));
        let d = boxed([-0.035, -0.035, -0.005], [3.255, 1.8, 0.005]);
        let r = reg("region w block 0 1 0 1 EDGE INF units box", Some(&d), None, &[]).unwrap();
        assert_eq!(r.extent(), Some(([0.0, 0.0, -0.005], [1.0, 1.0, 1e20])));
        assert!(reg("region w block -INF 1 0 1 0 1 units box", Some(&d), None, &[]).is_err());
    }

    #[test]
    fn side_out_flips_the_test_and_has_no_extent() {
        let r = reg("region b block 0 1 0 1 0 1 units box side out", None, None, &[]).unwrap();
        assert!(!r.matches([1.0, 1.0, 1.0]) && r.matches([1.5, 0.5, 0.5]) && r.extent().is_none());
    }

    #[test]
    fn open_face_matches_everything() {
        // LAMMPS: a region with an open face matches all points, even with side out.
        let r = reg("region r block 0 2 0 2 0 2 units box open 1 side out", None, None, &[]).unwrap();
        assert!(r.matches([10.0, 10.0, 10.0]) && r.matches([1.0, 1.0, 1.0]));
    }

    #[test]
    fn help_line_lists_every_style() {
        assert_eq!(
            syntax(),
            "region ID style args keyword value ... | region ID delete (styles: block xlo xhi ylo yhi zlo zhi | sphere x y z r | \
cylinder dim c1 c2 r lo hi | cone dim c1 c2 radlo radhi lo hi | ellipsoid x y z a b c | prism xlo xhi ylo yhi zlo zhi xy xz yz | plane px py pz nx ny nz | \
union N id1 id2 ...; keywords: side in|out, units lattice|box, open face, move v_x|NULL v_y|NULL v_z|NULL, rotate v_theta Px Py Pz Rx Ry Rz)"
                .replace("union N id1 id2 ...;", "union N id1 id2 ... | intersect N id1 id2 ...;")
        );
    }

    #[test]
    fn dynamic_and_unknown_are_rejected() {
        let e = reg("region r block 0 1 0 1 0 1 move x NULL NULL", None, None, &[]).unwrap_err();
        assert!(e.message.contains("v_name or NULL"), "{}", e.message);
        let e = reg("region r block 0 1 0 1 0 1 rotate v_t 0 0 0 0 0 0", None, None, &[]).unwrap_err();
        assert!(e.message.contains("0 length rotation"), "{}", e.message);
        let a = reg("region a block 0 1 0 1 0 1 move v_x NULL NULL", None, None, &[]).unwrap();
        let b = reg("region b block 0 1 0 1 0 1", None, None, &[]).unwrap();
        let e = reg("region u union 2 a b rotate v_t 0 0 0 0 0 1", None, None, &[a, b]).unwrap_err();
        assert!(e.message.contains("cannot be dynamic"), "{}", e.message);
        let e = reg("region r blok 0 1 0 1 0 1", None, None, &[]).unwrap_err();
        assert!(e.help[0].contains("block"), "{:?}", e.help);
        let e = reg("region r grid c_x:g:d gt 1.0", None, None, &[]).unwrap_err();
        assert_eq!(e.message, "region style `grid` is not supported");
        let e = reg("region r sphere 0 0 0", None, None, &[]).unwrap_err();
        assert!(e.message.contains("missing"));
        let e = reg("region r cylinder z 1 1 1 v_lo 2", None, None, &[]).unwrap_err();
        assert!(e.message.contains("takes a number for lo, not a variable"), "{}", e.message);
        let e = reg("region r sphere 0 0 v_z 1", None, None, &[]).unwrap_err();
        assert!(e.message.contains("Variable z for region sphere"), "{}", e.message);
        // any characters, as LAMMPS (examples/friction's `lo-fixed`)
        let r = reg("region lo-fixed sphere 0 0 0 1", None, None, &[]).unwrap();
        assert_eq!(r.id, "lo-fixed");
    }
}
