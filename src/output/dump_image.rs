//! `dump image` and `dump movie`: pictures of the particles in LAMMPS' syntax, rendered by
//! [`crate::output::render`] and written as PNG (or PPM) files, atomically. `dump movie` writes numbered
//! PNG frames (`stem.<step>.png`) instead of a video: dmhs has no video encoder.
//!
//! Camera as LAMMPS: orthographic, `view theta phi` toward the viewer, `up` projected into the
//! image plane, `center` as box fractions, and one pixel = 2 max(box lengths) / (height zoom),
//! so a deck frames the scene as LAMMPS does. Colours by type (`acolor`) or by a per-atom value
//! through a colour map (`amap`, all of LAMMPS' c/d/s and a/f styles).

use crate::output::colors::NAMED;
use crate::output::dump::{column_values, parse_column, Column};
use crate::output::log::write_atomic;
use crate::output::render::{Camera, Canvas, Rgb, Vec3};
use crate::models::world::World;
use dmhs_parser::{Args, DResult, Word};
use std::path::{Path, PathBuf};

pub const SYNTAX: &str = "dump ID group image|movie N file color diameter [keyword value ...]  \
(color: type or a per-atom value; diameter: type, a number or a per-atom value; keywords: atom, adiam, bond, size, view, center, up, zoom, box, axes, subbox, shiny, fsaa, fix)";

/// Keywords of the `dump image` command that dmhs implements.
const KEYWORDS: &[&str] = &["atom", "adiam", "bond", "size", "view", "center", "up", "zoom", "box", "axes", "subbox", "shiny", "fsaa", "fix"];
/// LAMMPS' other `dump image` keywords: errors that name them.
const LAMMPS_ONLY: &[&str] = &["autobond", "grid", "line", "tri", "ellipsoid", "body", "compute", "persp", "region", "ssao", "depthcue", "outline"];
/// `dump_modify` keywords for images that dmhs implements.
pub const MODIFY_KEYWORDS: &[&str] = &["acolor", "adiam", "amap", "backcolor", "boxcolor", "bcolor", "bdiam", "color", "fcolor", "pad", "framerate"];
const MODIFY_LAMMPS_ONLY: &[&str] = &[
    "atrans", "backcolor2", "btrans", "bitrate", "axestrans", "boxtrans", "subboxtrans", "gamma", "gtrans", "lights", "specular", "loadcolors",
    "savecolors", "ccolor", "ctrans", "ftrans", "gmap", "bmap", "element",
];

/// LAMMPS' default per-type colour sequence.
const TYPE_COLORS: [&str; 16] =
    ["red", "forestgreen", "blue", "gold", "cyan", "magenta", "silver", "orange", "lime", "gray", "darkred", "darkgreen", "darkblue", "darkcyan", "darkmagenta", "darkgray"];

/// What sets an atom's colour or diameter.
#[derive(Clone, Debug)]
enum AtomValue {
    Type,
    Const(f64),
    Column(String, Column),
}

/// A number or an equal-style variable (`v_name`), evaluated when a frame is drawn.
#[derive(Clone, Debug)]
enum Param {
    Num(f64),
    Var(String),
}

impl Param {
    fn value(&self, equal: &mut dyn FnMut(&str) -> Result<f64, String>) -> Result<f64, String> {
        match self {
            Param::Num(x) => Ok(*x),
            Param::Var(name) => equal(name),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Bound {
    Min,
    Max,
    Value(f64),
}

#[derive(Clone, Debug)]
enum MapStyle {
    /// value, colour: interpolated between entries
    Continuous(Vec<(Bound, Rgb)>),
    /// lo, hi, colour: the first entry that holds the value
    Discrete(Vec<(Bound, Bound, Rgb)>),
    /// colours of consecutive bins of width delta
    Sequential(f64, Vec<Rgb>),
}

/// LAMMPS' `amap lo hi style delta N entries...`.
#[derive(Clone, Debug)]
struct ColorMap {
    lo: Bound,
    hi: Bound,
    fractional: bool,
    style: MapStyle,
}

impl ColorMap {
    fn default_map() -> ColorMap {
        ColorMap { lo: Bound::Min, hi: Bound::Max, fractional: true, style: MapStyle::Continuous(vec![(Bound::Min, [0.0, 0.0, 1.0]), (Bound::Max, [1.0, 0.0, 0.0])]) }
    }

    /// The range of the map for values `vals` (dynamic bounds from the data).
    fn range(&self, vals: &[f64]) -> (f64, f64) {
        let finite = || vals.iter().cloned().filter(|v| v.is_finite());
        let lo = match self.lo {
            Bound::Value(x) => x,
            _ => finite().fold(f64::INFINITY, f64::min),
        };
        let hi = match self.hi {
            Bound::Value(x) => x,
            _ => finite().fold(f64::NEG_INFINITY, f64::max),
        };
        if lo.is_finite() && hi.is_finite() { (lo, hi) } else { (0.0, 0.0) }
    }

    fn at(&self, b: Bound, lo: f64, hi: f64) -> f64 {
        match b {
            Bound::Min => lo,
            Bound::Max => hi,
            Bound::Value(x) if self.fractional => lo + x * (hi - lo),
            Bound::Value(x) => x,
        }
    }

    fn color(&self, v: f64, lo: f64, hi: f64) -> Rgb {
        let v = if v.is_nan() { lo } else { v.clamp(lo.min(hi), hi.max(lo)) };
        match &self.style {
            MapStyle::Continuous(e) => {
                for w in e.windows(2) {
                    let (a, b) = (self.at(w[0].0, lo, hi), self.at(w[1].0, lo, hi));
                    if v <= b {
                        let t = if b > a { ((v - a) / (b - a)).clamp(0.0, 1.0) } else { 1.0 };
                        return [0, 1, 2].map(|k| w[0].1[k] + t * (w[1].1[k] - w[0].1[k]));
                    }
                }
                e.last().unwrap().1
            }
            MapStyle::Discrete(e) => e.iter().find(|(a, b, _)| self.at(*a, lo, hi) <= v && v <= self.at(*b, lo, hi)).map(|x| x.2).unwrap_or(e.last().unwrap().2),
            MapStyle::Sequential(delta, colors) => {
                let width = if self.fractional { delta * (hi - lo) } else { *delta };
                let bin = if width > 0.0 { ((v - lo) / width).floor().max(0.0) as usize } else { 0 };
                colors[bin % colors.len()]
            }
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum BondColor {
    None,
    Atom,
    Type,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum BondWidth {
    None,
    Number(f64),
    Atom,
    Type,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Axes {
    No,
    LowerLeft,
    Center,
}

pub struct ImageDump {
    movie: bool,
    /// File name with `*` for the step (for movies: `stem.*.png`).
    pattern: String,
    ppm: bool,
    color: AtomValue,
    diameter: AtomValue,
    atoms: bool,
    adiam: Option<f64>,
    bond_color: BondColor,
    bond_width: BondWidth,
    width: usize,
    height: usize,
    theta: Param,
    phi: Param,
    center_dynamic: bool,
    center: [Param; 3],
    /// The box when the dump was defined (`center s` fractions refer to it).
    static_box: ([f64; 3], [f64; 3]),
    up: [Param; 3],
    zoom: Param,
    box_on: bool,
    box_diam: f64,
    axes: Axes,
    axes_len: f64,
    axes_diam: f64,
    subbox: bool,
    shiny: f64,
    fsaa: bool,
    ntypes: usize,
    nbondtypes: usize,
    type_color: Vec<Rgb>,
    type_diam: Vec<f64>,
    bond_type_color: Vec<Rgb>,
    bond_type_diam: Vec<f64>,
    amap: ColorMap,
    background: Rgb,
    boxcolor: Rgb,
    user_colors: Vec<(String, Rgb)>,
    /// `fix ID color flag1 flag2`: wall planes of these fixes, drawn as box-wide outlines
    /// (fix ID, colour, line diameter as a fraction of the shortest box length).
    fixes: Vec<(String, Rgb, f64)>,
    pad: usize,
    framerate: f64,
}

fn named(name: &str, user: &[(String, Rgb)]) -> Option<Rgb> {
    if let Some((_, c)) = user.iter().rev().find(|(n, _)| n == name) {
        return Some(*c);
    }
    NAMED.iter().find(|(n, _)| *n == name).map(|(_, c)| c.map(|v| v as f64 / 255.0))
}

fn word_param(a: &mut Args, what: &str) -> DResult<Param> {
    let w = a.peek().ok_or_else(|| a.missing(what))?;
    if let Some(name) = w.text.strip_prefix("v_") {
        a.skip(1);
        return Ok(Param::Var(name.to_string()));
    }
    Ok(Param::Num(a.f64(what)?))
}

impl ImageDump {
    /// Parse `file color diameter keywords...` of `dump ID group image|movie N` (the file word
    /// is given; `a` is positioned after it).
    pub fn from_lammps(a: &mut Args, file: &Word, movie: bool, world: &World, base_dir: Option<&Path>) -> DResult<ImageDump> {
        let name = file.text.as_str();
        let lower = name.to_ascii_lowercase();
        let (pattern, ppm) = if movie {
            if name.contains('*') {
                return Err(a.error_at(file, "dump movie writes one sequence: its file name must not contain *", "no * in a movie name"));
            }
            // frames: movie.mp4 -> movie.*.png
            let p = Path::new(name);
            let stem = match p.extension() {
                Some(_) => p.with_extension("").to_string_lossy().to_string(),
                None => name.to_string(),
            };
            (format!("{stem}.*.png"), false)
        } else {
            if !name.contains('*') {
                return Err(a.error_at(file, "dump image writes one file per snapshot: the file name must contain * (replaced by the step)", "expected e.g. image.*.png"));
            }
            if lower.ends_with(".jpg") || lower.ends_with(".jpeg") || lower.ends_with(".tga") {
                return Err(a.error_at(file, "dmhs writes dump images as PNG (.png) or PPM (any other suffix), not JPEG or TGA", "use a .png name"));
            }
            if lower.ends_with(".gz") || lower.ends_with(".bz2") || lower.ends_with(".zst") || lower.ends_with(".xz") {
                return Err(a.error_at(file, "compressed image files are not supported", "use a .png name"));
            }
            (name.to_string(), !lower.ends_with(".png"))
        };
        let pattern = crate::output::log::resolve_path(base_dir, &pattern).to_string_lossy().to_string();
        let dom = world.state.domain().map_err(|e| a.error_at(file, e, "no box"))?;
        let cw = a.word("color (type or a per-atom value)")?;
        let color = Self::atom_value(a, cw, world, false)?;
        let dw = a.word("diameter (type, a number or a per-atom value)")?;
        let diameter = Self::atom_value(a, dw, world, true)?;
        let two_d = world.state.dimension == 2;
        let ntypes = world.state.ntypes.max(1);
        let nbondtypes = world.state.topo.nbondtypes;
        let palette: Vec<Rgb> = TYPE_COLORS.iter().map(|n| named(n, &[]).unwrap()).collect();
        let has_bonds = world.state.atoms.features.bonds && nbondtypes > 0;
        let mut d = ImageDump {
            movie,
            pattern,
            ppm,
            color,
            diameter,
            atoms: true,
            adiam: None,
            bond_color: if has_bonds { BondColor::Atom } else { BondColor::None },
            bond_width: if has_bonds { BondWidth::Number(0.5) } else { BondWidth::None },
            width: 512,
            height: 512,
            theta: Param::Num(if two_d { 0.0 } else { 60.0 }),
            phi: Param::Num(if two_d { 0.0 } else { 30.0 }),
            center_dynamic: false,
            center: [Param::Num(0.5), Param::Num(0.5), Param::Num(0.5)],
            static_box: ([0.0; 3], [1.0; 3]),
            up: if two_d { [Param::Num(0.0), Param::Num(1.0), Param::Num(0.0)] } else { [Param::Num(0.0), Param::Num(0.0), Param::Num(1.0)] },
            zoom: Param::Num(1.0),
            box_on: true,
            box_diam: 0.02,
            axes: Axes::No,
            axes_len: 0.0,
            axes_diam: 0.0,
            subbox: false,
            shiny: 0.0,
            fsaa: false,
            ntypes,
            nbondtypes,
            type_color: (0..ntypes).map(|t| palette[t % palette.len()]).collect(),
            type_diam: vec![1.0; ntypes],
            bond_type_color: (0..nbondtypes).map(|t| palette[t % palette.len()]).collect(),
            bond_type_diam: vec![0.5; nbondtypes],
            amap: ColorMap::default_map(),
            background: [0.0; 3],
            boxcolor: named("gold", &[]).unwrap(),
            user_colors: vec![],
            fixes: vec![],
            pad: if movie { 10 } else { 0 },
            framerate: 24.0,
        };
        while let Some(w) = a.peek() {
            a.skip(1);
            match w.text.as_str() {
                "atom" => d.atoms = a.yes_no("atom")?,
                "adiam" => d.adiam = Some(a.positive_f64("adiam (atom diameter)")?),
                "bond" => {
                    let c = a.word("bond color (atom, type or none)")?;
                    d.bond_color = match c.text.as_str() {
                        "atom" => BondColor::Atom,
                        "type" => BondColor::Type,
                        "none" => BondColor::None,
                        _ => return Err(a.error_at(c, format!("bond color `{}` is not supported", c.text), "expected atom, type or none")),
                    };
                    let wd = a.word("bond width (a number, atom, type or none)")?;
                    d.bond_width = match wd.text.as_str() {
                        "atom" => BondWidth::Atom,
                        "type" => BondWidth::Type,
                        "none" => BondWidth::None,
                        _ => BondWidth::Number(dmhs_parser::args::word_f64(wd, "bond width").map_err(|e| e.with_help(format!("syntax: {SYNTAX}")))?),
                    };
                    if (d.bond_color == BondColor::None) != (d.bond_width == BondWidth::None) {
                        return Err(a.error_at(wd, "bond color and width must both be none or both be set", "inconsistent bond settings"));
                    }
                    if d.bond_color != BondColor::None && !has_bonds {
                        return Err(a.error_at(c, "bonds cannot be drawn: this system has no bond types", "no bonds"));
                    }
                }
                "size" => {
                    d.width = a.i64_in("image width (pixels)", 1, 4096)? as usize;
                    d.height = a.i64_in("image height (pixels)", 1, 4096)? as usize;
                }
                "view" => {
                    d.theta = word_param(a, "view theta (degrees)")?;
                    d.phi = word_param(a, "view phi (degrees)")?;
                    if let Param::Num(t) = d.theta {
                        if !(0.0..=180.0).contains(&t) {
                            return Err(a.error_at(a.last().unwrap(), "view theta must be in 0..180 degrees", "bad theta"));
                        }
                    }
                    if two_d && (matches!(d.theta, Param::Num(t) if t != 0.0) || matches!(d.phi, Param::Num(p) if p != 0.0)) {
                        return Err(a.error_at(w, "a 2d image is viewed along z: view must be 0 0", "2d view"));
                    }
                }
                "center" => {
                    d.center_dynamic = a.choice("center flag (s or d)", &["s", "d"])? == 1;
                    for (k, what) in ["center Cx", "center Cy", "center Cz"].iter().enumerate() {
                        d.center[k] = word_param(a, what)?;
                    }
                }
                "up" => {
                    for (k, what) in ["up Ux", "up Uy", "up Uz"].iter().enumerate() {
                        d.up[k] = word_param(a, what)?;
                    }
                    if two_d && matches!(d.up[2], Param::Num(z) if z != 0.0) {
                        return Err(a.error_at(w, "a 2d image is viewed along z: the up vector must lie in the xy plane", "2d view"));
                    }
                }
                "zoom" => {
                    d.zoom = word_param(a, "zoom factor")?;
                    if matches!(d.zoom, Param::Num(z) if z <= 0.0) {
                        return Err(a.error_at(a.last().unwrap(), "zoom must be > 0", "bad zoom"));
                    }
                }
                "box" => {
                    d.box_on = a.yes_no("box")?;
                    d.box_diam = a.non_negative_f64("box line diameter (fraction of the shortest box length)")?;
                }
                "axes" => {
                    d.axes = match a.choice("axes", &["no", "yes", "lowerleft", "center"])? {
                        0 => Axes::No,
                        1 | 2 => Axes::LowerLeft,
                        _ => Axes::Center,
                    };
                    d.axes_len = a.non_negative_f64("axes length (fraction of the box length)")?;
                    d.axes_diam = a.non_negative_f64("axes diameter (fraction of the shortest box length)")?;
                }
                "subbox" => {
                    d.subbox = a.yes_no("subbox")?;
                    a.non_negative_f64("subbox line diameter")?;
                }
                "shiny" => d.shiny = a.f64_where("shiny", "in 0..1", |s| (0.0..=1.0).contains(&s))?,
                "fsaa" => d.fsaa = a.yes_no("fsaa")?,
                "fix" => {
                    let fw = a.word("fix ID")?;
                    let Some(f) = world.fix(&fw.text) else {
                        return Err(a.error_at(fw, format!("fix `{}` does not exist", fw.text), "unknown fix"));
                    };
                    if !["wall/reflect", "wall/gran"].contains(&f.style()) {
                        return Err(a.error_at(fw, format!("fix {} ({}) has nothing to draw: dmhs draws the planes of wall/reflect and wall/gran", fw.text, f.style()), "not a wall fix"));
                    }
                    let color = match a.choice("fix color style (const or type)", &["const", "type", "element"])? {
                        0 => [1.0; 3],
                        1 => d.type_color[0],
                        _ => return Err(a.error_at(a.last().unwrap(), "`element` colouring is not supported by dmhs", "use const or type")),
                    };
                    let diam = a.non_negative_f64("fix flag1 (line diameter, fraction of the shortest box length; 0: as the box)")?;
                    a.f64("fix flag2 (unused)")?;
                    d.fixes.push((fw.text.clone(), color, diam));
                }
                k if LAMMPS_ONLY.contains(&k) => {
                    return Err(a.error_at(w, format!("dump image keyword `{k}` is a LAMMPS option that dmhs does not support"), format!("supported: {}", KEYWORDS.join(", "))));
                }
                _ => return Err(a.unknown_keyword(w, KEYWORDS)),
            }
        }
        // LAMMPS converts a static centre with the box of the time the dump is defined
        d.static_box = (dom.lo, dom.hi);
        Ok(d)
    }

    fn atom_value(a: &Args, w: &Word, world: &World, diameter: bool) -> DResult<AtomValue> {
        let t = w.text.as_str();
        if t == "type" {
            return Ok(AtomValue::Type);
        }
        if t == "element" {
            return Err(a.error_at(w, "`element` colouring is not supported by dmhs (use type and dump_modify acolor)", "use type"));
        }
        if diameter && dmhs_parser::args::is_lammps_float(t) {
            let v: f64 = t.parse().unwrap_or(0.0);
            if v <= 0.0 {
                return Err(a.error_at(w, "the diameter must be > 0", "bad diameter"));
            }
            return Ok(AtomValue::Const(v));
        }
        let col = parse_column(t, world).map_err(|e| a.error_at(w, e, if diameter { "bad diameter attribute" } else { "bad color attribute" }))?;
        Ok(AtomValue::Column(t.to_string(), col))
    }

    /// The dmhs frame-file note printed when a `dump movie` is defined.
    pub fn movie_note(&self, id: &str) -> Option<String> {
        self.movie.then(|| {
            format!(
                "dump {id}: dmhs writes movies as PNG frames {} (no video encoder); make a video with\n  ffmpeg -framerate {} -pattern_type glob -i '{}' -pix_fmt yuv420p movie.mp4",
                self.pattern, self.framerate, self.pattern
            )
        })
    }

    fn color_of(&self, w: &Word) -> DResult<Rgb> {
        named(&w.text, &self.user_colors).ok_or_else(|| {
            let mut d = dmhs_parser::Diagnostic::at(w.span, format!("unknown color `{}`", w.text), "not a color name");
            let names = NAMED.iter().map(|(n, _)| *n).chain(self.user_colors.iter().map(|(n, _)| n.as_str()));
            if let Some(h) = dmhs_parser::suggest::did_you_mean_help(&w.text, names) {
                d = d.with_help(h);
            }
            d.with_help("colors are the 140 X11/CSS names (red, forestgreen, gold, ...) or ones defined by dump_modify color")
        })
    }

    fn bound(a: &mut Args, what: &str, allow: &[&str]) -> DResult<Bound> {
        let w = a.peek().ok_or_else(|| a.missing(what))?;
        match w.text.as_str() {
            "min" if allow.contains(&"min") => {
                a.skip(1);
                Ok(Bound::Min)
            }
            "max" if allow.contains(&"max") => {
                a.skip(1);
                Ok(Bound::Max)
            }
            _ => Ok(Bound::Value(a.f64(what)?)),
        }
    }

    /// One `dump_modify` keyword for images; `Ok(false)` if `w` is not one of them.
    pub fn modify(&mut self, w: &Word, a: &mut Args) -> DResult<bool> {
        match w.text.as_str() {
            "acolor" | "bcolor" => {
                let bond = w.text == "bcolor";
                let n = if bond { self.nbondtypes } else { self.ntypes };
                if n == 0 {
                    return Err(a.error_at(w, "bcolor: this system has no bond types", "no bonds"));
                }
                let (lo, hi) = a.type_range(if bond { "bond type" } else { "atom type" }, n)?;
                let cw = a.word("color name (or color1/color2/...)")?;
                let mut colors = vec![];
                for part in cw.text.split('/') {
                    let pw = Word::new(part, cw.span);
                    colors.push(self.color_of(&pw)?);
                }
                let table = if bond { &mut self.bond_type_color } else { &mut self.type_color };
                for (k, t) in (lo..=hi).enumerate() {
                    table[t - 1] = colors[k % colors.len()];
                }
            }
            "adiam" | "bdiam" => {
                let bond = w.text == "bdiam";
                let n = if bond { self.nbondtypes } else { self.ntypes };
                if n == 0 {
                    return Err(a.error_at(w, "bdiam: this system has no bond types", "no bonds"));
                }
                let (lo, hi) = a.type_range(if bond { "bond type" } else { "atom type" }, n)?;
                let v = a.positive_f64("diameter")?;
                let table = if bond { &mut self.bond_type_diam } else { &mut self.type_diam };
                for t in lo..=hi {
                    table[t - 1] = v;
                }
            }
            "amap" => self.amap = self.parse_amap(a)?,
            "backcolor" => self.background = self.color_of(a.word("background color")?)?,
            "boxcolor" => self.boxcolor = self.color_of(a.word("box color")?)?,
            "color" => {
                let name = a.word("color name")?.text.clone();
                let v = a.word("R G B (0..1) or a hex 0xRRGGBB")?;
                let rgb = if let Some(hex) = v.text.strip_prefix("0x").or_else(|| v.text.strip_prefix("#")) {
                    let x = u32::from_str_radix(hex, 16).ok().filter(|_| hex.len() == 6).ok_or_else(|| a.error_at(v, format!("`{}` is not a 24-bit hex color", v.text), "expected 0xRRGGBB"))?;
                    [(x >> 16) & 255, (x >> 8) & 255, x & 255].map(|c| c as f64 / 255.0)
                } else {
                    let r = dmhs_parser::args::word_f64(v, "red")?;
                    let g = a.f64("green")?;
                    let b = a.f64("blue")?;
                    if ![r, g, b].iter().all(|c| (0.0..=1.0).contains(c)) {
                        return Err(a.error_at(a.last().unwrap(), "color components must be in 0..1", "bad color"));
                    }
                    [r, g, b]
                };
                self.user_colors.push((name, rgb));
            }
            "fcolor" => {
                let fw = a.word("fix ID")?;
                let Some(k) = self.fixes.iter().position(|f| f.0 == fw.text) else {
                    return Err(a.error_at(fw, format!("fcolor: fix `{}` is not drawn by this dump (add `fix {} const 0 0` to it)", fw.text, fw.text), "not drawn"));
                };
                self.fixes[k].1 = self.color_of(a.word("color")?)?;
            }
            "pad" => self.pad = a.i64_in("pad (digits of the step in file names)", 0, 30)? as usize,
            "framerate" => self.framerate = a.positive_f64("framerate")?,
            k if MODIFY_LAMMPS_ONLY.contains(&k) => {
                return Err(a.error_at(w, format!("dump_modify {k} is a LAMMPS image option that dmhs does not support"), format!("supported: {}", MODIFY_KEYWORDS.join(", "))));
            }
            _ => return Ok(false),
        }
        Ok(true)
    }

    fn parse_amap(&self, a: &mut Args) -> DResult<ColorMap> {
        let lo = Self::bound(a, "amap lo (a number or min)", &["min"])?;
        let hi = Self::bound(a, "amap hi (a number or max)", &["max"])?;
        if let (Bound::Value(l), Bound::Value(h)) = (lo, hi) {
            if l >= h {
                return Err(a.error_at(a.last().unwrap(), "amap lo must be below hi", "bad range"));
            }
        }
        let sw = a.word("amap style (ca, cf, da, df, sa or sf)")?;
        let st = sw.text.as_bytes();
        if st.len() != 2 || !b"cds".contains(&st[0]) || !b"af".contains(&st[1]) {
            return Err(a.error_at(sw, format!("amap style `{}`: expected c, d or s followed by a or f", sw.text), "expected ca, cf, da, df, sa or sf"));
        }
        let fractional = st[1] == b'f';
        let delta = a.f64("amap delta (bin size; used by the s styles)")?;
        let n = a.i64_in("amap N (number of entries)", 1, 10_000)? as usize;
        let style = match st[0] {
            b'c' => {
                let mut e = vec![];
                for k in 0..n {
                    let b = Self::bound(a, "amap entry value (a number, min or max)", &["min", "max"])?;
                    let bw = a.last().unwrap();
                    if (k == 0 && b != Bound::Min) || (k == n - 1 && b != Bound::Max) {
                        return Err(a.error_at(bw, "a continuous amap runs from min (first entry) to max (last entry)", "expected min first and max last"));
                    }
                    e.push((b, self.color_of(a.word("amap entry color")?)?));
                }
                if n < 2 {
                    return Err(a.error_at(sw, "a continuous amap needs at least 2 entries (min and max)", "too few entries"));
                }
                MapStyle::Continuous(e)
            }
            b'd' => {
                let mut e = vec![];
                for k in 0..n {
                    let l = Self::bound(a, "amap entry lo (a number or min)", &["min"])?;
                    let h = Self::bound(a, "amap entry hi (a number or max)", &["max"])?;
                    if k == n - 1 && (l != Bound::Min || h != Bound::Max) {
                        return Err(a.error_at(a.last().unwrap(), "the last entry of a discrete amap must be min max", "expected min max"));
                    }
                    e.push((l, h, self.color_of(a.word("amap entry color")?)?));
                }
                MapStyle::Discrete(e)
            }
            _ => {
                if delta <= 0.0 {
                    return Err(a.error_at(sw, "a sequential amap needs delta > 0", "bad delta"));
                }
                let mut c = vec![];
                for _ in 0..n {
                    c.push(self.color_of(a.word("amap entry color")?)?);
                }
                MapStyle::Sequential(delta, c)
            }
        };
        Ok(ColorMap { lo, hi, fractional, style })
    }

    /// The file a snapshot at `step` goes to (`*` replaced by the step, zero-padded to `pad`).
    pub fn file_for(&self, step: i64) -> PathBuf {
        let s = if self.pad > 0 { format!("{:0width$}", step, width = self.pad) } else { step.to_string() };
        PathBuf::from(self.pattern.replacen('*', &s, 1))
    }

    /// Render the atoms of `groupbit` as they are now.
    /// `equal` evaluates equal-style variables.
    pub fn render(&self, world: &World, equal: &mut dyn FnMut(&str) -> Result<f64, String>, groupbit: u32) -> Result<Canvas, String> {
        let dom = world.state.domain()?.clone();
        let theta = self.theta.value(equal)?.to_radians();
        let phi = self.phi.value(equal)?.to_radians();
        let zoom = self.zoom.value(equal)?;
        if !(zoom > 0.0) {
            return Err(format!("dump image zoom must be > 0, got {zoom}"));
        }
        let up = Vec3::new(self.up[0].value(equal)?, self.up[1].value(equal)?, self.up[2].value(equal)?);
        let (lo, hi) = if self.center_dynamic { (dom.lo, dom.hi) } else { self.static_box };
        let (lo, hi) = (Vec3::from(lo), Vec3::from(hi));
        // `center` is given in fractions of the box
        let frac = Vec3::new(self.center[0].value(equal)?, self.center[1].value(equal)?, self.center[2].value(equal)?);
        let center = lo + frac.component_mul(&(hi - lo));
        let mut planes = vec![];
        for (fid, color, diam) in &self.fixes {
            let f = world.fix(fid).ok_or_else(|| format!("fix `{fid}` (drawn by this dump) does not exist"))?;
            planes.extend(f.image_planes(world.state, equal)?.into_iter().map(|(axis, c)| (axis, c, *color, *diam)));
        }
        let a = &world.state.atoms;
        let idx: Vec<usize> = (0..a.nlocal).filter(|&i| a.mask[i] & groupbit != 0).collect();
        let colors: Vec<Rgb> = match &self.color {
            AtomValue::Type => idx.iter().map(|&i| self.type_color[(a.typ[i].max(1) - 1) % self.ntypes]).collect(),
            AtomValue::Const(_) => vec![self.type_color[0]; idx.len()],
            AtomValue::Column(name, c) => {
                let vals = column_values(c, world, &idx).map_err(|e| format!("color `{name}`: {e}"))?;
                let (lo, hi) = self.amap.range(&vals);
                vals.iter().map(|&v| self.amap.color(v, lo, hi)).collect()
            }
        };
        let diams: Vec<f64> = match (&self.adiam, &self.diameter) {
            (Some(d), _) => vec![*d; idx.len()],
            (None, AtomValue::Type) => idx.iter().map(|&i| self.type_diam[(a.typ[i].max(1) - 1) % self.ntypes]).collect(),
            (None, AtomValue::Const(d)) => vec![*d; idx.len()],
            (None, AtomValue::Column(name, c)) => column_values(c, world, &idx).map_err(|e| format!("diameter `{name}`: {e}"))?,
        };
        let ss = if self.fsaa { 2 } else { 1 };
        let (w, h) = (self.width * ss, self.height * ss);
        let prd = dom.prd();
        let maxdel = 2.0 * prd[0].max(prd[1]).max(prd[2]);
        let cam = Camera::looking(theta, phi, up, center, maxdel / (self.height as f64 * zoom) / ss as f64, w, h)?;
        let mut cv = Canvas::new(w, h, self.background);
        cv.shiny = self.shiny;
        if self.atoms {
            for (k, &i) in idx.iter().enumerate() {
                if diams[k] > 0.0 {
                    cv.sphere(&cam, Vec3::from(a.x[i]), 0.5 * diams[k], colors[k]);
                }
            }
        }
        if self.bond_color != BondColor::None && !world.state.topo.bonds.is_empty() {
            self.draw_bonds(&mut cv, &cam, world.state, &dom, &idx, &colors, &diams);
        }
        let two_d = dom.dimension == 2;
        let shortest = if two_d { prd[0].min(prd[1]) } else { prd[0].min(prd[1]).min(prd[2]) };
        if self.box_on || self.subbox {
            let (lo, hi) = (dom.lo, dom.hi);
            let corner = |m: usize| Vec3::new(if m & 1 == 0 { lo[0] } else { hi[0] }, if m & 2 == 0 { lo[1] } else { hi[1] }, if m & 4 == 0 { lo[2] } else { hi[2] });
            let diam = self.box_diam * shortest;
            for m in 0..8usize {
                for bit in [1usize, 2, 4] {
                    if m & bit == 0 {
                        cv.cylinder(&cam, corner(m), corner(m | bit), diam, self.boxcolor);
                    }
                }
            }
        }
        // wall planes: the outline of the plane's section of the box
        for (axis, c, color, diam) in planes {
            let (lo, hi) = (dom.lo, dom.hi);
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let point = |a: f64, b: f64| {
                let mut p = Vec3::zeros();
                p[axis] = c;
                p[u] = a;
                p[v] = b;
                p
            };
            let corners = [point(lo[u], lo[v]), point(hi[u], lo[v]), point(hi[u], hi[v]), point(lo[u], hi[v])];
            let width = if diam > 0.0 { diam } else { self.box_diam.max(0.005) } * shortest;
            for k in 0..4 {
                cv.cylinder(&cam, corners[k], corners[(k + 1) % 4], width, color);
            }
        }
        if self.axes != Axes::No {
            let o = match self.axes {
                Axes::Center => (Vec3::from(dom.lo) + Vec3::from(dom.hi)) * 0.5,
                _ => Vec3::from(dom.lo),
            };
            let rgb = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
            for k in 0..3 {
                let mut e = o;
                e[k] += self.axes_len * prd[k];
                cv.cylinder(&cam, o, e, self.axes_diam * shortest, rgb[k]);
            }
        }
        Ok(if ss > 1 { cv.downsample(ss) } else { cv })
    }

    /// Bonds between drawn atoms, as two halves meeting at the minimum-image midpoint (so a bond
    /// across a periodic boundary is drawn at both atoms).
    #[allow(clippy::too_many_arguments)]
    fn draw_bonds(&self, cv: &mut Canvas, cam: &Camera, state: &crate::engine::state::State, dom: &crate::engine::domain::Domain, idx: &[usize], colors: &[Rgb], diams: &[f64]) {
        let a = &state.atoms;
        let mut slot: std::collections::HashMap<i64, usize> = std::collections::HashMap::with_capacity(idx.len());
        for (k, &i) in idx.iter().enumerate() {
            slot.insert(a.tag[i], k);
        }
        let prd = dom.prd();
        for b in &state.topo.bonds {
            if b.typ == 0 || b.off {
                continue;
            }
            let (Some(&ka), Some(&kb)) = (slot.get(&b.atoms[0]), slot.get(&b.atoms[1])) else { continue };
            let (xa, xb) = (Vec3::from(a.x[idx[ka]]), Vec3::from(a.x[idx[kb]]));
            let mut d = xb - xa;
            for k in 0..3 {
                if dom.periodic(k) && prd[k] > 0.0 {
                    d[k] -= prd[k] * (d[k] / prd[k]).round();
                }
            }
            let t = (b.typ - 1) % self.nbondtypes.max(1);
            let width = match self.bond_width {
                BondWidth::Number(x) => x,
                BondWidth::Atom => diams[ka].min(diams[kb]),
                BondWidth::Type => self.bond_type_diam.get(t).copied().unwrap_or(0.5),
                BondWidth::None => continue,
            };
            if width <= 0.0 {
                continue;
            }
            let (ca, cb) = match self.bond_color {
                BondColor::Type => {
                    let c = self.bond_type_color.get(t).copied().unwrap_or([1.0; 3]);
                    (c, c)
                }
                _ => (colors[ka], colors[kb]),
            };
            let (ma, mb) = (xa + d * 0.5, xb - d * 0.5);
            cv.cylinder(cam, xa, ma, width, ca);
            cv.cylinder(cam, xb, mb, width, cb);
        }
    }

    /// Render and write one snapshot (atomically: a temporary file renamed into place).
    pub fn write(&self, w: &World, equal: &mut dyn FnMut(&str) -> Result<f64, String>, groupbit: u32) -> Result<PathBuf, String> {
        let cv = self.render(w, equal, groupbit)?;
        let path = self.file_for(w.state.step);
        let bytes = if self.ppm { cv.ppm() } else { cv.png()? };
        write_atomic(&path, &bytes).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        Ok(path)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map(style: MapStyle, fractional: bool) -> ColorMap {
        ColorMap { lo: Bound::Min, hi: Bound::Max, fractional, style }
    }

    #[test]
    fn continuous_map_interpolates_between_entries() {
        let m = ColorMap::default_map();
        assert_eq!(m.color(0.0, 0.0, 2.0), [0.0, 0.0, 1.0]);
        assert_eq!(m.color(2.0, 0.0, 2.0), [1.0, 0.0, 0.0]);
        assert_eq!(m.color(1.0, 0.0, 2.0), [0.5, 0.0, 0.5]);
        // clamped outside the range
        assert_eq!(m.color(-5.0, 0.0, 2.0), [0.0, 0.0, 1.0]);
        // three entries, absolute values
        let m = map(MapStyle::Continuous(vec![(Bound::Min, [0.0; 3]), (Bound::Value(1.0), [1.0, 1.0, 1.0]), (Bound::Max, [1.0, 0.0, 0.0])]), false);
        assert_eq!(m.color(0.5, 0.0, 4.0), [0.5, 0.5, 0.5]);
        assert_eq!(m.color(2.5, 0.0, 4.0), [1.0, 0.5, 0.5]);
    }

    #[test]
    fn discrete_and_sequential_maps() {
        let m = map(MapStyle::Discrete(vec![(Bound::Value(1.0), Bound::Value(2.0), [0.0, 1.0, 0.0]), (Bound::Min, Bound::Max, [0.0; 3])]), false);
        assert_eq!(m.color(1.5, 0.0, 10.0), [0.0, 1.0, 0.0]);
        assert_eq!(m.color(3.0, 0.0, 10.0), [0.0; 3]);
        let m = map(MapStyle::Sequential(1.0, vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]), false);
        assert_eq!(m.color(0.5, 0.0, 10.0), [1.0, 0.0, 0.0]);
        // on a bin boundary: the higher bin
        assert_eq!(m.color(1.0, 0.0, 10.0), [0.0, 1.0, 0.0]);
        assert_eq!(m.color(2.2, 0.0, 10.0), [1.0, 0.0, 0.0]);
        // fractional delta: a fifth of the range
        let m = map(MapStyle::Sequential(0.2, vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]), true);
        assert_eq!(m.color(2.5, 0.0, 10.0), [0.0, 1.0, 0.0]);
    }

    #[test]
    fn named_colors() {
        assert_eq!(named("red", &[]), Some([1.0, 0.0, 0.0]));
        assert_eq!(named("forestgreen", &[]).map(|c| (c[1] * 255.0).round()), Some(139.0));
        assert_eq!(named("mine", &[("mine".into(), [0.1, 0.2, 0.3])]), Some([0.1, 0.2, 0.3]));
        assert_eq!(named("nosuch", &[]), None);
        assert_eq!(NAMED.len(), 140);
    }
}
