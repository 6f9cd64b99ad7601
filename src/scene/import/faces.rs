//! Imported faces made usable: concave and bent faces split into triangles (bent ones with a
//! warning), crossing ones (bowties) refused with their line, as the scene file does with
//! its polygons ([`crate::scene::polygon`]).

use super::obj_syntax::FaceLines;
use crate::scene::PolygonMesh;
use crate::scene::polygon::{self, PolygonError, Shape};
use glam::Vec3;
use std::path::Path;

/// Goes through the faces of a file's meshes in order, splitting and refusing them.
pub(super) struct FaceCheck {
    lines: FaceLines,
    /// Faces seen so far over the whole file.
    seen: usize,
    /// Bent faces split so far, and the line, corner and distance of the first.
    bent: usize,
    first_bent: Option<(usize, usize, f64)>,
}

impl FaceCheck {
    /// A check for a file whose faces are on `lines`.
    pub fn new(lines: FaceLines) -> FaceCheck {
        FaceCheck {
            lines,
            seen: 0,
            bent: 0,
            first_bent: None,
        }
    }

    /// `mesh` (the file's next part) with its concave and bent faces split into triangles;
    /// an error naming the line of a face whose edges cross. Faces with no area are kept
    /// as they are (they take and give no light).
    pub fn split(&mut self, mesh: PolygonMesh) -> Result<PolygonMesh, String> {
        let mut indices = Vec::with_capacity(mesh.indices.len());
        let mut face_sizes = Vec::with_capacity(mesh.face_sizes.len());
        let mut start = 0;
        for &size in &mesh.face_sizes {
            let face = &mesh.indices[start..start + size as usize];
            start += size as usize;
            let line = self.lines.line(self.seen);
            self.seen += 1;
            // Triangles are taken as they are: no corner list for them.
            let (corners, shape) = if face.len() > 3 {
                let corners: Vec<Vec3> = face
                    .iter()
                    .map(|&i| mesh.positions.get(i as usize).copied().unwrap_or(Vec3::NAN))
                    .collect();
                let shape = polygon::classify(&corners);
                (corners, shape)
            } else {
                (Vec::new(), Ok(Shape::Convex))
            };
            match shape {
                Ok(Shape::Convex)
                | Err(
                    PolygonError::Coincide(..)
                    | PolygonError::ZeroArea
                    | PolygonError::NotFinite(_)
                    | PolygonError::TooFew(_),
                ) => {
                    indices.extend_from_slice(face);
                    face_sizes.push(size);
                }
                Ok(shape) => {
                    if let Shape::NonPlanar {
                        corner, distance, ..
                    } = shape
                    {
                        self.bent += 1;
                        self.first_bent.get_or_insert((line, corner, distance));
                    }
                    for triangle in polygon::triangulate(&corners) {
                        indices.extend(triangle.map(|k| face[k]));
                        face_sizes.push(3);
                    }
                }
                Err(e) => return Err(format!("line {line}: face: {e}")),
            }
        }
        Ok(PolygonMesh {
            indices,
            face_sizes,
            ..mesh
        })
    }

    /// The warning about bent faces split, if any were.
    pub fn warning(&self, path: &Path) -> Option<String> {
        let (line, corner, distance) = self.first_bent?;
        Some(format!(
            "{}: {} face(s) not planar within {:.0e} of their size split into triangles (the \
             first on line {line}: its vertex {corner} is {distance:.3e} from its plane)",
            path.display(),
            self.bent,
            polygon::PLANARITY_TOLERANCE
        ))
    }
}
