//! Contact splits (seed 000 §4.2 and §6.3.1, the asymmetric initial linking): a face that
//! another face touches along an edge while standing across the first face's plane — a box
//! standing on the floor, a wall meeting a ceiling in its middle — is split at the toucher's
//! support plane before it becomes a root patch. No patch then lies partly inside a solid
//! that touches it, so no light leaks into the closed part or out of it.
//!
//! Only faces in contact are split, as the seed asks: the toucher must have an edge lying in
//! the face's plane (within the epsilon band of [`super::clip`]) that overlaps the face, and
//! its other corners must all lie on one side. Of the pieces a face has been cut into so far,
//! only those the contact edge overlaps are cut again, along the toucher's whole plane: a box
//! on a floor cuts the floor into its footprint and four pieces around it.

use super::clip::{Plane, SideCounts, split};
use glam::{DVec2, DVec3};
use std::collections::HashMap;

/// Relative rounding of scene geometry: coordinates are single precision (6·10⁻⁸ per
/// coordinate, compounded by transforms and tessellation), so corners that should share a
/// plane or a point — the pole of a tessellated sphere resting on a floor, a rotated box
/// standing on one — can be off it by a few 10⁻⁸ of the coordinates' magnitude. Contact
/// tests use this band, which holds such corners with margin.
const ROUNDING_EPSILON: f64 = 1e-6;

/// A face on its way to becoming root patches.
#[derive(Clone, Debug, PartialEq)]
pub struct Face {
    /// Corners, counter-clockwise around the front side (world space).
    pub corners: Vec<DVec3>,
    /// Texture coordinates per corner.
    pub uvs: Vec<DVec2>,
    /// Scene object it belongs to.
    pub object: u32,
    /// Face index within the object's polygon mesh.
    pub face: u32,
    /// Material.
    pub material: u32,
    /// Longest edge of the face this one was cut from (itself when uncut), scene units: what
    /// a uniform subdivision by levels measures its patches against.
    pub source_edge: f64,
    /// True for a piece cut from a larger face.
    pub cut: bool,
}

impl Face {
    /// The longest edge of `corners` (scene units).
    pub fn longest_edge(corners: &[DVec3]) -> f64 {
        (0..corners.len())
            .map(|i| corners[i].distance(corners[(i + 1) % corners.len()]))
            .fold(0.0, f64::max)
    }

    /// The face's support plane (front = the side its corners wind counter-clockwise around),
    /// `None` for a degenerate face.
    fn plane(&self) -> Option<Plane> {
        let n = self.corners.len();
        let newell: DVec3 = (0..n)
            .map(|i| self.corners[i].cross(self.corners[(i + 1) % n]))
            .sum();
        let normal = newell.try_normalize()?;
        let centroid = self.corners.iter().sum::<DVec3>() / n as f64;
        Some(Plane::new(centroid, normal))
    }

    fn bounds(&self) -> (DVec3, DVec3) {
        let lo = self
            .corners
            .iter()
            .copied()
            .fold(DVec3::INFINITY, DVec3::min);
        let hi = self
            .corners
            .iter()
            .copied()
            .fold(DVec3::NEG_INFINITY, DVec3::max);
        (lo, hi)
    }
}

/// Faces a bounding-box grid cell may hold before the grid gives up on finer cells.
const MAX_CELLS_PER_FACE: i64 = 4096;

/// `faces` with every face that another one touches (as the module describes) split at the
/// toucher's plane; the pieces keep object, face and material, with interpolated texture
/// coordinates. Faces nothing touches come back unchanged, in their order.
pub fn split_at_contacts(faces: Vec<Face>) -> Vec<Face> {
    let planes: Vec<Option<Plane>> = faces.iter().map(Face::plane).collect();
    let grid = BoundsGrid::new(&faces);
    let mut out = Vec::with_capacity(faces.len());
    for (index, face) in faces.iter().enumerate() {
        let mut pieces = vec![face.clone()];
        for toucher in grid.near(&face.bounds()) {
            if toucher == index {
                continue;
            }
            let Some(plane) = planes[toucher] else {
                continue;
            };
            pieces = pieces
                .into_iter()
                .flat_map(|piece| {
                    if touches(&faces[toucher], &piece, &plane) {
                        let halves = split(&plane, &piece.corners, &piece.uvs);
                        [halves.front, halves.back]
                            .into_iter()
                            .filter(|p| p.corners.len() >= 3)
                            .map(|p| Face {
                                corners: p.corners,
                                uvs: p.uvs,
                                cut: true,
                                ..piece.clone()
                            })
                            .collect()
                    } else {
                        vec![piece]
                    }
                })
                .collect();
        }
        out.extend(pieces);
    }
    out
}

/// True when `toucher` (support plane `toucher_plane`) stands on `face`: an edge of it lies in
/// the face's plane and overlaps the face, its other corners lie on one side, and its plane
/// cuts the face into two parts of non-zero area.
fn touches(toucher: &Face, face: &Face, toucher_plane: &Plane) -> bool {
    let Some(face_plane) = face.plane() else {
        return false;
    };
    let on_face = SideCounts::of(&face_plane, &toucher.corners);
    if on_face.on < 2
        || (on_face.front > 0 && on_face.back > 0)
        || on_face.front + on_face.back == 0
    {
        return false;
    }
    if !SideCounts::of(toucher_plane, &face.corners).straddles() {
        return false;
    }
    let tolerance = ROUNDING_EPSILON * extent(&face.corners).max(extent(&toucher.corners));
    let contact: Vec<DVec3> = toucher
        .corners
        .iter()
        .copied()
        .filter(|&p| face_plane.distance(p).abs() <= tolerance.max(f64::MIN_POSITIVE))
        .collect();
    contact.len() >= 2 && segment_overlaps(&contact, face, &face_plane, tolerance)
}

/// The largest coordinate magnitude of `points` (the scale of the configuration).
fn extent(points: &[DVec3]) -> f64 {
    points
        .iter()
        .map(|p| p.abs().max_element())
        .fold(0.0, f64::max)
}

/// True when the segment spanned by the collinear `contact` points overlaps the convex `face`
/// (in its plane) over a non-zero length.
fn segment_overlaps(contact: &[DVec3], face: &Face, plane: &Plane, tolerance: f64) -> bool {
    let (a, b) = farthest_pair(contact);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    let c = &face.corners;
    for i in 0..c.len() {
        let (p, q) = (c[i], c[(i + 1) % c.len()]);
        // Inward normal of the edge p → q (corners wind counter-clockwise about the normal).
        let inward = plane.normal.cross(q - p);
        let (da, db) = (inward.dot(a - p), inward.dot(b - p));
        let slack = tolerance * inward.length();
        if da < -slack && db < -slack {
            return false;
        }
        if da < -slack || db < -slack {
            // Clipped at the edge itself: the slack decides only whether the segment is
            // outside, so a segment that merely ends at the face's edge overlaps by nothing.
            let t = da / (da - db);
            if da < -slack {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    (t1 - t0) * a.distance(b) > tolerance
}

/// The two points of `points` farthest apart.
fn farthest_pair(points: &[DVec3]) -> (DVec3, DVec3) {
    let mut best = (points[0], points[0], -1.0);
    for (i, &p) in points.iter().enumerate() {
        for &q in &points[i + 1..] {
            let d = p.distance_squared(q);
            if d > best.2 {
                best = (p, q, d);
            }
        }
    }
    (best.0, best.1)
}

/// A uniform grid over face bounds, to find the faces near a box without testing all pairs.
struct BoundsGrid {
    cell: f64,
    cells: HashMap<[i64; 3], Vec<usize>>,
    /// Faces too large for the grid, tested against everything.
    large: Vec<usize>,
}

impl BoundsGrid {
    fn new(faces: &[Face]) -> Self {
        let mut sizes: Vec<f64> = faces
            .iter()
            .map(|f| {
                let (lo, hi) = f.bounds();
                (hi - lo).max_element()
            })
            .filter(|s| s.is_finite() && *s > 0.0)
            .collect();
        sizes.sort_by(f64::total_cmp);
        let cell = sizes.get(sizes.len() / 2).copied().unwrap_or(1.0);
        let mut grid = BoundsGrid {
            cell,
            cells: HashMap::new(),
            large: Vec::new(),
        };
        for (index, face) in faces.iter().enumerate() {
            let keys: Option<Vec<[i64; 3]>> = grid.cells_of(&face.bounds()).map(Iterator::collect);
            match keys {
                Some(keys) => {
                    for k in keys {
                        grid.cells.entry(k).or_default().push(index);
                    }
                }
                None => grid.large.push(index),
            }
        }
        grid
    }

    /// The cells a box covers (slightly enlarged), `None` when they are too many.
    fn cells_of(&self, &(lo, hi): &(DVec3, DVec3)) -> Option<impl Iterator<Item = [i64; 3]>> {
        let pad = ROUNDING_EPSILON * lo.abs().max(hi.abs()).max_element() + f64::MIN_POSITIVE;
        let to_cell = |v: f64| (v / self.cell).floor() as i64;
        let a = [lo.x - pad, lo.y - pad, lo.z - pad].map(to_cell);
        let b = [hi.x + pad, hi.y + pad, hi.z + pad].map(to_cell);
        let count = (0..3).map(|k| b[k] - a[k] + 1).product::<i64>();
        if !(1..=MAX_CELLS_PER_FACE).contains(&count) {
            return None;
        }
        Some((a[0]..=b[0]).flat_map(move |x| {
            (a[1]..=b[1]).flat_map(move |y| (a[2]..=b[2]).map(move |z| [x, y, z]))
        }))
    }

    /// Indices of the faces whose cells meet the box, each once, ascending.
    fn near(&self, bounds: &(DVec3, DVec3)) -> Vec<usize> {
        let mut found: Vec<usize> = match self.cells_of(bounds) {
            Some(keys) => keys
                .filter_map(|k| self.cells.get(&k))
                .flatten()
                .copied()
                .collect(),
            None => self.cells.values().flatten().copied().collect(),
        };
        found.extend(&self.large);
        found.sort_unstable();
        found.dedup();
        found
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn face(corners: &[[f64; 3]], object: u32) -> Face {
        Face {
            corners: corners.iter().map(|&c| DVec3::from_array(c)).collect(),
            uvs: vec![DVec2::ZERO; corners.len()],
            object,
            face: 0,
            material: 0,
            source_edge: 1.0,
            cut: false,
        }
    }

    /// A 4 × 4 floor at y = 0 facing up and the four walls of a unit box standing on it.
    fn floor_and_box() -> Vec<Face> {
        let floor = face(
            &[
                [0.0, 0.0, 0.0],
                [0.0, 0.0, 4.0],
                [4.0, 0.0, 4.0],
                [4.0, 0.0, 0.0],
            ],
            0,
        );
        let (x0, x1, z0, z1) = (1.0, 2.0, 1.0, 2.0);
        let wall = |a: [f64; 2], b: [f64; 2]| {
            face(
                &[
                    [a[0], 0.0, a[1]],
                    [b[0], 0.0, b[1]],
                    [b[0], 1.0, b[1]],
                    [a[0], 1.0, a[1]],
                ],
                1,
            )
        };
        vec![
            floor,
            wall([x0, z0], [x1, z0]),
            wall([x1, z0], [x1, z1]),
            wall([x1, z1], [x0, z1]),
            wall([x0, z1], [x0, z0]),
        ]
    }

    fn area(f: &Face) -> f64 {
        let n = f.corners.len();
        (0..n)
            .map(|i| f.corners[i].cross(f.corners[(i + 1) % n]))
            .sum::<DVec3>()
            .length()
            * 0.5
    }

    #[test]
    fn a_box_on_the_floor_splits_the_floor_along_its_walls_only() {
        let out = split_at_contacts(floor_and_box());
        let floor: Vec<&Face> = out.iter().filter(|f| f.object == 0).collect();
        // Each wall's plane cuts only the piece its bottom edge lies on: the footprint and four
        // pieces around it (a pinwheel, not a 3 × 3 grid).
        assert_eq!(floor.len(), 5, "{floor:?}");
        let total: f64 = floor.iter().map(|f| area(f)).sum();
        assert!((total - 16.0).abs() < 1e-12);
        assert!(floor.iter().any(|f| {
            (area(f) - 1.0).abs() < 1e-12
                && f.corners
                    .iter()
                    .all(|c| (1.0..=2.0).contains(&c.x) && (1.0..=2.0).contains(&c.z))
        }));
        // The walls stand on the floor but are not cut by it (the floor's plane only touches
        // them), and walls meeting at corners do not cut each other.
        assert_eq!(out.iter().filter(|f| f.object == 1).count(), 4);
    }

    #[test]
    fn faces_apart_or_merely_crossing_are_not_split() {
        let mut faces = floor_and_box();
        // Lift the box: no contact, no split.
        for f in faces.iter_mut().skip(1) {
            for c in &mut f.corners {
                c.y += 0.5;
            }
        }
        assert_eq!(split_at_contacts(faces.clone()).len(), 5);
        // A wall crossing the floor's plane without an edge in it: no contact either.
        for f in faces.iter_mut().skip(1) {
            for c in &mut f.corners {
                c.y -= 1.0;
            }
        }
        assert_eq!(split_at_contacts(faces).len(), 5);
    }
}
