//! The TOML scene format, OBJ/MTL and glTF import, and scene-file error messages.

use glam::{Vec2, Vec3};
use std::path::{Path, PathBuf};
use strahl::color::Rgb;
use strahl::scene::{self, LightKind, Scene, SceneError, Shape, Wrap};

/// Tolerance for coordinates computed in f32 from exact inputs.
const EPS: f32 = 1e-5;

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data")
}

fn load(text: &str) -> Result<Scene, SceneError> {
    scene::load_str(text, "scene.toml", &data_dir())
}

fn ok(text: &str) -> Scene {
    load(text).unwrap_or_else(|e| panic!("scene should load: {e}"))
}

fn error(text: &str) -> String {
    match load(text) {
        Ok(_) => panic!("scene should not load:\n{text}"),
        Err(e) => e.to_string(),
    }
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).length() < EPS
}

fn material<'a>(s: &'a Scene, name: &str) -> &'a scene::Material {
    let id = s
        .material_id(name)
        .unwrap_or_else(|| panic!("no material {name}"));
    &s.materials[id as usize]
}

#[test]
fn documented_example_is_in_the_docs_and_loads_with_expected_counts() {
    let example_path = data_dir().join("example.toml");
    let example = std::fs::read_to_string(&example_path).unwrap();
    let docs =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/scene-format.md"))
            .unwrap();
    assert!(
        docs.contains(example.trim_end()),
        "docs/scene-format.md must contain tests/data/example.toml verbatim"
    );

    let s = scene::load(&example_path).unwrap();
    assert_eq!(s.name, "example");
    assert_eq!((s.camera.width, s.camera.height), (320, 240));
    assert!((s.camera.fov_degrees - 50.0).abs() < EPS);
    assert_eq!(s.objects.len(), 16);
    assert_eq!(s.lights.len(), 6);
    // 10 defined + implicit default + "lamp" (tiny.mtl) + "glow" (tiny.gltf); tiny.mtl's
    // "checker" is replaced by the scene's own and its unused "unused" is dropped.
    let names: Vec<&str> = s.materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "white", "red", "light", "glossy", "mirror", "glass", "checker", "poster", "screen",
            "leaf", "default", "lamp", "glow"
        ]
    );
    // checker.ppm linear (shared by "checker" and "screen"), sRGB ("poster"), as alpha
    // ("leaf"), and the image inside tiny.gltf.
    assert_eq!(s.textures.len(), 4);
    let checker = material(&s, "checker");
    assert_eq!(
        checker.diffuse_texture,
        material(&s, "screen").emission_texture
    );
    assert!(checker.one_sided);
    let poster = &s.textures[material(&s, "poster").diffuse_texture.unwrap() as usize];
    assert_eq!(poster.wrap, Wrap::Clamp);
    assert_eq!(
        s.textures[checker.diffuse_texture.unwrap() as usize].wrap,
        Wrap::Repeat
    );
    assert!(material(&s, "light").two_sided);
    assert_eq!(material(&s, "white").diffuse, Rgb::splat(0.75));
    assert_eq!(material(&s, "glass").ior, 1.5);

    assert_eq!(s.object_name(4), "object-4");
    let pillar = &s.objects[8];
    assert_eq!(pillar.material, s.material_id("default").unwrap());
    assert!(matches!(pillar.shape, Shape::Cylinder { caps: false, .. }));
    // "obj sample, white" reports per face; its `material` overrides the MTL materials.
    assert!(s.objects[13].per_face && !s.objects[12].per_face);
    let Shape::Mesh(overridden) = &s.objects[13].shape else {
        panic!("expected a mesh");
    };
    assert!(overridden.face_materials.is_none());
    assert_eq!(s.objects[13].material, s.material_id("white").unwrap());

    match s.lights[0].kind {
        LightKind::Point { intensity, .. } => assert_eq!(intensity, Rgb::splat(5.0)),
        ref other => panic!("expected a point light, got {other:?}"),
    }
    match s.lights[2].kind {
        LightKind::Spot { direction, .. } => {
            let expected = (Vec3::new(0.8, 0.4, 0.2) - Vec3::new(1.5, 2.9, 1.5)).normalize();
            assert!(close(direction, expected));
        }
        ref other => panic!("expected a spot light, got {other:?}"),
    }
    match s.lights[3].kind {
        LightKind::Lambertian { intensity, .. } => assert_eq!(intensity, Rgb::splat(8.0)),
        ref other => panic!("expected a Lambertian light, got {other:?}"),
    }
    match s.lights[4].kind {
        LightKind::Directional { direction, .. } => {
            assert!(close(direction, Vec3::new(-1.0, -2.0, -1.0).normalize()));
        }
        ref other => panic!("expected a directional light, got {other:?}"),
    }
}

#[test]
fn every_object_type_builds_its_shape() {
    let s = ok(r#"
        [[objects]]
        type = "triangle"
        vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
        uvs = [[0, 0], [1, 0], [0, 1]]
        [[objects]]
        type = "polygon"
        vertices = [[0, 0, 0], [2, 0, 0], [3, 1, 0], [1, 2, 0], [-1, 1, 0]]
        [[objects]]
        type = "quad"
        vertices = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
        [[objects]]
        type = "parallelogram"
        origin = [1, 2, 3]
        edge_u = [1, 0, 0]
        edge_v = [0, 0, -1]
        [[objects]]
        type = "mesh"
        file = "tiny.obj"
        [[objects]]
        type = "sphere"
        radius = 2.5
        [[objects]]
        type = "box"
        min = [-1, -2, -3]
        max = [1, 2, 3]
        [[objects]]
        type = "cylinder"
        base = [0, 0, 0]
        top = [0, 2, 0]
        radius = 0.5
        [[objects]]
        type = "cone"
        base = [0, 0, 0]
        apex = [0, 0, 1]
        radius = 0.25
        cap = false
        [[objects]]
        type = "frustum"
        base = [0, 0, 0]
        top = [1, 0, 0]
        base_radius = 1
        top_radius = 0
        [[objects]]
        type = "plane"
        normal = [0, 0, 2]
    "#);
    let kinds: Vec<&str> = s.objects.iter().map(|o| o.shape.kind_name()).collect();
    assert_eq!(
        kinds,
        [
            "triangle",
            "polygon",
            "polygon",
            "parallelogram",
            "mesh",
            "sphere",
            "box",
            "cylinder",
            "cone",
            "frustum",
            "plane"
        ]
    );
    match &s.objects[0].shape {
        Shape::Triangle { vertices, uvs } => {
            assert_eq!(vertices[1], Vec3::X);
            assert_eq!(uvs.unwrap()[2], Vec2::Y);
        }
        other => panic!("{other:?}"),
    }
    match &s.objects[1].shape {
        Shape::Polygon { vertices, uvs } => {
            assert_eq!(vertices.len(), 5);
            assert!(uvs.is_none());
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(&s.objects[2].shape, Shape::Polygon { vertices, .. } if vertices.len() == 4));
    assert_eq!(
        s.objects[3].shape,
        Shape::Parallelogram {
            origin: Vec3::new(1.0, 2.0, 3.0),
            edge_u: Vec3::X,
            edge_v: -Vec3::Z
        }
    );
    assert_eq!(
        s.objects[5].shape,
        Shape::Sphere {
            center: Vec3::ZERO,
            radius: 2.5
        }
    );
    assert_eq!(
        s.objects[6].shape,
        Shape::Box {
            min: Vec3::new(-1.0, -2.0, -3.0),
            max: Vec3::new(1.0, 2.0, 3.0)
        }
    );
    assert_eq!(
        s.objects[7].shape,
        Shape::Cylinder {
            base: Vec3::ZERO,
            top: Vec3::new(0.0, 2.0, 0.0),
            radius: 0.5,
            caps: true
        }
    );
    assert!(matches!(
        s.objects[8].shape,
        Shape::Cone {
            radius: 0.25,
            cap: false,
            ..
        }
    ));
    assert!(matches!(
        s.objects[9].shape,
        Shape::Frustum {
            base_radius: 1.0,
            top_radius: 0.0,
            caps: true,
            ..
        }
    ));
    assert_eq!(
        s.objects[10].shape,
        Shape::Plane {
            point: Vec3::ZERO,
            normal: Vec3::new(0.0, 0.0, 2.0)
        }
    );
    // Every object without a material uses the implicit default (0.8 grey).
    let default = s.material_id("default").unwrap();
    assert_eq!(s.materials[default as usize].diffuse, Rgb::splat(0.8));
    assert!(s.objects.iter().all(|o| o.material == default));
    // Defaults of the camera.
    assert_eq!(s.camera.position, Vec3::new(0.0, 0.0, 5.0));
    assert_eq!((s.camera.width, s.camera.height), (512, 512));
}

#[test]
fn transform_steps_apply_in_the_order_written() {
    let s = ok(r#"
        [[objects]]
        type = "sphere"
        radius = 1
        transform = [{ translate = [1, 0, 0] }, { rotate = { axis = [0, 1, 0], degrees = 90 } }]
        [[objects]]
        type = "sphere"
        radius = 1
        transform = [{ rotate = { axis = [0, 1, 0], degrees = 90 } }, { translate = [1, 0, 0] }]
        [[objects]]
        type = "sphere"
        radius = 1
        transform = [{ scale = 2 }, { scale = [1, 3, 1] }, { matrix = [
            [1, 0, 0, 10],
            [0, 1, 0, 20],
            [0, 0, 1, 30],
            [0, 0, 0, 1],
        ] }]
    "#);
    let p = Vec3::X;
    // Translate to (2, 0, 0), then rotate +90° about y: x → −z.
    assert!(close(
        s.objects[0].transform.point(p),
        Vec3::new(0.0, 0.0, -2.0)
    ));
    // Rotate to (0, 0, −1), then translate.
    assert!(close(
        s.objects[1].transform.point(p),
        Vec3::new(1.0, 0.0, -1.0)
    ));
    assert!(close(
        s.objects[2].transform.point(Vec3::ONE),
        Vec3::new(12.0, 26.0, 32.0)
    ));
    let back = s.objects[2]
        .transform
        .to_object
        .transform_point3(Vec3::new(12.0, 26.0, 32.0));
    assert!(close(back, Vec3::ONE));
}

#[test]
fn obj_quads_stay_quads_and_mtl_materials_map_to_faces() {
    let s = ok(r#"
        [[objects]]
        type = "mesh"
        file = "tiny.obj"
    "#);
    let Shape::Mesh(mesh) = &s.objects[0].shape else {
        panic!("expected a mesh");
    };
    assert_eq!(mesh.face_sizes, vec![4, 3]);
    assert_eq!(mesh.positions.len(), 7);
    assert_eq!(mesh.positions[2], Vec3::new(1.0, 1.0, 0.0));
    assert_eq!(mesh.uvs.as_ref().unwrap()[2], Vec2::new(1.0, 1.0));
    assert_eq!(mesh.normals.as_ref().unwrap()[0], Vec3::Z);
    let faces = mesh.face_materials.as_ref().unwrap();
    let checker = &s.materials[faces[0] as usize];
    let lamp = &s.materials[faces[1] as usize];
    assert_eq!(checker.name, "checker");
    assert_eq!(checker.diffuse, Rgb::splat(0.6));
    // Ks 0.6 is clamped to 1 − Kd = 0.4.
    assert!((checker.specular.r - 0.4).abs() < EPS);
    assert_eq!(checker.shininess, 20.0);
    let texture = &s.textures[checker.diffuse_texture.unwrap() as usize];
    assert_eq!((texture.width, texture.height), (2, 2));
    // Bottom-right texel of checker.ppm, linear (PPM default): 51/255, 102/255, 153/255.
    assert!((texture.texel(1, 1)[2] - 0.6).abs() < 1e-6);
    assert_eq!(lamp.name, "lamp");
    assert_eq!(lamp.emission, Rgb::new(4.0, 3.0, 2.0));
    assert!(s.material_id("unused").is_none());

    // The scene file's definition wins; `material = …` overrides every face.
    let s = ok(r#"
        [materials.checker]
        diffuse = 0.1
        [[objects]]
        type = "mesh"
        file = "tiny.obj"
        [[objects]]
        type = "mesh"
        file = "tiny.obj"
        material = "checker"
    "#);
    let Shape::Mesh(first) = &s.objects[0].shape else {
        panic!("expected a mesh");
    };
    let faces = first.face_materials.as_ref().unwrap();
    assert_eq!(faces[0], s.material_id("checker").unwrap());
    assert_eq!(s.materials[faces[0] as usize].diffuse, Rgb::splat(0.1));
    let Shape::Mesh(second) = &s.objects[1].shape else {
        panic!("expected a mesh");
    };
    assert!(second.face_materials.is_none());
    assert_eq!(s.objects[1].material, s.material_id("checker").unwrap());

    // A missing material library leaves the faces to the object's material.
    let s = ok(r#"
        [[objects]]
        type = "mesh"
        file = "no_mtl.obj"
    "#);
    let Shape::Mesh(mesh) = &s.objects[0].shape else {
        panic!("expected a mesh");
    };
    assert!(mesh.face_materials.is_none());
    assert_eq!(s.objects[0].material, s.material_id("default").unwrap());
}

#[test]
fn gltf_import_applies_node_transforms_and_maps_its_material() {
    let s = ok(r#"
        [[objects]]
        type = "mesh"
        file = "tiny.gltf"
    "#);
    let Shape::Mesh(mesh) = &s.objects[0].shape else {
        panic!("expected a mesh");
    };
    // One quad (two triangles) in each of the two nodes.
    assert_eq!(mesh.triangle_count(), 4);
    assert_eq!(mesh.face_sizes, vec![3; 4]);
    // Parent: translate (0, 0, −1) · scale 2; child: parent · translate (1, 0, 0).
    let expected = [
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(2.0, 0.0, -1.0),
        Vec3::new(2.0, 2.0, -1.0),
        Vec3::new(0.0, 2.0, -1.0),
        Vec3::new(2.0, 0.0, -1.0),
        Vec3::new(4.0, 0.0, -1.0),
        Vec3::new(4.0, 2.0, -1.0),
        Vec3::new(2.0, 2.0, -1.0),
    ];
    assert_eq!(mesh.positions.len(), expected.len());
    for (p, e) in mesh.positions.iter().zip(expected) {
        assert!(close(*p, e), "{p} != {e}");
    }
    assert_eq!(&mesh.indices[..6], &[0, 1, 2, 0, 2, 3]);
    assert_eq!(&mesh.indices[6..], &[4, 5, 6, 4, 6, 7]);
    // glTF texture coordinates have v pointing down; the mesh's point up.
    assert_eq!(mesh.uvs.as_ref().unwrap()[0], Vec2::new(0.0, 0.0));
    assert_eq!(mesh.uvs.as_ref().unwrap()[3], Vec2::new(0.0, 1.0));

    let faces = mesh.face_materials.as_ref().unwrap();
    assert!(faces.iter().all(|&f| f == faces[0]));
    let glow = &s.materials[faces[0] as usize];
    assert_eq!(glow.name, "glow");
    assert_eq!(glow.diffuse, Rgb::new(0.5, 0.25, 0.125));
    // emissiveFactor (1, 0.5, 0) × emissiveStrength 3.
    assert_eq!(glow.emission, Rgb::new(3.0, 1.5, 0.0));
    // alphaMode MASK: the base colour texture's alpha cuts the surface.
    assert_eq!(glow.alpha_texture, glow.diffuse_texture);
    let texture = &s.textures[glow.diffuse_texture.unwrap() as usize];
    assert_eq!(texture.texel(0, 0), [1.0, 0.0, 0.0, 1.0]);
    assert_eq!(texture.texel(1, 0), [0.0, 1.0, 0.0, 0.0]);
}

#[test]
fn syntax_error_names_position_and_field() {
    let e = error("[camera]\nfov = 40\n\n[[objects]]\ntype = \"sphere\"\nradius = 2 2\n");
    assert!(e.starts_with("scene.toml:6:10: objects[0].radius: "), "{e}");
}

#[test]
fn unknown_field_is_named_with_a_suggestion() {
    let e = error("[[objects]]\ntype = \"sphere\"\nradiuss = 2\n");
    assert_eq!(
        e,
        "scene.toml:3:1: objects[0].radiuss: unknown field `radiuss` (did you mean `radius`?)"
    );
    let e = error("[[objects]]\ntype = \"box\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\nradius = 2\n");
    assert_eq!(
        e,
        "scene.toml:5:10: objects[0].radius: field does not apply to type box (its fields: min, max)"
    );
    let e = error("[camera]\nfov = 40\nzoom = 2\n");
    assert!(
        e.starts_with("scene.toml:3:1: camera.zoom: unknown field `zoom`"),
        "{e}"
    );
}

#[test]
fn unknown_material_lists_the_known_ones() {
    let e = error(
        "[materials.white]\ndiffuse = 0.7\n[materials.red]\ndiffuse = [0.6, 0.1, 0.1]\n\n\
         [[objects]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"whte\"\n",
    );
    assert_eq!(
        e,
        "scene.toml:9:12: objects[0].material: unknown material \"whte\" (known: white, red, default)"
    );
}

#[test]
fn negative_radius_is_rejected() {
    let e = error("[[objects]]\ntype = \"sphere\"\nradius = -0.5\n");
    assert_eq!(
        e,
        "scene.toml:3:10: objects[0].radius: radius must be > 0, got -0.5"
    );
}

#[test]
fn non_planar_and_concave_polygons_are_split_into_triangles() {
    for vertices in [
        // 0.1 out of plane over a size of 1.4: split (with a warning).
        "[[0, 0, 0], [1, 0, 0], [1, 1, 0.1], [0, 1, 0]]",
        // An L: concave.
        "[[0, 0, 0], [2, 0, 0], [2, 1, 0], [1, 1, 0], [1, 2, 0], [0, 2, 0]]",
    ] {
        let scene = ok(&format!(
            "[[objects]]\ntype = \"polygon\"\nvertices = {vertices}\n"
        ));
        let Shape::Mesh(mesh) = &scene.objects[0].shape else {
            panic!("{vertices}: {:?}", scene.objects[0].shape);
        };
        assert!(mesh.face_sizes.iter().all(|&n| n == 3), "{vertices}");
        let corners: usize = vertices.matches('[').count() - 1;
        assert_eq!(mesh.face_count(), corners - 2, "{vertices}");
    }
}

#[test]
fn missing_mesh_file_names_the_path() {
    let e = error("[[objects]]\ntype = \"mesh\"\nfile = \"nowhere.obj\"\n");
    assert!(
        e.starts_with("scene.toml:3:8: objects[0].file: cannot read mesh file"),
        "{e}"
    );
    assert!(e.contains("nowhere.obj"), "{e}");
}

#[test]
fn energy_violating_material_is_named() {
    let e = error("[materials.hot]\ndiffuse = 0.7\nmirror = [0.2, 0.4, 0.1]\n");
    assert!(
        e.starts_with("scene.toml:1:12: materials.hot: material \"hot\""),
        "{e}"
    );
    assert!(e.contains("1.100 in the green channel"), "{e}");
}

#[test]
fn singular_matrix_is_rejected() {
    let e = error(
        "[[objects]]\ntype = \"sphere\"\nradius = 1\n\
         transform = [{ translate = [1, 0, 0] }, { matrix = [[1, 0, 0, 0], [0, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]] }]\n",
    );
    assert!(
        e.starts_with("scene.toml:4:41: objects[0].transform[1]: singular matrix"),
        "{e}"
    );
}

#[test]
fn missing_scene_file_names_the_path() {
    let e = scene::load(Path::new("tests/data/absent.toml")).unwrap_err();
    assert!(matches!(e, SceneError::Unreadable { .. }));
    assert!(
        e.to_string()
            .starts_with("tests/data/absent.toml: cannot read scene file")
    );
}

/// `tiny.gltf` changed by `edit`, written to a scratch folder and loaded as a mesh object:
/// the load error.
fn broken_gltf(name: &str, edit: impl FnOnce(&mut serde_json::Value)) -> String {
    let text = std::fs::read_to_string(data_dir().join("tiny.gltf")).unwrap();
    let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
    edit(&mut json);
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("strahl-gltf-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("broken.gltf"), json.to_string()).unwrap();
    let scene = "[[objects]]\ntype = \"mesh\"\nfile = \"broken.gltf\"\n";
    let result = scene::load_str(scene, "scene.toml", &dir);
    std::fs::remove_dir_all(&dir).unwrap();
    match result {
        Ok(_) => panic!("{name}: the broken glTF loaded"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn gltf_accessors_that_would_be_misread_are_refused_with_their_place() {
    // Once a panic inside the glTF reader: positions 4 bytes apart, each 12 bytes long.
    let e = broken_gltf("stride", |j| j["bufferViews"][0]["byteStride"] = 4.into());
    assert!(
        e.contains("broken.gltf") && e.contains("POSITION (accessor 0)"),
        "{e}"
    );
    assert!(e.contains("byteStride 4"), "{e}");
    // Once silently dropped triangles: more indices than the view holds.
    let e = broken_gltf("count", |j| j["accessors"][2]["count"] = 600.into());
    assert!(
        e.contains("indices (accessor 2)") && e.contains("600 elements"),
        "{e}"
    );
    let e = broken_gltf("offset", |j| {
        j["bufferViews"][2]["byteOffset"] = 4000.into()
    });
    assert!(e.contains("runs past its buffer"), "{e}");
    // Once accepted: positions that are not three floats.
    let e = broken_gltf("vec2", |j| j["accessors"][0]["type"] = "VEC2".into());
    assert!(
        e.contains("POSITION") && e.contains("expected Vec3 of F32"),
        "{e}"
    );
    let e = broken_gltf("short", |j| {
        j["accessors"][0]["componentType"] = 5123.into()
    });
    assert!(e.contains("POSITION") && e.contains("U16"), "{e}");
    let e = broken_gltf("version", |j| j["asset"]["version"] = "3.0".into());
    assert!(e.contains("\"3.0\"") && e.contains("2.x"), "{e}");
}

#[test]
fn an_emission_that_would_overflow_is_rejected() {
    // Once rendered as infinite pixels with exit code 0.
    let e = error("[materials.sun]\nemission = 1e38\n");
    assert!(
        e.starts_with("scene.toml:2:12: materials.sun.emission: colour 1e38 is beyond 1e18"),
        "{e}"
    );
}

#[test]
fn a_lambertian_light_is_aimed_by_direction_or_look_at() {
    let scene = ok("[[lights]]\ntype = \"lambertian\"\nposition = [0, 3, 0]\n\
                    look_at = [0, 0, 0]\nintensity = 100\n");
    match scene.lights[0].kind {
        LightKind::Lambertian {
            position,
            direction,
            intensity,
        } => {
            assert!(close(position, Vec3::new(0.0, 3.0, 0.0)));
            assert!(close(direction, Vec3::NEG_Y));
            assert_eq!(intensity, Rgb::splat(100.0));
        }
        ref other => panic!("{other:?}"),
    }
    let e = error("[[lights]]\ntype = \"lambertian\"\nposition = [0, 3, 0]\nintensity = 1\n");
    assert!(
        e.contains("lights[0].direction") && e.contains("type lambertian needs direction"),
        "{e}"
    );
}

#[test]
fn photometric_amounts_convert_exactly() {
    let pi = std::f32::consts::PI;
    let lights = ok(&format!(
        "[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\nintensity_cd = 683\n\n\
         [[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\nflux_lm = {}\n\n\
         [[lights]]\ntype = \"lambertian\"\nposition = [0, 1, 0]\ndirection = [0, -1, 0]\n\
         flux_lm = {}\n\n\
         [[lights]]\ntype = \"spot\"\nposition = [0, 1, 0]\ndirection = [0, -1, 0]\n\
         inner_degrees = 20\nouter_degrees = 30\nflux_lm = {}\n\n\
         [[lights]]\ntype = \"directional\"\ndirection = [0, -1, 0]\nilluminance_lux = 683\n\
         color = [1, 0, 0]\n\n\
         [[lights]]\ntype = \"sky\"\nluminance_cd_m2 = 6830\ncolor = [0.5, 0.5, 0.5]\n\n\
         [materials.panel]\nluminance_cd_m2 = 1366\nemission_color = [0, 1, 0]\n",
        683.0 * 4.0 * pi,
        683.0 * pi,
        683.0 * LightKind::spot_solid_angle(20.0, 30.0),
    ));
    let near = |a: Rgb, b: Rgb| (a.r - b.r).abs() + (a.g - b.g).abs() + (a.b - b.b).abs() < 1e-5;
    for light in &lights.lights[..4] {
        let intensity = match light.kind {
            LightKind::Point { intensity, .. }
            | LightKind::Lambertian { intensity, .. }
            | LightKind::Spot { intensity, .. } => intensity,
            ref other => panic!("{other:?}"),
        };
        assert!(near(intensity, Rgb::WHITE), "{light:?}");
    }
    let LightKind::Directional { irradiance, .. } = lights.lights[4].kind else {
        panic!()
    };
    // 683 lux of pure red: Y = 0.2126·r = 1 W/m².
    assert!(
        near(irradiance, Rgb::new(1.0 / 0.2126, 0.0, 0.0)),
        "{irradiance:?}"
    );
    let LightKind::Sky { radiance } = lights.lights[5].kind else {
        panic!()
    };
    assert!(near(radiance, Rgb::splat(10.0)), "{radiance:?}");
    let panel = &lights.materials[lights.material_id("panel").unwrap() as usize];
    assert!(near(panel.emission, Rgb::new(0.0, 2.0 / 0.7152, 0.0)));
    assert!((panel.emission.luminance() * 683.0 - 1366.0).abs() < 1e-3);

    for (text, says) in [
        (
            "[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\nintensity = 1\nflux_lm = 5\n",
            "lights[0].flux_lm: give one of intensity, intensity_cd, flux_lm, not several",
        ),
        (
            "[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\nintensity = 1\ncolor = [1, 0, 0]\n",
            "lights[0].color: color is the colour of a photometric amount",
        ),
        (
            "[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\nintensity_cd = 5\ncolor = 0\n",
            "lights[0].color: the colour has no luminance",
        ),
        (
            "[[lights]]\ntype = \"point\"\nposition = [0, 1, 0]\nintensity_cd = -5\n",
            "lights[0].intensity_cd: must be a finite number ≥ 0",
        ),
        (
            "[[lights]]\ntype = \"sky\"\nilluminance_lux = 5\n",
            "lights[0].illuminance_lux: field does not apply to type sky",
        ),
        (
            "[materials.m]\nemission = 1\nluminance_cd_m2 = 5\n",
            "materials.m.luminance_cd_m2: give one of emission, luminance_cd_m2",
        ),
    ] {
        let e = error(text);
        assert!(e.contains(says), "{text}: {e}");
    }
}
