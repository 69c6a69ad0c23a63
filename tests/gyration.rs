//! compute gyration, compute vacf and fix spring/rg: the thermo tables of
//! lammps-refs/decks/in.thermo_gyration_vacf and in.thermo_spring_rg against LAMMPS' (stored, and
//! LAMMPS run now), the identities the computes obey, the restraint at work, and located errors.

mod common;
mod thermo_tables;
use thermo_tables::dmhs_table;

thermo_tables::thermo_table_tests!(["thermo_gyration_vacf", "thermo_spring_rg"]);

/// On every row the radius of gyration is the square root of the tensor's trace and equals the
/// group function gyration(); at step 0 the vacf sum is the mean of v^2, 2 KE / (N m) with m = 1,
/// which thermo's temperature gives as T (3N - 3) / N.
#[test]
fn gyration_is_the_trace_and_vacf_starts_at_mean_v2() {
    let (names, rows) = dmhs_table("thermo_gyration_vacf");
    let col = |n: &str| names.iter().position(|c| c == n).unwrap_or_else(|| panic!("no column {n}"));
    for r in &rows {
        let trace = r[col("c_g[1]")] + r[col("c_g[2]")] + r[col("c_g[3]")];
        assert!((r[col("c_g")] - trace.sqrt()).abs() < 1e-14 * r[col("c_g")], "step {}", r[0]);
        assert_eq!(r[col("c_g")], r[col("v_rg")], "step {}", r[0]);
    }
    let n = 500.0;
    let mean_v2 = rows[0][col("Temp")] * (3.0 * n - 3.0) / n;
    assert!((rows[0][col("c_va[4]")] - mean_v2).abs() < 1e-13 * mean_v2, "{} vs {mean_v2}", rows[0][col("c_va[4]")]);
}

#[test]
fn bad_computes_are_located() {
    let base = "units lj\nlattice fcc 0.8442\nregion box block 0 2 0 2 0 2\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n";
    common::assert_located_errors(
        base,
        &[
            ("compute g all gyration extra\n", "gyration"),
            ("compute v all vacf 1\n", "vacf"),
            ("fix r all spring/rg 5.0\n", "RG0"),
            ("fix r all spring/rg five 1.0\n", "K"),
            ("fix r all spring/rg 5.0 1.0 2.0\n", "unexpected"),
        ],
    );
}

/// The lower half, pulled towards Rg 3.2 with K 2000, shrinks from 3.63 by more than 0.2 in 100
/// steps, while the upper half, held at its starting Rg (RG0 NULL, printed as f_r2), stays
/// within 0.1 of it (K 5 is weak against the liquid's motion).
#[test]
fn spring_rg_pulls_the_radius_to_its_target() {
    let (names, rows) = dmhs_table("thermo_spring_rg");
    let col = |n: &str| names.iter().position(|c| c == n).unwrap_or_else(|| panic!("no column {n}"));
    assert!(rows[0][col("v_gl")] - rows[5][col("v_gl")] > 0.2, "{} -> {}", rows[0][col("v_gl")], rows[5][col("v_gl")]);
    for r in &rows {
        assert_eq!(r[col("f_r2")], rows[0][col("v_gu")]);
        assert!((r[col("v_gu")] - r[col("f_r2")]).abs() < 0.1, "step {}", r[0]);
    }
}
