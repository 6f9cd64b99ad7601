//! What `strahl view` answers: its page and script, the scene (camera, report), the lit
//! mesh, and readings along a ray. Only these paths exist; nothing is read from disk on a
//! request.

use anyhow::Result;
use serde::Serialize;
use std::io::Cursor;
use strahl::method::{LUMINOUS_EFFICACY, Probe, Ray, Shading, SolvedRadiosity};
use strahl::report::Report;

/// The page.
const INDEX: &str = include_str!("assets/index.html");
/// Its script.
const SCRIPT: &str = include_str!("assets/view.js");

/// The share of the surface area whose illuminance the false-colour range holds.
const TOP_QUANTILE: f64 = 0.99;

/// Most bytes of a request's path and query.
const MAX_URL: usize = 2048;

/// Everything the server hands out, made once after the solve.
pub struct ViewState<'s> {
    /// `/api/scene`: the camera and the report, JSON.
    scene: Vec<u8>,
    /// `/api/mesh`: the lit mesh, binary ([`mesh_bytes`]).
    mesh: Vec<u8>,
    /// Readings along rays, for `/api/pick`.
    probe: Probe<'s>,
    /// Object names by index.
    objects: Vec<String>,
}

/// The camera and report the page starts from.
#[derive(Serialize)]
struct SceneInfo<'a> {
    name: &'a str,
    camera: CameraInfo,
    summary: String,
    report: &'a Report,
    false_color: FalseColorInfo,
}

/// The false-colour scale of the page, as `strahl render --false-color` draws it.
#[derive(Serialize)]
struct FalseColorInfo {
    /// Position on the scale (0–1) and sRGB colour (0–255) of each stop.
    stops: Vec<(f32, [u8; 3])>,
    /// The illuminance at the scale's ends, lux: 0 to what 99 % of the area stays at or
    /// below, rounded up (brighter places take the top colour).
    range: (f32, f32),
}

/// The scene camera, scene units and degrees.
#[derive(Serialize)]
struct CameraInfo {
    position: [f32; 3],
    look_at: [f32; 3],
    up: [f32; 3],
    fov_degrees: f32,
}

/// What a pick answers.
#[derive(Serialize)]
struct PickInfo {
    /// Whether the ray met a surface (the rest is absent when it did not).
    hit: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    object: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    point: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    illuminance_lux: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    luminance_cd_m2: Option<f64>,
}

impl<'s> ViewState<'s> {
    /// The state serving `solved` with its `report`, read by `shading`.
    pub fn new(solved: &'s SolvedRadiosity, report: &Report, shading: Shading) -> Result<Self> {
        let scene = &solved.world().scene;
        let c = &scene.camera;
        let (mesh, brightest) = mesh_bytes(solved);
        let info = SceneInfo {
            name: &report.scene,
            camera: CameraInfo {
                position: c.position.to_array(),
                look_at: c.look_at.to_array(),
                up: c.up.to_array(),
                fov_degrees: c.fov_degrees,
            },
            summary: solved.summary(),
            report,
            false_color: FalseColorInfo {
                stops: strahl::image::STOPS.to_vec(),
                range: (0.0, strahl::image::nice_ceiling(brightest)),
            },
        };
        Ok(ViewState {
            scene: serde_json::to_vec(&info)?,
            mesh,
            probe: solved.probe(shading),
            objects: (0..scene.objects.len())
                .map(|k| scene.object_name(k).to_string())
                .collect(),
        })
    }

    /// The answer to `method` on `url`: status, content type and body.
    pub fn respond(&self, method: &tiny_http::Method, url: &str) -> (u16, &'static str, Vec<u8>) {
        let text = |status, body: &str| {
            (
                status,
                "text/plain; charset=utf-8",
                body.as_bytes().to_vec(),
            )
        };
        if !matches!(method, tiny_http::Method::Get | tiny_http::Method::Head) {
            return text(405, "only GET is served\n");
        }
        if url.len() > MAX_URL {
            return text(414, "request too long\n");
        }
        let (path, query) = url.split_once('?').unwrap_or((url, ""));
        match path {
            "/" | "/index.html" => (200, "text/html; charset=utf-8", INDEX.as_bytes().to_vec()),
            "/view.js" => (
                200,
                "text/javascript; charset=utf-8",
                SCRIPT.as_bytes().to_vec(),
            ),
            "/api/scene" => (200, "application/json", self.scene.clone()),
            "/api/mesh" => (200, "application/octet-stream", self.mesh.clone()),
            "/api/pick" => match self.pick(query) {
                Ok(info) => (
                    200,
                    "application/json",
                    serde_json::to_vec(&info).unwrap_or_default(),
                ),
                Err(problem) => text(400, &format!("{problem}\n")),
            },
            _ => text(404, "not found\n"),
        }
    }

    /// `/api/pick?o=X,Y,Z&d=X,Y,Z`: what the ray from `o` along `d` meets.
    fn pick(&self, query: &str) -> Result<PickInfo, String> {
        let mut origin = None;
        let mut direction = None;
        for pair in query.split('&').filter(|p| !p.is_empty()) {
            let (key, value) = pair
                .split_once('=')
                .ok_or_else(|| format!("'{pair}' is not KEY=VALUE"))?;
            let v = vector(value).ok_or_else(|| format!("{key}: '{value}' is not X,Y,Z"))?;
            match key {
                "o" => origin = Some(v),
                "d" => direction = Some(v),
                _ => return Err(format!("unknown parameter '{key}' (o and d are known)")),
            }
        }
        let (Some(o), Some(d)) = (origin, direction) else {
            return Err(
                "a pick needs o=X,Y,Z (the ray's origin) and d=X,Y,Z (its direction)".into(),
            );
        };
        let Some(d) = d.try_normalize() else {
            return Err("d must have a direction (not zero, not too small to normalise)".into());
        };
        let ray = Ray::new(o, d);
        Ok(match self.probe.at(&ray) {
            None => PickInfo {
                hit: false,
                object: None,
                point: None,
                illuminance_lux: None,
                luminance_cd_m2: None,
            },
            Some(hit) => PickInfo {
                hit: true,
                object: self.objects.get(hit.object as usize).cloned(),
                point: Some(hit.point.to_array()),
                illuminance_lux: Some(hit.illuminance),
                luminance_cd_m2: Some(hit.luminance),
            },
        })
    }
}

/// Three finite numbers `X,Y,Z`.
fn vector(text: &str) -> Option<glam::Vec3> {
    let mut parts = text
        .split(',')
        .map(|p| p.trim().parse::<f32>().ok().filter(|v| v.is_finite()));
    let v = glam::Vec3::new(parts.next()??, parts.next()??, parts.next()??);
    parts.next().is_none().then_some(v)
}

/// The lit mesh as the page reads it, little-endian: the vertex count `V` and triangle count
/// `T` (u32 each), `V` positions (3 × f32, scene units), `V` radiances (3 × f32, the
/// radiosity leaving the vertex over π, W·sr⁻¹·m⁻²), `V` illuminances (f32, lux on the
/// vertex's side), `T` triangles (3 × u32 vertex indices, counter-clockwise from the side
/// the light leaves). Each side of a patch is its own polygon, so both sides show their
/// own light. Also returns the illuminance that 99 % of the surface area stays at or below,
/// lux (the top of the false-colour range: the small, bright patches beside a lamp would
/// squeeze the rest into the scale's lowest colours).
fn mesh_bytes(solved: &SolvedRadiosity) -> (Vec<u8>, f32) {
    let lit = solved.lit_mesh(false);
    let triangles: Vec<[u32; 3]> = lit
        .polygons
        .iter()
        .flat_map(|p| (1..p.len() - 1).map(move |k| [p[0], p[k], p[k + 1]]))
        .collect();
    let lux: Vec<f32> = lit
        .irradiance
        .iter()
        .map(|e| (LUMINOUS_EFFICACY * e.luminance()).max(0.0) as f32)
        .collect();
    let mut out = Vec::with_capacity(8 + lit.positions.len() * 28 + triangles.len() * 12);
    out.extend((lit.positions.len() as u32).to_le_bytes());
    out.extend((triangles.len() as u32).to_le_bytes());
    for p in &lit.positions {
        p.to_array()
            .iter()
            .for_each(|v| out.extend(v.to_le_bytes()));
    }
    for b in &lit.radiosity {
        b.to_f32()
            .to_array()
            .iter()
            .for_each(|v| out.extend((v / std::f32::consts::PI).to_le_bytes()));
    }
    lux.iter().for_each(|v| out.extend(v.to_le_bytes()));
    for t in &triangles {
        t.iter().for_each(|i| out.extend(i.to_le_bytes()));
    }
    // Each vertex stands for a third of its triangles' area (every polygon has its own).
    let mut weight = vec![0.0f64; lux.len()];
    for t in &triangles {
        let [a, b, c] = t.map(|i| lit.positions[i as usize]);
        let third = f64::from((b - a).cross(c - a).length()) / 6.0;
        t.iter().for_each(|&i| weight[i as usize] += third);
    }
    let mut order: Vec<usize> = (0..lux.len()).collect();
    order.sort_by(|&i, &j| lux[i].total_cmp(&lux[j]));
    let total: f64 = weight.iter().sum();
    let mut below = 0.0;
    let top = order
        .iter()
        .find(|&&i| {
            below += weight[i];
            below >= TOP_QUANTILE * total
        })
        .or(order.last())
        .map_or(0.0, |&i| lux[i]);
    (out, top)
}

/// Answers one request and sends the answer; a client gone before it is sent is no error.
pub fn answer(request: tiny_http::Request, state: &ViewState) {
    let (status, content_type, body) = state.respond(request.method(), request.url());
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
