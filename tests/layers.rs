//! The engine crate's structure (docs/architecture.md): each layer of src/ imports only the
//! layers above it in `LAYERS`, and `unsafe` appears only in src/engine/par/.

use std::path::{Path, PathBuf};

const LAYERS: &[&str] = &["engine", "models", "output", "sim", "deck", "tools"];

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The code of a file without its test module (tests may build a whole simulation).
fn code(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    match text.find("#[cfg(test)]") {
        Some(k) => text[..k].to_string(),
        None => text,
    }
}

fn src() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src")
}

#[test]
fn layers_import_only_the_layers_below_them() {
    let mut bad = vec![];
    for (rank, layer) in LAYERS.iter().enumerate() {
        let mut files = vec![];
        rust_files(&src().join(layer), &mut files);
        assert!(!files.is_empty(), "src/{layer} is missing");
        for f in files {
            let text = code(&f);
            for higher in &LAYERS[rank + 1..] {
                if text.contains(&format!("crate::{higher}::")) || text.contains(&format!("crate::{higher}::{{")) {
                    bad.push(format!("{} imports crate::{higher}", f.strip_prefix(src()).unwrap().display()));
                }
            }
        }
    }
    assert!(bad.is_empty(), "imports against the layer order {LAYERS:?}:\n{}", bad.join("\n"));
}

#[test]
fn unsafe_lives_in_engine_par_only() {
    let mut files = vec![];
    rust_files(&src(), &mut files);
    rust_files(&PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("parser/src"), &mut files);
    let par = src().join("engine/par");
    let bad: Vec<String> = files
        .iter()
        .filter(|f| !f.starts_with(&par))
        .filter(|f| std::fs::read_to_string(f).unwrap().lines().any(|l| l.split("//").next().unwrap().contains("unsafe")))
        .map(|f| f.display().to_string())
        .collect();
    assert!(bad.is_empty(), "unsafe outside src/engine/par: {bad:?}");
}
