//! What LAMMPS' averaging fixes (fix ave/time, ave/atom, ave/chunk) share: the sampling steps
//! (Nrepeat samples Nevery steps apart, the last on a multiple of Nfreq, at or after `start`),
//! the totals over periods (ave one, running, window) and the output file.

use dmhs_parser::{Args, DResult};

#[derive(Clone, Debug)]
pub struct Sampling {
    pub nevery: i64,
    pub nrepeat: i64,
    pub nfreq: i64,
    /// Lower bound of the Nfreq multiples (fix ave/time `start`).
    pub start: i64,
    /// The next sampling step.
    pub nvalid: i64,
    /// Samples taken in the current period.
    pub irepeat: i64,
}

impl Sampling {
    /// Read `Nevery Nrepeat Nfreq`, checked as LAMMPS does.
    pub fn parse(a: &mut Args, style: &str) -> DResult<Sampling> {
        let nevery = a.i64_in("Nevery", 1, i64::MAX)?;
        let nrepeat = a.i64_in("Nrepeat", 1, i64::MAX)?;
        let w = a.peek();
        let nfreq = a.i64_in("Nfreq", 1, i64::MAX)?;
        if nfreq % nevery != 0 || nrepeat * nevery > nfreq {
            let w = w.expect("Nfreq was read");
            return Err(a.error_at(w, format!("inconsistent fix {style} Nevery/Nrepeat/Nfreq {nevery} {nrepeat} {nfreq}: Nfreq must be a multiple of Nevery and Nrepeat*Nevery <= Nfreq"), "inconsistent"));
        }
        Ok(Sampling { nevery, nrepeat, nfreq, start: 0, nvalid: 0, irepeat: 0 })
    }

    /// LAMMPS' nextvalid: `step` itself if it ends a period of one sample, else the first sample
    /// of the next period.
    pub fn next_valid(&self, step: i64) -> i64 {
        let mut nvalid = (step / self.nfreq) * self.nfreq + self.nfreq;
        while nvalid < self.start {
            nvalid += self.nfreq;
        }
        if nvalid - self.nfreq == step && self.nrepeat == 1 {
            nvalid = step;
        } else {
            nvalid -= (self.nrepeat - 1) * self.nevery;
        }
        if nvalid < step {
            nvalid += self.nfreq;
        }
        nvalid
    }

    /// When the fix is defined.
    pub fn begin(&mut self, step: i64) {
        self.nvalid = self.next_valid(step);
    }

    /// Before a run: a new period if the step moved past the next sample (reset_timestep).
    pub fn init(&mut self, step: i64) {
        if self.nvalid < step {
            self.irepeat = 0;
            self.nvalid = self.next_valid(step);
        }
    }

    /// Whether `step` is a sampling step.
    pub fn due(&self, step: i64) -> bool {
        step == self.nvalid
    }

    /// After the sample of `step`: the next sampling step; true if the sample ended a period.
    pub fn advance(&mut self, step: i64) -> bool {
        self.irepeat += 1;
        if self.irepeat < self.nrepeat {
            self.nvalid += self.nevery;
            return false;
        }
        self.irepeat = 0;
        self.nvalid = step + self.nfreq - (self.nrepeat - 1) * self.nevery;
        true
    }
}

/// How the averages of successive periods combine (`ave one|running|window M`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Ave {
    One,
    Running,
    Window(usize),
}

impl Ave {
    /// The words after the keyword `ave`.
    pub fn parse(a: &mut Args) -> DResult<Ave> {
        Ok(match a.choice("ave", &["one", "running", "window"])? {
            0 => Ave::One,
            1 => Ave::Running,
            _ => Ave::Window(a.usize_min("window length M", 1)?),
        })
    }
}

/// The totals of LAMMPS' averaging fixes over periods: the last period (one), all of them
/// (running) or the last M (window), element by element in LAMMPS' order.
#[derive(Clone, Debug)]
pub struct Combine {
    pub ave: Ave,
    /// Window: the last M periods' rows, oldest replaced first.
    list: Vec<Vec<Vec<f64>>>,
    iwindow: usize,
    full: bool,
    /// The number of periods in the totals.
    pub norm: usize,
}

impl Combine {
    pub fn new(ave: Ave) -> Combine {
        Combine { ave, list: Vec::new(), iwindow: 0, full: false, norm: 0 }
    }

    /// Row `r` of this period's averages `sum` into its total.
    pub fn row(&mut self, r: usize, total: &mut [f64], sum: &[f64]) {
        match self.ave {
            Ave::One => total.copy_from_slice(sum),
            Ave::Running => total.iter_mut().zip(sum).for_each(|(t, s)| *t += s),
            Ave::Window(_) => {
                // slots are made as periods arrive (a window of 4e9 periods is legal until run)
                if self.list.len() <= self.iwindow {
                    self.list.resize(self.iwindow + 1, Vec::new());
                }
                let slot = &mut self.list[self.iwindow];
                if slot.len() <= r {
                    slot.resize(r + 1, Vec::new());
                }
                slot[r].resize(sum.len(), 0.0);
                for (k, (t, s)) in total.iter_mut().zip(sum).enumerate() {
                    *t += s;
                    if self.full {
                        *t -= slot[r][k];
                    }
                    slot[r][k] = *s;
                }
            }
        }
    }

    /// After every row of a period: the number of periods the totals now hold.
    pub fn end_period(&mut self) -> usize {
        self.norm = match self.ave {
            Ave::One => 1,
            Ave::Running => self.norm + 1,
            Ave::Window(m) => {
                self.iwindow += 1;
                if self.iwindow == m {
                    self.iwindow = 0;
                    self.full = true;
                }
                if self.full { m } else { self.iwindow }
            }
        };
        self.norm
    }
}

/// The file of an averaging fix: comment lines, then a block per period; with `overwrite`
/// each block replaces the previous one.
pub struct AveFile {
    file: std::fs::File,
    start: u64,
    overwrite: bool,
}

impl AveFile {
    pub fn create(path: &std::path::Path, head: &str, overwrite: bool) -> std::io::Result<AveFile> {
        use std::io::Write;
        let mut file = std::fs::File::create(path)?;
        file.write_all(head.as_bytes())?;
        Ok(AveFile { file, start: head.len() as u64, overwrite })
    }

    pub fn write(&mut self, block: &str) -> std::io::Result<()> {
        use std::io::{Seek, Write};
        let f = &mut self.file;
        if self.overwrite {
            f.seek(std::io::SeekFrom::Start(self.start))?;
        }
        f.write_all(block.as_bytes())?;
        if self.overwrite {
            let end = f.stream_position()?;
            f.set_len(end)?;
        }
        f.flush()
    }
}

/// One value of a block: the user's `format` or LAMMPS' default ` %g`.
pub fn format_value(format: Option<&str>, x: f64) -> String {
    match format {
        Some(f) => dmhs_parser::numfmt::format_printf(f, x).unwrap_or_default(),
        None => format!(" {}", dmhs_parser::numfmt::format_g(x, 6)),
    }
}

/// The output keywords of the averaging fixes: `overwrite`, `format F`, `file F`,
/// `title1 T`, `title2 T`, `title3 T`.
#[derive(Default)]
pub struct FileOptions<'a> {
    pub overwrite: bool,
    pub format: Option<String>,
    pub file: Option<&'a dmhs_parser::Word>,
    pub titles: [Option<String>; 3],
}

impl<'a> FileOptions<'a> {
    pub const KEYWORDS: [&'static str; 6] = ["overwrite", "format", "file", "title1", "title2", "title3"];

    /// Read keyword `w` (already taken from `a`) and its value if it is one of these; false if
    /// it is another keyword.
    pub fn keyword(&mut self, w: &dmhs_parser::Word, a: &mut Args<'a>) -> DResult<bool> {
        match w.text.as_str() {
            "overwrite" => self.overwrite = true,
            "format" => self.format = Some(a.printf_format("format")?.to_string()),
            "file" => self.file = Some(a.word("file name")?),
            "title1" | "title2" | "title3" => {
                let k = (w.text.as_bytes()[5] - b'1') as usize;
                self.titles[k] = Some(a.str("title")?.to_string());
            }
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// `overwrite` needs `ave running`, as LAMMPS says.
    pub fn check(&self, ave: Ave, a: &Args) -> DResult<()> {
        if self.overwrite && ave != Ave::Running {
            return Err(a.missing("`ave running` (the overwrite keyword requires it)"));
        }
        Ok(())
    }
}
