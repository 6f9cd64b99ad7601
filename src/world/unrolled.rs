//! A periodic scene unrolled for the methods that put patches on its surfaces (radiosity):
//! the plot's objects, then copies of them shifted by whole periods wherever they reach into
//! a margin around the plot, as one scene that is all there is. The surfaces of the plot see
//! the light their neighbours reflect as far as the margin reaches; rays toward the sun and
//! the sky still cross the endless field (they are traced in the periodic world the unrolled
//! one keeps, [`World::plot_world`]), so every copy receives the direct light its original
//! does. What the field beyond the margin reflects the radiosity solvers bring by rays
//! (their far field, `radiosity/solve/far_field.rs`), so no margin is needed.
//! A ray traced from a surface (a gather ray, a sensor's) that leaves the margin meets the
//! field beyond it as the plot's own surfaces, whose light the solution holds.

use super::World;
use super::scene_geometry::{GeometryError, SurfaceHit};
use crate::accel::PrimitiveSet;
use crate::geometry::{Aabb, Ray, Transform};
use crate::scene::Scene;
use glam::Vec3;
use std::sync::Arc;

/// Plots the margin's outer rectangle may cover at most (ten periods beyond each side of a
/// square plot; the default margin, none, covers one).
const MAX_PLOTS: f32 = 441.0;

impl World {
    /// This periodic world unrolled with a margin of `margin` scene units around its plot
    /// (module doc): a world that is not periodic, whose first objects are the plot's, in
    /// order, followed by the copies (named `<name> @ i,k`, shifted by `i` periods in x and
    /// `k` in z), and whose rays toward lights cross the endless field of this world. `None`
    /// when this world is not periodic.
    pub fn unrolled(self: &Arc<World>, margin: f32) -> Result<Option<World>, GeometryError> {
        let Some(field) = self.field() else {
            return Ok(None);
        };
        let plot = field.plot;
        let period = plot.period();
        let mut bounds = vec![Aabb::EMPTY; self.scene.objects.len()];
        for prim in 0..self.geometry.len() as u32 {
            let object = self.geometry.owner(prim).0 as usize;
            bounds[object] =
                bounds[object].union(PrimitiveSet::bounds(self.geometry.as_ref(), prim));
        }
        // Every plot the margin's outer rectangle covers holds a copy of the scene: a margin
        // of many periods would copy it without bound.
        let plots = (1.0 + 2.0 * margin / period.x) * (1.0 + 2.0 * margin / period.y);
        if plots.is_nan() || plots > MAX_PLOTS {
            return Err(GeometryError::Degenerate {
                object: "the periodic plot".into(),
                reason: format!(
                    "a margin of {margin} covers {plots:.0} plots around it; at most \
                     {MAX_PLOTS} (give a smaller --periodic-margin)"
                ),
            });
        }
        let (lo, hi) = (
            [plot.x[0] - margin, plot.z[0] - margin],
            [plot.x[1] + margin, plot.z[1] + margin],
        );
        let mut scene: Scene = self.scene.clone();
        scene.periodic = None;
        for (index, object) in self.scene.objects.iter().enumerate() {
            let b = bounds[index];
            if b.is_empty() {
                continue;
            }
            // Shift i·p overlaps the margin's outer rectangle when min + i·p < hi and
            // max + i·p > lo.
            let shifts = |min: f32, max: f32, lo: f32, hi: f32, p: f32| {
                let first = ((lo - max) / p).floor() as i64;
                let last = ((hi - min) / p).ceil() as i64;
                (first..=last).filter(move |&i| min + i as f32 * p < hi && max + i as f32 * p > lo)
            };
            let name = self.scene.object_name(index);
            for i in shifts(b.min.x, b.max.x, lo[0], hi[0], period.x) {
                for k in shifts(b.min.z, b.max.z, lo[1], hi[1], period.y) {
                    if (i, k) == (0, 0) {
                        continue;
                    }
                    let shift = Vec3::new(i as f32 * period.x, 0.0, k as f32 * period.y);
                    let mut copy = object.clone();
                    copy.transform = object.transform.then(&Transform::translate(shift));
                    copy.name = Some(format!("{name} @ {i},{k}"));
                    scene.objects.push(copy);
                }
            }
        }
        let mut world = World::new(scene, self.kind)?;
        world.unrolls = Some(Arc::clone(self));
        Ok(Some(world))
    }

    /// The world whose scene is reported and through which rays toward lights are traced:
    /// the periodic world this one unrolls ([`World::unrolled`]), or this world itself.
    pub fn plot_world(&self) -> &World {
        self.unrolls.as_deref().unwrap_or(self)
    }

    /// Where `ray`, which met none of this unrolled world's surfaces, meets the endless field
    /// of `plot` beyond the margin: that surface as this world holds it in the plot (the hit
    /// in the periodic world lies in the plot; the last stretch of the ray is traced again
    /// here, from a ten-thousandth of a period before it), at the ray's whole length. `None`
    /// when the ray leaves the field for the sky. So what the field beyond the margin
    /// reflects is read off the plot's own patches.
    pub(super) fn beyond_margin(&self, plot: &World, ray: &Ray) -> Option<SurfaceHit> {
        let far = plot.intersect(ray)?;
        let period = plot.field().map_or(1.0, |f| f.plot.period().max_element());
        let back = 1e-4 * period;
        let last = Ray::new(far.p - ray.dir * back, ray.dir);
        let hit = self.closest_hit(&last, 2.0 * back)?;
        let mut surface = self.geometry.describe(&hit, &last);
        surface.t = far.t;
        Some(surface)
    }

    /// How many of this world's objects are the scene's own, in order (the rest copies of
    /// them, [`World::unrolled`]): all of them unless it is unrolled.
    pub fn own_objects(&self) -> usize {
        self.plot_world().scene.objects.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::AccelKind;
    use crate::color::Rgb;
    use crate::scene::{Material, Object, Periodic, Shape};

    /// A periodic plot 2 × 2 (x, z ∈ [−1, 1]) with a 0.5 × 0.5 quad at y = 0 in its corner,
    /// x, z ∈ [0.5, 1].
    fn plot_world() -> Arc<World> {
        let mut scene = Scene::empty("plot");
        let m = scene.add_material(Material::diffuse("grey", Rgb::splat(0.5)));
        scene.objects.push(Object {
            name: Some("leaf".into()),
            shape: Shape::Parallelogram {
                origin: Vec3::new(0.5, 0.0, 0.5),
                edge_u: Vec3::new(0.0, 0.0, 0.5),
                edge_v: Vec3::new(0.5, 0.0, 0.0),
            },
            transform: Transform::default(),
            material: m,
            per_face: false,
        });
        scene.periodic = Some(Periodic::new([-1.0, 1.0], [-1.0, 1.0]).unwrap());
        Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
    }

    #[test]
    fn copies_reach_into_the_margin_and_lights_see_the_endless_field() {
        let world = plot_world();
        let unrolled = world.unrolled(0.6).unwrap().unwrap();
        // The quad at [0.5, 1] reaches into the margin [−1.6, 1.6] shifted by −2 (to
        // [−1.5, −1]) and by 0: in x and z, so 2 × 2 places, three of them copies.
        let names: Vec<String> = (0..unrolled.scene.objects.len())
            .map(|i| unrolled.scene.object_name(i))
            .collect();
        assert_eq!(
            names,
            ["leaf", "leaf @ -1,-1", "leaf @ -1,0", "leaf @ 0,-1"]
        );
        assert_eq!(unrolled.own_objects(), 1);
        assert!(unrolled.field().is_none());
        assert!(std::ptr::eq(unrolled.plot_world(), world.as_ref()));
        // The copy at x, z ∈ [−1.5, −1] is there to rays from below…
        let up = Ray::new(Vec3::new(-1.25, -1.0, -1.25), Vec3::Y);
        assert!(unrolled.occluded(&up, 10.0));
        // …and where the margin ends the plot world still blocks a ray that runs on, which
        // meets the quad as the plot holds it, at the ray's whole length.
        let far = Ray::new(Vec3::new(-5.25, -1.0, -5.25), Vec3::Y);
        assert!(!unrolled.occluded(&far, 10.0));
        assert!(unrolled.plot_world().occluded(&far, 10.0));
        let hit = unrolled
            .intersect(&far)
            .expect("the field beyond the margin");
        assert_eq!(hit.object, 0);
        assert!(
            (hit.p - Vec3::new(0.75, 0.0, 0.75)).length() < 1e-4,
            "{:?}",
            hit.p
        );
        assert!((hit.t - 1.0).abs() < 1e-4, "{}", hit.t);
        let sky = Ray::new(Vec3::new(-5.0, -1.0, -5.0), Vec3::Y);
        assert!(unrolled.intersect(&sky).is_none());
        assert!(world.unrolled(0.6).unwrap().is_some());
        assert!(world.unrolled(25.0).is_err());
        let plain = Arc::new(World::new(Scene::empty("none"), AccelKind::Bvh).unwrap());
        assert!(plain.unrolled(1.0).unwrap().is_none());
    }
}
