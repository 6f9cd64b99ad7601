//! Patches as triangles under an accelerator: what rays meet when they look for patches
//! rather than the scene's own primitives (the display's and the final gather's leaves, the
//! near field's root patches).

use crate::accel::{PrimHit, PrimitiveSet};
use crate::geometry::{Aabb, Ray, Triangle};
use crate::radiosity::mesh::{PatchId, PatchMesh};

/// A list of patches as triangles: quads as the two triangles (0,1,2) and (0,2,3).
pub(crate) struct PatchTriangles {
    /// The triangles, scene units.
    pub triangles: Vec<Triangle>,
    /// Per triangle: the index of its patch in the list it was made from, and the patch's
    /// corner indices of its vertices.
    pub owners: Vec<(u32, [u8; 3])>,
}

impl PatchTriangles {
    /// The triangles of `patches` of `mesh`.
    pub fn new(mesh: &PatchMesh, patches: &[PatchId]) -> Self {
        let mut triangles = Vec::new();
        let mut owners = Vec::new();
        for (k, &patch) in patches.iter().enumerate() {
            let c = mesh.patch(patch).corners();
            let splits: &[[u8; 3]] = if c.len() == 3 {
                &[[0, 1, 2]]
            } else {
                &[[0, 1, 2], [0, 2, 3]]
            };
            for &s in splits {
                let v = s.map(|i| c[i as usize].as_vec3());
                triangles.push(Triangle::new(v[0], v[1], v[2]));
                owners.push((k as u32, s));
            }
        }
        PatchTriangles { triangles, owners }
    }
}

impl PrimitiveSet for PatchTriangles {
    fn len(&self) -> usize {
        self.triangles.len()
    }

    fn bounds(&self, prim: u32) -> Aabb {
        Aabb::from_points(self.triangles[prim as usize].vertices())
    }

    fn intersect(&self, prim: u32, ray: &Ray, t_max: f32) -> Option<PrimHit> {
        self.triangles[prim as usize]
            .intersect(ray, t_max)
            .map(|(t, b1, b2)| PrimHit {
                t,
                prim,
                local: [b1, b2],
                part: 0,
            })
    }
}
