//! Malformed scene, mesh and texture files as exporters and hostile users write them: each
//! must end with a non-zero exit and one message naming the file, the line or field at fault
//! and the problem — never a crash, a hang or a scene loaded with parts silently dropped.

mod common;

use common::{strahl, temp};

/// The start of every scene below: a camera and one material.
const HEAD: &str = "[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 0]\n\n\
                    [materials.white]\ndiffuse = 0.7\n\n";

/// What a case loads: a scene file (with `HEAD` in front unless `bare`) and the other files
/// it names.
struct Case {
    name: &'static str,
    scene: String,
    files: Vec<(&'static str, Vec<u8>)>,
    /// What the message must contain: the file, the line or field, the problem.
    says: Vec<&'static str>,
}

fn case(name: &'static str, body: &str, says: &[&'static str]) -> Case {
    Case {
        name,
        scene: format!("{HEAD}{body}"),
        files: Vec::new(),
        says: says.to_vec(),
    }
}

/// A scene whose one object is the mesh file `file` with `content`.
fn mesh(name: &'static str, file: &'static str, content: &[u8], says: &[&'static str]) -> Case {
    Case {
        files: vec![(file, content.to_vec())],
        ..case(
            name,
            &format!("[[objects]]\nname = \"m\"\ntype = \"mesh\"\nfile = \"{file}\"\n"),
            says,
        )
    }
}

/// A scene whose material `t` takes the texture file `file` with `content`.
fn texture(name: &'static str, file: &'static str, content: &[u8], says: &[&'static str]) -> Case {
    Case {
        files: vec![(file, content.to_vec())],
        ..case(
            name,
            &format!("[materials.t]\ndiffuse_texture = \"{file}\"\n"),
            says,
        )
    }
}

const SPHERE: &str = "[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\n";

/// `tests/data/tiny.gltf` with its image replaced by `image` (JSON).
fn tiny_gltf_with_image(image: &str) -> Vec<u8> {
    let mut gltf: serde_json::Value =
        serde_json::from_slice(&std::fs::read("../tests/data/tiny.gltf").unwrap()).unwrap();
    gltf["images"][0] = serde_json::from_str(image).unwrap();
    serde_json::to_vec(&gltf).unwrap()
}

fn cases() -> Vec<Case> {
    let sphere = |rest: &str| format!("{SPHERE}{rest}");
    let quad = |vertices: &str| format!("[[objects]]\ntype = \"quad\"\nvertices = {vertices}\n");
    let light = |body: &str| format!("[[lights]]\n{body}");
    let tri_obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    vec![
        // The scene file's own syntax and fields.
        case("syntax", "[[objects]\ntype = \"sphere\"\n", &[":8:", "unclosed array table"]),
        case("string", "[[objects]]\ntype = \"sphere\n", &[":9:", "invalid basic string"]),
        case("top-level", "[render]\nspp = 4\n", &[":8:", "render", "unknown field `render`"]),
        case("unknown type", "[[objects]]\ntype = \"sphear\"\n", &[":9:", "objects[0].type", "did you mean `sphere`"]),
        case("typo", &sphere("radus = 1\n"), &[":11:", "objects[0].radus", "did you mean `radius`"]),
        case("wrong type", &sphere("radius = \"big\"\n"), &[":11:", "objects[0].radius", "invalid type: string"]),
        case("nan", "[[objects]]\ntype = \"sphere\"\ncenter = [0, nan, 0]\nradius = 1\n", &[":10:", "objects[0].center", "not finite"]),
        case("inf", &sphere("radius = inf\n"), &[":11:", "objects[0].radius", "not finite"]),
        case("negative radius", &sphere("radius = -1\n"), &[":11:", "objects[0].radius", "must be > 0"]),
        case("missing radius", SPHERE, &["objects[0].radius", "missing field"]),
        case("duplicate key", &sphere("radius = 1\nradius = 2\n"), &[":12:", "objects[0].radius", "given twice"]),
        case("duplicate table", "[materials.white]\ndiffuse = 0.5\n", &[":8:", "materials.white", "table is given twice"]),
        case("unknown material", &sphere("radius = 1\nmaterial = \"whte\"\n"), &[":12:", "objects[0].material", "unknown material \"whte\""]),
        case("two-key step", &sphere("radius = 1\ntransform = [{ scale = 2, translate = [1, 0, 0] }]\n"), &[":12:", "objects[0].transform[0]", "exactly one of translate"]),
        case("zero scale", &sphere("radius = 1\ntransform = [{ scale = 0 }]\n"), &[":12:", "objects[0].transform[0]", "scale factor is zero"]),
        case("bowtie", &quad("[[0, 0, 0], [1, 1, 0], [1, 0, 0], [0, 1, 0]]"), &[":10:", "objects[0].vertices", "edges 0–1 and 2–3 cross"]),
        case("three-corner quad", &quad("[[0, 0, 0], [1, 1, 0], [1, 0, 0]]"), &[":10:", "objects[0].vertices", "needs 4 vertices"]),
        case("collinear", &quad("[[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]]"), &[":10:", "objects[0].vertices", "zero area"]),
        case("uv count", &format!("{}uvs = [[0, 0], [1, 0]]\n", quad("[[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]")), &[":11:", "objects[0].uvs", "2 texture coordinates for 4 vertices"]),
        case("colour length", "[materials.x]\ndiffuse = [0.5, 0.5]\n", &[":9:", "materials.x.diffuse", "invalid length 2"]),
        case("negative colour", "[materials.x]\ndiffuse = -0.5\n", &[":9:", "materials.x.diffuse", "must not be negative"]),
        case("reflectance above 1", "[materials.x]\ndiffuse = 1.5\n", &[":9:", "materials.x.diffuse", "must be in [0, 1]"]),
        case("reflects and passes more than 1", "[materials.x]\ndiffuse = 0.6\ntranslucency = 0.5\n", &["materials.x", "diffuse + translucency", "1.100"]),
        case("one-sided translucent", "[materials.x]\none_sided = true\ntranslucency = 0.2\n", &[":10:", "materials.x.translucency", "remove one_sided or translucency"]),
        case("huge emission", "[materials.x]\nemission = 1e38\n", &[":9:", "materials.x.emission", "beyond 1e18"]),
        case("material typo", "[materials.x]\ndifuse = 0.5\n", &[":9:", "materials.x.difuse", "did you mean `diffuse`"]),
        case("unknown light", &light("type = \"laser\"\n"), &[":9:", "lights[0].type", "unknown variant `laser`"]),
        case("light without power", &light("type = \"point\"\nposition = [0, 1, 0]\n"), &["lights[0].intensity", "missing field"]),
        case("negative intensity", &light("type = \"point\"\nposition = [0, 1, 0]\nintensity = -1\n"), &[":11:", "lights[0].intensity", "must not be negative"]),
        case("zero direction", &light("type = \"directional\"\ndirection = [0, 0, 0]\nirradiance = 1\n"), &[":10:", "lights[0].direction", "zero length"]),
        case("sky colour", &light("type = \"sky\"\nradiance = \"blue\"\n"), &[":10:", "lights[0].radiance", "invalid type"]),
        Case { scene: "[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 0]\nfov = 0\n".into(), ..case("fov 0", "", &[":4:", "camera.fov", "(0, 180)"]) },
        Case { scene: "[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 4]\n".into(), ..case("camera on its target", "", &["camera", "degenerate view"]) },
        Case { scene: "[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 0]\nwidth = 0\n".into(), ..case("width 0", "", &[":4:", "camera.width", "at least 1 pixel"]) },
        case("per-face type", &sphere("radius = 1\nper_face = \"yes\"\n"), &[":12:", "objects[0].per_face", "invalid type"]),
        case("missing mesh", "[[objects]]\ntype = \"mesh\"\nfile = \"nowhere.obj\"\n", &[":10:", "objects[0].file", "nowhere.obj", "No such file"]),
        case("missing texture", "[materials.t]\ndiffuse_texture = \"nowhere.png\"\n", &[":9:", "materials.t.diffuse_texture", "nowhere.png"]),
        // OBJ and MTL.
        mesh("obj number", "number.obj", b"v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n", &["objects[0].file", "number.obj", "line 2: v: x is not a number"]),
        mesh("obj nan", "nan.obj", b"v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", &["nan.obj", "line 2: v: nan is not a finite number"]),
        mesh("obj short vertex", "short.obj", b"v 0 0\n", &["short.obj", "line 1: v: 3 numbers expected, got 2"]),
        mesh("obj index", "index.obj", format!("{tri_obj}f 1 2 3\nf 1 2 7\n").as_bytes(), &["index.obj", "line 5: f:", "vertex 7 does not exist (3 given)"]),
        mesh("obj zero index", "zero.obj", format!("{tri_obj}f 0 1 2\n").as_bytes(), &["zero.obj", "line 4: f:", "vertex 0 does not exist"]),
        mesh("obj texture index", "vt.obj", format!("{tri_obj}f 1/4 2/4 3/4\n").as_bytes(), &["vt.obj", "line 4: f:", "texture coordinate 4 does not exist"]),
        mesh("obj two corners", "two.obj", format!("{tri_obj}f 1 2\n").as_bytes(), &["two.obj", "line 4: f: a face needs at least 3 corners"]),
        mesh("obj bowtie", "bowtie.obj", b"# a bowtie\nv 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 4\n", &["bowtie.obj", "line 6: face:", "edges 0–1 and 2–3 cross"]),
        mesh("obj binary", "binary.obj", &(0..=255u8).cycle().take(2048).collect::<Vec<u8>>(), &["binary.obj", "line 1:", "not an OBJ text file"]),
        mesh("obj extension", "mesh.stl", b"solid x\n", &["mesh.stl", "unsupported format"]),
        mesh("obj short normal", "vn.obj", b"vn 0 0\n", &["vn.obj", "line 1: vn: 3 numbers expected"]),
        mesh("obj corner", "corner.obj", format!("{tri_obj}f 1/1/1/1 2 3\n").as_bytes(), &["corner.obj", "line 4: f:", "is not v, v/vt, v//vn or v/vt/vn"]),
        mesh("obj relative index", "relative.obj", format!("{tri_obj}f -1 -2 -4\n").as_bytes(), &["relative.obj", "line 4: f:", "vertex -4 does not exist (3 given so far)"]),
        Case {
            files: vec![
                ("mtl.obj", format!("mtllib nan.mtl\n{tri_obj}usemtl a\nf 1 2 3\n").into_bytes()),
                ("nan.mtl", b"newmtl a\nKd nan 0 0\n".to_vec()),
            ],
            ..case("mtl nan", "[[objects]]\ntype = \"mesh\"\nfile = \"mtl.obj\"\n", &["mtl.obj", "nan.mtl: line 2: Kd: nan is not a finite number"])
        },
        Case {
            files: vec![
                ("tex.obj", format!("mtllib tex.mtl\n{tri_obj}usemtl a\nf 1 2 3\n").into_bytes()),
                ("tex.mtl", b"newmtl a\nmap_Kd nowhere.png\n".to_vec()),
            ],
            ..case("mtl texture", "[[objects]]\ntype = \"mesh\"\nfile = \"tex.obj\"\n", &["tex.obj", "cannot read texture", "nowhere.png\": No such file"])
        },
        // glTF.
        mesh("gltf not json", "junk.gltf", b"{ this is not json", &["junk.gltf"]),
        mesh("gltf version", "v3.gltf", br#"{"asset": {"version": "3.0"}}"#, &["v3.gltf", "asset.version is \"3.0\""]),
        mesh("gltf accessor", "accessor.gltf", br#"{"asset": {"version": "2.0"}, "meshes": [{"primitives": [{"attributes": {"POSITION": 5}}]}]}"#, &["accessor.gltf", "meshes[0].primitives[0].attributes.POSITION: accessor 5 does not exist"]),
        mesh("gltf buffer", "buffer.gltf", br#"{"asset": {"version": "2.0"}, "buffers": [{"byteLength": 12, "uri": "missing.bin"}]}"#, &["buffer.gltf", "buffers[0].uri", "missing.bin"]),
        mesh("glb truncated", "cut.glb", b"glTF\x02\x00\x00\x00\xff\x00\x00\x00", &["cut.glb"]),
        mesh("gltf empty", "empty.gltf", b"", &["empty.gltf"]),
        mesh("gltf image without mime type", "mime.gltf", &tiny_gltf_with_image(r#"{"bufferView": 0}"#), &["mime.gltf", "images[0].mimeType: an image in a buffer view needs its mimeType"]),
        mesh("gltf image past the views", "view.gltf", &tiny_gltf_with_image(r#"{"bufferView": 9, "mimeType": "image/png"}"#), &["view.gltf", "images[0].bufferView: buffer view 9 does not exist (3 views)"]),
        Case {
            files: vec![
                ("bomb.gltf", tiny_gltf_with_image(r#"{"uri": "bomb.ppm"}"#)),
                ("bomb.ppm", b"P6\n20000 20000\n255\n\0\0\0".to_vec()),
            ],
            ..case("gltf image bomb", "[[objects]]\ntype = \"mesh\"\nfile = \"bomb.gltf\"\n", &["bomb.gltf", "image 0", "20000×20000", "texels in all are read"])
        },
        // Textures.
        texture("ppm truncated", "cut.ppm", b"P6\n4 4\n255\nabc", &["materials.t.diffuse_texture", "cut.ppm", "truncated or corrupt"]),
        texture("png empty", "empty.png", b"", &["materials.t.diffuse_texture", "empty.png"]),
        texture("not an image", "text.png", b"hello", &["materials.t.diffuse_texture", "text.png"]),
        texture("pgm bad header", "bad.pgm", b"P5\n-4 4\n255\n", &["materials.t.diffuse_texture", "bad.pgm"]),
    ]
}

#[test]
fn every_malformed_file_is_refused_with_file_place_and_problem() {
    let cases = cases();
    assert!(cases.len() >= 60, "{} cases", cases.len());
    for (k, c) in cases.iter().enumerate() {
        let scene = temp("malformed", &format!("case{k}.toml"));
        std::fs::write(&scene, &c.scene).unwrap();
        for (file, content) in &c.files {
            std::fs::write(temp("malformed", file), content).unwrap();
        }
        let out = strahl(&["info", scene.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{}: {err}", c.name);
        assert!(
            err.starts_with("error: ") && err.contains(&format!("case{k}.toml")),
            "{}: the message names the scene file: {err}",
            c.name
        );
        assert!(!err.contains("panicked"), "{}: {err}", c.name);
        for needle in &c.says {
            assert!(err.contains(needle), "{}: '{needle}' not in: {err}", c.name);
        }
    }
}

#[test]
fn a_folder_given_as_mesh_is_named_as_such() {
    let folder = temp("malformed", "folder.obj");
    std::fs::create_dir_all(&folder).unwrap();
    let scene = temp("malformed", "folder.toml");
    std::fs::write(
        &scene,
        format!("{HEAD}[[objects]]\ntype = \"mesh\"\nfile = \"folder.obj\"\n"),
    )
    .unwrap();
    let out = strahl(&["info", scene.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("folder.obj") && err.contains("it is a folder"),
        "{err}"
    );
}

#[test]
fn empty_scenes_are_refused_by_render_and_solve() {
    let scene = temp("malformed", "empty.toml");
    std::fs::write(&scene, "").unwrap();
    let path = scene.to_str().unwrap();
    let image = temp("malformed", "empty.png");
    for (args, says) in [
        (
            vec!["render", path, "-o", image.to_str().unwrap()],
            "nothing to render",
        ),
        (vec!["solve", path], "no objects"),
    ] {
        let out = strahl(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?}");
        assert!(err.contains("empty.toml") && err.contains(says), "{err}");
    }
}
