//! A scene ready for tracing: flattened geometry, an accelerator over it, and its lights.

use super::{GeometryError, LightSet, SceneGeometry, SurfaceHit};
use crate::accel::{AccelKind, Accelerator};
use crate::geometry::Ray;
use crate::scene::{Material, Scene};
use std::time::Instant;

/// A scene with everything needed to answer ray queries.
pub struct World {
    /// The scene it was built from.
    pub scene: Scene,
    /// World-space primitives.
    pub geometry: SceneGeometry,
    /// The accelerator over `geometry`.
    pub accel: Box<dyn Accelerator<SceneGeometry>>,
    /// Which accelerator was built.
    pub accel_kind: AccelKind,
    /// Wall-clock seconds the accelerator took to build.
    pub build_seconds: f64,
    /// The lights.
    pub lights: LightSet,
}

impl World {
    /// Flattens `scene` and builds the accelerator `kind` over it.
    pub fn new(scene: Scene, kind: AccelKind) -> Result<World, GeometryError> {
        let geometry = SceneGeometry::new(&scene)?;
        let start = Instant::now();
        let accel = kind.build(&geometry);
        let build_seconds = start.elapsed().as_secs_f64();
        let lights = LightSet::new(&scene, &geometry);
        Ok(World {
            scene,
            geometry,
            accel,
            accel_kind: kind,
            build_seconds,
            lights,
        })
    }

    /// The closest surface hit along `ray` (unbounded).
    pub fn intersect(&self, ray: &Ray) -> Option<SurfaceHit> {
        self.accel
            .closest_hit(&self.geometry, ray, f32::INFINITY)
            .map(|h| self.geometry.describe(&h, ray))
    }

    /// Whether anything blocks `ray` for `t ∈ (0, t_max]`.
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.accel.any_hit(&self.geometry, ray, t_max)
    }

    /// The material of `hit`.
    pub fn material(&self, hit: &SurfaceHit) -> &Material {
        &self.scene.materials[hit.material as usize]
    }
}
