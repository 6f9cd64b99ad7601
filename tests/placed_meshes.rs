//! Meshes placed many times (a two-level BVH: the mesh's triangles kept once, each placement
//! a transform) against the same scene with every copy's triangles in world space: the same
//! hits ray by ray, the same areas, the same light per object by the light model (within the
//! photons' noise) and by hierarchical radiosity; and the scene file's `placements`.

use glam::{Mat4, Vec3};
use std::sync::Arc;
use strahl::color::Rgb;
use strahl::geometry::{Ray, Transform};
use strahl::method::{
    AccelKind, Cancel, LightTraceSettings, Method, NoProgress, RadiositySettings, SolverKind,
    SurfaceTraceSettings, World, run,
};
use strahl::report::Report;
use strahl::sampling::{Sampler, SequenceKind};
use strahl::scene::{Light, LightKind, Material, PolygonMesh, Scene, Shape, load_str};

/// A small plant: four blades (each two triangles) around the y axis, leaning out, and two
/// more triangles as a crown: ten triangles in one mesh.
fn plant() -> PolygonMesh {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for k in 0..4 {
        let a = k as f32 * std::f32::consts::FRAC_PI_2 + 0.3;
        let (s, c) = a.sin_cos();
        let out = Vec3::new(c, 0.0, s);
        let side = Vec3::new(-s, 0.0, c) * 0.05;
        let base = positions.len() as u32;
        positions.extend([
            -side,
            side,
            out * 0.3 + Vec3::Y * 0.4 + side,
            out * 0.3 + Vec3::Y * 0.4 - side,
        ]);
        triangles.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
    }
    let top = positions.len() as u32;
    positions.extend([
        Vec3::new(-0.1, 0.5, -0.1),
        Vec3::new(0.1, 0.5, -0.1),
        Vec3::new(0.1, 0.5, 0.1),
        Vec3::new(-0.1, 0.55, 0.1),
    ]);
    triangles.extend([[top, top + 1, top + 2], [top, top + 2, top + 3]]);
    PolygonMesh::from_triangles(positions, &triangles)
}

/// A 5 × 5 plot of the plant over grey ground under a low sun and a uniform sky, each copy
/// turned, scaled and one mirrored; the plants share one mesh when `shared`, else each has a
/// copy of its own.
fn plot(shared: bool) -> Scene {
    let mut scene = Scene::empty("plot");
    let ground = scene.add_material(Material::diffuse("ground", Rgb::splat(0.2)));
    let leaf = scene.add_material(Material {
        translucency: Rgb::splat(0.1),
        ..Material::diffuse("leaf", Rgb::new(0.1, 0.4, 0.1))
    });
    scene.add_object(
        "ground",
        Shape::Parallelogram {
            origin: Vec3::new(-0.5, 0.0, 3.0),
            edge_u: Vec3::new(3.0, 0.0, 0.0),
            edge_v: Vec3::new(0.0, 0.0, -3.0),
        },
        ground,
    );
    let mesh = Arc::new(plant());
    for i in 0..25 {
        let (x, z) = ((i % 5) as f32 * 0.5, (i / 5) as f32 * 0.5);
        let mut m = Mat4::from_translation(Vec3::new(x, 0.0, z))
            * Mat4::from_rotation_y(i as f32 * 0.7)
            * Mat4::from_scale(Vec3::splat(0.8 + 0.02 * i as f32));
        if i == 7 {
            m *= Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0));
        }
        let shape = if shared {
            Shape::Mesh(mesh.clone())
        } else {
            Shape::Mesh(Arc::new(plant()))
        };
        scene.add_object(&format!("plant-{i}"), shape, leaf);
        scene.objects.last_mut().unwrap().transform = Transform::from_matrix(m).unwrap();
    }
    scene.lights = vec![
        Light {
            name: Some("sun".into()),
            kind: LightKind::Directional {
                direction: Vec3::new(0.5, -0.6, 0.3).normalize(),
                irradiance: Rgb::splat(800.0),
            },
        },
        Light {
            name: Some("sky".into()),
            kind: LightKind::Sky {
                radiance: Rgb::splat(30.0),
            },
        },
    ];
    scene
}

fn worlds() -> (Arc<World>, Arc<World>) {
    let placed = Arc::new(World::new(plot(true), AccelKind::Bvh).unwrap());
    let copied = Arc::new(World::new(plot(false), AccelKind::Bvh).unwrap());
    (placed, copied)
}

/// The shared mesh is kept once: the placed world holds the ground's two triangles, the
/// plant's ten and 25 placements; the copied one 252 triangles.
#[test]
fn a_shared_mesh_is_kept_once() {
    let (placed, copied) = worlds();
    assert_eq!(placed.geometry.triangle_count(), 2);
    assert_eq!(placed.geometry.placement_count(), 25);
    assert_eq!(placed.geometry.placed_mesh_triangles(), 10);
    assert_eq!(copied.geometry.triangle_count(), 252);
    assert_eq!(copied.geometry.placement_count(), 0);
}

/// Rays from above the plot in random directions downward hit the same object and face at the
/// same distance with the same normal, side and texture coordinates in both worlds (a ray
/// grazing an edge may fall to the other side of it in one of them: at most one in 10⁴).
#[test]
fn placed_meshes_are_hit_where_their_copies_are() {
    let (placed, copied) = worlds();
    let (mut hits, mut differ) = (0, 0);
    let n = 40_000;
    for i in 0..n {
        let mut s = Sampler::new(SequenceKind::Random, 5, i, 0);
        let origin = Vec3::new(
            -0.5 + 3.0 * s.next_1d(),
            0.2 + 0.6 * s.next_1d(),
            -0.5 + 3.0 * s.next_1d(),
        );
        let dir = Vec3::new(s.next_1d() - 0.5, -0.2 - s.next_1d(), s.next_1d() - 0.5).normalize();
        let ray = Ray::new(origin, dir);
        match (placed.intersect(&ray), copied.intersect(&ray)) {
            (Some(a), Some(b)) => {
                let same = a.object == b.object
                    && a.face == b.face
                    && (a.t - b.t).abs() <= 1e-4 * b.t.max(1.0)
                    && a.ng.dot(b.ng) > 0.9999
                    && a.front_face == b.front_face
                    && (a.p - b.p).length() < 1e-4
                    && (a.uv - b.uv).length() < 1e-4;
                hits += 1;
                differ += usize::from(!same);
            }
            (None, None) => {}
            _ => differ += 1,
        }
    }
    assert!(hits > n / 2, "{hits} hits");
    assert!(differ * 10_000 <= n as usize, "{differ} of {n} rays differ");
}

/// The reports of `method` on the placed plants and on their copies.
fn reports(method: &Method) -> (Report, Report) {
    let (placed, copied) = worlds();
    let report = |world: &Arc<World>| {
        let outcome = run(world, method, &NoProgress, &Cancel::new()).unwrap();
        Report::new("plot", outcome.measurement.as_ref().unwrap())
    };
    (report(&placed), report(&copied))
}

/// The light model gives every plant the same light in both worlds within four standard
/// errors of the difference, and the same area.
#[test]
fn the_light_model_sees_placed_meshes_as_their_copies() {
    let method = Method::LightTrace(LightTraceSettings {
        photons: 400_000,
        seed: 3,
        ..Default::default()
    });
    let (a, b) = reports(&method);
    for (x, y) in a.objects.iter().zip(&b.objects) {
        assert_eq!(x.name, y.name);
        let (area_a, area_b) = (x.area.unwrap(), y.area.unwrap());
        assert!((area_a / area_b - 1.0).abs() < 1e-5, "{}", x.name);
        let (ea, eb) = (
            x.incident_power_standard_error.unwrap().g,
            y.incident_power_standard_error.unwrap().g,
        );
        let off = (x.incident_power.g - y.incident_power.g).abs();
        assert!(
            off <= 4.0 * (ea * ea + eb * eb).sqrt(),
            "{}: {} vs {} (σ {ea}, {eb})",
            x.name,
            x.incident_power.g,
            y.incident_power.g
        );
    }
}

/// Hierarchical radiosity meshes the placed plants as their copies and sees the same
/// shadows: every object's absorbed power within 0.5 %.
#[test]
fn radiosity_sees_placed_meshes_as_their_copies() {
    let method = Method::Radiosity(RadiositySettings::new(SolverKind::Hierarchical));
    let (a, b) = reports(&method);
    for (x, y) in a.objects.iter().zip(&b.objects) {
        let (pa, pb) = (x.absorbed_power.g, y.absorbed_power.g);
        assert!((pa / pb - 1.0).abs() < 0.005, "{}: {pa} vs {pb}", x.name);
    }
}

/// The surface tracer puts its points on placed meshes as on their copies and sees the same
/// light: every object's incident power within 2 % and four standard errors of the
/// difference (the points are the same but on a mirrored copy, whose triangles' corners come
/// in another order; measured: all 26 within 0.68 % and 0.56 standard errors).
#[test]
fn the_surface_tracer_sees_placed_meshes_as_their_copies() {
    let method = Method::SurfaceTrace(SurfaceTraceSettings {
        points: 4096,
        ..SurfaceTraceSettings::default()
    });
    let (a, b) = reports(&method);
    assert_eq!(a.objects.len(), 26);
    for (x, y) in a.objects.iter().zip(&b.objects) {
        let (pa, pb) = (x.incident_power.g, y.incident_power.g);
        let sigma = x.incident_power_standard_error.unwrap().g;
        let sigma = sigma.hypot(y.incident_power_standard_error.unwrap().g);
        assert!(
            (pa / pb - 1.0).abs() < 0.02 && (pa - pb).abs() <= 4.0 * sigma,
            "{}: {pa} vs {pb} ± {sigma}",
            x.name
        );
        assert!((x.area.unwrap() / y.area.unwrap() - 1.0).abs() < 1e-5);
    }
}

/// A shared mesh whose faces are all degenerate is not placed (it has no bounds) and adds no
/// primitive: the world builds, and rays miss it.
#[test]
fn a_shared_mesh_of_degenerate_faces_adds_nothing() {
    let flat =
        PolygonMesh::from_triangles(vec![Vec3::ZERO, Vec3::X, Vec3::X * 2.0], &[[0, 1, 2]; 8]);
    let mesh = Arc::new(flat);
    let mut scene = Scene::empty("degenerate");
    let m = scene.add_material(Material::diffuse("m", Rgb::splat(0.5)));
    for i in 0..3 {
        scene.add_object(&format!("flat-{i}"), Shape::Mesh(mesh.clone()), m);
    }
    let world = World::new(scene, AccelKind::Bvh).unwrap();
    assert_eq!(world.geometry.placement_count(), 0);
    assert!(
        world
            .intersect(&Ray::new(Vec3::new(1.0, 1.0, 0.0), -Vec3::Y))
            .is_none()
    );
}

const OBJ: &str = "v -0.05 0 0\nv 0.05 0 0\nv 0.05 0.4 0.3\nv -0.05 0.4 0.3\n\
v 0 0 -0.05\nv 0 0 0.05\nv 0.3 0.4 0.05\nv 0.3 0.4 -0.05\n\
v 0.05 0 0\nv -0.05 0 0\nv -0.05 0.4 -0.3\nv 0.05 0.4 -0.3\n\
v 0 0 0.05\nv 0 0 -0.05\nv -0.3 0.4 -0.05\nv -0.3 0.4 0.05\n\
f 1 2 3 4\nf 5 6 7 8\nf 9 10 11 12\nf 13 14 15 16\n";

/// `placements` in a scene file, inline and from a CSV file: one object per placement named
/// `name[i]`, each placement after the object's own `transform`; bad placements refused at
/// their field, file and line.
#[test]
fn a_scene_file_places_a_mesh_many_times() {
    let dir = std::env::temp_dir().join(format!("strahl-placed-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("plant.obj"), OBJ).unwrap();
    std::fs::write(
        dir.join("field.csv"),
        "x,y,z,degrees,scale\n0,0,0\n1,0,0,90\n0,0,1,45,2\n# a matrix\n1,0,0,3, 0,1,0,0, 0,0,1,3\n",
    )
    .unwrap();
    let scene = |placements: &str| {
        format!(
            "[[objects]]\ntype = \"mesh\"\nname = \"plant\"\nfile = \"plant.obj\"\n\
             transform = [{{ translate = [0, 1, 0] }}]\nplacements = {placements}\n"
        )
    };
    let load = |text: &str| load_str(text, "field.toml", &dir);
    let inline = load(&scene("[[0, 0, 0], [2, 0, 0, 180, 0.5]]")).unwrap();
    let names: Vec<String> = (0..2).map(|i| inline.object_name(i)).collect();
    assert_eq!(names, ["plant[0]", "plant[1]"]);
    let p = |s: &Scene, i: usize, v: Vec3| s.objects[i].transform.point(v);
    assert!((p(&inline, 1, Vec3::X) - Vec3::new(1.5, 0.5, 0.0)).length() < 1e-6);
    let from_csv = load(&scene("\"field.csv\"")).unwrap();
    assert_eq!(from_csv.objects.len(), 4);
    // Lifted by the object's own transform, then doubled, turned 45° about y and moved:
    // (1, 0, 0) → (1, 1, 0) → (2, 2, 0) → (√2, 2, −√2) → (√2, 2, 1 − √2).
    let turned = p(&from_csv, 2, Vec3::X);
    let r = std::f32::consts::SQRT_2;
    assert!(
        (turned - Vec3::new(r, 2.0, 1.0 - r)).length() < 1e-5,
        "{turned}"
    );
    assert!((p(&from_csv, 3, Vec3::ZERO) - Vec3::new(3.0, 1.0, 3.0)).length() < 1e-6);
    // All four share the mesh, and the world places it.
    let world = World::new(from_csv, AccelKind::Bvh).unwrap();
    assert_eq!(world.geometry.placement_count(), 4);
    assert_eq!(world.geometry.placed_mesh_triangles(), 8);
    let error = |text: &str| load(text).unwrap_err().to_string();
    let e = error(&scene("[[1, 2]]"));
    assert!(
        e.contains("objects[0].placements: placement 0: 2 numbers"),
        "{e}"
    );
    let e = error(&scene("[[0, 0, 0, 0, 0]]"));
    assert!(e.contains("singular"), "{e}");
    std::fs::write(dir.join("bad.csv"), "0,0,0\n1,0,oops\n").unwrap();
    let e = error(&scene("\"bad.csv\""));
    assert!(e.contains("bad.csv:2: expected numbers"), "{e}");
    let e = error("[[objects]]\ntype = \"sphere\"\nradius = 1\nplacements = [[0, 0, 0]]\n");
    assert!(e.contains("placements"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}
