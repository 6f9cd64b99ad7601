//! Links kept between hierarchical solves of a scene whose objects move
//! (`method::run_keeping`, `radiosity/solve/hierarchical/kept.rs`): the solve after a move
//! takes most of its patch links from the solve before, and reports what a solve of the
//! moved scene from scratch reports, bit for bit (the same solve with no links kept: its
//! rays are seeded by what the patches are, as they must be for links to be kept; a solve by
//! `method::run` seeds them by the patches' indices and is as accurate, not the same).

use glam::Vec3;
use std::sync::Arc;
use strahl::method::{
    AccelKind, Cancel, KeptLinks, Method, NoProgress, RadiositySettings, SolverKind, World,
    run_keeping,
};
use strahl::report::Report;
use strahl::scene::{Scene, open};

/// The report of `scene` solved by hierarchical radiosity at the defaults with the links
/// `kept`, its statistics (times, rays, counts) left out.
fn solved(scene: &Scene, kept: &mut KeptLinks) -> serde_json::Value {
    let world = Arc::new(World::new(scene.clone(), AccelKind::Bvh).unwrap());
    let method = Method::Radiosity(RadiositySettings::new(SolverKind::Hierarchical));
    let outcome = run_keeping(&world, &method, &NoProgress, &Cancel::new(), kept).unwrap();
    let report = Report::new(&scene.name, outcome.measurement.as_ref().unwrap());
    let mut value = serde_json::to_value(&report).unwrap();
    value.as_object_mut().unwrap().remove("stats");
    value
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
