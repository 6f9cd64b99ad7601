//! The command line fed what a careless or hostile user types: every case must end with a
//! non-zero exit and a message naming the flag or file and the problem — never a crash, a
//! hang, an allocation failure or a silent black result. And Ctrl-C: a partial result,
//! written, and exit code 130.

use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

mod common;

use common::strahl;

fn temp(name: &str) -> PathBuf {
    common::temp("hostile", name)
}

/// A case: the arguments after the subcommand's output or scene, and what the message must
/// say.
struct Case {
    args: &'static [&'static str],
    says: &'static [&'static str],
}

const fn case(args: &'static [&'static str], says: &'static [&'static str]) -> Case {
    Case { args, says }
}

/// `render cornell -o OUT.png` followed by these.
const RENDER: &[Case] = &[
    case(
        &["--width", "100000", "--height", "100000"],
        &["100000×100000", "--max-pixels"],
    ),
    case(
        &["--width", "4294967295", "--height", "1"],
        &["4294967295 pixels", "--max-pixels"],
    ),
    case(&["--width", "0"], &["--width", "0 is not in 1.."]),
    case(&["--width", "-3"], &["'-3'"]),
    case(&["--width", "abc"], &["--width", "abc"]),
    case(&["--exposure", "nan"], &["--exposure", "finite", "nan"]),
    case(&["--exposure", "inf"], &["--exposure", "finite"]),
    case(&["--aa-threshold", "nan"], &["--aa-threshold", "finite"]),
    case(&["--spp", "0"], &["--spp", "0 is not in 1.."]),
    case(
        &["--spp", "4294967295"],
        &["--spp 4294967295", "--max-samples"],
    ),
    case(
        &["--light-samples", "4294967294"],
        &["--light-samples 4294967294", "--max-samples"],
    ),
    case(&["--light-samples", "0"], &["--light-samples", "0 is not"]),
    case(
        &["--method", "pathtrace", "--first-hit-paths", "100000000"],
        &["--first-hit-paths 100000000", "--max-samples"],
    ),
    case(
        &["--method", "pathtrace", "--time-limit", "nan"],
        &["--time-limit", "finite"],
    ),
    case(
        &["--method", "final-gather", "--gather-rays", "99999999"],
        &["--gather-rays 99999999", "--max-samples"],
    ),
    case(&["--gather-rays", "0"], &["--gather-rays", "0 is not"]),
    case(&["--solver", "matrix"], &["--solver matrix", "raytrace"]),
    case(
        &["--method", "pathtrace", "--solver", "progressive"],
        &["--solver progressive", "pathtrace"],
    ),
    case(&["--method", "magic"], &["--method", "magic"]),
    case(&["--threads", "-1"], &["'-1'"]),
    case(&["--max-pixels", "0"], &["--max-pixels", "0 is not"]),
    case(&["--aa-map", "map.png"], &["--aa-map needs --aa adaptive"]),
    // Said "' ': unsupported image file extension", naming no flag.
    case(
        &["--aa", "adaptive", "--aa-map", " "],
        &["--aa-map: ' ': unsupported image file extension"],
    ),
    case(
        &["--method", "radiosity", "--export", " "],
        &["--export: ' ': an export file must end in"],
    ),
    case(
        &["--method", "radiosity", "--segments", "100000"],
        &["--segments", "100000 is not in 3..=1024"],
    ),
    case(
        &["--method", "radiosity", "--segments", "0"],
        &["--segments", "0 is not in 3"],
    ),
    case(
        &["--method", "radiosity", "--solver", "light-trace"],
        &["--method radiosity needs --solver"],
    ),
    case(
        &[
            "--method",
            "radiosity",
            "--solver",
            "progressive",
            "--mesh-size",
            "levels:12",
        ],
        &["more than 4000000 patches", "--max-patches"],
    ),
    case(
        &[
            "--method",
            "radiosity",
            "--solver",
            "matrix",
            "--mesh-size",
            "1e-9",
        ],
        &["patches", "--mesh-size"],
    ),
    case(
        &["--method", "radiosity", "--receiver-samples", "0"],
        &["--receiver-samples", "0 is not"],
    ),
    case(
        &["--method", "radiosity", "--receiver-samples", "1000"],
        &["--receiver-samples² 1000000", "--max-samples"],
    ),
    case(
        &["--method", "radiosity", "--link-samples", "0"],
        &["--link-samples", "0 is not"],
    ),
    case(
        &["--method", "radiosity", "--error", "nan"],
        &["--error", "finite"],
    ),
    case(
        &["--method", "radiosity", "--error=-1"],
        &["--error", "between 1e-8 and 1"],
    ),
    case(
        &["--method", "radiosity", "--min-area", "2"],
        &["--min-area", "between 1e-8 and 1"],
    ),
    case(
        &["--method", "radiosity", "--surface-error", "1.5"],
        &["--surface-error", "0 (off) or lie between 1e-4 and 1"],
    ),
    case(
        &["--method", "radiosity", "--tolerance", "inf"],
        &["--tolerance", "finite"],
    ),
    case(
        &["--method", "radiosity", "--solver", "matrix", "--links"],
        &["--links needs --solver hierarchical"],
    ),
];

/// `solve cornell` followed by these.
const SOLVE: &[Case] = &[
    case(&["--photons", "0"], &["--photons", "0 is not in 1.."]),
    case(
        &["--photons", "18446744073709551615"],
        &[
            "--photons",
            "18446744073709551615 is not in 1..=1000000000000",
        ],
    ),
    // No round, sweep or shot: the report would hold a negative indirect part.
    case(
        &["--solver", "hierarchical", "--max-rounds", "0"],
        &["--max-rounds must be at least 1"],
    ),
    case(
        &["--solver", "matrix", "--max-iterations", "0"],
        &["--max-iterations must be at least 1"],
    ),
    case(
        &["--solver", "progressive", "--max-shots", "0"],
        &["--max-shots must be at least 1"],
    ),
    case(&["--photons", "1e6"], &["--photons", "1e6"]),
    case(
        &["--export", "x.ply"],
        &["--export", "radiosity solution", "--solver"],
    ),
    case(&["--report", "x.xml"], &["--report: 'x.xml'"]),
    case(
        &["--export", " "],
        &["--export: ' ': an export file must end in"],
    ),
    case(&["--solver", "matrix", "--segments", "2"], &["--segments"]),
    case(
        &["--solver", "matrix", "--mesh-size", "levels:20"],
        &["--mesh-size", "levels must be an integer 0..=12"],
    ),
    case(
        &["--solver", "matrix", "--mesh-size", "levels:11"],
        &["more than 4000000 patches", "--max-patches"],
    ),
    case(
        &["--solver", "hierarchical", "--max-patches", "5"],
        &["more than 5 patches", "--max-patches"],
    ),
    case(
        &["--solver", "hierarchical", "--mesh-size", "levels:x"],
        &["--mesh-size"],
    ),
    case(
        &["--solver", "hierarchical", "--mesh-size", "-1"],
        &["'-1'"],
    ),
    case(
        &["--solver", "hierarchical", "--oracle", "psychic"],
        &["--oracle", "psychic"],
    ),
    case(&["--solver", "raytrace"], &["--solver", "raytrace"]),
    // Tried to allocate 8 GiB of ray buffers and aborted.
    case(
        &["--solver", "matrix", "--vis-rays", "4294967295"],
        &["--vis-rays 4294967295", "--max-samples"],
    ),
    // Ran until killed: links without end.
    case(
        &["--solver", "hierarchical", "--error", "1e-300"],
        &["--error", "between 1e-8 and 1"],
    ),
    case(
        &["--solver", "hierarchical", "--surface-error", "1e-9"],
        &["--surface-error", "between 1e-4 and 1"],
    ),
    case(
        &["--solver", "hierarchical", "--surface-gather", "1e-9"],
        &["--surface-gather", "between 1e-4 and 1"],
    ),
    case(
        &["--surface-gather", "0.01"],
        &["--surface-gather", "need --solver matrix"],
    ),
    case(
        &["--gather-below", "0.1"],
        &["--gather-below", "need --solver matrix"],
    ),
    case(
        &["--solver", "hierarchical", "--gather-below", "0"],
        &["--gather-below", "above 0 and at most 1"],
    ),
    // Stopped before any bounce: the report held the direct light alone, marked complete.
    case(
        &["--solver", "progressive", "--tolerance", "1e308"],
        &["--tolerance", "before light bounced once"],
    ),
    case(
        &["--solver", "matrix", "--tolerance", "0"],
        &["--tolerance", "between 1e-12 and 1"],
    ),
];

fn assert_refused(args: &[&str], says: &[&str]) {
    let o = strahl(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && o.status.code().is_some(),
        "{args:?}: exit {:?}, stderr {err}",
        o.status
    );
    for needle in says {
        assert!(err.contains(needle), "{args:?}: '{needle}' not in: {err}");
    }
}

#[test]
fn render_refuses_every_malformed_flag_with_a_message() {
    let out = temp("refused.png");
    for c in RENDER {
        let mut args = vec!["render", "cornell", "-o", out.to_str().unwrap(), "-q"];
        args.extend_from_slice(c.args);
        assert_refused(&args, c.says);
    }
    assert!(!out.exists(), "no image is written for a refused command");
}

#[test]
fn solve_refuses_every_malformed_flag_with_a_message() {
    for c in SOLVE {
        let mut args = vec!["solve", "cornell", "-q"];
        args.extend_from_slice(c.args);
        assert_refused(&args, c.says);
    }
}

#[test]
fn bench_refuses_repeats_out_of_bounds() {
    assert_refused(
        &["bench", "cornell", "--repeat", "0"],
        &["--repeat", "0 is not in 1.."],
    );
    assert_refused(
        &["bench", "cornell", "--repeat", "4294967295"],
        &["--repeat", "4294967295 is not in 1..=1000"],
    );
}

#[test]
fn an_absurd_thread_count_is_capped_with_a_warning() {
    // 100,000 threads took minutes to start; now four per core at most, the same image.
    let out = temp("threads.png");
    let start = Instant::now();
    let run = common::small_render(&out, &["--threads", "100000"]);
    let message = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{message}");
    assert!(
        message.contains("--threads 100000 is more than 4 per core"),
        "{message}"
    );
    assert!(start.elapsed() < Duration::from_secs(10));
}

#[test]
fn a_scene_without_light_is_refused_by_solve_and_warned_about_by_render() {
    let scene = temp("dark.toml");
    std::fs::write(
        &scene,
        "[materials.grey]\ndiffuse = 0.5\n\n\
         [[objects]]\nname = \"floor\"\ntype = \"quad\"\nmaterial = \"grey\"\n\
         vertices = [[-1, 0, -1], [-1, 0, 1], [1, 0, 1], [1, 0, -1]]\n",
    )
    .unwrap();
    let path = scene.to_str().unwrap();
    for solver in ["light-trace", "hierarchical"] {
        assert_refused(
            &["solve", path, "--solver", solver, "-q"],
            &["has no light", "nothing to solve"],
        );
    }
    let image = temp("dark.png");
    let o = strahl(&[
        "render",
        path,
        "-o",
        image.to_str().unwrap(),
        "--width",
        "8",
        "--height",
        "8",
    ]);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("warning: ") && image.exists());
}

#[test]
fn building_a_scene_over_the_memory_bound_ends_with_a_message() {
    // Building ten million spheres and their BVH (6 GB) cannot be stopped halfway: it aborted
    // where the machine had less; the memory watch ends it past the bound instead.
    let start = Instant::now();
    assert_refused(
        &["info", "spheres:10000000", "--max-memory", "300"],
        &["over the bound (--max-memory", "raise --max-memory"],
    );
    assert!(start.elapsed() < Duration::from_secs(10));
}

#[test]
fn validate_refuses_samples_out_of_bounds() {
    // Said only "22 validation checks failed".
    assert_refused(
        &["validate", "--quick", "--samples", "4294967295"],
        &["--samples", "4294967295 is not in 1..=16777216"],
    );
    assert_refused(
        &["validate", "--quick", "--error", "1e-300"],
        &["error", "between 1e-8 and 1"],
    );
}

#[test]
fn a_closed_box_that_reflects_all_light_stops_every_radiosity_solver() {
    // No steady state exists (B = E/(1 − ρ) with ρ = 1): hierarchical radiosity and the
    // radiosity display ran until killed, progressive for a million shots.
    let scene = temp("white_box.toml");
    std::fs::write(
        &scene,
        "[materials.white]\ndiffuse = 1.0\n\n\
         [materials.lamp]\ndiffuse = 1.0\nemission = 1.0\n\n\
         [[objects]]\nname = \"box\"\ntype = \"box\"\nmaterial = \"white\"\n\
         min = [0, 0, 0]\nmax = [1, 1, 1]\n\n\
         [[objects]]\nname = \"lamp\"\ntype = \"quad\"\nmaterial = \"lamp\"\n\
         vertices = [[0.4, 0.99, 0.4], [0.6, 0.99, 0.4], [0.6, 0.99, 0.6], [0.4, 0.99, 0.6]]\n",
    )
    .unwrap();
    let path = scene.to_str().unwrap();
    let image = temp("white_box.png");
    let says = [
        "no steady state",
        "reflect all light",
        "reflectance below 0.999",
    ];
    for solver in [
        "matrix",
        "progressive",
        "hierarchical",
        "hierarchical-shooting",
    ] {
        let start = Instant::now();
        assert_refused(&["solve", path, "--solver", solver, "-q"], &says);
        assert!(start.elapsed() < Duration::from_secs(10), "{solver}");
    }
    let start = Instant::now();
    let render = [
        "render",
        path,
        "-o",
        image.to_str().unwrap(),
        "--method",
        "radiosity",
        "-q",
    ];
    assert_refused(&render, &says);
    assert!(start.elapsed() < Duration::from_secs(10) && !image.exists());
}

/// Starts `args`, sends SIGINT after `after`, and returns the exit status and how long the
/// process took to end after the signal.
fn interrupt(args: &[&str], after: Duration) -> (std::process::ExitStatus, Duration) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_strahl"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(after);
    assert!(
        child.try_wait().unwrap().is_none(),
        "{args:?} ended too soon"
    );
    let sent = Instant::now();
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let status = child.wait().unwrap();
    (status, sent.elapsed())
}

#[test]
fn ctrl_c_writes_a_partial_image_and_report_and_exits_130() {
    // Far more work than the test waits for: whole tiles at this sample count take minutes.
    let image = temp("partial.png");
    let (status, took) = interrupt(
        &[
            "render",
            "cornell",
            "-o",
            image.to_str().unwrap(),
            "--spp",
            "60000",
            "--width",
            "64",
            "--height",
            "64",
            "--threads",
            "1",
            "-q",
        ],
        Duration::from_millis(1500),
    );
    assert_eq!(status.code(), Some(130));
    // Generous against a loaded machine; it stops within a pixel's samples.
    assert!(took < Duration::from_secs(10), "{took:?}");
    let film = strahl::image::load(&image).unwrap();
    assert_eq!((film.width(), film.height()), (64, 64));

    let report = temp("partial.json");
    let (status, _) = interrupt(
        &[
            "solve",
            "cornell",
            "--photons",
            "100000000000",
            "--report",
            report.to_str().unwrap(),
            "--threads",
            "1",
            "-q",
        ],
        Duration::from_millis(1500),
    );
    assert_eq!(status.code(), Some(130));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    // The light model's report is scaled to the photons traced and says it is not complete.
    assert_eq!(json["stats"]["complete"], serde_json::Value::Bool(false));
    let traced = json["stats"]["photons_traced"].as_u64().unwrap();
    assert!(traced > 0 && traced < 100_000_000_000, "{traced}");
}

#[test]
fn a_run_over_the_memory_bound_stops_with_a_message_naming_the_flag() {
    let image = temp("memory.png");
    for args in [
        vec![
            "solve",
            "cornell",
            "--solver",
            "hierarchical",
            "-q",
            "--max-memory",
            "1",
        ],
        vec![
            "render",
            "cornell",
            "--method",
            "pathtrace",
            "-q",
            "--max-memory",
            "1",
            "-o",
            image.to_str().unwrap(),
        ],
    ] {
        let o = strahl(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains("MiB of memory") && err.contains("--max-memory"),
            "{args:?}: {err}"
        );
    }
}

#[test]
fn textures_beyond_max_texels_are_refused_naming_the_flag() {
    // example.toml's checker.ppm has 2 × 2 texels.
    assert_refused(
        &[
            "solve",
            "../tests/data/example.toml",
            "-q",
            "--max-texels",
            "3",
        ],
        &["checker.ppm", "4 texels", "--max-texels"],
    );
    let o = strahl(&[
        "solve",
        "../tests/data/example.toml",
        "-q",
        "--photons",
        "1000",
        "--max-texels",
        "4",
        "--report",
        temp("texels.json").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}
