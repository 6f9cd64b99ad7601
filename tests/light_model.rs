//! Statistical and bookkeeping tests of the light model (`strahl solve --solver light-trace`).
//!
//! Every run uses a fixed seed, so results are deterministic. Tolerances are 4 standard
//! deviations of the estimator, with the standard deviation derived from the estimator's
//! variance (stated at each test), so a correct tracer passes and a wrong factor fails.

use glam::Vec3;
use std::f64::consts::PI;
use std::sync::Arc;
use strahl::accel::AccelKind;
use strahl::color::{Rgb, Rgb64};
use strahl::light_model::{LightTraceSettings, trace_light};
use strahl::progress::Cancel;
use strahl::progress::NoProgress;
use strahl::report::{ObjectReport, Report};
use strahl::scene::{Light, LightKind, Material, PolygonMesh, Scene, Shape};
use strahl::world::World;

/// Traces `photons` photons with `seed` and returns the report.
fn solve(scene: Scene, photons: u64, seed: u64) -> Report {
    let name = scene.name.clone();
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let settings = LightTraceSettings {
        photons,
        seed,
        ..LightTraceSettings::default()
    };
    let out = trace_light(&world, &settings, &NoProgress, &Cancel::new()).unwrap();
    assert!(out.complete());
    Report::new(&name, &out.measurement())
}

fn object<'a>(r: &'a Report, name: &str) -> &'a ObjectReport {
    r.objects.iter().find(|o| o.name == name).unwrap()
}

fn sum(c: Rgb64) -> f64 {
    c.to_array().iter().sum()
}

/// A parallelogram from its corner and two edges (front side `u × v`).
fn quad(origin: Vec3, u: Vec3, v: Vec3) -> Shape {
    Shape::Parallelogram {
        origin,
        edge_u: u,
        edge_v: v,
    }
}

/// An upward-facing square patch of side `s` centred at `(x, y, z)`.
fn patch(x: f32, y: f32, z: f32, s: f32) -> Shape {
    quad(
        Vec3::new(x - 0.5 * s, y, z + 0.5 * s),
        Vec3::X * s,
        Vec3::NEG_Z * s,
    )
}

/// The unit cube [0,1]³ as six inward-facing quads of material `m`.
fn closed_box(scene: &mut Scene, m: u32) {
    let (o, x, y, z) = (Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z);
    let faces = [
        ("floor", quad(o, z, x)),
        ("ceiling", quad(y, x, z)),
        ("left", quad(o, y, z)),
        ("right", quad(x, z, y)),
        ("back", quad(o, x, y)),
        ("front", quad(z, y, x)),
    ];
    for (name, shape) in faces {
        scene.add_object(name, shape, m);
    }
}

/// The white furnace: a closed unit cube whose six faces emit πL = 1 W·m⁻² and reflect ρ.
fn furnace(rho: f32) -> Scene {
    let mut scene = Scene::empty("furnace");
    let m = scene.add_material(Material::emitter(
        "glow",
        Rgb::splat(rho),
        Rgb::splat(1.0 / std::f32::consts::PI),
    ));
    closed_box(&mut scene, m);
    scene
}

#[test]
fn furnace_radiosity_is_emission_over_one_minus_rho() {
    // Each face: B = M/(1−ρ) = 1/(1 − 0.5) = 2 W·m⁻².
    // Variance: every photon carries p0 = Φ/N (Φ = 6 W) and reflects it K times, K geometric
    // with E[K²] = ρ(1+ρ)/(1−ρ)² = 3; face j sees K_j ≤ K of those, and by symmetry
    // E[K_j²] ≤ E[K·K_j] = E[K²]/6 = 0.5, so σ(B_j) ≤ Φ·√(0.5/N) (area 1).
    let n = 400_000u64;
    let report = solve(furnace(0.5), n, 7);
    let sigma = 6.0 * (0.5 / n as f64).sqrt();
    assert_eq!(report.objects.len(), 6);
    for o in &report.objects {
        assert!((o.area.unwrap() - 1.0).abs() < 1e-6);
        for c in 0..3 {
            assert!(
                (o.emitted_power[c] - 1.0).abs() < 1e-9,
                "{:?}",
                o.emitted_power
            );
            let b = o.radiosity.unwrap()[c];
            assert!(
                (b - 2.0).abs() < 4.0 * sigma,
                "{}: B = {b}, 4σ = {}",
                o.name,
                4.0 * sigma
            );
        }
    }
}

#[test]
fn closed_scene_absorbs_exactly_what_it_emits() {
    let report = solve(furnace(0.8), 50_000, 3);
    let t = &report.totals;
    for c in 0..3 {
        assert!((t.absorbed_power[c] - t.emitted_power[c]).abs() < 1e-9 * t.emitted_power[c]);
        assert_eq!(t.escaped_power[c], 0.0);
        assert!((t.emitted_power[c] - 6.0).abs() < 1e-9);
    }
    // Per object, incident = absorbed + reflected.
    for o in &report.objects {
        for c in 0..3 {
            let balance = o.absorbed_power[c] + o.reflected_power[c] - o.incident_power[c];
            assert!(balance.abs() < 1e-9, "{}: {balance}", o.name);
        }
    }
}

#[test]
fn open_cornell_box_absorbed_plus_escaped_equals_emitted() {
    let scene = strahl::scene::builtin::load("cornell").unwrap().unwrap();
    let report = solve(scene, 100_000, 11);
    let t = &report.totals;
    for c in 0..3 {
        let sum = t.absorbed_power[c] + t.escaped_power[c];
        assert!((sum - t.emitted_power[c]).abs() < 1e-9 * t.emitted_power[c]);
        // The open front lets a good part escape.
        assert!(
            t.escaped_power[c] > 0.05 * t.emitted_power[c],
            "{:?}",
            t.escaped_power
        );
    }
    assert_eq!(report.solver, "light-trace");
    assert!(object(&report, "floor").irradiance.unwrap()[0] > 0.0);
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| solve(furnace(0.6), 30_000, 5))
    };
    let (a, b) = (run(1), run(3));
    assert_eq!(a.objects, b.objects);
    assert_eq!(a.totals, b.totals);
}

/// Power (W) a patch of side `s` centred at `(cx, 0, cz)`, facing up, receives from a point
/// source of intensity `i` at height `h` above the origin: ∫ I·h/d³ dA (midpoint rule).
fn point_patch_power(i: f64, h: f64, cx: f64, cz: f64, s: f64) -> f64 {
    let n = 200;
    let da = (s / n as f64).powi(2);
    let mut sum = 0.0;
    for a in 0..n {
        for b in 0..n {
            let x = cx - s / 2.0 + (a as f64 + 0.5) * s / n as f64;
            let z = cz - s / 2.0 + (b as f64 + 0.5) * s / n as f64;
            let d = (x * x + z * z + h * h).sqrt();
            sum += i * h / d.powi(3) * da;
        }
    }
    sum
}

/// A point source of intensity 2 W/sr at height 1 over black patches on the plane y = 0.
fn point_source_scene(patches: &[(f32, f32)], side: impl Fn(f32, f32) -> f32) -> Scene {
    let mut scene = Scene::empty("point");
    let black = scene.add_material(Material::diffuse("black", Rgb::BLACK));
    for (k, &(x, z)) in patches.iter().enumerate() {
        scene.add_object(&format!("patch{k}"), patch(x, 0.0, z, side(x, z)), black);
    }
    scene.lights.push(Light {
        name: None,
        kind: LightKind::Point {
            position: Vec3::Y,
            intensity: Rgb::splat(2.0),
        },
    });
    scene
}

#[test]
fn point_source_irradiance_follows_inverse_square_and_cosine() {
    let points = [(0.0, 0.0), (1.0, 0.0), (0.0, -2.0), (1.5, 1.5)];
    let side = |x: f32, z: f32| 0.3 * (x * x + z * z + 1.0).sqrt();
    let n = 1_000_000u64;
    let report = solve(point_source_scene(&points, side), n, 1);
    let phi = 4.0 * PI * 2.0;
    for (k, &(x, z)) in points.iter().enumerate() {
        let s = side(x, z) as f64;
        let (x, z) = (x as f64, z as f64);
        let expected = point_patch_power(2.0, 1.0, x, z, s);
        // The patch is small: its mean irradiance is within 4% of I·cosθ/d² at its centre.
        let d2 = x * x + z * z + 1.0;
        let at_centre = 2.0 * (1.0 / d2.sqrt()) / d2;
        assert!((expected / (s * s) - at_centre).abs() < 0.04 * at_centre);
        // Hits are binomial: σ/P = √((1−p)/(N·p)), p = P/Φ.
        let p = expected / phi;
        let sigma = expected * ((1.0 - p) / (n as f64 * p)).sqrt();
        let o = object(&report, &format!("patch{k}"));
        for c in 0..3 {
            let got = o.incident_power[c];
            assert!(
                (got - expected).abs() < 4.0 * sigma,
                "patch{k}: {got} vs {expected} ± {sigma}"
            );
            let e = o.irradiance.unwrap()[c];
            // Areas are measured in single precision.
            assert!((e - got / (s * s)).abs() < 1e-5 * e);
        }
        assert!(o.illuminance_lux.unwrap() > 0.0);
    }
}

/// Form factor from a differential area to a parallel rectangle with one corner straight
/// above it, sides `x`, `y` (signed) at distance `h`.
fn corner_form_factor(x: f64, y: f64, h: f64) -> f64 {
    let (a, b) = (x / h, y / h);
    let (ra, rb) = ((1.0 + a * a).sqrt(), (1.0 + b * b).sqrt());
    (a / ra * (b / ra).atan() + b / rb * (a / rb).atan()) / (2.0 * PI)
}

/// Form factor from the point (x, z) on y = 0 (facing up) to the rectangle
/// [−a, a] × [−b, b] at height h facing down, by superposing four corner rectangles.
fn rectangle_form_factor(x: f64, z: f64, a: f64, b: f64, h: f64) -> f64 {
    let mut f = 0.0;
    for sx in [a - x, a + x] {
        for sz in [b - z, b + z] {
            f += corner_form_factor(sx, sz, h);
        }
    }
    f
}

#[test]
fn lambertian_point_source_sends_pi_i0_times_the_form_factor() {
    // I₀ = 2 W/sr facing down at height 1: a patch receives ∫ I₀·cos θ·cos θ'/d² dA =
    // π·I₀·F, F the form factor from the light's point to the patch; the light's power π·I₀.
    let (side, centres) = (0.5f32, [(0.0f32, 0.0f32), (1.0, 0.0), (-1.0, 1.5)]);
    let mut scene = Scene::empty("downlight");
    let black = scene.add_material(Material::diffuse("black", Rgb::BLACK));
    for (k, &(x, z)) in centres.iter().enumerate() {
        scene.add_object(&format!("patch{k}"), patch(x, 0.0, z, side), black);
    }
    scene.lights.push(Light {
        name: None,
        kind: LightKind::Lambertian {
            position: Vec3::Y,
            direction: Vec3::NEG_Y,
            intensity: Rgb::splat(2.0),
        },
    });
    let n = 1_000_000u64;
    let report = solve(scene, n, 3);
    let phi = PI * 2.0;
    assert!((sum(report.totals.emitted_power) - 3.0 * phi).abs() < 1e-6 * phi);
    for (k, &(x, z)) in centres.iter().enumerate() {
        let half = 0.5 * side as f64;
        let f = rectangle_form_factor(-x as f64, -z as f64, half, half, 1.0);
        let expected = phi * f;
        // Hits are binomial with p = F.
        let sigma = expected * ((1.0 - f) / (n as f64 * f)).sqrt();
        let got = object(&report, &format!("patch{k}")).incident_power[1];
        assert!(
            (got - expected).abs() < 4.0 * sigma,
            "patch{k}: {got} vs {expected} ± {sigma}"
        );
    }
}

#[test]
fn centred_form_factor_formula_matches_quadrature() {
    // F = (2/π)[a/√(1+a²)·atan(b/√(1+a²)) + b/√(1+b²)·atan(a/√(1+b²))], a, b half sides
    // over the distance, against ∫ cos·cos/(π r²) dA over the rectangle.
    let (a, b, h) = (0.5f64, 0.8f64, 1.2f64);
    let (ah, bh) = (a / h, b / h);
    let closed = 2.0 / PI
        * (ah / (1.0 + ah * ah).sqrt() * (bh / (1.0 + ah * ah).sqrt()).atan()
            + bh / (1.0 + bh * bh).sqrt() * (ah / (1.0 + bh * bh).sqrt()).atan());
    let n = 800;
    let mut quad = 0.0;
    for i in 0..n {
        for j in 0..n {
            let x = -a + (i as f64 + 0.5) * 2.0 * a / n as f64;
            let z = -b + (j as f64 + 0.5) * 2.0 * b / n as f64;
            let r2 = x * x + z * z + h * h;
            quad += h * h / (PI * r2 * r2) * (4.0 * a * b / (n * n) as f64);
        }
    }
    assert!((closed - quad).abs() < 1e-5, "{closed} vs {quad}");
    assert!((rectangle_form_factor(0.0, 0.0, a, b, h) - closed).abs() < 1e-12);
}

#[test]
fn patch_under_area_light_matches_the_form_factor() {
    // Light: 1 × 1 m at height 1, facing down, L = 1 (M = π W·m⁻²); black patches 0.4 m.
    let mut scene = Scene::empty("area");
    let light = scene.add_material(Material::emitter("lamp", Rgb::BLACK, Rgb::WHITE));
    let black = scene.add_material(Material::diffuse("black", Rgb::BLACK));
    scene.add_object(
        "lamp",
        quad(Vec3::new(-0.5, 1.0, -0.5), Vec3::X, Vec3::Z),
        light,
    );
    let (s, centres) = (0.4f32, [(0.0f32, 0.0f32), (0.9, 0.3)]);
    for (k, &(x, z)) in centres.iter().enumerate() {
        scene.add_object(&format!("patch{k}"), patch(x, 0.0, z, s), black);
    }
    let n = 1_000_000u64;
    let report = solve(scene, n, 2);
    let phi = PI;
    assert!((sum(object(&report, "lamp").emitted_power) - 3.0 * phi).abs() < 1e-6 * phi);
    for (k, &(cx, cz)) in centres.iter().enumerate() {
        let (cx, cz, s) = (cx as f64, cz as f64, s as f64);
        // Expected power: M·∫F dA over the patch (midpoint rule, 100 × 100).
        let m = 100;
        let mut expected = 0.0;
        for i in 0..m {
            for j in 0..m {
                let x = cx - s / 2.0 + (i as f64 + 0.5) * s / m as f64;
                let z = cz - s / 2.0 + (j as f64 + 0.5) * s / m as f64;
                expected +=
                    PI * rectangle_form_factor(x, z, 0.5, 0.5, 1.0) * (s * s) / (m * m) as f64;
            }
        }
        if k == 0 {
            // The centred patch is small: within 3% of M·F at its centre times its area.
            let point = PI * rectangle_form_factor(0.0, 0.0, 0.5, 0.5, 1.0) * s * s;
            assert!((expected - point).abs() < 0.03 * point);
        }
        let p = expected / phi;
        let sigma = expected * ((1.0 - p) / (n as f64 * p)).sqrt();
        let got = object(&report, &format!("patch{k}")).incident_power;
        for g in got.to_array() {
            assert!(
                (g - expected).abs() < 4.0 * sigma,
                "patch{k}: {g} vs {expected} ± {sigma}"
            );
        }
    }
}

#[test]
fn sky_and_sun_deliver_their_analytic_power() {
    // An isolated black quad of area A under uniform sky radiance L receives π·L·A on each
    // side (2π·L·A in all); a sun of irradiance E at 60° from the normal gives E·A·cos 60°.
    // Photons that enter the bounding sphere hit the quad with probability p = P/Φ.
    let build = |light: LightKind| {
        let mut scene = Scene::empty("sky");
        let black = scene.add_material(Material::diffuse("black", Rgb::BLACK));
        scene.add_object("leaf", patch(0.0, 0.0, 0.0, 1.0), black);
        scene.lights.push(Light {
            name: None,
            kind: light,
        });
        scene
    };
    let n = 200_000u64;
    let sky = solve(
        build(LightKind::Sky {
            radiance: Rgb::splat(0.5),
        }),
        n,
        4,
    );
    let sun_dir = Vec3::new(60f32.to_radians().sin(), -60f32.to_radians().cos(), 0.0);
    let sun = solve(
        build(LightKind::Directional {
            direction: sun_dir,
            irradiance: Rgb::splat(3.0),
        }),
        n,
        4,
    );
    for (report, expected) in [(&sky, 2.0 * PI * 0.5), (&sun, 3.0 * 0.5)] {
        let phi = report.totals.emitted_power[0];
        let p = expected / phi;
        let sigma = expected * ((1.0 - p) / (n as f64 * p)).sqrt();
        let got = object(report, "leaf").incident_power[1];
        assert!(
            (got - expected).abs() < 4.0 * sigma,
            "{got} vs {expected} ± {sigma}"
        );
    }
}

#[test]
fn spot_light_has_its_axis_intensity_and_no_light_outside_the_cone() {
    // Spot at height 2 pointing down, I = 5 W/sr inside 20°, zero beyond 40°: a patch on the
    // axis receives ≈ I·A/h² (exact value by quadrature), a patch at 60° off axis nothing.
    let mut scene = Scene::empty("spot");
    let black = scene.add_material(Material::diffuse("black", Rgb::BLACK));
    scene.add_object("axis", patch(0.0, 0.0, 0.0, 0.4), black);
    scene.add_object("outside", patch(2.0 * 3f32.sqrt(), 0.0, 0.0, 0.4), black);
    scene.lights.push(Light {
        name: None,
        kind: LightKind::Spot {
            position: Vec3::new(0.0, 2.0, 0.0),
            direction: Vec3::NEG_Y,
            intensity: Rgb::splat(5.0),
            inner_degrees: 20.0,
            outer_degrees: 40.0,
        },
    });
    let n = 400_000u64;
    let report = solve(scene, n, 9);
    let expected = point_patch_power(5.0, 2.0, 0.0, 0.0, 0.4);
    let phi = report.totals.emitted_power[0];
    let p = expected / phi;
    let sigma = expected * ((1.0 - p) / (n as f64 * p)).sqrt();
    let got = object(&report, "axis").incident_power[0];
    assert!(
        (got - expected).abs() < 4.0 * sigma,
        "{got} vs {expected} ± {sigma}"
    );
    assert_eq!(object(&report, "outside").incident_power, Rgb64::BLACK);
}

#[test]
fn error_falls_as_one_over_root_n() {
    // RMS error over 32 seeds of a patch's power at N and 16 N photons. For 1/√N the ratio
    // is 4; each RMS is estimated from 32 samples (relative σ ≈ 1/√64 = 12.5%), so the
    // ratio lies within [2.4, 6.6] with overwhelming probability, far from 1 (no
    // convergence) and 16 (1/N).
    let points = [(0.0f32, 0.0f32)];
    let expected = point_patch_power(2.0, 1.0, 0.0, 0.0, 0.5);
    let rms = |n: u64| {
        let mut sq = 0.0;
        for seed in 0..32 {
            let r = solve(point_source_scene(&points, |_, _| 0.5), n, 1000 + seed);
            sq += (r.objects[0].incident_power[0] - expected).powi(2);
        }
        (sq / 32.0).sqrt()
    };
    let (coarse, fine) = (rms(2_000), rms(32_000));
    let ratio = coarse / fine;
    assert!((2.4..6.6).contains(&ratio), "{coarse} / {fine} = {ratio}");
}

#[test]
fn per_face_output_splits_a_mesh_and_adds_up() {
    // Two unit quads in one mesh; a point light above the first face only.
    let build = |per_face: bool| {
        let mut scene = Scene::empty("faces");
        let grey = scene.add_material(Material::diffuse("grey", Rgb::splat(0.5)));
        let mesh = PolygonMesh::from_triangles(
            vec![
                Vec3::ZERO,
                Vec3::X,
                Vec3::new(1.0, 0.0, -1.0),
                Vec3::new(0.0, 0.0, -1.0),
                Vec3::new(3.0, 0.0, 0.0),
                Vec3::new(4.0, 0.0, 0.0),
                Vec3::new(4.0, 0.0, -1.0),
                Vec3::new(3.0, 0.0, -1.0),
            ],
            &[[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]],
        );
        scene.add_object("leaves", Shape::Mesh(Arc::new(mesh)), grey);
        scene.objects[0].per_face = per_face;
        scene.lights.push(Light {
            name: None,
            kind: LightKind::Point {
                position: Vec3::new(0.5, 0.2, -0.5),
                intensity: Rgb::WHITE,
            },
        });
        scene
    };
    let whole = solve(build(false), 20_000, 8);
    let split = solve(build(true), 20_000, 8);
    assert_eq!(whole.objects.len(), 1);
    assert_eq!(whole.objects[0].face, None);
    // from_triangles makes one face per triangle: four faces of 0.5 m² each.
    assert_eq!(split.objects.len(), 4);
    for (k, o) in split.objects.iter().enumerate() {
        assert_eq!((o.name.as_str(), o.face), ("leaves", Some(k as u32)));
        assert!((o.area.unwrap() - 0.5).abs() < 1e-6);
    }
    let total: f64 = split.objects.iter().map(|o| o.incident_power[0]).sum();
    assert!((total - whole.objects[0].incident_power[0]).abs() < 1e-9 * total);
    // The near face gets almost everything (the light is 0.2 m above it).
    let near = split.objects[0].incident_power[0] + split.objects[1].incident_power[0];
    assert!(near > 0.9 * total);
}

#[test]
fn ten_thousand_leaves_conserve_energy_and_almost_all_receive_light() {
    // 100 × 100 small tilted leaves under a sky and a sun.
    let scene = strahl::scene::builtin::load("canopy").unwrap().unwrap();
    let report = solve(scene, 200_000, 12);
    assert_eq!(report.objects.len(), 10_000);
    let t = &report.totals;
    for c in 0..3 {
        let sum = t.absorbed_power[c] + t.escaped_power[c];
        assert!((sum - t.emitted_power[c]).abs() < 1e-9 * t.emitted_power[c]);
    }
    let lit = report
        .objects
        .iter()
        .filter(|o| o.incident_power[1] > 0.0)
        .count();
    assert!(lit > 9_000, "{lit} leaves lit");
}

/// Asks the run to stop at its first progress report.
struct StopAtFirstBatch<'a>(&'a Cancel);

impl strahl::progress::ProgressListener for StopAtFirstBatch<'_> {
    fn start(&self, _total: u64) {}
    fn advance(&self, _units: u64) {
        self.0.request();
    }
    fn finish(&self) {}
}

#[test]
fn cancelled_run_keeps_its_photons_scaled_to_the_full_count() {
    let world = Arc::new(World::new(furnace(0.5), AccelKind::Bvh).unwrap());
    let settings = LightTraceSettings {
        photons: 1_000_000,
        seed: 1,
        ..LightTraceSettings::default()
    };
    let cancel = Cancel::new();
    let out = trace_light(&world, &settings, &StopAtFirstBatch(&cancel), &cancel).unwrap();
    assert!(!out.complete());
    // One batch of N/200 photons.
    assert_eq!(out.photons_traced, 5_000);
    let report = Report::new("furnace", &out.measurement());
    assert_eq!(report.stats.extra["complete"], false);
    // The radical-inverse source order keeps the prefix stratified: the van der Corput
    // star discrepancy bound n·D* ≤ log₂(n)/3 + 1 ≈ 5.1 at n = 5000 puts each face's count
    // within 2 × 5.1 of its 833.3 photons, so the scaled emission is within 1.3% of 1 W.
    for o in &report.objects {
        assert!(
            (o.emitted_power[0] - 1.0).abs() < 0.013,
            "{:?}",
            o.emitted_power
        );
    }
}

#[test]
fn textured_emitter_emits_its_texture_weighted_power() {
    // A 1 m² lamp of L = 2 with a texture white on the left quarter, black elsewhere: the
    // emitted power is π·A·L·(area mean of the texture), the mean taken here on a fine grid
    // of the texture as sampled. Per photon the power is π·A·L·c(uv), c ∈ [0, 1], so
    // σ ≤ π·A·L·0.5/√N.
    use strahl::scene::Texture;
    let texture = Texture::from_fn("quarter", 8, 8, |x, _| {
        if x < 2 {
            [1.0; 4]
        } else {
            [0.0, 0.0, 0.0, 1.0]
        }
    });
    let mut mean = 0.0;
    let m = 400;
    for i in 0..m {
        for j in 0..m {
            let uv = glam::Vec2::new((i as f32 + 0.5) / m as f32, (j as f32 + 0.5) / m as f32);
            mean += texture.color(uv).r as f64 / (m * m) as f64;
        }
    }
    let mut scene = Scene::empty("textured");
    let tex = scene.add_texture(texture);
    let lamp = scene.add_material(Material {
        emission_texture: Some(tex),
        ..Material::emitter("lamp", Rgb::BLACK, Rgb::splat(2.0))
    });
    scene.add_object("lamp", quad(Vec3::ZERO, Vec3::X, Vec3::NEG_Z), lamp);
    let n = 100_000u64;
    let report = solve(scene, n, 6);
    let expected = PI * 2.0 * mean;
    let sigma = PI * 2.0 * 0.5 / (n as f64).sqrt();
    let got = object(&report, "lamp").emitted_power[0];
    assert!(mean > 0.15 && mean < 0.35, "{mean}");
    assert!(
        (got - expected).abs() < 4.0 * sigma,
        "{got} vs {expected} ± {sigma}"
    );
}

/// A one-sided grey floor lit from its back and a white ceiling over it, under a point light
/// between them.
fn one_sided_floor_lit_from_behind() -> Scene {
    let mut scene = Scene::empty("one-sided");
    let grey = scene.add_material(Material {
        one_sided: true,
        ..Material::diffuse("grey", Rgb::splat(0.5))
    });
    let white = scene.add_material(Material::diffuse("white", Rgb::splat(0.8)));
    // The floor's front faces down: the light above meets its back.
    scene.add_object(
        "floor",
        quad(Vec3::new(-1.0, 0.0, -1.0), Vec3::X * 2.0, Vec3::Z * 2.0),
        grey,
    );
    scene.add_object(
        "roof",
        quad(Vec3::new(-1.0, 2.0, -1.0), Vec3::Z * 2.0, Vec3::X * 2.0),
        white,
    );
    scene.lights.push(Light {
        name: None,
        kind: LightKind::Point {
            position: Vec3::Y,
            intensity: Rgb::splat(1.0),
        },
    });
    scene
}

#[test]
fn a_one_sided_surface_absorbs_what_reaches_its_back_as_radiosity_counts_it() {
    let report = solve(one_sided_floor_lit_from_behind(), 400_000, 2);
    let floor = object(&report, "floor");
    // Everything that reaches the back is absorbed and nothing reflected, as the radiosity
    // solvers' back element of a one-sided material (reflectance 0) has it.
    assert_eq!(floor.reflected_power, Rgb64::BLACK);
    assert_eq!(floor.absorbed_power, floor.incident_power);
    let world = Arc::new(World::new(one_sided_floor_lit_from_behind(), AccelKind::Bvh).unwrap());
    let (system, solution) = strahl::radiosity::solve::hierarchical::solve_hierarchical(
        &world,
        strahl::radiosity::solve::SystemOptions::default(),
        &Default::default(),
        &NoProgress,
        &Cancel::new(),
    )
    .unwrap();
    let radiosity = Report::new("one-sided", &solution.measurement(&system));
    let expected = object(&radiosity, "floor").incident_power.g;
    let got = floor.incident_power.g;
    let se = floor.incident_power_standard_error.unwrap().g;
    assert!(
        (got - expected).abs() < 0.01 * expected + 4.0 * se,
        "light model {got} ± {se} W, hierarchical radiosity {expected} W"
    );
    assert_eq!(object(&radiosity, "floor").reflected_power, Rgb64::BLACK);
}
