//! `dmhs plot`: time series from a LAMMPS-layout thermo log (dmhs' or LAMMPS' own; every run's
//! thermo table), a `fix ave/time` file, or whitespace/comma columns under a header line, drawn
//! as lines with [`crate::output::plot`] into PNG or SVG (by the output's extension).

use crate::output::plot::{Chart, Legend, Series};
use std::path::{Path, PathBuf};

pub const USAGE: &str = "\
usage: dmhs plot FILE [--x COLUMN] [--y COL1,COL2,...] [-o OUT.png|OUT.svg] [--title TEXT] [--logy]
  FILE   a thermo log (LAMMPS layout: every run's table is read), a fix ave/time file, or
         columns (whitespace or commas) under a header line
  --x    the x column (default: the first column, e.g. Step)
  --y    comma-separated y columns (default: every other column)
  -o     output file; .svg gives SVG, anything else PNG (default: FILE with extension .png)
  --logy logarithmic y axis
";

/// Named columns of numbers; rows may miss columns (runs with different thermo styles).
#[derive(Debug, Default)]
pub struct Table {
    pub columns: Vec<String>,
    /// One value per column per row (NaN where a run did not have the column).
    pub rows: Vec<Vec<f64>>,
}

impl Table {
    fn column_index(&mut self, name: &str) -> usize {
        match self.columns.iter().position(|c| c == name) {
            Some(k) => k,
            None => {
                self.columns.push(name.to_string());
                for r in &mut self.rows {
                    r.push(f64::NAN);
                }
                self.columns.len() - 1
            }
        }
    }

    fn push_section(&mut self, header: &[String], rows: Vec<Vec<f64>>) {
        let map: Vec<usize> = header.iter().map(|h| self.column_index(h)).collect();
        for r in rows {
            let mut row = vec![f64::NAN; self.columns.len()];
            for (k, v) in r.into_iter().enumerate() {
                row[map[k]] = v;
            }
            self.rows.push(row);
        }
    }

    /// The column called `name` (exact, else ignoring case); the error lists the columns.
    pub fn find(&self, name: &str) -> Result<usize, String> {
        self.columns
            .iter()
            .position(|c| c == name)
            .or_else(|| self.columns.iter().position(|c| c.eq_ignore_ascii_case(name)))
            .ok_or_else(|| format!("no column `{name}`; the columns are: {}", self.columns.join(", ")))
    }
}

fn numbers(line: &str) -> Option<Vec<f64>> {
    let v: Result<Vec<f64>, _> = split(line).iter().map(|t| t.parse::<f64>()).collect();
    v.ok().filter(|v| !v.is_empty())
}

fn split(line: &str) -> Vec<&str> {
    line.split(|c: char| c.is_whitespace() || c == ',').filter(|t| !t.is_empty()).collect()
}

/// Parse a thermo log or a column file.
pub fn read_table(text: &str) -> Result<Table, String> {
    let mut t = Table::default();
    let lines: Vec<&str> = text.lines().collect();
    let is_log = lines.iter().any(|l| l.starts_with("Per MPI rank memory allocation") || l.starts_with("Loop time of"));
    if is_log {
        // each run: the header after "Per MPI rank memory", numeric rows until "Loop time of"
        let mut i = 0;
        while i < lines.len() {
            if !lines[i].starts_with("Per MPI rank memory allocation") {
                i += 1;
                continue;
            }
            i += 1;
            while i < lines.len() && lines[i].trim().is_empty() {
                i += 1;
            }
            let Some(h) = lines.get(i) else { break };
            let header: Vec<String> = split(h).iter().map(|s| s.to_string()).collect();
            let mut rows = vec![];
            i += 1;
            while i < lines.len() && !lines[i].starts_with("Loop time of") && !lines[i].starts_with("Per MPI rank memory allocation") {
                if let Some(v) = numbers(lines[i]) {
                    if v.len() == header.len() {
                        rows.push(v);
                    }
                }
                i += 1;
            }
            t.push_section(&header, rows);
        }
        if t.columns.is_empty() {
            return Err("no thermo table found in the log (looked for `Per MPI rank memory allocation` followed by a header line)".into());
        }
        return Ok(t);
    }
    // columns: the header is the last comment or text line before the first numeric row
    let mut header: Option<Vec<String>> = None;
    let mut rows = vec![];
    for line in &lines {
        let s = line.trim();
        if s.is_empty() {
            continue;
        }
        if let Some(v) = numbers(s) {
            let h = header.as_ref().ok_or("the first numeric row comes before any header line (expected a line of column names)")?;
            if v.len() == h.len() {
                rows.push(v);
            }
            continue;
        }
        if rows.is_empty() {
            let s = s.trim_start_matches('#').trim();
            header = Some(split(s).iter().map(|x| x.to_string()).collect());
        }
    }
    let header = header.ok_or("no header line with column names")?;
    if rows.is_empty() {
        return Err(format!("no rows of {} numbers under the header `{}`", header.len(), header.join(" ")));
    }
    t.push_section(&header, rows);
    Ok(t)
}

#[derive(Debug, Default)]
struct Options {
    file: Option<PathBuf>,
    x: Option<String>,
    y: Vec<String>,
    out: Option<PathBuf>,
    title: Option<String>,
    logy: bool,
}

fn parse(args: &[String]) -> Result<Options, String> {
    let mut o = Options::default();
    let mut i = 0;
    while i < args.len() {
        let a = args[i].as_str();
        let value = || args.get(i + 1).cloned().ok_or_else(|| format!("{a} needs a value"));
        match a {
            "--x" | "-x" => o.x = Some(value()?),
            "--y" | "-y" => o.y.extend(value()?.split(',').map(|s| s.trim().to_string()).filter(|s| !s.is_empty())),
            "-o" | "--out" => o.out = Some(PathBuf::from(value()?)),
            "--title" => o.title = Some(value()?),
            "--logy" => {
                o.logy = true;
                i += 1;
                continue;
            }
            _ if a.starts_with('-') && a.len() > 1 => return Err(format!("unknown option {a}")),
            _ if o.file.is_none() => {
                o.file = Some(PathBuf::from(a));
                i += 1;
                continue;
            }
            _ => return Err(format!("unexpected argument `{a}` (one input file)")),
        }
        i += 2;
    }
    Ok(o)
}

/// Draw the chart; returns the file written.
pub fn plot_file(file: &Path, x: Option<&str>, ys: &[String], out: Option<&Path>, title: Option<&str>, logy: bool) -> Result<PathBuf, String> {
    let text = std::fs::read_to_string(file).map_err(|e| format!("cannot read {}: {e}", file.display()))?;
    let table = read_table(&text).map_err(|e| format!("{}: {e}", file.display()))?;
    let xi = match x {
        Some(name) => table.find(name)?,
        None => 0,
    };
    let yis: Vec<usize> = if ys.is_empty() { (0..table.columns.len()).filter(|&k| k != xi).collect() } else { ys.iter().map(|y| table.find(y)).collect::<Result<_, _>>()? };
    if yis.is_empty() {
        return Err(format!("nothing to plot: the only column is `{}`", table.columns[xi]));
    }
    let name = file.file_name().map(|s| s.to_string_lossy().to_string()).unwrap_or_default();
    let mut chart = Chart::new(title.unwrap_or(&name)).x_label(&table.columns[xi]).legend(if yis.len() > 1 { Legend::UpperRight } else { Legend::None });
    if yis.len() == 1 {
        chart = chart.y_label(&table.columns[yis[0]]);
    }
    if logy {
        chart = chart.log_y();
    }
    for &k in &yis {
        let pts: Vec<(f64, f64)> = table.rows.iter().map(|r| (r[xi], r[k])).filter(|(a, b)| a.is_finite() && b.is_finite()).collect();
        chart = chart.series(Series::line(&table.columns[k], pts));
    }
    let out = out.map(Path::to_path_buf).unwrap_or_else(|| file.with_extension("png"));
    chart.save_as(&out)?;
    Ok(out)
}

/// `dmhs plot ...`; returns the exit code.
pub fn plot_cmd(args: &[String]) -> i32 {
    let o = match parse(args) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("dmhs plot: {e}\n{USAGE}");
            return 2;
        }
    };
    let Some(file) = o.file else {
        eprint!("dmhs plot: give a log or column file\n{USAGE}");
        return 2;
    };
    match plot_file(&file, o.x.as_deref(), &o.y, o.out.as_deref(), o.title.as_deref(), o.logy) {
        Ok(p) => {
            println!("wrote {}", p.display());
            0
        }
        Err(e) => {
            eprintln!("dmhs plot: {e}");
            1
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LOG: &str = "LAMMPS (22 Jul 2025)
Per MPI rank memory allocation (min/avg/max) = 3 | 3 | 3 Mbytes
   Step          Temp          KinEng
         0   1              1.5
        50   0.9            1.35
Loop time of 0.1 on 1 procs for 50 steps with 10 atoms

thermo_style custom step temp press
Per MPI rank memory allocation (min/avg/max) = 3 | 3 | 3 Mbytes
   Step          Temp          Press
        50   0.9            2
WARNING: something (src/x.cpp:1)
       100   0.8            3
Loop time of 0.1 on 1 procs for 50 steps with 10 atoms
";

    #[test]
    fn log_sections_are_joined_by_column_name() {
        let t = read_table(LOG).unwrap();
        assert_eq!(t.columns, ["Step", "Temp", "KinEng", "Press"]);
        assert_eq!(t.rows.len(), 4);
        assert_eq!(t.rows[3][..2], [100.0, 0.8]);
        assert!(t.rows[3][2].is_nan() && t.rows[0][3].is_nan());
        assert_eq!(t.find("temp").unwrap(), 1);
        let e = t.find("Volume").unwrap_err();
        assert!(e.contains("no column `Volume`") && e.contains("Step, Temp, KinEng, Press"), "{e}");
    }

    #[test]
    fn ave_time_and_csv_files() {
        let ave = "# Time-averaged data for fix 1\n# TimeStep c_t c_p\n100 1.0 2.0\n200 1.5 2.5\n";
        let t = read_table(ave).unwrap();
        assert_eq!(t.columns, ["TimeStep", "c_t", "c_p"]);
        assert_eq!(t.rows, vec![vec![100.0, 1.0, 2.0], vec![200.0, 1.5, 2.5]]);
        let csv = "t,x\n0,1\n1,2e-3\n";
        let t = read_table(csv).unwrap();
        assert_eq!(t.rows[1], vec![1.0, 0.002]);
        assert!(read_table("1 2 3\n").is_err());
    }

    #[test]
    fn options() {
        let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        let o = parse(&s(&["log.dmhs", "--x", "Step", "--y", "KE,Temp", "-o", "a.svg", "--title", "T", "--logy"])).unwrap();
        assert_eq!(o.y, ["KE", "Temp"]);
        assert_eq!(o.out, Some(PathBuf::from("a.svg")));
        assert!(o.logy && o.title.as_deref() == Some("T"));
        assert!(parse(&s(&["a", "b"])).is_err());
        assert!(parse(&s(&["a", "--bogus"])).is_err());
        assert!(parse(&s(&["a", "--x"])).is_err());
    }
}
