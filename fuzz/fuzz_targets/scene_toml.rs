//! The TOML scene loader, then the world built from what it loads (tessellation and BVH).
//! Mesh and texture paths resolve against `tests/data`, so inputs may name its files.

#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;
use strahl::accel::AccelKind;
use strahl::world::World;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let data_dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data"));
    if let Ok(scene) = strahl::scene::load_str(text, "fuzz.toml", data_dir) {
        let _ = World::new(scene, AccelKind::Bvh);
    }
});
