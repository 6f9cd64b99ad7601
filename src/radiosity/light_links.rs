//! Emitter-only links (seed 000 §9.3.1): the irradiance that point (isotropic or
//! Lambertian), spot and directional lights and the sky send to one side of a patch. These
//! lights only send; nothing is sent back to them.
//!
//! The irradiance (W·m⁻²) is the mean over the patch side:
//! - point and spot lights: `I·Ω/A` times the visible, falloff-weighted share of the patch,
//!   where `Ω` is the exact solid angle the patch subtends at the light (so a patch much
//!   larger than its distance to the light gets its full power, however few receiver points
//!   are used) and the share is estimated at the receiver points, each weighted by the solid
//!   angle its area subtends (`cos θ / d²`);
//! - directional light: `E·cos θ` times the patch's lit share, cut out exactly wherever the
//!   world allows ([`exact_directional_arrival`], [`exact_shadows`]), else the share of
//!   receiver points that see it;
//! - sky of uniform radiance `L`: `π·L` times the cosine-weighted share of directions that
//!   reach the sky, from stratified directions at every receiver point (fewer per point the
//!   more points there are: about 64 rays per patch side);
//! - CIE sky: the irradiance the unoccluded sky sends onto the patch's orientation (a fine
//!   quadrature of its radiance) times the share of the same directions that reach the sky,
//!   each weighted by the sky's radiance ([`crate::world::sky_irradiance`]).

use super::element::Side;
use super::form_factor::receiver_points;
use super::mesh::Patch;
use super::visibility::Visibility;
use crate::color::Rgb64;
use crate::geometry::angle::upper_angle;
use crate::scene::LightKind;
use crate::world::{ParallelShadows, World, sees_light, sky_irradiance};
use glam::DVec3;

/// Sky directions per axis at each receiver point of a patch (`n × n` cosine-weighted strata).
pub const SKY_DIRECTIONS_PER_AXIS: u32 = 4;

/// What a light sends to a patch ([`light_arrival`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightArrival {
    /// Irradiance averaged over the patch, W·m⁻².
    pub irradiance: Rgb64,
    /// Whether a shadow edge crosses the patch: some of its receiver points see the light
    /// and some do not (never set for the sky, whose share varies without an edge).
    pub partly_shadowed: bool,
    /// The irradiance the patch would receive without shadows, W·m⁻² (the sky's: what
    /// arrives).
    pub unshadowed: Rgb64,
}

impl LightArrival {
    /// Nothing arrives.
    const NONE: LightArrival = LightArrival {
        irradiance: Rgb64::BLACK,
        partly_shadowed: false,
        unshadowed: Rgb64::BLACK,
    };
}

/// Irradiance in W·m⁻² that `light` sends to side `side` of `patch`, averaged over the patch,
/// with shadows from every surface of `world`: exactly where `exact`, the light's shadows,
/// can tell (`exact_directional_arrival` in this module), else estimated at
/// `samples × samples` receiver points (what `light_arrival` in this module measures,
/// without telling whether a shadow edge crosses the patch).
pub fn light_irradiance(
    world: &World,
    (light, exact): (&LightKind, Option<&ParallelShadows>),
    patch: &Patch,
    side: Side,
    samples: u32,
) -> Rgb64 {
    exact
        .and_then(|shadows| exact_directional_arrival(shadows, light, patch, side))
        .unwrap_or_else(|| light_arrival(world, light, patch, side, samples))
        .irradiance
}

/// How far the boundary points of [`shadow_at_edges`] are pulled towards the centroid (a
/// share of the way), so that a point on an edge shared with a neighbour is not shadowed by
/// it.
const BOUNDARY_INSET: f64 = 1e-2;

/// What `light` sends to side `side` of `patch`, with shadows from every surface of `world`
/// (for patches of curved shapes, the world of [`super::Visibility::world`], whose surfaces
/// they lie on); the visible share is estimated at `samples × samples` receiver points (the
/// centroid for `samples ≤ 1`). A sky gives what [`sky_irradiance`] estimates.
pub fn light_arrival(
    world: &World,
    light: &LightKind,
    patch: &Patch,
    side: Side,
    samples: u32,
) -> LightArrival {
    let normal = side.normal(patch);
    let points = receiver_points(patch, samples);
    match *light {
        LightKind::Sky { .. } | LightKind::CieSky { .. } => {
            // About the same rays whatever the points: 4 × 4 directions at each of 2 × 2
            // points, one at each of 8 × 8.
            let per_axis = (SKY_DIRECTIONS_PER_AXIS * 2 / samples.max(1)).max(1);
            let irradiance = sky_irradiance(world, light, &points, normal, per_axis);
            LightArrival {
                irradiance,
                partly_shadowed: false,
                unshadowed: irradiance,
            }
        }
        LightKind::Directional { direction, .. } => {
            let Some(inc) = light.incidence(patch.centroid.as_vec3()) else {
                return LightArrival::NONE;
            };
            let cos = normal.dot(-direction.as_dvec3().normalize_or_zero());
            if cos <= 0.0 {
                return LightArrival::NONE;
            }
            let (mut seen, mut hidden) = (0.0, false);
            for &(x, w) in &points {
                if sees_light(world, x, normal, light) {
                    seen += w;
                } else {
                    hidden = true;
                }
            }
            let unshadowed = inc.irradiance.to_f64() * cos;
            LightArrival {
                irradiance: unshadowed * seen,
                partly_shadowed: hidden && seen > 0.0,
                unshadowed,
            }
        }
        LightKind::Point {
            position,
            intensity,
        }
        | LightKind::Lambertian {
            position,
            intensity,
            ..
        }
        | LightKind::Spot {
            position,
            intensity,
            ..
        } => {
            let at = position.as_dvec3();
            if normal.dot(at - patch.centroid) <= 0.0 {
                return LightArrival::NONE;
            }
            let (mut weighted, mut total, mut reaching) = (0.0, 0.0, 0.0);
            let (mut lit, mut hidden) = (false, false);
            for &(x, w) in &points {
                let d = at - x;
                let d2 = d.length_squared();
                if d2 <= 0.0 {
                    continue;
                }
                let solid_angle = w * normal.dot(d).max(0.0) / (d2 * d2.sqrt());
                total += solid_angle;
                let falloff = falloff(light, x);
                reaching += solid_angle * falloff;
                if falloff > 0.0 {
                    if sees_light(world, x, normal, light) {
                        weighted += solid_angle * falloff;
                        lit = true;
                    } else {
                        hidden = true;
                    }
                }
            }
            if total <= 0.0 {
                return LightArrival::NONE;
            }
            let per_weight =
                intensity.to_f64() * (solid_angle(at, patch.corners()) / patch.area / total);
            LightArrival {
                irradiance: per_weight * weighted,
                partly_shadowed: lit && hidden,
                unshadowed: per_weight * reaching,
            }
        }
    }
}

/// Per light of `world`'s scene, the shadows of a directional light cut out exactly in the
/// world the light links' rays would be traced in (`visibility`'s, over the endless field for
/// a periodic plot); `None` for the other lights and where that world holds what cannot be
/// projected ([`ParallelShadows::new`]).
pub fn exact_shadows(world: &World, visibility: &Visibility) -> Vec<Option<ParallelShadows>> {
    let shadows = visibility.world().plot_world();
    (world.scene.lights.iter())
        .map(|light| match light.kind {
            LightKind::Directional { direction, .. } => {
                ParallelShadows::new(shadows, direction.as_dvec3())
            }
            _ => None,
        })
        .collect()
}

/// What the directional `light` sends to side `side` of `patch`, exactly: its lit share cut
/// out of the patch by `shadows`, that light's shadows ([`ParallelShadows::lit_share_of`]),
/// partly shadowed when the share lies strictly between [`LIT_SNAP`] and `1 − LIT_SNAP`.
/// `None` for a light that is not directional, or a patch under too many shadows to cut
/// out: rays must tell then ([`light_arrival`]).
pub fn exact_directional_arrival(
    shadows: &ParallelShadows,
    light: &LightKind,
    patch: &Patch,
    side: Side,
) -> Option<LightArrival> {
    let LightKind::Directional {
        direction,
        irradiance,
    } = *light
    else {
        return None;
    };
    let cos = side
        .normal(patch)
        .dot(-direction.as_dvec3().normalize_or_zero());
    if cos <= 0.0 {
        return Some(LightArrival::NONE);
    }
    let share = shadows.lit_share_of(patch.corners())?;
    let share = if share < LIT_SNAP {
        0.0
    } else if share > 1.0 - LIT_SNAP {
        1.0
    } else {
        share
    };
    let unshadowed = irradiance.to_f64() * cos;
    Some(LightArrival {
        irradiance: unshadowed * share,
        partly_shadowed: share > 0.0 && share < 1.0,
        unshadowed,
    })
}

/// Lit shares this close to 0 or 1 count as 0 or 1: rounding, not a shadow worth refining a
/// patch for.
pub const LIT_SNAP: f64 = 1e-7;

/// True when `light` is hidden from a corner or the middle of an edge of side `side` of
/// `patch` (pulled in by [`BOUNDARY_INSET`] of the way to the centroid): a shadow that covers
/// a sliver along an edge lies between the rows of the receiver points of [`light_arrival`]
/// (`canopy:300`: a leaf 1.5 % in another's shadow read fully lit at 8 × 8 points). Never
/// for the sky, whose share varies without an edge.
pub fn shadow_at_edges(world: &World, light: &LightKind, patch: &Patch, side: Side) -> bool {
    if light.is_sky() {
        return false;
    }
    let normal = side.normal(patch);
    let corners = patch.corners();
    let n = corners.len();
    let inset = |x: DVec3| x + (patch.centroid - x) * BOUNDARY_INSET;
    (0..n)
        .flat_map(|k| [corners[k], 0.5 * (corners[k] + corners[(k + 1) % n])])
        .any(|x| falloff(light, x) > 0.0 && !sees_light(world, inset(x), normal, light))
}

/// The share of the intensity that `light` sends toward `x`: the spot falloff, the cosine
/// for a Lambertian light, 1 for a point light (and for the lights that send no intensity
/// from a point: directional light and skies).
fn falloff(light: &LightKind, x: DVec3) -> f64 {
    match *light {
        LightKind::Lambertian {
            position,
            direction,
            ..
        } => {
            let toward = (x - position.as_dvec3()).normalize_or_zero();
            toward.dot(direction.as_dvec3()).max(0.0)
        }
        LightKind::Spot {
            position,
            direction,
            inner_degrees,
            outer_degrees,
            ..
        } => {
            let toward = (x - position.as_dvec3()).normalize_or_zero();
            let cos = toward.dot(direction.as_dvec3().normalize_or_zero());
            LightKind::spot_falloff(cos as f32, inner_degrees, outer_degrees) as f64
        }
        LightKind::Point { .. }
        | LightKind::Directional { .. }
        | LightKind::Sky { .. }
        | LightKind::CieSky { .. } => 1.0,
    }
}

/// The solid angle (sr) that the convex planar polygon `corners` subtends at `point`: the
/// sum over a fan of triangles of Van Oosterom and Strackee's formula
/// `tan(Ω/2) = |a·(b×c)| / (abc + (a·b)c + (a·c)b + (b·c)a)`.
pub fn solid_angle(point: DVec3, corners: &[DVec3]) -> f64 {
    let mut total = 0.0;
    let a = corners[0] - point;
    for k in 1..corners.len() - 1 {
        let (b, c) = (corners[k] - point, corners[k + 1] - point);
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let numerator = a.dot(b.cross(c)).abs();
        let denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
        total += 2.0 * upper_angle(numerator, denominator);
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::AccelKind;
    use crate::color::Rgb;
    use crate::radiosity::mesh::{MeshOptions, PatchMesh};
    use crate::scene::{Material, Scene, Shape};
    use glam::Vec3;
    use std::f64::consts::PI;

    fn floor_world(with_roof: bool) -> (World, PatchMesh) {
        let mut scene = Scene::empty("floor");
        let m = scene.add_material(Material::default());
        scene.add_object(
            "floor",
            Shape::Parallelogram {
                origin: Vec3::ZERO,
                edge_u: Vec3::Z,
                edge_v: Vec3::X,
            },
            m,
        );
        if with_roof {
            scene.add_object(
                "roof",
                Shape::Parallelogram {
                    origin: Vec3::new(-5.0, 1.0, -5.0),
                    edge_u: Vec3::X * 10.0,
                    edge_v: Vec3::Z * 10.0,
                },
                m,
            );
        }
        let mesh = PatchMesh::from_scene(&scene, &MeshOptions::default()).unwrap();
        (World::new(scene, AccelKind::Bvh).unwrap(), mesh)
    }

    #[test]
    fn point_light_far_away_gives_intensity_cos_over_distance_squared() {
        let (world, mesh) = floor_world(false);
        let floor = mesh.patch(0);
        assert!(floor.normal.y > 0.99);
        // Far light: the irradiance barely varies over the unit patch, I·cosθ/d² at the
        // centroid (0.5, 0, 0.5) with the light 200 above and 200 to the side.
        let light = LightKind::Point {
            position: Vec3::new(200.5, 200.0, 0.5),
            intensity: Rgb::splat(8.0),
        };
        let e = light_irradiance(&world, (&light, None), floor, Side::Front, 1);
        let expected = 8.0 * std::f64::consts::FRAC_1_SQRT_2 / 80_000.0;
        assert!((e.r / expected - 1.0).abs() < 1e-4, "{e:?} vs {expected}");
        let below = LightKind::Point {
            position: Vec3::new(0.5, -1.0, 0.5),
            intensity: Rgb::splat(8.0),
        };
        assert_eq!(
            light_irradiance(&world, (&below, None), floor, Side::Front, 2),
            Rgb64::BLACK
        );
        // The back of the floor sees the light below it: the full I·Ω/A, Ω the exact solid
        // angle of the unit square.
        let back = light_irradiance(&world, (&below, None), floor, Side::Back, 2);
        let omega = solid_angle(DVec3::new(0.5, -1.0, 0.5), floor.corners());
        assert!((back.g - 8.0 * omega).abs() < 1e-12, "{back:?}");
    }

    #[test]
    fn a_huge_floor_gets_the_whole_half_of_a_point_light() {
        // A point light 1 above a 2000 × 2000 floor sends almost 2π·I into it, however
        // coarse the receiver sampling.
        let mut scene = Scene::empty("plain");
        let m = scene.add_material(Material::default());
        let s = 1000.0;
        scene.add_object(
            "floor",
            Shape::Parallelogram {
                origin: Vec3::new(-s, 0.0, s),
                edge_u: Vec3::X * (2.0 * s),
                edge_v: Vec3::NEG_Z * (2.0 * s),
            },
            m,
        );
        let mesh = PatchMesh::from_scene(&scene, &MeshOptions::default()).unwrap();
        let world = World::new(scene, AccelKind::Bvh).unwrap();
        let light = LightKind::Point {
            position: Vec3::new(0.0, 1.0, 0.0),
            intensity: Rgb::splat(1.0),
        };
        let floor = mesh.patch(0);
        let power = light_irradiance(&world, (&light, None), floor, Side::Front, 2).r * floor.area;
        let half = 2.0 * PI;
        assert!(power < half && power > 0.999 * half, "{power} vs {half}");
    }

    #[test]
    fn solid_angle_of_a_hemisphere_cap_and_a_cube_face() {
        // A cube face seen from the cube's centre: 4π/6.
        let face = [
            DVec3::new(-1.0, -1.0, 1.0),
            DVec3::new(1.0, -1.0, 1.0),
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(-1.0, 1.0, 1.0),
        ];
        let omega = solid_angle(DVec3::ZERO, &face);
        assert!((omega - 4.0 * PI / 6.0).abs() < 1e-12, "{omega}");
    }

    #[test]
    fn directional_light_is_shadowed_by_a_roof() {
        let sun = LightKind::Directional {
            direction: Vec3::new(0.0, -1.0, -1.0).normalize(),
            irradiance: Rgb::splat(2.0),
        };
        let LightKind::Directional { direction, .. } = sun else {
            unreachable!()
        };
        // By rays at receiver points, and with the roof's shadow cut out exactly.
        let (open, mesh) = floor_world(false);
        let exact = ParallelShadows::new(&open, direction.as_dvec3());
        for exact in [None, exact.as_ref()] {
            let e = light_irradiance(&open, (&sun, exact), mesh.patch(0), Side::Front, 2);
            assert!((e.g - 2.0 * std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-6);
        }
        let (roofed, mesh) = floor_world(true);
        let exact = ParallelShadows::new(&roofed, direction.as_dvec3());
        assert!(exact.is_some());
        for exact in [None, exact.as_ref()] {
            assert_eq!(
                light_irradiance(&roofed, (&sun, exact), mesh.patch(0), Side::Front, 2),
                Rgb64::BLACK
            );
        }
    }

    #[test]
    fn spot_light_outside_its_cone_sends_nothing() {
        let (world, mesh) = floor_world(false);
        let spot = |direction: Vec3| LightKind::Spot {
            position: Vec3::new(0.5, 1.0, 0.5),
            direction,
            intensity: Rgb::splat(1.0),
            inner_degrees: 10.0,
            outer_degrees: 20.0,
        };
        // Straight down the falloff is 1 near the centre: I·Ω/A times the share inside the
        // cone (only the centroid is sampled).
        let down = light_irradiance(
            &world,
            (&spot(-Vec3::Y), None),
            mesh.patch(0),
            Side::Front,
            1,
        );
        let omega = solid_angle(DVec3::new(0.5, 1.0, 0.5), mesh.patch(0).corners());
        assert!((down.b - omega).abs() < 1e-9, "{down:?} vs {omega}");
        let sideways = light_irradiance(
            &world,
            (&spot(Vec3::X), None),
            mesh.patch(0),
            Side::Front,
            1,
        );
        assert_eq!(sideways, Rgb64::BLACK);
    }

    #[test]
    fn an_open_sky_gives_pi_radiance_and_a_roof_takes_it() {
        let sky = LightKind::Sky {
            radiance: Rgb::splat(1.0),
        };
        let (open, mesh) = floor_world(false);
        let e = light_irradiance(&open, (&sky, None), mesh.patch(0), Side::Front, 2);
        assert!((e.r - PI).abs() < 1e-12, "{e:?}");
        let (roofed, mesh) = floor_world(true);
        let shaded = light_irradiance(&roofed, (&sky, None), mesh.patch(0), Side::Front, 2);
        assert!(shaded.r < 0.5, "{shaded:?}");
    }
}
