//! The path tracer and the light model are independent estimators of the same light: on a
//! diffuse scene (the Cornell box) the path-traced radiance, averaged over an object by
//! surface area and multiplied by π, equals the object's radiosity in the light model's report.
//!
//! Only pixels wholly inside an object are used (outline pixels mix in their neighbours, the
//! light's sixty-fold radiance among them). Leaving the outlines out shifts an object's mean by
//! 1–2 % (its outline is darker than its middle); the test measures that shift on the
//! radiosity display of the same view, whose per-object means are known exactly, and divides
//! it out.

use std::collections::HashMap;
use std::f64::consts::PI;
use std::sync::Arc;
use strahl::accel::AccelKind;
use strahl::light_model::{LightTraceSettings, trace_light};
use strahl::progress::Cancel;
use strahl::progress::NoProgress;
use strahl::radiosity::solve::{
    DisplaySettings, LinkDisplay, MatrixSettings, RadiositySystem, Shading, SystemOptions,
    render_solution, solve_matrix,
};
use strahl::radiosity::{MeshOptions, MeshSize};
use strahl::report::Report;
use strahl::scene::builtin;
use strahl::trace::PathTracer;
use strahl::trace::{ProgressiveSettings, render_progressive};
use strahl::world::World;

#[test]
fn path_traced_radiance_times_pi_is_the_light_models_radiosity() {
    // A wider view than the published camera, so the side walls are seen whole.
    let mut scene = builtin::load("cornell").unwrap().unwrap();
    scene.camera.fov_degrees = 60.0;
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let (w, h) = (256u32, 256u32);
    let settings = ProgressiveSettings {
        width: w,
        height: h,
        samples_per_pixel: 64,
        seed: 3,
        time_limit: None,
    };
    let tracer = PathTracer::new(&world, u32::MAX, 1);
    let image = render_progressive(&world, &tracer, &settings, &NoProgress, &Cancel::new())
        .unwrap()
        .film;
    // Which object every pixel corner sees; pixels whose four corners see the same object lie
    // inside it. Each such pixel stands for the surface area t²·Ω/|cos θ| it covers, with the
    // pixel's solid angle Ω ∝ cos³α (α off the optical axis).
    let camera = world.scene.camera.with_resolution(w, h).rays().unwrap();
    let forward = (world.scene.camera.look_at - world.scene.camera.position).normalize();
    let corner = |x: u32, y: u32| {
        world
            .intersect(&camera.ray(x as f32, y as f32))
            .map(|hit| hit.object)
    };
    // Radiosity solution (16 × 16 patches per face, without contact splits: only its
    // display's outline shift is used) shown with the same camera: B/π per patch.
    let options = SystemOptions {
        mesh: MeshOptions {
            size: MeshSize::Levels(4),
            contact_splits: false,
            ..MeshOptions::default()
        },
        ..SystemOptions::default()
    };
    let system = RadiositySystem::new(&world, options).unwrap();
    let cancel = Cancel::new();
    let solution = solve_matrix(&system, &MatrixSettings::default(), &NoProgress, &cancel).unwrap();
    let radiosity_report = Report::new("cornell", &solution.measurement(&system));
    let display = DisplaySettings {
        links: LinkDisplay::None,
        width: w,
        height: h,
        shading: Shading::Flat,
        wireframe: false,
        samples_per_axis: 1,
    };
    let shown = render_solution(
        &system,
        &solution,
        &world.scene.camera,
        &display,
        &NoProgress,
        &cancel,
    )
    .unwrap();
    // Per object: weighted sums of the path-traced and the displayed radiance, and weights.
    let mut sums: HashMap<u32, ([f64; 3], [f64; 3], f64, usize)> = HashMap::new();
    for py in 0..h {
        for px in 0..w {
            let c = corner(px, py);
            if c.is_none()
                || [
                    corner(px + 1, py),
                    corner(px, py + 1),
                    corner(px + 1, py + 1),
                ]
                .iter()
                .any(|&o| o != c)
            {
                continue;
            }
            let ray = camera.ray(px as f32 + 0.5, py as f32 + 0.5);
            let hit = world.intersect(&ray).unwrap();
            let cos_alpha = ray.dir.dot(forward) as f64;
            let weight =
                (hit.t as f64).powi(2) * cos_alpha.powi(3) / (ray.dir.dot(hit.ng).abs() as f64);
            let e = sums.entry(hit.object).or_default();
            let (traced, displayed) = (image.get(px, py), shown.get(px, py));
            for k in 0..3 {
                e.0[k] += weight * traced[k] as f64;
                e.1[k] += weight * displayed[k] as f64;
            }
            e.2 += weight;
            e.3 += 1;
        }
    }
    let photons = LightTraceSettings {
        photons: 4_000_000,
        seed: 9,
        max_bounces: 1000,
    };
    let out = trace_light(&world, &photons, &NoProgress, &Cancel::new()).unwrap();
    let report = Report::new("cornell", &out.measurement());
    // Objects the camera sees whole (the floor and the back wall are partly hidden by the
    // blocks, whose radiosity differs from the area they hide).
    for name in ["ceiling", "red_wall", "green_wall"] {
        let index = world
            .scene
            .objects
            .iter()
            .position(|o| o.name.as_deref() == Some(name))
            .unwrap() as u32;
        let (traced, displayed, weight, pixels) = sums[&index];
        assert!(pixels > 300, "{name}: only {pixels} pixels");
        let entry = report.objects.iter().find(|o| o.name == name).unwrap();
        let exact = radiosity_report
            .objects
            .iter()
            .find(|o| o.name == name)
            .unwrap();
        let rho =
            world.scene.materials[world.scene.objects[index as usize].material as usize].diffuse;
        let area = entry.area.expect("finite area");
        for k in 0..3 {
            // What leaving out the outline does to the mean, measured on the display.
            let outline_shift = PI * displayed[k] / weight / exact.radiosity.expect("area")[k];
            let from_image = PI * traced[k] / weight / outline_shift;
            // The light model's radiosity as ρ·E from its irradiance (every photon hit counts),
            // and as reflected power over area (noisier where ρ is small).
            let from_irradiance = rho[k] as f64 * entry.incident_power[k] / area;
            let reflected = entry.radiosity.expect("finite area")[k];
            let d1 = from_image / from_irradiance - 1.0;
            let d2 = from_image / reflected - 1.0;
            // Noise: 64 paths per pixel over thousands of pixels, 4·10⁶ photons — well under
            // 0.5 % for ρ·E; the outline correction is good to a few tenths of a percent.
            assert!(
                d1.abs() < 0.01,
                "{name}[{k}]: image {from_image} vs ρE {from_irradiance} ({d1:+.4})"
            );
            assert!(
                d2.abs() < 0.03,
                "{name}[{k}]: image {from_image} vs radiosity {reflected} ({d2:+.4})"
            );
        }
    }
}
