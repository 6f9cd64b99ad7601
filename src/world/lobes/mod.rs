//! The lobes a material scatters by ([`Lobe`]), one file each: the Lambertian lobe
//! (`lambert.rs`), diffuse transmission (`translucent.rs`), the normalised Phong lobe
//! (`phong.rs`), the ideal mirror (`mirror.rs`) and the smooth dielectric (`dielectric.rs`).
//! What every algorithm asks of a lobe is here, dispatched by an exhaustive `match`: its value
//! and density (path tracer, final gather, light sampling), a sampled direction (path tracer),
//! a photon's direction (light model), and the deterministic branches of a delta lobe (the
//! standard ray tracer). Adding a lobe adds its file, a variant of [`Lobe`] with the material's
//! weight for it, and the arms the compiler asks for here.

mod dielectric;
mod lambert;
mod mirror;
mod phong;
mod translucent;

pub use crate::scene::Lobe;

use super::SurfaceMaterial;
use crate::color::Rgb;
use crate::sampling::Sampler;
use glam::{Vec2, Vec3};

/// The local view at a surface point that scattering needs.
#[derive(Clone, Copy, Debug)]
pub struct LocalView {
    /// Unit shading normal turned toward the viewer.
    pub n: Vec3,
    /// Unit geometric normal turned toward the viewer.
    pub ng: Vec3,
    /// Unit direction toward the viewer (or back along the arriving photon).
    pub wo: Vec3,
    /// Whether the viewer is on the material's front side (decides the refraction indices).
    pub front_face: bool,
}

impl Lobe {
    /// The lobe's weight in `m` (its texture applied).
    #[inline]
    pub fn weight(self, m: &SurfaceMaterial) -> Rgb {
        match self {
            Lobe::Lambert => m.diffuse,
            Lobe::Translucent => m.translucency,
            Lobe::Phong => m.specular,
            Lobe::Mirror => m.mirror,
            Lobe::Dielectric => m.transmission,
        }
    }

    /// The lobe's part of the scattering function `f(wo, wi)` (1/sr) of `m`, weight
    /// included, for unit `wo` on the side of the unit normal `n` and unit `wi` on the side
    /// the lobe scatters to (the same side, or behind the surface for a lobe that
    /// [`transmits`](Lobe::transmits)); black for delta lobes.
    #[inline]
    pub fn eval(self, m: &SurfaceMaterial, n: Vec3, wo: Vec3, wi: Vec3) -> Rgb {
        match self {
            Lobe::Lambert => lambert::eval(m.diffuse),
            Lobe::Translucent => lambert::eval(m.translucency),
            Lobe::Phong => m.specular * phong::lobe(n, wo, wi, m.shininess),
            Lobe::Mirror | Lobe::Dielectric => Rgb::BLACK,
        }
    }

    /// Density (1/sr) with which [`Lobe::sample`] gives `wi`; 0 for delta lobes.
    #[inline]
    pub fn pdf(self, m: &SurfaceMaterial, n: Vec3, wo: Vec3, wi: Vec3) -> f32 {
        match self {
            Lobe::Lambert => lambert::pdf(n.dot(wi)),
            Lobe::Translucent => translucent::pdf(n.dot(wi)),
            Lobe::Phong => phong::pdf(mirror::direction(n, wo).dot(wi), m.shininess),
            Lobe::Mirror | Lobe::Dielectric => 0.0,
        }
    }

    /// True when `f·|cos θ| / pdf` of the lobe alone is its weight exactly (Lambert and
    /// translucent), so a sampler that chose it alone needs no division.
    #[inline]
    pub fn samples_its_weight(self) -> bool {
        match self {
            Lobe::Lambert | Lobe::Translucent => true,
            Lobe::Phong | Lobe::Mirror | Lobe::Dielectric => false,
        }
    }

    /// A direction of the lobe at `view` from the uniform point `u`, and the factor its
    /// weight carries besides (the dielectric's `η²` for refracted radiance, else 1). `u_choice`
    /// is a further uniform number, used by the dielectric to choose reflection or
    /// refraction. The direction may leave on the wrong side; the caller tests it.
    #[inline]
    pub fn sample(
        self,
        m: &SurfaceMaterial,
        view: &LocalView,
        u: Vec2,
        u_choice: f32,
    ) -> (Vec3, f32) {
        let LocalView { n, wo, .. } = *view;
        match self {
            Lobe::Lambert => (lambert::sample(n, u), 1.0),
            Lobe::Translucent => (translucent::sample(n, u), 1.0),
            Lobe::Phong => (phong::sample(n, wo, m.shininess, u), 1.0),
            Lobe::Mirror => (mirror::direction(n, wo), 1.0),
            Lobe::Dielectric => {
                let eta = dielectric::relative_index(view.front_face, m.ior);
                match dielectric::choose(n, wo, eta, u_choice) {
                    // Radiance is compressed into the smaller solid angle of the denser
                    // medium.
                    (t, true) => (t, eta * eta),
                    (r, false) => (r, 1.0),
                }
            }
        }
    }

    /// A photon's direction from the lobe at `view` (`wo` back along the photon) from the
    /// uniform point `u`, and the factor its power carries besides the lobe weight (the
    /// Phong lobe's `(s+2)/(s+1)·cos θ`, else 1); `None` when the lobe sends it below the
    /// surface. Diffuse photons leave about the geometric normal (behind the surface for the
    /// translucent lobe); the dielectric draws one
    /// more number from `sampler` to choose reflection or refraction.
    #[inline]
    pub fn sample_photon(
        self,
        m: &SurfaceMaterial,
        view: &LocalView,
        u: Vec2,
        sampler: &mut Sampler,
    ) -> Option<(Vec3, f32)> {
        let LocalView { n, ng, wo, .. } = *view;
        match self {
            Lobe::Lambert => Some((lambert::sample_photon(ng, u), 1.0)),
            Lobe::Translucent => Some((translucent::sample_photon(ng, u), 1.0)),
            Lobe::Phong => phong::sample_photon(n, wo, m.shininess, u),
            Lobe::Mirror => Some((mirror::direction(n, wo), 1.0)),
            Lobe::Dielectric => {
                let eta = dielectric::relative_index(view.front_face, m.ior);
                Some((dielectric::choose(n, wo, eta, sampler.next_1d()).0, 1.0))
            }
        }
    }

    /// True for the lobes that pass light through the surface (translucent and dielectric).
    #[inline]
    pub fn transmits(self) -> bool {
        match self {
            Lobe::Translucent | Lobe::Dielectric => true,
            Lobe::Lambert | Lobe::Phong | Lobe::Mirror => false,
        }
    }

    /// The directions a delta lobe sends the light arriving from `view` into, each with its
    /// weight (the standard ray tracer follows them all); none for lobes with a density.
    #[inline]
    pub fn branches(self, m: &SurfaceMaterial, view: &LocalView) -> [Option<(Vec3, Rgb)>; 2] {
        let LocalView { n, wo, .. } = *view;
        match self {
            Lobe::Lambert | Lobe::Translucent | Lobe::Phong => [None, None],
            Lobe::Mirror => [Some((mirror::direction(n, wo), m.mirror)), None],
            Lobe::Dielectric => {
                let eta = dielectric::relative_index(view.front_face, m.ior);
                let (reflected, fresnel, refracted) = dielectric::branches(n, wo, eta);
                match refracted {
                    Some(t) => [
                        Some((reflected, m.transmission * fresnel)),
                        Some((t, m.transmission * (1.0 - fresnel))),
                    ],
                    None => [Some((reflected, m.transmission)), None],
                }
            }
        }
    }
}
