//! Looking up a radiosity solution along a ray: the leaf patches as triangles under a BVH, and
//! a value per element shown flat or interpolated from the patch corners. The display shows
//! what camera rays meet; final gathering reads the light reflected where gather rays land.

use super::interpolate::{CornerValues, VertexWelding};
use super::patch_triangles::{PatchTriangles, hit_in_field};
use super::system::RadiositySystem;
use crate::accel::{AccelKind, Accelerator, PrimHit};
use crate::color::{Rgb, Rgb64};
use crate::geometry::{Ray, spawn_ray};
use crate::radiosity::element::Side;
use crate::radiosity::mesh::Patch;
use crate::radiosity::surface::{
    TextureAt, emission_of, is_textured, reflectance_of, translucency_of,
};
use glam::DVec2;
use std::f64::consts::PI;

/// How radiosity is shown across a patch (`--shading`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Shading {
    /// One colour per leaf patch.
    Flat,
    /// Corner values interpolated linearly over each triangle of the leaf.
    #[default]
    Smooth,
}

crate::choice::named_values!(Shading {
    Shading::Flat = "flat", "One colour per leaf patch";
    Shading::Smooth = "smooth", "Radiosity interpolated to the patch corners, smooth across the facets of curved shapes";
});

/// Where a ray meets the leaf mesh.
pub struct LeafHit<'a> {
    /// The leaf patch.
    pub patch: &'a Patch,
    /// The point hit, scene units.
    pub point: glam::DVec3,
    /// Distance along the ray, scene units.
    pub distance: f64,
    /// Radiance `value/π` there (W·sr⁻¹·m⁻² when the values are radiosities), on the side
    /// the ray meets.
    pub radiance: Rgb,
}

/// A value per element, flat or with smooth corner values.
struct ElementValues {
    /// Per element.
    flat: Vec<Rgb64>,
    /// Smooth corner values per side, per leaf (empty when flat).
    corners: [Vec<CornerValues>; 2],
}

impl ElementValues {
    fn new(system: &RadiositySystem, values: Vec<Rgb64>, shading: Shading) -> Self {
        let welding = match shading {
            Shading::Smooth => Some(VertexWelding::new(&system.mesh, &system.leaves)),
            Shading::Flat => None,
        };
        let corners = Side::BOTH.map(|side| match &welding {
            Some(welding) => {
                let per_leaf: Vec<Rgb64> = (0..system.leaves.len())
                    .map(|k| values[RadiositySystem::element(k, side)])
                    .collect();
                welding.smooth(&per_leaf)
            }
            None => Vec::new(),
        });
        ElementValues {
            flat: values,
            corners,
        }
    }

    /// The value on side `side` of leaf `leaf` at barycentric `(b1, b2)` of the leaf's
    /// triangle with corners `corner_ids`.
    fn at(&self, leaf: usize, side: Side, corner_ids: [u8; 3], [b1, b2]: [f64; 2]) -> Rgb64 {
        let corners = &self.corners[side.index()];
        if corners.is_empty() {
            return self.flat[RadiositySystem::element(leaf, side)];
        }
        let c = &corners[leaf];
        let w = [1.0 - b1 - b2, b1, b2];
        Rgb64::from(std::array::from_fn(|ch| {
            (0..3).map(|v| w[v] * c[corner_ids[v] as usize][ch]).sum()
        }))
    }
}

/// Irradiance per element, so that a textured surface shows its texture at full resolution
/// (seed 000 §7.5 without the second, coarse texture): where a ray meets a patch whose
/// material has a texture, the value shown is `E(uv)·[emitted] + ρ(uv)·H`, the texture taken
/// at the point hit and `H` looked up as the values are.
struct TextureDetail {
    irradiance: ElementValues,
    /// Whether the value includes the surface's own emission.
    emitted: bool,
}

/// A value per element of a solved system (a radiosity, W·m⁻²), found along rays.
pub struct RadiosityLookup<'s> {
    system: &'s RadiositySystem,
    triangles: PatchTriangles,
    accel: Box<dyn Accelerator<PatchTriangles>>,
    values: ElementValues,
    detail: Option<TextureDetail>,
    shading: Shading,
}

impl<'s> RadiosityLookup<'s> {
    /// The lookup of `values` (one per element of `system`, in element order) shown by
    /// `shading`.
    pub fn new(system: &'s RadiositySystem, values: Vec<Rgb64>, shading: Shading) -> Self {
        let triangles = PatchTriangles::new(&system.mesh, &system.leaves);
        let accel = AccelKind::Bvh.build(&triangles);
        RadiosityLookup {
            system,
            triangles,
            accel,
            values: ElementValues::new(system, values, shading),
            detail: None,
            shading,
        }
    }

    /// This lookup showing textured surfaces at full resolution: there the value is
    /// `E(uv) + ρ(uv)·H` (or `ρ(uv)·H` when not `emitted`), from `irradiance` (one per
    /// element, W·m⁻²) and the textures at the point hit, instead of the element's value.
    pub fn with_texture_detail(mut self, irradiance: Vec<Rgb64>, emitted: bool) -> Self {
        self.detail = Some(TextureDetail {
            irradiance: ElementValues::new(self.system, irradiance, self.shading),
            emitted,
        });
        self
    }

    /// The first leaf `ray` meets where its surface is present (an alpha texture's cut-away
    /// parts let the ray pass), and the radiance of the value there.
    pub fn hit(&self, ray: &Ray) -> Option<LeafHit<'_>> {
        self.first_hit(ray, true)
    }

    /// The first leaf `ray` meets, cut away or not, and the radiance there as if its surface
    /// were present (what a lightmap holds under a cut-out: never shown, but filtered into
    /// the texels beside it).
    pub fn hit_even_where_cut(&self, ray: &Ray) -> Option<LeafHit<'_>> {
        self.first_hit(ray, false)
    }

    /// The first leaf `ray` meets, passing through cut-away parts when `pass_cut_outs`. On
    /// a periodic plot (a system solved on its unrolled world) a ray that passes cut-outs
    /// meets the endless field: the leaf under the point it meets there.
    fn first_hit(&self, ray: &Ray, pass_cut_outs: bool) -> Option<LeafHit<'_>> {
        let world = self.system.world();
        let scene = &world.scene;
        let plot = world.plot_world();
        if pass_cut_outs && plot.field().is_some() {
            let hit = hit_in_field(plot, &self.triangles, self.accel.as_ref(), ray)?;
            return Some(self.leaf_hit(ray, hit, 0.0));
        }
        let mut ray = *ray;
        let mut travelled = 0.0;
        let hit = loop {
            let hit = self
                .accel
                .closest_hit(&self.triangles, &ray, f32::INFINITY)?;
            let (_, _, patch, uv) = self.place(&hit);
            let alpha = scene.materials[patch.material as usize]
                .alpha_texture
                .filter(|_| pass_cut_outs);
            match alpha.and_then(|t| scene.textures.get(t as usize)) {
                Some(t) if !t.is_present(uv.as_vec2()) => {
                    let triangle = &self.triangles.triangles[hit.prim as usize];
                    let at = triangle.point(hit.local[0], hit.local[1]);
                    travelled += hit.t;
                    ray = spawn_ray(at, triangle.normal_area2().normalize(), ray.dir);
                }
                _ => break hit,
            }
        };
        Some(self.leaf_hit(&ray, hit, travelled))
    }

    /// Where `hit` lies: the leaf, the corners of its triangle, the leaf's patch and the
    /// texture coordinates there.
    fn place(&self, hit: &PrimHit) -> (usize, [u8; 3], &Patch, DVec2) {
        let (leaf, corner_ids) = self.triangles.owners[hit.prim as usize];
        let patch = self.system.mesh.patch(self.system.leaves[leaf as usize]);
        let [b1, b2] = hit.local.map(f64::from);
        let uvs = corner_ids.map(|c| patch.uvs()[c as usize]);
        let uv = uvs[0] * (1.0 - b1 - b2) + uvs[1] * b1 + uvs[2] * b2;
        (leaf as usize, corner_ids, patch, uv)
    }

    /// What `ray` meets at `hit`, `travelled` scene units along it before.
    fn leaf_hit(&self, ray: &Ray, hit: PrimHit, travelled: f32) -> LeafHit<'_> {
        let scene = &self.system.world().scene;
        let (leaf, corner_ids, patch, uv) = self.place(&hit);
        let side = Side::hit_by(patch, ray.dir.as_dvec3());
        let local = hit.local.map(f64::from);
        let value = match &self.detail {
            Some(detail) if is_textured(scene, patch.material) => {
                let at = TextureAt::Point(uv);
                let h = detail.irradiance.at(leaf, side, corner_ids, local);
                let e = if detail.emitted {
                    emission_of(scene, patch.material, side, at)
                } else {
                    Rgb64::BLACK
                };
                let tau = translucency_of(scene, patch.material, at);
                let passed = if tau.is_black() {
                    Rgb64::BLACK
                } else {
                    tau * detail.irradiance.at(leaf, side.other(), corner_ids, local)
                };
                e + reflectance_of(scene, patch.material, side, at) * h + passed
            }
            _ => self.values.at(leaf, side, corner_ids, local),
        };
        let point = self.triangles.triangles[hit.prim as usize]
            .point(hit.local[0], hit.local[1])
            .as_dvec3();
        LeafHit {
            patch,
            point,
            distance: f64::from(travelled + hit.t),
            radiance: value.map(|x| x / PI).to_f32(),
        }
    }
}
