//! Small line/scatter charts drawn with `plotters`, written as PNG and SVG (the validation report's
//! figures). Linear or logarithmic axes, axis labels, a legend, optional per-point labels.
//!
//! ```no_run
//! use dmhs::output::plot::{Chart, Series};
//! let chart = Chart::new("Poiseuille flow")
//!     .x_label("y (mm)")
//!     .y_label("u (mm/s)")
//!     .series(Series::line("analytic", vec![(0.0, 0.0), (0.5, 0.025), (1.0, 0.0)]))
//!     .series(Series::points("dmhs", vec![(0.25, 0.019)]));
//! chart.save(std::path::Path::new("out/poiseuille")).unwrap(); // out/poiseuille.png, .svg
//! ```
//!
//! Text is rasterised in pure Rust (no fontconfig/freetype needed to build): the first TrueType font
//! found among `$DMHS_FONT` and the usual system paths (Debian: fonts-dejavu-core) is used.

use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// TrueType fonts tried in order when `$DMHS_FONT` is not set.
const FONT_PATHS: &[&str] = &[
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
    "/usr/share/fonts/liberation-sans/LiberationSans-Regular.ttf",
    "/usr/share/fonts/truetype/freefont/FreeSans.ttf",
    "/usr/share/fonts/truetype/noto/NotoSans-Regular.ttf",
    "/System/Library/Fonts/Supplemental/Arial.ttf",
    "/Library/Fonts/Arial.ttf",
    "C:\\Windows\\Fonts\\arial.ttf",
];

/// Register the chart font under the name "sans-serif" once per process.
fn ensure_font() -> Result<(), String> {
    static FONT: std::sync::OnceLock<Result<(), String>> = std::sync::OnceLock::new();
    FONT.get_or_init(|| {
        let from_env = std::env::var("DMHS_FONT").ok().filter(|p| !p.is_empty());
        let candidates: Vec<String> = match &from_env {
            Some(p) => vec![p.clone()],
            None => FONT_PATHS.iter().map(|p| p.to_string()).collect(),
        };
        for path in &candidates {
            let Ok(bytes) = std::fs::read(path) else { continue };
            // plotters keeps fonts for the life of the process
            let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
            return plotters::style::register_font("sans-serif", FontStyle::Normal, bytes)
                .map_err(|_| format!("{path}: not a TrueType font"));
        }
        Err(match from_env {
            Some(p) => format!("DMHS_FONT={p}: cannot read the font file"),
            None => "charts need a TrueType font: install one (Debian: apt-get install fonts-dejavu-core) or set DMHS_FONT=/path/to/font.ttf".to_string(),
        })
    })
    .clone()
}

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mark {
    Line,
    Dashed,
    Points,
    LinePoints,
}

/// One named series of (x, y) points.
#[derive(Clone, Debug)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub mark: Mark,
    /// Index into the palette (default: the series' position in the chart).
    pub color: Option<usize>,
    /// Text drawn beside each point (empty: none).
    pub labels: Vec<String>,
}

impl Series {
    fn new(name: &str, points: Vec<(f64, f64)>, mark: Mark) -> Series {
        Series { name: name.to_string(), points, mark, color: None, labels: vec![] }
    }
    pub fn line(name: &str, points: Vec<(f64, f64)>) -> Series {
        Series::new(name, points, Mark::Line)
    }
    pub fn dashed(name: &str, points: Vec<(f64, f64)>) -> Series {
        Series::new(name, points, Mark::Dashed)
    }
    pub fn points(name: &str, points: Vec<(f64, f64)>) -> Series {
        Series::new(name, points, Mark::Points)
    }
    pub fn line_points(name: &str, points: Vec<(f64, f64)>) -> Series {
        Series::new(name, points, Mark::LinePoints)
    }
    pub fn color(mut self, index: usize) -> Series {
        self.color = Some(index);
        self
    }
    pub fn labels(mut self, labels: Vec<String>) -> Series {
        self.labels = labels;
        self
    }
}

/// Where the legend goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Legend {
    UpperLeft,
    UpperRight,
    LowerLeft,
    LowerRight,
    None,
}

/// A chart: axes, labels, series.
#[derive(Clone, Debug)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_log: bool,
    pub y_log: bool,
    /// Axis ranges (None: from the data, with a margin).
    pub x_range: Option<(f64, f64)>,
    pub y_range: Option<(f64, f64)>,
    pub legend: Legend,
    pub size: (u32, u32),
    pub series: Vec<Series>,
}

/// Distinguishable colours (Okabe-Ito, then a few more).
const PALETTE: [(u8, u8, u8); 10] = [
    (0, 114, 178),
    (213, 94, 0),
    (0, 158, 115),
    (204, 121, 167),
    (230, 159, 0),
    (86, 180, 233),
    (0, 0, 0),
    (240, 228, 66),
    (120, 120, 120),
    (150, 60, 30),
];

pub fn palette(index: usize) -> RGBColor {
    let (r, g, b) = PALETTE[index % PALETTE.len()];
    RGBColor(r, g, b)
}

impl Chart {
    pub fn new(title: &str) -> Chart {
        Chart {
            title: title.to_string(),
            x_label: String::new(),
            y_label: String::new(),
            x_log: false,
            y_log: false,
            x_range: None,
            y_range: None,
            legend: Legend::UpperRight,
            size: (900, 600),
            series: vec![],
        }
    }
    pub fn x_label(mut self, s: &str) -> Chart {
        self.x_label = s.to_string();
        self
    }
    pub fn y_label(mut self, s: &str) -> Chart {
        self.y_label = s.to_string();
        self
    }
    pub fn log_x(mut self) -> Chart {
        self.x_log = true;
        self
    }
    pub fn log_y(mut self) -> Chart {
        self.y_log = true;
        self
    }
    pub fn x_range(mut self, lo: f64, hi: f64) -> Chart {
        self.x_range = Some((lo, hi));
        self
    }
    pub fn y_range(mut self, lo: f64, hi: f64) -> Chart {
        self.y_range = Some((lo, hi));
        self
    }
    pub fn legend(mut self, at: Legend) -> Chart {
        self.legend = at;
        self
    }
    pub fn series(mut self, s: Series) -> Chart {
        self.series.push(s);
        self
    }

    /// Write `stem.png` and `stem.svg` (creating the folder); returns the two paths.
    pub fn save(&self, stem: &Path) -> Result<Vec<PathBuf>, String> {
        ensure_font()?;
        if let Some(dir) = stem.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        }
        let png = stem.with_extension("png");
        let svg = stem.with_extension("svg");
        self.draw(BitMapBackend::new(&png, self.size).into_drawing_area()).map_err(|e| format!("{}: {e}", png.display()))?;
        self.draw(SVGBackend::new(&svg, self.size).into_drawing_area()).map_err(|e| format!("{}: {e}", svg.display()))?;
        Ok(vec![png, svg])
    }

    /// Write one file, SVG if the name ends in .svg and PNG otherwise, atomically (drawn into a
    /// temporary file in the same folder, then renamed).
    pub fn save_as(&self, path: &Path) -> Result<(), String> {
        ensure_font()?;
        let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
        std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        let svg = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("svg"));
        let tmp = crate::output::log::temp_file_in(dir, if svg { ".svg" } else { ".png" }).map_err(|e| format!("{}: {e}", dir.display()))?;
        if svg {
            self.draw(SVGBackend::new(tmp.path(), self.size).into_drawing_area())
        } else {
            self.draw(BitMapBackend::new(tmp.path(), self.size).into_drawing_area())
        }
        .map_err(|e| format!("{}: {e}", path.display()))?;
        tmp.persist(path).map_err(|e| format!("{}: {}", path.display(), e.error))?;
        Ok(())
    }

    /// The axis range of one coordinate: the given one, or the data's with a margin.
    fn range(&self, given: Option<(f64, f64)>, log: bool, coord: impl Fn(&(f64, f64)) -> f64) -> Result<(f64, f64), String> {
        if let Some(r) = given {
            return Ok(r);
        }
        let vals: Vec<f64> = self.series.iter().flat_map(|s| s.points.iter().map(&coord)).filter(|v| v.is_finite() && (!log || *v > 0.0)).collect();
        if vals.is_empty() {
            return Err(format!("chart `{}`: no data to plot", self.title));
        }
        let lo = vals.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = vals.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        Ok(if log {
            // a third of a decade around the data
            (lo / 10f64.powf(1.0 / 3.0), hi * 10f64.powf(1.0 / 3.0))
        } else if hi > lo {
            let m = 0.05 * (hi - lo);
            (lo - m, hi + m)
        } else {
            (lo - 0.5 * lo.abs().max(1.0), hi + 0.5 * hi.abs().max(1.0))
        })
    }

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String> {
        let (x0, x1) = self.range(self.x_range, self.x_log, |p| p.0)?;
        let (y0, y1) = self.range(self.y_range, self.y_log, |p| p.1)?;
        match (self.x_log, self.y_log) {
            (false, false) => self.render(root, x0..x1, y0..y1),
            (true, false) => self.render(root, (x0..x1).log_scale(), y0..y1),
            (false, true) => self.render(root, x0..x1, (y0..y1).log_scale()),
            (true, true) => self.render(root, (x0..x1).log_scale(), (y0..y1).log_scale()),
        }
    }

    fn render<DB, X, Y>(&self, root: DrawingArea<DB, Shift>, xr: X, yr: Y) -> Result<(), String>
    where
        DB: DrawingBackend,
        X: AsRangedCoord<Value = f64>,
        Y: AsRangedCoord<Value = f64>,
        X::CoordDescType: ValueFormatter<f64>,
        Y::CoordDescType: ValueFormatter<f64>,
    {
        let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        root.fill(&WHITE).map_err(err)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(&self.title, ("sans-serif", 22))
            .margin(14)
            .x_label_area_size(48)
            .y_label_area_size(78)
            .build_cartesian_2d(xr, yr)
            .map_err(err)?;
        let fx = |v: &f64| number(*v);
        let fy = |v: &f64| number(*v);
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .x_label_formatter(&fx)
            .y_label_formatter(&fy)
            .label_style(("sans-serif", 15))
            .axis_desc_style(("sans-serif", 17))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(err)?;
        for (k, s) in self.series.iter().enumerate() {
            let color = palette(s.color.unwrap_or(k));
            let inside = |v: f64, r: Option<(f64, f64)>| r.is_none_or(|(lo, hi)| lo <= v && v <= hi);
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .cloned()
                .filter(|(x, y)| x.is_finite() && y.is_finite() && (!self.x_log || *x > 0.0) && (!self.y_log || *y > 0.0))
                .filter(|(x, y)| inside(*x, self.x_range) && inside(*y, self.y_range))
                .collect();
            let line = color.stroke_width(2);
            let legend_mark = s.mark;
            let anno = match s.mark {
                Mark::Line | Mark::LinePoints => chart.draw_series(LineSeries::new(pts.clone(), line)).map_err(err)?,
                Mark::Dashed => chart.draw_series(DashedLineSeries::new(pts.clone(), 8, 5, line)).map_err(err)?,
                Mark::Points => chart.draw_series(pts.iter().map(|&p| Circle::new(p, 4, color.filled()))).map_err(err)?,
            };
            if !s.name.is_empty() {
                anno.label(&s.name).legend(move |(x, y)| -> DynElement<'static, DB, (i32, i32)> {
                    match legend_mark {
                        Mark::Points => Circle::new((x + 10, y), 4, color.filled()).into_dyn(),
                        Mark::Dashed => PathElement::new(vec![(x, y), (x + 7, y)], line).into_dyn(),
                        _ => PathElement::new(vec![(x, y), (x + 20, y)], line).into_dyn(),
                    }
                });
            }
            if s.mark == Mark::LinePoints {
                chart.draw_series(pts.iter().map(|&p| Circle::new(p, 4, color.filled()))).map_err(err)?;
            }
            if !s.labels.is_empty() {
                let style = TextStyle::from(("sans-serif", 13).into_font()).color(&color);
                chart
                    .draw_series(pts.iter().zip(&s.labels).map(|(&p, l)| EmptyElement::at(p) + Text::new(l.clone(), (6, -16), style.clone())))
                    .map_err(err)?;
            }
        }
        let pos = match self.legend {
            Legend::UpperLeft => Some(SeriesLabelPosition::UpperLeft),
            Legend::UpperRight => Some(SeriesLabelPosition::UpperRight),
            Legend::LowerLeft => Some(SeriesLabelPosition::LowerLeft),
            Legend::LowerRight => Some(SeriesLabelPosition::LowerRight),
            Legend::None => None,
        };
        if let Some(pos) = pos {
            if self.series.iter().any(|s| !s.name.is_empty()) {
                chart
                    .configure_series_labels()
                    .position(pos)
                    .label_font(("sans-serif", 15))
                    .background_style(WHITE.mix(0.85))
                    .border_style(RGBColor(150, 150, 150))
                    .draw()
                    .map_err(err)?;
            }
        }
        root.present().map_err(err)?;
        Ok(())
    }
}

/// Compact axis numbers: 0.001, 2.5e-5, 120, 1e6.
pub fn number(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if !(1e-3..1e5).contains(&a) {
        let s = format!("{v:.2e}");
        // 1.00e-5 -> 1e-5, 2.50e-5 -> 2.5e-5
        let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
        let m = m.trim_end_matches('0').trim_end_matches('.');
        return format!("{m}e{e}");
    }
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers() {
        assert_eq!(number(0.0), "0");
        assert_eq!(number(0.001), "0.001");
        assert_eq!(number(2.5e-5), "2.5e-5");
        assert_eq!(number(1e-6), "1e-6");
        assert_eq!(number(120.0), "120");
        assert_eq!(number(0.30000000000000004), "0.3");
        assert_eq!(number(1e6), "1e6");
    }

    #[test]
    fn draws_png_and_svg() {
        let dir = tempfile::tempdir().unwrap();
        let chart = Chart::new("test chart")
            .x_label("x")
            .y_label("y")
            .log_x()
            .log_y()
            .series(Series::line_points("a", vec![(1.0, 0.1), (10.0, 0.01), (100.0, 0.001)]).labels(vec!["N=10".into(), "N=20".into(), "N=40".into()]))
            .series(Series::points("b", vec![(2.0, 0.05)]))
            .series(Series::dashed("c", vec![(1.0, 0.2), (100.0, 0.002)]));
        let files = chart.save(&dir.path().join("sub/chart")).unwrap();
        let png = std::fs::read(&files[0]).unwrap();
        assert_eq!(&png[1..4], b"PNG");
        let svg = std::fs::read_to_string(&files[1]).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("test chart") && svg.contains("N=20"));
        // a linear chart with a single point (degenerate range) also draws
        Chart::new("one").series(Series::points("p", vec![(1.0, 1.0)])).save(&dir.path().join("one")).unwrap();
        // no data is an error, not a panic
        assert!(Chart::new("empty").save(&dir.path().join("empty")).is_err());
    }
}
