//! Running an engine as a child process and measuring its peak memory: the sum, over the
//! processes of the child's tree that run the engine (the MPI ranks under `mpiexec`, or the one
//! process), of each one's high-water resident set (VmHWM in /proc/PID/status). VmHWM only grows,
//! so its last reading before a process exits is its peak (up to the polling interval).

use std::collections::HashMap;
use std::io::Read;
use std::process::{Command, ExitStatus, Stdio};
use std::time::Duration;

/// What a measured child process left: its exit status, stdout and stderr, and the peak memory
/// of its engine processes in bytes (None where /proc could not be read).
pub struct Measured {
    pub status: ExitStatus,
    pub stdout: String,
    pub stderr: String,
    pub peak_bytes: Option<u64>,
}

/// (parent PID, command name) of every process in /proc.
fn process_table() -> HashMap<u32, (u32, String)> {
    let mut table = HashMap::new();
    let Ok(dir) = std::fs::read_dir("/proc") else { return table };
    for entry in dir.flatten() {
        let Ok(pid) = entry.file_name().to_string_lossy().parse::<u32>() else { continue };
        let Ok(stat) = std::fs::read_to_string(entry.path().join("stat")) else { continue };
        // "PID (comm) state PPID ...": comm may hold spaces and parentheses, so split at the last ')'
        let (Some(open), Some(close)) = (stat.find('('), stat.rfind(')')) else { continue };
        let comm = stat[open + 1..close].to_string();
        let Some(ppid) = stat[close + 1..].split_whitespace().nth(1).and_then(|w| w.parse().ok()) else { continue };
        table.insert(pid, (ppid, comm));
    }
    table
}

/// VmHWM of process `pid` in bytes.
fn high_water(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let kb: u64 = status.lines().find(|l| l.starts_with("VmHWM:"))?.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// Whether `pid` is `root` or a descendant of it in `table`.
fn descends_from(pid: u32, root: u32, table: &HashMap<u32, (u32, String)>) -> bool {
    let mut p = pid;
    for _ in 0..64 {
        if p == root {
            return true;
        }
        match table.get(&p) {
            Some(&(parent, _)) if parent != 0 => p = parent,
            _ => return false,
        }
    }
    false
}

/// Run `cmd` to completion, polling every `interval` the high-water memory of the processes in
/// its tree whose command name is `engine` (the kernel's name: the executable's file name, cut to
/// 15 bytes).
pub fn run_measured(cmd: &mut Command, engine: &str, interval: Duration) -> std::io::Result<Measured> {
    let engine: String = engine.chars().take(15).collect();
    let mut child = cmd.stdin(Stdio::null()).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn()?;
    // drain the pipes on their own threads so that a chatty child never blocks on a full pipe
    let drain = |pipe: Option<Box<dyn Read + Send>>| {
        std::thread::spawn(move || {
            let mut text = Vec::new();
            if let Some(mut p) = pipe {
                let _ = p.read_to_end(&mut text);
            }
            String::from_utf8_lossy(&text).into_owned()
        })
    };
    let out = drain(child.stdout.take().map(|p| Box::new(p) as Box<dyn Read + Send>));
    let err = drain(child.stderr.take().map(|p| Box::new(p) as Box<dyn Read + Send>));
    let root = child.id();
    let start = std::time::Instant::now();
    let mut peaks: HashMap<u32, u64> = HashMap::new();
    let mut readable = false;
    let mut last_scan: Option<std::time::Instant> = None;
    let status = loop {
        if let Some(status) = child.try_wait()? {
            break status;
        }
        // a run's first second is polled every 2 ms (the engine processes are looked for every
        // 20 ms), so that the peak of a run of a few milliseconds is read near its end; then
        // both every `interval`
        let young = start.elapsed() < Duration::from_secs(1);
        let scan_every = if young { interval.min(Duration::from_millis(20)) } else { interval };
        if last_scan.is_none_or(|t| t.elapsed() >= scan_every) {
            last_scan = Some(std::time::Instant::now());
            let table = process_table();
            readable |= !table.is_empty();
            for (&pid, (_, comm)) in &table {
                if *comm == engine && !peaks.contains_key(&pid) && descends_from(pid, root, &table) {
                    peaks.insert(pid, 0);
                }
            }
        }
        for (&pid, peak) in peaks.iter_mut() {
            if let Some(hwm) = high_water(pid) {
                *peak = (*peak).max(hwm);
            }
        }
        std::thread::sleep(if young { interval.min(Duration::from_millis(2)) } else { interval });
    };
    // engine processes seen before their first reading count only with one
    peaks.retain(|_, p| *p > 0);
    let stdout = out.join().unwrap_or_default();
    let stderr = err.join().unwrap_or_default();
    let peak_bytes = if readable && !peaks.is_empty() { Some(peaks.values().sum()) } else { None };
    Ok(Measured { status, stdout, stderr, peak_bytes })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_child_that_allocates_shows_its_peak() {
        // the shell holds a 20 MB string for 0.3 s
        let m = run_measured(Command::new("sh").args(["-c", "x=$(head -c 20000000 /dev/zero | tr '\\0' a); sleep 0.3; echo ${#x}"]), "sh", Duration::from_millis(20)).unwrap();
        assert!(m.status.success());
        assert_eq!(m.stdout.trim(), "20000000");
        let peak = m.peak_bytes.expect("peak read from /proc");
        assert!(peak > 20_000_000, "peak {peak}");
    }
}
