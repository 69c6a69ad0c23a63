//! VTK XML unstructured-grid files (.vtu) for ParaView: one file per snapshot, particles as
//! vertex cells, every per-particle field as point data (`dump ID group vtk N file*.vtu [fields]`),
//! and a `.pvd` collection that lists the snapshots with their times, so ParaView opens a run as
//! one time series. Arrays are binary by default, as VTK's own writers store them inline
//! (`format="binary"`: the array's byte count as a UInt64, then its little-endian values, base64
//! encoded together), which keeps the file valid XML; `dump_modify ID binary no` writes them as
//! ASCII text. Vector quantities whose three components are all dumped
//! (vx vy vz, fx fy fz, omegax omegay omegaz, ...) become one 3-component array; integer
//! attributes (id, type, mol, image flags) are integer arrays.

use crate::engine::state::State;
use std::fmt::Write;

/// The values of one array.
#[derive(Clone, Debug, PartialEq)]
pub enum Values {
    F64(Vec<f64>),
    I64(Vec<i64>),
}

impl Values {
    fn vtk_type(&self) -> &'static str {
        match self {
            Values::F64(_) => "Float64",
            Values::I64(_) => "Int64",
        }
    }
    fn len(&self) -> usize {
        match self {
            Values::F64(v) => v.len(),
            Values::I64(v) => v.len(),
        }
    }
    fn le_bytes(&self, out: &mut Vec<u8>) {
        match self {
            Values::F64(v) => v.iter().for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
            Values::I64(v) => v.iter().for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
        }
    }
    fn ascii(&self, components: usize, s: &mut String) {
        let per_line = components.max(1) * 4;
        match self {
            Values::F64(v) => v.chunks(per_line).for_each(|c| {
                let _ = writeln!(s, "{}", c.iter().map(|x| format!("{x:?}")).collect::<Vec<_>>().join(" "));
            }),
            Values::I64(v) => v.chunks(per_line).for_each(|c| {
                let _ = writeln!(s, "{}", c.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(" "));
            }),
        }
    }
}

/// A named per-particle array with 1 or 3 components (interleaved), for the atoms selected.
#[derive(Clone, Debug, PartialEq)]
pub struct Field {
    pub name: String,
    pub components: usize,
    pub values: Values,
}

/// Dump columns that are the three components of one vector, and the vector's name.
const VECTORS: &[([&str; 3], &str)] = &[
    (["vx", "vy", "vz"], "v"),
    (["fx", "fy", "fz"], "f"),
    (["omegax", "omegay", "omegaz"], "omega"),
    (["tqx", "tqy", "tqz"], "torque"),
    (["angmomx", "angmomy", "angmomz"], "angmom"),
    (["mux", "muy", "muz"], "mu"),
    (["xu", "yu", "zu"], "xu"),
    (["ix", "iy", "iz"], "image"),
];

/// The arrays of a snapshot from its columns: (name, values, integer?) in dump order. Three
/// components of a vector become one 3-component array at the place of the first.
pub fn fields(columns: Vec<(String, Vec<f64>, bool)>) -> Vec<Field> {
    let mut out = vec![];
    let mut used = vec![false; columns.len()];
    for k in 0..columns.len() {
        if used[k] {
            continue;
        }
        let (name, values, int) = &columns[k];
        let vector = VECTORS.iter().find(|(parts, _)| parts[0] == name).and_then(|(parts, vname)| {
            let at: Vec<usize> = parts.iter().filter_map(|p| columns.iter().position(|c| c.0 == *p)).collect();
            (at.len() == 3).then_some((at, *vname))
        });
        let pack = |v: Vec<f64>, int: bool| if int { Values::I64(v.iter().map(|x| x.round() as i64).collect()) } else { Values::F64(v) };
        match vector {
            Some((at, vname)) => {
                let n = values.len();
                let mut v = Vec::with_capacity(3 * n);
                for i in 0..n {
                    v.extend(at.iter().map(|&c| columns[c].1[i]));
                }
                let int = at.iter().all(|&c| columns[c].2);
                at.iter().for_each(|&c| used[c] = true);
                out.push(Field { name: vname.to_string(), components: 3, values: pack(v, int) });
            }
            None => {
                used[k] = true;
                out.push(Field { name: name.clone(), components: 1, values: pack(values.clone(), *int) });
            }
        }
    }
    out
}

/// Base64 (RFC 4648, with padding) of `bytes`.
fn base64(bytes: &[u8]) -> String {
    const T: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16 | (*c.get(1).unwrap_or(&0) as u32) << 8 | *c.get(2).unwrap_or(&0) as u32;
        for k in 0..4 {
            s.push(if k <= c.len() { T[(n >> (18 - 6 * k) & 63) as usize] as char } else { '=' });
        }
    }
    s
}

/// The bytes of base64 text (whitespace ignored).
fn unbase64(text: &str) -> Result<Vec<u8>, String> {
    let val = |c: u8| -> Result<u32, String> {
        Ok(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            _ => return Err(format!("bad base64 character `{}`", c as char)),
        } as u32)
    };
    let clean: Vec<u8> = text.bytes().filter(|c| !c.is_ascii_whitespace()).collect();
    let mut out = Vec::with_capacity(clean.len() / 4 * 3);
    for q in clean.chunks(4) {
        let pad = q.iter().filter(|&&c| c == b'=').count();
        let mut n = 0u32;
        for (k, &c) in q.iter().enumerate() {
            n |= if c == b'=' { 0 } else { val(c)? } << (18 - 6 * k);
        }
        out.extend_from_slice(&n.to_be_bytes()[1..4 - pad]);
    }
    Ok(out)
}

/// The document for particles at `points` with `fields`; `binary`: base64 arrays.
pub fn document(points: &[[f64; 3]], fields: &[Field], step: i64, time: f64, binary: bool) -> String {
    let n = points.len();
    let mut s = String::with_capacity(if binary { 12 } else { 24 } * n * (4 * fields.len() + 6) + 1024);
    s += "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>\n";
    let _ = writeln!(s, "<FieldData>\n<DataArray type=\"Int64\" Name=\"TIMESTEP\" NumberOfTuples=\"1\" format=\"ascii\">{step}</DataArray>");
    let _ = writeln!(s, "<DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" format=\"ascii\">{time:?}</DataArray>\n</FieldData>");
    let _ = writeln!(s, "<Piece NumberOfPoints=\"{n}\" NumberOfCells=\"{n}\">");
    let array = |s: &mut String, name: &str, components: Option<usize>, values: &Values| {
        let comps = components.map(|c| format!(" NumberOfComponents=\"{c}\"")).unwrap_or_default();
        let format = if binary { "binary" } else { "ascii" };
        let _ = writeln!(s, "<DataArray type=\"{}\" Name=\"{name}\"{comps} format=\"{format}\">", values.vtk_type());
        if binary {
            let mut bytes = ((values.len() * 8) as u64).to_le_bytes().to_vec();
            values.le_bytes(&mut bytes);
            *s += &base64(&bytes);
            s.push('\n');
        } else {
            values.ascii(components.unwrap_or(1), s);
        }
        *s += "</DataArray>\n";
    };
    s += "<PointData>\n";
    for f in fields {
        array(&mut s, &f.name, Some(f.components), &f.values);
    }
    s += "</PointData>\n<Points>\n";
    array(&mut s, "Points", Some(3), &Values::F64(points.iter().flatten().copied().collect()));
    s += "</Points>\n<Cells>\n";
    array(&mut s, "connectivity", None, &Values::I64((0..n as i64).collect()));
    array(&mut s, "offsets", None, &Values::I64((1..=n as i64).collect()));
    // cell types: 1 (VTK_VERTEX) each, one byte
    if binary {
        let mut bytes = (n as u64).to_le_bytes().to_vec();
        bytes.extend(std::iter::repeat_n(1u8, n));
        let _ = writeln!(s, "<DataArray type=\"UInt8\" Name=\"types\" format=\"binary\">\n{}\n</DataArray>", base64(&bytes));
    } else {
        let _ = writeln!(s, "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n{}\n</DataArray>", "1 ".repeat(n));
    }
    s += "</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
    s
}

/// A ParaView collection (.pvd) of `snapshots`: (time, file name relative to the .pvd).
pub fn collection(snapshots: &[(f64, String)]) -> String {
    let mut s = String::from("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n<Collection>\n");
    for (t, file) in snapshots {
        let _ = writeln!(s, "<DataSet timestep=\"{t:?}\" part=\"0\" file=\"{file}\"/>");
    }
    s += "</Collection>\n</VTKFile>\n";
    s
}

/// Every per-particle field the atom style has (used when `dump vtk` names none).
pub fn default_fields(state: &State) -> Vec<&'static str> {
    let ft = state.atoms.features;
    let mut v = vec!["id", "type", "vx", "vy", "vz", "fx", "fy", "fz", "mass"];
    if ft.molecule {
        v.push("mol");
    }
    if ft.charge {
        v.push("q");
    }
    if ft.sphere {
        v.extend(["radius", "omegax", "omegay", "omegaz"]);
    }
    if ft.sph {
        v.extend(["rho", "esph", "cv", "drho", "desph"]);
    }
    v
}

/// Read back what [`document`] wrote (binary or ASCII): the points and the point-data arrays, for
/// tests and for tools that check a file.
pub fn read(xml: &str) -> Result<(Vec<[f64; 3]>, Vec<Field>), String> {
    let attr = |tag: &str, key: &str| -> Option<String> {
        let at = tag.find(&format!(" {key}=\""))? + key.len() + 3;
        Some(tag[at..at + tag[at..].find('"')?].to_string())
    };
    let mut points = vec![];
    let mut fields = vec![];
    let mut in_point_data = false;
    let mut rest = xml;
    while let Some(open) = rest.find('<') {
        let close = rest[open..].find('>').ok_or("unclosed tag")? + open;
        let tag = &rest[open..=close];
        let after = &rest[close + 1..];
        if tag.starts_with("<PointData") {
            in_point_data = true;
        } else if tag.starts_with("</PointData") {
            in_point_data = false;
        } else if tag.starts_with("<DataArray") {
            let name = attr(tag, "Name").ok_or("DataArray without Name")?;
            let typ = attr(tag, "type").ok_or("DataArray without type")?;
            let components: usize = attr(tag, "NumberOfComponents").and_then(|c| c.parse().ok()).unwrap_or(1);
            let text = &after[..after.find("</DataArray>").ok_or("unclosed DataArray")?];
            let words: Vec<[u8; 8]> = if typ == "UInt8" {
                vec![]
            } else if attr(tag, "format").as_deref() == Some("binary") {
                let bytes = unbase64(text)?;
                let len = u64::from_le_bytes(bytes.get(..8).ok_or("binary array without its byte count")?.try_into().unwrap()) as usize;
                bytes.get(8..8 + len).ok_or("binary array shorter than its byte count")?.chunks(8).map(|c| c.try_into().unwrap()).collect()
            } else if typ == "Float64" {
                text.split_whitespace().map(|w| w.parse::<f64>().map(|x| x.to_le_bytes())).collect::<Result<_, _>>().map_err(|e| e.to_string())?
            } else {
                text.split_whitespace().map(|w| w.parse::<i64>().map(|x| x.to_le_bytes())).collect::<Result<_, _>>().map_err(|e| e.to_string())?
            };
            let values = if typ == "Float64" { Values::F64(words.iter().map(|b| f64::from_le_bytes(*b)).collect()) } else { Values::I64(words.iter().map(|b| i64::from_le_bytes(*b)).collect()) };
            if name == "Points" {
                if let Values::F64(v) = &values {
                    points = v.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
                }
            } else if in_point_data {
                fields.push(Field { name, components, values });
            }
        }
        rest = after;
    }
    Ok((points, fields))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vectors_are_grouped_and_integers_kept() {
        let cols = vec![
            ("id".to_string(), vec![1.0, 2.0], true),
            ("vx".to_string(), vec![0.1, 0.2], false),
            ("rho".to_string(), vec![1.5, 1.6], false),
            ("vz".to_string(), vec![0.5, 0.6], false),
            ("vy".to_string(), vec![0.3, 0.4], false),
            ("fx".to_string(), vec![9.0, 9.5], false),
        ];
        let f = fields(cols);
        let names: Vec<(&str, usize)> = f.iter().map(|f| (f.name.as_str(), f.components)).collect();
        assert_eq!(names, [("id", 1), ("v", 3), ("rho", 1), ("fx", 1)]);
        assert_eq!(f[0].values, Values::I64(vec![1, 2]));
        assert_eq!(f[1].values, Values::F64(vec![0.1, 0.3, 0.5, 0.2, 0.4, 0.6]));
    }

    #[test]
    fn binary_and_ascii_read_back_exactly() {
        let points = [[0.1, 0.2, 0.3], [1.0 / 3.0, -2.5e-300, 7.0]];
        let f = vec![
            Field { name: "id".into(), components: 1, values: Values::I64(vec![7, 9]) },
            Field { name: "v".into(), components: 3, values: Values::F64(vec![1.0, 2.0, 3.0, f64::MIN_POSITIVE, -0.0, 1e300]) },
        ];
        for binary in [true, false] {
            let doc = document(&points, &f, 100, 0.5, binary);
            let (p, back) = read(&doc).unwrap();
            assert_eq!(doc.contains("format=\"binary\""), binary);
            assert_eq!(p, points.to_vec(), "binary {binary}");
            assert_eq!(back, f, "binary {binary}");
        }
    }

    #[test]
    fn base64_round_trips() {
        for n in 0..12 {
            let bytes: Vec<u8> = (0..n).map(|k| (k * 37 + 250) as u8).collect();
            assert_eq!(unbase64(&base64(&bytes)).unwrap(), bytes);
        }
        assert_eq!(base64(b"Man"), "TWFu");
        assert_eq!(base64(b"Ma"), "TWE=");
        assert_eq!(base64(b"M"), "TQ==");
    }

    #[test]
    fn collection_lists_the_snapshots() {
        let c = collection(&[(0.0, "out.0.vtu".into()), (0.25, "out.100.vtu".into())]);
        assert!(c.contains("<DataSet timestep=\"0.25\" part=\"0\" file=\"out.100.vtu\"/>"), "{c}");
    }
}
