//! The lights of a scene as the algorithms see them: area lights (emissive objects, sampled
//! by area), point (isotropic or Lambertian), spot and directional lights, and the skies.

use super::SceneGeometry;
use super::sky::{CompiledCieSky, Sky};
use super::surface_material::emitted_toward;
use crate::color::Rgb;
use crate::sampling::warp::uniform_triangle;
use crate::scene::{LightKind, Scene};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// An emissive object: its triangles, chosen in proportion to their area.
#[derive(Clone, Debug)]
pub struct AreaLight {
    /// Scene object index.
    pub object: u32,
    /// Primitive indices of its triangles.
    pub prims: Vec<u32>,
    /// Cumulative area fractions of `prims` (last = 1).
    cdf: Vec<f32>,
    /// Total area, squared scene units.
    pub area: f32,
    /// Emitted power estimate π·L·A summed over sides (W), for choosing lights by power.
    pub power: Rgb,
    /// Radiance toward the front and the back, when it is the same at every point (one
    /// material without an emission texture); `None` when it varies.
    uniform_radiance: Option<[Rgb; 2]>,
}

impl AreaLight {
    /// Radiance toward the front and the back, when it is the same at every point of the
    /// light.
    #[inline]
    pub fn uniform_radiance(&self) -> Option<[Rgb; 2]> {
        self.uniform_radiance
    }
}

/// A point sampled on an area light.
#[derive(Clone, Copy, Debug)]
pub struct AreaSample {
    /// The point (world).
    pub p: Vec3,
    /// Unit front-side normal.
    pub n: Vec3,
    /// Barycentrics `(b1, b2)` of the point on its triangle.
    pub barycentrics: (f32, f32),
    /// Primitive sampled.
    pub prim: u32,
    /// Density with respect to area (1 / light area).
    pub pdf_area: f32,
}

/// All lights of a scene.
#[derive(Clone, Debug, Default)]
pub struct LightSet {
    /// Emissive objects.
    pub area: Vec<AreaLight>,
    /// Point (isotropic or Lambertian), spot and directional lights.
    pub delta: Vec<LightKind>,
    /// The skies (uniform and CIE), if the scene has any.
    pub sky: Option<Sky>,
    /// Per triangle primitive: index into `area` of its area light, or `u32::MAX`.
    light_of_prim: Vec<u32>,
}

impl LightSet {
    /// Collects the lights of `scene`, with emissive objects taken from `geometry`.
    pub fn new(scene: &Scene, geometry: &SceneGeometry) -> Self {
        let mut area: Vec<AreaLight> = Vec::new();
        let mut by_object = std::collections::HashMap::new();
        let mut light_of_prim = vec![u32::MAX; geometry.triangle_count()];
        for prim in 0..geometry.triangle_count() as u32 {
            let (object, material) = geometry.owner(prim);
            let m = &scene.materials[material as usize];
            if !m.is_emissive() {
                continue;
            }
            let tri = geometry
                .triangle(prim)
                .expect("index below the triangle count");
            let a = tri.area();
            let mean_emission = match m.emission_texture {
                Some(t) => m.emission * scene.textures[t as usize].mean_color(),
                None => m.emission,
            };
            let sides = if m.two_sided { 2.0 } else { 1.0 };
            let uniform = m
                .emission_texture
                .is_none()
                .then(|| [true, false].map(|front| emitted_toward(scene, m, Vec2::ZERO, front)));
            let slot = *by_object.entry(object).or_insert_with(|| {
                area.push(AreaLight {
                    object,
                    prims: Vec::new(),
                    cdf: Vec::new(),
                    area: 0.0,
                    power: Rgb::BLACK,
                    uniform_radiance: uniform,
                });
                area.len() - 1
            });
            light_of_prim[prim as usize] = slot as u32;
            let light = &mut area[slot];
            if light.uniform_radiance != uniform {
                light.uniform_radiance = None;
            }
            light.prims.push(prim);
            light.area += a;
            light.cdf.push(light.area);
            light.power += mean_emission * (PI * a * sides);
        }
        for light in &mut area {
            let total = light.area;
            for c in &mut light.cdf {
                *c /= total;
            }
        }
        let mut delta = Vec::new();
        let mut sky: Option<Sky> = None;
        for l in &scene.lights {
            match l.kind {
                LightKind::Sky { radiance } => {
                    let sky = sky.get_or_insert_default();
                    sky.uniform = Some(sky.uniform.unwrap_or(Rgb::BLACK) + radiance);
                }
                LightKind::CieSky {
                    sky: sky_type,
                    sun,
                    diffuse_horizontal,
                } => sky.get_or_insert_default().cie.push(CompiledCieSky::new(
                    sky_type,
                    sun,
                    diffuse_horizontal,
                )),
                LightKind::Point { .. }
                | LightKind::Lambertian { .. }
                | LightKind::Spot { .. }
                | LightKind::Directional { .. } => delta.push(l.kind.clone()),
            }
        }
        LightSet {
            area,
            delta,
            sky,
            light_of_prim,
        }
    }

    /// The index into [`LightSet::area`] of the area light that primitive `prim` belongs to,
    /// if it is an emissive triangle.
    #[inline]
    pub fn area_light_of(&self, prim: u32) -> Option<usize> {
        match self.light_of_prim.get(prim as usize) {
            Some(&i) if i != u32::MAX => Some(i as usize),
            _ => None,
        }
    }

    /// True when the scene has no light at all.
    pub fn is_empty(&self) -> bool {
        self.area.is_empty() && self.delta.is_empty() && self.sky.is_none()
    }

    /// A point on area light `light`, uniformly distributed over its area, from the uniform
    /// numbers `u_pick` (chooses the triangle) and `u` (the point on it).
    #[inline]
    pub fn sample_area(
        &self,
        geometry: &SceneGeometry,
        light: usize,
        u_pick: f32,
        u: Vec2,
    ) -> AreaSample {
        let l = &self.area[light];
        let i = l
            .cdf
            .partition_point(|&c| c <= u_pick)
            .min(l.prims.len() - 1);
        let prim = l.prims[i];
        let (b1, b2) = uniform_triangle(u);
        let (p, n) = geometry.triangle_point(prim, b1, b2);
        AreaSample {
            p,
            n,
            barycentrics: (b1, b2),
            prim,
            pdf_area: 1.0 / l.area,
        }
    }

    /// Radiance that the sample `s` of area light `light` emits toward its front (or back)
    /// side.
    #[inline]
    pub fn area_radiance(
        &self,
        scene: &Scene,
        geometry: &SceneGeometry,
        light: usize,
        s: &AreaSample,
        front: bool,
    ) -> Rgb {
        if let Some([toward_front, toward_back]) = self.area[light].uniform_radiance {
            return if front { toward_front } else { toward_back };
        }
        let material = &scene.materials[geometry.owner(s.prim).1 as usize];
        let (b1, b2) = s.barycentrics;
        let uv = geometry.triangle_uv(s.prim as usize, b1, b2);
        emitted_toward(scene, material, uv, front)
    }
}
