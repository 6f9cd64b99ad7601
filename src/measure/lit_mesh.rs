//! A lit mesh: polygons with the radiosity leaving each of their corners, the way a solver
//! hands a solution on for export (viewing in any mesh viewer); textured surfaces come with
//! a lightmap of what they look like, at the texture's resolution.

use super::Film;
use crate::color::Rgb64;
use crate::scene::TextureId;
use glam::{Vec2, Vec3};

/// A textured surface of a lit mesh, shown by its lightmap: the linear radiance leaving it
/// (W·sr⁻¹·m⁻², texture detail and emission included), over a chart of its own per side
/// and face.
#[derive(Clone, Debug, PartialEq)]
pub struct LightmappedSurface {
    /// Its name (the object's).
    pub name: String,
    /// The material's diffuse texture, an index into the scene's textures.
    pub base_texture: Option<TextureId>,
    /// The material's alpha texture (cut-outs), an index into the scene's textures.
    pub alpha_texture: Option<TextureId>,
    /// The lightmap, linear radiance per texel; row 0 on top, texture coordinate `(0, 0)`
    /// at the bottom-left corner as for every texture.
    pub lightmap: Film,
}

/// Polygons (triangles or quads) with per-corner radiosity. Every polygon has its own
/// corners: neighbours that share a position keep separate vertices, so values may jump
/// across an edge (between surfaces) or match (within one surface).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LitMesh {
    /// Vertex positions, scene units.
    pub positions: Vec<Vec3>,
    /// Unit normal per vertex (the front side of its polygon).
    pub normals: Vec<Vec3>,
    /// Radiosity leaving the vertex's surface, W·m⁻².
    pub radiosity: Vec<Rgb64>,
    /// Irradiance arriving at the vertex on its polygon's side, W·m⁻².
    pub irradiance: Vec<Rgb64>,
    /// Vertex indices of each polygon (3 or 4, counter-clockwise seen from the front).
    pub polygons: Vec<Vec<u32>>,
    /// Per vertex: the material's texture coordinates (`(0, 0)` on untextured surfaces).
    pub texcoords: Vec<Vec2>,
    /// Per vertex: where it lies in its surface's lightmap (`(0, 0)` on surfaces without
    /// one).
    pub lightmap_texcoords: Vec<Vec2>,
    /// Per polygon: the lightmapped surface it belongs to (an index into `surfaces`), `None`
    /// for surfaces shown by their corners' radiosity.
    pub polygon_surface: Vec<Option<u32>>,
    /// Per polygon: the index of the scene object it lies on.
    pub polygon_object: Vec<u32>,
    /// The textured surfaces and their lightmaps.
    pub surfaces: Vec<LightmappedSurface>,
}

impl LitMesh {
    /// Adds a polygon of scene object `object` with its `corners`, unit `normal` and
    /// per-corner `(radiosity, irradiance)` (W·m⁻², one each per corner).
    pub fn push_polygon(
        &mut self,
        object: u32,
        corners: &[Vec3],
        normal: Vec3,
        values: (&[Rgb64], &[Rgb64]),
    ) {
        let zero = vec![Vec2::ZERO; corners.len()];
        self.push_mapped_polygon(object, corners, normal, values, (&zero, &zero), None);
    }

    /// [`Self::push_polygon`] with per-corner texture coordinates `(material, lightmap)` on
    /// lightmapped surface `surface` (an index into `surfaces`, `None` for none).
    pub fn push_mapped_polygon(
        &mut self,
        object: u32,
        corners: &[Vec3],
        normal: Vec3,
        (radiosity, irradiance): (&[Rgb64], &[Rgb64]),
        (texcoords, lightmap_texcoords): (&[Vec2], &[Vec2]),
        surface: Option<u32>,
    ) {
        let first = self.positions.len() as u32;
        for (k, &p) in corners.iter().enumerate() {
            self.positions.push(p);
            self.normals.push(normal);
            self.radiosity.push(radiosity[k]);
            self.irradiance.push(irradiance[k]);
            self.texcoords.push(texcoords[k]);
            self.lightmap_texcoords.push(lightmap_texcoords[k]);
        }
        self.polygons
            .push((first..first + corners.len() as u32).collect());
        self.polygon_surface.push(surface);
        self.polygon_object.push(object);
    }
}
