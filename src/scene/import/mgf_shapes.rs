//! MGF's curved and solid primitives as polygons, and faces with seams split into triangles.
//!
//! **Tessellation.** Every circle is cut into [`SEGMENTS`] = 32 straight edges (corners on
//! the circle); a sphere also into [`SPHERE_BANDS`] = 16 bands of latitude (quads, triangles
//! at the poles: 512 faces), a torus's tube into [`TUBE_SEGMENTS`] = 16 (512 quads). The
//! polygons are inscribed, so their area is a little below the curved surface's: by 0.16 %
//! for cylinders, 0.16–0.64 % for cones (the flatter, the more), 0.64 % for rings and discs,
//! 0.80 % for spheres and about 1.0 % for tori (the unit tests hold each to the closed form).
//! `cyl`, `cone` and `prism` sides are quads, discs and cone tips triangles. Normals face out
//! of the solid, or in for negative radii (negative length for `prism`), and rings face along
//! their centre vertex's normal.
//!
//! **Seams.** MGF has no holes: a face with a hole runs from its outline along a seam to the
//! hole, around the hole the other way and back along the seam (`f v1 v2 v3 v4 v5 v6 v7 v8 v5
//! v4`). Such a face, whose corners repeat, is cut into triangles by ear clipping in its plane,
//! where a corner lying on another one's place does not block an ear.

use glam::{DVec2, DVec3};
use std::collections::HashSet;
use std::f64::consts::{PI, TAU};

/// Straight edges around every circle of a tessellated primitive.
pub const SEGMENTS: usize = 32;

/// Bands of latitude of a tessellated sphere.
pub const SPHERE_BANDS: usize = 16;

/// Segments around the tube of a tessellated torus.
pub const TUBE_SEGMENTS: usize = 16;

/// Faces with seams of more corners than this are refused (ear clipping costs up to the cube
/// of the corner count).
pub const MAX_SEAM_CORNERS: usize = 512;

/// A polygon's corners, counter-clockwise seen from its front.
pub(super) type Polygon = Vec<DVec3>;

/// An orthonormal pair `(u, v)` with `u × v = w` (`w` a unit vector).
fn frame(w: DVec3) -> (DVec3, DVec3) {
    let u = w.any_orthonormal_vector();
    (u, w.cross(u))
}

/// The unit direction at angle `phi` in the plane of `(u, v)`.
fn around((u, v): (DVec3, DVec3), phi: f64) -> DVec3 {
    u * phi.cos() + v * phi.sin()
}

/// The angle of corner `i` of [`SEGMENTS`] around a circle.
fn angle(i: usize) -> f64 {
    TAU * i as f64 / SEGMENTS as f64
}

/// `polygons` with their winding reversed when `inward`.
fn oriented(mut polygons: Vec<Polygon>, inward: bool) -> Vec<Polygon> {
    if inward {
        polygons.iter_mut().for_each(|p| p.reverse());
    }
    polygons
}

/// `sph`: the sphere around `centre` with radius `radius` (≠ 0; negative faces inward).
pub(super) fn sphere(centre: DVec3, radius: f64) -> Result<Vec<Polygon>, String> {
    if radius == 0.0 {
        return Err("radius: a sphere's radius must not be 0".into());
    }
    let axes = frame(DVec3::Z);
    let point = |band: usize, segment: usize| {
        let theta = PI * band as f64 / SPHERE_BANDS as f64;
        centre
            + radius.abs() * (theta.sin() * around(axes, angle(segment)) + theta.cos() * DVec3::Z)
    };
    let (north, south) = (
        centre + radius.abs() * DVec3::Z,
        centre - radius.abs() * DVec3::Z,
    );
    let mut polygons = Vec::with_capacity(SPHERE_BANDS * SEGMENTS);
    for band in 0..SPHERE_BANDS {
        for s in 0..SEGMENTS {
            polygons.push(match band {
                0 => vec![north, point(1, s), point(1, s + 1)],
                b if b + 1 == SPHERE_BANDS => vec![point(b, s), south, point(b, s + 1)],
                b => vec![
                    point(b, s),
                    point(b + 1, s),
                    point(b + 1, s + 1),
                    point(b, s + 1),
                ],
            });
        }
    }
    Ok(oriented(polygons, radius < 0.0))
}

/// `cone` (and `cyl`, with equal radii): the open side of the truncated cone from the disc of
/// radius `r1` around `p1` to that of radius `r2` around `p2`. One radius may be 0 (a tip);
/// both negative face inward.
pub(super) fn cone(p1: DVec3, r1: f64, p2: DVec3, r2: f64) -> Result<Vec<Polygon>, String> {
    if r1 == 0.0 && r2 == 0.0 {
        return Err("the radii must not both be 0".into());
    }
    if r1 * r2 < 0.0 {
        return Err(format!(
            "the radii {r1} and {r2} must not have different signs"
        ));
    }
    let w = (p2 - p1)
        .try_normalize()
        .ok_or("the two end vertices are at the same place (a flat disc is a ring)")?;
    let axes = frame(w);
    let polygons = (0..SEGMENTS)
        .map(|j| {
            let (d0, d1) = (around(axes, angle(j)), around(axes, angle(j + 1)));
            let quad = [
                p1 + r1.abs() * d0,
                p1 + r1.abs() * d1,
                p2 + r2.abs() * d1,
                p2 + r2.abs() * d0,
            ];
            without_repeats(&quad)
        })
        .collect();
    Ok(oriented(polygons, r1 < 0.0 || r2 < 0.0))
}

/// The unit normal a `ring` or `torus` (`shape`) is oriented by, from its centre vertex's.
fn centre_normal(normal: DVec3, shape: &str) -> Result<DVec3, String> {
    normal
        .try_normalize()
        .ok_or_else(|| format!("the centre vertex has no normal (n) to orient the {shape}"))
}

/// `ring`: the flat ring (a disc when `rmin` is 0) around `centre`, facing along `normal`.
pub(super) fn ring(
    centre: DVec3,
    normal: DVec3,
    rmin: f64,
    rmax: f64,
) -> Result<Vec<Polygon>, String> {
    let w = centre_normal(normal, "ring")?;
    if rmin < 0.0 || rmax <= rmin {
        return Err(format!("radii {rmin} and {rmax}: 0 ≤ rmin < rmax expected"));
    }
    let axes = frame(w);
    Ok((0..SEGMENTS)
        .map(|j| {
            let (d0, d1) = (around(axes, angle(j)), around(axes, angle(j + 1)));
            let quad = [
                centre + rmin * d0,
                centre + rmax * d0,
                centre + rmax * d1,
                centre + rmin * d1,
            ];
            without_repeats(&quad)
        })
        .collect())
}

/// `torus`: the torus around `centre` in the plane normal to `normal`, reaching from `rmin`
/// to `rmax` from the centre (both ≤ 0, not both 0: facing inward).
pub(super) fn torus(
    centre: DVec3,
    normal: DVec3,
    rmin: f64,
    rmax: f64,
) -> Result<Vec<Polygon>, String> {
    let w = centre_normal(normal, "torus")?;
    let inward = rmin < 0.0 || (rmin == 0.0 && rmax < 0.0);
    if rmin * rmax < 0.0 || rmax.abs() <= rmin.abs() {
        return Err(format!(
            "radii {rmin} and {rmax}: 0 ≤ rmin < rmax (or rmax < rmin ≤ 0 for inward normals) \
             expected"
        ));
    }
    let (major, tube) = ((rmin + rmax).abs() / 2.0, (rmax - rmin).abs() / 2.0);
    let axes = frame(w);
    let point = |i: usize, j: usize| {
        let psi = TAU * j as f64 / TUBE_SEGMENTS as f64;
        centre + (major + tube * psi.cos()) * around(axes, angle(i)) + tube * psi.sin() * w
    };
    let mut polygons = Vec::with_capacity(SEGMENTS * TUBE_SEGMENTS);
    for i in 0..SEGMENTS {
        for j in 0..TUBE_SEGMENTS {
            let quad = [
                point(i, j),
                point(i + 1, j),
                point(i + 1, j + 1),
                point(i, j + 1),
            ];
            polygons.push(without_repeats(&quad));
        }
    }
    Ok(oriented(polygons, inward))
}

/// `prism`: the closed solid swept by the face `base` a distance `length` against its normal
/// (so that every face points out; a negative length sweeps along it, pointing every face in).
pub(super) fn prism(base: &[DVec3], length: f64) -> Result<Vec<Polygon>, String> {
    if length == 0.0 {
        return Err("length: a prism's length must not be 0".into());
    }
    let normal = newell(base)
        .try_normalize()
        .ok_or("the base vertices enclose no area")?;
    let top: Polygon = base.iter().map(|&p| p - length * normal).collect();
    let n = base.len();
    let mut polygons = vec![base.to_vec(), top.iter().rev().copied().collect()];
    polygons.extend((0..n).map(|i| vec![base[i], top[i], top[(i + 1) % n], base[(i + 1) % n]]));
    Ok(polygons)
}

/// The Newell vector of a polygon: its normal times twice its area.
fn newell(points: &[DVec3]) -> DVec3 {
    let n = points.len();
    (0..n).map(|i| points[i].cross(points[(i + 1) % n])).sum()
}

/// `points` without corners equal to the one before (the last compared with the first).
pub(super) fn without_repeats(points: &[DVec3]) -> Polygon {
    let mut out: Polygon = Vec::with_capacity(points.len());
    for &p in points {
        if out.last() != Some(&p) {
            out.push(p);
        }
    }
    while out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    out
}

/// True when a corner of the polygon comes back later (a seam): `points` has no corner equal
/// to its neighbour ([`without_repeats`]).
pub(super) fn has_seam(points: &[DVec3]) -> bool {
    let mut seen = HashSet::with_capacity(points.len());
    !points
        .iter()
        .all(|p| seen.insert([p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]))
}

/// Triangles (indices into `points`, wound as the face) of a face with seams
/// ([`has_seam`]); none when it has no area. Errors beyond [`MAX_SEAM_CORNERS`].
pub(super) fn split_seams(points: &[DVec3]) -> Result<Vec<[usize; 3]>, String> {
    if points.len() > MAX_SEAM_CORNERS {
        return Err(format!(
            "a face with seams of {} vertices is more than the {MAX_SEAM_CORNERS} strahl splits \
             into triangles",
            points.len()
        ));
    }
    let (lo, hi) = points
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
    let size = (hi - lo).length();
    let Some(w) = (newell(points) / (size * size))
        .try_normalize()
        .filter(|_| size > 0.0)
    else {
        return Ok(Vec::new());
    };
    let (u, v) = frame(w);
    let flat: Vec<DVec2> = points
        .iter()
        .map(|&p| DVec2::new((p - lo).dot(u), (p - lo).dot(v)) / size)
        .collect();
    let same = |a: usize, b: usize| points[a] == points[b];
    let turn = |a: usize, b: usize, c: usize| (flat[b] - flat[a]).perp_dot(flat[c] - flat[a]);
    let mut left: Vec<usize> = (0..points.len()).collect();
    let mut triangles = Vec::with_capacity(points.len());
    let mut start = 0;
    loop {
        drop_spikes(&mut left, &same);
        let m = left.len();
        if m < 3 {
            break;
        }
        let corner = |k: usize| (left[(k + m - 1) % m], left[k % m], left[(k + 1) % m]);
        let is_ear = |k: usize| {
            let (a, b, c) = corner(k);
            turn(a, b, c) > 1e-12
                && left.iter().all(|&q| {
                    same(q, a)
                        || same(q, b)
                        || same(q, c)
                        || !inside(flat[q], flat[a], flat[b], flat[c])
                })
        };
        let k = (0..m)
            .map(|step| (start + step) % m)
            .find(|&k| is_ear(k))
            .unwrap_or_else(|| {
                // Rounding left no ear: cut the flattest corner.
                (0..m)
                    .min_by(|&x, &y| {
                        let bend = |k: usize| {
                            let (a, b, c) = corner(k);
                            turn(a, b, c).abs()
                        };
                        bend(x).total_cmp(&bend(y))
                    })
                    .unwrap_or(0)
            });
        let (a, b, c) = corner(k);
        if turn(a, b, c) > 1e-12 {
            triangles.push([a, b, c]);
        }
        left.remove(k);
        start = k;
    }
    Ok(triangles)
}

/// Removes corners that add nothing to a face with seams: one equal to the next, and the tip
/// of a spike that goes out and comes straight back (with the corner it returns to).
fn drop_spikes(left: &mut Vec<usize>, same: &impl Fn(usize, usize) -> bool) {
    let mut k = 0;
    while left.len() >= 3 && k < left.len() {
        let m = left.len();
        let (prev, here, next) = (left[(k + m - 1) % m], left[k], left[(k + 1) % m]);
        if same(here, next) {
            left.remove(k);
        } else if same(prev, next) {
            let (first, second) = if k + 1 < m { (k + 1, k) } else { (k, 0) };
            left.remove(first);
            left.remove(second);
        } else {
            k += 1;
            continue;
        }
        k = k.saturating_sub(2);
    }
}

/// True when `q` lies inside the triangle `a, b, c` (counter-clockwise) or on its edges.
fn inside(q: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    let side = |p: DVec2, r: DVec2| (r - p).perp_dot(q - p);
    side(a, b) >= 0.0 && side(b, c) >= 0.0 && side(c, a) >= 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(polygons: &[Polygon]) -> f64 {
        polygons.iter().map(|p| newell(p).length() / 2.0).sum()
    }

    /// Relative deviation of `got` from `want`.
    fn deviation(got: f64, want: f64) -> f64 {
        (got - want) / want
    }

    /// Every face's normal points away from `centre` (or towards it).
    fn all_face(polygons: &[Polygon], centre: DVec3, outward: bool) -> bool {
        polygons.iter().all(|p| {
            let mid = p.iter().sum::<DVec3>() / p.len() as f64;
            (newell(p).dot(mid - centre) > 0.0) == outward
        })
    }

    #[test]
    fn curved_primitives_are_inscribed_within_their_stated_area_deficit() {
        let c = DVec3::new(1.0, 2.0, 3.0);
        let s = sphere(c, 2.0).unwrap();
        assert_eq!(s.len(), SPHERE_BANDS * SEGMENTS);
        let d = deviation(area(&s), 4.0 * PI * 4.0);
        assert!((-0.0085..-0.0075).contains(&d), "sphere {d}");
        assert!(all_face(&s, c, true) && all_face(&sphere(c, -2.0).unwrap(), c, false));

        let top = c + DVec3::new(0.0, 3.0, 4.0);
        let cyl = cone(c, 0.5, top, 0.5).unwrap();
        let d = deviation(area(&cyl), TAU * 0.5 * 5.0);
        assert!((-0.0017..-0.0015).contains(&d), "cylinder {d}");
        let tip = cone(c, 1.0, top, 0.0).unwrap();
        let slant = (25.0f64 + 1.0).sqrt();
        let d = deviation(area(&tip), PI * 1.0 * slant);
        assert!((-0.0065..-0.0015).contains(&d), "cone {d}");
        assert!(tip.iter().all(|p| p.len() == 3));

        let n = DVec3::new(0.0, 0.0, 2.0);
        let r = ring(c, n, 0.5, 1.5).unwrap();
        let d = deviation(area(&r), PI * (1.5 * 1.5 - 0.5 * 0.5));
        assert!((-0.0065..-0.0063).contains(&d), "ring {d}");
        assert!(
            r.iter()
                .all(|p| newell(p).normalize().dot(DVec3::Z) > 0.999)
        );
        let disc = ring(c, n, 0.0, 1.0).unwrap();
        assert!(disc.iter().all(|p| p.len() == 3));

        let t = torus(c, n, 1.0, 3.0).unwrap();
        let d = deviation(area(&t), 4.0 * PI * PI * 2.0 * 1.0);
        assert!((-0.011..-0.0098).contains(&d), "torus {d}");
        // A horn torus (rmin 0) closes at the centre without degenerate faces.
        assert!(torus(c, n, 0.0, 2.0).unwrap().iter().all(|p| p.len() >= 3));
    }

    #[test]
    fn prisms_are_closed_and_face_out() {
        let base = [DVec3::ZERO, DVec3::Y, DVec3::new(1.0, 1.0, 0.0), DVec3::X];
        // Seen from +z the base turns clockwise: its normal is −z, the prism grows to +z.
        let p = prism(&base, 2.0).unwrap();
        assert_eq!(p.len(), 6);
        assert!((area(&p) - (2.0 + 4.0 * 2.0)).abs() < 1e-12);
        let centre = DVec3::new(0.5, 0.5, 1.0);
        assert!(all_face(&p, centre, true));
        let inward = prism(&base, -2.0).unwrap();
        assert!(all_face(&inward, DVec3::new(0.5, 0.5, -1.0), false));
        assert!(prism(&[DVec3::ZERO, DVec3::X, DVec3::X * 2.0], 1.0).is_err());
    }

    #[test]
    fn primitives_refuse_bad_radii_and_missing_normals() {
        let c = DVec3::ZERO;
        let n = DVec3::Z;
        assert!(sphere(c, 0.0).is_err());
        assert!(cone(c, 1.0, c, 1.0).unwrap_err().contains("same place"));
        assert!(
            cone(c, 1.0, n, -1.0)
                .unwrap_err()
                .contains("different signs")
        );
        assert!(cone(c, 0.0, n, 0.0).is_err());
        assert!(
            ring(c, DVec3::ZERO, 0.0, 1.0)
                .unwrap_err()
                .contains("no normal")
        );
        assert!(ring(c, n, 1.0, 1.0).is_err());
        assert!(torus(c, n, -1.0, 2.0).is_err());
        assert!(torus(c, n, -2.0, -1.0).is_err());
        assert!(torus(c, n, -1.0, -2.0).is_ok());
    }

    #[test]
    fn faces_with_seams_split_into_their_area() {
        // A 4 × 4 square with a 2 × 2 hole, joined by a seam from corner 3 to the hole.
        let outer = [(0., 0.), (4., 0.), (4., 4.), (0., 4.)];
        let hole = [(1., 3.), (3., 3.), (3., 1.), (1., 1.)];
        let p = |(x, y): (f64, f64)| DVec3::new(x, y, 0.0);
        let mut face: Vec<DVec3> = outer.iter().map(|&c| p(c)).collect();
        face.extend(hole.iter().map(|&c| p(c)));
        face.push(p(hole[0]));
        face.push(p(outer[3]));
        assert!(has_seam(&face) && !has_seam(&face[..4]));
        let triangles = split_seams(&face).unwrap();
        let tris: Vec<Polygon> = triangles
            .iter()
            .map(|t| t.iter().map(|&i| face[i]).collect())
            .collect();
        assert!((area(&tris) - 12.0).abs() < 1e-12, "{}", area(&tris));
        assert!(tris.iter().all(|t| newell(t).z > 0.0));
        // The hole is not covered: its centre is in no triangle.
        let centre = DVec2::new(2.0, 2.0);
        let flat = |v: DVec3| DVec2::new(v.x, v.y);
        assert!(
            !tris
                .iter()
                .any(|t| inside(centre, flat(t[0]), flat(t[1]), flat(t[2])))
        );
        let huge = vec![DVec3::ZERO; MAX_SEAM_CORNERS + 1];
        assert!(
            split_seams(&huge)
                .unwrap_err()
                .contains("more than the 512")
        );
        assert_eq!(
            without_repeats(&[p((0., 0.)), p((0., 0.)), p((1., 0.)), p((0., 0.))]).len(),
            2
        );
    }
}
