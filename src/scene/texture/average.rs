//! The exact mean of a texture over a polygon of texture space (seed 000 §7.2, done exactly):
//! each texel is a constant square, and every texel the polygon covers counts by the area it
//! covers.
//!
//! The polygon is cut into texel rows; in each row, the texels between the points where the
//! row's top and bottom lines both lie inside the polygon are covered whole and are summed as
//! they are, and only the few texels at the row's ends are clipped. The cost is the number of
//! texels covered plus the polygon's perimeter in texels. A polygon that is not convex has
//! every texel clipped (the area of a clipped simple polygon stays exact).

use super::{ALPHA_CUTOFF, Texture};
use crate::geometry::convex2::signed_area;
use glam::DVec2;

/// What a texture holds over a polygon of texture space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexelStats {
    /// Mean RGBA, each texel weighted by the area of it covered.
    pub mean: [f64; 4],
    /// Smallest value per channel of the texels it touches.
    pub min: [f32; 4],
    /// Largest value per channel of the texels it touches.
    pub max: [f32; 4],
}

/// How much of a polygon an alpha texture leaves in place ([`Texture::coverage`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coverage {
    /// The share of the polygon's area that is present, in `[0, 1]`.
    pub mean: f64,
    /// 0 when any texel it touches is cut away, else 1.
    pub min: f64,
    /// 1 when any texel it touches is present, else 0.
    pub max: f64,
}

impl Texture {
    /// The mean RGBA of the texture over the polygon with texture coordinates `uv`, as
    /// [`Self::polygon_stats`] finds it.
    pub fn polygon_mean(&self, uv: &[DVec2]) -> [f64; 4] {
        self.polygon_stats(uv).mean
    }

    /// The mean, smallest and largest RGBA of the texture over the polygon with texture
    /// coordinates `uv` (any simple polygon, either orientation; outside `[0, 1]²` the wrap
    /// mode applies). The mean is `Σ texel · covered area / polygon area`, exact up to
    /// rounding; the smallest and largest are over the texels it covers, partly or whole. A
    /// polygon of no area (a point or a segment in texture space) takes the texel under its
    /// first corner.
    pub fn polygon_stats(&self, uv: &[DVec2]) -> TexelStats {
        self.polygon_stats_of(uv, |t| t)
    }

    /// How much of the polygon with texture coordinates `uv` the texture's alpha leaves in
    /// place, as an alpha texture cuts a surface ([`Texture::is_present`]): the share of
    /// its area on texels whose alpha is at least [`ALPHA_CUTOFF`] (in `[0, 1]`, exact up to
    /// rounding), and the smallest and largest presence (0 or 1) of the texels it touches.
    pub fn coverage(&self, uv: &[DVec2]) -> Coverage {
        let stats = self.polygon_stats_of(uv, |t| {
            let present = if t[3] >= ALPHA_CUTOFF { 1.0 } else { 0.0 };
            [present; 4]
        });
        Coverage {
            mean: stats.mean[0].clamp(0.0, 1.0),
            min: f64::from(stats.min[0]),
            max: f64::from(stats.max[0]),
        }
    }

    /// [`Self::polygon_stats`] of the texel values `value(texel)`.
    fn polygon_stats_of(&self, uv: &[DVec2], value: impl Fn([f32; 4]) -> [f32; 4]) -> TexelStats {
        let (w, h) = (self.width as f64, self.height as f64);
        let points: Vec<DVec2> = uv
            .iter()
            .map(|p| DVec2::new(p.x * w, (1.0 - p.y) * h))
            .collect();
        let total = signed_area(&points);
        let texel_at = |p: DVec2| value(self.texel(p.x.floor() as i64, p.y.floor() as i64));
        if points.is_empty() || !total.is_finite() || total.abs() <= 1e-12 * (w * h).max(1.0) {
            let t = points.first().map_or([0.0; 4], |&p| texel_at(p));
            return TexelStats {
                mean: t.map(f64::from),
                min: t,
                max: t,
            };
        }
        let convex = is_convex(&points);
        let (y_min, y_max) = span(&points, |p| p.y);
        let mut sum = [0.0; 4];
        let (mut min, mut max) = ([f32::INFINITY; 4], [f32::NEG_INFINITY; 4]);
        let mut add = |x: i64, y: i64, weight: f64| {
            let t = value(self.texel(x, y));
            for c in 0..4 {
                sum[c] += weight * f64::from(t[c]);
                min[c] = min[c].min(t[c]);
                max[c] = max[c].max(t[c]);
            }
        };
        for row in y_min.floor() as i64..y_max.ceil() as i64 {
            let (top, bottom) = (row as f64, row as f64 + 1.0);
            let slab = clip(&clip(&points, 1, top, true), 1, bottom, false);
            if slab.len() < 3 {
                continue;
            }
            let (x_min, x_max) = span(&slab, |p| p.x);
            let (first, last) = (x_min.floor() as i64, x_max.ceil() as i64);
            // Columns `full.0..full.1` lie wholly inside: between the chords of the row's top
            // and bottom lines (convexity puts every vertical segment between them inside).
            let full = match (convex, chord(&slab, top), chord(&slab, bottom)) {
                (true, Some(a), Some(b)) => {
                    let (lo, hi) = (a.0.max(b.0).ceil() as i64, a.1.min(b.1).floor() as i64);
                    if lo < hi { (lo, hi) } else { (last, last) }
                }
                _ => (last, last),
            };
            let sign = total.signum();
            for x in full.0..full.1 {
                add(x, row, sign);
            }
            for x in (first..full.0).chain(full.1.max(full.0)..last) {
                let (left, right) = (x as f64, x as f64 + 1.0);
                let cell = clip(&clip(&slab, 0, left, true), 0, right, false);
                if cell.len() >= 3 {
                    add(x, row, signed_area(&cell));
                }
            }
        }
        TexelStats {
            mean: sum.map(|s| s / total),
            min,
            max,
        }
    }
}

/// Whether `polygon` turns one way only (collinear corners allowed).
fn is_convex(polygon: &[DVec2]) -> bool {
    let n = polygon.len();
    let turns = (0..n).map(|i| {
        let (a, b, c) = (polygon[i], polygon[(i + 1) % n], polygon[(i + 2) % n]);
        (b - a).perp_dot(c - b)
    });
    let (mut left, mut right) = (false, false);
    for t in turns {
        left |= t > 0.0;
        right |= t < 0.0;
    }
    !(left && right)
}

/// The smallest and largest `key` over `points`.
fn span(points: &[DVec2], key: impl Fn(DVec2) -> f64) -> (f64, f64) {
    points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(key(p)), hi.max(key(p)))
        })
}

/// The part of `polygon` on one side of the line `p[axis] = at`: where `p[axis] ≥ at`
/// (`above`) or `≤ at` (Sutherland–Hodgman). Crossings lie on the line exactly, so
/// [`chord`] finds them.
fn clip(polygon: &[DVec2], axis: usize, at: f64, above: bool) -> Vec<DVec2> {
    let inside = |p: DVec2| if above { p[axis] - at } else { at - p[axis] };
    let n = polygon.len();
    let mut out = Vec::with_capacity(n + 2);
    for i in 0..n {
        let (a, b) = (polygon[i], polygon[(i + 1) % n]);
        let (da, db) = (inside(a), inside(b));
        if da >= 0.0 {
            out.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            let mut p = a + (b - a) * (da / (da - db));
            p[axis] = at;
            out.push(p);
        }
    }
    out
}

/// The x-interval where horizontal line `y` meets `polygon` (a slab clipped at `y`), if it
/// meets it along a segment.
fn chord(polygon: &[DVec2], y: f64) -> Option<(f64, f64)> {
    let (lo, hi) = polygon
        .iter()
        .filter(|p| p.y == y)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.x), hi.max(p.x))
        });
    (lo < hi).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::super::Wrap;
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_pcg::Pcg64Mcg;

    /// 7 × 5 texels of distinct values in each channel.
    fn odd_texture() -> Texture {
        Texture::from_fn("odd", 7, 5, |x, y| {
            let v = (x * 5 + y) as f32 / 35.0;
            [v, 1.0 - v, (x % 2) as f32, (y % 3) as f32 / 2.0]
        })
    }

    /// The mean over a convex `polygon` (texture coordinates) found the other way round:
    /// each texel square of the bounding box clipped by the polygon's edges, in texel space.
    fn mean_by_texel_squares(texture: &Texture, polygon: &[DVec2]) -> [f64; 4] {
        let (w, h) = (texture.width as f64, texture.height as f64);
        let mut points: Vec<DVec2> = polygon
            .iter()
            .map(|p| DVec2::new(p.x * w, (1.0 - p.y) * h))
            .collect();
        if signed_area(&points) < 0.0 {
            points.reverse();
        }
        let (x0, x1) = span(&points, |p| p.x);
        let (y0, y1) = span(&points, |p| p.y);
        let (mut sum, mut area) = ([0.0; 4], 0.0);
        for y in y0.floor() as i64..y1.ceil() as i64 {
            for x in x0.floor() as i64..x1.ceil() as i64 {
                let mut cell = vec![
                    DVec2::new(x as f64, y as f64),
                    DVec2::new(x as f64 + 1.0, y as f64),
                    DVec2::new(x as f64 + 1.0, y as f64 + 1.0),
                    DVec2::new(x as f64, y as f64 + 1.0),
                ];
                for i in 0..points.len() {
                    let (a, b) = (points[i], points[(i + 1) % points.len()]);
                    let edge = b - a;
                    let mut kept = Vec::new();
                    for j in 0..cell.len() {
                        let (p, q) = (cell[j], cell[(j + 1) % cell.len()]);
                        let (dp, dq) = (edge.perp_dot(p - a), edge.perp_dot(q - a));
                        if dp >= 0.0 {
                            kept.push(p);
                        }
                        if (dp >= 0.0) != (dq >= 0.0) {
                            kept.push(p + (q - p) * (dp / (dp - dq)));
                        }
                    }
                    cell = kept;
                }
                if cell.len() >= 3 {
                    let a = signed_area(&cell);
                    let t = texture.texel(x, y);
                    for c in 0..4 {
                        sum[c] += a * f64::from(t[c]);
                    }
                    area += a;
                }
            }
        }
        sum.map(|s| s / area)
    }

    /// A random convex polygon of 3 to 8 corners around a random centre, radius up to 0.8
    /// (so it often crosses the texture's edges and wraps).
    fn random_convex(rng: &mut Pcg64Mcg) -> Vec<DVec2> {
        let n = rng.random_range(3..=8);
        let centre = DVec2::new(rng.random_range(-1.0..2.0), rng.random_range(-1.0..2.0));
        let radius = rng.random_range(0.01..0.8);
        let mut angles: Vec<f64> = (0..n)
            .map(|_| rng.random_range(0.0..std::f64::consts::TAU))
            .collect();
        angles.sort_by(f64::total_cmp);
        let stretch = rng.random_range(0.3..3.0);
        angles
            .iter()
            .map(|a| centre + radius * DVec2::new(a.cos() * stretch, a.sin()))
            .collect()
    }

    #[test]
    fn random_convex_polygons_match_the_texel_by_texel_mean() {
        let texture = odd_texture();
        let mut rng = Pcg64Mcg::seed_from_u64(7);
        for _ in 0..500 {
            let mut polygon = random_convex(&mut rng);
            if rng.random_bool(0.5) {
                polygon.reverse();
            }
            let (fast, slow) = (
                texture.polygon_mean(&polygon),
                mean_by_texel_squares(&texture, &polygon),
            );
            for c in 0..4 {
                assert!(
                    (fast[c] - slow[c]).abs() < 1e-9,
                    "{polygon:?}: {fast:?} vs {slow:?}"
                );
            }
        }
    }

    #[test]
    fn random_convex_polygons_match_a_supersampled_mean() {
        // 400 × 400 point samples (cell centres of the bounding box, those inside counted):
        // the boundary cells' error is at most their share, about perimeter / (400·size).
        let texture = odd_texture();
        let mut rng = Pcg64Mcg::seed_from_u64(11);
        for _ in 0..20 {
            let polygon = random_convex(&mut rng);
            let (x0, x1) = span(&polygon, |p| p.x);
            let (y0, y1) = span(&polygon, |p| p.y);
            let n = 400;
            let (mut sum, mut count) = ([0.0; 4], 0.0);
            for i in 0..n {
                for j in 0..n {
                    let p = DVec2::new(
                        x0 + (x1 - x0) * (i as f64 + 0.5) / n as f64,
                        y0 + (y1 - y0) * (j as f64 + 0.5) / n as f64,
                    );
                    let inside = (0..polygon.len()).all(|k| {
                        let (a, b) = (polygon[k], polygon[(k + 1) % polygon.len()]);
                        (b - a).perp_dot(p - a) >= 0.0
                    });
                    if inside {
                        let x = (p.x * 7.0).floor() as i64;
                        let y = ((1.0 - p.y) * 5.0).floor() as i64;
                        let t = texture.texel(x, y);
                        for c in 0..4 {
                            sum[c] += f64::from(t[c]);
                        }
                        count += 1.0;
                    }
                }
            }
            let exact = texture.polygon_mean(&polygon);
            for c in 0..4 {
                assert!(
                    (sum[c] / count - exact[c]).abs() < 0.01,
                    "{polygon:?} channel {c}"
                );
            }
        }
    }

    #[test]
    fn coverage_is_the_texel_by_texel_share_of_present_texels() {
        // The odd texture's alpha is 0, ½, 1, 0, ½ by row: present (≥ ½) on three rows of five.
        let texture = odd_texture();
        let mask = Texture::from_fn("mask", 7, 5, |x, y| {
            let present = if texture.texel(i64::from(x), i64::from(y))[3] >= ALPHA_CUTOFF {
                1.0
            } else {
                0.0
            };
            [present; 4]
        });
        let mut rng = Pcg64Mcg::seed_from_u64(5);
        for _ in 0..200 {
            let polygon = random_convex(&mut rng);
            let coverage = texture.coverage(&polygon);
            let expected = mean_by_texel_squares(&mask, &polygon)[0];
            assert!((coverage.mean - expected).abs() < 1e-9, "{polygon:?}");
            assert!(coverage.min - 1e-12 <= coverage.mean && coverage.mean <= coverage.max + 1e-12);
        }
        let whole = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(DVec2::from);
        assert!((texture.coverage(&whole).mean - 3.0 / 5.0).abs() < 1e-12);
        assert_eq!(
            (texture.coverage(&whole).min, texture.coverage(&whole).max),
            (0.0, 1.0)
        );
    }

    #[test]
    fn the_unit_square_gives_the_mean_of_all_texels_and_any_period_the_same() {
        let texture = odd_texture();
        let all = texture.mean_color();
        for offset in [DVec2::ZERO, DVec2::new(3.0, -2.0)] {
            let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
                .map(|(u, v)| DVec2::new(u, v) + offset);
            let mean = texture.polygon_mean(&square);
            assert!((mean[0] - f64::from(all.r)).abs() < 1e-7, "{mean:?}");
            assert!((mean[2] - f64::from(all.b)).abs() < 1e-7, "{mean:?}");
        }
    }

    #[test]
    fn a_concave_polygon_is_the_sum_of_its_parts() {
        let texture = odd_texture();
        let p = |u: f64, v: f64| DVec2::new(u, v);
        // An L: the square [0.1, 0.9]² less its top-right quarter.
        let l = [
            p(0.1, 0.1),
            p(0.9, 0.1),
            p(0.9, 0.5),
            p(0.5, 0.5),
            p(0.5, 0.9),
            p(0.1, 0.9),
        ];
        let bottom = [p(0.1, 0.1), p(0.9, 0.1), p(0.9, 0.5), p(0.1, 0.5)];
        let top_left = [p(0.1, 0.5), p(0.5, 0.5), p(0.5, 0.9), p(0.1, 0.9)];
        let (a, b, c) = (
            texture.polygon_mean(&l),
            texture.polygon_mean(&bottom),
            texture.polygon_mean(&top_left),
        );
        for k in 0..4 {
            let parts = (b[k] * 0.32 + c[k] * 0.16) / 0.48;
            assert!(
                (a[k] - parts).abs() < 1e-12,
                "channel {k}: {} vs {parts}",
                a[k]
            );
        }
    }

    #[test]
    fn a_clamped_texture_extends_its_edge_outwards() {
        let texture = Texture {
            wrap: Wrap::Clamp,
            ..odd_texture()
        };
        // [1, 3] × [0.2, 0.4] lies right of the image, in row 3 (y = (1 − v)·5 ∈ [3, 4]):
        // it sees the last texel of that row only.
        let p = |u: f64, v: f64| DVec2::new(u, v);
        let mean = texture.polygon_mean(&[p(1.0, 0.2), p(3.0, 0.2), p(3.0, 0.4), p(1.0, 0.4)]);
        let t = texture.texel(6, 3).map(f64::from);
        for c in 0..4 {
            assert!((mean[c] - t[c]).abs() < 1e-12, "{mean:?} vs {t:?}");
        }
        let slow = mean_by_texel_squares(&texture, &[p(-0.5, -0.3), p(0.4, -0.2), p(0.2, 0.6)]);
        let fast = texture.polygon_mean(&[p(-0.5, -0.3), p(0.4, -0.2), p(0.2, 0.6)]);
        for c in 0..4 {
            assert!((fast[c] - slow[c]).abs() < 1e-9, "{fast:?} vs {slow:?}");
        }
    }

    #[test]
    fn a_polygon_of_no_area_takes_the_texel_under_it() {
        let texture = odd_texture();
        let point = [DVec2::new(0.3, 0.3); 3];
        let t = texture.texel(2, 3).map(f64::from);
        assert_eq!(texture.polygon_mean(&point), t);
    }
}
