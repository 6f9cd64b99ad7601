//! Patches as triangles under an accelerator: what rays meet when they look for patches
//! rather than the scene's own primitives (the display's and the final gather's leaves, the
//! near and far fields' patches), where a ray meets them in the endless field of a periodic
//! plot ([`hit_in_field`]), and the rays the near and far fields cast from patches
//! ([`side_ray`]).

use crate::accel::{Accelerator, PrimHit, PrimitiveSet};
use crate::geometry::{Aabb, Frame, Ray, Triangle, spawn_ray};
use crate::radiosity::element::Side;
use crate::radiosity::mesh::{Patch, PatchId, PatchMesh};
use crate::sampling::warp::cosine_hemisphere;
use crate::world::World;
use glam::Vec2;

/// How far before and beyond the point a ray meets in the endless field the patches are
/// searched for it, as a share of the plot's longer period: the point lies on the plot's
/// surfaces, the patches on them or (curved shapes) on facets that pass a little inside and
/// a little outside the surface (meshed as large as it is). With the search starting only
/// just before the point, a sphere's facets were missed where they bulge out, and the
/// radiosity image of a field of spheres showed a black spot on every facet.
const SEARCH: f32 = 1e-2;

/// Times a ray that meets a curved surface where no facet is (past a facet's outline, near a
/// silhouette) goes on through the endless field, at most.
const PASSES: usize = 8;

/// Where `ray` first meets the endless field of the periodic world `plot` (`None` where it
/// meets nothing, or the world is not periodic): the triangle of `triangles` (patches of
/// the plot and of copies of it that reach into it, on its surfaces) at the point met, with
/// `t` the distance along `ray`. The periodic world finds the point (in the plot, or on a
/// copy that reaches into it); the patches under it are searched for along the ray's last
/// stretch. Where none is there, or only one facing the other way (a curved surface met
/// outside its facets' outline), the ray goes on past the point and past where it leaves
/// the surface again, as it would past the facets.
pub(crate) fn hit_in_field(
    plot: &World,
    triangles: &PatchTriangles,
    accel: &dyn Accelerator<PatchTriangles>,
    ray: &Ray,
) -> Option<PrimHit> {
    let period = plot.field()?.plot.period().max_element();
    let reach = SEARCH * period;
    let (mut ray, mut travelled) = (*ray, 0.0);
    // After a curved surface met outside its facets, the point where the ray leaves it again
    // is passed too: inside it there is no facet to meet.
    let mut inside = false;
    for _ in 0..PASSES {
        let far = plot.intersect(&ray)?;
        let leaving = far.ng.dot(ray.dir) > 0.0;
        if !(inside && leaving) {
            // Never from behind the ray's origin, where the surface it leaves lies.
            let before = reach.min(0.5 * far.t);
            let search = Ray::new(far.p - ray.dir * before, ray.dir);
            // The patch met from the side the surface is (a ray that passes just inside a
            // curved surface's rim would meet its far facets from behind).
            let facing = |hit: &PrimHit| {
                let normal = triangles.triangles[hit.prim as usize].normal_area2();
                (normal.dot(ray.dir) > 0.0) == leaving
            };
            if let Some(mut hit) = accel
                .closest_hit(triangles, &search, before + reach)
                .filter(facing)
            {
                hit.t += travelled + far.t - before;
                return Some(hit);
            }
        }
        inside = !leaving;
        travelled += far.t + reach;
        ray = Ray::new(ray.origin + ray.dir * (far.t + reach), ray.dir);
    }
    None
}

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

/// The `k`-th of the `2·per_side` cosine-distributed rays of the patch at place `place` of a
/// list (the first half from its front): direction and origin from one 4-D point, the
/// origins spread over the whole patch (leaving its rim out would favour what its middle
/// sees).
pub(crate) fn side_ray(patch: &Patch, place: usize, k: u32, per_side: u32) -> Ray {
    let side = Side::BOTH[(k / per_side) as usize];
    let normal = side.normal(patch).as_vec3();
    let seed = (place as u32).wrapping_mul(2) + side.index() as u32;
    let [ux, uy, us, ut] = sobol_burley::sample_4d(k % per_side, 0, seed);
    let dir = Frame::from_normal(normal).to_world(cosine_hemisphere(Vec2::new(ux, uy)));
    let origin = patch.point_at(f64::from(us), f64::from(ut)).as_vec3();
    spawn_ray(origin, normal, dir)
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
