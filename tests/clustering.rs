//! Clustering in hierarchical radiosity: groups of root patches exchange light as a whole
//! while they are small against their distance. Checked against the same solve linking every
//! pair of root patches (the independent method: exact polygon form factors and visibility
//! rays per pair), against the light model on aggregate powers, and for the link count it is
//! for: growing far slower than the square of the number of surfaces.

use std::collections::HashMap;
use std::sync::Arc;
use strahl::accel::AccelKind;
use strahl::light_model::{LightTraceSettings, trace_light};
use strahl::progress::{Cancel, NoProgress};
use strahl::radiosity::solve::SystemOptions;
use strahl::radiosity::solve::hierarchical::{HierarchicalSettings, solve_hierarchical};
use strahl::radiosity::{MeshOptions, MeshSize};
use strahl::report::Report;
use strahl::scene::builtin;
use strahl::world::World;

fn world(name: &str) -> Arc<World> {
    Arc::new(World::new(builtin::load(name).unwrap().unwrap(), AccelKind::Bvh).unwrap())
}

/// Per object name, the luminance of the absorbed power, W; and the links of the solution.
fn solve(world: &Arc<World>, clustering: bool) -> (HashMap<String, f64>, usize) {
    solve_at(world, clustering, HierarchicalSettings::default().error)
}

/// [`solve`] at the error `error`.
fn solve_at(world: &Arc<World>, clustering: bool, error: f64) -> (HashMap<String, f64>, usize) {
    let options = SystemOptions {
        mesh: MeshOptions {
            size: MeshSize::Levels(0),
            ..MeshOptions::default()
        },
        ..SystemOptions::default()
    };
    let settings = HierarchicalSettings {
        clustering,
        error,
        ..HierarchicalSettings::default()
    };
    let (system, solution) =
        solve_hierarchical(world, options, &settings, &NoProgress, &Cancel::new()).unwrap();
    let report = Report::new(&world.scene.name, &solution.measurement(&system));
    (absorbed(&report), solution.links)
}

fn absorbed(report: &Report) -> HashMap<String, f64> {
    report
        .objects
        .iter()
        .map(|o| (o.name.clone(), o.absorbed_power.luminance()))
        .collect()
}

/// The largest relative difference per object, and that of the sums.
fn differences(a: &HashMap<String, f64>, b: &HashMap<String, f64>) -> (f64, f64) {
    let worst = b
        .iter()
        .map(|(name, &v)| (a[name] / v - 1.0).abs())
        .fold(0.0, f64::max);
    let total = a.values().sum::<f64>() / b.values().sum::<f64>() - 1.0;
    (worst, total.abs())
}

#[test]
fn clustering_agrees_with_linking_every_pair_of_root_patches() {
    // 27 cubes (162 faces) in a closed room: light bounces many times between them.
    // Measured: worst cube 0.86 %, sum 0.023 %.
    let blocks = world("blocks:27");
    let (clustered, _) = solve(&blocks, true);
    let (pairwise, _) = solve(&blocks, false);
    let (worst, total) = differences(&clustered, &pairwise);
    assert!(worst < 0.015 && total < 0.001, "{worst} {total}");
    // 300 leaves under sky and sun, with 27 % of the links (22,605 instead of 84,468).
    // Measured: worst leaf 1.07 %, sum 0.095 %.
    let canopy = world("canopy:300");
    let (clustered, clustered_links) = solve(&canopy, true);
    let (pairwise, pairwise_links) = solve(&canopy, false);
    let (worst, total) = differences(&clustered, &pairwise);
    assert!(worst < 0.03 && total < 0.003, "{worst} {total}");
    assert!(
        3 * clustered_links < pairwise_links,
        "{clustered_links} {pairwise_links}"
    );
}

#[test]
fn clustered_light_on_many_cubes_agrees_with_the_light_model() {
    // Per cube the light model's own noise at a test's budget is about 1 %, so the cubes are
    // compared together, and with the room. Against 10⁷ photons, the cubes' sum is −0.3 %
    // at the default error, +0.16 % at 3·10⁻⁵ (+0.22 % without clustering) and +0.38 % at
    // 10⁻⁵; the room +0.3 to +0.6 %.
    let blocks = world("blocks:27");
    let (clustered, _) = solve_at(&blocks, true, 3e-5);
    let settings = LightTraceSettings {
        photons: 4_000_000,
        seed: 3,
        max_bounces: 1000,
    };
    let out = trace_light(&blocks, &settings, &NoProgress, &Cancel::new()).unwrap();
    let reference = absorbed(&Report::new("blocks", &out.measurement()));
    let cubes = |m: &HashMap<String, f64>| -> f64 {
        m.iter()
            .filter(|(name, _)| name.starts_with("block-"))
            .map(|(_, v)| v)
            .sum()
    };
    let cube_error = cubes(&clustered) / cubes(&reference) - 1.0;
    let room_error = clustered["room"] / reference["room"] - 1.0;
    assert!(cube_error.abs() < 0.01, "cubes: {cube_error}");
    assert!(room_error.abs() < 0.01, "room: {room_error}");
}

#[test]
fn links_grow_far_slower_than_the_square_of_the_surfaces() {
    // Four times the leaves: linking every pair would need sixteen times the links.
    // Measured: 19,574 and 98,634 links (×5.0).
    let (_, few) = solve(&world("canopy:250"), true);
    let (_, many) = solve(&world("canopy:1000"), true);
    assert!(many < 7 * few, "{few} → {many}");
}
