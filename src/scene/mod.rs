//! The scene model: objects with shapes, transforms and materials; textures; lights; the
//! camera. Scenes come from TOML files ([`load`]), bare mesh files ([`load_mesh_file`]) or
//! are built in ([`builtin`]); [`open`] takes any of them by the name a user gives.

pub mod builtin;
mod camera;
mod day;
mod file;
pub mod import;
mod light;
mod material;
mod mesh;
mod moving;
mod object;
mod open;
mod periodic;
pub(crate) mod polygon;
mod sensor;
mod spectral;
mod tessellate;
mod texture;

pub use crate::color::{
    Band, MAX_WAVELENGTH_NM, MOLAR_PHOTON_ENERGY_NM, Spectrum, SpectrumError, StandardSpectrum,
};
/// An object's placement: object space to world space and back.
pub use crate::geometry::Transform;
pub use camera::{Camera, CameraRays};
pub use day::{Day, DayState};
pub use file::{LoadOptions, SceneError, load, load_mesh_file, load_str, load_str_with, load_with};
pub use light::{Incidence, Light, LightKind};
// What a CIE sky and a sun placed by date name (for front ends building scenes in code).
pub use crate::sky::{
    CieSkyType, DEFAULT_DELTA_T_S, LocalTime, Observer, STANDARD_PRESSURE_MBAR,
    STANDARD_TEMPERATURE_C, SUNRISE_REFRACTION_DEG, SunPosition, sun_position,
};
pub use material::{ENERGY_TOLERANCE, Lobe, MAX_COLOUR, Material, MaterialId};
pub use mesh::PolygonMesh;
pub use moving::{MoveError, Moved};
pub use object::{AnalyticKind, Object, Shape};
pub use open::{OpenError, is_mesh_file, open};
pub use periodic::Periodic;
pub use sensor::{MAX_SENSORS, Sensor};
pub use spectral::{
    BandChannel, BandGroup, BandQuantity, MaterialSpectra, PhotonClass, Spectral, SpectralError,
};
pub use tessellate::{polygon_area, polygon_normal};
pub use texture::{
    ALPHA_CUTOFF, ColorSpace, Coverage, MAX_TEXELS, MAX_TEXTURE_SIDE, TexelStats, Texture,
    TextureError, TextureId, Wrap,
};

use glam::Vec3;

/// A complete scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Display name (file name or built-in name).
    pub name: String,
    /// The camera.
    pub camera: Camera,
    /// All materials, referenced by [`MaterialId`].
    pub materials: Vec<Material>,
    /// All textures, referenced by [`TextureId`].
    pub textures: Vec<Texture>,
    /// All objects.
    pub objects: Vec<Object>,
    /// Point (isotropic or Lambertian), spot, directional and sky lights (emissive surfaces
    /// are lights too).
    pub lights: Vec<Light>,
    /// Measuring points (they neither block nor reflect light).
    pub sensors: Vec<Sensor>,
    /// The plot that repeats in x and z, for a scene standing for a field; `None` for a
    /// scene that is all there is.
    pub periodic: Option<Periodic>,
    /// The wavelength bands the scene reports light in, with its lights' and materials'
    /// spectra; `None` for a scene in RGB only.
    pub spectral: Option<Spectral>,
    /// The day of sun and sky states among the lights (a `day` light), to solve state by
    /// state; `None` without one.
    pub day: Option<Day>,
}

impl Scene {
    /// True when something in the scene sends light: a point (isotropic or Lambertian), spot,
    /// directional or sky light, or an object whose material emits.
    pub fn has_light(&self) -> bool {
        let emits = |m: MaterialId| {
            self.materials
                .get(m as usize)
                .is_some_and(|m| !m.emission.is_black())
        };
        // A mesh's faces may have materials of their own (MGF, OBJ with MTL).
        !self.lights.is_empty()
            || self
                .objects
                .iter()
                .any(|o| o.materials().iter().any(|&m| emits(m)))
    }

    /// Drops from every material the lobes radiosity does not model
    /// ([`Material::keep_diffuse_lobes`]): the scene every radiosity solver solves.
    pub fn keep_diffuse_lobes(&mut self) {
        self.materials
            .iter_mut()
            .for_each(Material::keep_diffuse_lobes);
    }

    /// An empty scene with a default camera looking down −z from `(0, 0, 5)`.
    pub fn empty(name: &str) -> Self {
        Scene {
            name: name.to_string(),
            camera: Camera {
                position: Vec3::new(0.0, 0.0, 5.0),
                look_at: Vec3::ZERO,
                up: Vec3::Y,
                fov_degrees: 45.0,
                width: 512,
                height: 512,
            },
            materials: Vec::new(),
            textures: Vec::new(),
            objects: Vec::new(),
            lights: Vec::new(),
            sensors: Vec::new(),
            periodic: None,
            spectral: None,
            day: None,
        }
    }

    /// Adds a material and returns its id.
    pub fn add_material(&mut self, m: Material) -> MaterialId {
        self.materials.push(m);
        (self.materials.len() - 1) as MaterialId
    }

    /// Adds a texture and returns its id.
    pub fn add_texture(&mut self, t: Texture) -> TextureId {
        self.textures.push(t);
        (self.textures.len() - 1) as TextureId
    }

    /// Id of the material called `name`.
    pub fn material_id(&self, name: &str) -> Option<MaterialId> {
        self.materials
            .iter()
            .position(|m| m.name == name)
            .map(|i| i as MaterialId)
    }

    /// Adds an object with the identity transform.
    pub fn add_object(&mut self, name: &str, shape: Shape, material: MaterialId) {
        self.objects.push(Object {
            name: Some(name.to_string()),
            shape,
            transform: Default::default(),
            material,
            per_face: false,
        });
    }

    /// A digest of everything in the scene (FNV-1a, 64 bits, of its full description): two
    /// scenes with the same digest are the same scene to every method, so work done on one
    /// may be merged with work done on the other (batches of a run on other machines).
    pub fn digest(&self) -> u64 {
        let text = format!("{self:?}");
        text.bytes().fold(0xcbf2_9ce4_8422_2325, |hash, byte| {
            (hash ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01b3)
        })
    }

    /// The report name of object `index`: its name, or `object-<index>`.
    pub fn object_name(&self, index: usize) -> String {
        self.objects[index]
            .name
            .clone()
            .unwrap_or_else(|| format!("object-{index}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;
    use std::sync::Arc;

    #[test]
    fn a_mesh_face_with_an_emitting_material_of_its_own_is_a_light() {
        let mut scene = Scene::empty("lamp");
        let grey = scene.add_material(Material::diffuse("grey", Rgb::splat(0.5)));
        let lamp = scene.add_material(Material {
            name: "lamp".into(),
            emission: Rgb::splat(1.0),
            ..Material::default()
        });
        let positions = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 0.0)];
        let mut mesh = PolygonMesh::from_triangles(positions, &[[0, 1, 2], [1, 3, 2]]);
        scene.add_object("room", Shape::Mesh(Arc::new(mesh.clone())), grey);
        assert!(!scene.has_light());
        // The second face emits; the object's own material does not.
        mesh.face_materials = Some(vec![grey, lamp]);
        scene.objects[0].shape = Shape::Mesh(Arc::new(mesh));
        assert!(scene.has_light());
    }
}
