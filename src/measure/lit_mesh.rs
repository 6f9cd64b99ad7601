//! A lit mesh: polygons with the radiosity leaving each of their corners, the way a solver
//! hands a solution on for export (lightmap baking, viewing in any mesh viewer).

use crate::color::Rgb64;
use glam::Vec3;

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
    /// Vertex indices of each polygon (3 or 4, counter-clockwise seen from the front).
    pub polygons: Vec<Vec<u32>>,
}

impl LitMesh {
    /// Adds a polygon with its `corners`, unit `normal` and per-corner `radiosity`
    /// (W·m⁻², one per corner).
    pub fn push_polygon(&mut self, corners: &[Vec3], normal: Vec3, radiosity: &[Rgb64]) {
        let first = self.positions.len() as u32;
        for (&p, &b) in corners.iter().zip(radiosity) {
            self.positions.push(p);
            self.normals.push(normal);
            self.radiosity.push(b);
        }
        self.polygons
            .push((first..first + corners.len() as u32).collect());
    }
}
