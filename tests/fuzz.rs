//! Mutation fuzzing of `dmhs check` and short runs (issue 15): the project's own decks and the
//! data files they read, mutated (tokens deleted, duplicated, swapped; hostile numbers; lines
//! spliced from other decks; truncation; invalid UTF-8; bad expressions; data files with wrong
//! counts, IDs, types and section headers), each run as a child process under a time and a
//! memory limit. Any panic (exit 101, "panicked at"), abort (a signal) or hang (the time
//! limit) fails the test; exit 0, 1 and 2 are all fine. Deterministic: a fixed seed and a
//! small PRNG (splitmix64), one stream per case, so a case is reproduced by its seed and number.
//!
//! By hand:
//!   DMHS_FUZZ_SEED=7 DMHS_FUZZ_CASES=20000 DMHS_FUZZ_RUNS=2000 cargo test --release --test fuzz -- --nocapture
//!   DMHS_FUZZ_SEED=7 DMHS_FUZZ_ONLY=1234 cargo test --release --test fuzz -- --nocapture   (one case)
//! A failing case is printed and written to target/fuzz-failures/seed-S-case-N/ (the deck as
//! in.case, the data files beside it, the command in cmd.txt), ready to run there. DMHS_BIN
//! runs the cases against another build.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Default seed and case counts: a few thousand checks and a few hundred runs.
const SEED: u64 = 0x15_f022;
const CHECK_CASES: usize = 2500;
const RUN_CASES: usize = 300;
/// Per case: seconds of wall time and kilobytes of address space. A case out of time is run
/// again with SLOW_LIMIT_S before it counts as a hang: a mutated size (`variable n index 100`
/// in the melt deck: 4 million atoms) can make a legitimate deck take 15 s on a loaded machine.
const TIME_LIMIT_S: u32 = 10;
const SLOW_LIMIT_S: u32 = 60;
const MEMORY_LIMIT_KB: u64 = 2_000_000;
/// Data files larger than this are left out of the corpus (a case copies its files).
const MAX_DATA_BYTES: u64 = 100_000;
/// Steps of a run case: every `run` command of a run case becomes `run RUN_STEPS`.
const RUN_STEPS: &str = "5";

/// splitmix64: a small, good, deterministic generator.
struct Rng(u64);

impl Rng {
    fn new(seed: u64, case: u64) -> Rng {
        let mut r = Rng(seed ^ case.wrapping_mul(0x9e37_79b9_7f4a_7c15));
        r.next();
        r
    }
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// 0..n (n > 0)
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn pick<'a, T>(&mut self, v: &'a [T]) -> &'a T {
        &v[self.below(v.len())]
    }
    fn chance(&mut self, percent: u64) -> bool {
        self.next() % 100 < percent
    }
}

const HOSTILE_NUMBERS: &[&str] = &[
    "0", "-1", "-0", "0.0", "1", "2", "NaN", "nan", "inf", "-inf", "1e308", "-1e308", "1e400", "1e-300", "1e30", "-1e30", "2147483647", "2147483648",
    "-2147483649", "4294967296", "9223372036854775807", "9223372036854775808", "18446744073709551616", "99999999999999999999", "1e11", "0x10", "1.5",
    "-0.5", "3", "100",
];

const BAD_EXPRESSIONS: &[&str] = &[
    "${", "$(", "v_", "${undefined}", "$(1/0)", "$(v_nope)", "$((1+2)", "$(1+2))", "$(1+)", "$(sqrt(-1))", "$(1e308*10)", "$(2^1e9)", "$(ln(0))",
    "$(0/0)", "v_nope", "c_nope[1]", "f_nope", "c_thermo_temp[99]", "$(c_thermo_temp[0])", "\"unterminated", "'", "\"\"\"", "$", "${a", "$(v_x[",
    "$(atan2(1))", "$(round(1e300))", "$(1:%.99999f)", "$(1:%d)", "&", "#", "*", "1*", "*0", "0*", "2*1", "EDGE", "INF", "-INF", "NULL", "none", "yes",
];

const SECTION_HEADERS: &[&str] = &[
    "Atoms", "Atom", "Atoms # sphere", "Atoms # atomic", "Atoms # sph", "Atoms # bond", "Atoms # bogus", "Velocities", "Velocity", "Masses", "Bonds",
    "Angles", "Dihedrals", "Impropers", "Pair Coeffs", "Pair Coeffs # lj/cut", "PairIJ Coeffs", "Bond Coeffs", "Angle Coeffs", "Ellipsoids", "Nonsense",
    "",
];

/// One file of the corpus.
struct Source {
    path: PathBuf,
    text: Vec<u8>,
}

struct Deck {
    src: Source,
    /// Data files of the deck's folder (given as `-var data NAME` when the deck reads ${data}).
    data: Vec<usize>,
    /// A run of RUN_STEPS steps of the unmutated deck completes quickly.
    runnable: bool,
}

struct Corpus {
    decks: Vec<Deck>,
    data: Vec<Source>,
    /// Every command line of every deck, for splicing.
    lines: Vec<String>,
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else { return };
    let mut entries: Vec<PathBuf> = rd.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            walk(&p, out);
        } else {
            out.push(p);
        }
    }
}

/// Decks whose short runs are too slow for the fuzz budget (many atoms, or long set-up).
fn slow_to_run(name: &str) -> bool {
    ["examples/bench/", "examples/gallery/", "reliability/in.big_box"].iter().any(|s| name.contains(s))
}

fn corpus() -> Corpus {
    let mut files = vec![];
    for d in ["tests/decks", "examples", "lammps-refs/decks"] {
        walk(&root().join(d), &mut files);
    }
    let mut decks = vec![];
    let mut data = vec![];
    for p in &files {
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        if name.ends_with(".data") {
            if std::fs::metadata(p).map(|m| m.len()).unwrap_or(u64::MAX) <= MAX_DATA_BYTES {
                data.push(Source { path: p.clone(), text: std::fs::read(p).unwrap() });
            }
        } else if name.starts_with("in.") {
            decks.push(Source { path: p.clone(), text: std::fs::read(p).unwrap() });
        }
    }
    let mut lines = vec![];
    let decks = decks
        .into_iter()
        .map(|src| {
            let text = String::from_utf8_lossy(&src.text).into_owned();
            for l in text.lines() {
                let t = l.trim();
                if !t.is_empty() && !t.starts_with('#') {
                    lines.push(t.to_string());
                }
            }
            let dir = src.path.parent().unwrap().to_path_buf();
            let own: Vec<usize> = (0..data.len()).filter(|&k| data[k].path.parent() == Some(dir.as_path())).collect();
            // a deck that reads a data file too large for the corpus cannot run here
            let reads_missing = text.lines().any(|l| {
                let mut w = l.split_whitespace();
                w.next() == Some("read_data") && w.next().map(|f| !f.contains('$') && !own.iter().any(|&k| data[k].path.file_name().unwrap().to_string_lossy() == f)).unwrap_or(false)
            });
            let rel = src.path.strip_prefix(root()).unwrap().to_string_lossy().into_owned();
            let runnable = !reads_missing && !slow_to_run(&rel) && !text.contains("read_restart");
            Deck { src, data: own, runnable }
        })
        .collect();
    Corpus { decks, data, lines }
}

fn is_number(t: &str) -> bool {
    t.parse::<f64>().is_ok()
}

/// Splits into lines of tokens (whitespace-separated), mutates, and joins with single spaces.
fn lines_of(text: &[u8]) -> Vec<Vec<String>> {
    String::from_utf8_lossy(text).lines().map(|l| l.split_whitespace().map(str::to_string).collect()).collect()
}

fn join(lines: &[Vec<String>]) -> Vec<u8> {
    let mut s = String::new();
    for l in lines {
        s += &l.join(" ");
        s.push('\n');
    }
    s.into_bytes()
}

/// A random non-empty, non-comment line (index), if any.
fn some_line(rng: &mut Rng, lines: &[Vec<String>]) -> Option<usize> {
    let cands: Vec<usize> = (0..lines.len()).filter(|&k| !lines[k].is_empty() && !lines[k][0].starts_with('#')).collect();
    if cands.is_empty() {
        None
    } else {
        Some(*rng.pick(&cands))
    }
}

/// A token of line `l` (a number when `numeric` and the line has one).
fn some_token(rng: &mut Rng, line: &[String], numeric: bool) -> usize {
    let nums: Vec<usize> = (0..line.len()).filter(|&k| is_number(&line[k])).collect();
    if numeric && !nums.is_empty() {
        *rng.pick(&nums)
    } else {
        rng.below(line.len())
    }
}

/// One token-level or line-level mutation of a deck or data file; returns its description.
fn mutate_tokens(rng: &mut Rng, lines: &mut Vec<Vec<String>>, splice: &[String], data_file: bool) -> String {
    let Some(l) = some_line(rng, lines) else { return "nothing to mutate".into() };
    let n = lines[l].len();
    let what = rng.below(if data_file { 13 } else { 11 });
    match what {
        // a plausible number scaled or negated: passes the first checks, reaches the physics
        10 | 12 if lines[l].iter().any(|t| is_number(t)) => {
            let t = some_token(rng, &lines[l], true);
            let x: f64 = lines[l][t].parse().unwrap();
            let y = match rng.below(6) {
                0 => -x,
                1 => x * 1e3,
                2 => x * 1e-3,
                3 => x * 0.5,
                4 => x + 1.0,
                _ => x * 1e6,
            };
            let v = if lines[l][t].contains(['.', 'e']) { format!("{y}") } else { format!("{}", y.round() as i64) };
            let old = std::mem::replace(&mut lines[l][t], v.clone());
            format!("line {}: `{old}` -> `{v}`", l + 1)
        }
        0 => {
            let t = rng.below(n);
            let tok = lines[l].remove(t);
            format!("line {}: deleted token `{tok}`", l + 1)
        }
        1 => {
            let t = rng.below(n);
            let tok = lines[l][t].clone();
            lines[l].insert(t, tok.clone());
            format!("line {}: duplicated token `{tok}`", l + 1)
        }
        2 => {
            let (a, b) = (rng.below(n), rng.below(n));
            lines[l].swap(a, b);
            format!("line {}: swapped tokens {} and {}", l + 1, a + 1, b + 1)
        }
        3 | 4 | 5 => {
            let t = some_token(rng, &lines[l], true);
            let v = rng.pick(HOSTILE_NUMBERS).to_string();
            let old = std::mem::replace(&mut lines[l][t], v.clone());
            format!("line {}: `{old}` -> `{v}`", l + 1)
        }
        6 => {
            let t = some_token(rng, &lines[l], false);
            let v = rng.pick(BAD_EXPRESSIONS).to_string();
            let old = std::mem::replace(&mut lines[l][t], v.clone());
            format!("line {}: `{old}` -> `{v}`", l + 1)
        }
        7 => {
            let removed = lines.remove(l);
            format!("line {}: deleted `{}`", l + 1, removed.join(" "))
        }
        8 => {
            let m = some_line(rng, lines).unwrap_or(l);
            lines.swap(l, m);
            format!("lines {} and {} swapped", l + 1, m + 1)
        }
        9 => {
            if data_file || splice.is_empty() || rng.chance(30) {
                let dup = lines[l].clone();
                lines.insert(l, dup);
                format!("line {} duplicated", l + 1)
            } else {
                let s = rng.pick(splice).clone();
                let at = rng.below(lines.len() + 1);
                lines.insert(at, s.split_whitespace().map(str::to_string).collect());
                format!("inserted `{s}` before line {}", at + 1)
            }
        }
        11 => {
            // a header count (N atoms, N atom types, box bounds) or the first column (an ID)
            let heads: Vec<usize> = (0..lines.len()).filter(|&k| lines[k].len() >= 2 && is_number(&lines[k][0]) && !is_number(lines[k].last().unwrap())).collect();
            let k = if !heads.is_empty() && rng.chance(50) { *rng.pick(&heads) } else { l };
            let v = if rng.chance(50) {
                rng.pick(HOSTILE_NUMBERS).to_string()
            } else {
                let old: i64 = lines[k][0].parse().unwrap_or(0);
                (old + [-1i64, 1, 2, -2][rng.below(4)]).to_string()
            };
            let old = std::mem::replace(&mut lines[k][0], v.clone());
            format!("line {}: first field `{old}` -> `{v}`", k + 1)
        }
        _ => {
            // a section header changed, or a type column (the second) changed
            let heads: Vec<usize> = (0..lines.len()).filter(|&k| !lines[k].is_empty() && lines[k][0].chars().next().unwrap().is_ascii_uppercase()).collect();
            if !heads.is_empty() && rng.chance(50) {
                let k = *rng.pick(&heads);
                let h = rng.pick(SECTION_HEADERS).to_string();
                let old = std::mem::replace(&mut lines[k], h.split_whitespace().map(str::to_string).collect());
                format!("line {}: header `{}` -> `{h}`", k + 1, old.join(" "))
            } else if n >= 2 {
                let v = rng.pick(HOSTILE_NUMBERS).to_string();
                let old = std::mem::replace(&mut lines[l][1], v.clone());
                format!("line {}: second field `{old}` -> `{v}`", l + 1)
            } else {
                "nothing".into()
            }
        }
    }
}

/// Mutates a file: 1-3 token or line mutations, sometimes truncation or invalid UTF-8.
fn mutate(rng: &mut Rng, text: &[u8], splice: &[String], data_file: bool) -> (Vec<u8>, Vec<String>) {
    let mut what = vec![];
    let mut lines = lines_of(text);
    let n = [1, 1, 1, 1, 1, 1, 2, 2, 2, 3][rng.below(10)];
    for _ in 0..n {
        what.push(mutate_tokens(rng, &mut lines, splice, data_file));
    }
    let mut bytes = join(&lines);
    if rng.chance(8) && !bytes.is_empty() {
        let at = rng.below(bytes.len());
        bytes.truncate(at);
        what.push(format!("truncated at byte {at}"));
    }
    if rng.chance(5) {
        let at = rng.below(bytes.len() + 1);
        const BAD_UTF8: [&[u8]; 6] = [b"\xff", b"\xc3", b"\xe2\x82", b"\xed\xa0\x80", b"\x00", b"\xf4\x90\x80\x80"];
        let bad = *rng.pick(&BAD_UTF8);
        bytes.splice(at..at, bad.iter().copied());
        what.push(format!("invalid UTF-8 {bad:?} at byte {at}"));
    }
    (bytes, what)
}

/// Every `run` command becomes a short run (a mutated `run` is fuzzed by the check cases).
fn cap_runs(deck: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(deck.len());
    for line in deck.split_inclusive(|&b| b == b'\n') {
        let s = String::from_utf8_lossy(line);
        if s.split_whitespace().next() == Some("run") {
            out.extend_from_slice(format!("run {RUN_STEPS}\n").as_bytes());
        } else {
            out.extend_from_slice(line);
        }
    }
    out
}

/// The input files of one case and how it is run.
struct Case {
    deck_name: String,
    deck: Vec<u8>,
    /// File name and contents of each data file the case provides.
    files: Vec<(String, Vec<u8>)>,
    args: Vec<String>,
    what: Vec<String>,
}

fn make_case(c: &Corpus, seed: u64, number: usize, run: bool) -> Case {
    let mut rng = Rng::new(seed, number as u64 * 2 + run as u64);
    let pool: Vec<usize> = (0..c.decks.len()).filter(|&k| !run || c.decks[k].runnable).collect();
    let d = &c.decks[*rng.pick(&pool)];
    let mut files: Vec<(String, Vec<u8>)> = d.data.iter().map(|&k| (c.data[k].path.file_name().unwrap().to_string_lossy().into_owned(), c.data[k].text.clone())).collect();
    let mut what = vec![];
    let mut args = vec![];
    let text = String::from_utf8_lossy(&d.src.text);
    if text.contains("${data}") && !files.is_empty() {
        args.extend(["-var".to_string(), "data".to_string(), files[rng.below(files.len())].0.clone()]);
    }
    // mutate the deck, a data file, or both
    let which = if files.is_empty() { 0 } else { rng.below(3) };
    let mut deck = d.src.text.clone();
    if which != 1 {
        let (m, w) = mutate(&mut rng, &deck, &c.lines, false);
        deck = m;
        what.extend(w.into_iter().map(|w| format!("deck {w}")));
    }
    if which != 0 {
        let k = rng.below(files.len());
        let (m, w) = mutate(&mut rng, &files[k].1, &[], true);
        files[k].1 = m;
        what.extend(w.into_iter().map(|w| format!("{} {w}", files[k].0)));
    }
    if run {
        deck = cap_runs(&deck);
    }
    let deck_name = d.src.path.strip_prefix(root()).unwrap().to_string_lossy().into_owned();
    Case { deck_name, deck, files, args, what }
}

/// How a case ended, when it is a failure.
fn verdict(code: Option<i32>, signal: Option<i32>, stderr: &str) -> Option<String> {
    if code == Some(124) || signal == Some(9) || signal == Some(15) {
        return Some(format!("hang: no end within {SLOW_LIMIT_S} s"));
    }
    if code == Some(101) || stderr.contains("panicked at") {
        return Some("panic".into());
    }
    if let Some(s) = signal {
        return Some(format!("abort: killed by signal {s}"));
    }
    match code {
        Some(0 | 1 | 2) => None,
        Some(c) if c > 128 => Some(format!("abort: killed by signal {}", c - 128)),
        c => Some(format!("unexpected exit status {c:?}")),
    }
}

fn run_case(case: &Case, sub: &str, dir: &Path, limit_s: u32) -> (Option<i32>, Option<i32>, String, String) {
    std::fs::write(dir.join("in.case"), &case.deck).unwrap();
    for (name, text) in &case.files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let o = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {MEMORY_LIMIT_KB}; exec timeout {limit_s} \"$0\" \"$@\""))
        .arg(std::env::var_os("DMHS_BIN").map(PathBuf::from).unwrap_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_dmhs"))))
        .arg(sub)
        .arg("in.case")
        .args(["-log", "none", "-threads", "1", "-echo", "screen"])
        .args(&case.args)
        .current_dir(dir)
        .env("RUST_BACKTRACE", "1")
        .stdin(Stdio::null())
        .output()
        .unwrap();
    use std::os::unix::process::ExitStatusExt;
    (o.status.code(), o.status.signal(), String::from_utf8_lossy(&o.stdout).into_owned(), String::from_utf8_lossy(&o.stderr).into_owned())
}

fn env_num(name: &str) -> Option<u64> {
    std::env::var(name).ok().map(|v| {
        let v = v.trim();
        v.strip_prefix("0x").map(|h| u64::from_str_radix(h, 16)).unwrap_or_else(|| v.parse()).unwrap_or_else(|_| panic!("{name}={v}: not a number"))
    })
}

#[test]
fn mutated_decks_never_panic_abort_or_hang() {
    let seed = env_num("DMHS_FUZZ_SEED").unwrap_or(SEED);
    let checks = env_num("DMHS_FUZZ_CASES").map(|n| n as usize).unwrap_or(CHECK_CASES);
    let runs = env_num("DMHS_FUZZ_RUNS").map(|n| n as usize).unwrap_or(RUN_CASES);
    let only = env_num("DMHS_FUZZ_ONLY").map(|n| n as usize);
    let c = corpus();
    assert!(c.decks.len() > 50 && c.data.len() > 10, "corpus: {} decks, {} data files", c.decks.len(), c.data.len());
    // case numbers 0..checks are `check` cases, checks..checks+runs are short runs
    let cases: Vec<usize> = match only {
        Some(n) => vec![n],
        None => (0..checks + runs).collect(),
    };
    let next = AtomicUsize::new(0);
    let failures = Mutex::new(Vec::<String>::new());
    let counts = Mutex::new([0usize; 3]);
    let slow = Mutex::new(Vec::<usize>::new());
    let workers = std::thread::available_parallelism().map(|n| n.get()).unwrap_or(2).min(8);
    let out = root().join("target/fuzz-failures");
    std::thread::scope(|s| {
        for _ in 0..workers {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some(&number) = cases.get(i) else { break };
                let run = number >= checks;
                let case = make_case(&c, seed, number, run);
                let sub = if run { "run" } else { "check" };
                let tmp = tempfile::tempdir().unwrap();
                let mut r = run_case(&case, sub, tmp.path(), TIME_LIMIT_S);
                if r.0 == Some(124) {
                    slow.lock().unwrap().push(number);
                    let tmp = tempfile::tempdir().unwrap();
                    r = run_case(&case, sub, tmp.path(), SLOW_LIMIT_S);
                }
                let (code, signal, stdout, stderr) = r;
                if let Some(code) = code.filter(|c| (0..=2).contains(c)) {
                    counts.lock().unwrap()[code as usize] += 1;
                }
                if let Some(v) = verdict(code, signal, &stderr) {
                    let dir = out.join(format!("seed-{seed}-case-{number}"));
                    let _ = std::fs::remove_dir_all(&dir);
                    std::fs::create_dir_all(&dir).unwrap();
                    std::fs::write(dir.join("in.case"), &case.deck).unwrap();
                    for (name, text) in &case.files {
                        std::fs::write(dir.join(name), text).unwrap();
                    }
                    let cmd = format!("dmhs {sub} in.case -log none -threads 1 -echo screen {}", case.args.join(" "));
                    std::fs::write(dir.join("cmd.txt"), format!("{cmd}\n")).unwrap();
                    let tail: String = stderr.lines().rev().take(12).collect::<Vec<_>>().into_iter().rev().collect::<Vec<_>>().join("\n");
                    let msg = format!(
                        "{v}: seed {seed} case {number} ({sub} of {} mutated: {})\n  reproduce: DMHS_FUZZ_SEED={seed} DMHS_FUZZ_CASES={checks} DMHS_FUZZ_ONLY={number}, or `{cmd}` in {}\n  stderr:\n{tail}\n  stdout tail: {}\n",
                        case.deck_name,
                        case.what.join("; "),
                        dir.display(),
                        stdout.lines().last().unwrap_or("")
                    );
                    eprintln!("{msg}");
                    failures.lock().unwrap().push(msg);
                }
            });
        }
    });
    let f = failures.into_inner().unwrap();
    let [ok, failed, refused] = counts.into_inner().unwrap();
    println!("fuzz seed {seed}: {} cases ({checks} check, {runs} run): exit 0 {ok}, exit 1 {failed}, exit 2 {refused}; {} failures", cases.len(), f.len());
    let mut sl = slow.into_inner().unwrap();
    sl.sort();
    if !sl.is_empty() {
        println!("slower than {TIME_LIMIT_S} s (run again with {SLOW_LIMIT_S} s): cases {sl:?}");
    }
    assert!(f.is_empty(), "{} of {} fuzz cases panicked, aborted or hung:\n{}", f.len(), cases.len(), f.join("\n"));
}
