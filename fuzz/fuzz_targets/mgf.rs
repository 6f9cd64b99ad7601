//! The MGF reader with an included file: the input is the MGF text, a zero byte, and the text
//! of a second file (written as `inc.mgf`, which the first may include with `i inc.mgf`, and
//! which may include itself or the first, `fuzz.mgf`).

#![no_main]

mod common;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let (mgf, included) = match data.iter().position(|&b| b == 0) {
        Some(i) => (&data[..i], &data[i + 1..]),
        None => (data, &[][..]),
    };
    let dir = common::scratch();
    std::fs::write(dir.join("inc.mgf"), included).expect("cannot write inc.mgf");
    let path = dir.join("fuzz.mgf");
    std::fs::write(&path, mgf).expect("cannot write fuzz.mgf");
    let _ = strahl::scene::import::mgf::load(&path);
});
