//! Radiosity solvers end to end: the furnace, matrix against progressive on the Cornell box,
//! Jacobi against Gauss-Seidel, light links, the report, display (and its illuminance and
//! luminance per pixel) and export.

use glam::Vec3;
use std::sync::Arc;
use strahl::accel::AccelKind;
use strahl::color::{Rgb, Rgb64};
use strahl::image::{ToneMap, ToneMapping};
use strahl::light_model::{LightTraceSettings, trace_light};
use strahl::measure::{Photometric, RoundSolution};
use strahl::progress::{Cancel, NoProgress, ProgressListener};
use strahl::radiosity::solid_angle;
use strahl::radiosity::solve::hierarchical::{
    HierarchicalSettings, Oracle, solve_hierarchical, solve_hierarchical_shooting,
};
use strahl::radiosity::solve::{
    DisplaySettings, Iteration, LinkDisplay, MatrixSettings, RadiositySystem, Shading,
    ShootingSettings, Solution, SystemOptions, render_solution, solve_matrix, solve_progressive,
    value_image,
};
use strahl::radiosity::{MeshOptions, MeshSize, Side};
use strahl::report::{Report, export_lit_mesh};
use strahl::scene::{Camera, Light, LightKind, Material, Scene, Shape, builtin};
use strahl::world::World;

const RHO: f32 = 0.5;
const L: f32 = 2.0;

/// The six faces of the unit cube as parallelograms facing inwards (face 1 is the ceiling).
fn unit_cube_faces() -> [Shape; 6] {
    [
        (Vec3::ZERO, Vec3::Z, Vec3::X),
        (Vec3::Y, Vec3::X, Vec3::Z),
        (Vec3::ZERO, Vec3::Y, Vec3::Z),
        (Vec3::X, Vec3::Z, Vec3::Y),
        (Vec3::ZERO, Vec3::X, Vec3::Y),
        (Vec3::Z, Vec3::Y, Vec3::X),
    ]
    .map(|(origin, edge_u, edge_v)| Shape::Parallelogram {
        origin,
        edge_u,
        edge_v,
    })
}

/// The unit cube as six parallelograms facing inwards, all emitting `L` with reflectance ρ.
fn furnace() -> Arc<World> {
    let mut scene = Scene::empty("furnace");
    let m = scene.add_material(Material::emitter("glow", Rgb::splat(RHO), Rgb::splat(L)));
    for (k, shape) in unit_cube_faces().into_iter().enumerate() {
        scene.add_object(&format!("face{k}"), shape, m);
    }
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

fn options(levels: u32) -> SystemOptions {
    SystemOptions {
        mesh: MeshOptions {
            segments: 16,
            size: MeshSize::Levels(levels),
            ..MeshOptions::default()
        },
        ..SystemOptions::default()
    }
}

fn matrix(system: &RadiositySystem, iteration: Iteration, tolerance: f64) -> Solution {
    let settings = MatrixSettings {
        iteration,
        tolerance,
        max_iterations: 10_000,
    };
    solve_matrix(system, &settings, &NoProgress, &Cancel::new()).unwrap()
}

fn progressive(system: &RadiositySystem, overshoot: bool, tolerance: f64) -> Solution {
    let settings = ShootingSettings {
        tolerance,
        max_shots: 1_000_000,
        overshoot,
    };
    solve_progressive(system, &settings, &NoProgress, &Cancel::new()).unwrap()
}

/// Inside the furnace (the faces' front sides) every element has `B = E/(1 − ρ)` to within
/// `tolerance`; outside (their back sides, which see nothing and do not emit) `B = 0`.
fn assert_furnace(system: &RadiositySystem, solution: &Solution, tolerance: f64) {
    let expected = std::f64::consts::PI * L as f64 / (1.0 - RHO as f64);
    assert!(solution.converged, "{}", solution.solver);
    for (element, b) in system.elements.iter().zip(&solution.radiosity) {
        for c in b.to_array() {
            match element.side {
                Side::Front => assert!(
                    ((c - expected) / expected).abs() < tolerance,
                    "{}: {c} vs {expected}",
                    solution.solver
                ),
                Side::Back => assert_eq!(c, 0.0, "{}: outside", solution.solver),
            }
        }
    }
}

#[test]
fn furnace_gives_e_over_one_minus_rho_for_every_solver() {
    let world = furnace();
    let system = RadiositySystem::new(&world, options(2)).unwrap();
    assert_eq!((system.leaves.len(), system.len()), (96, 192));
    assert_furnace(&system, &matrix(&system, Iteration::Jacobi, 1e-7), 1e-4);
    assert_furnace(
        &system,
        &matrix(&system, Iteration::GaussSeidel, 1e-7),
        1e-4,
    );
    assert_furnace(&system, &progressive(&system, false, 1e-7), 1e-4);
    assert_furnace(&system, &progressive(&system, true, 1e-7), 1e-4);
}

#[test]
fn furnace_report_balances_emission_and_absorption() {
    let world = furnace();
    let system = RadiositySystem::new(&world, options(1)).unwrap();
    let solution = matrix(&system, Iteration::GaussSeidel, 1e-9);
    let report = Report::new("furnace", &solution.measurement(&system));
    assert_eq!(report.objects.len(), 6);
    // Each face: area 1, H = B (closed box), incident = B, absorbed = (1 − ρ)·B = E.
    let b = std::f64::consts::PI * L as f64 / (1.0 - RHO as f64);
    for o in &report.objects {
        assert!((o.area.unwrap() - 1.0).abs() < 1e-6);
        assert!((o.incident_power[1] - b).abs() / b < 1e-4, "{o:?}");
        assert!((o.radiosity.unwrap()[0] - b).abs() / b < 1e-4);
    }
    let t = &report.totals;
    let (emitted, absorbed) = (t.emitted_power.luminance(), t.absorbed_power.luminance());
    assert!((emitted - 6.0 * std::f64::consts::PI * L as f64).abs() < 1e-6);
    assert!(
        (absorbed - emitted).abs() / emitted < 1e-4,
        "{absorbed} vs {emitted}"
    );
    assert_eq!(report.stats.extra["patches"], 24);
}

fn cornell() -> Arc<World> {
    let scene = builtin::load("cornell").unwrap().unwrap();
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

#[test]
fn cornell_matrix_and_progressive_agree_per_object() {
    let world = cornell();
    let system = RadiositySystem::new(&world, options(2)).unwrap();
    let m = matrix(&system, Iteration::GaussSeidel, 1e-6);
    let p = progressive(&system, false, 1e-6);
    let rm = Report::new("cornell", &m.measurement(&system));
    let rp = Report::new("cornell", &p.measurement(&system));
    for (a, b) in rm.objects.iter().zip(&rp.objects) {
        let (x, y) = (a.incident_power.luminance(), b.incident_power.luminance());
        assert!(x > 0.0, "{} receives light", a.name);
        assert!((x - y).abs() / x < 0.005, "{}: {x} vs {y}", a.name);
    }
    // Overshooting converges to the same solution.
    let o = progressive(&system, true, 1e-6);
    let ro = Report::new("cornell", &o.measurement(&system));
    for (a, b) in rm.objects.iter().zip(&ro.objects) {
        let (x, y) = (a.incident_power.luminance(), b.incident_power.luminance());
        assert!((x - y).abs() / x < 0.005, "{}: {x} vs {y}", a.name);
    }
}

#[test]
fn the_closed_blocks_stay_dark_inside() {
    // The inside of each block (the backs of its faces) sees only the block and the floor
    // under it. The back of a block's top face once took, past the block's own walls, the
    // light of the part of a wall patch above the top: the visibility of a pair whose patch
    // straddles the other's plane was that of the front sides (the matrix solver at its
    // default mesh: 5.6 % of the tall block's dimmest face's light inside the block).
    let world = cornell();
    let system = RadiositySystem::new(&world, options(2)).unwrap();
    let m = matrix(&system, Iteration::GaussSeidel, 1e-6);
    let names: Vec<_> = world.scene.objects.iter().map(|o| o.name.clone()).collect();
    let (mut inside, mut outside) = (0.0, 0.0);
    for k in 0..system.len() {
        let patch = system.patch(k);
        if names[patch.object as usize]
            .as_deref()
            .unwrap_or("")
            .ends_with("_block")
        {
            let power = m.irradiance[k].luminance() * system.area[k];
            match system.elements[k].side {
                Side::Front => outside += power,
                Side::Back => inside += power,
            }
        }
    }
    assert!(
        outside > 0.0 && inside < 1e-6 * outside,
        "{inside} inside, {outside} outside"
    );
}

#[test]
fn overshooting_converges_in_fewer_shots_on_every_mesh() {
    // On the coarsest mesh overshooting once stalled: a patch that had been shot ahead of
    // its light kept shooting its negative amount plus the ambient guess again, a zero shot,
    // for ever. Measured: 216 vs 313 shots at levels 0, 697 vs 1047 at levels 1.
    let world = cornell();
    for levels in [0, 1] {
        let system = RadiositySystem::new(&world, options(levels)).unwrap();
        let plain = progressive(&system, false, 1e-4);
        let ahead = progressive(&system, true, 1e-4);
        assert!(plain.converged && ahead.converged, "levels {levels}");
        assert!(
            ahead.iterations() < plain.iterations(),
            "levels {levels}: {} vs {}",
            ahead.iterations(),
            plain.iterations()
        );
    }
}

#[test]
fn gauss_seidel_needs_fewer_sweeps_than_jacobi() {
    let world = cornell();
    let system = RadiositySystem::new(&world, options(1)).unwrap();
    let jacobi = matrix(&system, Iteration::Jacobi, 1e-6);
    let gs = matrix(&system, Iteration::GaussSeidel, 1e-6);
    assert!(jacobi.converged && gs.converged);
    assert!(
        gs.iterations() < jacobi.iterations(),
        "{} vs {}",
        gs.iterations(),
        jacobi.iterations()
    );
    // Residuals fall monotonically for Jacobi on a non-negative system.
    assert!(
        jacobi
            .convergence
            .windows(2)
            .all(|w| w[1] <= w[0] * 1.000_001)
    );
}

/// A grey unit floor (y = 0, facing up) lit by `light` alone.
fn floor_under(light: LightKind) -> Arc<World> {
    let mut scene = Scene::empty("lamp");
    let m = scene.add_material(Material::diffuse("grey", Rgb::splat(0.5)));
    scene.add_object(
        "floor",
        Shape::Parallelogram {
            origin: Vec3::ZERO,
            edge_u: Vec3::Z,
            edge_v: Vec3::X,
        },
        m,
    );
    scene.lights.push(Light {
        name: None,
        kind: light,
    });
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

#[test]
fn point_light_link_gives_the_exact_mean_irradiance_and_the_lights_full_power() {
    let at = Vec3::new(2.5, 2.0, 0.5);
    let world = floor_under(LightKind::Point {
        position: at,
        intensity: Rgb::splat(8.0),
    });
    let mut opts = options(0);
    opts.link_samples = 1;
    let system = RadiositySystem::new(&world, opts).unwrap();
    // The mean irradiance over the unit floor: I·Ω/A, Ω the solid angle it subtends at the
    // light (exact however few receiver points are used).
    let floor = system.mesh.patch(system.leaves[0]);
    let h = 8.0 * solid_angle(at.as_dvec3(), floor.corners()) / floor.area;
    for solution in [
        matrix(&system, Iteration::Jacobi, 1e-9),
        progressive(&system, false, 1e-9),
    ] {
        assert!((solution.radiosity[0][0] - 0.5 * h).abs() < 1e-12);
        // The back of the floor sees nothing.
        assert_eq!(solution.radiosity[1], Rgb64::BLACK);
        let report = Report::new("lamp", &solution.measurement(&system));
        let floor = &report.objects[0];
        assert!((floor.irradiance.unwrap()[2] - h).abs() < 1e-12);
        assert!((floor.absorbed_power[1] - 0.5 * h).abs() < 1e-12);
        // The light's power is 4π·I, as the light model reports it; what misses the floor
        // escapes.
        let t = &report.totals;
        let power = 4.0 * std::f64::consts::PI * 8.0;
        assert!((t.emitted_power[0] - power).abs() < 1e-4);
        assert!((t.escaped_power[0] - (power - 0.5 * h)).abs() < 1e-4);
    }
}

#[test]
fn lambertian_point_light_link_matches_the_form_factor() {
    // I₀ = 2 W/sr facing down from (0.5, 1, 0.5) over a unit floor: it receives π·I₀·F, F
    // the form factor from the light's point to the floor (the centred closed form).
    let world = floor_under(LightKind::Lambertian {
        position: Vec3::new(0.5, 1.0, 0.5),
        direction: Vec3::NEG_Y,
        intensity: Rgb::splat(2.0),
    });
    let pi = std::f64::consts::PI;
    let a: f64 = 0.5; // half side over height
    let f = 2.0 / pi * (a / (1.0 + a * a).sqrt() * (a / (1.0 + a * a).sqrt()).atan()) * 2.0;
    let expected = pi * 2.0 * f;
    let settings = HierarchicalSettings {
        error: 1e-5,
        ..HierarchicalSettings::default()
    };
    let (system, solution) =
        solve_hierarchical(&world, options(0), &settings, &NoProgress, &Cancel::new()).unwrap();
    let report = Report::new("downlight", &solution.measurement(&system));
    let got = report.objects[0].incident_power[0];
    assert!(
        (got - expected).abs() < 2e-3 * expected,
        "{got} vs {expected}"
    );
    let power = report.totals.emitted_power[0];
    assert!((power - pi * 2.0).abs() < 1e-5, "{power}");
}

/// The display of `solution` through the scene's camera.
fn display(
    world: &Arc<World>,
    system: &RadiositySystem,
    solution: &Solution,
    settings: &DisplaySettings,
) -> strahl::measure::Film {
    let camera = &world.scene.camera;
    render_solution(
        system,
        solution,
        camera,
        settings,
        &NoProgress,
        &Cancel::new(),
    )
    .unwrap()
}

#[test]
fn display_renders_light_and_flat_and_smooth_have_equal_means() {
    let world = cornell();
    let system = RadiositySystem::new(&world, options(2)).unwrap();
    let solution = matrix(&system, Iteration::GaussSeidel, 1e-5);
    let render = |shading, wireframe| {
        let settings = DisplaySettings {
            links: LinkDisplay::None,
            width: 48,
            height: 48,
            shading,
            wireframe,
            samples_per_axis: 2,
        };
        display(&world, &system, &solution, &settings)
    };
    let flat = render(Shading::Flat, false);
    let smooth = render(Shading::Smooth, false);
    let wire = render(Shading::Smooth, true);
    let (f, s, w) = (
        flat.mean().luminance(),
        smooth.mean().luminance(),
        wire.mean().luminance(),
    );
    assert!(f > 0.0);
    assert!((f - s).abs() / f < 0.05, "{f} vs {s}");
    assert!(flat.rms_difference(&smooth).unwrap() > 1e-4);
    assert!(w < s, "wireframe lines darken the image: {w} vs {s}");
    // Almost every pixel sees the lit room (the open front shows at the rim).
    let dark = flat
        .pixels()
        .iter()
        .filter(|p| p.luminance() <= 0.0)
        .count();
    assert!(dark < flat.pixels().len() / 10, "{dark} black pixels");
}

#[test]
fn inside_the_furnace_every_pixel_reads_its_illuminance_and_luminance() {
    // Every face emits πL and reflects ρ: B = πL/(1 − ρ) = 4π W·m⁻², and inside the closed
    // cube the irradiance is B too: 683·4π lux, and 683·B/π = 2732 cd·m⁻².
    let world = furnace();
    let system = RadiositySystem::new(&world, options(2)).unwrap();
    let solution = matrix(&system, Iteration::GaussSeidel, 1e-8);
    let camera = Camera {
        position: Vec3::new(0.5, 0.5, 0.9),
        look_at: Vec3::new(0.5, 0.4, 0.0),
        up: Vec3::Y,
        fov_degrees: 100.0,
        width: 40,
        height: 30,
    };
    let settings = DisplaySettings {
        links: LinkDisplay::None,
        width: 40,
        height: 30,
        shading: Shading::Smooth,
        wireframe: false,
        samples_per_axis: 2,
    };
    let b = std::f64::consts::PI * f64::from(L) / (1.0 - f64::from(RHO));
    for (quantity, expected) in [
        (Photometric::Illuminance, 683.0 * b),
        (Photometric::Luminance, 683.0 * b / std::f64::consts::PI),
    ] {
        let image = value_image(
            &system,
            &solution,
            &camera,
            &settings,
            quantity,
            &NoProgress,
            &Cancel::new(),
        )
        .unwrap();
        assert_eq!(
            (image.width, image.height, image.quantity),
            (40, 30, quantity)
        );
        assert_eq!(image.values.len(), 1200);
        for v in &image.values {
            let v = f64::from(v.expect("every pixel sees a face"));
            assert!(
                (v / expected - 1.0).abs() < 1e-3,
                "{quantity}: {v} vs {expected}"
            );
        }
    }
    // Looking out of the open Cornell box's front, the pixels past its walls see nothing.
    let cornell = cornell();
    let system = RadiositySystem::new(&cornell, options(1)).unwrap();
    let solution = matrix(&system, Iteration::GaussSeidel, 1e-5);
    let mut outside = cornell.scene.camera.clone();
    outside.look_at = outside.position * 2.0 - outside.look_at;
    let image = value_image(
        &system,
        &solution,
        &outside,
        &settings,
        Photometric::Illuminance,
        &NoProgress,
        &Cancel::new(),
    )
    .unwrap();
    assert!(image.values.iter().all(Option::is_none));
}

#[test]
fn the_radiosity_image_keeps_link_segments_only_when_it_draws_them() {
    use strahl::method::{
        ImageSize, LinkSelection, Method, RadiosityImageSettings, RadiositySettings, SolverKind,
        run,
    };
    let world = cornell();
    let image = |links| {
        let mut radiosity = RadiositySettings::new(SolverKind::Hierarchical);
        radiosity.hierarchical.error = 1e-3;
        let settings = RadiosityImageSettings {
            size: ImageSize {
                width: Some(24),
                height: Some(24),
            },
            radiosity: radiosity.without_surface_gather(),
            links,
            ..RadiosityImageSettings::default()
        };
        let outcome = run(
            &world,
            &Method::RadiosityImage(settings),
            &NoProgress,
            &Cancel::new(),
        )
        .unwrap();
        let segments = outcome.radiosity.unwrap().solution.link_segments.len();
        (outcome.image.unwrap(), segments)
    };
    let (plain, none) = image(LinkSelection::None);
    let (drawn, all) = image(LinkSelection::All);
    // Without links shown the solve keeps none (56 bytes a link); shown, they are drawn.
    assert_eq!(none, 0);
    assert!(all > 1000, "{all}");
    let differ = (0..24)
        .flat_map(|y| (0..24).map(move |x| (x, y)))
        .filter(|&(x, y)| plain.get(x, y) != drawn.get(x, y))
        .count();
    assert!(differ > 24, "{differ} pixels differ");
}

#[test]
fn display_draws_the_links_of_one_object() {
    let world = cornell();
    let settings = HierarchicalSettings {
        error: 1e-3,
        link_segments: true,
        ..HierarchicalSettings::default()
    };
    let (system, solution) = hierarchical(&world, &settings);
    let light = world
        .scene
        .objects
        .iter()
        .position(|o| o.name.as_deref() == Some("light"))
        .unwrap() as u32;
    let of_light = solution
        .link_segments
        .iter()
        .filter(|l| l.receiver_object == Some(light) || l.emitter_object == Some(light))
        .count();
    assert!(of_light > 0 && of_light < solution.link_segments.len());
    let render = |links| {
        let settings = DisplaySettings {
            links,
            width: 48,
            height: 48,
            shading: Shading::Flat,
            wireframe: false,
            samples_per_axis: 1,
        };
        display(&world, &system, &solution, &settings)
    };
    let plain = render(LinkDisplay::None);
    let lines = render(LinkDisplay::Object(light));
    let all = render(LinkDisplay::All);
    let changed = |film: &strahl::measure::Film| {
        film.pixels()
            .iter()
            .zip(plain.pixels())
            .filter(|(a, b)| a != b)
            .count()
    };
    // The light's links fan out from the ceiling over much of the room; all links cover more.
    let (some, more) = (changed(&lines), changed(&all));
    assert!(
        some > 48 && some <= more,
        "{some} and {more} pixels changed"
    );
}

#[test]
fn the_links_shown_include_those_from_lamps_the_sun_and_the_sky() {
    // A grey floor and a block on it under a lamp, the sun and a sky: every light reaches the
    // floor, so each has links shown, from the receiver's centre to the lamp, or toward the
    // sun or along the receiving side's normal (the sky) at the scene's bounding radius.
    let mut scene = Scene::empty("lit-floor");
    let grey = scene.add_material(Material::diffuse("grey", Rgb::splat(0.5)));
    let floor = Shape::Parallelogram {
        origin: Vec3::new(-1.0, 0.0, -1.0),
        edge_u: Vec3::Z * 2.0,
        edge_v: Vec3::X * 2.0,
    };
    scene.add_object("floor", floor, grey);
    let block = Shape::Box {
        min: Vec3::new(-0.2, 0.0, -0.2),
        max: Vec3::new(0.2, 0.4, 0.2),
    };
    scene.add_object("block", block, grey);
    let lamp = Vec3::new(0.5, 1.0, 0.0);
    let sun = Vec3::new(1.0, -2.0, 0.5).normalize();
    for kind in [
        LightKind::Point {
            position: lamp,
            intensity: Rgb::splat(1.0),
        },
        LightKind::Directional {
            direction: sun,
            irradiance: Rgb::splat(100.0),
        },
        LightKind::Sky {
            radiance: Rgb::splat(10.0),
        },
    ] {
        scene.lights.push(Light { name: None, kind });
    }
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let reach = f64::from(world.geometry.bounding_sphere().1);
    let settings = HierarchicalSettings {
        link_segments: true,
        ..HierarchicalSettings::default()
    };
    let (_, solution) = hierarchical(&world, &settings);
    for light in 0..3 {
        let links: Vec<_> = solution
            .link_segments
            .iter()
            .filter(|l| l.light == Some(light))
            .collect();
        assert!(links.len() >= 2, "light {light}: {} links", links.len());
        for l in links {
            assert_eq!(l.emitter_object, None);
            assert!(l.receiver_object.is_some() && l.level.is_some());
            let to_emitter = l.emitter - l.receiver;
            match light {
                0 => assert_eq!(l.emitter, lamp.as_dvec3()),
                1 => assert!((to_emitter + reach * sun.as_dvec3()).length() < 1e-9),
                _ => {
                    assert!((to_emitter.length() - reach).abs() < 1e-9);
                    // The floor's links come from above it, whichever side they reach.
                    if l.receiver_object == Some(0) {
                        assert!(to_emitter.y.abs() > 0.999 * reach, "{to_emitter}");
                    }
                }
            }
        }
    }
    // The patch links keep no light.
    assert!(
        solution
            .link_segments
            .iter()
            .any(|l| l.light.is_none() && l.emitter_object.is_some())
    );
}

#[test]
fn exports_parse_as_gltf_and_ply() {
    let world = furnace();
    let system = RadiositySystem::new(&world, options(1)).unwrap();
    let solution = matrix(&system, Iteration::GaussSeidel, 1e-6);
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("strahl-radiosity-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let tone = ToneMapping {
        operator: ToneMap::Auto,
        exposure_ev: 0.0,
    };
    let glb = dir.join("furnace.glb");
    export_lit_mesh(&solution.lit_mesh(&system, true), &[], &tone, &glb).unwrap();
    let gltf_path = dir.join("furnace.gltf");
    export_lit_mesh(&solution.lit_mesh(&system, true), &[], &tone, &gltf_path).unwrap();
    for path in [&glb, &gltf_path] {
        let (doc, buffers, _) = gltf::import(path).unwrap();
        let primitive = doc.meshes().next().unwrap().primitives().next().unwrap();
        // Both sides of 24 quads.
        let colors = primitive.get(&gltf::Semantic::Colors(0)).expect("COLOR_0");
        assert_eq!(colors.count(), 2 * 24 * 4);
        let reader = primitive.reader(|b| Some(&buffers[b.index()]));
        assert_eq!(
            reader.read_indices().unwrap().into_u32().count(),
            2 * 24 * 6
        );
        // Uniform radiosity inside: one tone-mapped colour (to rounding) in (0, 1]; the
        // outside is black.
        let rgb: Vec<[f32; 3]> = reader.read_colors(0).unwrap().into_rgb_f32().collect();
        let (inside, outside) = rgb.split_at(24 * 4);
        assert!(
            inside
                .iter()
                .all(|c| (c[0] - inside[0][0]).abs() < 1e-5 && c[0] > 0.0 && c[0] <= 1.0)
        );
        assert!(outside.iter().all(|c| c[0] == 0.0));
    }
    let ply = dir.join("furnace.ply");
    export_lit_mesh(&solution.lit_mesh(&system, false), &[], &tone, &ply).unwrap();
    let text = std::fs::read_to_string(&ply).unwrap();
    let (header, body) = text.split_once("end_header\n").unwrap();
    assert!(header.starts_with("ply\nformat ascii 1.0\n"));
    assert!(header.contains("element vertex 192\n") && header.contains("element face 48\n"));
    let lines: Vec<&str> = body.lines().collect();
    assert_eq!(lines.len(), 192 + 48);
    let b: f64 = lines[0].split(' ').nth(9).unwrap().parse().unwrap();
    let expected = std::f64::consts::PI * L as f64 / (1.0 - RHO as f64);
    assert!((b - expected).abs() / expected < 1e-4);
    // Each face names the object it lies on: each of the box's faces holds 8 of them (2 × 2
    // patches, both sides).
    assert!(header.contains("property list uchar uint vertex_indices\nproperty uint object\n"));
    let mut per_object = vec![0; world.scene.objects.len()];
    for face in &lines[192..] {
        let words: Vec<&str> = face.split(' ').collect();
        assert_eq!(words.len(), 6, "{face}");
        per_object[words[5].parse::<usize>().unwrap()] += 1;
    }
    assert_eq!(per_object, [8; 6]);
    std::fs::remove_dir_all(&dir).unwrap();
}

fn hierarchical(
    world: &Arc<World>,
    settings: &HierarchicalSettings,
) -> (RadiositySystem, Solution) {
    hierarchical_with(world, options(0), settings)
}

fn hierarchical_with(
    world: &Arc<World>,
    options: SystemOptions,
    settings: &HierarchicalSettings,
) -> (RadiositySystem, Solution) {
    solve_hierarchical(world, options, settings, &NoProgress, &Cancel::new()).unwrap()
}

#[test]
fn hierarchical_furnace_gives_e_over_one_minus_rho() {
    let world = furnace();
    for oracle in [Oracle::Lischinski, Oracle::Bfa] {
        let settings = HierarchicalSettings {
            oracle,
            tolerance: 1e-9,
            ..HierarchicalSettings::default()
        };
        let (system, solution) = hierarchical(&world, &settings);
        match oracle {
            // Exact up to the form factors' variation the oracle lets links keep.
            Oracle::Lischinski => assert_furnace(&system, &solution, 0.01),
            // BFA does not bound that variation: element by element it is far off (links kept
            // at coarse receivers mix levels), but no light is created or lost.
            Oracle::Bfa => {
                let report = Report::new("furnace", &solution.measurement(&system));
                let t = &report.totals;
                let (e, a) = (t.emitted_power.luminance(), t.absorbed_power.luminance());
                assert!((a / e - 1.0).abs() < 0.01, "absorbed {a} of {e}");
            }
        }
    }
}

/// Keeps every round's solution a solver hands on.
#[derive(Default)]
struct Observer(std::sync::Mutex<Vec<RoundSolution>>);

impl ProgressListener for Observer {
    fn start(&self, _total: u64) {}
    fn advance(&self, _units: u64) {}
    fn finish(&self) {}
    fn wants_rounds(&self) -> bool {
        true
    }
    fn round(&self, solution: &RoundSolution) {
        self.0.lock().unwrap().push(solution.clone());
    }
}

#[test]
fn an_observer_sees_every_round_and_the_last_is_the_solution() {
    let world = furnace();
    let settings = HierarchicalSettings {
        tolerance: 1e-9,
        fine_gather: false,
        ..HierarchicalSettings::default()
    };
    let observer = Observer::default();
    let (system, solution) =
        solve_hierarchical(&world, options(0), &settings, &observer, &Cancel::new()).unwrap();
    let rounds = observer.0.into_inner().unwrap();
    assert_eq!(rounds.len(), solution.rounds.len());
    for (k, (seen, stats)) in rounds.iter().zip(&solution.rounds).enumerate() {
        assert_eq!(seen.round, k + 1);
        assert_eq!((seen.links, seen.leaves), (stats.links, stats.leaves));
        assert_eq!(seen.change, stats.residual);
        // Both sides of every leaf, each a polygon of its own.
        assert_eq!(seen.mesh.polygons.len() as u64, 2 * seen.leaves);
    }
    // The last round is the solution: inside the furnace every side reflects and emits
    // B = E/(1 − ρ) = 4π and receives 4π; outside nothing arrives.
    let last = &rounds.last().unwrap().mesh;
    assert_eq!(last.polygons.len(), system.len());
    let b = std::f64::consts::PI * L as f64 / (1.0 - RHO as f64);
    for (k, polygon) in last.polygons.iter().enumerate() {
        let v = polygon[0] as usize;
        let (radiosity, irradiance) = (
            last.radiosity[v].luminance(),
            last.irradiance[v].luminance(),
        );
        let inside = last.normals[v].dot(last.positions[v] - Vec3::splat(0.5)) < 0.0;
        if inside {
            assert!((radiosity / b - 1.0).abs() < 0.01, "{k}: {radiosity}");
            assert!((irradiance / b - 1.0).abs() < 0.01, "{k}: {irradiance}");
        } else {
            assert_eq!(irradiance, 0.0, "{k}");
        }
    }
}

#[test]
fn hierarchical_shooting_furnace_gives_e_over_one_minus_rho() {
    let world = furnace();
    let shooting = ShootingSettings {
        tolerance: 1e-7,
        ..ShootingSettings::default()
    };
    for oracle in [Oracle::Lischinski, Oracle::Bfa] {
        // Every element within 1 % with Lischinski (measured: 0.84 % at the smallest elements,
        // in the corners), 4 % with BFA, which does not bound the form factors' variation
        // (measured: 3.2 %). Shooting from single elements and refining receivers only (the
        // seed's way), the elements along the edges took 20 % too much light.
        let settings = HierarchicalSettings {
            oracle,
            error: 1e-6,
            ..HierarchicalSettings::default()
        };
        let (system, solution) = solve_hierarchical_shooting(
            &world,
            options(0),
            &settings,
            &shooting,
            &NoProgress,
            &Cancel::new(),
        )
        .unwrap();
        assert!(system.leaves.len() > 6 * 64, "{}", system.leaves.len());
        let tolerance = match oracle {
            Oracle::Lischinski => 0.01,
            Oracle::Bfa => 0.04,
        };
        assert_furnace(&system, &solution, tolerance);
        let report = Report::new("furnace", &solution.measurement(&system));
        let per_face = report.totals.emitted_power.luminance() / 6.0;
        for face in &report.objects {
            let a = face.absorbed_power.luminance();
            assert!(
                (a / per_face - 1.0).abs() < 2e-3,
                "{}: {a} of {per_face}",
                face.name
            );
        }
    }
}

#[test]
fn hierarchical_mesh_does_not_change_when_the_scene_or_the_light_is_scaled() {
    let base = builtin::load("cornell").unwrap().unwrap();
    let mut scaled = base.clone();
    let by = strahl::geometry::Transform::scale(Vec3::splat(1024.0)).unwrap();
    for object in &mut scaled.objects {
        object.transform = object.transform.then(&by);
    }
    let mut brighter = base.clone();
    for m in &mut brighter.materials {
        m.emission *= 100.0;
    }
    let counts = |scene: Scene| {
        let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
        let settings = HierarchicalSettings {
            error: 3e-4,
            ..HierarchicalSettings::default()
        };
        let (system, solution) = hierarchical(&world, &settings);
        (system.leaves.len(), solution.links)
    };
    let reference = counts(base);
    assert!(reference.0 > 100 && reference.1 > 1000, "{reference:?}");
    assert_eq!(counts(brighter), reference, "light × 100");
    // Scaled by a power of two every computation scales exactly, so every decision is the
    // same (scaled by 1000, rounding differs and flips a few borderline decisions: ±6 %).
    assert_eq!(counts(scaled), reference, "scene × 1024");
}

#[test]
fn hierarchical_results_do_not_depend_on_the_thread_count() {
    // At the default error the box has about 37,000 links, more than one chunk of the
    // parallel gather; the surface error adds the importance solve.
    let world = cornell();
    let settings = HierarchicalSettings {
        surface_error: 0.03,
        ..HierarchicalSettings::default()
    };
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| hierarchical(&world, &settings).1.radiosity)
    };
    assert_eq!(run(1), run(3));
}

/// What the closed box of [`closed_box`] holds.
#[derive(Clone, Copy, PartialEq)]
enum Inside {
    /// Nothing: one of its faces emits.
    Nothing,
    /// A small lamp just under the ceiling, the only emitter.
    Lamp,
    /// A 0.2 m plate at half height under the emitting face.
    Plate,
}

/// The unit cube, inwards, reflecting `rho`, with `inside` in it.
fn closed_box(rho: f32, inside: Inside) -> Arc<World> {
    let mut scene = Scene::empty("box");
    let grey = scene.add_material(Material::diffuse("grey", Rgb::splat(rho)));
    let glow = scene.add_material(Material::emitter("glow", Rgb::splat(rho), Rgb::splat(L)));
    for (k, shape) in unit_cube_faces().into_iter().enumerate() {
        let m = if k == 1 && inside != Inside::Lamp {
            glow
        } else {
            grey
        };
        scene.add_object(&format!("face{k}"), shape, m);
    }
    let square = |y: f32| Shape::Parallelogram {
        origin: Vec3::new(0.4, y, 0.4),
        edge_u: Vec3::X * 0.2,
        edge_v: Vec3::Z * 0.2,
    };
    match inside {
        Inside::Nothing => {}
        Inside::Lamp => scene.add_object("lamp", square(0.999), glow),
        Inside::Plate => scene.add_object("plate", square(0.5), grey),
    }
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

#[test]
fn hierarchical_closed_box_absorbs_what_it_emits() {
    // Energy is conserved within the oracle's error: a closed box absorbs all it emits, lit
    // by one whole face or by a small lamp just under the ceiling (whose back sees the
    // ceiling at a millimetre: the case a form-factor-only error bound misses).
    for lamp in [false, true] {
        let world = closed_box(RHO, if lamp { Inside::Lamp } else { Inside::Nothing });
        let (system, solution) = hierarchical(&world, &HierarchicalSettings::default());
        let report = Report::new("box", &solution.measurement(&system));
        let t = &report.totals;
        let (e, a) = (t.emitted_power.luminance(), t.absorbed_power.luminance());
        // Measured at the default error: 0.12 % and 0.78 % (light lost in the millimetre gap
        // above the lamp, where the minimum area stops refinement); at 5·10⁻⁵: 0.004 % and
        // 0.67 %.
        let tolerance = if lamp { 0.01 } else { 0.002 };
        assert!(
            (a / e - 1.0).abs() < tolerance,
            "lamp {lamp}: absorbed {a} of {e}"
        );
    }
}

#[test]
fn a_closed_box_with_a_plate_in_it_absorbs_what_it_emits() {
    // A 0.2 m plate at half height under the emitting ceiling, everything reflecting 0.95:
    // light bounces twenty times on average, so a form-factor sum a few 10⁻⁴ off shows as
    // per cent. Whether a link is partly hidden is judged by rays other than those that
    // measure its visible share; judged by the same rays, every shadow came out too small
    // (a link whose rays missed the plate was kept whole, one whose rays met it refined) and
    // the box absorbed 0.92 % more than it emitted. Measured now: +0.12 %.
    let world = closed_box(0.95, Inside::Plate);
    let (system, solution) = hierarchical(&world, &HierarchicalSettings::default());
    let t = Report::new("plate box", &solution.measurement(&system)).totals;
    let (e, a) = (t.emitted_power.luminance(), t.absorbed_power.luminance());
    assert!((a / e - 1.0).abs() < 0.003, "absorbed {a} of {e}");
}

/// A black unit floor under a black plate a centimetre above it that leaves only the strip
/// `x > 0.9` open, lit by a large emitter overhead that ends at `x = 1`: every Gauss point
/// of the floor is in shadow, its edge is not.
fn floor_lit_only_at_its_edge() -> Arc<World> {
    let mut scene = Scene::empty("strip");
    let black = scene.add_material(Material::diffuse("black", Rgb::BLACK));
    let glow = scene.add_material(Material::emitter("glow", Rgb::BLACK, Rgb::splat(L)));
    let quad = |origin: Vec3, u: Vec3, v: Vec3| Shape::Parallelogram {
        origin,
        edge_u: u,
        edge_v: v,
    };
    scene.add_object("floor", quad(Vec3::ZERO, Vec3::Z, Vec3::X), black);
    let plate = quad(Vec3::new(-3.0, 0.01, -2.0), Vec3::Z * 5.0, Vec3::X * 3.9);
    scene.add_object("plate", plate, black);
    let sky = quad(Vec3::new(-2.0, 1.0, -1.0), Vec3::X * 3.0, Vec3::Z * 3.0);
    scene.add_object("emitter", sky, glow);
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

#[test]
fn hierarchical_links_a_pair_that_sees_itself_only_near_an_edge() {
    // The floor's four Gauss points see nothing of the emitter; a link dropped for that would
    // never be refined and the lit strip would stay black (it did: 0 W).
    let world = floor_lit_only_at_its_edge();
    // All the floor's light falls on a strip two nodes wide at the default error, where the
    // oracle lets each link be off by 10⁻⁴ of the 56 W emitted, 2 % of the floor's power:
    // a finer error makes the comparison sharp.
    let settings = HierarchicalSettings {
        error: 2e-6,
        ..HierarchicalSettings::default()
    };
    let (system, solution) = hierarchical(&world, &settings);
    let floor = |report: &Report| {
        report
            .objects
            .iter()
            .find(|o| o.name == "floor")
            .unwrap()
            .incident_power[1]
    };
    let radiosity = floor(&report_of(&system, &solution));
    let reference = floor(&light_model_report(&world, 4_000_000, 3));
    // Measured: 2.1 % apart; 0.45 % of the photons reach the floor, so the light model's
    // own error is about 0.75 % there.
    assert!(
        (radiosity / reference - 1.0).abs() < 0.04,
        "{radiosity} W vs light model {reference} W"
    );
}

#[test]
fn hierarchical_refines_next_to_an_emitter_until_its_light_is_right() {
    // A black unit floor under a small lamp five centimetres above its centre: the floor's
    // direct light varies a hundredfold across it, and only refinement near the lamp brings
    // it within the oracle's bound.
    let mut scene = Scene::empty("lamp-over-floor");
    let black = scene.add_material(Material::diffuse("black", Rgb::BLACK));
    let glow = scene.add_material(Material::emitter("glow", Rgb::BLACK, Rgb::splat(L)));
    let floor = Shape::Parallelogram {
        origin: Vec3::ZERO,
        edge_u: Vec3::Z,
        edge_v: Vec3::X,
    };
    scene.add_object("floor", floor, black);
    let lamp = Shape::Parallelogram {
        origin: Vec3::new(0.45, 0.05, 0.45),
        edge_u: Vec3::X * 0.1,
        edge_v: Vec3::Z * 0.1,
    };
    scene.add_object("lamp", lamp, glow);
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let (system, solution) = hierarchical(&world, &HierarchicalSettings::default());
    // Leaves under the lamp are far smaller than those at the floor's corners.
    let floor_leaves: Vec<&strahl::radiosity::Patch> = system
        .leaves
        .iter()
        .map(|&l| system.mesh.patch(l))
        .filter(|p| p.normal.y.abs() > 0.5 && p.centroid.y < 0.01)
        .collect();
    let area_near = |near: bool| {
        floor_leaves
            .iter()
            .filter(|p| {
                let d = (p.centroid.x - 0.5).hypot(p.centroid.z - 0.5);
                if near { d < 0.1 } else { d > 0.6 }
            })
            .map(|p| p.area)
            .fold(f64::INFINITY, f64::min)
    };
    let (near, far) = (area_near(true), area_near(false));
    assert!(
        near * 16.0 <= far,
        "smallest leaf near the lamp {near}, far {far}"
    );
    // The floor takes what the lamp sends it, against the light model: 99 % of the lamp's
    // power lands on the floor, so 10⁶ photons leave it about 0.01 % of noise. Measured:
    // 0.003 % apart; leaves 64 times smaller under the lamp than at the corners.
    let floor_power = |report: &Report| report.objects[0].incident_power[1];
    let radiosity = floor_power(&report_of(&system, &solution));
    let reference = floor_power(&light_model_report(&world, 1_000_000, 4));
    assert!(
        (radiosity / reference - 1.0).abs() < 0.005,
        "{radiosity} W vs light model {reference} W"
    );
}

#[test]
fn contact_splits_keep_every_faces_area() {
    let scene = builtin::load("cornell").unwrap().unwrap();
    let area_of = |contact_splits: bool| {
        let options = MeshOptions {
            contact_splits,
            ..MeshOptions::default()
        };
        let mesh = strahl::radiosity::PatchMesh::from_scene(&scene, &options).unwrap();
        let mut per_object = vec![0.0f64; scene.objects.len()];
        for &r in &mesh.roots {
            per_object[mesh.patch(r).object as usize] += mesh.patch(r).area;
        }
        (per_object, mesh.roots.len())
    };
    let (whole, roots) = area_of(false);
    let (cut, cut_roots) = area_of(true);
    assert!(cut_roots > roots, "{cut_roots} vs {roots}");
    for (a, b) in whole.iter().zip(&cut) {
        assert!((a - b).abs() <= 1e-12 * a, "{a} vs {b}");
    }
}

/// A white ball of radius ½ resting on a white 2 × 2 quad, lit by a small lamp above: the
/// ball's pole touches the quad's centroid, and the ball's facets meet the quad edge-on.
fn ball_on_quad() -> Arc<World> {
    let mut scene = Scene::empty("ball-on-quad");
    let white = scene.add_material(Material::diffuse("white", Rgb::splat(0.7)));
    let lamp = scene.add_material(Material::emitter("lamp", Rgb::splat(0.5), Rgb::splat(5.0)));
    let quad = Shape::Parallelogram {
        origin: Vec3::new(-1.0, 0.0, 1.0),
        edge_u: Vec3::X * 2.0,
        edge_v: Vec3::Z * -2.0,
    };
    scene.add_object("quad", quad, white);
    let ball = Shape::Sphere {
        center: Vec3::new(0.0, 0.5, 0.0),
        radius: 0.5,
    };
    scene.add_object("ball", ball, white);
    let light = Shape::Parallelogram {
        origin: Vec3::new(-0.2, 2.0, -0.2),
        edge_u: Vec3::X * 0.4,
        edge_v: Vec3::Z * 0.4,
    };
    scene.add_object("lamp", light, lamp);
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

/// Luminance of the absorbed power per object name.
fn absorbed(report: &Report) -> std::collections::HashMap<String, f64> {
    report
        .objects
        .iter()
        .map(|o| (o.name.clone(), o.absorbed_power.luminance()))
        .collect()
}

/// The light model's report of `world` at `photons` photons from seed `seed`.
fn light_model_report(world: &Arc<World>, photons: u64, seed: u64) -> Report {
    let settings = LightTraceSettings {
        photons,
        seed,
        max_bounces: 1000,
    };
    let out = trace_light(world, &settings, &NoProgress, &Cancel::new()).unwrap();
    Report::new(&world.scene.name, &out.measurement())
}

fn report_of(system: &RadiositySystem, solution: &Solution) -> Report {
    Report::new("ball-on-quad", &solution.measurement(system))
}

#[test]
fn a_ball_touching_a_quad_gives_finite_light_that_agrees_with_the_light_model() {
    // Once inf/NaN: the pole's point form factor to the quad, evaluated in the quad's plane,
    // summed rounding noise up to 1, and f32 noise contact-split the ball's facets into
    // slivers. Every solver now gives finite figures that conserve energy, and the
    // hierarchical solution agrees with the light model.
    let world = ball_on_quad();
    let system = RadiositySystem::new(&world, options(0)).unwrap();
    let flat = [
        matrix(&system, Iteration::GaussSeidel, 1e-6),
        progressive(&system, false, 1e-6),
        progressive(&system, true, 1e-6),
    ];
    for solution in &flat {
        let report = report_of(&system, solution);
        let t = &report.totals;
        let (e, a, x) = (
            t.emitted_power.luminance(),
            t.absorbed_power.luminance(),
            t.escaped_power.luminance(),
        );
        assert!(a.is_finite() && x.is_finite(), "{}: {a} {x}", report.solver);
        assert!(
            x >= 0.0 && (a + x - e).abs() < 1e-6 * e,
            "{}",
            report.solver
        );
        for o in &report.objects {
            assert!(o.absorbed_power.luminance() > 0.0, "{}", o.name);
        }
    }
    let reference = absorbed(&light_model_report(&world, 4_000_000, 5));
    let mut options = options(0);
    options.mesh.segments = 32;
    let (system, solution) = hierarchical_with(&world, options, &HierarchicalSettings::default());
    let r = absorbed(&report_of(&system, &solution));
    // Measured: quad +2.5 %, ball +1.7 %, lamp −3.1 % (it receives only reflected light);
    // the light model's noise at 4·10⁶ photons is under 1 %.
    for (name, tolerance) in [("quad", 0.03), ("ball", 0.03), ("lamp", 0.05)] {
        let error = r[name] / reference[name] - 1.0;
        assert!(error.abs() < tolerance, "{name}: {error:+.4}");
    }
}
