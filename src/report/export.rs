//! Export of a [`LitMesh`] (a radiosity solution, or any lit mesh) as a coloured mesh: binary
//! glTF (`.glb`), glTF with its buffer in a `.bin` file beside it (`.gltf`), or ASCII PLY
//! (`.ply`).
//!
//! Every polygon keeps its own vertices (triangles in glTF, the triangle or quad in PLY),
//! carrying its per-corner radiosity. Polygons are one-sided (a two-sided surface comes as
//! two polygons back to back, each with the radiosity of its side; the glTF material is not
//! `doubleSided`, so viewers show each from its front):
//! - glTF: `COLOR_0` holds the tone-mapped colour (display-linear, in `[0, 1]`: what any
//!   viewer shows; the material is unlit), `COLOR_1` the linear radiosity in W·m⁻² (a
//!   standard attribute that viewers carry along but do not show), plus `POSITION` (scene
//!   units) and `NORMAL`.
//! - PLY: `x y z nx ny nz`, `red green blue` (tone-mapped, sRGB-encoded 8-bit) and
//!   `radiosity_r radiosity_g radiosity_b` (linear, W·m⁻²).
//!
//! Tone mapping acts on the radiance `B/π` of the vertices as on an image's pixels.

use crate::color::{Rgb, linear_to_srgb};
use crate::image::ToneMapping;
use crate::measure::{Film, LitMesh};
use serde_json::json;
use std::f64::consts::PI;
use std::path::Path;

/// glTF component type of 32-bit floats.
const GL_FLOAT: u32 = 5126;
/// glTF component type of 32-bit unsigned integers.
const GL_UNSIGNED_INT: u32 = 5125;
/// Buffer-view target of vertex attributes.
const GL_ARRAY_BUFFER: u32 = 34962;
/// Buffer-view target of indices.
const GL_ELEMENT_ARRAY_BUFFER: u32 = 34963;

/// Mesh file formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExportFormat {
    /// Binary glTF 2.0.
    Glb,
    /// glTF 2.0 JSON with the buffer in `<name>.bin`.
    Gltf,
    /// ASCII PLY.
    Ply,
}

/// Error while exporting.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// The extension is not `.glb`, `.gltf` or `.ply`.
    #[error("{path}: an export file must end in .glb, .gltf or .ply")]
    UnknownFormat {
        /// The path given.
        path: String,
    },
    /// Writing failed.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The cause.
        source: std::io::Error,
    },
}

impl ExportFormat {
    /// The format named by the extension of `path` (any case).
    pub fn from_path(path: &Path) -> Result<Self, ExportError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("glb") => Ok(ExportFormat::Glb),
            Some("gltf") => Ok(ExportFormat::Gltf),
            Some("ply") => Ok(ExportFormat::Ply),
            _ => Err(ExportError::UnknownFormat {
                path: path.display().to_string(),
            }),
        }
    }
}

/// The vertices and polygons written out.
struct ExportMesh {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    radiosity: Vec<[f32; 3]>,
    /// Tone-mapped, display-linear colours in `[0, 1]`.
    colors: Vec<[f32; 3]>,
    /// Vertex indices of each polygon (3 or 4).
    polygons: Vec<Vec<u32>>,
}

/// Writes `lit` to `path` in the format its extension names, with display colours from
/// `tone_mapping` applied to the vertices' radiance `B/π`.
pub fn export_lit_mesh(
    lit: &LitMesh,
    tone_mapping: &ToneMapping,
    path: &Path,
) -> Result<(), ExportError> {
    let format = ExportFormat::from_path(path)?;
    let mesh = build(lit, tone_mapping);
    let io = |source| ExportError::Io {
        path: path.display().to_string(),
        source,
    };
    match format {
        ExportFormat::Ply => std::fs::write(path, ply(&mesh)).map_err(io),
        ExportFormat::Glb => {
            let (json, bin) = gltf_parts(&mesh, None);
            std::fs::write(path, glb(&json, &bin)).map_err(io)
        }
        ExportFormat::Gltf => {
            let bin_path = path.with_extension("bin");
            let bin_name = bin_path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            let (json, bin) = gltf_parts(&mesh, Some(&bin_name));
            std::fs::write(&bin_path, bin).map_err(|source| ExportError::Io {
                path: bin_path.display().to_string(),
                source,
            })?;
            std::fs::write(path, json).map_err(io)
        }
    }
}

fn build(lit: &LitMesh, tone_mapping: &ToneMapping) -> ExportMesh {
    let mut mesh = ExportMesh {
        positions: lit.positions.iter().map(|p| p.to_array()).collect(),
        normals: lit.normals.iter().map(|n| n.to_array()).collect(),
        radiosity: lit
            .radiosity
            .iter()
            .map(|b| b.to_f32().to_array())
            .collect(),
        colors: Vec::new(),
        polygons: lit.polygons.clone(),
    };
    let radiance: Vec<Rgb> = mesh
        .radiosity
        .iter()
        .map(|&b| Rgb::from(b) * (1.0 / PI as f32))
        .collect();
    if let Some(film) = Film::from_pixels(radiance.len() as u32, 1, radiance) {
        mesh.colors = tone_mapping
            .apply(&film)
            .into_iter()
            .map(|c| c.to_array())
            .collect();
    }
    mesh
}

/// The PLY text.
fn ply(mesh: &ExportMesh) -> String {
    let mut out = String::new();
    out.push_str("ply\nformat ascii 1.0\ncomment strahl radiosity solution\n");
    out.push_str(&format!("element vertex {}\n", mesh.positions.len()));
    for p in [
        "float x",
        "float y",
        "float z",
        "float nx",
        "float ny",
        "float nz",
        "uchar red",
        "uchar green",
        "uchar blue",
        "float radiosity_r",
        "float radiosity_g",
        "float radiosity_b",
    ] {
        out.push_str(&format!("property {p}\n"));
    }
    out.push_str(&format!("element face {}\n", mesh.polygons.len()));
    out.push_str("property list uchar uint vertex_indices\nend_header\n");
    for v in 0..mesh.positions.len() {
        let (p, n, b) = (mesh.positions[v], mesh.normals[v], mesh.radiosity[v]);
        let c = mesh.colors[v].map(|x| (linear_to_srgb(x) * 255.0).round().clamp(0.0, 255.0) as u8);
        out.push_str(&format!(
            "{} {} {} {} {} {} {} {} {} {} {} {}\n",
            p[0], p[1], p[2], n[0], n[1], n[2], c[0], c[1], c[2], b[0], b[1], b[2]
        ));
    }
    for poly in &mesh.polygons {
        out.push_str(&poly.len().to_string());
        for i in poly {
            out.push_str(&format!(" {i}"));
        }
        out.push('\n');
    }
    out
}

/// The glTF JSON and its binary buffer; `uri` names the buffer file (`None` for GLB).
fn gltf_parts(mesh: &ExportMesh, uri: Option<&str>) -> (String, Vec<u8>) {
    let indices: Vec<u32> = mesh
        .polygons
        .iter()
        .flat_map(|p| {
            if p.len() == 3 {
                vec![p[0], p[1], p[2]]
            } else {
                vec![p[0], p[1], p[2], p[0], p[2], p[3]]
            }
        })
        .collect();
    let mut bin = Vec::new();
    let mut views = Vec::new();
    let attributes = [
        &mesh.positions,
        &mesh.normals,
        &mesh.colors,
        &mesh.radiosity,
    ];
    for data in attributes {
        let offset = bin.len();
        for v in data.iter() {
            for x in v {
                bin.extend_from_slice(&x.to_le_bytes());
            }
        }
        views.push(
            json!({"buffer": 0, "byteOffset": offset, "byteLength": bin.len() - offset,
            "target": GL_ARRAY_BUFFER}),
        );
    }
    let offset = bin.len();
    for i in &indices {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    views.push(
        json!({"buffer": 0, "byteOffset": offset, "byteLength": bin.len() - offset,
        "target": GL_ELEMENT_ARRAY_BUFFER}),
    );
    let count = mesh.positions.len();
    let (min, max) = mesh.positions.iter().fold(
        ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]),
        |(lo, hi), p| {
            (
                std::array::from_fn(|c| lo[c].min(p[c])),
                std::array::from_fn(|c| hi[c].max(p[c])),
            )
        },
    );
    let vec3 = |view: usize| json!({"bufferView": view, "componentType": GL_FLOAT, "count": count, "type": "VEC3"});
    let mut position = vec3(0);
    position["min"] = json!(min);
    position["max"] = json!(max);
    let mut buffer = json!({"byteLength": bin.len()});
    if let Some(uri) = uri {
        buffer["uri"] = json!(uri);
    }
    let doc = json!({
        "asset": {"version": "2.0", "generator": "strahl radiosity"},
        "extensionsUsed": ["KHR_materials_unlit"],
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "radiosity"}],
        "meshes": [{"name": "radiosity", "primitives": [{
            "attributes": {"POSITION": 0, "NORMAL": 1, "COLOR_0": 2, "COLOR_1": 3},
            "indices": 4, "material": 0, "mode": 4}]}],
        "materials": [{"name": "radiosity", "doubleSided": false,
            "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0],
                "metallicFactor": 0.0, "roughnessFactor": 1.0},
            "extensions": {"KHR_materials_unlit": {}}}],
        "buffers": [buffer],
        "bufferViews": views,
        "accessors": [position, vec3(1), vec3(2), vec3(3),
            {"bufferView": 4, "componentType": GL_UNSIGNED_INT, "count": indices.len(), "type": "SCALAR"}],
    });
    (doc.to_string(), bin)
}

/// A GLB container: 12-byte header, JSON chunk (space-padded), BIN chunk (zero-padded).
fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut json = json.as_bytes().to_vec();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let mut bin = bin.to_vec();
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    for word in [0x4654_6C67, 2, total as u32, json.len() as u32, 0x4E4F_534A] {
        out.extend_from_slice(&u32::to_le_bytes(word));
    }
    out.extend_from_slice(&json);
    for word in [bin.len() as u32, 0x004E_4942] {
        out.extend_from_slice(&u32::to_le_bytes(word));
    }
    out.extend_from_slice(&bin);
    out
}
