//! `compute ID group bond/local value ... [set dist NAME]`: one row per bond whose two atoms are
//! in the group (LAMMPS' compute bond/local), read by `dump local` and `compute reduce`.
//! Values: dist, dx, dy, dz, engpot, force, fx, fy, fz (the bond style's single energy and
//! force), engvib, engrot, engtrans, omega, velvib (the pair's motion about its centre of
//! mass) and v_NAME (an equal-style variable, evaluated per bond after `set dist NAME` has set
//! the internal variable NAME to the bond's length).
//!
//! Rows come in LAMMPS' order: the owned atoms in LAMMPS' local order, each with the bonds of
//! its own list in list order (`newton_bond on`: a bond is listed by its first atom; off: by
//! both atoms, and taken from the one with the lower ID). Broken bonds (type 0) are skipped;
//! bonds turned off by delete_bonds are listed with energy and force 0, as LAMMPS documents.

use super::Compute;
use crate::models::world::World;
use dmhs_parser::{Args, Command, DResult, Word};

const SYNTAX: &str = "compute ID group bond/local value1 value2 ... [set dist NAME]  (values: dist dx dy dz engpot force fx fy fz engvib engrot engtrans omega velvib v_NAME)";

#[derive(Clone, Debug, PartialEq)]
enum Value {
    Dist,
    Dx,
    Dy,
    Dz,
    EngPot,
    Force,
    Fx,
    Fy,
    Fz,
    EngVib,
    EngRot,
    EngTrans,
    Omega,
    VelVib,
    Var(String),
}

const NAMES: [&str; 14] = ["dist", "dx", "dy", "dz", "engpot", "force", "fx", "fy", "fz", "engvib", "engrot", "engtrans", "omega", "velvib"];

pub struct ComputeBondLocal {
    id: String,
    groupbit: u32,
    values: Vec<Value>,
    /// `set dist NAME`: the internal variable that holds each bond's length.
    dist_var: Option<String>,
}

impl ComputeBondLocal {
    pub fn from_lammps(id: String, groupbit: u32, args: &[Word], cmd: &Command, w: &World) -> DResult<Self> {
        let mut a = Args::from_words(args, cmd.span, SYNTAX);
        if !w.state.atoms.features.bonds {
            return Err(a.error_at(&cmd.name, "Compute bond/local used when bonds are not allowed", "no bonds in this atom style"));
        }
        let mut values = Vec::new();
        while let Some(word) = a.peek() {
            let t = word.text.as_str();
            let v = match NAMES.iter().position(|n| *n == t) {
                Some(k) => [Value::Dist, Value::Dx, Value::Dy, Value::Dz, Value::EngPot, Value::Force, Value::Fx, Value::Fy, Value::Fz, Value::EngVib, Value::EngRot, Value::EngTrans, Value::Omega, Value::VelVib][k].clone(),
                None if t.starts_with("v_") && t.len() > 2 => Value::Var(t[2..].to_string()),
                None if t == "set" => break,
                None => {
                    let mut d = a.error_at(word, format!("Invalid keyword `{t}` in compute bond/local command"), "expected a bond/local value or `set`");
                    if let Some(h) = dmhs_parser::suggest::did_you_mean_help(t, NAMES) {
                        d = d.with_help(h);
                    }
                    return Err(d);
                }
            };
            a.skip(1);
            values.push(v);
        }
        if values.is_empty() {
            return Err(a.missing("a value (dist, engpot, force, ...)"));
        }
        let mut dist_var = None;
        while let Some(kw) = a.peek() {
            a.skip(1);
            if kw.text != "set" {
                return Err(a.error_at(kw, format!("Unknown compute bond/local keyword: {}", kw.text), "expected set"));
            }
            a.choice("set keyword", &["dist"])?;
            dist_var = Some(a.word("variable name")?.text.clone());
        }
        let nvar = values.iter().filter(|v| matches!(v, Value::Var(_))).count();
        if nvar > 0 && dist_var.is_none() {
            return Err(a.error_at(&cmd.name, "Compute bond/local variable requires a set variable", "add `set dist NAME`"));
        }
        if nvar == 0 && dist_var.is_some() {
            return Err(a.error_at(&cmd.name, "Compute bond/local set used with without a variable", "no v_NAME value"));
        }
        Ok(ComputeBondLocal { id, groupbit, values, dist_var })
    }
}

/// The bond rows as LAMMPS lists them: (atom 1, atom 2, bond record), local indices.
pub(super) fn listed_bonds(w: &World, groupbit: u32) -> Vec<(usize, usize, usize)> {
    let s = w.state;
    let a = &s.atoms;
    let map = a.tag_map();
    // each owned atom's list: (slot, partner tag, record)
    let mut lists: Vec<Vec<(u32, i64, usize)>> = vec![Vec::new(); a.nlocal];
    for (rec, b) in s.topo.bonds.iter().enumerate() {
        if b.typ == 0 {
            continue;
        }
        let holders: &[usize] = if s.newton_bond { &[0] } else { &[0, 1] };
        for &k in holders {
            if let Some(i) = map.get(b.atoms[k]).filter(|&i| i < a.nlocal) {
                lists[i].push((b.slots[k], b.atoms[1 - k], rec));
            }
        }
    }
    let mut rows = Vec::new();
    for &i in s.lammps_order.indices(a.nlocal).iter() {
        if a.mask[i] & groupbit == 0 {
            continue;
        }
        let mut list = std::mem::take(&mut lists[i]);
        list.sort_by_key(|e| e.0);
        for (_, partner, rec) in list {
            let Some(j) = map.get(partner) else { continue };
            if a.mask[j] & groupbit == 0 || (!s.newton_bond && a.tag[i] > partner) {
                continue;
            }
            rows.push((i, j, rec));
        }
    }
    rows
}

impl Compute for ComputeBondLocal {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &str {
        "bond/local"
    }
    fn groupbit(&self) -> u32 {
        self.groupbit
    }
    fn local_needs_variables(&self, col: usize) -> bool {
        matches!(self.values.get(col), Some(Value::Var(_)))
    }
    fn local_cols(&self) -> Option<usize> {
        Some(if self.values.len() == 1 { 0 } else { self.values.len() })
    }
    fn local(&self, w: &World, mut ev: Option<&mut dyn dmhs_parser::EvalContext>) -> Result<Vec<Vec<f64>>, String> {
        let s = w.state;
        let a = &s.atoms;
        let single = self.values.iter().any(|v| matches!(v, Value::EngPot | Value::Force | Value::Fx | Value::Fy | Value::Fz));
        let vel = self.values.iter().any(|v| matches!(v, Value::EngVib | Value::EngRot | Value::EngTrans | Value::Omega | Value::VelVib));
        let bond = match w.bond {
            Some(b) => Some(b),
            None if single => return Err(format!("compute {}: No bond style is defined for compute bond/local", self.id)),
            None => None,
        };
        let dom = s.domain()?;
        let mut out = Vec::new();
        for (i, j, rec) in listed_bonds(w, self.groupbit) {
            let b = &s.topo.bonds[rec];
            let (x1, x2) = (a.x[i], a.x[j]);
            let mut d = [x1[0] - x2[0], x1[1] - x2[1], x1[2] - x2[2]];
            dom.minimum_image(&mut d);
            let rsq = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            let (fbond, engpot) = match bond {
                Some(st) if single && !b.off => {
                    let sb = crate::models::bonded::SingleBond { state: s, rec, typ: b.typ, i, j, del: d, rsq };
                    st.single(&sb).map_err(|e| format!("compute {}: {e}", self.id))?
                }
                _ => (0.0, 0.0),
            };
            let (mut engvib, mut engrot, mut engtrans, mut omegasq, mut vvib) = (0.0, 0.0, 0.0, 0.0, 0.0);
            if vel {
                // the pair's motion about its centre of mass, in LAMMPS' order of operations
                let (m1, m2) = (s.mass(i), s.mass(j));
                let (v1, v2) = (a.v[i], a.v[j]);
                let mt = m1 + m2;
                let inv = 1.0 / mt;
                let xcm: [f64; 3] = std::array::from_fn(|k| (m1 * x1[k] + m2 * x2[k]) * inv);
                let vcm: [f64; 3] = std::array::from_fn(|k| (m1 * v1[k] + m2 * v2[k]) * inv);
                let lensq = |u: [f64; 3]| u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
                let dot = |u: [f64; 3], w: [f64; 3]| u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
                engtrans = 0.5 * mt * lensq(vcm);
                // unit vector from atom 1 to atom 2 (LAMMPS' norm3: scale by 1/sqrt)
                let r12: [f64; 3] = std::array::from_fn(|k| x2[k] - x1[k]);
                let scale = 1.0 / lensq(r12).sqrt();
                let r12 = r12.map(|c| c * scale);
                let dr1: [f64; 3] = std::array::from_fn(|k| x1[k] - xcm[k]);
                let dr2: [f64; 3] = std::array::from_fn(|k| x2[k] - xcm[k]);
                let dv1: [f64; 3] = std::array::from_fn(|k| v1[k] - vcm[k]);
                let dv2: [f64; 3] = std::array::from_fn(|k| v2[k] - vcm[k]);
                let (p1, p2) = (dot(dv1, r12), dot(dv2, r12));
                engvib = 0.5 * (m1 * p1 * p1 + m2 * p2 * p2);
                vvib = p2 - p1;
                let inertia = m1 * lensq(dr1) + m2 * lensq(dr2);
                let vrotsq = lensq(dv1) - p1 * p1;
                omegasq = vrotsq / lensq(dr1);
                engrot = 0.5 * inertia * omegasq;
                let mvv2e = s.units.mvv2e;
                engtrans *= mvv2e;
                engvib *= mvv2e;
                engrot *= mvv2e;
            }
            let dist = rsq.sqrt();
            if let (Some(name), Some(ev)) = (&self.dist_var, ev.as_mut().map(|e| &mut **e as &mut dyn dmhs_parser::EvalContext)) {
                ev.variables().set_internal(name, dist);
            }
            let mut row = Vec::with_capacity(self.values.len());
            for v in &self.values {
                row.push(match v {
                    Value::Dist => dist,
                    Value::Dx => d[0],
                    Value::Dy => d[1],
                    Value::Dz => d[2],
                    Value::EngPot => engpot,
                    Value::Force => dist * fbond,
                    Value::Fx => d[0] * fbond,
                    Value::Fy => d[1] * fbond,
                    Value::Fz => d[2] * fbond,
                    Value::EngVib => engvib,
                    Value::EngRot => engrot,
                    Value::EngTrans => engtrans,
                    Value::Omega => omegasq.sqrt(),
                    Value::VelVib => vvib,
                    // without variables (compute reduce, which refuses these columns) a NaN
                    Value::Var(name) => match ev.as_mut() {
                        Some(ev) => dmhs_parser::variables::compute_equal(&mut **ev, name).map_err(|e| format!("compute {}: {e}", self.id))?,
                        None => f64::NAN,
                    },
                });
            }
            out.push(row);
        }
        Ok(out)
    }
}
