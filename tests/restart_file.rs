//! The restart file (format "dmhs restart" version 2): read_restart refuses every bad field
//! with a message naming the file, the field and, for per-atom values, the atom ID, at the
//! field's place in the file and at the read_restart command; truncated, binary, LAMMPS and
//! old dmhs files are refused with a clear message, never a panic. (Continuations from restart files: tests/dem_restart.rs; exact
//! doubles and the write-side checks: the unit tests of src/deck/restart.)

use dmhs::deck::{run_text, DeckOptions};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn run(dir: &Path, deck: &str) -> Result<(), String> {
    let opts = DeckOptions { base_dir: Some(dir.to_path_buf()), ..Default::default() };
    run_text("in.test", deck, &opts).map(|_| ()).map_err(|f| f.rendered)
}

/// The restart file of 18 bonded granular clumps (bonds, angles, contacts) after 200 steps.
fn base() -> &'static Value {
    static BASE: OnceLock<Value> = OnceLock::new();
    BASE.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        std::fs::copy(root().join("lammps-refs/decks/gran_clumps.data"), dir.path().join("gran_clumps.data")).unwrap();
        let text = std::fs::read_to_string(root().join("lammps-refs/decks/in.gran_clumps_granular")).unwrap();
        let setup: String = text.lines().take_while(|l| !l.starts_with("run")).map(|l| format!("{l}\n")).collect();
        run(dir.path(), &format!("{setup}run 200\nwrite_restart base.restart\n")).unwrap();
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("base.restart")).unwrap()).unwrap()
    })
}

/// read_restart of a file with these bytes: its error message.
fn refused(bytes: &[u8]) -> String {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("bad.restart"), bytes).unwrap();
    match run(dir.path(), "read_restart bad.restart\n") {
        Ok(()) => panic!("the file was read"),
        Err(e) => e,
    }
}

/// read_restart of the base file after `edit`: its error message.
fn edited(edit: impl FnOnce(&mut Value)) -> String {
    let mut v = base().clone();
    edit(&mut v);
    refused(serde_json::to_string(&v).unwrap().as_bytes())
}

/// The message names the file and the command's place, and says `what`.
fn says(message: &str, what: &str) {
    assert!(message.contains("restart file ") && message.contains("bad.restart"), "no file name in:\n{message}");
    assert!(message.contains("in.test:1"), "no command location in:\n{message}");
    assert!(message.contains(what), "expected `{what}` in:\n{message}");
}

#[test]
fn the_base_file_reads_back() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("ok.restart"), serde_json::to_string(base()).unwrap()).unwrap();
    run(dir.path(), "read_restart ok.restart\nfix 1 all nve\nrun 10\n").unwrap();
}

#[test]
fn atom_type_out_of_range() {
    for (t, what) in [(json!(0), "is 0, outside 1..=2"), (json!(-1), "is -1, outside 1..=2"), (json!(3), "is 3, outside 1..=2"), (json!(4294967296u64), "is 4294967296, outside 1..=2")] {
        let m = edited(|v| {
            v["types"] = json!({"atom_types": 2, "masses": [null, null]});
            v["atoms"]["type"][5] = t;
        });
        let id = base()["atoms"]["id"][5].clone();
        says(&m, &format!("atoms.type[5] (atom {id}) {what} (types.atom_types)"));
    }
}

#[test]
fn atom_id_not_positive_or_too_large() {
    for id in [json!(0), json!(-4), json!(2147483648u64)] {
        says(&edited(|v| v["atoms"]["id"][7] = id.clone()), &format!("atoms.id[7] is {id}: atom IDs must be in 1..=2147483647"));
    }
}

#[test]
fn atom_id_twice() {
    let first = base()["atoms"]["id"][0].clone();
    says(&edited(|v| v["atoms"]["id"][9] = first.clone()), &format!("atoms.id[9]: atom ID {first} appears twice"));
}

#[test]
fn type_mass_not_positive() {
    says(&edited(|v| v["types"]["masses"][0] = json!(0.0)), "types.masses[0] (type 1) is 0: a mass must be > 0");
    says(&edited(|v| v["types"]["masses"][0] = json!(-2.5)), "types.masses[0] (type 1) is -2.5: a mass must be > 0");
}

#[test]
fn masses_not_one_per_type() {
    says(&edited(|v| v["types"]["masses"] = json!([1.0, 1.0])), "types.masses has 2 entries for 1 types (types.atom_types)");
}

#[test]
fn per_atom_mass_or_radius_invalid() {
    let id = base()["atoms"]["id"][3].clone();
    says(&edited(|v| v["atoms"]["rmass"][3] = json!(0.0)), &format!("atoms.rmass[3] (atom {id}) is 0: a mass must be > 0"));
    says(&edited(|v| v["atoms"]["radius"][3] = json!(-0.5)), &format!("atoms.radius[3] (atom {id}) is -0.5: a radius must be >= 0"));
}

#[test]
fn bond_refers_to_a_missing_atom() {
    says(&edited(|v| v["topology"]["bonds"][2][2] = json!(999)), "topology.bonds[2] refers to atom 999, which does not exist");
    says(&edited(|v| v["topology"]["angles"][0][1] = json!(-1)), "topology.angles[0] refers to atom -1, which does not exist");
}

#[test]
fn bond_type_out_of_range() {
    says(&edited(|v| v["topology"]["bonds"][4][0] = json!(2)), "topology.bonds[4]: the type is 2, outside 1..=1 (topology.bond_types)");
    says(&edited(|v| v["topology"]["angles"][4][0] = json!(0)), "topology.angles[4]: the type is 0, outside 1..=1 (topology.angle_types)");
}

#[test]
fn topology_the_atom_style_lacks() {
    says(&edited(|v| v["topology"]["dihedrals"] = json!([[1, 1, 2, 3, 4]])), "topology.dihedrals: the atom style has no dihedrals");
}

#[test]
fn array_shorter_than_the_atom_count() {
    says(&edited(|v| drop(v["atoms"]["x"].as_array_mut().unwrap().pop())), "atoms.x has 71 entries for 72 atoms (atoms.count)");
    says(&edited(|v| v["atoms"]["count"] = json!(73)), "atoms.id has 72 entries for 73 atoms (atoms.count)");
}

#[test]
fn array_of_the_atom_style_missing_or_extra() {
    says(&edited(|v| drop(v["atoms"].as_object_mut().unwrap().remove("radius"))), "atoms.radius is missing (atom style hybrid sphere angle has it)");
    says(&edited(|v| v["atoms"]["q"] = json!(vec![0.0; 72])), "atoms.q is given, but atom style hybrid sphere angle has no q");
}

#[test]
fn image_flag_out_of_range() {
    says(&edited(|v| v["atoms"]["image"][0][1] = json!(2147483648u64)), "invalid value: integer `2147483648`, expected i32");
}

#[test]
fn number_of_the_wrong_kind() {
    says(&edited(|v| v["atoms"]["x"][0][0] = json!("1.0")), "invalid type: string \"1.0\", expected f64");
    says(&edited(|v| v["atoms"]["type"][0] = json!(1.5)), "invalid type: floating point `1.5`, expected i64");
}

#[test]
fn number_too_large_for_a_double() {
    let text = serde_json::to_string(base()).unwrap().replacen("\"dt\":0.0001", "\"dt\":1e400", 1);
    says(&refused(text.as_bytes()), "number out of range");
}

#[test]
fn box_lo_not_below_hi() {
    says(&edited(|v| v["box"]["current"]["hi"][1] = json!(-4.5)), "box.current: lo[1] = -4.5 is not below hi[1] = -4.5");
}

#[test]
fn box_length_overflows() {
    says(
        &edited(|v| {
            v["box"]["current"]["lo"][0] = json!(-1e308);
            v["box"]["current"]["hi"][0] = json!(1e308);
        }),
        "box.current: the length hi[0] - lo[0] = 1e308 - (-1e308) overflows a double",
    );
}

#[test]
fn dimension_units_boundary_atom_style() {
    says(&edited(|v| v["settings"]["dimension"] = json!(4)), "settings.dimension is 4, not 2 or 3");
    says(&edited(|v| v["settings"]["units"] = json!("metal")), "settings.units is `metal`: dmhs supports lj, si and cgs");
    says(&edited(|v| v["settings"]["boundary"][0] = json!("pf")), "settings.boundary[0] is `pf`");
    says(&edited(|v| v["settings"]["atom_style"] = json!(["ellipsoid"])), "settings.atom_style: `ellipsoid` is not an atom style dmhs supports");
}

#[test]
fn time_origin_after_the_step() {
    says(&edited(|v| v["settings"]["time_origin"]["step"] = json!(1000)), "settings.time_origin.step is 1000: must be in 0..=200 (settings.step)");
}

#[test]
fn mask_outside_the_groups() {
    let id = base()["atoms"]["id"][2].clone();
    says(&edited(|v| v["atoms"]["mask"][2] = json!(0)), &format!("atoms.mask[2] (atom {id}) is 0: every atom is in group all (bit 0)"));
    says(&edited(|v| v["atoms"]["mask"][2] = json!(9)), &format!("atoms.mask[2] (atom {id}) is 9: bit 3 is not a group in `groups`"));
}

#[test]
fn group_names() {
    says(&edited(|v| v["groups"] = json!(["mobile"])), "groups[0] must be `all`");
    says(&edited(|v| v["groups"] = json!(["all", "a", "a"])), "groups[2]: group `a` appears twice");
}

/// Values per contact of the pair style (granular with linear_history: the tangential spring).
const SIZE: usize = 3;

#[test]
fn contact_with_a_missing_atom() {
    assert_eq!(base()["contact_histories"][0]["size"], SIZE);
    says(&edited(|v| v["contact_histories"][0]["contacts"] = json!([[1, 5000, [0, 0, 0], vec![0.0; SIZE]]])), "contact_histories[0].contacts[0] refers to atom 5000, which does not exist");
    says(&edited(|v| v["contact_histories"][0]["contacts"] = json!([[1, 5, [0, 0, 0], [0.0]]])), "contact_histories[0].contacts[0] has 1 values, not 3 (contact_histories[0].size)");
}

#[test]
fn contact_history_the_pair_style_lacks() {
    says(&edited(|v| v["contact_histories"][0] = json!({"size": 2, "contacts": []})), "contact_histories[0] has 2 values per contact; the pair style's store has 3");
    says(&edited(|v| v["contact_histories"].as_array_mut().unwrap().push(json!({"size": SIZE, "contacts": []}))), "contact_histories has 2 stores; the pair style of the file's force field has 1");
}

#[test]
fn force_field_only_force_field_commands() {
    let k = base()["force_field"].as_array().unwrap().len();
    says(&edited(|v| v["force_field"].as_array_mut().unwrap().push(json!(["run", "10"]))), &format!("force_field[{k}] `run 10` is not one of the force-field commands"));
}

#[test]
fn unknown_or_missing_member() {
    says(&edited(|v| v["atoms"]["colour"] = json!([])), "unknown field `colour`");
    says(&edited(|v| drop(v.as_object_mut().unwrap().remove("topology"))), "missing field `topology`");
}

#[test]
fn truncated_file() {
    let text = serde_json::to_string_pretty(base()).unwrap();
    says(&refused(&text.as_bytes()[..text.len() / 2]), "the file ends early, at line");
    says(&refused(b""), "the file is empty");
}

#[test]
fn binary_garbage() {
    let bytes: Vec<u8> = (0..4096u32).map(|i| (i.wrapping_mul(2654435761) >> 13) as u8).collect();
    says(&refused(&bytes), "a binary file, not a dmhs restart file");
}

#[test]
fn lammps_binary_restart() {
    // LAMMPS' header: the length of the magic string, then the string
    let mut bytes = 16i32.to_le_bytes().to_vec();
    bytes.extend(b"LammpS RestartT\0");
    bytes.extend([1, 0, 0, 0, 0xff, 0xfe, 0x80, 0x00]);
    let m = refused(&bytes);
    says(&m, "dmhs does not read LAMMPS binary restart files");
    says(&m, "-restart2data");
}

#[test]
fn old_text_format() {
    says(&refused(b"DMHS restart 1\nstep 1000\natime 0.0 0\n"), "(`DMHS restart 1`), which is no longer read");
}

#[test]
fn other_format_or_version() {
    says(&edited(|v| v["format"] = json!("something else")), "not a dmhs restart file (its `format` is `something else`");
    let m = edited(|v| {
        v["version"] = json!(3);
        v["atoms"]["temperature"] = json!([]);
    });
    says(&m, "restart format version 3 is from a newer dmhs; this one reads version 2");
    says(&refused(b"LAMMPS data file\n\n2 atoms\n"), "not a dmhs restart file");
}
