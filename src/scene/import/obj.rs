//! Wavefront OBJ import (via `tobj`) with MTL materials.
//!
//! Faces keep their vertex count (quads stay quads); every object and group of the file goes
//! into one mesh. MTL mapping: `Kd` → diffuse (clamped to `[0, 1]`, default 0.8), `Ke` →
//! emission (radiance, negative values clamped to 0), `Ks` → specular (clamped so that
//! diffuse + specular ≤ 1 per channel), `Ns` → shininess, `map_Kd` → diffuse texture,
//! `map_Ke` → emission texture, `map_d` → alpha texture. `d` and `Tr` are ignored: only an
//! alpha map cuts surfaces away. Texture paths are relative to the OBJ file's folder; texture
//! options before the file name (`-s 1 1 1 file.png`) are skipped.

use super::faces::FaceCheck;
use super::obj_syntax;
use super::{ImportError, ImportedMaterial, ImportedMesh, TextureSource, append_mesh};
use crate::color::Rgb;
use crate::scene::{ColorSpace, Material, PolygonMesh};
use glam::{Vec2, Vec3};
use std::path::Path;

/// Reads an OBJ file and the MTL libraries it names. A material library that cannot be
/// opened is not an error: the faces then carry no material and a warning is recorded.
pub fn load(path: &Path) -> Result<ImportedMesh, ImportError> {
    let text = read_text(path)?;
    let face_lines = obj_syntax::check(&text).map_err(|e| ImportError::invalid(path, e))?;
    let options = tobj::LoadOptions {
        triangulate: false,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let folder = path.parent().unwrap_or(Path::new(""));
    let library_error = std::cell::RefCell::new(None);
    let (models, mtl) = tobj::load_obj_buf(&mut text.as_bytes(), &options, |library| {
        let library = folder.join(library);
        let text = std::fs::read(&library).map_err(|_| tobj::LoadError::OpenFileFailed)?;
        let text = String::from_utf8_lossy(&text);
        match obj_syntax::check_mtl(&text) {
            Ok(text) => tobj::load_mtl_buf(&mut text.as_bytes()),
            Err(e) => {
                *library_error.borrow_mut() = Some(format!("{}: {e}", library.display()));
                Err(tobj::LoadError::MaterialParseError)
            }
        }
    })
    .map_err(|e| ImportError::invalid(path, e))?;
    if let Some(e) = library_error.into_inner() {
        return Err(ImportError::invalid(path, e));
    }
    let mut warnings = Vec::new();
    let mtl_materials = match mtl {
        Ok(materials) => materials,
        Err(tobj::LoadError::OpenFileFailed) => {
            warnings.push(format!(
                "{}: material library not found; its faces use the object's material",
                path.display()
            ));
            Vec::new()
        }
        Err(e) => return Err(ImportError::invalid(path, format!("material library: {e}"))),
    };
    let materials = mtl_materials
        .iter()
        .map(|m| convert_material(m, folder).map_err(|e| ImportError::invalid(path, e)))
        .collect::<Result<Vec<_>, _>>()?;

    let mut mesh = PolygonMesh::default();
    let mut face_materials = Vec::new();
    let mut faces = FaceCheck::new(face_lines);
    for model in models {
        let part = convert_mesh(&model.mesh)
            .map_err(|e| ImportError::invalid(path, format!("object \"{}\": {e}", model.name)))?;
        let part = faces
            .split(part)
            .map_err(|e| ImportError::invalid(path, e))?;
        let material = match model.mesh.material_id {
            Some(id) if id < materials.len() => Some(id as u32),
            _ => None,
        };
        face_materials.extend(std::iter::repeat_n(material, part.face_count()));
        append_mesh(&mut mesh, part);
    }
    mesh.validate().map_err(|e| ImportError::invalid(path, e))?;
    warnings.extend(faces.warning(path));
    let (materials, face_materials) = keep_used(materials, face_materials);
    Ok(ImportedMesh {
        mesh,
        face_materials,
        materials,
        embedded_textures: Vec::new(),
        warnings,
    })
}

/// The text of the OBJ file at `path`, without a leading byte-order mark. Bytes that are not
/// UTF-8 (a Latin-1 comment) are replaced; a folder or a file with control characters
/// outside comments is refused.
fn read_text(path: &Path) -> Result<String, ImportError> {
    if path.is_dir() {
        return Err(ImportError::unreadable(path, "it is a folder, not a file"));
    }
    let bytes = std::fs::read(path).map_err(|e| ImportError::unreadable(path, e))?;
    let bytes = bytes.strip_prefix("\u{feff}".as_bytes()).unwrap_or(&bytes);
    let text = String::from_utf8_lossy(bytes).into_owned();
    for (i, line) in text.lines().enumerate() {
        let code = line.split('#').next().unwrap_or("");
        if code
            .chars()
            .any(|c| c.is_control() && c != '\t' && c != '\r')
        {
            return Err(ImportError::invalid(
                path,
                format!(
                    "line {}: control characters: not an OBJ text file (binary data?)",
                    i + 1
                ),
            ));
        }
    }
    Ok(text)
}

/// One `tobj` mesh as a polygon mesh.
fn convert_mesh(m: &tobj::Mesh) -> Result<PolygonMesh, String> {
    let count = m.positions.len() / 3;
    let positions: Vec<Vec3> = m
        .positions
        .chunks_exact(3)
        .map(|p| Vec3::new(p[0], p[1], p[2]))
        .collect();
    let normals = (m.normals.len() == 3 * count && count > 0).then(|| {
        m.normals
            .chunks_exact(3)
            .map(|n| Vec3::new(n[0], n[1], n[2]))
            .collect()
    });
    let uvs = (m.texcoords.len() == 2 * count && count > 0).then(|| {
        m.texcoords
            .chunks_exact(2)
            .map(|t| Vec2::new(t[0], t[1]))
            .collect()
    });
    let face_sizes = if m.face_arities.is_empty() {
        if !m.indices.len().is_multiple_of(3) {
            return Err("index count is not a multiple of 3".into());
        }
        vec![3; m.indices.len() / 3]
    } else {
        m.face_arities.clone()
    };
    let mesh = PolygonMesh {
        positions,
        normals,
        uvs,
        indices: m.indices.clone(),
        face_sizes,
        face_materials: None,
    };
    mesh.validate()?;
    Ok(mesh)
}

/// Drops materials no face uses and renumbers the rest in order of first use.
fn keep_used(
    materials: Vec<ImportedMaterial>,
    faces: Vec<Option<u32>>,
) -> (Vec<ImportedMaterial>, Vec<Option<u32>>) {
    let mut new_id = vec![None; materials.len()];
    let mut kept = Vec::new();
    let faces = faces
        .into_iter()
        .map(|f| {
            f.map(|old| {
                *new_id[old as usize].get_or_insert_with(|| {
                    kept.push(materials[old as usize].clone());
                    (kept.len() - 1) as u32
                })
            })
        })
        .collect();
    (kept, faces)
}

/// Converts one MTL material; fails on non-finite numbers.
fn convert_material(m: &tobj::Material, folder: &Path) -> Result<ImportedMaterial, String> {
    let color = |key: &str, v: Option<[f32; 3]>, default: f32| -> Result<Rgb, String> {
        let c = v.map(Rgb::from).unwrap_or(Rgb::splat(default));
        if c.is_finite() {
            Ok(c)
        } else {
            Err(format!("material \"{}\": {key} is not finite", m.name))
        }
    };
    let diffuse = color("Kd", m.diffuse, 0.8)?.map(|c| c.clamp(0.0, 1.0));
    let specular_raw = color("Ks", m.specular, 0.0)?;
    let specular = Rgb::new(
        specular_raw.r.clamp(0.0, 1.0 - diffuse.r),
        specular_raw.g.clamp(0.0, 1.0 - diffuse.g),
        specular_raw.b.clamp(0.0, 1.0 - diffuse.b),
    );
    let emission = color("Ke", m.emissive, 0.0)?.map(|c| c.max(0.0));
    let defaults = Material::default();
    let shininess = match m.shininess {
        Some(ns) if ns.is_finite() => ns.max(0.0),
        Some(_) => return Err(format!("material \"{}\": Ns is not finite", m.name)),
        None => defaults.shininess,
    };
    let texture = |spec: Option<&String>, alpha: bool| {
        spec.and_then(|s| texture_file(s)).map(|file| {
            let path = folder.join(file);
            TextureSource::File {
                color_space: if alpha {
                    ColorSpace::Linear
                } else {
                    ColorSpace::default_for(&path)
                },
                path,
                alpha_from_grey: alpha,
            }
        })
    };
    Ok(ImportedMaterial {
        material: Material {
            name: m.name.clone(),
            diffuse,
            emission,
            specular,
            shininess,
            ..defaults
        },
        diffuse_texture: texture(m.diffuse_texture.as_ref(), false),
        emission_texture: texture(m.unknown_param.get("map_Ke"), false),
        alpha_texture: texture(m.dissolve_texture.as_ref(), true),
    })
}

/// The file name in an MTL texture statement, skipping leading options such as
/// `-s 1 1 1` (the file name is then the last word).
fn texture_file(spec: &str) -> Option<&str> {
    let spec = spec.trim();
    if spec.starts_with('-') {
        spec.split_whitespace().last()
    } else {
        Some(spec).filter(|s| !s.is_empty())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_byte_order_mark_and_latin_1_comments_are_read_past() {
        let dir = std::env::temp_dir().join(format!("strahl-obj-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("bom.obj");
        let mut bytes = b"\xef\xbb\xbfv 0 0 0\n# mod\xe9le\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec();
        std::fs::write(&path, &bytes).unwrap();
        assert_eq!(load(&path).unwrap().mesh.face_count(), 1);
        bytes.extend_from_slice(b"v 0 0 \x01\n");
        std::fs::write(&path, &bytes).unwrap();
        let e = load(&path).unwrap_err().to_string();
        assert!(e.contains("line 6: control characters"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn texture_options_are_skipped() {
        assert_eq!(texture_file("wood.png"), Some("wood.png"));
        assert_eq!(texture_file("-s 2 2 1 wood.png"), Some("wood.png"));
        assert_eq!(texture_file("  "), None);
    }

    #[test]
    fn specular_is_clamped_to_keep_energy() {
        let m = tobj::Material {
            name: "m".into(),
            diffuse: Some([0.7, 0.2, 1.5]),
            specular: Some([0.5, 0.5, 0.5]),
            emissive: Some([-1.0, 2.0, 0.0]),
            ..Default::default()
        };
        let out = convert_material(&m, Path::new("")).unwrap().material;
        assert!((out.diffuse.b - 1.0).abs() < 1e-6);
        assert!((out.specular.r - 0.3).abs() < 1e-6);
        assert!((out.specular.g - 0.5).abs() < 1e-6);
        assert_eq!(out.specular.b, 0.0);
        assert_eq!(out.emission, Rgb::new(0.0, 2.0, 0.0));
        assert!(out.albedo_bound() <= 1.0 + 1e-6);
    }

    #[test]
    fn unused_materials_are_dropped_and_renumbered() {
        let mat = |name: &str| ImportedMaterial {
            material: Material::diffuse(name, Rgb::splat(0.5)),
            diffuse_texture: None,
            emission_texture: None,
            alpha_texture: None,
        };
        let (kept, faces) = keep_used(
            vec![mat("a"), mat("b"), mat("c")],
            vec![Some(2), None, Some(0), Some(2)],
        );
        assert_eq!(kept.len(), 2);
        assert_eq!(kept[0].material.name, "c");
        assert_eq!(faces, vec![Some(0), None, Some(1), Some(0)]);
    }
}
