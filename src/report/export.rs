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
//!   units) and `NORMAL`. Textured surfaces are a primitive each with their own material:
//!   the lightmap (tone-mapped like the vertex colours, sRGB PNG) is its **emissive texture**
//!   on `TEXCOORD_1`, which three.js, Babylon.js and Blender all show; the material's own
//!   texture is its base-colour texture on `TEXCOORD_0` (repeating or clamped as in the
//!   scene, its alpha the cut-out with `alphaMode: "MASK"`), with a base-colour factor of 0
//!   so that a viewer's own lights add nothing to the baked light. Raising that factor to 1
//!   and removing the emission relights the surface in the viewer.
//! - PLY: `x y z nx ny nz`, `red green blue` (tone-mapped, sRGB-encoded 8-bit) and
//!   `radiosity_r radiosity_g radiosity_b` (linear, W·m⁻²) per vertex; per face its vertices
//!   and `object`, the index of the scene object it lies on (the report's order of objects
//!   when every object has a name of its own).
//!
//! Tone mapping acts on the radiance `B/π` of the vertices as on an image's pixels.

use crate::atomic_file;
use crate::color::{Rgb, linear_to_srgb};
use crate::image::ToneMapping;
use crate::measure::{Film, LitMesh};
use crate::scene::{Texture, TextureId, Wrap};
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
/// Sampler filter: linear.
const GL_LINEAR: u32 = 9729;
/// Sampler wrap: repeat.
const GL_REPEAT: u32 = 10497;
/// Sampler wrap: clamp to edge.
const GL_CLAMP_TO_EDGE: u32 = 33071;

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
    #[error("'{path}': an export file must end in .glb, .gltf or .ply")]
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
    /// True for the formats that carry textures, and so the lightmaps of textured surfaces
    /// (glTF); PLY has vertex colours only.
    pub fn carries_lightmaps(self) -> bool {
        matches!(self, ExportFormat::Glb | ExportFormat::Gltf)
    }

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
    /// Material and lightmap texture coordinates, glTF's way (`(0, 0)` at the image's top
    /// left).
    texcoords: [Vec<[f32; 2]>; 2],
    /// Vertex indices of each polygon (3 or 4).
    polygons: Vec<Vec<u32>>,
    /// Per polygon: its lightmapped surface, if any.
    polygon_surface: Vec<Option<u32>>,
    /// Per polygon: the scene object it lies on (PLY's `object`).
    polygon_object: Vec<u32>,
    /// The lightmapped surfaces.
    surfaces: Vec<ExportSurface>,
}

/// A lightmapped surface written out: its name, its images as RGBA8 (sRGB) with their
/// sizes, and how its base texture wraps.
struct ExportSurface {
    name: String,
    base: Option<Image>,
    cut_out: bool,
    lightmap: Image,
}

/// An 8-bit sRGB RGBA image and how it wraps.
struct Image {
    width: u32,
    height: u32,
    rgba: Vec<u8>,
    wrap: Wrap,
}

/// Writes `lit` to `path` in the format its extension names, with display colours from
/// `tone_mapping` applied to the vertices' radiance `B/π` and the lightmaps' radiance
/// together; `textures` are the scene's, which the lightmapped surfaces name.
pub fn export_lit_mesh(
    lit: &LitMesh,
    textures: &[Texture],
    tone_mapping: &ToneMapping,
    path: &Path,
) -> Result<(), ExportError> {
    let format = ExportFormat::from_path(path)?;
    let mesh = build(lit, textures, tone_mapping);
    let io = |source| ExportError::Io {
        path: path.display().to_string(),
        source,
    };
    match format {
        ExportFormat::Ply => atomic_file::write(path, ply(&mesh).as_bytes()).map_err(io),
        ExportFormat::Glb => {
            let (json, bin) = gltf_parts(&mesh, None);
            atomic_file::write(path, &glb(&json, &bin)).map_err(io)
        }
        ExportFormat::Gltf => {
            let bin_path = path.with_extension("bin");
            let bin_name = bin_path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            let (json, bin) = gltf_parts(&mesh, Some(&bin_name));
            atomic_file::write(&bin_path, &bin).map_err(|source| ExportError::Io {
                path: bin_path.display().to_string(),
                source,
            })?;
            atomic_file::write(path, json.as_bytes()).map_err(io)
        }
    }
}

fn build(lit: &LitMesh, textures: &[Texture], tone_mapping: &ToneMapping) -> ExportMesh {
    let flip = |uvs: &[glam::Vec2]| uvs.iter().map(|t| [t.x, 1.0 - t.y]).collect();
    let mut mesh = ExportMesh {
        positions: lit.positions.iter().map(|p| p.to_array()).collect(),
        normals: lit.normals.iter().map(|n| n.to_array()).collect(),
        radiosity: lit
            .radiosity
            .iter()
            .map(|b| b.to_f32().to_array())
            .collect(),
        colors: Vec::new(),
        texcoords: [flip(&lit.texcoords), flip(&lit.lightmap_texcoords)],
        polygons: lit.polygons.clone(),
        polygon_surface: lit.polygon_surface.clone(),
        polygon_object: lit.polygon_object.clone(),
        surfaces: Vec::new(),
    };
    // The vertices' radiance and every lightmap texel, tone-mapped as one image so that an
    // automatic exposure treats them alike.
    let mut radiance: Vec<Rgb> = mesh
        .radiosity
        .iter()
        .map(|&b| Rgb::from(b) * (1.0 / PI as f32))
        .collect();
    let vertices = radiance.len();
    for s in &lit.surfaces {
        radiance.extend_from_slice(s.lightmap.pixels());
    }
    let Some(film) = Film::from_pixels(radiance.len() as u32, 1, radiance) else {
        return mesh;
    };
    let mapped: Vec<[f32; 3]> = tone_mapping
        .apply(&film)
        .into_iter()
        .map(|c| c.to_array())
        .collect();
    mesh.colors = mapped[..vertices].to_vec();
    let mut next = vertices;
    for s in &lit.surfaces {
        let (w, h) = (s.lightmap.width(), s.lightmap.height());
        let texels = &mapped[next..next + (w * h) as usize];
        next += (w * h) as usize;
        let texture = |id: Option<TextureId>| id.and_then(|t| textures.get(t as usize));
        mesh.surfaces.push(ExportSurface {
            name: s.name.clone(),
            base: base_image(texture(s.base_texture), texture(s.alpha_texture)),
            cut_out: s.alpha_texture.is_some(),
            lightmap: Image {
                width: w,
                height: h,
                rgba: texels
                    .iter()
                    .flat_map(|c| {
                        let [r, g, b] = c.map(srgb_byte);
                        [r, g, b, 255]
                    })
                    .collect(),
                wrap: Wrap::Clamp,
            },
        });
    }
    mesh
}

/// An sRGB-encoded byte of the display-linear value `v` in `[0, 1]`.
fn srgb_byte(v: f32) -> u8 {
    (linear_to_srgb(v) * 255.0).round().clamp(0.0, 255.0) as u8
}

/// The base-colour image of a surface: the diffuse texture's colour with, as alpha, where
/// the alpha texture leaves the surface in place (at each texel's centre); white where only
/// an alpha texture is given; none without either.
fn base_image(base: Option<&Texture>, alpha: Option<&Texture>) -> Option<Image> {
    let source = base.or(alpha)?;
    let (w, h) = (source.width, source.height);
    let mut rgba = Vec::with_capacity((w * h * 4) as usize);
    for y in 0..h {
        for x in 0..w {
            let [r, g, b] = match base {
                Some(t) => {
                    let texel = t.texel(i64::from(x), i64::from(y));
                    [texel[0], texel[1], texel[2]].map(srgb_byte)
                }
                None => [255; 3],
            };
            let uv = glam::Vec2::new(
                (x as f32 + 0.5) / w as f32,
                1.0 - (y as f32 + 0.5) / h as f32,
            );
            let present = alpha.is_none_or(|t| t.is_present(uv));
            rgba.extend_from_slice(&[r, g, b, if present { 255 } else { 0 }]);
        }
    }
    Some(Image {
        width: w,
        height: h,
        rgba,
        wrap: source.wrap,
    })
}

/// `image` as PNG bytes (empty if the encoder refuses it, which it does only for an image
/// whose texels do not fill its size: never for the images built here).
fn png(image: &Image) -> Vec<u8> {
    use ::image::ImageEncoder;
    let mut bytes = Vec::new();
    let encoded = ::image::codecs::png::PngEncoder::new(&mut bytes).write_image(
        &image.rgba,
        image.width,
        image.height,
        ::image::ExtendedColorType::Rgba8,
    );
    if encoded.is_err() {
        bytes.clear();
    }
    bytes
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
    out.push_str("property list uchar uint vertex_indices\nproperty uint object\nend_header\n");
    for v in 0..mesh.positions.len() {
        let (p, n, b) = (mesh.positions[v], mesh.normals[v], mesh.radiosity[v]);
        let c = mesh.colors[v].map(|x| (linear_to_srgb(x) * 255.0).round().clamp(0.0, 255.0) as u8);
        out.push_str(&format!(
            "{} {} {} {} {} {} {} {} {} {} {} {}\n",
            p[0], p[1], p[2], n[0], n[1], n[2], c[0], c[1], c[2], b[0], b[1], b[2]
        ));
    }
    for (poly, object) in mesh.polygons.iter().zip(&mesh.polygon_object) {
        out.push_str(&poly.len().to_string());
        for i in poly {
            out.push_str(&format!(" {i}"));
        }
        out.push_str(&format!(" {object}\n"));
    }
    out
}

/// The glTF JSON and its binary buffer; `uri` names the buffer file (`None` for GLB).
fn gltf_parts(mesh: &ExportMesh, uri: Option<&str>) -> (String, Vec<u8>) {
    let mut bin = Vec::new();
    let mut views = Vec::new();
    let mut add_view = |bin: &mut Vec<u8>, bytes: &[u8], target: Option<u32>| {
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let offset = bin.len();
        bin.extend_from_slice(bytes);
        let mut view = json!({"buffer": 0, "byteOffset": offset, "byteLength": bytes.len()});
        if let Some(target) = target {
            view["target"] = json!(target);
        }
        views.push(view);
        views.len() - 1
    };
    let floats = |data: &mut dyn Iterator<Item = f32>| -> Vec<u8> {
        data.flat_map(f32::to_le_bytes).collect()
    };
    let count = mesh.positions.len();
    let mut accessors = Vec::new();
    let mut attribute = |bin: &mut Vec<u8>, bytes: Vec<u8>, kind: &str| {
        let view = add_view(bin, &bytes, Some(GL_ARRAY_BUFFER));
        accessors.push(
            json!({"bufferView": view, "componentType": GL_FLOAT, "count": count, "type": kind}),
        );
        accessors.len() - 1
    };
    let position = attribute(
        &mut bin,
        floats(&mut mesh.positions.iter().flatten().copied()),
        "VEC3",
    );
    let normal = attribute(
        &mut bin,
        floats(&mut mesh.normals.iter().flatten().copied()),
        "VEC3",
    );
    let color = attribute(
        &mut bin,
        floats(&mut mesh.colors.iter().flatten().copied()),
        "VEC3",
    );
    let radiosity = attribute(
        &mut bin,
        floats(&mut mesh.radiosity.iter().flatten().copied()),
        "VEC3",
    );
    let lightmapped = !mesh.surfaces.is_empty();
    let texcoords = lightmapped.then(|| {
        mesh.texcoords
            .each_ref()
            .map(|t| attribute(&mut bin, floats(&mut t.iter().flatten().copied()), "VEC2"))
    });
    let (min, max) = mesh.positions.iter().fold(
        ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]),
        |(lo, hi), p| {
            (
                std::array::from_fn(|c| lo[c].min(p[c])),
                std::array::from_fn(|c| hi[c].max(p[c])),
            )
        },
    );
    accessors[position]["min"] = json!(min);
    accessors[position]["max"] = json!(max);
    // One primitive for the vertex-coloured polygons (material 0), one per lightmapped
    // surface (material 1 + its index).
    let mut primitives = Vec::new();
    for group in std::iter::once(None).chain((0..mesh.surfaces.len() as u32).map(Some)) {
        let indices: Vec<u32> = mesh
            .polygons
            .iter()
            .zip(&mesh.polygon_surface)
            .filter(|(_, s)| **s == group)
            .flat_map(|(p, _)| {
                if p.len() == 3 {
                    vec![p[0], p[1], p[2]]
                } else {
                    vec![p[0], p[1], p[2], p[0], p[2], p[3]]
                }
            })
            .collect();
        if indices.is_empty() {
            continue;
        }
        let bytes: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let view = add_view(&mut bin, &bytes, Some(GL_ELEMENT_ARRAY_BUFFER));
        accessors.push(json!({"bufferView": view, "componentType": GL_UNSIGNED_INT,
            "count": indices.len(), "type": "SCALAR"}));
        let indices = accessors.len() - 1;
        let primitive = match (group, texcoords) {
            (Some(surface), Some([uv, lightmap_uv])) => json!({
                "attributes": {"POSITION": position, "NORMAL": normal, "COLOR_0": color,
                    "COLOR_1": radiosity, "TEXCOORD_0": uv, "TEXCOORD_1": lightmap_uv},
                "indices": indices, "material": 1 + surface, "mode": 4}),
            _ => json!({
                "attributes": {"POSITION": position, "NORMAL": normal, "COLOR_0": color,
                    "COLOR_1": radiosity},
                "indices": indices, "material": 0, "mode": 4}),
        };
        primitives.push(primitive);
    }
    // Materials, textures, samplers and PNG images of the lightmapped surfaces.
    let mut materials = vec![json!({"name": "radiosity", "doubleSided": false,
        "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0],
            "metallicFactor": 0.0, "roughnessFactor": 1.0},
        "extensions": {"KHR_materials_unlit": {}}})];
    let (mut images, mut textures) = (Vec::new(), Vec::new());
    let samplers = json!([
        {"magFilter": GL_LINEAR, "minFilter": GL_LINEAR, "wrapS": GL_REPEAT, "wrapT": GL_REPEAT},
        {"magFilter": GL_LINEAR, "minFilter": GL_LINEAR, "wrapS": GL_CLAMP_TO_EDGE,
            "wrapT": GL_CLAMP_TO_EDGE},
    ]);
    let mut texture = |bin: &mut Vec<u8>, image: &Image, name: String| {
        let view = add_view(bin, &png(image), None);
        images.push(json!({"bufferView": view, "mimeType": "image/png", "name": name}));
        let sampler = if image.wrap == Wrap::Repeat { 0 } else { 1 };
        textures.push(json!({"sampler": sampler, "source": images.len() - 1}));
        textures.len() - 1
    };
    for surface in &mesh.surfaces {
        let lightmap = texture(
            &mut bin,
            &surface.lightmap,
            format!("{} lightmap", surface.name),
        );
        let mut pbr = json!({"baseColorFactor": [0.0, 0.0, 0.0, 1.0],
            "metallicFactor": 0.0, "roughnessFactor": 1.0});
        if let Some(base) = &surface.base {
            let index = texture(&mut bin, base, format!("{} texture", surface.name));
            pbr["baseColorTexture"] = json!({"index": index, "texCoord": 0});
        }
        let mut material = json!({"name": surface.name, "doubleSided": false,
            "pbrMetallicRoughness": pbr,
            "emissiveTexture": {"index": lightmap, "texCoord": 1},
            "emissiveFactor": [1.0, 1.0, 1.0]});
        if surface.cut_out && surface.base.is_some() {
            material["alphaMode"] = json!("MASK");
            material["alphaCutoff"] = json!(0.5);
        }
        materials.push(material);
    }
    let mut buffer = json!({"byteLength": bin.len()});
    if let Some(uri) = uri {
        buffer["uri"] = json!(uri);
    }
    let mut doc = json!({
        "asset": {"version": "2.0", "generator": "strahl radiosity"},
        "extensionsUsed": ["KHR_materials_unlit"],
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "radiosity"}],
        "meshes": [{"name": "radiosity", "primitives": primitives}],
        "materials": materials,
        "buffers": [buffer],
        "bufferViews": views,
        "accessors": accessors,
    });
    if lightmapped {
        doc["images"] = json!(images);
        doc["textures"] = json!(textures);
        doc["samplers"] = samplers;
    }
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
