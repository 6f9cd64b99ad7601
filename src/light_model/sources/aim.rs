//! Where parallel photons (directional lights and the sky) are aimed: a few spheres that
//! together hold all bounded geometry. A sphere projects onto every plane as a disc of its own
//! radius, so one set of spheres serves every direction.
//!
//! The spheres are a cut through a small cluster tree: the bounded primitives are split, the
//! largest cluster first, at the middle of the longest axis of their centres, into at most
//! [`MAX_CLUSTERS`] clusters, and of every cluster and its two halves the cheaper cover (the
//! smaller sum of squared radii) is kept. Each sphere is centred on its cluster's bounding
//! box and reaches the farthest triangle vertex (or box corner of an analytic shape).
//!
//! A photon picks a disc with probability proportional to its area, a uniform point in it,
//! and carries the fraction (Σ disc areas)/(πR²)/m of its share, m being the number of discs
//! holding the point (and nothing where the point lies outside the entry disc of radius R).
//! The expected fraction sent is then the area of the union of the discs within the entry
//! disc over πR²: exactly the rays of a uniform point of the entry disc that can meet
//! anything, each with the density of the uniform rays at least, so no estimate is worse than
//! with uniform points.

use crate::accel::{PrimitiveSet, partition};
use crate::geometry::{Aabb, Frame};
use crate::sampling::Sampler;
use crate::sampling::warp::concentric_disk;
use crate::world::SceneGeometry;
use glam::{Vec2, Vec3};

/// Most clusters the spheres are chosen from (each aimed photon tests its point against every
/// chosen disc).
const MAX_CLUSTERS: usize = 64;

/// Aiming is used when the discs' total area is at most this fraction of the entry disc's
/// (dimensionless); nearer to 1 it would save next to no photons and only change the random
/// sequence.
const WORTHWHILE_AREA: f64 = 0.9;

/// A sphere (scene units).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Ball {
    center: Vec3,
    radius: f32,
}

impl Ball {
    /// Squared radius (scene units²), the disc's area over π.
    fn area_over_pi(&self) -> f64 {
        f64::from(self.radius) * f64::from(self.radius)
    }
}

/// A sphere grown like the entry sphere ([`crate::world::World::entry_sphere`]), so that
/// rounding never puts geometry outside it.
fn padded(radius: f32) -> f32 {
    radius * 1.001 + 1e-6
}

/// The spheres parallel photons are aimed at.
#[derive(Clone, Debug)]
pub(super) struct AimSet {
    /// The spheres, centres relative to the entry sphere's centre.
    balls: Vec<Ball>,
    /// Cumulative area fractions of the discs (last = 1).
    cdf: Vec<f32>,
    /// Σ disc areas over the entry disc's area, dimensionless.
    area_fraction: f64,
    /// Radius of the entry sphere, scene units.
    entry_radius: f32,
}

/// Where an aimed photon crosses the plane through the entry sphere's centre perpendicular to
/// its direction.
pub(super) struct AimedPoint {
    /// Offset from the entry sphere's centre along the frame's tangents `(s, t)`, scene units.
    pub offset: Vec2,
    /// Fraction of the photon's share of the light's power it carries, dimensionless.
    pub carried: f64,
}

impl AimSet {
    /// The spheres for `geometry` inside the entry sphere `(center, radius)`, or `None` when
    /// aiming would not pay (see [`WORTHWHILE_AREA`]), there is no bounded geometry, or some
    /// geometry is unbounded (an infinite plane meets rays anywhere in the entry disc).
    pub fn new(geometry: &SceneGeometry, (center, radius): (Vec3, f32)) -> Option<Self> {
        let prims = bounded_primitives(geometry)?;
        let balls = ClusterTree::build(geometry, prims).cheapest_cover();
        Self::from_balls(&balls, center, radius)
    }

    /// The set of `balls` (world space) for the entry sphere `(center, radius)`, if worthwhile.
    fn from_balls(balls: &[Ball], center: Vec3, radius: f32) -> Option<Self> {
        let total: f64 = balls.iter().map(Ball::area_over_pi).sum();
        let area_fraction = total / (f64::from(radius) * f64::from(radius));
        let cdf = balls
            .iter()
            .scan(0.0, |sum, b| {
                *sum += b.area_over_pi();
                Some((*sum / total) as f32)
            })
            .collect();
        let balls = balls
            .iter()
            .map(|b| Ball {
                center: b.center - center,
                ..*b
            })
            .collect();
        (area_fraction <= WORTHWHILE_AREA).then_some(AimSet {
            balls,
            cdf,
            area_fraction,
            entry_radius: radius,
        })
    }

    /// A point for a photon travelling along `frame.n`.
    pub fn sample(&self, frame: &Frame, sampler: &mut Sampler) -> AimedPoint {
        let u = sampler.next_1d();
        let pick = self
            .cdf
            .partition_point(|&c| c <= u)
            .min(self.cdf.len() - 1);
        let ball = self.balls[pick];
        let offset = project(ball.center, frame) + concentric_disk(sampler.next_2d()) * ball.radius;
        let carried = if offset.length_squared() <= self.entry_radius * self.entry_radius {
            self.area_fraction / f64::from(self.multiplicity(offset, pick, frame))
        } else {
            0.0
        };
        AimedPoint { offset, carried }
    }

    /// How many discs hold `point` of the plane across `frame.n`, disc `pick` (where it was
    /// drawn) counted whatever the rounding.
    fn multiplicity(&self, point: Vec2, pick: usize, frame: &Frame) -> u32 {
        let others = self.balls.iter().enumerate().filter(|&(i, b)| {
            i != pick && (project(b.center, frame) - point).length_squared() <= b.radius * b.radius
        });
        1 + others.count() as u32
    }
}

/// `v` in the coordinates of the plane across `frame.n`.
fn project(v: Vec3, frame: &Frame) -> Vec2 {
    Vec2::new(v.dot(frame.s), v.dot(frame.t))
}

/// Every primitive of `geometry`, or `None` when there are none or some are unbounded.
fn bounded_primitives(geometry: &SceneGeometry) -> Option<Vec<u32>> {
    let prims: Vec<u32> = (0..geometry.len() as u32).collect();
    let bounded = |&p: &u32| {
        let b = PrimitiveSet::bounds(geometry, p);
        b.min.is_finite() && b.max.is_finite()
    };
    (!prims.is_empty() && prims.iter().all(bounded)).then_some(prims)
}

/// A cluster of primitives: a range of [`ClusterTree::prims`] and its sphere.
#[derive(Clone, Debug)]
struct Cluster {
    start: usize,
    end: usize,
    ball: Ball,
    /// Its two halves, once split.
    halves: Option<[usize; 2]>,
    /// False once a split has failed (all centres at one point).
    splittable: bool,
}

/// Clusters of primitives, each after its parent.
struct ClusterTree<'a> {
    geometry: &'a SceneGeometry,
    prims: Vec<u32>,
    clusters: Vec<Cluster>,
}

impl<'a> ClusterTree<'a> {
    /// The tree over `prims`: the largest unsplit cluster halved until there are
    /// [`MAX_CLUSTERS`] or none can be split.
    fn build(geometry: &'a SceneGeometry, prims: Vec<u32>) -> Self {
        let mut tree = ClusterTree {
            geometry,
            clusters: Vec::new(),
            prims,
        };
        let root = tree.cluster(0, tree.prims.len());
        tree.clusters.push(root);
        let mut leaves = 1;
        while leaves < MAX_CLUSTERS {
            let Some(largest) = tree.largest_splittable_leaf() else {
                break;
            };
            if tree.split(largest) {
                leaves += 1;
            } else {
                tree.clusters[largest].splittable = false;
            }
        }
        tree
    }

    /// The cluster of `prims[start..end]` with its sphere.
    fn cluster(&self, start: usize, end: usize) -> Cluster {
        let prims = &self.prims[start..end];
        let bounds = prims
            .iter()
            .map(|&p| PrimitiveSet::bounds(self.geometry, p))
            .fold(Aabb::EMPTY, |a, b| a.union(b));
        let center = bounds.center();
        let radius = prims
            .iter()
            .map(|&p| self.farthest_distance(p, center))
            .fold(0.0f32, f32::max);
        Cluster {
            start,
            end,
            ball: Ball {
                center,
                radius: padded(radius),
            },
            halves: None,
            splittable: true,
        }
    }

    /// Distance from `from` to the farthest point of primitive `prim`: a triangle's farthest
    /// vertex, an analytic shape's farthest bounding-box corner.
    fn farthest_distance(&self, prim: u32, from: Vec3) -> f32 {
        match self.geometry.triangle(prim) {
            Some(t) => t
                .vertices()
                .iter()
                .map(|v| v.distance(from))
                .fold(0.0, f32::max),
            None => {
                let b = PrimitiveSet::bounds(self.geometry, prim);
                (b.min - from).abs().max((b.max - from).abs()).length()
            }
        }
    }

    /// The unsplit cluster with the largest sphere that may still be split.
    fn largest_splittable_leaf(&self) -> Option<usize> {
        self.clusters
            .iter()
            .enumerate()
            .filter(|(_, c)| c.halves.is_none() && c.splittable)
            .max_by(|a, b| a.1.ball.radius.total_cmp(&b.1.ball.radius))
            .map(|(i, _)| i)
    }

    /// Halves cluster `index` at the middle of the longest axis of its primitives' centres;
    /// false when all centres lie on one side.
    fn split(&mut self, index: usize) -> bool {
        let (start, end) = (self.clusters[index].start, self.clusters[index].end);
        let geometry = self.geometry;
        let centre = |p: u32| PrimitiveSet::bounds(geometry, p).center();
        let centres = Aabb::from_points(self.prims[start..end].iter().map(|&p| centre(p)));
        let axis = centres.longest_axis();
        let middle = centres.center()[axis];
        let below = start + partition(&mut self.prims[start..end], |p| centre(p)[axis] < middle);
        if below == start || below == end {
            return false;
        }
        let halves = [self.cluster(start, below), self.cluster(below, end)];
        let first = self.clusters.len();
        self.clusters.extend(halves);
        self.clusters[index].halves = Some([first, first + 1]);
        true
    }

    /// The spheres of the cut through the tree with the least total area: each cluster is
    /// covered by its own sphere or by its halves' covers, whichever is smaller.
    fn cheapest_cover(&self) -> Vec<Ball> {
        let mut cost = vec![0.0f64; self.clusters.len()];
        let mut whole = vec![true; self.clusters.len()];
        for (i, c) in self.clusters.iter().enumerate().rev() {
            cost[i] = c.ball.area_over_pi();
            if let Some([a, b]) = c.halves
                && cost[a] + cost[b] < cost[i]
            {
                cost[i] = cost[a] + cost[b];
                whole[i] = false;
            }
        }
        let mut balls = Vec::new();
        let mut pending = vec![0];
        while let Some(i) = pending.pop() {
            match self.clusters[i].halves {
                Some(halves) if !whole[i] => pending.extend(halves),
                _ => balls.push(self.clusters[i].ball),
            }
        }
        balls
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::SequenceKind;

    fn ball(x: f32, y: f32, z: f32, radius: f32) -> Ball {
        Ball {
            center: Vec3::new(x, y, z),
            radius,
        }
    }

    /// Photon `i`'s point for light travelling along −z (the plane is the xy plane).
    fn point(set: &AimSet, i: u64) -> AimedPoint {
        let mut sampler = Sampler::new(SequenceKind::Random, 3, i, 0);
        set.sample(&Frame::from_normal(Vec3::NEG_Z), &mut sampler)
    }

    #[test]
    fn coincident_spheres_count_once() {
        // Two equal spheres: every point is in both, so each carries the area of one disc.
        let balls = [ball(1.0, 2.0, 0.0, 0.5), ball(1.0, 2.0, 0.0, 0.5)];
        let set = AimSet::from_balls(&balls, Vec3::ZERO, 10.0).unwrap();
        let centre = project(balls[0].center, &Frame::from_normal(Vec3::NEG_Z));
        for i in 0..100 {
            let p = point(&set, i);
            assert!((p.carried - 0.25 / 100.0).abs() < 1e-15, "{}", p.carried);
            assert!((p.offset - centre).length() <= 0.5 + 1e-6);
        }
    }

    #[test]
    fn overlapping_discs_send_the_area_of_their_union() {
        // Unit discs 1 apart (union 2π − lens, lens = 2·acos(½) − ½·√3) and a disc poking out
        // of the entry disc of radius 4 (only its part inside counts: by quadrature).
        let lens = 2.0 * 0.5f64.acos() - 0.5 * 3f64.sqrt();
        let (cx, r, big) = (3.5f64, 1.0f64, 4.0f64);
        let steps = 2000;
        let mut inside = 0.0;
        for i in 0..steps {
            for j in 0..steps {
                let x = cx - r + 2.0 * r * (i as f64 + 0.5) / steps as f64;
                let y = -r + 2.0 * r * (j as f64 + 0.5) / steps as f64;
                if (x - cx).powi(2) + y * y <= r * r && x * x + y * y <= big * big {
                    inside += (2.0 * r / steps as f64).powi(2);
                }
            }
        }
        let union = 2.0 * std::f64::consts::PI - lens + inside;
        let balls = [
            ball(-2.0, 0.0, 0.0, 1.0),
            ball(-1.0, 0.0, 0.0, 1.0),
            ball(3.5, 0.0, 5.0, 1.0),
        ];
        let set = AimSet::from_balls(&balls, Vec3::ZERO, 4.0).unwrap();
        let n = 400_000;
        let sent: Vec<f64> = (0..n)
            .map(|i| point(&set, i).carried * std::f64::consts::PI * 16.0)
            .collect();
        let mean = sent.iter().sum::<f64>() / n as f64;
        let var = sent.iter().map(|s| (s - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
        let sigma = (var / n as f64).sqrt();
        assert!(
            (mean - union).abs() < 4.0 * sigma,
            "{mean} vs {union} ± {sigma}"
        );
    }

    #[test]
    fn spheres_as_large_as_the_entry_sphere_are_not_worth_aiming_at() {
        let whole = [ball(0.0, 0.0, 0.0, 1.0)];
        assert!(AimSet::from_balls(&whole, Vec3::ZERO, 1.0).is_none());
        let two = [ball(0.0, 0.0, 0.0, 0.7), ball(0.5, 0.0, 0.0, 0.7)];
        assert!(AimSet::from_balls(&two, Vec3::ZERO, 1.0).is_none());
        assert!(AimSet::from_balls(&two[..1], Vec3::ZERO, 1.0).is_some());
    }
}
