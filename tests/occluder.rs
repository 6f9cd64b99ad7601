//! A lit wall seen past a black box (after the obstruction cases of CIE 171:2006): every
//! radiosity solver against the closed form.
//!
//! A 4 × 3 wall at `z = 0` emits radiance `L = 1` towards `+z`; a black box stands on the
//! floor in front of it; the far wall (`z = 4`) and the floor behind the box are black tiles,
//! each its own object. Nothing reflects, so a tile's irradiance is `π·L` times the mean over
//! the tile of the point-to-polygon form factor of the part of the wall the point sees: the
//! whole wall less the box's silhouette cast on the wall's plane from the point (the convex
//! hull of its eight corners' projections, clipped to the wall). The form factor of each
//! polygon is Lambert's contour integral, `F = (1/2π) Σ γᵢ n·(Rᵢ × Rᵢ₊₁)/|Rᵢ × Rᵢ₊₁|`; the
//! mean over a tile is a product Gauss–Legendre rule on 8 × 8 cells (16 × 16 cells change
//! no tile by 10⁻⁴).

use glam::{DVec2, DVec3};
use std::collections::HashMap;
use std::sync::Arc;
use strahl::accel::AccelKind;
use strahl::color::Rgb;
use strahl::progress::{Cancel, NoProgress};
use strahl::radiosity::VisibilityOptions;
use strahl::radiosity::solve::hierarchical::{
    HierarchicalSettings, solve_hierarchical, solve_hierarchical_shooting,
};
use strahl::radiosity::solve::{
    Iteration, MatrixSettings, RadiositySystem, ShootingSettings, Solution, SystemOptions,
    solve_matrix, solve_progressive,
};
use strahl::radiosity::{MeshOptions, MeshSize};
use strahl::report::Report;
use strahl::scene::{Material, Scene, Shape};
use strahl::world::World;

/// The emitting wall's width (x) and height (y).
const WALL: (f64, f64) = (4.0, 3.0);
/// The far wall's distance from the emitting wall.
const DEPTH: f64 = 4.0;
/// The black box's corners.
const BOX: ([f64; 3], [f64; 3]) = ([1.25, 0.0, 1.5], [2.75, 1.5, 2.5]);

/// A tile: its name, corner, edges (front towards `edge_u × edge_v`).
struct Tile {
    name: String,
    origin: DVec3,
    edge_u: DVec3,
    edge_v: DVec3,
}

/// The far wall in 1 × 1 tiles facing the emitting wall, and the floor behind the box in
/// 1 × 0.5 tiles facing up.
fn tiles() -> Vec<Tile> {
    let mut tiles = Vec::new();
    for i in 0..4 {
        for j in 0..3 {
            tiles.push(Tile {
                name: format!("far {i}{j}"),
                origin: DVec3::new(f64::from(i) + 1.0, f64::from(j), DEPTH),
                edge_u: DVec3::NEG_X,
                edge_v: DVec3::Y,
            });
        }
    }
    for i in 0..4 {
        for k in 0..3 {
            tiles.push(Tile {
                name: format!("floor {i}{k}"),
                origin: DVec3::new(f64::from(i), 0.0, BOX.1[2] + 0.5 * f64::from(k)),
                edge_u: DVec3::Z * 0.5,
                edge_v: DVec3::X,
            });
        }
    }
    tiles
}

fn scene() -> Arc<World> {
    let mut scene = Scene::empty("occluder");
    let black = scene.add_material(Material::diffuse("black", Rgb::splat(0.0)));
    let glow = scene.add_material(Material::emitter("glow", Rgb::splat(0.0), Rgb::splat(1.0)));
    let parallelogram = |origin: DVec3, edge_u: DVec3, edge_v: DVec3| Shape::Parallelogram {
        origin: origin.as_vec3(),
        edge_u: edge_u.as_vec3(),
        edge_v: edge_v.as_vec3(),
    };
    scene.add_object(
        "wall",
        parallelogram(DVec3::ZERO, DVec3::X * WALL.0, DVec3::Y * WALL.1),
        glow,
    );
    scene.add_object(
        "box",
        Shape::Box {
            min: DVec3::from(BOX.0).as_vec3(),
            max: DVec3::from(BOX.1).as_vec3(),
        },
        black,
    );
    for tile in tiles() {
        scene.add_object(
            &tile.name,
            parallelogram(tile.origin, tile.edge_u, tile.edge_v),
            black,
        );
    }
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

/// Lambert's contour integral: the form factor from a point with unit normal `n` to a
/// polygon wholly in front of it.
fn point_to_polygon(x: DVec3, n: DVec3, polygon: &[DVec3]) -> f64 {
    let sum: f64 = (0..polygon.len())
        .map(|i| {
            let (a, b) = (polygon[i] - x, polygon[(i + 1) % polygon.len()] - x);
            let c = a.cross(b);
            let length = c.length();
            if length == 0.0 {
                return 0.0;
            }
            length.atan2(a.dot(b)) * n.dot(c) / length
        })
        .sum();
    sum.abs() / (2.0 * std::f64::consts::PI)
}

/// The convex hull of `points`, counter-clockwise (Andrew's monotone chain).
fn convex_hull(mut points: Vec<DVec2>) -> Vec<DVec2> {
    points.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    let turn = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut hull: Vec<DVec2> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        for &p in &points {
            while hull.len() >= start + 2
                && turn(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
        if pass == 0 {
            points.reverse();
        }
    }
    hull
}

/// `polygon` clipped to the half-plane `coordinate(axis) · sign ≤ limit · sign`
/// (Sutherland–Hodgman).
fn clip(polygon: &[DVec2], axis: usize, limit: f64, sign: f64) -> Vec<DVec2> {
    let inside = |p: DVec2| p[axis] * sign <= limit * sign;
    let mut out = Vec::new();
    for i in 0..polygon.len() {
        let (p, q) = (polygon[i], polygon[(i + 1) % polygon.len()]);
        if inside(p) {
            out.push(p);
        }
        if inside(p) != inside(q) {
            let t = (limit - p[axis]) / (q[axis] - p[axis]);
            out.push(p + (q - p) * t);
        }
    }
    out
}

/// The form factor from point `x` (unit normal `n`, farther from the wall than the box) to
/// the part of the wall it sees past the box.
fn visible_form_factor(x: DVec3, n: DVec3) -> f64 {
    let wall = [
        DVec3::ZERO,
        DVec3::new(WALL.0, 0.0, 0.0),
        DVec3::new(WALL.0, WALL.1, 0.0),
        DVec3::new(0.0, WALL.1, 0.0),
    ];
    let (lo, hi) = (DVec3::from(BOX.0), DVec3::from(BOX.1));
    let silhouette: Vec<DVec2> = (0..8)
        .map(|k| {
            let c = DVec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            );
            // Where the line from x through the corner meets the wall's plane z = 0.
            let t = x.z / (x.z - c.z);
            (x + (c - x) * t).truncate()
        })
        .collect();
    let mut shadow = convex_hull(silhouette);
    for (axis, limit, sign) in [
        (0, 0.0, -1.0),
        (0, WALL.0, 1.0),
        (1, 0.0, -1.0),
        (1, WALL.1, 1.0),
    ] {
        shadow = clip(&shadow, axis, limit, sign);
    }
    let hidden = if shadow.len() >= 3 {
        let polygon: Vec<DVec3> = shadow.iter().map(|p| p.extend(0.0)).collect();
        point_to_polygon(x, n, &polygon)
    } else {
        0.0
    };
    point_to_polygon(x, n, &wall) - hidden
}

/// The exact irradiance of every tile, W·m⁻².
fn exact_irradiance() -> HashMap<String, f64> {
    const CELLS: usize = 8;
    // Gauss–Legendre nodes and weights on [0, 1], six points.
    const NODES: [(f64, f64); 6] = [
        (0.033_765_242_898_423_99, 0.085_662_246_189_585_17),
        (0.169_395_306_766_867_74, 0.180_380_786_524_069_3),
        (0.380_690_406_958_401_5, 0.233_956_967_286_345_5),
        (0.619_309_593_041_598_5, 0.233_956_967_286_345_5),
        (0.830_604_693_233_132_3, 0.180_380_786_524_069_3),
        (0.966_234_757_101_576, 0.085_662_246_189_585_17),
    ];
    tiles()
        .into_iter()
        .map(|tile| {
            let n = tile.edge_u.cross(tile.edge_v).normalize();
            let mut mean = 0.0;
            for a in 0..CELLS {
                for b in 0..CELLS {
                    for &(s, ws) in &NODES {
                        for &(t, wt) in &NODES {
                            let u = (a as f64 + s) / CELLS as f64;
                            let v = (b as f64 + t) / CELLS as f64;
                            let x = tile.origin + tile.edge_u * u + tile.edge_v * v;
                            mean += ws * wt * visible_form_factor(x, n);
                        }
                    }
                }
            }
            let mean = mean / (CELLS * CELLS) as f64;
            (tile.name, std::f64::consts::PI * mean)
        })
        .collect()
}

/// The largest relative error of any tile's irradiance in `solution`, with its tile.
fn worst_tile(system: &RadiositySystem, solution: &Solution) -> (f64, String) {
    let exact = exact_irradiance();
    let report = Report::new("occluder", &solution.measurement(system));
    report
        .objects
        .iter()
        .filter_map(|o| {
            let expected = exact.get(&o.name)?;
            let computed = o.irradiance?.to_array()[1];
            Some(((computed - expected).abs() / expected, o.name.clone()))
        })
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .unwrap()
}

fn options(size: MeshSize, seed: u64) -> SystemOptions {
    SystemOptions {
        mesh: MeshOptions {
            size,
            ..MeshOptions::default()
        },
        visibility: VisibilityOptions {
            seed,
            ..VisibilityOptions::default()
        },
        ..SystemOptions::default()
    }
}

/// Whether the segment from `x` to `y` passes through the box (slab test).
fn crosses_box(x: DVec3, y: DVec3) -> bool {
    let (lo, hi) = (DVec3::from(BOX.0), DVec3::from(BOX.1));
    let d = y - x;
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for axis in 0..3 {
        let (a, b) = (
            (lo[axis] - x[axis]) / d[axis],
            (hi[axis] - x[axis]) / d[axis],
        );
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    t0 < t1
}

#[test]
fn the_reference_agrees_with_a_brute_force_sum_over_the_wall() {
    // The kernel cos θ·cos θ'/(π r²) summed over the midpoints of a 1200 × 900 grid on the
    // wall, leaving out those the box hides: the silhouette, the hull and the clipping of
    // the reference checked by an independent method (its error is the grid's, ≈ 10⁻⁴). The
    // points: behind the box, beside and above it, and on the floor in its full shadow, at
    // its edge and away from it.
    let (nx, ny) = (1200, 900);
    let cell = (WALL.0 / f64::from(nx), WALL.1 / f64::from(ny));
    for (x, n) in [
        (DVec3::new(2.0, 0.75, DEPTH), DVec3::NEG_Z),
        (DVec3::new(0.3, 2.6, DEPTH), DVec3::NEG_Z),
        (DVec3::new(3.5, 1.2, DEPTH), DVec3::NEG_Z),
        (DVec3::new(1.7, 0.0, 2.8), DVec3::Y),
        (DVec3::new(1.1, 0.0, 2.8), DVec3::Y),
        (DVec3::new(3.6, 0.0, 3.3), DVec3::Y),
    ] {
        let mut sum = 0.0;
        for i in 0..nx {
            for j in 0..ny {
                let y = DVec3::new(
                    (f64::from(i) + 0.5) * cell.0,
                    (f64::from(j) + 0.5) * cell.1,
                    0.0,
                );
                if crosses_box(x, y) {
                    continue;
                }
                let d = y - x;
                let r2 = d.length_squared();
                sum += n.dot(d) * d.z.abs() / (r2 * r2);
            }
        }
        let brute = sum * cell.0 * cell.1 / std::f64::consts::PI;
        let exact = visible_form_factor(x, n);
        assert!(
            (brute - exact).abs() <= 1e-3 * exact + 1e-9,
            "{x}: {brute} vs {exact}"
        );
    }
}

#[test]
fn flat_solvers_converge_with_the_mesh_at_adaptive_visibility() {
    // Adaptive visibility cast 2 × 2 rays where 4 × 4 were needed: +1.25 % at 0.25 m
    // patches (the issue saw 4.1 %). Now: 2.6 % at 0.5 m, 0.20 % at 0.25 m.
    let world = scene();
    let coarse = RadiositySystem::new(&world, options(MeshSize::MaxEdge(0.5), 0)).unwrap();
    let shooting = ShootingSettings {
        tolerance: 1e-9,
        max_shots: 1_000_000,
        overshoot: false,
    };
    let solution = solve_progressive(&coarse, &shooting, &NoProgress, &Cancel::new()).unwrap();
    let (coarse_error, tile) = worst_tile(&coarse, &solution);
    assert!(
        coarse_error < 0.035,
        "progressive 0.5: {tile} {coarse_error}"
    );
    let fine = RadiositySystem::new(&world, options(MeshSize::MaxEdge(0.25), 0)).unwrap();
    let matrix = MatrixSettings {
        iteration: Iteration::GaussSeidel,
        tolerance: 1e-9,
        max_iterations: 100,
    };
    let solution = solve_matrix(&fine, &matrix, &NoProgress, &Cancel::new()).unwrap();
    let (fine_error, tile) = worst_tile(&fine, &solution);
    assert!(fine_error < 0.006, "matrix 0.25: {tile} {fine_error}");
}

#[test]
fn hierarchical_solvers_lose_no_pair_behind_the_box() {
    // A quarter of the wall seen from a far tile mostly past the box: every ray from its
    // Gauss points was blocked and so were the edge probes, and the pair was dropped
    // (one tile 2.1 % dark at --error 1e-6, seed 1). Blocked pairs are now kept and looked
    // at again while what they could bring matters: 0.57–0.94 % (seeds 0, 1).
    let world = scene();
    let settings = HierarchicalSettings {
        error: 1e-6,
        tolerance: 1e-9,
        ..HierarchicalSettings::default()
    };
    for seed in [0, 1] {
        let (system, solution) = solve_hierarchical(
            &world,
            options(MeshSize::Levels(0), seed),
            &settings,
            &NoProgress,
            &Cancel::new(),
        )
        .unwrap();
        let (error, tile) = worst_tile(&system, &solution);
        assert!(error < 0.0125, "hierarchical, seed {seed}: {tile} {error}");
    }
    let shooting = ShootingSettings {
        tolerance: 1e-7,
        max_shots: 100_000,
        overshoot: false,
    };
    let (system, solution) = solve_hierarchical_shooting(
        &world,
        options(MeshSize::Levels(0), 0),
        &settings,
        &shooting,
        &NoProgress,
        &Cancel::new(),
    )
    .unwrap();
    let (error, tile) = worst_tile(&system, &solution);
    assert!(error < 0.0125, "hierarchical shooting: {tile} {error}");
}
