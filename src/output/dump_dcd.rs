//! `dump dcd`: CHARMM/NAMD DCD trajectories (VMD's binary format) as LAMMPS' DumpDCD writes
//! them: Fortran-style records in native byte order, a header fixed by the first snapshot (its
//! step, the dump interval, dt as a float, the atom count), then per snapshot the box (6
//! doubles: a, cos gamma, b, cos beta, cos alpha, c) and the x, y and z arrays of the group's
//! atoms sorted by ID as 32-bit floats. After each snapshot the header's frame count and last
//! step are rewritten, so the file is complete after every snapshot.

use crate::models::world::World;
use std::fs::File;
use std::io::{Seek, SeekFrom, Write};
use std::path::Path;

/// Where the header keeps the frame count and the last snapshot's step.
const NFILE_POS: u64 = 8;
const NSTEP_POS: u64 = 20;

/// What a dump dcd keeps between snapshots.
#[derive(Debug, Default)]
pub struct Dcd {
    file: Option<File>,
    frames: u32,
    /// The group's atom count when the dump was defined (every snapshot must have it).
    pub natoms: usize,
    /// The dump interval of the first snapshot (it may not change).
    every: Option<i64>,
    /// `dump_modify unwrap yes`: unwrapped coordinates.
    pub unwrap: bool,
}

impl Dcd {
    pub fn new(natoms: usize) -> Dcd {
        Dcd { natoms, ..Dcd::default() }
    }

    /// The interval the file's header holds, once the first snapshot is written.
    pub fn fixed_every(&self) -> Option<i64> {
        self.every
    }

    /// One snapshot of the owned atoms `idx` (the dump's group, sorted by ID) to `path`;
    /// `every` is the dump's interval (None: write_dump, written as 0).
    pub fn write(&mut self, w: &World, idx: &[usize], every: Option<i64>, path: &Path) -> Result<(), String> {
        let s = w.state;
        let a = &s.atoms;
        if idx.len() != self.natoms {
            return Err(format!("Dump dcd of non-matching # of atoms: {} in the group now, {} when the dump was defined", idx.len(), self.natoms));
        }
        let step = u32::try_from(s.step).ok().filter(|&t| t <= i32::MAX as u32).ok_or_else(|| format!("Too big a timestep for dump dcd: {}", s.step))?;
        match (self.every, every) {
            (Some(old), Some(new)) if old != new => return Err(format!("Cannot change dump_modify every for dump dcd (from {old} to {new})")),
            (None, _) => self.every = Some(every.unwrap_or(0)),
            _ => {}
        }
        let domain = s.domain.as_ref().ok_or("no simulation box")?;
        let prd = domain.prd();
        let io = |e: std::io::Error| format!("cannot write {}: {e}", path.display());
        if self.file.is_none() {
            // LAMMPS opens the file for writing anew, whatever `append` says
            let mut f = File::create(path).map_err(|e| format!("cannot open {}: {e}", path.display()))?;
            f.write_all(&header(step, self.every.unwrap_or(0), s.dt, self.natoms)).map_err(io)?;
            self.file = Some(f);
            self.frames = 0;
        }
        let mut buf = Vec::with_capacity(56 + 3 * (4 * self.natoms + 8));
        let dim = [prd[0], 0.0, prd[1], 0.0, 0.0, prd[2]];
        record(&mut buf, &dim.iter().flat_map(|v| v.to_ne_bytes()).collect::<Vec<u8>>());
        for d in 0..3 {
            let coord = |i: usize| if self.unwrap { a.x[i][d] + a.image[i][d] as f64 * prd[d] } else { a.x[i][d] };
            let bytes: Vec<u8> = idx.iter().flat_map(|&i| (coord(i) as f32).to_ne_bytes()).collect();
            record(&mut buf, &bytes);
        }
        self.frames += 1;
        let f = self.file.as_mut().expect("opened above");
        f.write_all(&buf).map_err(io)?;
        f.seek(SeekFrom::Start(NFILE_POS)).and_then(|_| f.write_all(&self.frames.to_ne_bytes())).map_err(io)?;
        f.seek(SeekFrom::Start(NSTEP_POS)).and_then(|_| f.write_all(&step.to_ne_bytes())).map_err(io)?;
        f.seek(SeekFrom::End(0)).and_then(|_| f.flush()).map_err(io)?;
        Ok(())
    }
}

/// A Fortran unformatted record: its length, the bytes, its length again.
fn record(out: &mut Vec<u8>, bytes: &[u8]) {
    let n = (bytes.len() as u32).to_ne_bytes();
    out.extend_from_slice(&n);
    out.extend_from_slice(bytes);
    out.extend_from_slice(&n);
}

/// The DCD header (LAMMPS' write_dcd_header, "CHARMM version 24"): frames 0 until the first
/// is written, the first step as start and last step, the interval, dt; two 80-character title
/// lines; the atom count.
fn header(step: u32, every: i64, dt: f64, natoms: usize) -> Vec<u8> {
    let mut out = Vec::with_capacity(276);
    let mut first = Vec::with_capacity(84);
    first.extend_from_slice(b"CORD");
    let ints = |v: &mut Vec<u8>, xs: &[u32]| xs.iter().for_each(|x| v.extend_from_slice(&x.to_ne_bytes()));
    ints(&mut first, &[0, step, every as u32, step, 0, 0, 0, 0, 0]);
    first.extend_from_slice(&(dt as f32).to_ne_bytes());
    ints(&mut first, &[1, 0, 0, 0, 0, 0, 0, 0, 0, 24]);
    record(&mut out, &first);
    let mut title = Vec::with_capacity(164);
    ints(&mut title, &[2]);
    // LAMMPS 22 Jul 2025 pads the first line with NULs, the second with blanks
    title.extend_from_slice(pad80("Written by dmhs", '\0').as_bytes());
    title.extend_from_slice(pad80(&format!("REMARKS Created {}", created_now()), ' ').as_bytes());
    record(&mut out, &title);
    record(&mut out, &(natoms as u32).to_ne_bytes());
    out
}

/// `s` cut or padded with `pad` to 80 bytes (ASCII).
fn pad80(s: &str, pad: char) -> String {
    let mut t: String = s.chars().take(80).collect();
    while t.len() < 80 {
        t.push(pad);
    }
    t
}

/// The time now as LAMMPS' title writes it (`%d %B,%Y at %H:%M`), in UTC.
fn created_now() -> String {
    let secs = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs()) as i64;
    let (days, rem) = (secs.div_euclid(86400), secs.rem_euclid(86400));
    let (y, m, d) = civil_from_days(days);
    const MONTHS: [&str; 12] = ["January", "February", "March", "April", "May", "June", "July", "August", "September", "October", "November", "December"];
    format!("{d:02} {},{y} at {:02}:{:02}", MONTHS[m as usize - 1], rem / 3600, rem % 3600 / 60)
}

/// Year, month (1-12) and day of the days since 1970-01-01 (the proleptic Gregorian
/// calendar; H. Hinnant's algorithm).
fn civil_from_days(z: i64) -> (i64, i64, i64) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    (yoe + era * 400 + i64::from(m <= 2), m, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dates_and_header_layout() {
        assert_eq!(civil_from_days(0), (1970, 1, 1));
        assert_eq!(civil_from_days(20_429), (2025, 12, 7));
        assert_eq!(civil_from_days(-1), (1969, 12, 31));
        let h = header(50, 10, 0.005, 4000);
        // 84-byte record, 164-byte title record, 4-byte count record
        assert_eq!(h.len(), 8 + 84 + 8 + 164 + 8 + 4);
        assert_eq!(&h[4..8], b"CORD");
        assert_eq!(u32::from_ne_bytes(h[NSTEP_POS as usize..NSTEP_POS as usize + 4].try_into().unwrap()), 50);
        assert_eq!(u32::from_ne_bytes(h[h.len() - 8..h.len() - 4].try_into().unwrap()), 4000);
    }
}
