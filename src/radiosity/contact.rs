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
//!
//! Nearly touching counts too: a face that hovers parallel to another close to it — a sign
//! a centimetre in front of a wall, a lamp just under the ceiling, a rug on the floor — cuts
//! the other along its outline (the planes through its edges along the other's normal), so
//! the dark footprint behind it is a patch of its own. Without the cut, a node half behind
//! the sign and half in the open takes light at a coarse level and hands it evenly to its
//! leaves, the dark ones included, and the sign's back is lit by the leak (`neon`: the sign
//! absorbed 4.5 % too much). A face hovers when its plane is within about 8° (cosine 0.99) of
//! parallel, all its corners lie on one side at most 5 % of its longest edge away,
//! and its outline overlaps the face.

use super::box_tree::BoxTree;
use super::clip::{Plane, SideCounts, split};
use super::shaft::Bounds;
use glam::{DVec2, DVec3};
use rayon::prelude::*;

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
    /// Size of the surface this face is part of, scene units: the longest edge of the face
    /// it was cut from (itself when uncut), or the size of the curved shape it is a facet
    /// of. What a uniform subdivision by levels measures the patches of a part against.
    pub source_edge: f64,
    /// True for part of a larger surface: a piece cut from a face, or a facet of a curved
    /// shape.
    pub part: bool,
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

    fn bounds(&self) -> Bounds {
        Bounds::from_points(self.corners.iter().copied())
    }

    /// The face's bounds grown by the gap a face hovering over it may leave (a share of its
    /// size) and the rounding of the corners: what a face must meet to touch or hover.
    fn reach(&self) -> Bounds {
        let Bounds { min, max } = self.bounds();
        let pad = ROUNDING_EPSILON * min.abs().max(max.abs()).max_element() + f64::MIN_POSITIVE;
        let r = DVec3::splat(HOVER_GAP * (max - min).max_element() + 2.0 * pad);
        Bounds {
            min: min - r,
            max: max + r,
        }
    }
}

/// Largest gap, as a share of the hovering face's longest edge, at which a parallel face
/// counts as nearly touching ([`hovers`]).
const HOVER_GAP: f64 = 0.05;

/// Smallest `|cos|` of the angle between the planes of a hovering face and the face it
/// cuts (about 8°).
const HOVER_ANGLE_COS: f64 = 0.99;

/// `faces` with every face that another one touches (as the module describes) split at the
/// toucher's plane; the pieces keep object, face and material, with interpolated texture
/// coordinates. Faces nothing touches come back unchanged, in their order.
pub fn split_at_contacts(faces: Vec<Face>) -> Vec<Face> {
    let planes: Vec<Option<Plane>> = faces.iter().map(Face::plane).collect();
    let reaches: Vec<Bounds> = faces.iter().map(Face::reach).collect();
    let tree = BoxTree::new(&faces.iter().map(Face::bounds).collect::<Vec<_>>());
    let split: Vec<Vec<Face>> = faces
        .par_iter()
        .enumerate()
        .map(|(index, face)| split_face(index, face, &faces, (&planes, &reaches), &tree))
        .collect();
    split.into_iter().flatten().collect()
}

/// Face `index` of `faces` split at the faces near it that touch it or hover over it. Each
/// of those is tested only against the pieces so far whose bounds come within its reach (a
/// floor under a room's furniture is cut into thousands of pieces).
fn split_face(
    index: usize,
    face: &Face,
    faces: &[Face],
    (planes, reaches): (&[Option<Plane>], &[Bounds]),
    tree: &BoxTree,
) -> Vec<Face> {
    let mut pieces = vec![(face.clone(), face.bounds())];
    for other in tree.meeting(&reaches[index]) {
        if other == index {
            continue;
        }
        let Some(plane) = planes[other] else {
            continue;
        };
        let toucher = &faces[other];
        let near = &reaches[other];
        // Cut in place, keeping the pieces' order: most pieces are out of reach.
        let mut i = 0;
        while i < pieces.len() {
            let (piece, bounds) = &pieces[i];
            if !bounds.overlaps(near) {
                i += 1;
                continue;
            }
            let cut_pieces = if touches(toucher, piece, &plane) {
                cut(piece.clone(), &[plane])
            } else if let Some(outline) = hovers(toucher, piece) {
                cut(piece.clone(), &outline)
            } else {
                i += 1;
                continue;
            };
            let count = cut_pieces.len();
            pieces.splice(
                i..=i,
                cut_pieces.into_iter().map(|p| {
                    let b = p.bounds();
                    (p, b)
                }),
            );
            i += count;
        }
    }
    pieces.into_iter().map(|(piece, _)| piece).collect()
}

/// `piece` cut at each of `planes` in turn (pieces a plane does not cross beyond the
/// rounding of the geometry stay whole: no sliver thinner than that is cut off).
fn cut(piece: Face, planes: &[Plane]) -> Vec<Face> {
    let tolerance = ROUNDING_EPSILON * extent(&piece.corners);
    let mut pieces = vec![piece];
    for plane in planes {
        pieces = pieces
            .into_iter()
            .flat_map(|piece| {
                if !crosses(plane, &piece.corners, tolerance) {
                    return vec![piece];
                }
                let halves = split(plane, &piece.corners, &piece.uvs);
                [halves.front, halves.back]
                    .into_iter()
                    .filter(|p| p.corners.len() >= 3)
                    .map(|p| Face {
                        corners: p.corners,
                        uvs: p.uvs,
                        part: true,
                        ..piece.clone()
                    })
                    .collect()
            })
            .collect();
    }
    pieces
}

/// When `hoverer` hovers over `face` (see the module documentation), the planes through its
/// edges along the face's normal, which cut out its footprint; else `None`.
fn hovers(hoverer: &Face, face: &Face) -> Option<Vec<Plane>> {
    let face_plane = face.plane()?;
    let hover_plane = hoverer.plane()?;
    if face_plane.normal.dot(hover_plane.normal).abs() < HOVER_ANGLE_COS {
        return None;
    }
    let gap = HOVER_GAP * Face::longest_edge(&hoverer.corners);
    let tolerance = ROUNDING_EPSILON * extent(&face.corners).max(extent(&hoverer.corners));
    let distances: Vec<f64> = hoverer
        .corners
        .iter()
        .map(|&p| face_plane.distance(p))
        .collect();
    let one_side = distances.iter().all(|&d| d > tolerance && d <= gap)
        || distances.iter().all(|&d| d < -tolerance && d >= -gap);
    if !one_side {
        return None;
    }
    // The outline's planes, each facing into the footprint (the hoverer's corners wind
    // about its own normal, which may face either way).
    let n = hoverer.corners.len();
    let centroid = hoverer.corners.iter().sum::<DVec3>() / n as f64;
    let outline: Vec<Plane> = (0..n)
        .filter_map(|i| {
            let (p, q) = (hoverer.corners[i], hoverer.corners[(i + 1) % n]);
            let normal = face_plane.normal.cross(q - p).try_normalize()?;
            let normal = if normal.dot(centroid - p) < 0.0 {
                -normal
            } else {
                normal
            };
            Some(Plane::new(p, normal))
        })
        .collect();
    // The footprint overlaps the face when no outline plane has the whole face behind it
    // and the face's edges do not hold the whole footprint outside (both convex).
    let face_outside = outline.iter().any(|plane| {
        let s = SideCounts::of(plane, &face.corners);
        s.front == 0
    });
    let footprint: Vec<DVec3> = hoverer
        .corners
        .iter()
        .map(|&p| p - face_plane.normal * face_plane.distance(p))
        .collect();
    let footprint_outside = (0..face.corners.len()).any(|i| {
        let (p, q) = (face.corners[i], face.corners[(i + 1) % face.corners.len()]);
        let inward = face_plane.normal.cross(q - p);
        footprint.iter().all(|&f| inward.dot(f - p) <= 0.0)
    });
    (!face_outside && !footprint_outside).then_some(outline)
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
    let tolerance = ROUNDING_EPSILON * extent(&face.corners).max(extent(&toucher.corners));
    if !crosses(toucher_plane, &face.corners, tolerance) {
        return false;
    }
    let contact: Vec<DVec3> = toucher
        .corners
        .iter()
        .copied()
        .filter(|&p| face_plane.distance(p).abs() <= tolerance.max(f64::MIN_POSITIVE))
        .collect();
    contact.len() >= 2 && segment_overlaps(&contact, face, &face_plane, tolerance)
}

/// True when `plane` cuts `corners` into two pieces each reaching farther than `tolerance`
/// (scene units) from it. A plane that passes within the rounding of the geometry of a corner
/// (the neighbouring facets of a tessellated sphere, whose pole corners differ by a few 10⁻⁸)
/// would cut off a sliver with an edge shorter than that rounding: no cut.
fn crosses(plane: &Plane, corners: &[DVec3], tolerance: f64) -> bool {
    let (lo, hi) = corners
        .iter()
        .map(|&p| plane.distance(p))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
            (lo.min(d), hi.max(d))
        });
    SideCounts::of(plane, corners).straddles() && lo < -tolerance && hi > tolerance
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
            part: false,
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
    fn a_plane_passing_within_the_rounding_of_a_corner_cuts_off_no_sliver() {
        // A wall standing on the floor 10⁻⁸ inside the floor's edge (as the facets of a
        // tessellated sphere around its pole do, in single precision): cutting there would
        // leave a sliver 10⁻⁸ wide.
        let floor = face(
            &[
                [0.0, 0.0, 0.0],
                [0.0, 0.0, 1.0],
                [1.0, 0.0, 1.0],
                [1.0, 0.0, 0.0],
            ],
            0,
        );
        let x = 1e-8;
        let wall = face(
            &[[x, 0.0, 0.0], [x, 0.0, 1.0], [x, 1.0, 1.0], [x, 1.0, 0.0]],
            1,
        );
        let out = split_at_contacts(vec![floor.clone(), wall]);
        let pieces: Vec<&Face> = out.iter().filter(|f| f.object == 0).collect();
        assert_eq!(pieces, [&floor]);
        // One clearly inside cuts.
        let wall = face(
            &[
                [0.25, 0.0, 0.0],
                [0.25, 0.0, 1.0],
                [0.25, 1.0, 1.0],
                [0.25, 1.0, 0.0],
            ],
            1,
        );
        let out = split_at_contacts(vec![floor, wall]);
        assert_eq!(out.iter().filter(|f| f.object == 0).count(), 2);
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

    /// A 4 × 3 wall at z = 0 facing +z and a 1 × 0.5 sign `gap` in front of it, tilted by
    /// `tilt` (its top edge moved along z).
    fn wall_and_sign(gap: f64, tilt: f64) -> Vec<Face> {
        let wall = face(
            &[
                [0.0, 0.0, 0.0],
                [4.0, 0.0, 0.0],
                [4.0, 3.0, 0.0],
                [0.0, 3.0, 0.0],
            ],
            0,
        );
        let sign = face(
            &[
                [1.0, 1.0, gap],
                [2.0, 1.0, gap],
                [2.0, 1.5, gap + tilt],
                [1.0, 1.5, gap + tilt],
            ],
            1,
        );
        vec![wall, sign]
    }

    #[test]
    fn a_sign_just_in_front_of_a_wall_cuts_out_its_footprint() {
        let out = split_at_contacts(wall_and_sign(0.01, 0.0));
        let wall: Vec<&Face> = out.iter().filter(|f| f.object == 0).collect();
        // The four outline planes cut the wall into a 3 × 3 grid; the middle is the footprint.
        assert_eq!(wall.len(), 9, "{wall:?}");
        let total: f64 = wall.iter().map(|f| area(f)).sum();
        assert!((total - 12.0).abs() < 1e-12);
        assert!(wall.iter().any(|f| {
            (area(f) - 0.5).abs() < 1e-12
                && f.corners
                    .iter()
                    .all(|c| (1.0..=2.0).contains(&c.x) && (1.0..=1.5).contains(&c.y))
        }));
        // The wall lies behind the sign, not in front: the sign stays whole.
        assert_eq!(out.iter().filter(|f| f.object == 1).count(), 1);
    }

    #[test]
    fn a_face_far_off_or_tilted_does_not_cut() {
        // 0.1 from the wall is a tenth of the sign's longest edge: more than the 5 % allowed.
        assert_eq!(split_at_contacts(wall_and_sign(0.1, 0.0)).len(), 2);
        // Tilted by 0.2 over its 0.5 height (22°).
        assert_eq!(split_at_contacts(wall_and_sign(0.01, 0.2)).len(), 2);
        // Beside the wall rather than in front of it.
        let mut faces = wall_and_sign(0.01, 0.0);
        for c in &mut faces[1].corners {
            c.x += 5.0;
        }
        assert_eq!(split_at_contacts(faces).len(), 2);
    }
}
