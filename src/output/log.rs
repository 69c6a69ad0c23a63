//! Where text goes: the screen and the log file (LAMMPS' `-screen`, `-log`, `log`).
//! Files that must never be left half-written use [`write_atomic`].

use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

#[derive(Default)]
pub struct Output {
    pub screen: bool,
    log: Option<(PathBuf, BufWriter<File>)>,
    /// Captured text (for tests and the library API), when enabled.
    pub captured: Option<String>,
    /// A rank other than 0 of a distributed run: it writes no screen text and no log (rank 0
    /// writes them, as LAMMPS' rank 0 does).
    pub muted: bool,
    pub warnings: Warnings,
}

/// LAMMPS' count of warnings and its limit (`thermo_modify warn`): every line printed that
/// starts with `WARNING: ` counts, and one past the limit is not printed.
#[derive(Clone, Copy, Debug)]
pub struct Warnings {
    pub count: u64,
    /// The most printed: 0 every one (`always`), negative none (`ignore`); LAMMPS' default 100.
    pub max: i64,
    /// The "Too many warnings" notice was printed (once per thermo style, as LAMMPS).
    pub noticed: bool,
}

impl Default for Warnings {
    fn default() -> Self {
        Warnings { count: 0, max: 100, noticed: false }
    }
}

impl Warnings {
    /// Count one warning; whether it is printed (LAMMPS' Error::warning).
    fn admit(&mut self) -> bool {
        self.count += 1;
        self.max == 0 || (self.max > 0 && self.count <= self.max as u64)
    }
}

impl Output {
    pub fn new(screen: bool) -> Output {
        Output { screen, log: None, captured: None, muted: false, warnings: Warnings::default() }
    }
    /// LAMMPS' notice at a thermo output once the warnings passed their limit.
    pub fn warnings_notice(&mut self) {
        let w = self.warnings;
        if w.max > 0 && !w.noticed && w.count > w.max as u64 {
            self.warnings.noticed = true;
            self.emit(&format!("WARNING: Too many warnings: {} vs {}. All future warnings will be suppressed", w.count, w.max), true, true);
        }
    }
    /// Open (or append to) a log file; `None` closes the current log.
    pub fn set_log(&mut self, path: Option<&Path>, append: bool) -> std::io::Result<()> {
        if let Some((_, mut w)) = self.log.take() {
            let _ = w.flush();
        }
        if self.muted {
            return Ok(());
        }
        if let Some(p) = path {
            let f = if append { OpenOptions::new().create(true).append(true).open(p)? } else { File::create(p)? };
            self.log = Some((p.to_path_buf(), BufWriter::new(f)));
        }
        Ok(())
    }
    pub fn log_path(&self) -> Option<&Path> {
        self.log.as_ref().map(|(p, _)| p.as_path())
    }
    /// Text to screen and log.
    pub fn print(&mut self, text: &str) {
        self.print_to(text, true, true);
    }
    pub fn print_to(&mut self, text: &str, screen: bool, log: bool) {
        if text.starts_with("WARNING: ") && !self.warnings.admit() {
            return;
        }
        self.emit(text, screen, log);
    }
    fn emit(&mut self, text: &str, screen: bool, log: bool) {
        if self.muted {
            return;
        }
        if screen && self.screen {
            let mut out = std::io::stdout().lock();
            let _ = out.write_all(text.as_bytes());
            if !text.ends_with('\n') {
                let _ = out.write_all(b"\n");
            }
        }
        if log {
            self.log_only(text);
        }
        if let Some(c) = &mut self.captured {
            c.push_str(text);
            if !text.ends_with('\n') {
                c.push('\n');
            }
        }
    }
    /// Text to the log file only (not the screen, not the captured text): the error that
    /// stopped a deck, which the command line writes to stderr, so that the log ends with it
    /// as LAMMPS' log.lammps ends with its ERROR line.
    pub fn log_only(&mut self, text: &str) {
        if let Some((_, w)) = &mut self.log {
            let _ = w.write_all(text.as_bytes());
            if !text.ends_with('\n') {
                let _ = w.write_all(b"\n");
            }
        }
    }
    pub fn flush(&mut self) {
        if let Some((_, w)) = &mut self.log {
            let _ = w.flush();
        }
        let _ = std::io::stdout().flush();
    }
}

impl Drop for Output {
    fn drop(&mut self) {
        self.flush();
    }
}

/// Write a whole file so that readers see either the old file or the complete new one
/// (written to a temporary file in the same directory, then renamed over the target).
pub fn write_atomic(path: &Path, contents: &[u8]) -> std::io::Result<()> {
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let mut tmp = temp_file_in(dir, "")?;
    tmp.write_all(contents)?;
    tmp.flush()?;
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// A temporary file in `dir` (name ending in `suffix`) to be renamed over a target: created
/// with the permissions of an ordinary new file (0666 less the umask, not tempfile's 0600).
pub fn temp_file_in(dir: &Path, suffix: &str) -> std::io::Result<tempfile::NamedTempFile> {
    let mut b = tempfile::Builder::new();
    b.prefix(".dmhs").suffix(suffix);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        b.permissions(std::fs::Permissions::from_mode(0o666));
    }
    b.tempfile_in(dir)
}

/// A file name from a command, resolved against the deck's folder `base` (None: the working
/// directory).
pub fn resolve_path(base: Option<&Path>, name: &str) -> std::path::PathBuf {
    match base {
        Some(d) if Path::new(name).is_relative() => d.join(name),
        _ => std::path::PathBuf::from(name),
    }
}
