//! Axis-aligned bounding boxes.

use super::Ray;
use glam::{Mat4, Vec3};

/// An axis-aligned box. The empty box has `min = +∞`, `max = -∞`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Lower corner.
    pub min: Vec3,
    /// Upper corner.
    pub max: Vec3,
}

impl Default for Aabb {
    fn default() -> Self {
        Aabb::EMPTY
    }
}

impl Aabb {
    /// The empty box (neutral element of [`Aabb::union`]).
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    /// The box spanned by two corners (in any order).
    pub fn new(a: Vec3, b: Vec3) -> Self {
        Aabb {
            min: a.min(b),
            max: a.max(b),
        }
    }

    /// The smallest box holding all `points`.
    pub fn from_points(points: impl IntoIterator<Item = Vec3>) -> Self {
        points.into_iter().fold(Aabb::EMPTY, |b, p| b.grow(p))
    }

    /// True when the box holds no point.
    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x || self.min.y > self.max.y || self.min.z > self.max.z
    }

    /// This box grown to hold `p`.
    pub fn grow(self, p: Vec3) -> Self {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The smallest box holding both boxes.
    pub fn union(self, o: Aabb) -> Self {
        Aabb {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    /// Size along each axis (zero for the empty box).
    pub fn extent(&self) -> Vec3 {
        if self.is_empty() {
            Vec3::ZERO
        } else {
            self.max - self.min
        }
    }

    /// Centre point.
    pub fn center(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    /// Surface area (zero for the empty box).
    pub fn surface_area(&self) -> f32 {
        let e = self.extent();
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// Index of the longest axis (0 = x, 1 = y, 2 = z).
    pub fn longest_axis(&self) -> usize {
        let e = self.extent();
        if e.x >= e.y && e.x >= e.z {
            0
        } else if e.y >= e.z {
            1
        } else {
            2
        }
    }

    /// True when `p` lies inside or on the box.
    pub fn contains(&self, p: Vec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    /// True when the two boxes share at least one point.
    pub fn overlaps(&self, o: &Aabb) -> bool {
        self.min.cmple(o.max).all() && o.min.cmple(self.max).all()
    }

    /// The box holding this box after the affine map `m`.
    pub fn transformed(&self, m: &Mat4) -> Aabb {
        if self.is_empty() {
            return *self;
        }
        (0..8)
            .map(|i| {
                Vec3::new(
                    if i & 1 == 0 { self.min.x } else { self.max.x },
                    if i & 2 == 0 { self.min.y } else { self.max.y },
                    if i & 4 == 0 { self.min.z } else { self.max.z },
                )
            })
            .fold(Aabb::EMPTY, |b, p| b.grow(m.transform_point3(p)))
    }

    /// The parameter interval `[t_enter, t_exit]` in which `ray` is inside the box, clipped to
    /// `[0, t_max]`; `None` when the ray misses. `inv_dir` is `1 / ray.dir` per component.
    #[inline]
    pub fn ray_interval(&self, ray: &Ray, inv_dir: Vec3, t_max: f32) -> Option<(f32, f32)> {
        let t0 = (self.min - ray.origin) * inv_dir;
        let t1 = (self.max - ray.origin) * inv_dir;
        let t_near = t0.min(t1).max_element().max(0.0);
        let t_far = t0.max(t1).min_element().min(t_max);
        (t_near <= t_far).then_some((t_near, t_far))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_interval_hits_and_misses() {
        let b = Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0));
        let ray = Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X);
        let (t0, t1) = b
            .ray_interval(&ray, ray.dir.recip(), f32::INFINITY)
            .unwrap();
        assert!((t0 - 4.0).abs() < 1e-6 && (t1 - 6.0).abs() < 1e-6);
        let miss = Ray::new(Vec3::new(-5.0, 2.0, 0.0), Vec3::X);
        assert!(
            b.ray_interval(&miss, miss.dir.recip(), f32::INFINITY)
                .is_none()
        );
        // Parallel to a slab, inside it: infinities must not produce NaN misses.
        let inside = Ray::new(Vec3::new(-5.0, 0.5, 0.5), Vec3::X);
        assert!(
            b.ray_interval(&inside, inside.dir.recip(), f32::INFINITY)
                .is_some()
        );
    }

    #[test]
    fn union_and_area() {
        let b = Aabb::new(Vec3::ZERO, Vec3::ONE).union(Aabb::new(Vec3::ONE, Vec3::splat(2.0)));
        assert_eq!(b.extent(), Vec3::splat(2.0));
        assert_eq!(b.surface_area(), 24.0);
        assert_eq!(Aabb::EMPTY.surface_area(), 0.0);
    }
}
