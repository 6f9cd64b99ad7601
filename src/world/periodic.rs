//! A periodic scene compiled for ray queries: the plot's geometry and its copies in the
//! neighbouring plots that reach into it, and the closest hit along a ray that wraps from
//! one side of the plot to the opposite one.
//!
//! A ray is followed through the plot one crossing at a time: from its origin (moved into
//! the plot) to where it leaves through a side, the closest hit on the plot's geometry or on
//! one of its copies shifted by whole periods (the copies that reach into the plot, found
//! once when the world is built, [`Field::new`]) is the hit; with none, the ray continues
//! from the opposite side. It escapes when it is above all geometry going up or below it
//! going down, or after [`MAX_CROSSINGS`] crossings (a ray all but horizontal in an empty
//! layer). A ray starting above all geometry going down (a camera's, a sun's) skips
//! straight to just above the highest geometry (and one below all going up, to just below).

use super::World;
use super::scene_geometry::{GeometryError, SceneGeometry, SurfaceHit};
use crate::accel::PrimitiveSet;
use crate::geometry::Ray;
use crate::scene::{Periodic, Scene};
use glam::Vec3;

/// Crossings of the plot after which a ray that met nothing counts as escaped.
pub const MAX_CROSSINGS: u32 = 1000;
/// Copies of the plot's geometry a ray may have to be tested against, at most (the plot
/// and its eight neighbours, and more for geometry reaching over a neighbour).
const MAX_COPIES: usize = 25;

/// A periodic scene's plot as ray queries see it.
#[derive(Clone, Debug)]
pub struct Field {
    /// The plot.
    pub plot: Periodic,
    /// Every copy of the geometry that reaches into the plot, the plot's own first: its
    /// shift (whole periods in x and z) and the part of the plot it reaches into, as
    /// `[x_min, x_max, z_min, z_max]`.
    copies: Vec<(Vec3, [f32; 4])>,
    /// Lowest y of all geometry, scene units.
    pub bottom: f32,
    /// Highest y of all geometry, scene units.
    pub top: f32,
}

impl Field {
    /// The field of `plot` over `geometry`; refused when the plot is empty or not finite,
    /// when some geometry is unbounded (an infinite plane would be in every copy at once: a
    /// ground is a quad the plot's size) or reaches more than two periods beyond the plot.
    pub fn new(
        plot: Periodic,
        scene: &Scene,
        geometry: &SceneGeometry,
    ) -> Result<Field, GeometryError> {
        // A plot built in code bypasses the file's check: an empty period would divide by 0.
        let plot = Periodic::new(plot.x, plot.z).map_err(|reason| GeometryError::Degenerate {
            object: "the periodic plot".into(),
            reason,
        })?;
        for prim in 0..geometry.len() as u32 {
            let b = PrimitiveSet::bounds(geometry, prim);
            if !(b.min.is_finite() && b.max.is_finite()) {
                let object = geometry.owner(prim).0 as usize;
                return Err(GeometryError::Degenerate {
                    object: scene.object_name(object),
                    reason: "an unbounded shape cannot be in a periodic scene (give the ground \
                             as a quad covering the plot)"
                        .into(),
                });
            }
        }
        let bounds = geometry.bounds();
        let period = plot.period();
        let mut copies = Vec::new();
        if !bounds.is_empty() {
            // Copy i·period overlaps [lo, hi] when min + i·p < hi and max + i·p > lo.
            let shifts = |min: f32, max: f32, [lo, hi]: [f32; 2], p: f32| {
                let first = ((lo - max) / p).floor() as i64;
                let last = ((hi - min) / p).ceil() as i64;
                (first..=last)
                    .filter(|&i| min + i as f32 * p < hi && max + i as f32 * p > lo)
                    .collect::<Vec<_>>()
            };
            let xs = shifts(bounds.min.x, bounds.max.x, plot.x, period.x);
            let zs = shifts(bounds.min.z, bounds.max.z, plot.z, period.y);
            if xs.len() * zs.len() > MAX_COPIES {
                return Err(GeometryError::Degenerate {
                    object: "the periodic plot".into(),
                    reason: format!(
                        "the geometry spans {} × {} plots; it may reach at most two periods \
                         beyond the plot's sides",
                        xs.len(),
                        zs.len()
                    ),
                });
            }
            for &i in &xs {
                for &k in &zs {
                    let shift = Vec3::new(i as f32 * period.x, 0.0, k as f32 * period.y);
                    let (min, max) = (bounds.min + shift, bounds.max + shift);
                    let reach = [
                        min.x.max(plot.x[0]),
                        max.x.min(plot.x[1]),
                        min.z.max(plot.z[0]),
                        max.z.min(plot.z[1]),
                    ];
                    copies.push((shift, reach));
                }
            }
            copies.sort_by_key(|(shift, _)| shift != &Vec3::ZERO);
        }
        Ok(Field {
            plot,
            copies,
            bottom: bounds.min.y,
            top: bounds.max.y,
        })
    }

    /// The number of copies of the geometry a ray is tested against in every crossing.
    pub fn copies(&self) -> usize {
        self.copies.len()
    }

    /// Where `ray` starts in the plot — its origin moved into it by whole periods, then,
    /// if above all geometry going down (or below it going up), moved along the ray to just
    /// above the highest (below the lowest) geometry, since it meets nothing before — and how far
    /// it was moved along the ray; `None` when it goes away from all geometry.
    fn start(&self, ray: &Ray) -> Option<(Vec3, f32)> {
        let origin = self.plot.wrap(ray.origin);
        let level = if origin.y > self.top {
            self.top
        } else if origin.y < self.bottom {
            self.bottom
        } else {
            return Some((origin, 0.0));
        };
        let t = (level - origin.y) / ray.dir.y;
        if !(t.is_finite() && t > 0.0) {
            return None;
        }
        // Stop a little short of the level, so that a surface lying at it is still ahead.
        let margin = 1e-4 * (self.top - self.bottom).max(self.plot.period().max_element());
        let t = (t - margin / ray.dir.y.abs()).max(0.0);
        Some((self.plot.wrap(origin + ray.dir * t), t))
    }

    /// The shifts of the copies of the geometry that the segment of length `length` from
    /// `origin` (in the plot) along `dir` may meet: those reaching into the part of the plot
    /// it crosses.
    fn reaching(&self, origin: Vec3, dir: Vec3, length: f32) -> impl Iterator<Item = Vec3> + '_ {
        let end = if length.is_finite() {
            origin + dir * length
        } else {
            origin
        };
        let (x0, x1) = (origin.x.min(end.x), origin.x.max(end.x));
        let (z0, z1) = (origin.z.min(end.z), origin.z.max(end.z));
        self.copies
            .iter()
            .filter(move |(_, [rx0, rx1, rz0, rz1])| {
                !(x1 < *rx0 || x0 > *rx1 || z1 < *rz0 || z0 > *rz1)
            })
            .map(|&(shift, _)| shift)
    }

    /// Where a ray from `origin` along `dir` that leaves the plot through `sides` (x, z) after
    /// `t_exit` enters it again: on the opposite side, exactly; `None` when it leaves for good
    /// (a vertical ray, or one above all geometry going up or below it going down).
    fn cross(&self, origin: Vec3, dir: Vec3, t_exit: f32, sides: [bool; 2]) -> Option<Vec3> {
        if !t_exit.is_finite() {
            return None;
        }
        let mut p = origin + dir * t_exit;
        if (p.y > self.top && dir.y >= 0.0) || (p.y < self.bottom && dir.y <= 0.0) {
            return None;
        }
        let enter = |v: f32, d: f32, leaves: bool, [lo, hi]: [f32; 2]| match leaves {
            true if d > 0.0 => lo,
            true => hi,
            false => v.clamp(lo, hi),
        };
        p.x = enter(p.x, dir.x, sides[0], self.plot.x);
        p.z = enter(p.z, dir.z, sides[1], self.plot.z);
        Some(p)
    }

    /// The distance along `ray` (origin in the plot) to where it leaves through a side, and
    /// which sides (x, z) it leaves through there; infinite for a vertical ray.
    fn exit(&self, ray: &Ray) -> (f32, [bool; 2]) {
        let side = |o: f32, d: f32, [lo, hi]: [f32; 2]| {
            if d > 0.0 {
                (hi - o) / d
            } else if d < 0.0 {
                (lo - o) / d
            } else {
                f32::INFINITY
            }
        };
        let tx = side(ray.origin.x, ray.dir.x, self.plot.x).max(0.0);
        let tz = side(ray.origin.z, ray.dir.z, self.plot.z).max(0.0);
        let t = tx.min(tz);
        (t, [tx == t, tz == t])
    }
}

impl World {
    /// Whether anything blocks `ray` for `t ∈ (0, t_max]` in the endless field of a periodic
    /// scene, the ray wrapping from side to side as in [`Self::intersect_field`].
    pub(super) fn occluded_field(&self, field: &Field, ray: &Ray, t_max: f32) -> bool {
        let dir = ray.dir;
        let Some((mut origin, skipped)) = field.start(ray) else {
            return false;
        };
        let mut left = t_max - skipped;
        for _ in 0..MAX_CROSSINGS {
            if left <= 0.0 {
                return false;
            }
            let segment = Ray::new(origin, dir);
            let (t_exit, sides) = field.exit(&segment);
            let limit = t_exit.min(left);
            if field
                .reaching(origin, dir, limit)
                .any(|shift| self.accel_any_hit(&Ray::new(origin - shift, dir), limit))
            {
                return true;
            }
            if t_exit >= left {
                return false;
            }
            match field.cross(origin, dir, t_exit, sides) {
                Some(next) => origin = next,
                None => return false,
            }
            left -= t_exit;
        }
        false
    }

    /// The closest hit along `ray` in the endless field of a periodic scene; the hit point is
    /// in the plot and `t` the distance travelled to it over every crossing.
    pub(super) fn intersect_field(&self, field: &Field, ray: &Ray) -> Option<SurfaceHit> {
        let dir = ray.dir;
        let (mut origin, mut travelled) = field.start(ray)?;
        for _ in 0..MAX_CROSSINGS {
            let segment = Ray::new(origin, dir);
            let (t_exit, sides) = field.exit(&segment);
            let mut t_max = t_exit;
            let mut best = None;
            for shift in field.reaching(origin, dir, t_exit) {
                let shifted = Ray::new(origin - shift, dir);
                if let Some(hit) = self.closest_hit(&shifted, t_max) {
                    t_max = hit.t;
                    best = Some((hit, shifted, shift));
                }
            }
            if let Some((hit, shifted, shift)) = best {
                let mut surface = self.geometry.describe(&hit, &shifted);
                surface.p += shift;
                surface.t += travelled;
                return Some(surface);
            }
            match field.cross(origin, dir, t_exit, sides) {
                Some(next) => origin = next,
                None => return None,
            }
            travelled += t_exit;
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::AccelKind;
    use crate::scene::{Material, Shape};

    /// A plot of 2 × 2 with a unit square at height 1 reaching over its +x side by half.
    fn straddling() -> World {
        let mut scene = Scene::empty("field");
        let m = scene.add_material(Material::default());
        scene.add_object(
            "leaf",
            Shape::Parallelogram {
                origin: Vec3::new(1.5, 1.0, 0.5),
                edge_u: Vec3::X,
                edge_v: Vec3::Z,
            },
            m,
        );
        scene.periodic = Some(Periodic::new([0.0, 2.0], [0.0, 2.0]).unwrap());
        World::new(scene, AccelKind::Bvh).unwrap()
    }

    #[test]
    fn a_ray_meets_the_part_of_a_leaf_beyond_the_side_through_the_opposite_side() {
        let world = straddling();
        let down = |x: f32, z: f32| world.intersect(&Ray::new(Vec3::new(x, 2.0, z), -Vec3::Y));
        // The part inside the plot, the part beyond x = 2 seen at x − 2, and a gap.
        let inside = down(1.7, 1.0).expect("hit");
        assert!((inside.p - Vec3::new(1.7, 1.0, 1.0)).length() < 1e-5);
        let copy = down(0.3, 1.0).expect("hit through the copy");
        assert!((copy.p - Vec3::new(0.3, 1.0, 1.0)).length() < 1e-5);
        assert_eq!(copy.object, 0);
        assert!(down(1.0, 1.0).is_none() && down(0.3, 1.6).is_none());
        // A ray leaving through −x at height 1.45 going down meets the leaf after crossing
        // two plots, 4.5 along x from where it started.
        let dir = Vec3::new(-1.0, -0.1, 0.0);
        let slanted = Ray::new(Vec3::new(0.2, 1.45, 1.0), dir.normalize());
        let hit = world.intersect(&slanted).expect("hit after wrapping");
        assert!((hit.t - 4.5 * dir.length()).abs() < 1e-4, "{}", hit.t);
        assert!(
            (hit.p - Vec3::new(1.7, 1.0, 1.0)).length() < 1e-4,
            "{:?}",
            hit.p
        );
        // Up, away from everything: escapes.
        let up = Ray::new(
            Vec3::new(1.0, 1.5, 1.0),
            Vec3::new(1.0, 0.2, 0.3).normalize(),
        );
        assert!(world.intersect(&up).is_none());
    }

    #[test]
    fn unbounded_geometry_and_geometry_spanning_many_plots_are_refused() {
        let mut scene = Scene::empty("plane");
        let m = scene.add_material(Material::default());
        scene.add_object(
            "ground",
            Shape::Plane {
                point: Vec3::ZERO,
                normal: Vec3::Y,
            },
            m,
        );
        scene.periodic = Some(Periodic::new([0.0, 1.0], [0.0, 1.0]).unwrap());
        let e = World::new(scene, AccelKind::Bvh).err().expect("refused");
        assert!(e.to_string().contains("unbounded"), "{e}");
        let mut scene = straddling().scene.clone();
        scene.periodic = Some(Periodic::new([0.0, 0.1], [0.0, 0.1]).unwrap());
        let e = World::new(scene, AccelKind::Bvh).err().expect("refused");
        assert!(e.to_string().contains("plots"), "{e}");
        let mut scene = straddling().scene.clone();
        scene.periodic = Some(Periodic {
            x: [0.0, 0.0],
            z: [0.0, 1.0],
        });
        let e = World::new(scene, AccelKind::Bvh).err().expect("refused");
        assert!(e.to_string().contains("x range"), "{e}");
    }
}
