//! `strahl view` as a browser meets it: the page, the scene, the lit mesh, the links and
//! the readings along rays over HTTP, against the furnace's closed form; moves re-solved as
//! a solve from scratch of the moved scene; refusals of what it does not serve; several
//! clients at once; Ctrl-C; and the page itself in headless Chromium.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// A running `strahl view` and the `host:port` it serves.
struct Viewer {
    child: Child,
    address: String,
}

impl Drop for Viewer {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Starts `strahl view ARGS --port 0 -q` and waits for the address it prints.
fn start(args: &[&str]) -> Viewer {
    let mut child = Command::new(env!("CARGO_BIN_EXE_strahl"))
        .arg("view")
        .args(args)
        .args(["--port", "0", "-q"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let address = line
        .split("http://")
        .nth(1)
        .and_then(|rest| rest.split('/').next())
        .unwrap_or_else(|| panic!("no address in '{line}'"))
        .to_string();
    Viewer { child, address }
}

/// Sends `request` (a whole HTTP request) and returns the status, the headers (lower case)
/// and the body.
fn send(address: &str, request: &str) -> (u16, String, Vec<u8>) {
    let mut stream = TcpStream::connect(address).unwrap();
    stream
        .set_read_timeout(Some(Duration::from_secs(30)))
        .unwrap();
    stream.write_all(request.as_bytes()).unwrap();
    let mut response = Vec::new();
    stream.read_to_end(&mut response).unwrap();
    let split = response
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("a header");
    let head = String::from_utf8_lossy(&response[..split]).to_lowercase();
    let status = head
        .split_whitespace()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .expect("a status");
    (status, head, response[split + 4..].to_vec())
}

/// `method path` over a connection of its own (HTTP/1.0: the body comes whole, never in
/// chunks).
fn request(address: &str, method: &str, path: &str) -> (u16, String, Vec<u8>) {
    send(
        address,
        &format!("{method} {path} HTTP/1.0\r\nHost: {address}\r\n\r\n"),
    )
}

fn get(address: &str, path: &str) -> (u16, String, Vec<u8>) {
    request(address, "GET", path)
}

fn json(body: &[u8]) -> serde_json::Value {
    serde_json::from_slice(body).unwrap()
}

/// Waits until the viewer serves the final solution of every move asked for; returns its
/// status.
fn solved(address: &str) -> serde_json::Value {
    let started = Instant::now();
    let mut version = 0;
    loop {
        let (code, _, body) = get(address, &format!("/api/status?version={version}"));
        assert_eq!(code, 200);
        let status = json(&body);
        assert!(status["error"].is_null(), "{status}");
        if status["stage"] == "final"
            && status["solving"] == false
            && status["solved_moves"] == status["moves"]
        {
            return status;
        }
        version = status["version"].as_u64().unwrap();
        assert!(started.elapsed() < Duration::from_secs(120), "{status}");
    }
}

/// The viewer on a closed unit box emitting L = 2 on both sides with ρ = 0.5 (and `extra`
/// scene-file text), solved by the matrix solver on 4 × 4 patches a face; returns it with
/// the folder of its scene file, named by `label`.
fn furnace(label: &str, extra: &str) -> (Viewer, std::path::PathBuf) {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("strahl-view-{label}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("furnace.toml");
    std::fs::write(
        &scene,
        format!(
            "[camera]\nposition = [0.5, 0.5, 0.5]\nlook_at = [0.5, 0.4, 0.0]\nfov = 90\n\n\
             [materials.glow]\ndiffuse = 0.5\nemission = 2.0\ntwo_sided = true\n\n\
             [[objects]]\nname = \"box\"\ntype = \"box\"\nmaterial = \"glow\"\n\
             min = [0, 0, 0]\nmax = [1, 1, 1]\n\n{extra}"
        ),
    )
    .unwrap();
    let viewer = start(&[
        scene.to_str().unwrap(),
        "--solver",
        "matrix",
        "--mesh-size",
        "levels:2",
    ]);
    solved(&viewer.address);
    (viewer, dir)
}

#[test]
fn inside_the_furnace_a_click_reads_its_closed_form_and_the_mesh_is_whole() {
    // A closed unit box emitting L = 2 on both sides, ρ = 0.5: inside, B = E = πL/(1 − ρ)
    // = 4π W·m⁻², 683·4π lux and 683·4 cd/m².
    let (viewer, _) = furnace("furnace", "");
    let b = 4.0 * std::f64::consts::PI;
    for direction in ["0.3,-1,0.2", "-1,0.1,0.4", "0.1,0.9,-0.2"] {
        let (status, _, body) = get(
            &viewer.address,
            &format!("/api/pick?o=0.5,0.5,0.5&d={direction}"),
        );
        assert_eq!(status, 200);
        let pick = json(&body);
        assert_eq!(pick["hit"], true);
        assert_eq!(pick["object"], "box");
        let lux = pick["illuminance_lux"].as_f64().unwrap();
        assert!((lux / (683.0 * b) - 1.0).abs() < 1e-3, "{direction}: {lux}");
        let luminance = pick["luminance_cd_m2"].as_f64().unwrap();
        assert!(
            (luminance / 2732.0 - 1.0).abs() < 1e-3,
            "{direction}: {luminance}"
        );
    }
    // Looking out of the box's wall from outside, away from it: nothing.
    let (_, _, body) = get(&viewer.address, "/api/pick?o=3,3,3&d=1,1,1");
    assert_eq!(json(&body)["hit"], false);

    let (status, head, mesh) = get(&viewer.address, "/api/mesh");
    assert_eq!(status, 200);
    assert!(head.contains("application/octet-stream"));
    let word = |k: usize| u32::from_le_bytes(mesh[4 * k..4 * k + 4].try_into().unwrap()) as usize;
    let (vertices, triangles) = (word(0), word(1));
    // Six faces of 4 × 4 patches, two sides each, two triangles per patch.
    assert_eq!(triangles, 6 * 16 * 2 * 2);
    assert_eq!(mesh.len(), 8 + 28 * vertices + 12 * triangles);
    let indices = (8 + 28 * vertices) / 4;
    assert!((0..3 * triangles).all(|k| word(indices + k) < vertices));
    // Every vertex of the inside shows the radiance B/π = 4 W·sr⁻¹·m⁻² (the outside too: it
    // emits and reflects alike, but only what it emits, L = 2, leaves it).
    let radiance =
        |k: usize| f32::from_le_bytes(mesh[8 + 12 * vertices + 4 * k..][..4].try_into().unwrap());
    let values: Vec<f32> = (0..3 * vertices).map(radiance).collect();
    assert!(
        values
            .iter()
            .all(|&v| (v - 4.0).abs() < 4e-3 || (v - 2.0).abs() < 2e-3)
    );
    // And the illuminance per vertex: 683·4π lux inside, nothing arriving outside.
    let lux =
        |k: usize| f32::from_le_bytes(mesh[8 + 24 * vertices + 4 * k..][..4].try_into().unwrap());
    let inside = (683.0 * b) as f32;
    assert!((0..vertices).all(|k| (lux(k) / inside - 1.0).abs() < 1e-3 || lux(k) == 0.0));
    assert_eq!(
        (0..vertices).filter(|&k| lux(k) > 0.0).count(),
        vertices / 2
    );
    // The page's false-colour range holds the brightest vertex.
    let (_, _, scene) = get(&viewer.address, "/api/scene");
    let range = &json(&scene)["false_color"]["range"];
    assert_eq!(
        (range[0].as_f64(), range[1].as_f64()),
        (Some(0.0), Some(10_000.0))
    );
}

/// The parts of an `/api/solution` answer: each its length (u32, little-endian), its bytes
/// and zeros to a multiple of four.
fn parts(mut answer: &[u8]) -> Vec<Vec<u8>> {
    let mut parts = Vec::new();
    while !answer.is_empty() {
        let length = u32::from_le_bytes(answer[..4].try_into().unwrap()) as usize;
        parts.push(answer[4..4 + length].to_vec());
        let padded = 4 + length.next_multiple_of(4);
        assert!(answer[4 + length..padded].iter().all(|&b| b == 0));
        answer = &answer[padded..];
    }
    parts
}

#[test]
fn one_request_brings_the_status_and_what_is_new_of_the_latest_solution() {
    let (viewer, _) = furnace("news", "");
    let address = viewer.address.as_str();
    let status = json(&get(address, "/api/status").2);
    let version = status["version"].as_u64().unwrap();
    let mesh_version = status["mesh_version"].as_u64().unwrap();
    let [scene, mesh, lightmaps] = ["/api/scene", "/api/mesh", "/api/lightmaps"].map(|path| {
        let (code, _, body) = get(address, path);
        assert_eq!(code, 200, "{path}");
        body
    });
    // A page that has nothing: the status, then the scene, mesh and lightmaps as served
    // one by one.
    let (code, head, answer) = get(address, "/api/solution");
    assert_eq!(code, 200);
    assert!(head.contains("application/octet-stream"));
    let all = parts(&answer);
    assert_eq!(all.len(), 4);
    assert_eq!(json(&all[0])["version"].as_u64(), Some(version));
    assert_eq!((&all[1], &all[2], &all[3]), (&scene, &mesh, &lightmaps));
    // A page that has an earlier solution with this mesh: the status and the scene only.
    let earlier = format!("/api/solution?after={}&mesh={mesh_version}", version - 1);
    let news = parts(&get(address, &earlier).2);
    assert_eq!((news.len(), &news[1]), (2, &scene));
    // A page that has this solution: nothing new comes within the wait (two seconds), then
    // the status alone.
    let started = Instant::now();
    let news = parts(
        &get(
            address,
            &format!("/api/solution?after={version}&mesh={mesh_version}"),
        )
        .2,
    );
    assert!(started.elapsed() >= Duration::from_millis(1900));
    assert_eq!(news.len(), 1);
    assert_eq!(json(&news[0])["version"].as_u64(), Some(version));
    for query in ["after=x", "mesh=-1", "version=1"] {
        assert_eq!(
            get(address, &format!("/api/solution?{query}")).0,
            400,
            "{query}"
        );
    }
}

#[test]
fn it_serves_its_page_and_scene_refuses_everything_else_and_keeps_serving() {
    let viewer = start(&["cornell"]);
    let address = viewer.address.as_str();
    assert!(address.starts_with("127.0.0.1:"), "{address}");
    solved(address);

    let (status, head, page) = get(address, "/");
    assert_eq!(status, 200);
    assert!(head.contains("text/html"));
    assert!(head.contains("x-content-type-options: nosniff"));
    assert!(head.contains("content-security-policy: default-src 'self'"));
    assert!(String::from_utf8_lossy(&page).contains("<canvas"));
    let (status, head, _) = get(address, "/view.js");
    assert_eq!(status, 200);
    assert!(head.contains("text/javascript"));
    let (status, _, scene) = get(address, "/api/scene");
    assert_eq!(status, 200);
    let scene = json(&scene);
    assert_eq!(scene["name"], "cornell");
    let objects = scene["report"]["objects"].as_array().unwrap();
    assert!(objects.iter().any(|o| o["name"] == "floor"));
    // A click on the floor names it and reads a positive illuminance.
    let (_, _, pick) = get(address, "/api/pick?o=0.278,0.273,-0.8&d=0,-0.3,1");
    let pick = json(&pick);
    assert_eq!(pick["object"], "floor");
    assert!(pick["illuminance_lux"].as_f64().unwrap() > 0.0);

    for path in [
        "/../../etc/passwd",
        "/..%2F..%2Fetc%2Fpasswd",
        "/api/unknown",
        "/assets/view.js",
        "/Cargo.toml",
    ] {
        assert_eq!(get(address, path).0, 404, "{path}");
    }
    assert_eq!(request(address, "POST", "/").0, 405);
    assert_eq!(request(address, "DELETE", "/api/mesh").0, 405);
    assert_eq!(get(address, "/api/move?name=light&by=0,0,0").0, 405);
    for query in [
        "name=nothing&by=0,0,0.1",
        "name=light",
        "name=light&by=1,2",
        "name=light&by=inf,0,0",
        "by=0,0,1",
        "name=light&by=0,0,1&what=3",
    ] {
        let (status, _, body) = request(address, "POST", &format!("/api/move?{query}"));
        assert_eq!(status, 400, "{query}: {}", String::from_utf8_lossy(&body));
    }
    assert_eq!(get(address, "/api/status?version=x").0, 400);
    for query in [
        "o=1,2&d=0,0,1",
        "o=0,0,0",
        "o=0,0,0&d=0,0,0",
        "o=0,0,0&d=1e-30,0,0",
        "o=nan,0,0&d=0,0,1",
        "x=1",
    ] {
        let (status, _, body) = get(address, &format!("/api/pick?{query}"));
        assert_eq!(status, 400, "{query}: {}", String::from_utf8_lossy(&body));
    }
    assert_eq!(get(address, &format!("/{}", "a".repeat(5000))).0, 414);
    // Garbage instead of a request, and a client that leaves mid-request: still serving.
    let (status, _, _) = send(address, "NONSENSE\r\n\r\n");
    assert!((400..500).contains(&status), "{status}");
    let mut gone = TcpStream::connect(address).unwrap();
    gone.write_all(b"GET /api/mesh HTTP/1.1\r\nHost: x\r\n")
        .unwrap();
    drop(gone);
    // Several clients at once, each given the whole mesh.
    let (_, _, mesh) = get(address, "/api/mesh");
    let clients: Vec<_> = (0..6)
        .map(|_| {
            let address = address.to_string();
            std::thread::spawn(move || get(&address, "/api/mesh"))
        })
        .collect();
    for client in clients {
        let (status, _, body) = client.join().unwrap();
        assert_eq!(status, 200);
        assert_eq!(body, mesh);
    }
}

/// The illuminance read straight down onto the floor at `(x, 0, z)`, lux: by the viewer at
/// `address`.
fn floor_lux(address: &str, x: f64, z: f64) -> f64 {
    let (_, _, body) = get(address, &format!("/api/pick?o={x},0.3,{z}&d=0,-1,0"));
    let pick = json(&body);
    assert_eq!(pick["object"], "floor");
    pick["illuminance_lux"].as_f64().unwrap()
}

#[test]
fn a_move_to_a_position_in_the_furnace_keeps_what_it_cannot_reach_and_the_closed_form() {
    // A small cube of the furnace's own glowing material inside it: B = 4π W·m⁻² on every
    // surface wherever the cube is, so the matrix solved after the cube moved — from the
    // couplings the move did not reach and the solution before — must give it again.
    let cube = "[[objects]]\nname = \"cube\"\ntype = \"box\"\nmaterial = \"glow\"\n\
                min = [0.2, 0.2, 0.2]\nmax = [0.3, 0.3, 0.3]\n";
    let (viewer, _) = furnace("furnace-move", cube);
    let address = viewer.address.as_str();
    // Typed as a position: the cube's centre from (0.25, 0.25, 0.25) to (0.65, 0.35, 0.45).
    let (_, _, scene) = get(address, "/api/scene");
    let scene = json(&scene);
    let at = |scene: &serde_json::Value| {
        let k = scene["movable"]
            .as_array()
            .unwrap()
            .iter()
            .position(|n| n == "cube");
        let position = scene["positions"][k.unwrap()].as_array().unwrap().clone();
        position
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect::<Vec<_>>()
    };
    assert!(
        at(&scene).iter().all(|v| (v - 0.25).abs() < 1e-6),
        "{:?}",
        at(&scene)
    );
    for refused in ["by=0,0,0.1&to=0.5,0.5,0.5", "to=0.5,0.5", "x=1"] {
        let (status, _, _) = request(address, "POST", &format!("/api/move?name=cube&{refused}"));
        assert_eq!(status, 400, "{refused}");
    }
    let (status, _, body) = request(address, "POST", "/api/move?name=cube&to=0.65,0.35,0.45");
    assert_eq!(status, 202, "{}", String::from_utf8_lossy(&body));
    let after = solved(address);
    assert_eq!(after["moves"], 1);
    let (_, _, scene) = get(address, "/api/scene");
    let moved = at(&json(&scene));
    let to = [0.65, 0.35, 0.45];
    assert!(
        moved.iter().zip(to).all(|(v, t)| (v - t).abs() < 1e-6),
        "{moved:?}"
    );
    let (kept, computed) = (
        after["links_kept"].as_u64().unwrap(),
        after["links_computed"].as_u64().unwrap(),
    );
    // The furnace's and the cube's 96 patches (192 elements) each: every pair with a cube
    // element is computed again, and most of the walls' pairs kept.
    let walls = 192 * 192;
    assert_eq!(kept + computed, 4 * walls);
    assert!(kept > walls / 2, "{kept} kept, {computed} computed");
    // The couplings around the cube see it by rays: the first solve, before the move, read
    // 0.03–0.18 % above the closed form at these points.
    let b = 4.0 * std::f64::consts::PI;
    for direction in ["0.3,-1,0.2", "-1,0.1,0.4", "0.1,0.9,-0.2", "1,0.3,0.4"] {
        let (_, _, body) = get(address, &format!("/api/pick?o=0.4,0.5,0.4&d={direction}"));
        let lux = json(&body)["illuminance_lux"].as_f64().unwrap();
        assert!((lux / (683.0 * b) - 1.0).abs() < 3e-3, "{direction}: {lux}");
    }
}

/// The same by a solve from scratch of the built-in box with the light moved `by`, at the
/// defaults the viewer solves with.
fn floor_lux_from_scratch(by: glam::Vec3, x: f32, z: f32) -> f64 {
    use strahl::method::{
        AccelKind, Cancel, KeptLinks, Method, NoProgress, RadiositySettings, World,
    };
    let mut scene = strahl::scene::open("cornell", &Default::default()).unwrap();
    scene.move_named("light", by).unwrap();
    let world = std::sync::Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let method = Method::Radiosity(RadiositySettings::default());
    // The viewer's solver from scratch: no links kept from a solve before (the viewer keeps
    // them, which asks for its rays seeded by what the patches are).
    let mut none = KeptLinks::new();
    let outcome =
        strahl::method::run_keeping(&world, &method, &NoProgress, &Cancel::new(), &mut none)
            .unwrap();
    let ray = strahl::method::Ray::new(glam::Vec3::new(x, 0.3, z), glam::Vec3::NEG_Y);
    let hit = outcome
        .radiosity
        .unwrap()
        .probe(Default::default())
        .at(&ray);
    hit.unwrap().illuminance
}

#[test]
fn a_moved_light_is_solved_again_as_a_solve_from_scratch_would() {
    let viewer = start(&["cornell"]);
    let address = viewer.address.as_str();
    let before = solved(address);
    assert_eq!(before["moves"], 0);
    // Under the light's first place.
    let at_first = floor_lux(address, 0.278, 0.28);
    // Two moves in a row (the second stops the solve of the first): the light 10 cm toward
    // the back wall, then 5 cm back.
    for by in ["0,0,0.1", "0,0,-0.05"] {
        let (status, _, body) = request(address, "POST", &format!("/api/move?name=light&by={by}"));
        assert_eq!(status, 202, "{}", String::from_utf8_lossy(&body));
    }
    let after = solved(address);
    assert_eq!(after["moves"], 2);
    assert!(after["final_seconds"].as_f64().unwrap() > 0.0, "{after}");
    let (_, _, scene) = get(address, "/api/scene");
    let scene = json(&scene);
    assert_eq!(
        (scene["moves"].as_u64(), scene["stage"].as_str()),
        (Some(2), Some("final"))
    );
    let moved = floor_lux(address, 0.278, 0.28);
    let from_scratch = floor_lux_from_scratch(glam::Vec3::new(0.0, 0.0, 0.05), 0.278, 0.28);
    // The light moved away from the point: less light there, as a solve from scratch finds.
    assert!(moved < 0.97 * at_first, "{at_first} → {moved}");
    assert!(
        (moved / from_scratch - 1.0).abs() < 0.01,
        "{moved} vs {from_scratch}"
    );
}

#[test]
fn the_links_are_served_with_the_objects_at_their_ends() {
    let viewer = start(&["cornell"]);
    let address = viewer.address.as_str();
    solved(address);
    let (_, _, scene) = get(address, "/api/scene");
    let scene = json(&scene);
    let (shown, total) = (
        scene["links"][0].as_u64().unwrap() as usize,
        scene["links"][1].as_u64().unwrap() as usize,
    );
    assert!(shown > 1000 && shown == total, "{shown} of {total}");
    let objects = scene["objects"].as_array().unwrap().len() as i32;
    let (status, _, links) = get(address, "/api/links");
    assert_eq!(status, 200);
    assert_eq!(links.len(), 4 + 40 * shown);
    let word = |at: usize| <[u8; 4]>::try_from(&links[at..at + 4]).unwrap();
    assert_eq!(u32::from_le_bytes(word(0)) as usize, shown);
    let mut levels = std::collections::BTreeSet::new();
    for k in 0..shown {
        let at = 4 + 40 * k;
        // Both ends inside the box (0.56 m wide, 0.55 m high and deep; a little slack).
        for j in 0..6 {
            let v = f32::from_le_bytes(word(at + 4 * j));
            assert!((-0.01..0.6).contains(&v), "link {k}: {v}");
        }
        for j in [6, 7] {
            let object = i32::from_le_bytes(word(at + 4 * j));
            assert!((-1..objects).contains(&object), "link {k}: object {object}");
        }
        let level = i32::from_le_bytes(word(at + 32));
        let (receiver, emitter) = (
            i32::from_le_bytes(word(at + 24)),
            i32::from_le_bytes(word(at + 28)),
        );
        // A link with a cluster at an end has no level in the patch hierarchy; the box is
        // lit by its emitting surface alone, so no link comes from a lamp, the sun or a sky.
        assert_eq!(level == -1, receiver == -1 || emitter == -1, "link {k}");
        assert_eq!(i32::from_le_bytes(word(at + 36)), -1, "link {k}");
        levels.insert(level);
    }
    // The box's links run between root patches and down several levels of the quadtrees.
    assert!(
        levels.contains(&0) && levels.iter().any(|&l| l >= 3),
        "{levels:?}"
    );
}

#[test]
fn the_links_asked_for_with_a_mesh_are_that_meshs_or_none() {
    let viewer = start(&["cornell"]);
    let address = viewer.address.as_str();
    solved(address);
    let (_, _, scene) = get(address, "/api/scene");
    let mesh = json(&scene)["mesh_version"].as_u64().unwrap();
    let (status, _, latest) = get(address, "/api/links");
    assert_eq!(status, 200);
    let (status, _, of_mesh) = get(address, &format!("/api/links?mesh={mesh}"));
    assert_eq!(status, 200);
    assert_eq!(of_mesh, latest);
    // A page that still draws an older mesh gets no links of a newer one.
    let (status, _, body) = get(address, &format!("/api/links?mesh={}", mesh + 1));
    assert_eq!(status, 409, "{}", String::from_utf8_lossy(&body));
    let (status, _, _) = get(address, "/api/links?mesh=first");
    assert_eq!(status, 400);
}

#[test]
fn the_links_from_the_sun_and_the_sky_are_served() {
    // The canopy's leaves are lit by a sun and a sky (lights 0 and 1): links from both come
    // with the patches' links, their emitter end no object.
    let viewer = start(&["canopy:30"]);
    let address = viewer.address.as_str();
    solved(address);
    let (status, _, links) = get(address, "/api/links");
    assert_eq!(status, 200);
    let word = |at: usize| i32::from_le_bytes(<[u8; 4]>::try_from(&links[at..at + 4]).unwrap());
    let count = word(0) as usize;
    assert_eq!(links.len(), 4 + 40 * count);
    let mut from = [0; 3];
    for k in 0..count {
        let at = 4 + 40 * k;
        let light = word(at + 36);
        assert!((-1..2).contains(&light), "link {k}: light {light}");
        from[(light + 1) as usize] += 1;
        if light >= 0 {
            assert_eq!(
                word(at + 28),
                -1,
                "link {k}: a light's link has no emitting object"
            );
        }
    }
    assert!(
        from.iter().all(|&n| n > 0),
        "patch, sun and sky links: {from:?}"
    );
}

/// The Cornell box's camera view rendered by the viewer (64 × 48 pixels, `&method=…` in
/// `method`, render number `render`, `samples` camera samples per pixel a pass) once it has
/// at least `passes` passes, as served: a PNG read back as linear RGB.
fn render_view(
    address: &str,
    (method, render): (&str, u64),
    samples: u64,
    passes: u64,
) -> strahl::measure::Film {
    let query = format!("o=0.278,0.273,-0.8&t=0.278,0.273,0.2&fov=39.3&size=64,48{method}");
    let (status, _, body) = request(address, "POST", &format!("/api/render?{query}"));
    assert_eq!(status, 202, "{}", String::from_utf8_lossy(&body));
    assert_eq!(json(&body)["render"], render);
    let started = Instant::now();
    let status = loop {
        let (_, _, body) = get(address, "/api/render");
        let status = json(&body);
        assert!(status["error"].is_null(), "{status}");
        if status["passes"].as_u64().unwrap() >= passes {
            break status;
        }
        assert!(started.elapsed() < Duration::from_secs(60), "{status}");
        std::thread::sleep(Duration::from_millis(50));
    };
    assert_eq!(
        status["samples_per_pixel"].as_u64(),
        status["passes"].as_u64().map(|p| samples * p)
    );
    let (code, head, png) = get(address, "/api/render.png");
    assert_eq!(code, 200);
    assert!(head.contains("image/png"));
    let file = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "strahl-view-render-{}-{render}.png",
        std::process::id()
    ));
    std::fs::write(&file, &png).unwrap();
    let film = strahl::image::load(&file).unwrap();
    assert_eq!((film.width(), film.height()), (64, 48));
    film
}

/// Mean luminance of `film`'s pixels in columns `x` and rows `y`.
fn region(film: &strahl::measure::Film, x: std::ops::Range<u32>, y: std::ops::Range<u32>) -> f64 {
    let count = (x.len() * y.len()) as f64;
    let sum: f64 = y
        .flat_map(|y| x.clone().map(move |x| (x, y)))
        .map(|(x, y)| f64::from(film.get(x, y).luminance()))
        .sum();
    sum / count
}

#[test]
fn a_view_is_rendered_by_final_gather_over_the_final_solution() {
    let viewer = start(&["cornell"]);
    let address = viewer.address.as_str();
    solved(address);
    let query = "o=0.278,0.273,-0.8&t=0.278,0.273,0.2&fov=39.3&size=64,48";
    let (status, _, _) = request(address, "POST", &format!("/api/render?{query}&method=x"));
    assert_eq!(status, 400);
    let gathered = render_view(address, ("&method=final-gather", 1), 1, 256);
    let (left, right) = (gathered.get(13, 24), gathered.get(51, 24));
    assert!(left.r > 2.0 * left.g, "left {left:?}");
    assert!(right.g > 2.0 * right.r, "right {right:?}");
    // The same view path-traced: both images are scaled by their own automatic exposure,
    // so the side walls are compared by their share of the floor's light, within 2 %. Both
    // renders run to their end (256 passes, seeded: the same images every run; 256 gathers
    // of 16 rays a pixel against 1,024 paths), measured +1.25 % (red) and +1.11 % (green):
    // the gathered indirect light is the solution's. The ceiling around the lamp is clipped
    // in the PNG.
    let traced = render_view(address, ("&method=pathtrace", 2), 4, 256);
    let walls = |image: &strahl::measure::Film| {
        let floor = region(image, 20..44, 40..47);
        [8..18, 46..56].map(|x| region(image, x, 15..35) / floor)
    };
    for (g, t) in walls(&gathered).into_iter().zip(walls(&traced)) {
        assert!(
            (g / t - 1.0).abs() < 0.02,
            "final gather {g}, path tracing {t}"
        );
    }
    // While a move is being solved there is no final solution of the scene as it is: a
    // final gather is refused then (409), or taken only once that solution is there.
    let (status, _, _) = request(address, "POST", "/api/move?name=light&by=0,0,0.05");
    assert_eq!(status, 202);
    let ask = || {
        request(
            address,
            "POST",
            &format!("/api/render?{query}&method=final-gather"),
        )
    };
    let (status, _, body) = ask();
    let now = json(&get(address, "/api/status").2);
    match status {
        409 => {}
        202 => assert!(now["stage"] == "final" && now["solved_moves"] == 1, "{now}"),
        _ => panic!("{status}: {}", String::from_utf8_lossy(&body)),
    }
    solved(address);
    assert_eq!(ask().0, 202);
}

#[test]
fn a_view_is_rendered_by_path_tracing_pass_after_pass_and_a_move_stops_it() {
    let viewer = start(&["cornell"]);
    let address = viewer.address.as_str();
    solved(address);
    assert_eq!(get(address, "/api/render.png").0, 404);
    for query in [
        "o=0.278,0.273,-0.8&t=0.278,0.273,-0.8&fov=40&size=64,48",
        "o=0.278,0.273,-0.8&t=0.278,0.273,0.2&fov=0&size=64,48",
        "o=0.278,0.273,-0.8&t=0.278,0.273,0.2&fov=40&size=0,48",
        "o=0.278,0.273,-0.8&t=0.278,0.273,0.2&fov=40&size=100000,100000",
        "o=0.278,0.273,-0.8&t=0.278,0.273,0.2&fov=40",
        "o=0.278,0.273,-0.8&t=0.278,0.273,0.2&fov=40&size=64,48&spp=3",
    ] {
        let (status, _, body) = request(address, "POST", &format!("/api/render?{query}"));
        assert_eq!(status, 400, "{query}: {}", String::from_utf8_lossy(&body));
    }
    let film = render_view(address, ("", 1), 4, 2);
    // The red wall on the left, the green one on the right.
    let (left, right) = (film.get(13, 24), film.get(51, 24));
    assert!(left.r > 2.0 * left.g, "left {left:?}");
    assert!(right.g > 2.0 * right.r, "right {right:?}");
    // A move makes the view stale: the render stops.
    let (status, _, _) = request(address, "POST", "/api/move?name=light&by=0,0,0.05");
    assert_eq!(status, 202);
    let started = Instant::now();
    while json(&get(address, "/api/render").2)["running"] == true {
        assert!(started.elapsed() < Duration::from_secs(30));
        std::thread::sleep(Duration::from_millis(50));
    }
}

#[test]
fn ctrl_c_stops_the_server_within_a_second() {
    let mut viewer = start(&["cornell"]);
    assert_eq!(get(&viewer.address, "/").0, 200);
    let sent = Instant::now();
    let kill = Command::new("kill")
        .args(["-INT", &viewer.child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let status = viewer.child.wait().unwrap();
    let took = sent.elapsed();
    assert_eq!(status.code(), Some(130));
    // The workers look at Ctrl-C every 0.2 s; generous against a loaded machine.
    assert!(took < Duration::from_secs(3), "{took:?}");
    assert!(TcpStream::connect(&viewer.address).is_err());
}

/// The Chromium the browser test runs: `STRAHL_CHROMIUM`, or `chromium` on the path
/// (`scripts/test`, the README's test command, installs Debian's).
fn chromium() -> String {
    if let Ok(path) = std::env::var("STRAHL_CHROMIUM") {
        return path;
    }
    let found = Command::new("chromium")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(
        found,
        "the viewer's browser test needs Chromium: run scripts/test (it installs Debian's \
         chromium) or set STRAHL_CHROMIUM"
    );
    "chromium".to_string()
}

/// Runs headless Chromium on `url` with `extra` (what to hand back), the page given ten
/// seconds of its own time to load, fetch and draw (WebGL2 by SwiftShader, no GPU needed).
fn headless(url: &str, profile: &std::path::Path, extra: &[&str]) -> std::process::Output {
    Command::new(chromium())
        .args([
            "--headless=new",
            "--no-sandbox",
            "--use-angle=swiftshader",
            "--enable-unsafe-swiftshader",
            "--window-size=800,600",
            "--virtual-time-budget=10000",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(extra)
        .arg(url)
        .output()
        .unwrap()
}

#[test]
fn a_real_browser_runs_the_page_and_draws_the_lit_box() {
    let viewer = start(&["cornell"]);
    solved(&viewer.address);
    let url = format!("http://{}/?still", viewer.address);
    let url_solid = url.clone();
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("strahl-view-browser-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // The page's script ran: it fetched the scene and the mesh and says what it drew.
    let dom = headless(&url, &dir.join("profile-dom"), &["--dump-dom"]);
    let dom = String::from_utf8_lossy(&dom.stdout);
    assert!(dom.contains("strahl view — cornell"), "{dom}");
    assert!(dom.contains("triangles"), "{dom}");
    assert!(!dom.contains("error:"), "{dom}");
    // What it drew: the red wall on the left, the green one on the right, lit.
    let shot = dir.join("view.png");
    let screenshot = format!("--screenshot={}", shot.display());
    headless(&url, &dir.join("profile-shot"), &[&screenshot]);
    let film = strahl::image::load(&shot).unwrap();
    assert_eq!((film.width(), film.height()), (800, 600));
    let pixel = |x: u32, y: u32| film.pixels()[(y * film.width() + x) as usize];
    let (left, right) = (pixel(160, 300), pixel(640, 300));
    assert!(left.r > 3.0 * left.g && left.r > 0.05, "left wall {left:?}");
    assert!(
        right.g > 3.0 * right.r && right.g > 0.05,
        "right wall {right:?}"
    );

    // In false colour (on from the address): the legend shows, and the walls take the
    // scale's colours for their illuminance, no longer red and green.
    let url = format!("{url}&false-color");
    let dom = headless(&url, &dir.join("profile-false-dom"), &["--dump-dom"]);
    let dom = String::from_utf8_lossy(&dom.stdout);
    let legend = dom.split("id=\"legend\"").nth(1).expect("a legend");
    assert!(!legend.starts_with(" hidden"), "{dom}");
    assert!(legend.contains(">lux<"), "{dom}");
    let false_shot = dir.join("false-colour.png");
    let screenshot = format!("--screenshot={}", false_shot.display());
    headless(&url, &dir.join("profile-false-shot"), &[&screenshot]);
    let film = strahl::image::load(&false_shot).unwrap();
    let left = film.pixels()[(300 * film.width() + 160) as usize];
    assert!(
        left.b > left.r || left.g > left.r,
        "left wall in false colour {left:?}"
    );

    // The wireframe and the links drawn over the solid view change much of the picture.
    let solid = strahl::image::load(&shot).ok();
    let differing = |query: &str, profile: &str| {
        let other = dir.join(format!("{profile}.png"));
        let shot = format!("--screenshot={}", other.display());
        headless(
            &format!("{url_solid}&{query}"),
            &dir.join(profile),
            &[&shot],
        );
        let (a, b) = (
            solid.as_ref().unwrap(),
            strahl::image::load(&other).unwrap(),
        );
        let changed = a
            .pixels()
            .iter()
            .zip(b.pixels())
            .filter(|(p, q)| (p.r - q.r).abs() + (p.g - q.g).abs() + (p.b - q.b).abs() > 0.05)
            .count();
        changed as f64 / a.pixels().len() as f64
    };
    let wireframe = differing("wireframe", "profile-wireframe");
    assert!(wireframe > 0.05, "wireframe changed {wireframe}");
    let links = differing("links", "profile-links");
    assert!(links > 0.05, "links changed {links}");
    // Only the links of one level: fewer lines, so less of the picture changes.
    let level = differing("links&level=2", "profile-level");
    assert!(
        level > 0.0 && level < links,
        "links of level 2 changed {level}, all {links}"
    );

    // A click on the floor near the front reads what the solution gives there; after the
    // page moves the light 5 cm toward the back, the same click reads what a solve from
    // scratch of the moved box gives (the page waits for the final solution of the move).
    let read = |query: &str, profile: &str| {
        let dom = headless(
            &format!("{url_solid}&{query}"),
            &dir.join(profile),
            &["--dump-dom"],
        );
        let dom = String::from_utf8_lossy(&dom.stdout).to_string();
        let reading = dom
            .split("id=\"reading\"")
            .nth(1)
            .expect("a reading")
            .to_string();
        let attribute = |name: &str| {
            reading
                .split(&format!("data-{name}=\""))
                .nth(1)
                .and_then(|rest| rest.split('"').next())
                .unwrap_or_else(|| panic!("no data-{name} in {dom}"))
                .to_string()
        };
        let point: Vec<f32> = attribute("point")
            .split(',')
            .map(|v| v.parse().unwrap())
            .collect();
        (
            attribute("object"),
            attribute("lux").parse::<f64>().unwrap(),
            point,
        )
    };
    let (object, before, point) = read("pick=0.5,0.95", "profile-pick");
    assert_eq!(object, "floor");
    let (x, z) = (point[0], point[2]);
    let first = floor_lux_from_scratch(glam::Vec3::ZERO, x, z);
    assert!((before / first - 1.0).abs() < 0.01, "{before} vs {first}");
    let (object, after, moved_point) = read("move=light:0,0,0.05&pick=0.5,0.95", "profile-move");
    assert_eq!(object, "floor");
    assert!(
        moved_point
            .iter()
            .zip(&point)
            .all(|(a, b)| (a - b).abs() < 1e-5)
    );
    let from_scratch = floor_lux_from_scratch(glam::Vec3::new(0.0, 0.0, 0.05), x, z);
    assert!(
        (after / from_scratch - 1.0).abs() < 0.01,
        "{after} vs {from_scratch}"
    );
    assert!(
        after < 0.97 * before,
        "moving the light away: {before} → {after}"
    );
}

#[test]
fn the_page_lists_the_sensors_and_draws_the_chosen_range_with_isolines() {
    // The furnace of the first test (683·4π ≈ 8,583 lux everywhere inside) with a sensor
    // at its centre, facing down.
    let (viewer, dir) = furnace(
        "sensors",
        "[[sensors]]\nname = \"middle\"\nposition = [0.5, 0.5, 0.5]\nnormal = [0, -1, 0]\n",
    );
    let url = format!(
        "http://{}/?still&false-color&range=0,10000&isolines=4",
        viewer.address
    );
    let dom = headless(&url, &dir.join("profile-dom"), &["--dump-dom"]);
    let dom = String::from_utf8_lossy(&dom.stdout);
    // The legend runs over the range asked for, one label per level.
    let legend = dom.split("id=\"legend\"").nth(1).expect("a legend");
    let labels: Vec<&str> = legend
        .split("<div>")
        .filter_map(|part| part.split("</div>").next())
        .filter(|text| text.parse::<f64>().is_ok())
        .collect();
    assert_eq!(labels, ["10000", "7500", "5000", "2500", "0"], "{dom}");
    // The sensor's reading: 683·4π lux.
    let sensors = dom.split("id=\"sensors\"").nth(1).expect("the sensors");
    assert!(sensors.contains("data-count=\"1\""), "{dom}");
    assert!(sensors.contains("middle: 8583 lux"), "{dom}");
}

/// The luminances of `film` (linear) over the pixels `x × y`, row by row.
fn luminances(
    film: &strahl::measure::Film,
    x: std::ops::Range<u32>,
    y: std::ops::Range<u32>,
) -> Vec<f64> {
    y.flat_map(|y| x.clone().map(move |x| (x, y)))
        .map(|(x, y)| f64::from(film.pixels()[(y * film.width() + x) as usize].luminance()))
        .collect()
}

fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len() as f64
}

/// The root mean square of the differences between `a` and `b`, over `b`'s mean.
fn relative_rms_difference(a: &[f64], b: &[f64]) -> f64 {
    let squares: Vec<f64> = a.iter().zip(b).map(|(a, b)| (a - b).powi(2)).collect();
    mean(&squares).sqrt() / mean(b)
}

/// `scene` rendered by `strahl render --method radiosity` as the page shows it in a headless
/// window (800 × 600, the scene camera's field of view, linear tone mapping at +1 EV), into
/// `dir`, read back as linear RGB.
fn rendered_as_the_page(scene: &std::ffi::OsStr, dir: &std::path::Path) -> strahl::measure::Film {
    let rendered = dir.join("rendered.png");
    let status = Command::new(env!("CARGO_BIN_EXE_strahl"))
        .arg("render")
        .arg(scene)
        .args([
            "--method",
            "radiosity",
            "--tonemap",
            "linear",
            "--exposure",
            "1",
        ])
        .args(["--width", "800", "--height", "600", "-q", "-o"])
        .arg(&rendered)
        .status()
        .unwrap();
    assert!(status.success());
    strahl::image::load(&rendered).unwrap()
}

#[test]
fn textured_surfaces_show_their_textures_lit_by_the_solution_through_the_tone_mapping_chosen() {
    let viewer = start(&["cornell-textured"]);
    solved(&viewer.address);
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("strahl-view-textures-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let shot = |query: &str, name: &str| {
        let file = dir.join(format!("{name}.png"));
        let url = format!("http://{}/?still&{query}", viewer.address);
        let screenshot = format!("--screenshot={}", file.display());
        headless(&url, &dir.join(format!("profile-{name}")), &[&screenshot]);
        strahl::image::load(&file).unwrap()
    };
    // Linear tone mapping at +1 EV, as `strahl render` maps the same solution seen from the
    // same camera (the page's window is 800 × 600, its vertical field of view the camera's).
    let textured = shot("tonemap=linear&exposure=1", "textured");
    let flat = shot("tonemap=linear&exposure=1&textures=off", "flat");
    let rendered = rendered_as_the_page(std::ffi::OsStr::new("cornell-textured"), &dir);
    // The checkered floor (front left), clear of the panel: the page shows what the
    // render shows, pixel by pixel within the rasterisers' differences; without the
    // lightmaps the checkers' edges are as sharp as the leaves that resolve them.
    let region = |film: &strahl::measure::Film| luminances(film, 130..390, 520..580);
    let (page, flat, cli) = (region(&textured), region(&flat), region(&rendered));
    let (textured_off, flat_off) = (
        relative_rms_difference(&page, &cli),
        relative_rms_difference(&flat, &cli),
    );
    eprintln!(
        "floor: mean {:.4} on the page, {:.4} rendered; RMS difference from the render \
         {textured_off:.4} with textures, {flat_off:.4} without",
        mean(&page),
        mean(&cli)
    );
    assert!((mean(&page) / mean(&cli) - 1.0).abs() < 0.02);
    assert!(
        textured_off < 0.5 * flat_off,
        "{textured_off} vs {flat_off}"
    );
    // The other tone mappings change the picture as their definitions say: automatic
    // exposure brightens this box (its log-average luminance is under 0.18 / 2), the
    // logarithmic mapping up to the lamp darkens it.
    let floor = |film: &strahl::measure::Film| mean(&region(film));
    let linear = floor(&shot("tonemap=linear", "linear"));
    let auto = floor(&shot("tonemap=auto", "auto"));
    let log = floor(&shot("tonemap=log", "log"));
    eprintln!("floor: linear {linear:.4}, auto {auto:.4}, log {log:.4}");
    assert!(auto > 1.5 * linear, "{auto} vs {linear}");
    assert!(log < 0.8 * linear, "{log} vs {linear}");
}

#[test]
fn surfaces_cut_by_an_alpha_texture_show_their_holes_as_a_render_does() {
    // A dark grille over a lit floor, cut into stripes by a grey mask (white: present,
    // black: cut away; 4 × 1 texels, repeating twice across the grille).
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("strahl-view-cut-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("stripes.pgm"), "P2\n4 1\n255\n255 0 255 0\n").unwrap();
    let scene = dir.join("grille.toml");
    std::fs::write(
        &scene,
        "[camera]\nposition = [0, 2.2, 2.2]\nlook_at = [0, 0, 0]\nfov = 50\n\n\
         [materials.floor]\ndiffuse = 0.8\n\n\
         [materials.grille]\ndiffuse = 0.1\nalpha_texture = \"stripes.pgm\"\n\n\
         [[objects]]\nname = \"floor\"\ntype = \"quad\"\nmaterial = \"floor\"\n\
         vertices = [[-1, 0, 1], [1, 0, 1], [1, 0, -1], [-1, 0, -1]]\n\n\
         [[objects]]\nname = \"grille\"\ntype = \"quad\"\nmaterial = \"grille\"\n\
         vertices = [[-0.6, 0.5, 0.6], [0.6, 0.5, 0.6], [0.6, 0.5, -0.6], [-0.6, 0.5, -0.6]]\n\
         uvs = [[0, 0], [2, 0], [2, 1], [0, 1]]\n\n\
         [[lights]]\nname = \"bulb\"\ntype = \"point\"\nposition = [0.3, 2.5, 0.2]\nintensity = 5\n",
    )
    .unwrap();
    let viewer = start(&[scene.to_str().unwrap()]);
    solved(&viewer.address);
    let shot = dir.join("page.png");
    let url = format!("http://{}/?still&tonemap=linear&exposure=1", viewer.address);
    let screenshot = format!("--screenshot={}", shot.display());
    headless(&url, &dir.join("profile"), &[&screenshot]);
    let page = strahl::image::load(&shot).unwrap();
    let rendered = rendered_as_the_page(scene.as_os_str(), &dir);
    // The grille right of the panel: the floor through its holes, its dark
    // stripes between them, as the render shows them.
    let region = |film: &strahl::measure::Film| luminances(film, 425..560, 150..320);
    let (page, cli) = (region(&page), region(&rendered));
    let off = relative_rms_difference(&page, &cli);
    let bright = |values: &[f64]| {
        let half = 0.5 * values.iter().cloned().fold(0.0, f64::max);
        values.iter().filter(|&&v| v > half).count() as f64 / values.len() as f64
    };
    eprintln!(
        "grille: mean {:.4} on the page, {:.4} rendered; RMS difference {off:.4}; \
         share seen through holes {:.3} on the page, {:.3} rendered",
        mean(&page),
        mean(&cli),
        bright(&page),
        bright(&cli)
    );
    // Measured: means within 1.1 %, shares 0.432 / 0.436, RMS 7.7 % (a grille drawn whole
    // shows no holes; one whose lightmap held the floor's light under its holes showed its
    // stripes lit by the floor's light filtered into them: +21 % in the mean).
    assert!((mean(&page) / mean(&cli) - 1.0).abs() < 0.03);
    assert!((bright(&page) - bright(&cli)).abs() < 0.03);
    assert!(off < 0.15, "{off}");
}
