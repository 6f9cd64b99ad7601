//! Alpha textures cut surfaces in every method: a plate with a square hole cut by its alpha
//! texture, under a lamp and over a floor, against the same plate built as geometry (a frame
//! of four plates). The cut-away part neither receives nor sends light nor blocks it, so the
//! two scenes must give the same per-object light (radiosity and the light model) and the
//! same images of the floor with the hole's light in the frame's shadow (standard ray
//! tracer, path tracer, radiosity display, final gather), and the camera must see the lamp
//! through the hole.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use strahl::measure::Film;
use strahl::report::Report;

/// How the plate's hole is made.
#[derive(Clone, Copy, Debug)]
enum Plate {
    /// One 2 × 2 quad whose alpha texture cuts away its middle 1 × 1.
    Cut,
    /// Four quads around the hole.
    Frame,
}

/// Where the camera looks from.
#[derive(Clone, Copy)]
enum View {
    /// Down at the floor from just under the plate (120° field of view, the floor from −1.56
    /// to 1.56 across the image).
    Floor,
    /// Up through the hole at the lamp.
    Lamp,
}

/// The scene file: a 1 × 1 lamp at y = 2 facing down, the plate at y = 1, a 4 × 4 floor.
fn scene_text(plate: Plate, view: View) -> String {
    let camera = match view {
        View::Floor => "position = [0, 0.9, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, -1]\nfov = 120",
        View::Lamp => "position = [0, 0.2, 0]\nlook_at = [0, 2, 0]\nup = [0, 0, -1]\nfov = 90",
    };
    let quad = |name: &str, material: &str, origin: [f32; 3], u: [f32; 3], v: [f32; 3]| {
        format!(
            "[[objects]]\nname = \"{name}\"\ntype = \"parallelogram\"\nmaterial = \"{material}\"\n\
             origin = {origin:?}\nedge_u = {u:?}\nedge_v = {v:?}\n"
        )
    };
    let mut text = format!(
        "[camera]\n{camera}\nwidth = 32\nheight = 32\n\n\
         [materials.floor]\ndiffuse = 0.5\n\
         [materials.lamp]\ndiffuse = 0\nemission = 10\n\
         [materials.plate]\ndiffuse = 0.6\n\
         [materials.cut]\ndiffuse = 0.6\nalpha_texture = \"hole.pgm\"\n\n"
    );
    text += &quad(
        "lamp",
        "lamp",
        [-0.5, 2.0, -0.5],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
    );
    text += &quad(
        "floor",
        "floor",
        [-2.0, 0.0, -2.0],
        [0.0, 0.0, 4.0],
        [4.0, 0.0, 0.0],
    );
    match plate {
        Plate::Cut => {
            text += &quad(
                "plate",
                "cut",
                [-1.0, 1.0, -1.0],
                [0.0, 0.0, 2.0],
                [2.0, 0.0, 0.0],
            )
        }
        Plate::Frame => {
            for (k, (origin, dz, dx)) in [
                ([-1.0, 1.0, -1.0], 0.5, 2.0),
                ([-1.0, 1.0, 0.5], 0.5, 2.0),
                ([-1.0, 1.0, -0.5], 1.0, 0.5),
                ([0.5, 1.0, -0.5], 1.0, 0.5),
            ]
            .into_iter()
            .enumerate()
            {
                text += &quad(
                    &format!("plate {k}"),
                    "plate",
                    origin,
                    [0.0, 0.0, dz],
                    [dx, 0.0, 0.0],
                );
            }
        }
    }
    text
}

/// A folder holding both scenes for `view` and the mask: an 8 × 8 grey image, black (cut
/// away) in its middle 4 × 4.
fn scenes(view: View, tag: &str) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("strahl-alpha-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut mask = String::from("P2\n8 8\n255\n");
    for y in 0..8 {
        let row: Vec<&str> = (0..8)
            .map(|x| {
                if (2..6).contains(&x) && (2..6).contains(&y) {
                    "0"
                } else {
                    "255"
                }
            })
            .collect();
        mask += &(row.join(" ") + "\n");
    }
    std::fs::write(dir.join("hole.pgm"), mask).unwrap();
    for plate in [Plate::Cut, Plate::Frame] {
        std::fs::write(scene_path(&dir, plate), scene_text(plate, view)).unwrap();
    }
    dir
}

fn scene_path(dir: &Path, plate: Plate) -> PathBuf {
    dir.join(format!("{plate:?}.toml").to_lowercase())
}

fn strahl(args: &[&str]) {
    let out = Command::new(env!("CARGO_BIN_EXE_strahl"))
        .args(args)
        .arg("--quiet")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The image of `plate` rendered by `method` (with its extra `options`).
fn render(dir: &Path, plate: Plate, method: &str, options: &[&str]) -> Film {
    let out = dir.join(format!("{plate:?}-{method}.pfm"));
    let (scene, image) = (scene_path(dir, plate), out.display().to_string());
    let mut args = vec![
        "render",
        scene.to_str().unwrap(),
        "-o",
        &image,
        "--method",
        method,
    ];
    args.extend(options);
    strahl(&args);
    strahl::image::load(&out).unwrap()
}

/// Luminance of pixel `(x, y)`.
fn luminance(film: &Film, x: u32, y: u32) -> f64 {
    film.get(x, y).to_f64().luminance()
}

/// The mean absolute luminance difference of two images over the first one's mean.
fn relative_difference(a: &Film, b: &Film) -> f64 {
    let (pa, pb) = (a.pixels(), b.pixels());
    let diff: f64 = pa
        .iter()
        .zip(pb)
        .map(|(x, y)| (x.to_f64().luminance() - y.to_f64().luminance()).abs())
        .sum();
    let mean: f64 = pa.iter().map(|x| x.to_f64().luminance()).sum();
    diff / mean
}

/// Each method with its options and the largest difference allowed between the images of
/// the cut plate and of the frame (measured: 0 for the ray tracers, which meet the same
/// surfaces; 0.7 % for the radiosity display, whose meshes differ; 0.02 % for final gather).
const METHODS: [(&str, &[&str], f64); 4] = [
    ("raytrace", &["--spp", "16", "--light-samples", "16"], 0.005),
    ("pathtrace", &["--spp", "64"], 0.005),
    ("radiosity", &[], 0.02),
    ("final-gather", &["--gather-rays", "16"], 0.005),
];

#[test]
fn every_method_casts_the_shadow_of_the_cut_away_shape() {
    let dir = scenes(View::Floor, "floor");
    for (method, options, tolerance) in METHODS {
        let cut = render(&dir, Plate::Cut, method, options);
        let frame = render(&dir, Plate::Frame, method, options);
        // The floor under the hole's middle (the image's centre) sees the whole lamp through
        // the hole; 1.4 to the side (pixel 30) it lies in the frame's shadow but for a sliver.
        let (lit, shadow) = (luminance(&cut, 16, 16), luminance(&cut, 30, 16));
        assert!(lit > 4.0 * shadow, "{method}: lit {lit}, shadow {shadow}");
        let difference = relative_difference(&cut, &frame);
        assert!(difference < tolerance, "{method}: {difference}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn every_method_sees_the_lamp_through_the_hole() {
    let dir = scenes(View::Lamp, "lamp");
    for (method, options, _) in METHODS {
        let cut = render(&dir, Plate::Cut, method, options);
        // The lamp's radiance is 10; the plate's underside is lit only by the floor.
        let (through, plate) = (luminance(&cut, 16, 16), luminance(&cut, 2, 16));
        assert!(
            (through - 10.0).abs() < 0.5,
            "{method}: through the hole {through}"
        );
        assert!(plate < 1.0, "{method}: the plate {plate}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Absorbed luminance per object, the frame's four plates summed as `plate`.
fn absorbed(dir: &Path, plate: Plate, solver: &[&str]) -> HashMap<String, f64> {
    let out = dir.join(format!("{plate:?}-{}.json", solver[0]));
    let scene = scene_path(dir, plate);
    let report = out.display().to_string();
    let mut args = vec![
        "solve",
        scene.to_str().unwrap(),
        "--report",
        &report,
        "--solver",
    ];
    args.extend(solver);
    strahl(&args);
    let report: Report = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let mut sums = HashMap::new();
    for o in report.objects {
        let name = o.name.split(' ').next().unwrap().to_string();
        *sums.entry(name).or_insert(0.0) += o.absorbed_power.luminance();
    }
    sums
}

#[test]
fn the_cut_plate_exchanges_the_light_of_the_frame() {
    let dir = scenes(View::Floor, "solve");
    let light_model = ["light-trace", "--photons", "4000000", "--seed", "3"];
    let cut = absorbed(&dir, Plate::Cut, &["hierarchical"]);
    let frame = absorbed(&dir, Plate::Frame, &["hierarchical"]);
    let traced = absorbed(&dir, Plate::Cut, &light_model);
    for object in ["plate", "floor", "lamp"] {
        let (c, f, t) = (cut[object], frame[object], traced[object]);
        // Radiosity against radiosity: the two meshes differ, the light does not.
        assert!((c - f).abs() < 0.01 * f, "{object}: cut {c}, frame {f}");
        // Against the light model (4·10⁶ photons: noise below 0.3 % on the plate).
        assert!(
            (c - t).abs() < 0.02 * t,
            "{object}: radiosity {c}, light model {t}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
