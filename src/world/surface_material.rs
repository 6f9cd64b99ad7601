//! Materials evaluated at a surface point: textures applied, emission, and the reflection
//! function of the lobes with a density beside the weights of the delta lobes.

use super::SurfaceHit;
use crate::color::Rgb;
use crate::scene::{Lobe, Material, Scene};
use glam::Vec3;

/// A material at one surface point, with textures applied.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceMaterial {
    /// Diffuse reflectance ρ.
    pub diffuse: Rgb,
    /// Diffuse transmittance τ (black for a one-sided material).
    pub translucency: Rgb,
    /// Phong lobe weight.
    pub specular: Rgb,
    /// Phong exponent.
    pub shininess: f32,
    /// Ideal mirror reflectance.
    pub mirror: Rgb,
    /// Ideal refraction weight.
    pub transmission: Rgb,
    /// Index of refraction behind the front face.
    pub ior: f32,
    /// The back face absorbs everything.
    pub one_sided: bool,
}

impl SurfaceMaterial {
    /// The material of `hit`, textures applied.
    #[inline]
    pub fn at(scene: &Scene, hit: &SurfaceHit) -> Self {
        let m = &scene.materials[hit.material as usize];
        let diffuse = match m.diffuse_texture {
            Some(t) => m.diffuse * scene.textures[t as usize].color(hit.uv),
            None => m.diffuse,
        };
        SurfaceMaterial {
            diffuse,
            // A one-sided material's back absorbs everything: nothing passes through.
            translucency: if m.one_sided {
                Rgb::BLACK
            } else {
                m.translucency
            },
            specular: m.specular,
            shininess: m.shininess,
            mirror: m.mirror,
            transmission: m.transmission,
            ior: m.ior,
            one_sided: m.one_sided,
        }
    }

    /// True when the hit side reflects nothing (back of a one-sided material).
    #[inline]
    pub fn is_black_from(&self, front_face: bool) -> bool {
        self.one_sided && !front_face
    }

    /// True when the material scatters by its Lambert lobe alone.
    #[inline]
    pub fn is_lambertian(&self) -> bool {
        Lobe::ALL
            .iter()
            .all(|&lobe| lobe == Lobe::Lambert || lobe.weight(self).is_black())
    }

    /// True when a lobe with a density has weight (light sampling can reach the surface).
    #[inline]
    pub fn has_density(&self) -> bool {
        Lobe::ALL
            .iter()
            .any(|&lobe| !lobe.is_delta() && !lobe.weight(self).is_black())
    }

    /// True when light passes diffusely through the surface (a translucent lobe with
    /// weight): light from behind reaches the viewer's side.
    #[inline]
    pub fn is_translucent(&self) -> bool {
        !self.translucency.is_black()
    }

    /// The hemispheres the surface scatters light between, as signs of the normal on the
    /// viewer's side: in front (`1`), and behind (`-1`) when it is translucent.
    #[inline]
    pub fn hemispheres(&self) -> &'static [f32] {
        if self.is_translucent() {
            &[1.0, -1.0]
        } else {
            &[1.0]
        }
    }

    /// The non-delta scattering function `f(wo, wi)` (1/sr), the sum of the lobes with a
    /// density, for unit directions `wo` (toward the viewer, on the side of the unit normal
    /// `n`) and `wi` (toward the light): the reflecting lobes when `wi` is on the viewer's
    /// side, the transmitting (translucent) lobe when it is behind.
    #[inline]
    pub fn eval(&self, n: Vec3, wo: Vec3, wi: Vec3) -> Rgb {
        let cos = n.dot(wi);
        if cos == 0.0 || n.dot(wo) <= 0.0 {
            return Rgb::BLACK;
        }
        let behind = cos < 0.0;
        let mut f = Rgb::BLACK;
        for lobe in Lobe::ALL {
            if !lobe.is_delta() && lobe.transmits() == behind && !lobe.weight(self).is_black() {
                f += lobe.eval(self, n, wo, wi);
            }
        }
        f
    }
}

/// Radiance emitted by `hit` back along the ray that found it (front face only unless the
/// material is two-sided), emission texture applied.
#[inline]
pub fn emitted(scene: &Scene, hit: &SurfaceHit) -> Rgb {
    emitted_toward(
        scene,
        &scene.materials[hit.material as usize],
        hit.uv,
        hit.front_face,
    )
}

/// Radiance emitted by material `m` at texture coordinate `uv` toward the front
/// (`front = true`) or back side.
#[inline]
pub fn emitted_toward(scene: &Scene, m: &Material, uv: glam::Vec2, front: bool) -> Rgb {
    if m.emission.is_black() || !(front || m.two_sided) {
        return Rgb::BLACK;
    }
    match m.emission_texture {
        Some(t) => m.emission * scene.textures[t as usize].color(uv),
        None => m.emission,
    }
}
