//! Every input that once crashed a fuzz target (`fuzz/`, `scripts/fuzz.sh`), kept in
//! `tests/data/fuzz/` and fed to the same reader: each must now give a result or an error,
//! never a panic. The extension says which reader: `.toml` a scene file, `.obj_mtl` an OBJ
//! text, a zero byte and its MTL text, `.gltf`/`.glb` a glTF file, `.texture` an image.

use std::path::{Path, PathBuf};
use strahl::scene::{ColorSpace, MAX_TEXELS, Texture, import, load_str};

/// This test's scratch folder.
fn scratch() -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("strahl-fuzz-regressions-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Feeds `input` to the reader its extension names; `Err` only when the reader panicked.
fn replay(name: &str, input: &[u8]) -> Result<(), String> {
    let dir = scratch();
    let run = || match Path::new(name).extension().and_then(|e| e.to_str()) {
        Some("toml") => {
            let text = String::from_utf8_lossy(input);
            let _ = load_str(&text, name, Path::new("tests/data"));
        }
        Some("obj_mtl") => {
            let cut = input.iter().position(|&b| b == 0).unwrap_or(input.len());
            std::fs::write(dir.join("fuzz.mtl"), input.get(cut + 1..).unwrap_or(&[])).unwrap();
            std::fs::write(dir.join("fuzz.obj"), &input[..cut]).unwrap();
            if let Ok(mesh) = import::load_mesh(&dir.join("fuzz.obj")) {
                mesh.mesh.validate().unwrap();
            }
        }
        Some(ext @ ("gltf" | "glb")) => {
            let path = dir.join(format!("fuzz.{ext}"));
            std::fs::write(&path, input).unwrap();
            let _ = import::load_mesh(&path);
        }
        Some("texture") => {
            let path = dir.join("fuzz.ppm");
            std::fs::write(&path, input).unwrap();
            if let Ok(texture) = Texture::load(&path, ColorSpace::Srgb, MAX_TEXELS) {
                assert!(texture.mean_color().is_finite());
            }
        }
        other => panic!("{name}: unknown kind {other:?}"),
    };
    std::panic::catch_unwind(run).map_err(|_| format!("{name} panicked"))
}

#[test]
fn inputs_that_crashed_the_fuzzers_no_longer_do() {
    let mut entries: Vec<_> = std::fs::read_dir("tests/data/fuzz")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e != "md"))
        .collect();
    entries.sort();
    assert!(entries.len() >= 2);
    let failures: Vec<String> = entries
        .iter()
        .filter_map(|path| {
            let name = path.file_name().unwrap().to_str().unwrap();
            replay(name, &std::fs::read(path).unwrap()).err()
        })
        .collect();
    assert!(failures.is_empty(), "{failures:?}");
}

/// The error reading `tests/data/fuzz/{file}` as a mesh gives.
fn import_error(file: &str) -> String {
    import::load_mesh(&Path::new("tests/data/fuzz").join(file))
        .unwrap_err()
        .to_string()
}

#[test]
fn a_glb_shorter_than_its_header_is_an_error() {
    let err = import_error("glb_short_length.glb");
    assert!(err.contains("fewer than the 12 of the header"), "{err}");
}

#[test]
fn an_accessor_of_no_elements_is_an_error() {
    // A release build wrapped `count − 1` and read nothing; a checked build panicked.
    let err = import_error("gltf_accessor_count_zero.gltf");
    assert!(err.contains("POSITION (accessor 0): count 0"), "{err}");
}
