//! The OBJ importer with its material library: the input is the OBJ text, a zero byte, and
//! the MTL text (written as `fuzz.mtl`, which the OBJ may name in `mtllib`).

#![no_main]

mod common;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let (obj, mtl) = match data.iter().position(|&b| b == 0) {
        Some(i) => (&data[..i], &data[i + 1..]),
        None => (data, &[][..]),
    };
    let dir = common::scratch();
    std::fs::write(dir.join("fuzz.mtl"), mtl).expect("cannot write fuzz.mtl");
    let path = dir.join("fuzz.obj");
    std::fs::write(&path, obj).expect("cannot write fuzz.obj");
    let _ = strahl::scene::import::load_mesh(&path);
});
