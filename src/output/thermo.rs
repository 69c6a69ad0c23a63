//! Thermodynamic output in LAMMPS' layout (`thermo`, `thermo_style`, `thermo_modify`), and the
//! values of thermo keywords (also used by expressions).

use crate::engine::state::State;
use crate::models::world::World;
use dmhs_parser::EvalContext;
use dmhs_parser::numfmt::format_printf;

/// One column of thermo output.
#[derive(Clone, Debug, PartialEq)]
pub enum Field {
    Keyword(String),
    Compute(String, Option<usize>),
    Fix(String, Option<usize>),
    /// `c_ID[i][j]`, `f_ID[i][j]`: a global array element (1-based).
    ComputeArray(String, usize, usize),
    FixArray(String, usize, usize),
    Variable(String),
    /// `v_name[i]`: element i (1-based) of a vector-style variable.
    VariableElement(String, usize),
}

#[derive(Clone, Debug)]
pub struct Column {
    pub field: Field,
    /// Header text (`thermo_modify colname` may replace it).
    pub label: String,
    pub int: bool,
    /// The keyword as the thermo style gave it (`thermo_modify colname` and `format` find
    /// columns by it).
    pub word: String,
}

#[derive(Clone, Debug)]
pub struct Thermo {
    /// `thermo N` (0: only the first and last steps of a run).
    pub every: i64,
    /// `thermo v_name`: an equal-style variable gives the step of each next output (LAMMPS'
    /// var_thermo); `every` is then 0.
    pub every_var: Option<String>,
    /// The step of the next output under `every_var`, set at a run's setup and after each
    /// output.
    pub next: i64,
    pub columns: Vec<Column>,
    pub custom: bool,
    /// `thermo_modify norm`; None: LAMMPS' default (yes for lj units).
    pub norm: Option<bool>,
    pub format_line: Option<Vec<String>>,
    pub format_int: Option<String>,
    pub format_float: Option<String>,
    /// Per-column formats (1-based column -> format).
    pub format_column: Vec<(usize, String)>,
    /// `thermo_modify lost warn|ignore`: atoms that leave a fixed boundary are removed.
    pub lost_ignore: bool,
    /// `lost warn`: the first loss is reported (LAMMPS warns once).
    pub lost_warn: bool,
    pub lost_warned: bool,
    pub flush: bool,
    /// `thermo_modify temp ID`: the temperature compute of temp, ke, etotal (and of the
    /// pressure compute thermo_press); `press ID`: the pressure compute of press and pxx...
    pub temp_id: String,
    pub press_id: String,
    /// The last column is the Volume that [`Thermo::init_volume_column`] added.
    pub volume_added: bool,
    /// How a step's values are laid out (`thermo_style multi|yaml`, `thermo_modify line`).
    pub line: LineStyle,
    /// thermo_modify changed this style (a new thermo_style then warns that the changes are
    /// lost, as LAMMPS).
    pub modified: bool,
}

/// LAMMPS' thermo line layouts: one line of columns under a header; blocks of `Label = value`
/// three to a line under a step and CPU line; YAML (a keywords list, then one list per step).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LineStyle {
    One,
    Multi,
    Yaml,
}

impl Default for Thermo {
    fn default() -> Self {
        Thermo {
            every: 0,
            every_var: None,
            next: 0,
            columns: parse_columns(STYLE_ONE).unwrap(),
            custom: false,
            norm: None,
            format_line: None,
            format_int: None,
            format_float: None,
            format_column: vec![],
            lost_ignore: false,
            lost_warn: false,
            lost_warned: false,
            flush: false,
            temp_id: "thermo_temp".into(),
            press_id: "thermo_press".into(),
            volume_added: false,
            line: LineStyle::One,
            modified: false,
        }
    }
}

/// Keywords whose values are integers.
const INT_KEYWORDS: &[&str] = &["step", "elapsed", "elaplong", "atoms", "bonds", "angles", "dihedrals", "impropers", "nbuild", "ndanger", "part"];

/// The keywords of LAMMPS' thermo styles one, multi and yaml.
pub const STYLE_ONE: &[&str] = &["step", "temp", "epair", "emol", "etotal", "press"];
pub const STYLE_MULTI: &[&str] = &["etotal", "ke", "temp", "pe", "ebond", "eangle", "edihed", "eimp", "evdwl", "ecoul", "elong", "press"];
pub const STYLE_YAML: &[&str] = &["step", "temp", "ke", "pe", "ebond", "eangle", "edihed", "eimp", "evdwl", "ecoul", "elong", "press"];

/// All thermo keywords dmhs knows, with their header labels.
pub const KEYWORDS: &[(&str, &str)] = &[
    ("step", "Step"),
    ("elapsed", "Elapsed"),
    ("elaplong", "Elaplong"),
    ("dt", "Dt"),
    ("time", "Time"),
    ("cpu", "CPU"),
    ("tpcpu", "T/CPU"),
    ("spcpu", "S/CPU"),
    ("atoms", "Atoms"),
    ("temp", "Temp"),
    ("press", "Press"),
    ("pe", "PotEng"),
    ("ke", "KinEng"),
    ("etotal", "TotEng"),
    ("ecouple", "Ecouple"),
    ("econserve", "Econserve"),
    ("enthalpy", "Enthalpy"),
    ("evdwl", "E_vdwl"),
    ("ecoul", "E_coul"),
    ("epair", "E_pair"),
    ("ebond", "E_bond"),
    ("eangle", "E_angle"),
    ("edihed", "E_dihed"),
    ("eimp", "E_impro"),
    ("emol", "E_mol"),
    ("elong", "E_long"),
    ("etail", "E_tail"),
    ("vol", "Volume"),
    ("density", "Density"),
    ("lx", "Lx"),
    ("ly", "Ly"),
    ("lz", "Lz"),
    ("xlo", "Xlo"),
    ("xhi", "Xhi"),
    ("ylo", "Ylo"),
    ("yhi", "Yhi"),
    ("zlo", "Zlo"),
    ("zhi", "Zhi"),
    ("xy", "Xy"),
    ("xz", "Xz"),
    ("yz", "Yz"),
    ("cella", "Cella"),
    ("cellb", "Cellb"),
    ("cellc", "Cellc"),
    ("cellalpha", "CellAlpha"),
    ("cellbeta", "CellBeta"),
    ("cellgamma", "CellGamma"),
    ("xlat", "Xlat"),
    ("ylat", "Ylat"),
    ("zlat", "Zlat"),
    ("bonds", "Bonds"),
    ("angles", "Angles"),
    ("dihedrals", "Diheds"),
    ("impropers", "Impros"),
    ("pxx", "Pxx"),
    ("pyy", "Pyy"),
    ("pzz", "Pzz"),
    ("pxy", "Pxy"),
    ("pxz", "Pxz"),
    ("pyz", "Pyz"),
    ("fmax", "Fmax"),
    ("fnorm", "Fnorm"),
    ("nbuild", "Nbuild"),
    ("ndanger", "Ndanger"),
];

/// Parse `c_ID`, `c_ID[2]`, `c_ID[2][3]`, `f_ID` (the same), `v_name` or a keyword into a column.
pub fn parse_column(word: &str) -> Result<Column, String> {
    let indexed = |rest: &str| -> Result<(String, Vec<usize>), String> {
        let Some(k) = rest.find('[') else { return Ok((rest.to_string(), Vec::new())) };
        let bad = || format!("bad index in `{word}`: expected ID[i] or ID[i][j] with i, j >= 1");
        let inner = rest[k..].strip_prefix('[').and_then(|t| t.strip_suffix(']')).ok_or_else(bad)?;
        let idx = inner.split("][").map(|t| t.parse::<usize>().ok().filter(|&n| n >= 1)).collect::<Option<Vec<_>>>().ok_or_else(bad)?;
        if idx.len() > 2 {
            return Err(bad());
        }
        Ok((rest[..k].to_string(), idx))
    };
    let field = if let Some(r) = word.strip_prefix("c_") {
        match indexed(r)? {
            (id, i) if i.len() == 2 => Field::ComputeArray(id, i[0], i[1]),
            (id, i) => Field::Compute(id, i.first().copied()),
        }
    } else if let Some(r) = word.strip_prefix("f_") {
        match indexed(r)? {
            (id, i) if i.len() == 2 => Field::FixArray(id, i[0], i[1]),
            (id, i) => Field::Fix(id, i.first().copied()),
        }
    } else if let Some(r) = word.strip_prefix("v_") {
        match indexed(r)? {
            (name, i) if i.is_empty() => Field::Variable(name),
            (name, i) if i.len() == 1 => Field::VariableElement(name, i[0]),
            _ => return Err(format!("bad index in `{word}`: a variable takes one index, v_name[i]")),
        }
    } else if let Some((_, label)) = KEYWORDS.iter().find(|(k, _)| *k == word) {
        return Ok(Column { field: Field::Keyword(word.to_string()), label: label.to_string(), int: INT_KEYWORDS.contains(&word), word: word.to_string() });
    } else {
        return Err(format!("unknown thermo keyword `{word}`"));
    };
    Ok(Column { field, label: word.to_string(), int: false, word: word.to_string() })
}

pub fn parse_columns(words: &[&str]) -> Result<Vec<Column>, String> {
    words.iter().map(|w| parse_column(w)).collect()
}

/// Whether extensive quantities are divided by the number of atoms.
pub fn normalize(thermo: &Thermo, state: &State) -> bool {
    thermo.norm.unwrap_or(state.units.style == crate::engine::units::UnitStyle::Lj) && state.natoms() > 0
}

fn temp_compute(w: &World, thermo: &Thermo) -> Result<(f64, f64), String> {
    let c = w.compute(&thermo.temp_id).ok_or_else(|| format!("compute {} (the thermo temperature) is missing", thermo.temp_id))?;
    Ok((c.scalar(w)?, c.dof(w).unwrap_or(0.0)))
}

fn press_compute<'a>(w: &World<'a>, thermo: &Thermo) -> Result<&'a dyn crate::models::compute::Compute, String> {
    w.compute(&thermo.press_id).ok_or_else(|| format!("compute {} (the thermo pressure) is missing", thermo.press_id))
}

/// The value of a thermo keyword, with LAMMPS' normalisation of extensive quantities; `cpu` is
/// the seconds of the last run's loop.
pub fn keyword_value(w: &World, thermo: &Thermo, cpu: f64, name: &str) -> Option<Result<f64, String>> {
    if !KEYWORDS.iter().any(|(k, _)| *k == name) {
        return None;
    }
    Some((|| -> Result<f64, String> {
        let norm = normalize(thermo, w.state);
        let n = w.state.natoms() as f64;
        let ext = |v: f64| if norm { v / n } else { v };
        let e = &w.state.energies;
        let box_value = |f: &dyn Fn(&crate::engine::domain::Domain) -> f64| w.state.domain().map(f);
        // thermo's ke: the temperature's dof kT / 2
        let kinetic = || temp_compute(w, thermo).map(|(t, dof)| t * 0.5 * dof * w.state.units.boltz);
        Ok(match name {
            "step" => w.state.step as f64,
            "elapsed" => (w.state.step - w.state.run_window.map(|w| w.0).unwrap_or(w.state.step)) as f64,
            "elaplong" => (w.state.step - w.state.run_window.map(|w| w.0).unwrap_or(w.state.step)) as f64,
            "dt" => w.state.dt,
            "time" => w.state.time(),
            "cpu" | "tpcpu" | "spcpu" => cpu,
            "atoms" => n,
            "temp" => temp_compute(w, thermo)?.0,
            "press" => press_compute(w, thermo)?.scalar(w)?,
            "pe" => ext(w.pe()),
            "ke" => ext(kinetic()?),
            "etotal" => ext(w.pe()) + ext(kinetic()?),
            // LAMMPS' compute_enthalpy: etotal + press vol / nktv2p (vol per atom when normalised)
            "enthalpy" => {
                let vol = ext(box_value(&|d| d.volume())?);
                ext(w.pe()) + ext(kinetic()?) + press_compute(w, thermo)?.scalar(w)? * vol / w.state.units.nktv2p
            }
            "ecouple" => ext(w.ecouple()),
            // LAMMPS adds the coupling energy to the total energy
            "econserve" => ext(w.ecouple()) + (ext(w.pe()) + ext(kinetic()?)),
            "evdwl" => ext(e.pair.evdwl),
            "ecoul" => ext(e.pair.ecoul),
            "epair" => ext(e.pair.evdwl + e.pair.ecoul),
            "ebond" => ext(e.ebond),
            "eangle" => ext(e.eangle),
            "edihed" => ext(e.edihed),
            "eimp" | "elong" | "etail" => 0.0,
            "emol" => ext(e.ebond + e.eangle + e.edihed),
            "vol" => box_value(&|d| d.volume())?,
            "density" => {
                let m: f64 = (0..w.state.natoms()).map(|i| w.state.mass(i)).sum();
                m / box_value(&|d| d.volume())?
            }
            "lx" => box_value(&|d| d.prd()[0])?,
            "ly" => box_value(&|d| d.prd()[1])?,
            "lz" => box_value(&|d| d.prd()[2])?,
            "xlo" => box_value(&|d| d.lo[0])?,
            "xhi" => box_value(&|d| d.hi[0])?,
            "ylo" => box_value(&|d| d.lo[1])?,
            "yhi" => box_value(&|d| d.hi[1])?,
            "zlo" => box_value(&|d| d.lo[2])?,
            "zhi" => box_value(&|d| d.hi[2])?,
            "xy" => box_value(&|d| d.tilts()[0])?,
            "xz" => box_value(&|d| d.tilts()[1])?,
            "yz" => box_value(&|d| d.tilts()[2])?,
            "cella" | "cellb" | "cellc" | "cellalpha" | "cellbeta" | "cellgamma" => box_value(&|d| cell(d, name))?,
            "xlat" | "ylat" | "zlat" => {
                let s = w.state.lattice_scale()?;
                s[["xlat", "ylat", "zlat"].iter().position(|k| *k == name).unwrap()]
            }
            "bonds" => w.state.topo.bonds.len() as f64,
            "angles" => w.state.topo.angles.len() as f64,
            "dihedrals" => w.state.topo.dihedrals.len() as f64,
            "impropers" => 0.0,
            "pxx" | "pyy" | "pzz" | "pxy" | "pxz" | "pyz" => {
                let v = press_compute(w, thermo)?.vector(w)?;
                v[["pxx", "pyy", "pzz", "pxy", "pxz", "pyz"].iter().position(|k| *k == name).unwrap()]
            }
            "fmax" => w.state.atoms.f[..w.state.natoms()].iter().flat_map(|f| f.iter()).fold(0.0, |m: f64, v| m.max(v.abs())),
            "fnorm" => w.state.atoms.f[..w.state.natoms()].iter().flat_map(|f| f.iter()).map(|v| v * v).sum::<f64>().sqrt(),
            "nbuild" => w.state.neighbor.nbuilds as f64,
            "ndanger" => w.state.neighbor.ndanger as f64,
            _ => unreachable!(),
        })
    })())
}

/// Centre `s` in `width` columns ({fmt} `^` alignment: extra space goes right).
fn center(s: &str, width: usize) -> String {
    let n = s.chars().count();
    if n >= width {
        return s.to_string();
    }
    let left = (width - n) / 2;
    format!("{}{}{}", " ".repeat(left), s, " ".repeat(width - n - left))
}

/// LAMMPS' lattice-cell keywords: the edge lengths a, b, c and the angles between them in
/// degrees (90 for an orthogonal box).
fn cell(d: &crate::engine::domain::Domain, name: &str) -> f64 {
    let h = d.h();
    let tri = d.triclinic();
    let b = (h[1] * h[1] + h[5] * h[5]).sqrt();
    let c = (h[2] * h[2] + h[3] * h[3] + h[4] * h[4]).sqrt();
    let deg = |cos: f64| cos.acos() * 180.0 / std::f64::consts::PI;
    match name {
        "cella" => h[0],
        "cellb" if tri => b,
        "cellb" => h[1],
        "cellc" if tri => c,
        "cellc" => h[2],
        _ if !tri => 90.0,
        "cellalpha" => deg((h[5] * h[4] + h[1] * h[3]) / ((h[1] * h[1] + h[5] * h[5]) * (h[2] * h[2] + h[3] * h[3] + h[4] * h[4])).sqrt()),
        "cellbeta" => deg(h[4] / c),
        _ => deg(h[5] / b),
    }
}

impl Thermo {
    /// LAMMPS' Thermo::init: style one gets a Volume column for a run in which the box can
    /// change (a shrink-wrapped face, or a fix that moves the box or the sub-domains).
    pub fn init_volume_column(&mut self, box_change: bool) {
        if self.volume_added {
            self.columns.pop();
            self.volume_added = false;
        }
        if box_change && !self.custom {
            self.columns.extend(parse_columns(&["vol"]).unwrap());
            self.volume_added = true;
        }
    }

    /// The header printed before a run's first values: the column labels (one line), the
    /// keywords list (yaml), nothing (multi).
    pub fn header(&self) -> Option<String> {
        match self.line {
            LineStyle::Multi => None,
            LineStyle::Yaml => Some(format!("---\nkeywords: [{}]\ndata:", self.columns.iter().map(|c| format!("'{}', ", c.label)).collect::<String>())),
            LineStyle::One => {
                let mut h = String::new();
                for c in &self.columns {
                    h += &center(&c.label, if c.int { 11 } else { 14 });
                    h.push(' ');
                }
                h.pop();
                Some(h)
            }
        }
    }

    /// What ends a run's output (yaml: the end of the document).
    pub fn footer(&self) -> Option<&'static str> {
        (self.line == LineStyle::Yaml).then_some("...")
    }

    fn format_of(&self, k: usize, int: bool) -> String {
        if let Some((_, f)) = self.format_column.iter().find(|(c, _)| *c == k + 1) {
            return f.clone();
        }
        if int {
            if let Some(f) = &self.format_int {
                return f.clone();
            }
        } else if let Some(f) = &self.format_float {
            return f.clone();
        }
        if let Some(line) = &self.format_line {
            if let Some(f) = line.get(k) {
                return f.clone();
            }
        }
        match (self.line, int) {
            (LineStyle::One, true) => "%10d ".to_string(),
            (LineStyle::One, false) => "% -14.8g".to_string(),
            (LineStyle::Multi, true) => "%14d".to_string(),
            (LineStyle::Multi, false) => "%14.4f".to_string(),
            (LineStyle::Yaml, true) => "%d".to_string(),
            (LineStyle::Yaml, false) => "%.15g".to_string(),
        }
    }

    /// Format one step's values (already computed, in column order); `step` and `cpu` (the
    /// seconds of the run so far) head a multi block.
    pub fn format_line(&self, values: &[f64], step: i64, cpu: f64) -> String {
        let text = |k: usize, c: &Column, v: f64| {
            let fmt = self.format_of(k, c.int);
            let s = if c.int { format_printf(&fmt, v.round()) } else { format_printf(&fmt, v) };
            s.unwrap_or_else(|_| format!("{v}"))
        };
        let mut line = String::new();
        match self.line {
            LineStyle::One => {
                for (k, (c, &v)) in self.columns.iter().zip(values).enumerate() {
                    line += &text(k, c, v);
                    line.push(' ');
                }
                line.pop();
            }
            LineStyle::Multi => {
                let cpu = format_printf("%12.7g", cpu).unwrap_or_else(|_| format!("{cpu}"));
                line += &format!("------------ Step {step:14} ----- CPU = {cpu} (sec) -------------");
                for (k, (c, &v)) in self.columns.iter().zip(values).enumerate() {
                    if k % 3 == 0 {
                        line.push('\n');
                    }
                    line += &format!("{:<8} = {} ", c.label, text(k, c, v));
                }
                line.pop();
            }
            LineStyle::Yaml => {
                line += "  - [";
                for (k, (c, &v)) in self.columns.iter().zip(values).enumerate() {
                    line += &text(k, c, v);
                    line += ", ";
                }
                line.push(']');
            }
        }
        line
    }
}

/// Evaluate every column for the current step; extensive compute and fix values are divided by
/// the atom count under `thermo_modify norm yes`, as LAMMPS' thermo output does (expressions see
/// them whole).
pub fn values(thermo: &Thermo, w: &World, ev: &mut dyn EvalContext) -> Result<Vec<f64>, String> {
    let norm = normalize(thermo, w.state);
    let per_atom = |v: f64, extensive: bool| if norm && extensive { v / w.state.natoms() as f64 } else { v };
    let mut out = Vec::with_capacity(thermo.columns.len());
    for c in &thermo.columns {
        let v = match &c.field {
            Field::Keyword(k) => ev.thermo_keyword(k).unwrap()?,
            Field::Compute(id, i) => per_atom(ev.compute_value(id, *i)?, w.compute(id).is_some_and(|c| c.extensive(*i))),
            Field::Fix(id, i) => per_atom(ev.fix_value(id, *i)?, w.fix(id).is_some_and(|f| f.extensive(*i))),
            Field::ComputeArray(id, i, j) => ev.compute_array_value(id, *i, *j)?,
            Field::FixArray(id, i, j) => per_atom(ev.fix_array_value(id, *i, *j)?, w.fix(id).is_some_and(|f| f.array_extensive())),
            Field::Variable(name) => dmhs_parser::variables::compute_equal(ev, name)?,
            Field::VariableElement(name, i) => {
                if ev.variables().style(name) != Some("vector") {
                    return Err(format!("Thermo custom variable {name} is not vector-style (v_{name}[{i}])"));
                }
                let v = ev.vector_variable(name)?;
                *v.get(i - 1).ok_or_else(|| format!("Thermo custom variable v_{name}[{i}]: the vector has {} values", v.len()))?
            }
        };
        out.push(v);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn header_matches_lammps_layout() {
        let t = Thermo::default();
        assert_eq!(
            t.header().unwrap(),
            "   Step          Temp          E_pair         E_mol          TotEng         Press     "
        );
    }
}
