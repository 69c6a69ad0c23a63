//! VTK XML unstructured-grid files (.vtu) for ParaView: one file per snapshot, particles as
//! vertex cells, every per-particle field as point data (`dump ID group vtk N file*.vtu [fields]`).

use crate::engine::state::State;
use std::fmt::Write;

/// A named per-particle array with 1 or 3 components, for the owned atoms selected.
pub struct Field {
    pub name: String,
    pub components: usize,
    pub values: Vec<f64>,
}

/// The document for particles at `points` with `fields`.
pub fn document(points: &[[f64; 3]], fields: &[Field], step: i64, time: f64) -> String {
    let n = points.len();
    let mut s = String::with_capacity(64 * n * (fields.len() + 2));
    s += "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>\n";
    let _ = writeln!(s, "<FieldData>\n<DataArray type=\"Int64\" Name=\"TIMESTEP\" NumberOfTuples=\"1\" format=\"ascii\">{step}</DataArray>");
    let _ = writeln!(s, "<DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" format=\"ascii\">{time:?}</DataArray>\n</FieldData>");
    let _ = writeln!(s, "<Piece NumberOfPoints=\"{n}\" NumberOfCells=\"{n}\">");
    s += "<PointData>\n";
    for f in fields {
        let _ = writeln!(s, "<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">", f.name, f.components);
        for chunk in f.values.chunks(f.components.max(1) * 4) {
            let line: Vec<String> = chunk.iter().map(|v| format!("{v:?}")).collect();
            s += &line.join(" ");
            s.push('\n');
        }
        s += "</DataArray>\n";
    }
    s += "</PointData>\n<Points>\n<DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for p in points {
        let _ = writeln!(s, "{:?} {:?} {:?}", p[0], p[1], p[2]);
    }
    s += "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for k in 0..n {
        let _ = write!(s, "{k} ");
    }
    s += "\n</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for k in 1..=n {
        let _ = write!(s, "{k} ");
    }
    s += "\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for _ in 0..n {
        s += "1 ";
    }
    s += "\n</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
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
