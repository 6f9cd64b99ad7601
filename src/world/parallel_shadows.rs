//! The shadows of a directional light (the sun) found exactly: the share of a triangle that
//! the parallel light reaches, by cutting the shadows of the other triangles out of it — no
//! rays, no noise.
//!
//! Along the light, a point `o` shadows a point `r` of a receiver when `o = r + s·t` for some
//! `s > 0` (`t` the unit vector toward the light): `o` lies on the light's side of the
//! receiver's plane, and the two fall on the same point when projected along `t`. So each
//! triangle near the receiver is clipped to the light's side of the receiver's plane,
//! projected along `t`, and cut out of the receiver's projection ([`convex2::subtract`]);
//! what remains, over the area of the receiver's projection, is the lit share (the
//! projection along `t` onto a plane is affine: it keeps ratios of areas within the
//! receiver's plane).
//!
//! The projection is along `t` onto the coordinate plane across `t`'s largest component; in
//! a periodic scene onto the ground plane `y = 0`, where a plot's copies, shifted by whole
//! periods in x and z, fall shifted by the same periods — so the triangles of the endless
//! field that shadow a receiver are the plot's own, each at the shifts that bring its
//! projection over the receiver's. The triangles are binned by their projected bounds in a
//! uniform grid of about as many cells as triangles (wrapping around the plot in a periodic
//! scene); the few that cover many cells (a ground) are candidates of every receiver.
//!
//! Only for worlds of triangles that block light wherever they are: placed meshes, analytic
//! shapes and alpha textures (cut-outs) are left to rays ([`ParallelShadows::new`] declines).

use super::{SceneGeometry, World};
use crate::geometry::convex2::{self, signed_area};
use glam::{DVec2, DVec3};
use std::sync::Arc;

/// Grid cells a triangle's projected bounds may cover before it is tested by every receiver
/// instead of binned.
const BINNED_CELLS: usize = 64;
/// Candidate triangles (times their shifts) beyond which a receiver is left to rays.
const MAX_CANDIDATES: usize = 4096;
/// Convex pieces of a receiver's lit part beyond which it is left to rays.
const MAX_PIECES: usize = 1024;
/// How far a point must lie on the light's side of the receiver's plane to shadow it, a
/// share of the receiver's longest edge and, in ulps of single precision, of its distance
/// from the origin (where the triangles' corners are rounded): the receiver's own
/// triangles, and the others of its surface, in its plane, do not.
const PLANE_BAND: (f64, f64) = (1e-7, 8.0);

/// A world's triangles as a directional light sees them, ready to tell the lit share of each.
pub struct ParallelShadows {
    /// Unit vector toward the light.
    toward: DVec3,
    /// The axis projected along, then the two kept as the projection's coordinates.
    axes: [usize; 3],
    /// The world's triangles (shared with it).
    geometry: Arc<SceneGeometry>,
    /// Every triangle's projected bounds, `[min, max]`.
    bounds: Vec<[DVec2; 2]>,
    /// The plot's periods in the projection's coordinates (x, z), for a periodic scene.
    period: Option<DVec2>,
    /// Corner of the grid, projected coordinates.
    origin: DVec2,
    /// Size of a cell.
    cell: DVec2,
    /// Cells along each projected axis.
    cells: [usize; 2],
    /// Cell `c`'s triangles are `items[start[c]..start[c + 1]]`.
    start: Vec<u32>,
    items: Vec<u32>,
    /// Triangles too large to bin, candidates of every receiver.
    large: Vec<u32>,
}

impl ParallelShadows {
    /// The shadows in `world` of parallel light travelling along `direction`; `None` when the
    /// world holds what this cannot take (placed meshes, analytic shapes, alpha textures, an
    /// unrolled field) or the light runs level with a periodic plot.
    pub fn new(world: &World, direction: DVec3) -> Option<ParallelShadows> {
        let geometry = &world.geometry;
        if geometry.placement_count() > 0
            || geometry.analytic_count() > 0
            || geometry.has_alpha()
            || world.unrolls.is_some()
        {
            return None;
        }
        let toward = -direction.normalize_or_zero();
        let field = world.field();
        let across = if field.is_some() {
            1
        } else {
            let a = toward.abs();
            if a.x >= a.y && a.x >= a.z {
                0
            } else if a.y >= a.z {
                1
            } else {
                2
            }
        };
        if toward[across].abs() < 1e-3 {
            return None;
        }
        let axes = [across, (across + 1) % 3, (across + 2) % 3];
        // In a periodic scene x and z, in this order, as the plot's periods are.
        let axes = if across == 1 { [1, 0, 2] } else { axes };
        let mut shadows = ParallelShadows {
            toward,
            axes,
            geometry: Arc::clone(geometry),
            bounds: Vec::new(),
            period: field.map(|f| f.plot.period().as_dvec2()),
            origin: DVec2::ZERO,
            cell: DVec2::ONE,
            cells: [1, 1],
            start: Vec::new(),
            items: Vec::new(),
            large: Vec::new(),
        };
        shadows.bounds = (0..shadows.count() as u32)
            .map(|prim| shadows.projected_bounds(&shadows.corners(prim)))
            .collect();
        let (lo, hi) = match field {
            Some(f) => (
                DVec2::new(f64::from(f.plot.x[0]), f64::from(f.plot.z[0])),
                DVec2::new(f64::from(f.plot.x[1]), f64::from(f.plot.z[1])),
            ),
            None => shadows.bounds.iter().fold(
                (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
                |(lo, hi), b| (lo.min(b[0]), hi.max(b[1])),
            ),
        };
        shadows.bin(lo, hi);
        Some(shadows)
    }

    /// The number of triangles.
    fn count(&self) -> usize {
        self.geometry.triangle_count()
    }

    /// Triangle `prim`'s corners, scene units.
    fn corners(&self, prim: u32) -> [DVec3; 3] {
        let t = self
            .geometry
            .triangle(prim)
            .expect("a world of triangles only");
        let p0 = t.p0.as_dvec3();
        [p0, p0 + t.e1.as_dvec3(), p0 + t.e2.as_dvec3()]
    }

    /// `p` projected along the light onto the projection's plane.
    #[inline]
    fn project(&self, p: DVec3) -> DVec2 {
        let [a, u, v] = self.axes;
        let s = p[a] / self.toward[a];
        DVec2::new(p[u] - s * self.toward[u], p[v] - s * self.toward[v])
    }

    fn projected_bounds(&self, t: &[DVec3; 3]) -> [DVec2; 2] {
        let q = t.map(|p| self.project(p));
        [q[0].min(q[1]).min(q[2]), q[0].max(q[1]).max(q[2])]
    }

    /// Bins every triangle by its projected bounds in a grid over `[lo, hi]`.
    fn bin(&mut self, lo: DVec2, hi: DVec2) {
        let extent = (hi - lo).max(DVec2::splat(1e-12));
        let n = self.count().max(1) as f64;
        let nx = (n * extent.x / extent.y).sqrt().ceil().clamp(1.0, 4096.0);
        let ny = (n / nx).ceil().clamp(1.0, 4096.0);
        self.cells = [nx as usize, ny as usize];
        self.origin = lo;
        self.cell = extent / DVec2::new(nx, ny);
        let mut counts = vec![0u32; self.cells[0] * self.cells[1] + 1];
        let mut large = Vec::new();
        for (k, b) in self.bounds.iter().enumerate() {
            match self.cells_of(b, BINNED_CELLS) {
                Some(cells) => cells.for_each(|c| counts[c] += 1),
                None => large.push(k as u32),
            }
        }
        let mut start = Vec::with_capacity(counts.len());
        let mut sum = 0;
        for &c in &counts {
            start.push(sum);
            sum += c;
        }
        let mut items = vec![0; sum as usize];
        let mut next = start.clone();
        for (k, b) in self.bounds.iter().enumerate() {
            if let Some(cells) = self.cells_of(b, BINNED_CELLS) {
                cells.for_each(|c| {
                    items[next[c] as usize] = k as u32;
                    next[c] += 1;
                });
            }
        }
        self.start = start;
        self.items = items;
        self.large = large;
    }

    /// The grid cells the projected bounds `b` cover (wrapped around a periodic plot,
    /// clamped to the grid otherwise); `None` when they are more than `limit`.
    fn cells_of(
        &self,
        b: &[DVec2; 2],
        limit: usize,
    ) -> Option<impl Iterator<Item = usize> + use<>> {
        let range = |axis: usize| {
            let n = self.cells[axis] as i64;
            let cell = |x: f64| ((x - self.origin[axis]) / self.cell[axis]).floor() as i64;
            let (first, last) = (cell(b[0][axis]), cell(b[1][axis]));
            if self.period.is_some() {
                (first, last.min(first.saturating_add(n - 1)), n)
            } else {
                (first.clamp(0, n - 1), last.clamp(0, n - 1), n)
            }
        };
        let (x0, x1, nx) = range(0);
        let (y0, y1, ny) = range(1);
        // Bounds far beyond the grid saturate; at most the whole grid each way.
        let covered = (x1.saturating_sub(x0) + 1).saturating_mul(y1.saturating_sub(y0) + 1);
        let covered = usize::try_from(covered).unwrap_or(usize::MAX);
        (covered <= limit).then(|| {
            (y0..=y1).flat_map(move |y| {
                (x0..=x1).map(move |x| (y.rem_euclid(ny) * nx + x.rem_euclid(nx)) as usize)
            })
        })
    }

    /// The share (0 to 1) of triangle `prim` that the light reaches, on its side facing the
    /// light ([`Self::lit_share_of`] its corners).
    pub fn lit_share(&self, prim: u32) -> Option<f64> {
        self.lit_share_of(&self.corners(prim))
    }

    /// The share (0 to 1) of the planar convex polygon `receiver` (corners in order, scene
    /// units; a triangle of the world or a part of one) that the light reaches, on its side
    /// facing the light; `None` when too many triangles or shadows overlap it to cut them out
    /// (over 4,096 candidate triangles, or a lit part in over 1,024 convex pieces): rays must
    /// tell then. A polygon seen edge-on counts as lit (it receives nothing either way).
    pub fn lit_share_of(&self, receiver: &[DVec3]) -> Option<f64> {
        let normal = (receiver[1] - receiver[0]).cross(receiver[2] - receiver[0]);
        let facing = normal.dot(self.toward);
        let mut own: Vec<DVec2> = receiver.iter().map(|&p| self.project(p)).collect();
        let mut area = signed_area(&own);
        if area < 0.0 {
            own.reverse();
            area = -area;
        }
        if facing == 0.0 || area <= 0.0 {
            return Some(1.0);
        }
        // The light's side of the receiver's plane, with a band about it.
        let n = receiver.len();
        let size = (0..n)
            .map(|i| (receiver[(i + 1) % n] - receiver[i]).length())
            .fold(0.0, f64::max);
        let reach = receiver
            .iter()
            .map(|p| p.abs().max_element())
            .fold(0.0, f64::max);
        let light_side = normal.normalize() * facing.signum();
        let band = PLANE_BAND.0 * size + PLANE_BAND.1 * f64::from(f32::EPSILON) * reach;
        let ahead = |p: DVec3| light_side.dot(p - receiver[0]) - band;
        let bounds = own
            .iter()
            .fold([own[0], own[0]], |[lo, hi], &p| [lo.min(p), hi.max(p)]);
        let candidates = self.candidates(&bounds)?;
        let min_area = 1e-12 * area;
        let mut pieces = vec![own];
        let mut next = Vec::new();
        let mut corners = Vec::with_capacity(4);
        for (k, shift) in candidates {
            let occluder = self.corners(k).map(|p| p + shift);
            clip_to_front(&occluder, ahead, &mut corners);
            if corners.len() < 3 {
                continue;
            }
            let mut hole: Vec<DVec2> = corners.iter().map(|&p| self.project(p)).collect();
            let hole_area = signed_area(&hole);
            if hole_area.abs() <= min_area {
                continue;
            }
            if hole_area < 0.0 {
                hole.reverse();
            }
            let (lo, hi) = hole
                .iter()
                .fold((hole[0], hole[0]), |(lo, hi), &p| (lo.min(p), hi.max(p)));
            next.clear();
            for piece in pieces.drain(..) {
                let apart = piece
                    .iter()
                    .fold([true; 4], |[l, r, b, t], p| {
                        [
                            l && p.x <= lo.x,
                            r && p.x >= hi.x,
                            b && p.y <= lo.y,
                            t && p.y >= hi.y,
                        ]
                    })
                    .contains(&true);
                if apart {
                    next.push(piece);
                } else {
                    convex2::subtract(&piece, &hole, min_area, &mut next);
                }
            }
            if next.len() > MAX_PIECES {
                return None;
            }
            std::mem::swap(&mut pieces, &mut next);
            if pieces.is_empty() {
                return Some(0.0);
            }
        }
        let lit: f64 = pieces.iter().map(|p| signed_area(p)).sum();
        Some((lit / area).clamp(0.0, 1.0))
    }

    /// The triangles whose projection may overlap the projected bounds `b`, each with every
    /// shift of the plot (scene units) that brings it over them; `None` when they are more
    /// than [`MAX_CANDIDATES`].
    fn candidates(&self, b: &[DVec2; 2]) -> Option<Vec<(u32, DVec3)>> {
        let mut found: Vec<u32> = match self.cells_of(b, MAX_CANDIDATES) {
            Some(cells) => cells
                .flat_map(|c| &self.items[self.start[c] as usize..self.start[c + 1] as usize])
                .copied()
                .collect(),
            None => {
                // The receiver's bounds cover more cells than are binned: every triangle.
                if self.count() > MAX_CANDIDATES {
                    return None;
                }
                (0..self.count() as u32).collect()
            }
        };
        found.extend_from_slice(&self.large);
        found.sort_unstable();
        found.dedup();
        let mut candidates = Vec::with_capacity(found.len());
        for k in found {
            let [lo, hi] = self.bounds[k as usize];
            let Some(period) = self.period else {
                if lo.cmplt(b[1]).all() && hi.cmpgt(b[0]).all() {
                    candidates.push((k, DVec3::ZERO));
                }
                continue;
            };
            // Shifts i·period with lo + i·p < b.max and hi + i·p > b.min.
            let shifts = |axis: usize| {
                let p = period[axis];
                let first = ((b[0][axis] - hi[axis]) / p).floor() as i64;
                let last = ((b[1][axis] - lo[axis]) / p).ceil() as i64;
                (first..=last).filter(move |&i| {
                    lo[axis] + i as f64 * p < b[1][axis] && hi[axis] + i as f64 * p > b[0][axis]
                })
            };
            for i in shifts(0) {
                for k2 in shifts(1) {
                    let mut shift = DVec3::ZERO;
                    shift[self.axes[1]] = i as f64 * period.x;
                    shift[self.axes[2]] = k2 as f64 * period.y;
                    candidates.push((k, shift));
                    if candidates.len() > MAX_CANDIDATES {
                        return None;
                    }
                }
            }
        }
        (candidates.len() <= MAX_CANDIDATES).then_some(candidates)
    }
}

/// The part of `triangle` where `ahead` is positive (a plane's front), its corners written to
/// `corners` (emptied first; fewer than three when none of it is there).
fn clip_to_front(triangle: &[DVec3; 3], ahead: impl Fn(DVec3) -> f64, corners: &mut Vec<DVec3>) {
    corners.clear();
    let d = triangle.map(&ahead);
    for i in 0..3 {
        let j = (i + 1) % 3;
        if d[i] > 0.0 {
            corners.push(triangle[i]);
        }
        if (d[i] > 0.0) != (d[j] > 0.0) {
            corners.push(triangle[i] + (triangle[j] - triangle[i]) * (d[i] / (d[i] - d[j])));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::AccelKind;
    use crate::scene::{LightKind, Material, Periodic, Scene, Shape};
    use crate::world::sees_light;
    use glam::Vec3;
    use rand::{RngExt, SeedableRng};
    use rand_pcg::Pcg32;

    /// Axis-aligned squares `[x, x + w] × [z, z + d]` at height `y`, objects in this order.
    fn squares(rects: &[(f32, f32, f32, f32, f32)], plot: Option<Periodic>) -> World {
        let mut scene = Scene::empty("squares");
        let m = scene.add_material(Material::default());
        for (k, &(x, y, z, w, d)) in rects.iter().enumerate() {
            scene.add_object(
                &format!("square-{k}"),
                Shape::Parallelogram {
                    origin: Vec3::new(x, y, z),
                    edge_u: Vec3::X * w,
                    edge_v: Vec3::Z * d,
                },
                m,
            );
        }
        scene.periodic = plot;
        World::new(scene, AccelKind::Bvh).unwrap()
    }

    /// The lit share of object `object`, its triangles' shares weighted by their areas.
    fn share_of(world: &World, shadows: &ParallelShadows, object: u32) -> f64 {
        let (mut lit, mut area) = (0.0, 0.0);
        for prim in 0..world.geometry.triangle_count() as u32 {
            if world.geometry.owner(prim).0 == object {
                let a = f64::from(world.geometry.triangle(prim).unwrap().area());
                lit += a * shadows.lit_share(prim).unwrap();
                area += a;
            }
        }
        lit / area
    }

    /// Light coming from 45° above +x: a point at height h shadows the ground h further −x.
    const SLANTED: DVec3 = DVec3::new(-1.0, -1.0, 0.0);

    // The squares' corners are single precision (1.8 is 1.8 within 5·10⁻⁸): shares to 10⁻⁶.
    #[test]
    fn shadows_are_cut_out_exactly_and_their_overlap_counted_once() {
        // A unit square on the ground; a unit square at height 1 whose shadow covers
        // x ∈ [0.25, 1.25]; one at height 2 over x ∈ [−0.2, 0.8], z ∈ [0, 0.5]. The shadows'
        // union on the receiver: 0.75 + 0.4 − 0.275 = 0.875.
        let world = squares(
            &[
                (0.0, 0.0, 0.0, 1.0, 1.0),
                (1.25, 1.0, 0.0, 1.0, 1.0),
                (1.8, 2.0, 0.0, 1.0, 0.5),
            ],
            None,
        );
        let shadows = ParallelShadows::new(&world, SLANTED).unwrap();
        assert!((share_of(&world, &shadows, 0) - 0.125).abs() < 1e-6);
        // The highest square shades the middle one on [1.25, 1.8] × [0, 0.5] (its shadow
        // one lower falls 1 further −x); nothing is above the highest.
        assert!((share_of(&world, &shadows, 1) - 0.725).abs() < 1e-6);
        assert!((share_of(&world, &shadows, 2) - 1.0).abs() < 1e-12);
        // Straight down: the middle one in the highest one's shadow on [1.8, 2.25] × [0, 0.5].
        let down = ParallelShadows::new(&world, DVec3::NEG_Y).unwrap();
        assert!((share_of(&world, &down, 0) - 1.0).abs() < 1e-12);
        assert!((share_of(&world, &down, 1) - 0.775).abs() < 1e-6);
        // Straight up: the highest one in the middle one's, the same overlap, of its 0.5.
        let up = ParallelShadows::new(&world, DVec3::Y).unwrap();
        assert!((share_of(&world, &up, 1) - 1.0).abs() < 1e-12);
        assert!((share_of(&world, &up, 2) - 0.55).abs() < 1e-6);
    }

    #[test]
    fn a_periodic_plot_s_copies_cast_shadows_across_its_sides() {
        // Plot [0, 2]²; the receiver [0.5, 1] × [0.5, 1] on the ground; a square at height 3
        // over x ∈ [1.75, 2.25] (reaching over the +x side) casts its shadow on
        // x ∈ [−1.25, −0.75], which the copy one period over puts on [0.75, 1.25]: half of
        // the receiver. Rays through the endless field agree.
        let plot = Periodic::new([0.0, 2.0], [0.0, 2.0]).unwrap();
        let world = squares(
            &[(0.5, 0.0, 0.5, 0.5, 0.5), (1.75, 3.0, 0.5, 0.5, 0.5)],
            Some(plot),
        );
        let shadows = ParallelShadows::new(&world, SLANTED).unwrap();
        assert!((share_of(&world, &shadows, 0) - 0.5).abs() < 1e-6);
        let light = LightKind::Directional {
            direction: SLANTED.as_vec3().normalize(),
            irradiance: crate::color::Rgb::WHITE,
        };
        let sees = |x: f64| sees_light(&world, DVec3::new(x, 0.0, 0.75), DVec3::Y, &light);
        assert!(sees(0.6) && !sees(0.9));
    }

    #[test]
    fn the_lit_share_of_every_leaf_of_a_random_canopy_is_what_rays_see() {
        // 60 leaves turned at random over a periodic plot 1 × 1 under a slanted sun: every
        // triangle's lit share against the share of a 64 × 64 grid of its points from which
        // a shadow ray through the endless field reaches the light (the grid's own error is
        // about its boundary cells: under 3 % for a triangle half in shadow, far less on
        // average).
        let mut scene = Scene::empty("canopy");
        let m = scene.add_material(Material::default());
        let mut rng = Pcg32::seed_from_u64(5);
        for k in 0..60 {
            let normal = Vec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            )
            .normalize();
            let (u, v) = normal.any_orthonormal_pair();
            let centre = Vec3::new(
                rng.random_range(0.0..1.0),
                rng.random_range(0.1..0.6),
                rng.random_range(0.0..1.0),
            );
            scene.add_object(
                &format!("leaf-{k}"),
                Shape::Parallelogram {
                    origin: centre - (u + v) * 0.1,
                    edge_u: u * 0.2,
                    edge_v: v * 0.2,
                },
                m,
            );
        }
        scene.periodic = Some(Periodic::new([0.0, 1.0], [0.0, 1.0]).unwrap());
        let world = World::new(scene, AccelKind::Bvh).unwrap();
        let direction = DVec3::new(0.4, -1.0, 0.3).normalize();
        let light = LightKind::Directional {
            direction: direction.as_vec3(),
            irradiance: crate::color::Rgb::WHITE,
        };
        let shadows = ParallelShadows::new(&world, direction).unwrap();
        let grid = 64;
        let (mut squares, mut partly) = (0.0, 0);
        for prim in 0..world.geometry.triangle_count() as u32 {
            let t = world.geometry.triangle(prim).unwrap();
            let (p0, e1, e2) = (t.p0.as_dvec3(), t.e1.as_dvec3(), t.e2.as_dvec3());
            let normal = e1.cross(e2).normalize();
            let normal = normal * -normal.dot(direction).signum();
            let mut seen = 0;
            for i in 0..grid {
                for j in 0..grid {
                    let (mut a, mut b) = (
                        (i as f64 + 0.5) / grid as f64,
                        (j as f64 + 0.5) / grid as f64,
                    );
                    if a + b > 1.0 {
                        (a, b) = (1.0 - a, 1.0 - b);
                    }
                    seen += u32::from(sees_light(&world, p0 + e1 * a + e2 * b, normal, &light));
                }
            }
            let rays = f64::from(seen) / f64::from(grid * grid);
            let exact = shadows.lit_share(prim).unwrap();
            assert!(
                (exact - rays).abs() < 0.03,
                "triangle {prim}: {exact} against {rays}"
            );
            squares += (exact - rays).powi(2);
            partly += usize::from(rays > 0.02 && rays < 0.98);
        }
        let rms = (squares / world.geometry.triangle_count() as f64).sqrt();
        assert!(rms < 0.005, "RMS {rms}");
        assert!(partly >= 10, "only {partly} triangles partly in shadow");
    }

    #[test]
    fn what_cannot_be_projected_is_left_to_rays() {
        let mut scene = Scene::empty("ball");
        let m = scene.add_material(Material::default());
        scene.add_object(
            "ball",
            Shape::Sphere {
                center: Vec3::ZERO,
                radius: 1.0,
            },
            m,
        );
        let world = World::new(scene, AccelKind::Bvh).unwrap();
        assert!(ParallelShadows::new(&world, DVec3::NEG_Y).is_none());
        // Light level with a periodic plot: no projection onto its ground.
        let plot = Periodic::new([0.0, 2.0], [0.0, 2.0]).unwrap();
        let world = squares(&[(0.5, 0.0, 0.5, 0.5, 0.5)], Some(plot));
        assert!(ParallelShadows::new(&world, DVec3::X).is_none());
    }
}
