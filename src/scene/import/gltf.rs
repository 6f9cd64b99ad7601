//! glTF 2.0 import (`.gltf` with external or base64-embedded buffers, and binary `.glb`).
//!
//! All triangle primitives of all meshes reachable from the default scene (else the first
//! scene, else every root node) go into one mesh, with node transforms applied. Material
//! mapping: `baseColorFactor` → diffuse, `baseColorTexture` → diffuse texture (sRGB),
//! `emissiveFactor` × `KHR_materials_emissive_strength` → emission radiance,
//! `emissiveTexture` → emission texture (sRGB), `alphaMode: MASK` with a base colour texture
//! → that texture's alpha as cut-out. Metallic/roughness, normal and occlusion maps,
//! `alphaCutoff` (always ½ here) and `doubleSided` are ignored. Texture coordinates are
//! flipped to the bottom-left origin of [`crate::scene::Texture`].

use super::{ImportError, ImportedMaterial, ImportedMesh, TextureSource, append_mesh};
use crate::color::Rgb;
use crate::color::srgb_to_linear;
use crate::scene::{ColorSpace, MAX_TEXELS, MAX_TEXTURE_SIDE, Material, PolygonMesh, Texture};
use ::gltf::mesh::Mode;
use glam::{Mat3, Mat4, Vec2, Vec3};
use std::collections::HashMap;
use std::path::Path;

/// Deepest node hierarchy followed (guards against cyclic files).
const MAX_NODE_DEPTH: usize = 256;

/// Reads a glTF or GLB file with its buffers and the images its materials use.
pub fn load(path: &Path) -> Result<ImportedMesh, ImportError> {
    let bytes = std::fs::read(path).map_err(|e| ImportError::unreadable(path, e))?;
    check_glb_header(&bytes).map_err(|e| ImportError::invalid(path, e))?;
    check_references(&bytes).map_err(|e| ImportError::invalid(path, e))?;
    let ::gltf::Gltf { document, blob } =
        ::gltf::Gltf::from_slice(&bytes).map_err(|e| ImportError::invalid(path, e))?;
    let version = &document.as_json().asset.version;
    if !version.starts_with("2.") {
        return Err(ImportError::invalid(
            path,
            format!("asset.version is \"{version}\"; glTF 2.x is read"),
        ));
    }
    let folder = path.parent().unwrap_or(Path::new(""));
    for buffer in document.buffers() {
        if let ::gltf::buffer::Source::Uri(uri) = buffer.source()
            && let Some(file) = relative_file(uri)
        {
            let at = |e: String| {
                ImportError::invalid(path, format!("buffers[{}].uri: {e}", buffer.index()))
            };
            if !folder.join(file.map_err(at)?).is_file() {
                return Err(at(format!("cannot read \"{uri}\" next to the glTF file")));
            }
        }
    }
    let buffers = ::gltf::import_buffers(&document, Some(folder), blob)
        .map_err(|e| ImportError::invalid(path, format!("buffer: {e}")))?;
    let mut importer = Importer {
        path,
        folder,
        buffers: &buffers,
        out: ImportedMesh {
            mesh: PolygonMesh::default(),
            face_materials: Vec::new(),
            materials: Vec::new(),
            embedded_textures: Vec::new(),
            warnings: Vec::new(),
        },
        material_ids: HashMap::new(),
        image_ids: HashMap::new(),
    };
    let roots: Vec<_> = match document
        .default_scene()
        .or_else(|| document.scenes().next())
    {
        Some(scene) => scene.nodes().collect(),
        None => {
            let children: Vec<usize> = document
                .nodes()
                .flat_map(|n| n.children().map(|c| c.index()))
                .collect();
            document
                .nodes()
                .filter(|n| !children.contains(&n.index()))
                .collect()
        }
    };
    for node in roots {
        importer.node(&node, Mat4::IDENTITY, 0)?;
    }
    importer
        .out
        .mesh
        .validate()
        .map_err(|e| ImportError::invalid(path, e))?;
    Ok(importer.out)
}

/// The file a URI without a scheme names, percent-decoded (`None` for `data:` and other
/// schemes); an error when the decoded bytes are not UTF-8 (the `gltf` crate unwrapped the
/// decoding and panicked).
fn relative_file(uri: &str) -> Option<Result<String, String>> {
    if uri.contains(':') {
        return None;
    }
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = bytes
            .get(i + 1..i + 3)
            .and_then(|h| std::str::from_utf8(h).ok())
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match (bytes[i], hex) {
            (b'%', Some(byte)) => {
                out.push(byte);
                i += 3;
            }
            (b, _) => {
                out.push(b);
                i += 1;
            }
        }
    }
    Some(
        String::from_utf8(out).map_err(|_| {
            format!("\"{uri}\" decodes to a name that is not UTF-8 (a stray %-escape?)")
        }),
    )
}

/// Checks that a binary glTF's header declares a length no shorter than the header itself
/// (the `gltf` crate subtracts the header's size from it unchecked).
fn check_glb_header(bytes: &[u8]) -> Result<(), String> {
    const HEADER: usize = 12;
    if let Some(length) = bytes
        .strip_prefix(b"glTF")
        .and_then(|rest| rest.get(4..8))
        .map(|l| u32::from_le_bytes([l[0], l[1], l[2], l[3]]) as usize)
        && length < HEADER
    {
        return Err(format!(
            "the binary glTF header declares {length} bytes, fewer than the {HEADER} of the \
             header itself"
        ));
    }
    Ok(())
}

/// Checks the references the `gltf` crate follows without checking (it panicked on each):
/// every mesh primitive's attributes and morph targets name existing accessors (its
/// validation reads the POSITION accessor before checking the index), and every image has
/// a `uri` or a `bufferView` (an existing one, with a `mimeType`). Input that is not glTF JSON
/// (or GLB holding it) is left for the `gltf` crate to refuse.
fn check_references(bytes: &[u8]) -> Result<(), String> {
    let json = match ::gltf::Glb::from_slice(bytes) {
        Ok(glb) => glb.json.into_owned(),
        Err(_) => bytes.to_vec(),
    };
    // Lossily: the `gltf` crate reads a key with a stray byte as an unknown key.
    let Ok(root) = serde_json::from_str::<serde_json::Value>(&String::from_utf8_lossy(&json))
    else {
        return Ok(());
    };
    let count = |key: &str| root[key].as_array().map_or(0, Vec::len);
    let accessors = count("accessors");
    let meshes = root["meshes"].as_array().map(Vec::as_slice).unwrap_or(&[]);
    for (m, mesh) in meshes.iter().enumerate() {
        let primitives = mesh["primitives"]
            .as_array()
            .map(Vec::as_slice)
            .unwrap_or(&[]);
        for (p, primitive) in primitives.iter().enumerate() {
            let targets = primitive["targets"]
                .as_array()
                .map(Vec::as_slice)
                .unwrap_or(&[]);
            let tables = std::iter::once(("attributes".to_string(), &primitive["attributes"]))
                .chain(
                    targets
                        .iter()
                        .enumerate()
                        .map(|(t, target)| (format!("targets[{t}]"), target)),
                );
            for (name, table) in tables {
                for (semantic, index) in table.as_object().into_iter().flatten() {
                    if index.as_u64().is_some_and(|i| i >= accessors as u64) {
                        return Err(format!(
                            "meshes[{m}].primitives[{p}].{name}.{semantic}: accessor {index} \
                             does not exist ({accessors} accessors)"
                        ));
                    }
                }
            }
        }
    }
    let views = count("bufferViews");
    let images = root["images"].as_array().map(Vec::as_slice).unwrap_or(&[]);
    for (i, image) in images.iter().enumerate() {
        let view = &image["bufferView"];
        if view.is_null() {
            if !image["uri"].is_string() {
                return Err(format!("images[{i}]: neither a uri nor a bufferView"));
            }
        } else if view.as_u64().is_none_or(|v| v >= views as u64) {
            return Err(format!(
                "images[{i}].bufferView: buffer view {view} does not exist ({views} views)"
            ));
        } else if !image["mimeType"].is_string() {
            return Err(format!(
                "images[{i}].mimeType: an image in a buffer view needs its mimeType"
            ));
        }
    }
    Ok(())
}

/// State of one import.
struct Importer<'a> {
    path: &'a Path,
    folder: &'a Path,
    buffers: &'a [::gltf::buffer::Data],
    out: ImportedMesh,
    /// Document material index → index in `out.materials`.
    material_ids: HashMap<usize, u32>,
    /// (document image index, sRGB?) → index in `out.embedded_textures`.
    image_ids: HashMap<(usize, bool), usize>,
}

impl Importer<'_> {
    fn invalid(&self, reason: impl ToString) -> ImportError {
        ImportError::invalid(self.path, reason)
    }

    /// Adds the meshes of `node` and its descendants; `parent` is the parent's
    /// node-to-file transform.
    fn node(&mut self, node: &::gltf::Node, parent: Mat4, depth: usize) -> Result<(), ImportError> {
        if depth > MAX_NODE_DEPTH {
            return Err(self.invalid(format!(
                "node hierarchy deeper than {MAX_NODE_DEPTH} (cyclic?)"
            )));
        }
        let to_file = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if let Some(mesh) = node.mesh() {
            for primitive in mesh.primitives() {
                self.primitive(&primitive, to_file).map_err(|e| {
                    self.invalid(format!(
                        "mesh {} primitive {}: {e}",
                        mesh.index(),
                        primitive.index()
                    ))
                })?;
            }
        }
        for child in node.children() {
            self.node(&child, to_file, depth + 1)?;
        }
        Ok(())
    }

    /// Adds one primitive transformed by `to_file`; points and lines are skipped with a
    /// warning.
    fn primitive(&mut self, primitive: &::gltf::Primitive, to_file: Mat4) -> Result<(), String> {
        let buffers = self.buffers;
        check_accessors(primitive, buffers)?;
        let reader = primitive.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
        let positions: Vec<Vec3> = reader
            .read_positions()
            .ok_or("no vertex positions")?
            .map(|p| to_file.transform_point3(Vec3::from(p)))
            .collect();
        let normal_map = Mat3::from_mat4(to_file).inverse().transpose();
        let normals = reader.read_normals().map(|it| {
            it.map(|n| (normal_map * Vec3::from(n)).normalize_or_zero())
                .collect::<Vec<_>>()
        });
        let uvs = reader.read_tex_coords(0).map(|it| {
            it.into_f32()
                .map(|[u, v]| Vec2::new(u, 1.0 - v))
                .collect::<Vec<_>>()
        });
        let indices: Vec<u32> = match reader.read_indices() {
            Some(it) => it.into_u32().collect(),
            None => (0..positions.len() as u32).collect(),
        };
        let Some(mut triangles) = triangles(primitive.mode(), &indices) else {
            self.out.warnings.push(format!(
                "{}: skipped a primitive of mode {:?} (only triangles are imported)",
                self.path.display(),
                primitive.mode()
            ));
            return Ok(());
        };
        if to_file.determinant() < 0.0 {
            for t in &mut triangles {
                t.swap(1, 2);
            }
        }
        let mut part = PolygonMesh::from_triangles(positions, &triangles);
        part.normals = normals;
        part.uvs = uvs;
        part.validate()?;
        let material = match primitive.material().index() {
            Some(_) => Some(self.material(&primitive.material())?),
            None => None,
        };
        let faces = part.face_count();
        self.out
            .face_materials
            .extend(std::iter::repeat_n(material, faces));
        append_mesh(&mut self.out.mesh, part);
        Ok(())
    }

    /// The local id of a document material, converting it on first use.
    fn material(&mut self, m: &::gltf::Material) -> Result<u32, String> {
        let index = m.index().unwrap_or(usize::MAX);
        if let Some(&id) = self.material_ids.get(&index) {
            return Ok(id);
        }
        let name = m
            .name()
            .map(str::to_string)
            .unwrap_or_else(|| format!("material-{index}"));
        let pbr = m.pbr_metallic_roughness();
        let [r, g, b, _] = pbr.base_color_factor();
        let diffuse = Rgb::new(r, g, b);
        let strength = m.emissive_strength().unwrap_or(1.0);
        let emission = Rgb::from(m.emissive_factor()) * strength;
        if !diffuse.is_finite() || !emission.is_finite() {
            return Err(format!("material \"{name}\" has non-finite factors"));
        }
        let diffuse_texture = match pbr.base_color_texture() {
            Some(info) => Some(self.texture(&info.texture(), ColorSpace::Srgb)?),
            None => None,
        };
        let emission_texture = match m.emissive_texture() {
            Some(info) => Some(self.texture(&info.texture(), ColorSpace::Srgb)?),
            None => None,
        };
        let alpha_texture = match m.alpha_mode() {
            ::gltf::material::AlphaMode::Mask => diffuse_texture.clone(),
            _ => None,
        };
        self.out.materials.push(ImportedMaterial {
            material: Material {
                name,
                diffuse: diffuse.map(|c| c.clamp(0.0, 1.0)),
                emission: emission.map(|c| c.max(0.0)),
                ..Material::default()
            },
            diffuse_texture,
            emission_texture,
            alpha_texture,
        });
        let id = (self.out.materials.len() - 1) as u32;
        self.material_ids.insert(index, id);
        Ok(id)
    }

    /// Decodes the image of `texture` (once per image and colour space).
    fn texture(
        &mut self,
        texture: &::gltf::Texture,
        space: ColorSpace,
    ) -> Result<TextureSource, String> {
        let image = texture.source();
        let key = (image.index(), space == ColorSpace::Srgb);
        if let Some(&i) = self.image_ids.get(&key) {
            return Ok(TextureSource::Embedded(i));
        }
        self.check_image_size(&image)
            .map_err(|e| format!("image {}: {e}", image.index()))?;
        let data =
            ::gltf::image::Data::from_source(image.source(), Some(self.folder), self.buffers)
                .map_err(|e| format!("image {}: {e}", image.index()))?;
        let name = format!("{}#image{}", self.path.display(), image.index());
        let decoded = decode_image(&name, &data, space)?;
        self.out.embedded_textures.push(decoded);
        let i = self.out.embedded_textures.len() - 1;
        self.image_ids.insert(key, i);
        Ok(TextureSource::Embedded(i))
    }
}

impl Importer<'_> {
    /// Refuses an image whose header declares more than [`MAX_TEXELS`] texels (or over
    /// [`MAX_TEXTURE_SIDE`] a side) before the `gltf` crate decodes it: a small file may
    /// declare a huge image. Images in buffer views and in files are checked; data URIs and
    /// other schemes are left to the decoder.
    fn check_image_size(&self, image: &::gltf::Image) -> Result<(), String> {
        let reader = match image.source() {
            ::gltf::image::Source::View { view, .. } => {
                let buffer = &self.buffers[view.buffer().index()];
                let bytes = buffer
                    .get(view.offset()..view.offset() + view.length())
                    .ok_or("its buffer view lies outside its buffer")?;
                image::ImageReader::new(std::io::Cursor::new(bytes.to_vec()))
                    .with_guessed_format()
                    .map_err(|e| e.to_string())?
                    .into_dimensions()
            }
            ::gltf::image::Source::Uri { uri, .. } => {
                let Some(file) = relative_file(uri) else {
                    return Ok(());
                };
                image::ImageReader::open(self.folder.join(file?))
                    .and_then(|r| r.with_guessed_format())
                    .map_err(|e| format!("\"{uri}\": {e}"))?
                    .into_dimensions()
            }
        };
        let (width, height) = reader.map_err(|e| e.to_string())?;
        let texels = u64::from(width) * u64::from(height);
        if width > MAX_TEXTURE_SIDE || height > MAX_TEXTURE_SIDE || texels > MAX_TEXELS {
            return Err(format!(
                "the image is {width}×{height} = {texels} texels; embedded textures of at most \
                 {MAX_TEXTURE_SIDE} texels a side and {MAX_TEXELS} texels in all are read"
            ));
        }
        Ok(())
    }
}

/// The triangles of a primitive's index list, or `None` for point and line modes.
fn triangles(mode: Mode, indices: &[u32]) -> Option<Vec<[u32; 3]>> {
    let n = indices.len();
    let tris = match mode {
        Mode::Triangles => indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
        Mode::TriangleStrip => (2..n)
            .map(|i| {
                if i % 2 == 0 {
                    [indices[i - 2], indices[i - 1], indices[i]]
                } else {
                    [indices[i - 1], indices[i - 2], indices[i]]
                }
            })
            .collect(),
        Mode::TriangleFan => (2..n)
            .map(|i| [indices[0], indices[i - 1], indices[i]])
            .collect(),
        _ => return None,
    };
    Some(tris)
}

/// A decoded glTF image as a linear RGBA texture; colour channels are decoded per `space`,
/// alpha is kept as stored.
fn decode_image(
    name: &str,
    data: &::gltf::image::Data,
    space: ColorSpace,
) -> Result<Texture, String> {
    use ::gltf::image::Format;
    let (channels, bytes) = match data.format {
        Format::R8 => (1, 1),
        Format::R8G8 => (2, 1),
        Format::R8G8B8 => (3, 1),
        Format::R8G8B8A8 => (4, 1),
        Format::R16 => (1, 2),
        Format::R16G16 => (2, 2),
        Format::R16G16B16 => (3, 2),
        Format::R16G16B16A16 => (4, 2),
        Format::R32G32B32FLOAT => (3, 4),
        Format::R32G32B32A32FLOAT => (4, 4),
    };
    let (w, h) = (data.width as usize, data.height as usize);
    if w == 0 || h == 0 || data.pixels.len() != w * h * channels * bytes {
        return Err(format!("image {name} has an inconsistent size"));
    }
    let px = &data.pixels;
    let value = |i: usize| -> f32 {
        let at = i * bytes;
        match bytes {
            1 => px[at] as f32 / 255.0,
            2 => u16::from_ne_bytes([px[at], px[at + 1]]) as f32 / 65535.0,
            _ => f32::from_ne_bytes([px[at], px[at + 1], px[at + 2], px[at + 3]]),
        }
    };
    let decode = |v: f32| match space {
        ColorSpace::Linear => v,
        ColorSpace::Srgb => srgb_to_linear(v),
    };
    Ok(Texture::from_fn(name, data.width, data.height, |x, y| {
        let base = (y as usize * w + x as usize) * channels;
        let c = |k: usize| value(base + k);
        let (r, g, b, a) = match channels {
            1 => (c(0), c(0), c(0), 1.0),
            2 => (c(0), c(0), c(0), c(1)),
            3 => (c(0), c(1), c(2), 1.0),
            _ => (c(0), c(1), c(2), c(3)),
        };
        [decode(r), decode(g), decode(b), a]
    }))
}

/// Refuses a primitive whose accessors the reader would misread or read out of bounds: each
/// attribute strahl uses (positions, normals, first texture coordinates) and the indices must
/// have the glTF type and component type they are defined with, a stride no shorter than an
/// element, and every element inside its buffer view and the view inside its buffer.
fn check_accessors(
    primitive: &::gltf::Primitive,
    buffers: &[::gltf::buffer::Data],
) -> Result<(), String> {
    use ::gltf::Semantic;
    use ::gltf::accessor::{DataType, Dimensions};
    let float = [DataType::F32].as_slice();
    let texcoord = [DataType::F32, DataType::U8, DataType::U16].as_slice();
    let index = [DataType::U8, DataType::U16, DataType::U32].as_slice();
    let checks = [
        (Semantic::Positions, "POSITION", Dimensions::Vec3, float),
        (Semantic::Normals, "NORMAL", Dimensions::Vec3, float),
        (
            Semantic::TexCoords(0),
            "TEXCOORD_0",
            Dimensions::Vec2,
            texcoord,
        ),
    ];
    for (semantic, name, dimensions, types) in checks {
        if let Some(accessor) = primitive.get(&semantic) {
            check_accessor(&accessor, buffers, name, dimensions, types)?;
        }
    }
    if let Some(accessor) = primitive.indices() {
        check_accessor(&accessor, buffers, "indices", Dimensions::Scalar, index)?;
    }
    Ok(())
}

/// One accessor's checks for [`check_accessors`].
fn check_accessor(
    accessor: &::gltf::Accessor,
    buffers: &[::gltf::buffer::Data],
    name: &str,
    dimensions: ::gltf::accessor::Dimensions,
    types: &[::gltf::accessor::DataType],
) -> Result<(), String> {
    let at = format!("{name} (accessor {})", accessor.index());
    if accessor.dimensions() != dimensions || !types.contains(&accessor.data_type()) {
        return Err(format!(
            "{at}: {:?} of {:?}, expected {dimensions:?} of {}",
            accessor.dimensions(),
            accessor.data_type(),
            types
                .iter()
                .map(|t| format!("{t:?}"))
                .collect::<Vec<_>>()
                .join(" or ")
        ));
    }
    if accessor.sparse().is_some() {
        return Err(format!("{at}: sparse accessors are not supported"));
    }
    let Some(view) = accessor.view() else {
        return Err(format!("{at}: no buffer view"));
    };
    let size = accessor.size();
    let stride = view.stride().unwrap_or(size);
    if stride < size {
        return Err(format!(
            "{at}: byteStride {stride} is shorter than one element ({size} bytes)"
        ));
    }
    let buffer = buffers
        .get(view.buffer().index())
        .map_or(0, |data| data.0.len());
    let view_end = view.offset().checked_add(view.length());
    if view_end.is_none_or(|end| end > buffer) {
        return Err(format!(
            "{at}: buffer view {} ({} bytes from byte {}) runs past its buffer's {buffer} bytes",
            view.index(),
            view.length(),
            view.offset()
        ));
    }
    let count = accessor.count();
    if count == 0 {
        // The `gltf` crate's reader takes `count − 1` (a panic in checked builds).
        return Err(format!(
            "{at}: count 0 (an accessor holds at least one element)"
        ));
    }
    let end = accessor
        .offset()
        .checked_add(stride.saturating_mul(count - 1))
        .and_then(|end| end.checked_add(size));
    if end.is_none_or(|end| end > view.length()) {
        return Err(format!(
            "{at}: {count} elements from byte {} do not fit in buffer view {} ({} bytes)",
            accessor.offset(),
            view.index(),
            view.length()
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans_become_consistently_wound_triangles() {
        let strip = triangles(Mode::TriangleStrip, &[0, 1, 2, 3]).unwrap();
        assert_eq!(strip, vec![[0, 1, 2], [2, 1, 3]]);
        let fan = triangles(Mode::TriangleFan, &[0, 1, 2, 3]).unwrap();
        assert_eq!(fan, vec![[0, 1, 2], [0, 2, 3]]);
        assert!(triangles(Mode::Lines, &[0, 1]).is_none());
    }

    #[test]
    fn rgba8_image_decodes_srgb_colour_and_keeps_alpha() {
        let data = ::gltf::image::Data {
            pixels: vec![255, 128, 0, 64],
            format: ::gltf::image::Format::R8G8B8A8,
            width: 1,
            height: 1,
        };
        let t = decode_image("t", &data, ColorSpace::Srgb).unwrap();
        let [r, g, b, a] = t.texels[0];
        assert!((r - 1.0).abs() < 1e-6 && b == 0.0);
        assert!((g - srgb_to_linear(128.0 / 255.0)).abs() < 1e-6);
        assert!((a - 64.0 / 255.0).abs() < 1e-6);
    }
}
