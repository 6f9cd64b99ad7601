//! Links kept between hierarchical solves of a scene whose objects move
//! (`method::run_keeping`, `radiosity/solve/hierarchical/kept.rs`): the solve after a move
//! takes most of its patch links from the solve before, and reports what a solve of the
//! moved scene from scratch reports, bit for bit (the same solve with no links kept: its
//! rays are seeded by what the patches are, as they must be for links to be kept; a solve by
//! `method::run` seeds them by the patches' indices and is as accurate, not the same).

use glam::Vec3;
use std::sync::Arc;
use strahl::method::{
    AccelKind, Cancel, KeptLinks, MeshSize, Method, NoProgress, RadiositySettings, SolverKind,
    World, run_keeping,
};
use strahl::report::Report;
use strahl::scene::{Scene, open};

/// The report of `scene` solved by hierarchical radiosity at the defaults with the links
/// `kept`, its statistics (times, rays, counts) left out.
fn solved(scene: &Scene, kept: &mut KeptLinks) -> serde_json::Value {
    let settings = RadiositySettings::new(SolverKind::Hierarchical);
    solved_by(scene, settings, kept).0
}

/// The report of `scene` solved by radiosity with `settings` and the links `kept`, its
/// statistics left out, and the solver's iterations.
fn solved_by(
    scene: &Scene,
    settings: RadiositySettings,
    kept: &mut KeptLinks,
) -> (serde_json::Value, usize) {
    let world = Arc::new(World::new(scene.clone(), AccelKind::Bvh).unwrap());
    let method = Method::Radiosity(settings);
    let outcome = run_keeping(&world, &method, &NoProgress, &Cancel::new(), kept).unwrap();
    let iterations = outcome.radiosity.as_ref().unwrap().solution.iterations();
    let report = Report::new(&scene.name, outcome.measurement.as_ref().unwrap());
    let mut value = serde_json::to_value(&report).unwrap();
    value.as_object_mut().unwrap().remove("stats");
    (value, iterations)
}

/// Solves `scene`, moves `name` by `by`, solves again keeping links; checks its report
/// against the moved scene's solved with no links kept, and that more than `least` of the
/// second solve's patch links were taken from the first.
fn moved_and_solved_again(spec: &str, name: &str, by: Vec3, least: f64) {
    let mut scene = open(spec, &Default::default()).unwrap();
    let mut kept = KeptLinks::new();
    let before = solved(&scene, &mut kept);
    assert_eq!(kept.reused(), 0);
    scene.move_named(name, by).unwrap();
    let again = solved(&scene, &mut kept);
    let share = kept.reused() as f64 / (kept.reused() + kept.computed()) as f64;
    let from_scratch = solved(&scene, &mut KeptLinks::new());
    if again != from_scratch {
        for (a, b) in again["objects"]
            .as_array()
            .unwrap()
            .iter()
            .zip(from_scratch["objects"].as_array().unwrap())
        {
            if a != b {
                eprintln!(
                    "{} {} vs {}",
                    a["name"], a["incident_power"], b["incident_power"]
                );
            }
        }
    }
    assert!(again == from_scratch, "kept links changed the solution");
    assert!(again != before, "the move changed nothing");
    eprintln!(
        "{spec}, {name} moved: {:.1} % of the links kept",
        100.0 * share
    );
    assert!(share > least, "{share}");
}

#[test]
fn a_moved_light_is_solved_with_the_links_it_does_not_reach_kept_as_from_scratch() {
    moved_and_solved_again("cornell", "light", Vec3::new(0.0, 0.0, 0.05), 0.5);
}

#[test]
fn a_moved_block_is_solved_with_the_links_it_does_not_reach_kept_as_from_scratch() {
    moved_and_solved_again("cornell", "short_block", Vec3::new(0.03, 0.0, 0.0), 0.2);
}

#[test]
fn a_moved_sphere_is_solved_with_the_links_it_does_not_reach_kept_as_from_scratch() {
    // A curved shape is meshed anew where it moved: its facets are new patches (keyed by
    // their corners), the others' links to and from it computed again.
    moved_and_solved_again("spheres:6", "sphere-2", Vec3::new(0.1, 0.05, -0.1), 0.2);
}

#[test]
fn a_scene_changed_otherwise_than_by_moves_keeps_no_links() {
    let mut scene = open("cornell", &Default::default()).unwrap();
    let mut kept = KeptLinks::new();
    solved(&scene, &mut kept);
    // The same scene again: every link is taken.
    solved(&scene, &mut kept);
    assert_eq!(kept.computed(), 0);
    assert!(kept.reused() > 0);
    // A wall made darker: a link does not depend on it, but only moves are trusted.
    scene.materials[0].diffuse = strahl::color::Rgb::splat(0.1);
    solved(&scene, &mut kept);
    assert_eq!(kept.reused(), 0);
}

/// The matrix solver on a mesh of two levels (a quarter of the default's leaves: 1,000
/// elements on the Cornell box), iterated until a sweep changes the radiosity by at most `tolerance` of the
/// source power.
fn matrix(tolerance: f64) -> RadiositySettings {
    let mut settings = RadiositySettings::new(SolverKind::Matrix);
    settings.system.mesh.size = MeshSize::Levels(2);
    settings.matrix.tolerance = tolerance;
    settings
}

/// Every reported surface's (object's or face's) incident power per channel, W, in the
/// report's order.
fn incident_powers(report: &serde_json::Value) -> Vec<f64> {
    let objects = report["objects"].as_array().unwrap();
    let channels = objects
        .iter()
        .flat_map(|o| o["incident_power"].as_array().unwrap());
    channels.map(|c| c.as_f64().unwrap()).collect()
}

/// The largest difference between two reports' surfaces, relative to the second's.
fn largest_difference(a: &serde_json::Value, b: &serde_json::Value) -> f64 {
    let (a, b) = (incident_powers(a), incident_powers(b));
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs() / y.abs().max(1e-12))
        .fold(0.0, f64::max)
}

#[test]
fn a_moved_light_is_solved_by_the_matrix_from_the_couplings_and_solution_before() {
    let mut scene = open("cornell", &Default::default()).unwrap();
    // Every face of the blocks reported on its own: the dim ones too.
    for object in &mut scene.objects {
        object.per_face = true;
    }
    let default = RadiositySettings::new(SolverKind::Matrix).matrix.tolerance;
    let (exact, default) = (matrix(1e-12), matrix(default));
    let mut kept = KeptLinks::new();
    solved_by(&scene, exact, &mut kept);
    let mut kept_default = KeptLinks::new();
    let (before, _) = solved_by(&scene, default, &mut kept_default);
    scene
        .move_named("light", Vec3::new(0.0, 0.0, 0.05))
        .unwrap();

    // Iterated to the end, the couplings kept give the moved box's own matrix: the same
    // fixed point as the matrix computed in full, to the iteration's last digits.
    let (again, _) = solved_by(&scene, exact, &mut kept);
    let share = kept.reused() as f64 / (kept.reused() + kept.computed()) as f64;
    let (from_scratch, _) = solved_by(&scene, exact, &mut KeptLinks::new());
    let exact_difference = largest_difference(&again, &from_scratch);
    eprintln!(
        "matrix, light moved: {:.1} % of the couplings kept, {exact_difference:.1e} apart",
        100.0 * share
    );
    assert!(share > 0.5, "{share}");
    assert!(exact_difference < 1e-9, "{exact_difference}");

    // At the default tolerance the solve starts from the solution before: fewer sweeps, the
    // same solution within the tolerance.
    let (warm, warm_sweeps) = solved_by(&scene, default, &mut kept_default);
    let (cold, cold_sweeps) = solved_by(&scene, default, &mut KeptLinks::new());
    let difference = largest_difference(&warm, &cold);
    eprintln!(
        "sweeps {warm_sweeps} warm, {cold_sweeps} cold; {difference:.1e} apart, {} surfaces",
        incident_powers(&cold).len() / 3
    );
    assert!(warm_sweeps < cold_sweeps);
    assert!(difference < 1e-3, "{difference}");
    assert!(
        largest_difference(&before, &cold) > 1e-2,
        "the move changed nothing"
    );
}

#[test]
fn a_matrix_solve_stopped_by_a_move_leaves_the_couplings_kept_for_the_next() {
    let mut scene = open("cornell", &Default::default()).unwrap();
    let settings = matrix(RadiositySettings::new(SolverKind::Matrix).matrix.tolerance);
    let mut kept = KeptLinks::new();
    solved_by(&scene, settings, &mut kept);
    // Moved, and the solve stopped before its matrix was assembled (as the viewer stops it
    // when the next move comes): nothing assembled, what was kept stays.
    scene
        .move_named("light", Vec3::new(0.0, 0.0, 0.05))
        .unwrap();
    let world = Arc::new(World::new(scene.clone(), AccelKind::Bvh).unwrap());
    let stopped = Cancel::new();
    stopped.request();
    let method = Method::Radiosity(settings);
    let outcome = run_keeping(&world, &method, &NoProgress, &stopped, &mut kept).unwrap();
    assert!(!outcome.complete);
    assert_eq!(kept.reused(), 0);
    // Moved again: the solve takes the couplings of the solve before the stopped one where
    // neither move reached them.
    scene
        .move_named("light", Vec3::new(0.05, 0.0, 0.0))
        .unwrap();
    let (again, _) = solved_by(&scene, settings, &mut kept);
    let share = kept.reused() as f64 / (kept.reused() + kept.computed()) as f64;
    assert!(share > 0.5, "{share}");
    let (from_scratch, _) = solved_by(&scene, settings, &mut KeptLinks::new());
    let difference = largest_difference(&again, &from_scratch);
    assert!(difference < 1e-3, "{difference}");
}

#[test]
fn links_kept_over_several_moves_give_each_solve_as_from_scratch() {
    // The links kept carry over from move to move: those a move reached are computed again,
    // the others taken from whichever solve made them.
    let mut scene = open("cornell", &Default::default()).unwrap();
    let mut kept = KeptLinks::new();
    solved(&scene, &mut kept);
    for by in [
        Vec3::new(0.0, 0.0, 0.05),
        Vec3::new(0.04, 0.0, 0.0),
        Vec3::new(-0.04, 0.0, -0.05),
    ] {
        scene.move_named("light", by).unwrap();
        kept.settle();
        let again = solved(&scene, &mut kept);
        let share = kept.reused() as f64 / (kept.reused() + kept.computed()) as f64;
        assert!(share > 0.5, "{share}");
        assert!(
            again == solved(&scene, &mut KeptLinks::new()),
            "moved by {by}"
        );
    }
}
