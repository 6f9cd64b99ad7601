//! The glTF importer: binary glTF when the input starts with the GLB magic, JSON otherwise.

#![no_main]

mod common;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let name = if data.starts_with(b"glTF") {
        "fuzz.glb"
    } else {
        "fuzz.gltf"
    };
    let path = common::scratch().join(name);
    std::fs::write(&path, data).expect("cannot write the glTF input");
    let _ = strahl::scene::import::load_mesh(&path);
});
