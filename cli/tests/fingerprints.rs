//! What users get, pinned bit for bit: every method's output on the Cornell box, an image
//! of every built-in scene, and every lobe a material can have (`tests/data/lobes.toml`), produced by the `strahl` binary and compared with a fingerprint
//! (64-bit FNV-1a) of its exact bytes.
//!
//! Images are written as PFM (the linear `f32` radiance, unrounded); reports as JSON with the
//! wall-clock timings removed; solutions as PLY and GLB. A change that alters no result leaves
//! every fingerprint as it is. A change that alters results on purpose records the new
//! fingerprints (the failure message lists them) and says so in its commit.

use std::path::{Path, PathBuf};
use std::process::Command;

/// One run of the binary and the files whose fingerprints it must reproduce.
struct Case {
    name: &'static str,
    args: Vec<String>,
    /// (file name in the case's folder, expected fingerprint).
    outputs: Vec<(&'static str, u64)>,
}

fn case(name: &'static str, args: &str, outputs: &[(&'static str, u64)]) -> Case {
    Case {
        name,
        args: args.split_whitespace().map(str::to_string).collect(),
        outputs: outputs.to_vec(),
    }
}

/// 64-bit FNV-1a of `bytes`.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// Removes every `seconds`, `seconds_*` and `peak_memory_*` entry from `value` and the
/// objects within it.
fn drop_timings(value: &mut serde_json::Value) {
    match value {
        serde_json::Value::Object(map) => {
            map.retain(|k, _| {
                k != "seconds" && !k.starts_with("seconds_") && !k.starts_with("peak_memory_")
            });
            map.values_mut().for_each(drop_timings);
        }
        serde_json::Value::Array(items) => items.iter_mut().for_each(drop_timings),
        _ => {}
    }
}

/// The bytes a fingerprint is taken of: the file itself, or for a JSON report the report
/// without its timings and memory figures (`seconds`, `seconds_*` and `peak_memory_*`
/// anywhere in `stats`).
fn comparable_bytes(path: &Path) -> Vec<u8> {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    if path.extension().is_some_and(|e| e == "json") {
        let mut report: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
        drop_timings(&mut report["stats"]);
        return serde_json::to_vec(&report).unwrap();
    }
    bytes
}

fn folder(case: &str) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("strahl-fingerprints-{}", std::process::id()))
        .join(case);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn outputs_match_their_fingerprints() {
    let cases = [
        // The Cornell box by every method.
        case(
            "raytrace",
            "render cornell -o {}/image.pfm --width 48 --height 40 --spp 4",
            &[("image.pfm", 0xf260312793beaf0b)],
        ),
        case(
            "raytrace-adaptive",
            "render cornell -o {}/image.pfm --width 48 --height 40 --aa adaptive --aa-map {}/map.pfm",
            &[
                ("image.pfm", 0xbd99424b1f04dfb3),
                ("map.pfm", 0x3fa79115a7e76e67),
            ],
        ),
        case(
            "raytrace-no-shadows-octree",
            "render cornell -o {}/image.pfm --width 32 --height 32 --aa none --shadows off --accel octree",
            &[("image.pfm", 0x5a9155c322405ea2)],
        ),
        case(
            "pathtrace",
            "render cornell -o {}/image.pfm --method pathtrace --width 48 --height 40 --spp 16",
            &[("image.pfm", 0xa3ee22db3c8e7885)],
        ),
        case(
            "pathtrace-branching",
            "render cornell -o {}/image.pfm --method pathtrace --width 32 --height 32 --spp 4 --first-hit-paths 3 --depth 4",
            &[("image.pfm", 0xc01c23d38a68eaf0)],
        ),
        case(
            "radiosity-matrix",
            "render cornell -o {}/image.pfm --method radiosity --solver matrix --mesh-size levels:2 --shading flat --wireframe --width 48 --height 40",
            &[("image.pfm", 0xfd0b9ba6f8dbe4bf)],
        ),
        case(
            "radiosity-progressive",
            "render cornell -o {}/image.pfm --method radiosity --solver progressive --mesh-size levels:2 --width 48 --height 40",
            &[("image.pfm", 0x0867cae804d723ad)],
        ),
        case(
            "solve-light-trace",
            "solve cornell --solver light-trace --photons 100000 --report {}/report.json",
            &[("report.json", 0x7bc794b486e23e42)],
        ),
        case(
            "solve-matrix",
            "solve cornell --solver matrix --iteration jacobi --mesh-size levels:2 --report {}/report.json --export {}/solution.ply",
            &[
                ("report.json", 0x0d06c625c48cd092),
                ("solution.ply", 0xefd6b29488e22c08),
            ],
        ),
        case(
            "solve-progressive",
            "solve cornell --solver progressive --overshoot --mesh-size levels:2 --vis-rays 16 --report {}/report.json --export {}/solution.glb",
            &[
                ("report.json", 0x230a181a19fcfa7b),
                ("solution.glb", 0x691b84ca53fd1518),
            ],
        ),
        case(
            "solve-hierarchical",
            "solve cornell --solver hierarchical --error 3e-4 --report {}/report.json --export {}/solution.ply",
            &[
                ("report.json", 0xdf5b18b405dd3e3a),
                ("solution.ply", 0xb76b10c8324c9e34),
            ],
        ),
        case(
            "solve-hierarchical-shooting",
            "solve cornell --solver hierarchical-shooting --error 1e-3 --report {}/report.json",
            &[("report.json", 0x67cc2b38942dd24b)],
        ),
        case(
            "radiosity-hierarchical",
            "render cornell -o {}/image.pfm --method radiosity --solver hierarchical --error 3e-4 --width 48 --height 40",
            &[("image.pfm", 0x3625a474b8fea949)],
        ),
        case(
            "final-gather",
            "render cornell -o {}/image.pfm --method final-gather --solver hierarchical --error 1e-3 --gather-rays 4 --spp 1 --width 32 --height 24",
            &[("image.pfm", 0x5e719a2952d2f84a)],
        ),
        // Every other built-in scene.
        case(
            "cornell-textured",
            "render cornell-textured -o {}/image.pfm --method pathtrace --width 32 --height 32 --spp 8",
            &[("image.pfm", 0xc5cefae8bb3bbf02)],
        ),
        case(
            "spheres",
            "render spheres:30 -o {}/image.pfm --width 32 --height 32 --spp 4",
            &[("image.pfm", 0xceefd5b8c561de3e)],
        ),
        case(
            "neon",
            "render neon -o {}/image.pfm --method pathtrace --width 32 --height 32 --spp 8",
            &[("image.pfm", 0xcd31f26dbb05d1c3)],
        ),
        case(
            "canopy",
            "solve canopy:300 --solver light-trace --photons 50000 --report {}/report.json",
            &[("report.json", 0x642a0bfb166cdb24)],
        ),
        // Every lobe (Lambert, Phong, mirror, dielectric, and all four in one material) by
        // the methods that follow them.
        case(
            "lobes-raytrace",
            "render ../tests/data/lobes.toml -o {}/image.pfm --width 48 --height 36",
            &[("image.pfm", 0x22e64d264e899000)],
        ),
        case(
            "lobes-pathtrace",
            "render ../tests/data/lobes.toml -o {}/image.pfm --method pathtrace --width 48 --height 36 --spp 16",
            &[("image.pfm", 0xc2012fc19801b859)],
        ),
        case(
            "lobes-light-trace",
            "solve ../tests/data/lobes.toml --solver light-trace --photons 100000 --report {}/report.json",
            &[("report.json", 0xa8b2127b4501f3da)],
        ),
        case(
            "lobes-final-gather",
            "render ../tests/data/lobes.toml -o {}/image.pfm --method final-gather --error 1e-3 --gather-rays 4 --spp 1 --width 32 --height 24",
            &[("image.pfm", 0xd7c0ad0cdc0ad356)],
        ),
        case(
            "blocks",
            "solve blocks:20 --solver hierarchical --error 1e-3 --report {}/report.json",
            &[("report.json", 0x97f67e4f5d5063cd)],
        ),
    ];
    let mut mismatches = Vec::new();
    for case in &cases {
        let dir = folder(case.name);
        let args: Vec<String> = case
            .args
            .iter()
            .map(|a| a.replace("{}", dir.to_str().unwrap()))
            .collect();
        let out = Command::new(env!("CARGO_BIN_EXE_strahl"))
            .args(&args)
            .arg("--quiet")
            .output()
            .expect("the binary runs");
        assert!(
            out.status.success(),
            "{}: {}",
            case.name,
            String::from_utf8_lossy(&out.stderr)
        );
        for &(file, expected) in &case.outputs {
            let got = fnv1a(&comparable_bytes(&dir.join(file)));
            if got != expected {
                mismatches.push(format!("{}/{file}: {got:#018x}", case.name));
            }
        }
    }
    assert!(
        mismatches.is_empty(),
        "outputs differ from their fingerprints:\n{}",
        mismatches.join("\n")
    );
}
