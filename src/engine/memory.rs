//! What memory this process can still get, and the check that refuses an allocation that could
//! not fit (a billion atoms, a table of thousands of types) before it is made, instead of an
//! abort on a failed allocation.

/// Memory this process can still get, and where the bound comes from: the machine's
/// MemAvailable (/proc/meminfo), or the process' address-space limit (`ulimit -v`, from
/// /proc/self/limits, less what the process already maps) when that is lower; None where unknown.
pub fn available() -> Option<(f64, &'static str)> {
    let kb_field = |text: &str, key: &str| -> Option<f64> { text.lines().find(|l| l.starts_with(key))?.split_whitespace().nth(1)?.parse().ok() };
    let machine = kb_field(&std::fs::read_to_string("/proc/meminfo").ok()?, "MemAvailable:")? * 1024.0;
    let limit = std::fs::read_to_string("/proc/self/limits").ok().and_then(|t| {
        let line = t.lines().find(|l| l.starts_with("Max address space"))?;
        line.trim_start_matches("Max address space").split_whitespace().next()?.parse::<f64>().ok()
    });
    let mapped = std::fs::read_to_string("/proc/self/status").ok().and_then(|t| kb_field(&t, "VmSize:")).unwrap_or(0.0) * 1024.0;
    match limit {
        Some(l) if l - mapped < machine => Some(((l - mapped).max(0.0), "the address-space limit of this process, ulimit -v")),
        _ => Some((machine, "MemAvailable in /proc/meminfo")),
    }
}

/// Bytes as text: "3.2 GiB", "1.8e3 TiB".
pub fn human(bytes: f64) -> String {
    let units = ["bytes", "KiB", "MiB", "GiB", "TiB"];
    let mut v = bytes;
    let mut k = 0;
    while v >= 1024.0 && k + 1 < units.len() {
        v /= 1024.0;
        k += 1;
    }
    if v >= 1e4 { format!("{v:.2e} {}", units[k]) } else { format!("{v:.1} {}", units[k]) }
}

/// Refuse an allocation of `need` bytes (for `what`, e.g. "4.0e9 atoms x 140 bytes") that is
/// larger than the memory available; no check where that is unknown.
pub fn check_fits(need: f64, what: &str) -> Result<(), String> {
    check_fits_in(need, what, available())
}

fn check_fits_in(need: f64, what: &str, avail: Option<(f64, &str)>) -> Result<(), String> {
    match avail {
        Some((avail, source)) if !(need <= avail) => Err(format!(
            "this would need about {} of memory ({what}), more than the {} this machine has available ({source})",
            human(need),
            human(avail)
        )),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn too_large_is_refused_with_both_sizes() {
        assert_eq!(check_fits_in(1e12, "x", None), Ok(()));
        assert_eq!(check_fits_in(1e9, "x", Some((2e9, "MemAvailable"))), Ok(()));
        let e = check_fits_in(4.0 * 1024f64.powi(4), "4 TiB of atoms", Some((16.0 * 1024f64.powi(3), "MemAvailable"))).unwrap_err();
        assert!(e.contains("about 4.0 TiB") && e.contains("(4 TiB of atoms)") && e.contains("the 16.0 GiB this machine has available"), "{e}");
        assert!(check_fits_in(f64::NAN, "x", Some((1.0, "MemAvailable"))).is_err());
    }
}
