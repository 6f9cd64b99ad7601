//! The scene compiled for ray queries: what every light-transport algorithm shares.
//!
//! A [`World`] holds the scene, its geometry flattened into world-space primitives
//! ([`SceneGeometry`], the second stage of intersection included), an accelerator over them,
//! and the lights as samplers see them ([`LightSet`]), with the irradiance a non-surface
//! light sends to a point ([`point_irradiance`]). [`SurfaceMaterial`] is a material at a
//! surface point with its textures applied; [`lobes`] holds what the ray tracers, the path
//! tracer and the light model ask of each lobe it scatters by (one file per lobe), on the
//! mirror, refraction and Fresnel formulas of [`optics`].
//!
//! Invariant: primitive indices are fixed when the world is built (triangles first, sorted
//! along a Morton curve, then analytic shapes), so every accelerator, light and hit refers to
//! the same primitive by the same index.

mod light_at_point;
mod lights;
pub mod lobes;
pub mod optics;
mod parallel_shadows;
mod periodic;
mod placed_mesh;
mod ray_bench;
mod scene_geometry;
mod sky;
mod surface_material;
mod unrolled;

pub use light_at_point::{
    non_surface_irradiance, point_irradiance, sees_light, sees_point, sky_irradiance, sky_share,
};
pub use lights::{AreaLight, AreaSample, LightSet};
pub use parallel_shadows::ParallelShadows;
pub use periodic::{Field, MAX_CROSSINGS};
pub use placed_mesh::PLACED_MESH_MIN_TRIANGLES;
pub use ray_bench::{
    PRIMARY_WIDTH, QueryTiming, RANDOM_RAYS, RayBench, RaySet, RaySetError, bench_rays, ray_set,
};
pub use scene_geometry::{
    EMITTER_SEGMENTS, GeometryError, SceneGeometry, SurfaceHit, SurfaceTriangle,
};
pub use sky::{CompiledCieSky, Sky};
pub use surface_material::{SurfaceMaterial, emitted, emitted_toward};

use crate::accel::{AccelKind, AccelStats, Accelerator, PrimHit};
use crate::color::{Rgb, Rgb64};
use crate::geometry::Ray;
use crate::scene::{LightKind, Material, Scene, Shape};
use glam::Vec3;
use std::borrow::Cow;
use std::f32::consts::PI;
use std::sync::Arc;
use std::time::Instant;

/// A scene with everything needed to answer ray queries.
pub struct World {
    /// The scene it was built from.
    pub scene: Scene,
    /// World-space primitives (shared with the worlds [`World::relit`] makes).
    pub geometry: Arc<SceneGeometry>,
    /// The lights.
    pub lights: LightSet,
    /// The accelerator over `geometry`.
    accel: Arc<dyn Accelerator<SceneGeometry>>,
    /// Which accelerator.
    kind: AccelKind,
    /// Wall-clock seconds the accelerator took to build.
    build_seconds: f64,
    /// The plot of a periodic scene with its neighbours' geometry reaching into it.
    field: Option<Arc<Field>>,
    /// The periodic world this one unrolls ([`World::unrolled`]).
    unrolls: Option<Arc<World>>,
}

/// Refuses a material of `scene` that scatters more than it receives (scene files check
/// this with the file's place; scenes built in code meet it here).
fn check_energy(scene: &Scene) -> Result<(), GeometryError> {
    let creates_light = scene.materials.iter().find_map(|m| {
        let sum = m.albedo_bound();
        (sum.is_nan() || sum > 1.0 + crate::scene::ENERGY_TOLERANCE).then_some((m, sum))
    });
    match creates_light {
        Some((m, sum)) => Err(GeometryError::CreatesLight {
            material: m.name.clone(),
            sum,
        }),
        None => Ok(()),
    }
}

impl World {
    /// Flattens `scene` and builds the accelerator `kind` over it; refuses a degenerate shape
    /// and a material that scatters more than it receives.
    pub fn new(scene: Scene, kind: AccelKind) -> Result<World, GeometryError> {
        check_energy(&scene)?;
        let geometry = Arc::new(SceneGeometry::new(&scene)?);
        let start = Instant::now();
        let accel = Arc::from(kind.build(geometry.as_ref()));
        let build_seconds = start.elapsed().as_secs_f64();
        let lights = LightSet::new(&scene, &geometry);
        let field = match scene.periodic {
            Some(plot) => Some(Arc::new(Field::new(plot, &scene, &geometry)?)),
            None => None,
        };
        Ok(World {
            scene,
            geometry,
            lights,
            accel,
            kind,
            build_seconds,
            field,
            unrolls: None,
        })
    }

    /// The world of `scene`, the same geometry as this world's scene with other materials
    /// and lights (a band of a scene with bands, [`crate::scene::Scene::band_groups`]): its
    /// primitives, accelerator and periodic field are this world's, shared, not built again.
    /// Refuses a scene whose objects or plot differ, and what [`World::new`] refuses of
    /// materials.
    pub fn relit(&self, scene: Scene) -> Result<World, GeometryError> {
        if scene.objects != self.scene.objects || scene.periodic != self.scene.periodic {
            return Err(GeometryError::NotRelit);
        }
        check_energy(&scene)?;
        let lights = LightSet::new(&scene, &self.geometry);
        Ok(World {
            scene,
            geometry: Arc::clone(&self.geometry),
            lights,
            accel: Arc::clone(&self.accel),
            kind: self.kind,
            build_seconds: 0.0,
            field: self.field.clone(),
            // An unrolled world's objects are more than its scene's own: refused above.
            unrolls: None,
        })
    }

    /// A warning when the scene is so small that the fixed part of the ray offset
    /// ([`crate::geometry::OFFSET_ABSOLUTE`]) is more than 10⁻⁴ of its size, so that rays
    /// leaving a surface start visibly off it (a room 10⁻⁶ units across loses about 10 % of
    /// its light in the light model): the scene then wants smaller units.
    pub fn scale_warning(&self) -> Option<String> {
        let bounds = self.geometry.bounds();
        let size = (bounds.max - bounds.min).length();
        let smallest = 1e4 * crate::geometry::OFFSET_ABSOLUTE;
        (size > 0.0 && size < smallest).then(|| {
            format!(
                "the scene is {size:.1e} units across: below {smallest:.0e} units the ray \
                 offsets are no longer small against it and results lose accuracy; give \
                 lengths in smaller units (millimetres instead of metres, say)"
            )
        })
    }

    /// The object whose inside holds point `p`, if any: every one of 14 rays from `p` (along
    /// the axes and the cube diagonals) meets the back side of that one object. A camera
    /// there sees only the object's inside (a sphere or box around it, a closed mesh).
    pub fn enclosing_object(&self, p: Vec3) -> Option<u32> {
        let mut directions = vec![
            Vec3::X,
            Vec3::NEG_X,
            Vec3::Y,
            Vec3::NEG_Y,
            Vec3::Z,
            Vec3::NEG_Z,
        ];
        for x in [-1.0, 1.0] {
            for y in [-1.0, 1.0] {
                for z in [-1.0, 1.0] {
                    directions.push(Vec3::new(x, y, z).normalize());
                }
            }
        }
        let mut inside = None;
        for dir in directions {
            let hit = self.intersect(&Ray::new(p, dir))?;
            if hit.front_face || inside.is_some_and(|o| o != hit.object) {
                return None;
            }
            inside = Some(hit.object);
        }
        inside
    }

    /// This world with every curved analytic shape (sphere, cylinder, cone, frustum) replaced
    /// by its polygon mesh of `segments` segments around the axis, with the same accelerator
    /// kind: the surfaces that methods working on those meshes (radiosity patches) must see,
    /// since the facets lie off the true surface. `None` when there is no curved shape,
    /// so this world serves as it is.
    pub fn faceted(&self, segments: u32) -> Result<Option<World>, GeometryError> {
        self.meshed(segments, Shape::is_curved)
    }

    /// This world with every analytic shape (curved ones as in [`World::faceted`], boxes
    /// exactly) replaced by its polygon mesh: a world whose surfaces are all triangles, for
    /// methods that put points on them. An infinite plane is refused (it has no mesh).
    /// `None` when there is no analytic shape.
    pub fn tessellated(&self, segments: u32) -> Result<Option<World>, GeometryError> {
        self.meshed(segments, Shape::is_analytic)
    }

    /// This world with the shapes `which` picks replaced by their polygon meshes of
    /// `segments` segments; `None` when it picks none.
    fn meshed(
        &self,
        segments: u32,
        which: fn(&Shape) -> bool,
    ) -> Result<Option<World>, GeometryError> {
        if !self.scene.objects.iter().any(|o| which(&o.shape)) {
            return Ok(None);
        }
        let mut scene = self.scene.clone();
        for (index, object) in scene.objects.iter_mut().enumerate() {
            if which(&object.shape) {
                let mesh =
                    object
                        .shape
                        .to_mesh(segments)
                        .map_err(|reason| GeometryError::Degenerate {
                            object: self.scene.object_name(index),
                            reason,
                        })?;
                object.shape = Shape::Mesh(std::sync::Arc::new(mesh.into_owned()));
            }
        }
        let mut world = World::new(scene, self.kind)?;
        world.unrolls = match &self.unrolls {
            Some(plot) => Some(match plot.meshed(segments, which)? {
                Some(meshed) => Arc::new(meshed),
                None => Arc::clone(plot),
            }),
            None => None,
        };
        Ok(Some(world))
    }

    /// This world with the lobes radiosity does not model (Phong, mirror, refraction) dropped
    /// from every material ([`Scene::keep_diffuse_lobes`]), with the same
    /// accelerator kind: what the radiosity methods solve, so that the rays they trace (the
    /// final gather at the reported surfaces) count that light as absorbed, as their
    /// solutions do. `None` when every material is diffuse, so this world serves as it is.
    pub fn diffuse(&self) -> Result<Option<World>, GeometryError> {
        if self.scene.materials.iter().all(|m| m.is_diffuse()) {
            return Ok(None);
        }
        let mut scene = self.scene.clone();
        scene.keep_diffuse_lobes();
        let mut world = World::new(scene, self.kind)?;
        world.unrolls = match &self.unrolls {
            Some(plot) => Some(match plot.diffuse()? {
                Some(diffuse) => Arc::new(diffuse),
                None => Arc::clone(plot),
            }),
            None => None,
        };
        Ok(Some(world))
    }

    /// The closest surface hit along `ray` (unbounded), described. In a periodic scene, the
    /// closest hit in the endless field: the ray starts from its origin moved into the plot
    /// and wraps from side to side ([`Field`]); the hit point lies in the plot. In a world
    /// unrolled from one ([`World::unrolled`]), a ray that leaves the margin meets the field
    /// beyond it as the plot's own surfaces.
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<SurfaceHit> {
        if let Some(field) = &self.field {
            return self.intersect_field(field, ray);
        }
        let hit = self
            .closest_hit(ray, f32::INFINITY)
            .map(|h| self.geometry.describe(&h, ray));
        match &self.unrolls {
            Some(plot) if hit.is_none() => self.beyond_margin(plot, ray),
            _ => hit,
        }
    }

    /// The plot of a periodic scene as ray queries see it; `None` for a scene that is all
    /// there is.
    pub fn field(&self) -> Option<&Field> {
        self.field.as_deref()
    }

    /// The closest primitive hit along `ray` with `t ∈ (0, t_max]`, not yet described (the
    /// first stage of intersection: distance and primitive only), among the scene's own
    /// primitives (in a periodic scene, the plot's geometry as it is, without its copies).
    #[inline]
    pub fn closest_hit(&self, ray: &Ray, t_max: f32) -> Option<PrimHit> {
        self.accel.closest_hit(&self.geometry, ray, t_max)
    }

    /// Whether anything blocks `ray` for `t ∈ (0, t_max]`; in a periodic scene, anything of
    /// the endless field, the ray wrapping from side to side as in [`Self::intersect`].
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        if let Some(field) = &self.field {
            return self.occluded_field(field, ray, t_max);
        }
        self.accel_any_hit(ray, t_max)
    }

    /// Whether any of the scene's own primitives blocks `ray` for `t ∈ (0, t_max]`.
    #[inline]
    fn accel_any_hit(&self, ray: &Ray, t_max: f32) -> bool {
        self.accel.any_hit(&self.geometry, ray, t_max)
    }

    /// The sphere through which directional and sky light enter the scene (centre, radius in
    /// scene units): the bounding sphere of the bounded geometry, a little larger so that no
    /// light starts on the geometry it is aimed at.
    pub fn entry_sphere(&self) -> (Vec3, f32) {
        let (center, radius) = self.geometry.bounding_sphere();
        (center, radius * 1.001 + 1e-6)
    }

    /// The power (W per channel) all the scene's lights that are not surfaces send into it,
    /// each as [`World::light_power`] says.
    pub fn lights_power(&self) -> Rgb64 {
        self.scene
            .lights
            .iter()
            .map(|l| self.light_power(&l.kind).to_f64())
            .sum()
    }

    /// The power (W per channel) a light that is not a surface sends into the scene, the one
    /// definition every solver reports: point 4π·I, spot I times its solid angle
    /// ([`LightKind::power`]), directional E·πR², sky of radiance L 4π²R²·L (the power
    /// entering the entry sphere of radius R from outside), CIE sky πR²·∫L dω over the upper
    /// hemisphere (the same, from above the horizon only). In a periodic scene, what these
    /// send into the plot of area A through its top and bottom: directional E·A·cos θ (θ
    /// from the downward vertical; nothing from a light going up), sky 2π·A·L (from above
    /// and from below), CIE sky A times its diffuse horizontal irradiance.
    pub fn light_power(&self, light: &LightKind) -> Rgb {
        if let Some(field) = &self.field {
            let area = field.plot.area();
            match *light {
                LightKind::Directional {
                    direction,
                    irradiance,
                } => {
                    let down = (-direction.normalize_or_zero().y).max(0.0);
                    return irradiance * (area * down);
                }
                LightKind::Sky { radiance } => return radiance * (2.0 * PI * area),
                LightKind::CieSky {
                    diffuse_horizontal, ..
                } => return diffuse_horizontal * area,
                LightKind::Point { .. } | LightKind::Lambertian { .. } | LightKind::Spot { .. } => {
                }
            }
        }
        let (_, radius) = self.entry_sphere();
        match *light {
            LightKind::Sky { radiance } => radiance * (4.0 * PI * PI * radius * radius),
            LightKind::CieSky { .. } => self.cie_sky(light).map_or(Rgb::BLACK, |sky| {
                sky.radiance_integral().to_f32() * (PI * radius * radius)
            }),
            ref kind => kind.power(radius).unwrap_or(Rgb::BLACK),
        }
    }

    /// The compiled CIE sky of `light`: this world's, or compiled now for a CIE sky the
    /// world does not hold; `None` for any other kind of light.
    pub fn cie_sky(&self, light: &LightKind) -> Option<Cow<'_, CompiledCieSky>> {
        if let Some(sky) = self.lights.sky.as_ref().and_then(|s| s.cie_of(light)) {
            return Some(Cow::Borrowed(sky));
        }
        match *light {
            LightKind::CieSky {
                sky,
                sun,
                diffuse_horizontal,
            } => Some(Cow::Owned(CompiledCieSky::new(
                sky,
                sun,
                diffuse_horizontal,
            ))),
            LightKind::Point { .. }
            | LightKind::Lambertian { .. }
            | LightKind::Spot { .. }
            | LightKind::Directional { .. }
            | LightKind::Sky { .. } => None,
        }
    }

    /// The material of `hit`.
    #[inline]
    pub fn material(&self, hit: &SurfaceHit) -> &Material {
        &self.scene.materials[hit.material as usize]
    }

    /// Size and shape of the accelerator.
    pub fn accel_stats(&self) -> AccelStats {
        self.accel.stats()
    }

    /// Wall-clock seconds the accelerator took to build.
    pub fn build_seconds(&self) -> f64 {
        self.build_seconds
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builtin;

    #[test]
    fn a_point_inside_a_closed_object_is_found_and_one_outside_is_not() {
        let mut scene = Scene::empty("ball");
        let m = scene.add_material(Material::default());
        scene.add_object(
            "ball",
            Shape::Sphere {
                center: Vec3::ZERO,
                radius: 2.0,
            },
            m,
        );
        scene.add_object(
            "box",
            Shape::Box {
                min: Vec3::splat(4.0),
                max: Vec3::splat(5.0),
            },
            m,
        );
        let world = World::new(scene, AccelKind::Bvh).unwrap();
        assert_eq!(world.enclosing_object(Vec3::new(0.5, 0.2, 0.0)), Some(0));
        assert_eq!(world.enclosing_object(Vec3::splat(4.5)), Some(1));
        assert_eq!(world.enclosing_object(Vec3::new(0.0, 0.0, 3.0)), None);
        let cornell = builtin::load("cornell").unwrap().unwrap();
        let camera = cornell.camera.position;
        let world = World::new(cornell, AccelKind::Bvh).unwrap();
        assert_eq!(world.enclosing_object(camera), None);
    }
}
