//! Timing of formula evaluation (run by hand, not part of the suite):
//! `cargo test -p dmhs-parser --release --test expr_bench -- --ignored --nocapture`.
//! Each formula is evaluated 1e5 times; the best of 7 rounds is printed (`EXPR_BENCH_N` and
//! `EXPR_BENCH_ROUNDS` change these, e.g. for a run under callgrind; `EXPR_BENCH_PARSE=0` skips
//! the timing of `parse`, `EXPR_BENCH_ONLY=k` times formula k alone).

use dmhs_parser::expr::{evaluate, parse};
use dmhs_parser::variables::Variables;
use dmhs_parser::EvalContext;
use std::hint::black_box;
use std::time::Instant;

/// A context with internal variables `a`, `b` (as a fix would set them) and the `step` and `dt` keywords.
struct Ctx {
    vars: Variables,
}

impl EvalContext for Ctx {
    fn variables(&mut self) -> &mut Variables {
        &mut self.vars
    }
    fn thermo_keyword(&mut self, name: &str) -> Option<Result<f64, String>> {
        match name {
            "step" => Some(Ok(42.0)),
            "dt" => Some(Ok(0.005)),
            _ => None,
        }
    }
}

const FORMULAS: &[&str] = &[
    "v_a*2.0+sqrt(v_b)^2-ternary(step>10,1,2)",
    "0.5*(1.0-cos(2*PI*step/1000))",
    "-2^2+3*(4-1)/7%5 >= 1 && !(1e-3 < 2.5e2) || 7",
    "ramp(1.0,2.0)*1.25e-3+swiggle(0.0,0.1,50)",
];

fn env_or(name: &str, default: usize) -> usize {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

fn best_of(rounds: usize, mut f: impl FnMut()) -> f64 {
    (0..rounds)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
#[ignore]
fn bench_evaluate_and_parse() {
    let mut vars = Variables::default();
    vars.set_internal("a", 1.5);
    vars.set_internal("b", 2.25);
    let mut ctx = Ctx { vars };
    let (n, rounds) = (env_or("EXPR_BENCH_N", 100_000), env_or("EXPR_BENCH_ROUNDS", 7));
    let only = std::env::var("EXPR_BENCH_ONLY").ok().and_then(|v| v.parse::<usize>().ok());
    for (k, f) in FORMULAS.iter().enumerate().filter(|(k, _)| only.is_none_or(|o| o == *k)) {
        let eval_ms = best_of(rounds, || {
            for _ in 0..n {
                black_box(evaluate(black_box(f), &mut ctx).ok());
            }
        }) * 1e3;
        let parse_ms = best_of(if env_or("EXPR_BENCH_PARSE", 1) == 0 { 0 } else { rounds }, || {
            for _ in 0..n {
                black_box(parse(black_box(f)).ok());
            }
        }) * 1e3;
        let per = 1e5 / n as f64;
        println!("evaluate {:8.2} ms  parse {:8.2} ms  per 1e5: [{k}] {f}", eval_ms * per, parse_ms * per);
    }
}
