//! Where light-tracing photons start: every light of a scene as a source of known power
//! (watts of the scene's radiometric units) that emits photons with the right distribution.
//!
//! Powers and emission:
//! - emissive surface: Φ = π·L·A per emitting side (emission texture mean applied); points
//!   uniform by area, directions cosine-distributed about the emitting side's normal (a
//!   random side when two-sided), each photon weighted by the (textured) radiance at its
//!   point, so textured emitters are unbiased;
//! - point light: Φ = 4π·I, isotropic;
//! - spot light: Φ = I·∫ falloff dω = 2π·I·[(1 − cos θᵢ) + (cos θᵢ − cos θₒ)/2] for the
//!   smoothstep falloff between the inner and outer cone (2π·I·(1 − cos θᵢ) when the inner
//!   cone is the wider); directions exactly distributed as the falloff (rejection sampling);
//! - directional light: Φ = E·πR², parallel photons from a disc of radius R perpendicular to
//!   the light, covering the bounding sphere (radius R) of the bounded geometry;
//! - sky of uniform radiance L: Φ = 4π²R²·L, the power entering the bounding sphere from
//!   outside (πL per unit area of the sphere's surface 4πR², or equivalently, per direction,
//!   L times the sphere's cross-section πR², over 4π sr): uniform directions, each with a
//!   uniform point on the disc across the sphere;
//! - CIE sky: Φ = πR²·∫L dω over the upper hemisphere (black below the horizon): directions
//!   drawn from the world's table of the sky's radiance (nearly in proportion to L), each
//!   photon weighted by L/(p·∫L dω) so the draw is exact, with points as for the uniform sky.
//!
//! Aimed parallel photons. Of the rays through the disc across the sphere, only those through
//! the union of the discs of a few spheres holding all bounded geometry (`sources/aim.rs`) can
//! meet anything. Directional and sky photons start from a point of that union instead (a disc
//! picked by area, a uniform point in it), each carrying the fraction (Σ disc areas)/(πR²)/m of
//! its share, m the number of discs holding the point: the expected power entering through
//! every point of the union is the uniform points', and the photons no longer go mostly past
//! everything when the geometry fills little of the sphere. Each photon is still tallied as
//! emitting its full share, the part it does not carry (rays known to meet nothing) as escaped
//! at once, so emitted = absorbed + escaped stays exact. When the spheres together are nearly
//! as large as the disc across the bounding sphere, or some geometry is unbounded, the points
//! are uniform over that disc as above.
//!
//! Unbounded shapes (infinite planes) are outside the bounding sphere's measure: they receive
//! directional and sky light only where it falls inside the sphere's shadow cylinder.
//!
//! Periodic scenes. In a plot repeated without end ([`crate::world::Field`]), directional and
//! sky light enter through the plot's top (a rectangle just above all geometry) and the sky's
//! light from below the horizon through its bottom, with the powers of
//! [`World::light_power`]: photons start at uniform points of the rectangle, directional ones
//! along the light, uniform-sky ones cosine-distributed about the vertical (a random one of
//! the two), CIE-sky ones drawn from its table and weighted by `L·cos θ` over the draw's
//! density.

mod aim;

use crate::color::Rgb;
use crate::geometry::{Frame, Ray, spawn_ray};
use crate::sampling::Sampler;
use crate::sampling::warp::{concentric_disk, cosine_hemisphere, uniform_sphere, uniform_triangle};
use crate::scene::{LightKind, Periodic};
use crate::world::{World, emitted_toward};
use aim::AimSet;
use glam::Vec3;
use std::f32::consts::PI;

/// Rejection-sampling attempts for a spot direction before falling back to the axis (each
/// attempt succeeds with probability at least ½).
const SPOT_ATTEMPTS: u32 = 64;

/// What a source is.
#[derive(Clone, Debug)]
enum SourceKind {
    /// Area light `light` of [`crate::world::LightSet::area`], triangles chosen through `cdf`.
    Surface {
        light: usize,
        cdf: Vec<f32>,
        sides: f32,
    },
    /// Isotropic point light.
    Point { position: Vec3 },
    /// Lambertian point light with its axis frame.
    Lambertian { position: Vec3, frame: Frame },
    /// Spot light with its axis frame and the widest cone cosine that can emit.
    Spot {
        position: Vec3,
        frame: Frame,
        cos_min: f32,
        inner_degrees: f32,
        outer_degrees: f32,
    },
    /// Parallel light travelling along `frame.n`.
    Directional { frame: Frame },
    /// Uniform sky radiance.
    Sky,
    /// CIE sky `index` of the world's [`crate::world::Sky::cie`].
    CieSky { index: usize },
}

/// One light as a photon source.
#[derive(Clone, Debug)]
pub struct PhotonSource {
    kind: SourceKind,
    /// Emitted power, W per channel (for textured emitters an estimate from the texture mean).
    pub power: Rgb,
}

/// A photon leaving a source.
#[derive(Clone, Copy, Debug)]
pub struct EmittedPhoton {
    /// Where it starts and where it goes (unit direction).
    pub ray: Ray,
    /// Its power if it were the only photon of its source, W per channel; divide by the
    /// number of photons the source sends.
    pub power: Rgb,
    /// The emitting surface `(object, face)`, or `None` for non-surface lights.
    pub surface: Option<(u32, u32)>,
    /// The fraction of `power` the photon carries into the scene, in [0, 1], dimensionless:
    /// below 1 for aimed directional and sky photons, whose rest is known to meet nothing
    /// (it escapes at once); 1 for every other photon.
    pub carried: f64,
    /// The unit normal of the emitting side of the surface (directions are cosine-distributed
    /// about it), or `None` for non-surface lights.
    pub normal: Option<Vec3>,
}

/// All photon sources of a scene.
#[derive(Clone, Debug)]
pub struct PhotonSources {
    /// The sources with non-zero power.
    pub sources: Vec<PhotonSource>,
    /// Centre of the bounding sphere of the bounded geometry.
    center: Vec3,
    /// Its radius (1 when there is no bounded geometry).
    radius: f32,
    /// The spheres directional and sky photons are aimed at, when aiming pays.
    aim: Option<AimSet>,
    /// In a periodic scene: the plot, and the heights (scene units) of the rectangles above
    /// and below all geometry through which directional and sky photons enter it.
    entry: Option<(Periodic, [f32; 2])>,
}

impl PhotonSources {
    /// The sources of `world`'s lights with power.
    pub fn new(world: &World) -> Self {
        Self::build(world, false)
    }

    /// The sources of all `world`'s lights, dark ones too: the same list, light for light,
    /// for every world of one geometry and the same lights in other strengths.
    pub fn all(world: &World) -> Self {
        Self::build(world, true)
    }

    fn build(world: &World, keep_dark: bool) -> Self {
        let (center, radius) = world.entry_sphere();
        let mut sources = Vec::new();
        for (index, light) in world.lights.area.iter().enumerate() {
            let mut cdf = Vec::with_capacity(light.prims.len());
            let mut sum = 0.0f32;
            for &prim in &light.prims {
                sum += world.geometry.triangle(prim).map_or(0.0, |t| t.area());
                cdf.push(sum);
            }
            cdf.iter_mut()
                .for_each(|c| *c /= sum.max(f32::MIN_POSITIVE));
            let material = world.geometry.owner(light.prims[0]).1;
            let sides = if world.scene.materials[material as usize].two_sided {
                2.0
            } else {
                1.0
            };
            sources.push(PhotonSource {
                kind: SourceKind::Surface {
                    light: index,
                    cdf,
                    sides,
                },
                power: light.power,
            });
        }
        for light in &world.lights.delta {
            let power = world.light_power(light);
            let source = match *light {
                LightKind::Point { position, .. } => PhotonSource {
                    kind: SourceKind::Point { position },
                    power,
                },
                LightKind::Lambertian {
                    position,
                    direction,
                    ..
                } => {
                    let Some(axis) = direction.try_normalize() else {
                        continue;
                    };
                    PhotonSource {
                        kind: SourceKind::Lambertian {
                            position,
                            frame: Frame::from_normal(axis),
                        },
                        power,
                    }
                }
                LightKind::Spot {
                    position,
                    direction,
                    inner_degrees,
                    outer_degrees,
                    ..
                } => {
                    let Some(axis) = direction.try_normalize() else {
                        continue;
                    };
                    let cos_min = inner_degrees
                        .max(outer_degrees)
                        .min(180.0)
                        .to_radians()
                        .cos();
                    PhotonSource {
                        kind: SourceKind::Spot {
                            position,
                            frame: Frame::from_normal(axis),
                            cos_min,
                            inner_degrees,
                            outer_degrees,
                        },
                        power,
                    }
                }
                LightKind::Directional { direction, .. } => {
                    let Some(d) = direction.try_normalize() else {
                        continue;
                    };
                    PhotonSource {
                        kind: SourceKind::Directional {
                            frame: Frame::from_normal(d),
                        },
                        power,
                    }
                }
                LightKind::Sky { .. } | LightKind::CieSky { .. } => continue,
            };
            sources.push(source);
        }
        if let Some(sky) = &world.lights.sky {
            if let Some(radiance) = sky.uniform {
                sources.push(PhotonSource {
                    kind: SourceKind::Sky,
                    power: world.light_power(&LightKind::Sky { radiance }),
                });
            }
            for (index, cie) in sky.cie.iter().enumerate() {
                sources.push(PhotonSource {
                    kind: SourceKind::CieSky { index },
                    power: world.light_power(&cie.light()),
                });
            }
        }
        if !keep_dark {
            sources.retain(|s| s.power.is_finite() && s.power.max_channel() > 0.0);
        }
        let parallel = sources.iter().any(|s| {
            matches!(
                s.kind,
                SourceKind::Directional { .. } | SourceKind::Sky | SourceKind::CieSky { .. }
            )
        });
        let entry = world.field().map(|field| {
            let period = field.plot.period();
            let margin = 1e-3 * (field.top - field.bottom).max(period.max_element());
            (field.plot, [field.bottom - margin, field.top + margin])
        });
        let aim = (parallel && entry.is_none())
            .then(|| AimSet::new(&world.geometry, (center, radius)))
            .flatten();
        PhotonSources {
            sources,
            center,
            radius,
            aim,
            entry,
        }
    }

    /// A photon from source `index`.
    pub fn emit(&self, world: &World, index: usize, sampler: &mut Sampler) -> EmittedPhoton {
        let source = &self.sources[index];
        match &source.kind {
            SourceKind::Surface { light, cdf, sides } => {
                let l = &world.lights.area[*light];
                let u_pick = sampler.next_1d();
                let i = cdf.partition_point(|&c| c <= u_pick).min(cdf.len() - 1);
                let (b1, b2) = uniform_triangle(sampler.next_2d());
                let at = world.geometry.point_on_triangle(l.prims[i], b1, b2);
                let front = *sides < 2.0 || sampler.next_1d() < 0.5;
                let n = if front { at.ng } else { -at.ng };
                let dir = Frame::from_normal(n).to_world(cosine_hemisphere(sampler.next_2d()));
                let material = &world.scene.materials[at.material as usize];
                let radiance = emitted_toward(&world.scene, material, at.uv, front);
                EmittedPhoton {
                    ray: spawn_ray(at.p, at.ng, dir),
                    power: radiance * (PI * l.area * sides),
                    surface: Some((at.object, at.face)),
                    carried: 1.0,
                    normal: Some(n),
                }
            }
            SourceKind::Point { position } => EmittedPhoton {
                ray: Ray::new(*position, uniform_sphere(sampler.next_2d())),
                power: source.power,
                surface: None,
                carried: 1.0,
                normal: None,
            },
            SourceKind::Lambertian { position, frame } => EmittedPhoton {
                ray: Ray::new(
                    *position,
                    frame.to_world(cosine_hemisphere(sampler.next_2d())),
                ),
                power: source.power,
                surface: None,
                carried: 1.0,
                normal: None,
            },
            SourceKind::Spot {
                position,
                frame,
                cos_min,
                inner_degrees,
                outer_degrees,
                ..
            } => {
                let mut local = Vec3::Z;
                for _ in 0..SPOT_ATTEMPTS {
                    let u = sampler.next_2d();
                    let cos = 1.0 - u.x * (1.0 - cos_min);
                    let falloff = LightKind::spot_falloff(cos, *inner_degrees, *outer_degrees);
                    if sampler.next_1d() < falloff {
                        let sin = (1.0 - cos * cos).max(0.0).sqrt();
                        let phi = 2.0 * PI * u.y;
                        local = Vec3::new(sin * phi.cos(), sin * phi.sin(), cos);
                        break;
                    }
                }
                EmittedPhoton {
                    ray: Ray::new(*position, frame.to_world(local)),
                    power: source.power,
                    surface: None,
                    carried: 1.0,
                    normal: None,
                }
            }
            SourceKind::Directional { frame, .. } => match self.entry {
                Some(entry) => entering_photon(entry, frame.n, source.power, sampler),
                None => self.parallel_photon(frame, source.power, sampler),
            },
            SourceKind::Sky => match self.entry {
                Some(entry) => {
                    let vertical = if sampler.next_1d() < 0.5 {
                        -Vec3::Y
                    } else {
                        Vec3::Y
                    };
                    let local = cosine_hemisphere(sampler.next_2d());
                    let dir = Frame::from_normal(vertical).to_world(local);
                    entering_photon(entry, dir, source.power, sampler)
                }
                None => {
                    let frame = Frame::from_normal(uniform_sphere(sampler.next_2d()));
                    self.parallel_photon(&frame, source.power, sampler)
                }
            },
            SourceKind::CieSky { index } => {
                let u = sampler.next_2d();
                let u = [f64::from(u.x), f64::from(u.y)];
                let sky = world.lights.sky.as_ref().and_then(|s| s.cie.get(*index));
                if let Some(entry) = self.entry {
                    let arrival = sky.and_then(|s| s.sample_arrival_horizontal(u));
                    let (toward, weight) = arrival.unwrap_or((glam::DVec3::Y, 0.0));
                    let power = source.power * weight as f32;
                    return entering_photon(entry, -toward.as_vec3(), power, sampler);
                }
                let arrival = sky.and_then(|s| s.sample_arrival(u));
                // A black sky has no sources; the zenith with no power stands in regardless.
                let (toward, weight) = arrival.unwrap_or((glam::DVec3::Y, 0.0));
                let frame = Frame::from_normal(-toward.as_vec3());
                self.parallel_photon(&frame, source.power * weight as f32, sampler)
            }
        }
    }

    /// A photon of `power` travelling along `frame.n`, entering the bounding sphere through
    /// a point of its cross-section: uniform over the whole cross-section, or aimed at what
    /// it can meet (carrying the corresponding fraction of its share).
    fn parallel_photon(&self, frame: &Frame, power: Rgb, sampler: &mut Sampler) -> EmittedPhoton {
        let (offset, carried) = match &self.aim {
            Some(aim) => {
                let point = aim.sample(frame, sampler);
                (point.offset, point.carried)
            }
            None => (concentric_disk(sampler.next_2d()) * self.radius, 1.0),
        };
        let origin =
            self.center + frame.s * offset.x + frame.t * offset.y - frame.n * (2.0 * self.radius);
        EmittedPhoton {
            ray: Ray::new(origin, frame.n),
            power,
            surface: None,
            carried,
            normal: None,
        }
    }
}

/// A photon of `power` travelling along the unit `dir`, entering a periodic plot at a
/// uniform point of its top (going down) or bottom (going up); `entry` is the plot and the
/// bottom's and top's heights.
fn entering_photon(
    (plot, [bottom, top]): (Periodic, [f32; 2]),
    dir: Vec3,
    power: Rgb,
    sampler: &mut Sampler,
) -> EmittedPhoton {
    let y = if dir.y < 0.0 { top } else { bottom };
    EmittedPhoton {
        ray: Ray::new(plot.point(sampler.next_2d(), y), dir),
        power,
        surface: None,
        carried: 1.0,
        normal: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spot_solid_angle_matches_quadrature_of_the_falloff() {
        for (inner, outer) in [(20.0, 40.0), (10.0, 10.0), (30.0, 15.0), (60.0, 120.0)] {
            let steps = 200_000;
            let mut sum = 0.0f64;
            for i in 0..steps {
                let cos = -1.0 + 2.0 * (i as f64 + 0.5) / steps as f64;
                sum += LightKind::spot_falloff(cos as f32, inner, outer) as f64;
            }
            let quadrature = 2.0 * std::f64::consts::PI * sum * 2.0 / steps as f64;
            let formula = LightKind::spot_solid_angle(inner, outer) as f64;
            assert!(
                (quadrature - formula).abs() < 1e-4 * formula.max(1.0),
                "{inner}/{outer}: {quadrature} vs {formula}"
            );
        }
    }
}
