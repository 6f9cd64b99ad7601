//! Radiosity solutions on curved (tessellated) shapes, by every solver: displayed flat and
//! smooth, exported and final-gathered, with the work of the smooth corner values bounded and
//! the results checked.
//!
//! The smooth values once followed the midpoints of a sliver's edge shorter than the weld
//! grid down 24 levels, 2²⁴ lookups per edge: `render spheres --method radiosity` never
//! finished. [`check_solution`] bounds the lookups by the corners, not by wall time.

use std::path::Path;
use std::sync::Arc;
use strahl::accel::AccelKind;
use strahl::color::Rgb64;
use strahl::image::ToneMapping;
use strahl::light_model::LightTraceSettings;
use strahl::measure::Film;
use strahl::method::{Method, RadiositySettings, SolvedRadiosity, run, solve_radiosity};
use strahl::progress::{Cancel, NoProgress};
use strahl::radiosity::solve::{
    DisplaySettings, LinkDisplay, RadiositySystem, Shading, Solution, SolverKind, render_solution,
    vertex_radiosity,
};
use strahl::radiosity::{MeshSize, Side};
use strahl::report::{Report, export_lit_mesh};
use strahl::sampling::SequenceKind;
use strahl::scene::{Scene, builtin};
use strahl::trace::{
    AntialiasMode, PathTracer, ProgressiveSettings, RenderSettings, render, render_progressive,
};
use strahl::world::World;

/// Image side, pixels.
const SIZE: u32 = 32;

const SOLVERS: [SolverKind; 4] = [
    SolverKind::Matrix,
    SolverKind::Progressive,
    SolverKind::Hierarchical,
    SolverKind::HierarchicalShooting,
];

/// Settings that keep one solve of a test scene within a second or two.
#[derive(Clone, Copy)]
struct Coarse {
    /// Segments around curved shapes.
    segments: u32,
    /// Initial levels of the flat solvers.
    levels: u32,
    /// Stop of the shooting solvers (fraction of the emitted power left unshot).
    tolerance: f64,
}

fn solve(world: &Arc<World>, solver: SolverKind, coarse: Coarse) -> SolvedRadiosity {
    let mut settings = RadiositySettings::new(solver);
    settings.system.mesh.segments = coarse.segments;
    if !solver.is_hierarchical() {
        settings.system.mesh.size = MeshSize::Levels(coarse.levels);
    }
    settings.hierarchical.error = 1e-3;
    settings.shooting.tolerance = coarse.tolerance;
    solve_radiosity(world, &settings, &NoProgress, &Cancel::new()).unwrap()
}

fn world(scene: Scene) -> Arc<World> {
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

fn builtin_world(name: &str) -> Arc<World> {
    world(builtin::load(name).unwrap().unwrap())
}

fn file_world(file: &str) -> Arc<World> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    world(strahl::scene::load(&dir.join(file)).unwrap())
}

/// Per-channel `(min, max)` of `values`.
fn range(values: impl IntoIterator<Item = [f64; 3]>) -> ([f64; 3], [f64; 3]) {
    values.into_iter().fold(
        ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
        |(lo, hi), v| {
            (
                std::array::from_fn(|c| lo[c].min(v[c])),
                std::array::from_fn(|c| hi[c].max(v[c])),
            )
        },
    )
}

fn within(v: [f64; 3], (lo, hi): ([f64; 3], [f64; 3]), slack: f64) -> bool {
    (0..3).all(|c| v[c] >= lo[c] - slack * hi[c].abs() && v[c] <= hi[c] + slack * hi[c].abs())
}

fn pixels(film: &Film) -> impl Iterator<Item = [f64; 3]> + '_ {
    film.pixels()
        .iter()
        .map(|p| [f64::from(p.r), f64::from(p.g), f64::from(p.b)])
}

fn display(
    system: &RadiositySystem,
    solution: &Solution,
    world: &Arc<World>,
    shading: Shading,
) -> Film {
    let settings = DisplaySettings {
        width: SIZE,
        height: SIZE,
        shading,
        wireframe: false,
        samples_per_axis: 1,
        links: LinkDisplay::None,
    };
    render_solution(
        system,
        solution,
        &world.scene.camera,
        &settings,
        &NoProgress,
        &Cancel::new(),
    )
    .unwrap()
}

/// Final gather of `solved` at [`SIZE`]², 4 samples per pixel.
fn final_gather(solved: &SolvedRadiosity, world: &Arc<World>) -> Film {
    let gather = solved.final_gather(Shading::Smooth, 4, 16);
    let settings = RenderSettings {
        width: SIZE,
        height: SIZE,
        antialias: AntialiasMode::Stochastic,
        samples_per_pixel: 4,
        adaptive_threshold: 0.05,
        seed: 3,
        sequence: SequenceKind::Random,
    };
    render(world, &gather, &settings, &NoProgress, &Cancel::new())
        .unwrap()
        .film
}

/// Mean luminance of `film`.
fn mean(film: &Film) -> f64 {
    film.pixels()
        .iter()
        .map(|p| f64::from(p.luminance()))
        .sum::<f64>()
        / film.pixels().len() as f64
}

/// Checks one solution as the module describes and returns its final gather.
fn check_solution(world: &Arc<World>, solver: SolverKind, coarse: Coarse, label: &str) -> Film {
    let solved = solve(world, solver, coarse);
    let (system, solution) = (&solved.system, &solved.solution);
    let label = format!("{label}, {solver:?}");
    let values = solution.display_radiosity(system);
    let corners: usize = system
        .leaves
        .iter()
        .map(|&id| system.mesh.patch(id).corners().len())
        .sum();
    // The smooth corner values of each side: bounded work, and each corner within the range
    // of the flat values of its object (a corner value is a mean of leaf values and their
    // linear interpolations).
    for side in Side::BOTH {
        let per_leaf: Vec<Rgb64> = (0..system.leaves.len())
            .map(|k| values[RadiositySystem::element(k, side)])
            .collect();
        let smooth = vertex_radiosity(&system.mesh, &system.leaves, &per_leaf);
        // One lookup per edge and two per vertex found on an edge; a vertex lies inside the
        // edges of at most two leaves, so at most 5 lookups per corner.
        assert!(
            smooth.midpoint_lookups <= 5 * corners as u64,
            "{label}: {} midpoint lookups for {corners} corners",
            smooth.midpoint_lookups
        );
        let objects = world.scene.objects.len();
        let mut by_object = vec![Vec::new(); objects];
        for (k, &id) in system.leaves.iter().enumerate() {
            by_object[system.mesh.patch(id).object as usize].push(per_leaf[k].to_array());
        }
        let ranges: Vec<_> = by_object.into_iter().map(range).collect();
        for (k, &id) in system.leaves.iter().enumerate() {
            let patch = system.mesh.patch(id);
            for value in &smooth.corners[k][..patch.corners().len()] {
                assert!(
                    within(value.to_array(), ranges[patch.object as usize], 1e-9),
                    "{label}: corner {value:?} outside its object's range"
                );
            }
        }
    }
    // Displays (one ray per pixel): finite, and every pixel that shows a leaf (the
    // background is black) within the range of the leaves' radiance.
    let leaf_range = range(
        values
            .iter()
            .map(|v| v.map(|x| x / std::f64::consts::PI).to_array()),
    );
    let flat = display(system, solution, world, Shading::Flat);
    let smooth = display(system, solution, world, Shading::Smooth);
    for (name, film) in [("flat", &flat), ("smooth", &smooth)] {
        assert!(
            pixels(film).all(|p| p.iter().all(|x| x.is_finite())),
            "{label}: {name} display has non-finite pixels"
        );
        assert!(
            pixels(film)
                .filter(|p| p.iter().any(|&x| x > 0.0))
                .all(|p| within(p, leaf_range, 1e-5)),
            "{label}: {name} display outside the range of the leaves"
        );
    }
    // Both show the same surfaces: the pixels lit in one are lit in the other (a smooth value
    // is black only where every leaf around it is).
    let lit =
        |film: &Film| -> Vec<bool> { pixels(film).map(|p| p.iter().any(|&x| x > 0.0)).collect() };
    let (flat_lit, smooth_lit) = (lit(&flat), lit(&smooth));
    assert!(
        flat_lit.contains(&true),
        "{label}: the flat display is black"
    );
    let differing = flat_lit
        .iter()
        .zip(&smooth_lit)
        .filter(|(a, b)| a != b)
        .count();
    assert!(
        differing * 100 <= flat_lit.len(),
        "{label}: {differing} pixels lit in one display and black in the other"
    );
    // Export: every vertex colour within the leaves' range (so finite), written as glTF and
    // PLY.
    let lit = solution.lit_mesh(system, false);
    assert!(!lit.polygons.is_empty(), "{label}: nothing exported");
    let value_range = range(values.iter().map(|v| v.to_array()));
    assert!(
        lit.radiosity
            .iter()
            .all(|v| within(v.to_array(), value_range, 1e-9)),
        "{label}: exported vertex colour outside the leaves' range"
    );
    for extension in ["glb", "ply"] {
        let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
            "strahl-curved-{}-{}.{extension}",
            std::process::id(),
            label.replace([' ', ',', ':'], "-")
        ));
        export_lit_mesh(&lit, &world.scene.textures, &ToneMapping::default(), &path).unwrap();
        assert!(std::fs::metadata(&path).unwrap().len() > 0);
        std::fs::remove_file(&path).unwrap();
    }
    // Final gather: finite.
    let gathered = final_gather(&solved, world);
    assert!(
        pixels(&gathered).all(|p| p.iter().all(|x| x.is_finite() && *x >= 0.0)),
        "{label}: final gather has negative or non-finite pixels"
    );
    gathered
}

/// The path tracer's image of `world` at [`SIZE`]², 1024 paths per pixel.
fn path_traced(world: &Arc<World>) -> Film {
    let tracer = PathTracer::new(world, u32::MAX, 1);
    let settings = ProgressiveSettings {
        width: SIZE,
        height: SIZE,
        samples_per_pixel: 1024,
        seed: 1,
        time_limit: None,
    };
    render_progressive(world, &tracer, &settings, &NoProgress, &Cancel::new())
        .unwrap()
        .film
}

/// Every solver on a diffuse room file; each final gather's mean within `tolerance` of the
/// path tracer's.
fn room_against_the_path_tracer(file: &str, tolerance: f64) {
    let world = file_world(file);
    let reference = mean(&path_traced(&world));
    let coarse = Coarse {
        segments: 8,
        levels: 1,
        tolerance: 1e-3,
    };
    for solver in SOLVERS {
        let gathered = mean(&check_solution(&world, solver, coarse, file));
        let difference = gathered / reference - 1.0;
        eprintln!("{file}, {solver:?}: final gather mean {difference:+.4} vs the path tracer");
        assert!(
            difference.abs() < tolerance,
            "{file}, {solver:?}: final gather mean {gathered} vs path tracer {reference}"
        );
    }
}

#[test]
fn a_sphere_on_a_floor_by_every_solver() {
    room_against_the_path_tracer("sphere_on_floor.toml", 0.03);
}

#[test]
fn cylinders_and_cones_by_every_solver() {
    room_against_the_path_tracer("cylinders_and_cones.toml", 0.03);
}

#[test]
fn the_built_in_spheres_by_every_solver() {
    // Glossy spheres under point lights: radiosity counts their glossy part as absorbed, so
    // the final gather is checked only to be finite (inside `check_solution`). The flat
    // solvers get four segments (eight facets a sphere) to keep their n² cheap.
    for name in ["spheres:5", "spheres"] {
        let world = builtin_world(name);
        for solver in SOLVERS {
            let segments = match solver {
                SolverKind::Matrix | SolverKind::Progressive | SolverKind::HierarchicalShooting => {
                    4
                }
                SolverKind::Hierarchical => 8,
            };
            let coarse = Coarse {
                segments,
                levels: 0,
                tolerance: 1e-2,
            };
            check_solution(&world, solver, coarse, name);
        }
    }
}

/// The built-in spheres sphere by sphere: hierarchical radiosity at its defaults (16 segments)
/// against the light model (10⁷ photons on the scene with its glossy lobes dropped, what
/// radiosity solves; a sphere's standard error about 0.5 %). The meshed spheres are as large
/// as the spheres, so they catch, one with another, the light the spheres catch: the median
/// sphere within 0.6 % (measured +0.06 %; meshes with their corners on the spheres had every
/// sphere but one too dark, the median by 2.9 %), the RMS within 1.5 % (measured 1.2 %, 1.0 %
/// against 4·10⁷ photons: the facets' shape under lamps as close as 0.1 to a sphere stays,
/// falling with more segments, 0.7 % at 24).
#[test]
fn the_built_in_spheres_catch_the_light_the_light_model_gives_them() {
    let world = builtin_world("spheres");
    let diffuse = Arc::new(world.diffuse().unwrap().unwrap());
    let photons = Method::LightTrace(LightTraceSettings {
        photons: 10_000_000,
        ..LightTraceSettings::default()
    });
    let hierarchical = Method::Radiosity(RadiositySettings::new(SolverKind::Hierarchical));
    let power = |world: &Arc<World>, method: &Method| -> Vec<f64> {
        let outcome = run(world, method, &NoProgress, &Cancel::new()).unwrap();
        let report = Report::new("spheres", outcome.measurement.as_ref().unwrap());
        let sum = |p: Rgb64| p.r + p.g + p.b;
        report
            .objects
            .iter()
            .map(|o| sum(o.incident_power))
            .collect()
    };
    let reference = power(&diffuse, &photons);
    let mut deviations: Vec<f64> = power(&world, &hierarchical)
        .iter()
        .zip(&reference)
        .map(|(p, q)| p / q - 1.0)
        .collect();
    deviations.sort_by(f64::total_cmp);
    let median = deviations[deviations.len() / 2];
    let rms = (deviations.iter().map(|d| d * d).sum::<f64>() / deviations.len() as f64).sqrt();
    eprintln!("spheres: median {median:+.4}, RMS {rms:.4}");
    assert!(
        median.abs() < 0.006 && rms < 0.015,
        "median {median}, RMS {rms}"
    );
}
