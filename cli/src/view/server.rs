//! What `strahl view` answers: its page and script, the solver's status, the latest
//! solution (scene, lit mesh, links), readings along rays, moves, and renders of a view.
//! Only these paths exist; nothing is read from disk on a request.

use super::Viewer;
use super::rendering::{Refused, Source};
use super::snapshot::Snapshot;
use super::solving::{Move, Status};
use std::io::Cursor;
use std::net::{IpAddr, SocketAddr, TcpListener};
use std::time::Duration;
use strahl::method::Ray;
use strahl::scene::Camera;

/// The page.
const INDEX: &str = include_str!("assets/index.html");
/// Its script.
const SCRIPT: &str = include_str!("assets/view.js");

/// Most bytes of a request's path and query.
const MAX_URL: usize = 2048;

/// The longest a status request waits for a new solution before it answers.
const LONGEST_WAIT: Duration = Duration::from_secs(2);

/// The answer to a request for a solution's part before the first solution.
const NO_SOLUTION: &str = "no solution yet: /api/status tells when there is one\n";

/// An answer: status, content type and body.
type Answer = (u16, &'static str, Vec<u8>);

/// Listens on `bind:port` with Nagle's algorithm off (`TCP_NODELAY`), which the connections
/// it accepts take over where the system passes it on (Linux does). With it on, an answer
/// sent in more than one write (the scene's 12 kB: its header, then its body) waits for the
/// page's delayed acknowledgement, 40 ms on Linux — a third of the time from a move to its
/// light on screen.
pub fn listen(bind: IpAddr, port: u16) -> std::io::Result<TcpListener> {
    use socket2::{Domain, Protocol, Socket, Type};
    let address = SocketAddr::new(bind, port);
    let socket = Socket::new(
        Domain::for_address(address),
        Type::STREAM,
        Some(Protocol::TCP),
    )?;
    // As the standard library's listeners do on Unix: a restarted viewer takes its port
    // again at once.
    #[cfg(unix)]
    socket.set_reuse_address(true)?;
    socket.set_tcp_nodelay(true)?;
    socket.bind(&address.into())?;
    socket.listen(128)?;
    Ok(socket.into())
}

/// A plain-text answer.
fn text(status: u16, body: &str) -> Answer {
    (
        status,
        "text/plain; charset=utf-8",
        body.as_bytes().to_vec(),
    )
}

/// A JSON answer.
fn json(value: &impl serde::Serialize) -> Answer {
    match serde_json::to_vec(value) {
        Ok(body) => (200, "application/json", body),
        Err(e) => text(500, &format!("{e}\n")),
    }
}

/// The answer to `method` on `url`.
pub fn respond(viewer: &Viewer, method: &tiny_http::Method, url: &str) -> Answer {
    if url.len() > MAX_URL {
        return text(414, "request too long\n");
    }
    let (path, query) = url.split_once('?').unwrap_or((url, ""));
    let params = match parameters(query) {
        Ok(params) => params,
        Err(problem) => return text(400, &format!("{problem}\n")),
    };
    match (method, path) {
        (tiny_http::Method::Post, "/api/move") => move_named(viewer, &params),
        (_, "/api/move") => text(405, "a move is a POST\n"),
        (tiny_http::Method::Post, "/api/render") => render(viewer, &params),
        (tiny_http::Method::Get | tiny_http::Method::Head, _) => get(viewer, path, &params),
        _ => text(
            405,
            "only GET is served (and POST to /api/move and /api/render)\n",
        ),
    }
}

/// The answer to a GET of `path` with `params`.
fn get(viewer: &Viewer, path: &str, params: &[(String, String)]) -> Answer {
    let solving = &viewer.solving;
    let solution = |serve: fn(&Snapshot) -> Answer| match solving.snapshot() {
        Some(snapshot) => serve(&snapshot),
        None => text(503, NO_SOLUTION),
    };
    match path {
        "/" | "/index.html" => (200, "text/html; charset=utf-8", INDEX.as_bytes().to_vec()),
        "/view.js" => (
            200,
            "text/javascript; charset=utf-8",
            SCRIPT.as_bytes().to_vec(),
        ),
        "/api/status" => {
            match known(params, &["version"]).and_then(|()| count(params, "version")) {
                Ok(version) => json(&solving.news_after(version, LONGEST_WAIT).0),
                Err(problem) => text(400, &format!("{problem}\n")),
            }
        }
        "/api/solution" => match known(params, &["after", "mesh"])
            .and_then(|()| Ok((count(params, "after")?, count(params, "mesh")?)))
        {
            Ok((after, mesh)) => {
                let (status, latest) = solving.news_after(after, LONGEST_WAIT);
                match news(&status, latest.as_deref(), after, mesh) {
                    Ok(parts) => (200, "application/octet-stream", parts),
                    Err(e) => text(500, &format!("{e}\n")),
                }
            }
            Err(problem) => text(400, &format!("{problem}\n")),
        },
        "/api/scene" => solution(|s| (200, "application/json", s.scene.clone())),
        "/api/mesh" => solution(|s| (200, "application/octet-stream", s.mesh.clone())),
        "/api/lightmaps" => solution(|s| (200, "application/octet-stream", s.lightmaps.clone())),
        "/api/links" => match known(params, &["mesh"]).and_then(|()| count(params, "mesh")) {
            Ok(mesh) => links(solving.snapshot().as_deref(), mesh),
            Err(problem) => text(400, &format!("{problem}\n")),
        },
        "/api/render" => json(&viewer.rendering.status()),
        "/api/render.png" => match viewer.rendering.png() {
            Some(png) => (200, "image/png", png.to_vec()),
            None => text(404, "no image yet: POST /api/render starts one\n"),
        },
        "/api/pick" => match (pick_ray(params), solving.readable()) {
            (Err(problem), _) => text(400, &format!("{problem}\n")),
            (Ok(_), None) => text(503, "no solution yet\n"),
            (Ok(ray), Some(snapshot)) => json(&snapshot.pick(&ray)),
        },
        _ => text(404, "not found\n"),
    }
}

/// `POST /api/move?name=NAME&by=X,Y,Z` or `…&to=X,Y,Z`: moves the object or light `NAME` by
/// the offset, or so that its position (an object's centre, a light's place; `/api/scene`'s
/// `positions`) is the point (scene units), and starts solving anew.
fn move_named(viewer: &Viewer, params: &[(String, String)]) -> Answer {
    let asked = known(params, &["name", "by", "to"]).and_then(|()| {
        let name = value(params, "name").ok_or("a move needs name=NAME (an object or light)")?;
        let point =
            |key: &str, v: &str| vector(v).ok_or_else(|| format!("{key}: '{v}' is not X,Y,Z"));
        let how = match (value(params, "by"), value(params, "to")) {
            (Some(by), None) => Move::By(point("by", by)?),
            (None, Some(to)) => Move::To(point("to", to)?),
            _ => {
                return Err(
                    "a move needs by=X,Y,Z (an offset) or to=X,Y,Z (a position), scene units"
                        .into(),
                );
            }
        };
        Ok((name, how))
    });
    match asked {
        Err(problem) => text(400, &format!("{problem}\n")),
        Ok((name, how)) => match viewer.solving.move_named(name, how) {
            Ok(moves) => {
                // The view rendered before the move is no longer the scene.
                viewer.rendering.stop(moves);
                let (status, kind, body) = json(&serde_json::json!({ "moves": moves }));
                (if status == 200 { 202 } else { status }, kind, body)
            }
            Err(e) => text(400, &format!("{e}\n")),
        },
    }
}

/// `POST /api/render?o=X,Y,Z&t=X,Y,Z&fov=DEGREES&size=W,H[&method=pathtrace|final-gather]`:
/// renders the scene as it is now, seen from `o` looking at `t` (y up) with a vertical field
/// of view of `fov` degrees, `W × H` pixels, by path tracing (the default) or by final
/// gathering over the final solution (409 until the scene as it is now has one); the image
/// refines pass after pass (`GET /api/render`, `GET /api/render.png`).
fn render(viewer: &Viewer, params: &[(String, String)]) -> Answer {
    let asked = known(params, &["o", "t", "fov", "size", "method"]).and_then(|()| {
        let get = |key: &str| value(params, key).ok_or_else(|| format!("a render needs {key}="));
        let point = |key: &str| {
            let v = get(key)?;
            vector(v).ok_or_else(|| format!("{key}: '{v}' is not X,Y,Z"))
        };
        let (position, look_at) = (point("o")?, point("t")?);
        let fov = get("fov")?;
        let fov_degrees = fov
            .parse::<f32>()
            .ok()
            .filter(|f| (1.0..=170.0).contains(f))
            .ok_or_else(|| format!("fov: '{fov}' is not 1 to 170 degrees"))?;
        let size = get("size")?;
        let (width, height) = size
            .split_once(',')
            .and_then(|(w, h)| Some((w.parse::<u32>().ok()?, h.parse::<u32>().ok()?)))
            .ok_or_else(|| format!("size: '{size}' is not W,H (pixels)"))?;
        if (look_at - position).length() < 1e-6 {
            return Err("o and t must differ".to_string());
        }
        Ok(Camera {
            position,
            look_at,
            up: glam::Vec3::Y,
            fov_degrees,
            width,
            height,
        })
    });
    let camera = match asked {
        Ok(camera) => camera,
        Err(problem) => return text(400, &format!("{problem}\n")),
    };
    let (source, moves) = match value(params, "method") {
        None | Some("pathtrace") => {
            let (scene, moves) = viewer.solving.scene();
            (Source::PathTrace(Box::new(scene)), moves)
        }
        Some("final-gather") => match viewer.solving.final_solution() {
            Some(solution) => {
                let moves = solution.moves();
                (Source::FinalGather(solution), moves)
            }
            None => {
                return text(
                    409,
                    "the scene as it is now has no final solution yet: /api/status says when \
                     it has\n",
                );
            }
        },
        Some(other) => {
            return text(
                400,
                &format!("method: '{other}' is not pathtrace or final-gather\n"),
            );
        }
    };
    match viewer.rendering.start(source, camera, moves) {
        Ok(render) => {
            let (status, kind, body) = json(&serde_json::json!({ "render": render }));
            (if status == 200 { 202 } else { status }, kind, body)
        }
        Err(Refused::Size(problem)) => text(400, &format!("{problem}\n")),
        Err(Refused::Moved) => text(
            409,
            "the scene moved while the render was asked for: ask again\n",
        ),
    }
}

/// The query's `KEY=VALUE` pairs (a bare `KEY` has an empty value), percent-decoded.
fn parameters(query: &str) -> Result<Vec<(String, String)>, String> {
    let decode = |s: &str| {
        percent_encoding::percent_decode_str(s)
            .decode_utf8()
            .map(|s| s.into_owned())
            .map_err(|_| format!("'{s}' is not UTF-8 once decoded"))
    };
    query
        .split('&')
        .filter(|p| !p.is_empty())
        .map(|pair| {
            let (key, value) = pair.split_once('=').unwrap_or((pair, ""));
            Ok((decode(key)?, decode(value)?))
        })
        .collect()
}

/// Refuses parameters other than `allowed`.
fn known(params: &[(String, String)], allowed: &[&str]) -> Result<(), String> {
    match params.iter().find(|(k, _)| !allowed.contains(&k.as_str())) {
        Some((key, _)) => Err(format!(
            "unknown parameter '{key}' ({} known)",
            allowed.join(", ")
        )),
        None => Ok(()),
    }
}

/// The count `key`, if given.
fn count(params: &[(String, String)], key: &str) -> Result<Option<u64>, String> {
    value(params, key)
        .map(|v| {
            v.parse::<u64>()
                .map_err(|_| format!("{key}: '{v}' is not a count"))
        })
        .transpose()
}

/// `/api/solution?after=VERSION&mesh=VERSION`: what the page needs to show the latest
/// solution, in one answer (one request where a status and then the scene, mesh and
/// lightmaps took four, each a trip through the browser on the cores the solver works on:
/// 10–25 ms of a move's first light on screen). Parts one after the other, each its length
/// in bytes (u32, little-endian) and its bytes, padded with zeros to a multiple of four:
/// the `status` (JSON, `/api/status`); then, unless the `latest` solution is version
/// `after`, its scene (`/api/scene`); and, unless its mesh is version `mesh`, its mesh and
/// lightmaps (`/api/mesh`, `/api/lightmaps`). Read under one lock: the parts are of one
/// solution.
fn news(
    status: &Status,
    latest: Option<&Snapshot>,
    after: Option<u64>,
    mesh: Option<u64>,
) -> serde_json::Result<Vec<u8>> {
    let mut parts = Vec::new();
    let mut push = |part: &[u8]| {
        parts.extend_from_slice(&(part.len() as u32).to_le_bytes());
        parts.extend_from_slice(part);
        parts.resize(parts.len().next_multiple_of(4), 0);
    };
    push(&serde_json::to_vec(status)?);
    if let Some(latest) = latest.filter(|_| after != Some(status.version)) {
        push(&latest.scene);
        if mesh != Some(latest.mesh_version()) {
            push(&latest.mesh);
            push(&latest.lightmaps);
        }
    }
    Ok(parts)
}

/// `/api/links?mesh=VERSION`: the latest solution's links; with `mesh`, only while its mesh
/// is that version (409 once a newer one came: the page asks with the mesh it draws, so the
/// links drawn are always that mesh's).
fn links(latest: Option<&Snapshot>, mesh: Option<u64>) -> Answer {
    let Some(latest) = latest else {
        return text(503, NO_SOLUTION);
    };
    match mesh.filter(|&m| m != latest.mesh_version()) {
        Some(gone) => text(
            409,
            &format!(
                "mesh {gone} is no longer the latest (mesh {} is): its links are gone\n",
                latest.mesh_version()
            ),
        ),
        None => (200, "application/octet-stream", latest.links.clone()),
    }
}

/// The value of `key`, if given.
fn value<'p>(params: &'p [(String, String)], key: &str) -> Option<&'p str> {
    params
        .iter()
        .find(|(k, _)| k == key)
        .map(|(_, v)| v.as_str())
}

/// The ray of `/api/pick?o=X,Y,Z&d=X,Y,Z`: from `o` along `d`.
fn pick_ray(params: &[(String, String)]) -> Result<Ray, String> {
    known(params, &["o", "d"])?;
    let read = |key: &str| {
        value(params, key)
            .map(|v| vector(v).ok_or_else(|| format!("{key}: '{v}' is not X,Y,Z")))
            .transpose()
    };
    let (Some(o), Some(d)) = (read("o")?, read("d")?) else {
        return Err("a pick needs o=X,Y,Z (the ray's origin) and d=X,Y,Z (its direction)".into());
    };
    let Some(d) = d.try_normalize() else {
        return Err("d must have a direction (not zero, not too small to normalise)".into());
    };
    Ok(Ray::new(o, d))
}

/// Three finite numbers `X,Y,Z`.
fn vector(text: &str) -> Option<glam::Vec3> {
    let mut parts = text
        .split(',')
        .map(|p| p.trim().parse::<f32>().ok().filter(|v| v.is_finite()));
    let v = glam::Vec3::new(parts.next()??, parts.next()??, parts.next()??);
    parts.next().is_none().then_some(v)
}

/// Answers one request and sends the answer; a client gone before it is sent is no error.
pub fn answer(request: tiny_http::Request, viewer: &Viewer) {
    let (status, content_type, body) = respond(viewer, request.method(), request.url());
    let header = |name: &str, value: &str| {
        tiny_http::Header::from_bytes(name.as_bytes(), value.as_bytes()).expect("a valid header")
    };
    let length = body.len();
    let response = tiny_http::Response::new(
        tiny_http::StatusCode(status),
        vec![
            header("Content-Type", content_type),
            header("X-Content-Type-Options", "nosniff"),
            header("Cache-Control", "no-store"),
            header(
                "Content-Security-Policy",
                "default-src 'self'; style-src 'self' 'unsafe-inline'",
            ),
        ],
        Cursor::new(body),
        Some(length),
        None,
    );
    // The client may have gone (a closed tab): nothing to do about it.
    let _ = request.respond(response);
}
