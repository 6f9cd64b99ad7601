//! Turning a parsed scene file into a [`Scene`]: camera, materials (in file order, then the
//! implicit `default`, then imported ones), objects, lights and sensors.

use super::LoadOptions;
use super::camera::build_camera;
use super::error::{SceneError, Source};
use super::fields::Table;
use super::format::{ObjectEntry, ObjectType, SceneFile};
use super::lights::build_lights;
use super::locate::toml_error;
use super::materials::{TextureContext, build_material};
use super::meshes::{FaceMaterials, MeshCache};
use super::periodic::build_periodic;
use super::placements::build_placements;
use super::sensors::build_sensors;
use super::shapes::build_shape;
use super::spectra::{build_spectral, build_spectrum};
use super::textures::TextureCache;
use super::transform::build_transform;
use crate::scene::{LightKind, Material, MaterialId, Object, Scene, Shape};
use std::path::Path;

/// Name of the material objects use when they name none.
const DEFAULT_MATERIAL: &str = "default";

/// Parses and builds the scene in `src`; relative paths start at `base_dir`.
pub(super) fn build_scene(
    src: Source<'_>,
    base_dir: &Path,
    options: &LoadOptions,
) -> Result<Scene, SceneError> {
    let file: SceneFile = toml::from_str(src.text).map_err(|e| toml_error(src, &e))?;
    let name = Path::new(src.file).file_stem().map_or_else(
        || src.file.to_string(),
        |s| s.to_string_lossy().into_owned(),
    );
    let mut scene = Scene::empty(&name);
    scene.camera = build_camera(src, file.camera.as_ref())?;

    let mut textures = TextureCache::new(options.max_texels);
    let mut entries: Vec<_> = file.materials.iter().collect();
    entries.sort_by_key(|(key, _)| key.span().start);
    for (key, entry) in entries {
        let t = Table::new(src, format!("materials.{}", key.get_ref()), key.span());
        let mut context = TextureContext {
            base_dir,
            cache: &mut textures,
        };
        let material =
            build_material(&t, key.get_ref(), entry.get_ref(), &mut context, &mut scene)?;
        scene.add_material(material);
    }
    let file_defined = scene.materials.len();
    if scene.material_id(DEFAULT_MATERIAL).is_none() {
        scene.add_material(Material::default());
    }
    let known: Vec<String> = scene.materials.iter().map(|m| m.name.clone()).collect();

    let mut meshes = MeshCache::default();
    for (i, entry) in file.objects.iter().enumerate() {
        let t = Table::new(src, format!("objects[{i}]"), entry.span());
        let mut context = ObjectContext {
            base_dir,
            known: &known,
            file_defined,
            textures: &mut textures,
            meshes: &mut meshes,
        };
        let object = build_object(&t, entry.get_ref(), &mut context, &mut scene)?;
        match &entry.get_ref().placements {
            // One object per placement, `name[i]`, sharing the mesh.
            Some(placements) => {
                let placed = build_placements(&t, placements, base_dir, &object.transform)?;
                let index = scene.objects.len();
                let name = (object.name.clone()).unwrap_or_else(|| format!("object-{index}"));
                scene
                    .objects
                    .extend(placed.into_iter().enumerate().map(|(i, transform)| Object {
                        name: Some(format!("{name}[{i}]")),
                        transform,
                        ..object.clone()
                    }));
            }
            None => scene.objects.push(object),
        }
    }
    let mut light_spectra = Vec::new();
    for (i, entry) in file.lights.iter().enumerate() {
        let t = Table::new(src, format!("lights[{i}]"), entry.span());
        let (lights, day) = build_lights(&t, entry.get_ref())?;
        if let Some(mut day) = day {
            if scene.day.is_some() {
                return Err(t.table_error(
                    "a scene holds one day light (its states may be as many as you like)",
                ));
            }
            let first = scene.lights.len();
            for state in &mut day.states {
                state.lights.iter_mut().for_each(|i| *i += first);
            }
            scene.day = Some(day);
        }
        let e = entry.get_ref();
        let spectrum = e
            .spectrum
            .as_ref()
            .map(|v| build_spectrum(&t, "spectrum", v, base_dir))
            .transpose()?;
        // A day's skies take `sky_spectrum` where it is given, its suns `spectrum`.
        let sky_spectrum = match &e.sky_spectrum {
            Some(v) => Some(build_spectrum(&t, "sky_spectrum", v, base_dir)?),
            None => spectrum.clone(),
        };
        light_spectra.extend(lights.iter().map(|light| {
            let sky = matches!(light.kind, LightKind::CieSky { .. });
            (i, if sky { &sky_spectrum } else { &spectrum }.clone())
        }));
        scene.lights.extend(lights);
    }
    for (i, entry) in file.sensors.iter().enumerate() {
        let t = Table::new(src, format!("sensors[{i}]"), entry.span());
        build_sensors(&t, i, entry.get_ref(), &mut scene.sensors)?;
    }
    if let Some(entry) = &file.periodic {
        let t = Table::new(src, "periodic", entry.span());
        scene.periodic = Some(build_periodic(&t, entry.get_ref())?);
    }
    scene.spectral = build_spectral(src, &file, base_dir, &mut scene, light_spectra)?;
    Ok(scene)
}

/// What building an object needs besides the scene.
struct ObjectContext<'a> {
    base_dir: &'a Path,
    /// Names of the scene file's materials (plus `default`), in id order.
    known: &'a [String],
    /// Number of materials the scene file defines.
    file_defined: usize,
    textures: &'a mut TextureCache,
    meshes: &'a mut MeshCache,
}

/// One `[[objects]]` entry as an object.
fn build_object(
    t: &Table<'_>,
    e: &ObjectEntry,
    c: &mut ObjectContext<'_>,
    scene: &mut Scene,
) -> Result<Object, SceneError> {
    let kind = *e.kind.get_ref();
    t.only_fields(&e.shape_fields(), kind.fields(), kind.name())?;
    let material: Option<MaterialId> = match &e.material {
        Some(m) => {
            let name = m.get_ref();
            let id = c.known.iter().position(|k| k == name).ok_or_else(|| {
                t.error(
                    m.span(),
                    "material",
                    format!(
                        "unknown material \"{name}\" (known: {})",
                        c.known.join(", ")
                    ),
                )
            })?;
            Some(id as MaterialId)
        }
        None => None,
    };
    let default_id = c
        .known
        .iter()
        .position(|k| k == DEFAULT_MATERIAL)
        .unwrap_or(0) as MaterialId;
    let shape = if kind == ObjectType::Mesh {
        let file = e
            .file
            .as_ref()
            .ok_or_else(|| t.missing("file", "type mesh"))?;
        let faces = match material {
            Some(_) => FaceMaterials::Object,
            None => FaceMaterials::FromFile {
                fallback: default_id,
                file_defined: c.file_defined,
            },
        };
        let path = c.base_dir.join(file.get_ref());
        let mesh = c
            .meshes
            .mesh(scene, c.textures, &path, faces)
            .map_err(|m| t.error(file.span(), "file", m))?;
        Shape::Mesh(mesh)
    } else {
        build_shape(t, e)?
    };
    let transform = match &e.transform {
        Some(steps) => build_transform(t, steps)?,
        None => Default::default(),
    };
    Ok(Object {
        name: e.name.clone(),
        shape,
        transform,
        material: material.unwrap_or(default_id),
        per_face: e.per_face.unwrap_or(false),
    })
}
