//! The sky of a scene as the algorithms see it: the uniform skies' radiance summed, and every
//! CIE standard sky compiled once — its radiance by direction, the irradiance it sends onto an
//! unoccluded surface of any orientation, and a table of the directions its light arrives
//! from, for photons.

use crate::color::{Rgb, Rgb64};
use crate::scene::LightKind;
use crate::sky::{CieSky, CieSkyType, SkyTable};
use glam::{DVec3, Vec3};
use std::f64::consts::{FRAC_PI_2, TAU};

/// Rows (equal zenith-angle widths) of the midpoint quadrature over the upper hemisphere.
const QUADRATURE_ROWS: usize = 90;
/// Columns (equal azimuth widths) of the midpoint quadrature over the upper hemisphere.
const QUADRATURE_COLUMNS: usize = 180;
/// Rows of the table photon directions are drawn from.
const TABLE_ROWS: usize = 64;
/// Columns of the table photon directions are drawn from.
const TABLE_COLUMNS: usize = 128;

/// Every sky of a scene: the sum of its uniform skies and its CIE skies, whose radiances add.
#[derive(Clone, Debug, Default)]
pub struct Sky {
    /// The summed radiance of the uniform skies, W·sr⁻¹·m⁻², from every direction; `None`
    /// when the scene has none.
    pub uniform: Option<Rgb>,
    /// The CIE standard skies, over the upper hemisphere only.
    pub cie: Vec<CompiledCieSky>,
}

impl Sky {
    /// The radiance arriving from the unit direction `dir` (pointing away from the receiver),
    /// W·sr⁻¹·m⁻²: the uniform skies' from every direction plus the CIE skies' from above
    /// the horizon.
    pub fn radiance(&self, dir: Vec3) -> Rgb {
        self.cie
            .iter()
            .fold(self.uniform.unwrap_or(Rgb::BLACK), |sum, sky| {
                sum + sky.radiance(dir)
            })
    }

    /// The luminance of the irradiance every sky sends onto an unoccluded upward-facing
    /// surface, W·m⁻² (`π·L` for a uniform sky, the diffuse horizontal irradiance for a CIE
    /// sky): what choosing the sky among lights by power weighs it by, per unit area of the
    /// scene's cross-section.
    pub fn horizontal_luminance(&self) -> f32 {
        let uniform = std::f32::consts::PI * self.uniform.map_or(0.0, Rgb::luminance);
        self.cie
            .iter()
            .fold(uniform, |sum, sky| sum + sky.diffuse_horizontal.luminance())
    }

    /// The sky lights as the scene states them: the uniform skies as one, then each CIE sky.
    pub fn lights(&self) -> impl Iterator<Item = LightKind> + '_ {
        let uniform = self.uniform.map(|radiance| LightKind::Sky { radiance });
        uniform
            .into_iter()
            .chain(self.cie.iter().map(CompiledCieSky::light))
    }

    /// The compiled CIE sky of the CIE sky `light`, if this sky holds it.
    pub fn cie_of(&self, light: &LightKind) -> Option<&CompiledCieSky> {
        self.cie.iter().find(|sky| sky.light() == *light)
    }
}

/// A CIE standard sky compiled for the algorithms ([`LightKind::CieSky`]).
#[derive(Clone, Debug)]
pub struct CompiledCieSky {
    /// Which standard sky.
    sky_type: CieSkyType,
    /// Unit direction toward the sun, as the light gives it.
    sun: Vec3,
    /// Diffuse horizontal irradiance, W·m⁻² per channel.
    diffuse_horizontal: Rgb,
    /// The sky scaled to a diffuse horizontal irradiance of 1.
    unit: CieSky,
    /// Midpoint quadrature of the upper hemisphere: directions and the unit sky's radiance
    /// times the solid angle of their cells (sr·sr⁻¹), scaled so that `Σ w·cos θ = 1`
    /// exactly, as the unit sky's horizontal irradiance is.
    quadrature: Vec<(DVec3, f64)>,
    /// `∫ L dω` of the unit sky over the upper hemisphere (W·m⁻² per W·m⁻² of diffuse
    /// horizontal irradiance), from `quadrature`.
    radiance_integral: f64,
    /// The directions light arrives from, drawn in proportion to the unit sky's radiance.
    arrivals: SkyTable,
    /// The directions light arrives from through a horizontal surface, drawn in proportion
    /// to the unit sky's radiance times the cosine of the zenith angle.
    horizontal_arrivals: SkyTable,
}

impl CompiledCieSky {
    /// The CIE sky of type `sky_type` with the sun toward `sun` (normalised here; the zenith
    /// when it has no direction) sending `diffuse_horizontal` (W·m⁻² per channel) onto an
    /// unoccluded upward-facing surface.
    pub fn new(sky_type: CieSkyType, sun: Vec3, diffuse_horizontal: Rgb) -> CompiledCieSky {
        let toward = sun.as_dvec3().try_normalize().unwrap_or(DVec3::Y);
        let unit = CieSky::standard(sky_type, toward, 1.0);
        let radiance = |d: DVec3| {
            let l = unit.radiance(d);
            if l.is_finite() { l.max(0.0) } else { 0.0 }
        };
        let (row_width, column_width) = (
            FRAC_PI_2 / QUADRATURE_ROWS as f64,
            TAU / QUADRATURE_COLUMNS as f64,
        );
        let mut quadrature = Vec::with_capacity(QUADRATURE_ROWS * QUADRATURE_COLUMNS);
        for row in 0..QUADRATURE_ROWS {
            let theta = (row as f64 + 0.5) * row_width;
            let (sin, cos) = theta.sin_cos();
            for column in 0..QUADRATURE_COLUMNS {
                let phi = (column as f64 + 0.5) * column_width;
                let d = DVec3::new(sin * phi.sin(), cos, -sin * phi.cos());
                quadrature.push((d, radiance(d) * sin * row_width * column_width));
            }
        }
        let horizontal: f64 = quadrature.iter().map(|(d, w)| w * d.y).sum();
        if horizontal > 0.0 {
            quadrature.iter_mut().for_each(|(_, w)| *w /= horizontal);
        }
        let radiance_integral = quadrature.iter().map(|(_, w)| w).sum();
        // The table weighs each direction by `L·cos θ`; dividing by `cos θ` (never 0 at the
        // points it averages) makes the draw proportional to `L`.
        let arrivals = SkyTable::new(TABLE_ROWS, TABLE_COLUMNS, |d| radiance(d) / d.y);
        let horizontal_arrivals = SkyTable::new(TABLE_ROWS, TABLE_COLUMNS, radiance);
        CompiledCieSky {
            sky_type,
            sun,
            diffuse_horizontal,
            unit,
            quadrature,
            radiance_integral,
            arrivals,
            horizontal_arrivals,
        }
    }

    /// The light this sky was compiled from.
    pub fn light(&self) -> LightKind {
        LightKind::CieSky {
            sky: self.sky_type,
            sun: self.sun,
            diffuse_horizontal: self.diffuse_horizontal,
        }
    }

    /// The sky's radiance from the unit direction `dir`, W·sr⁻¹·m⁻²; black below the horizon.
    pub fn radiance(&self, dir: Vec3) -> Rgb {
        self.diffuse_horizontal * self.relative_radiance(dir.as_dvec3()) as f32
    }

    /// The radiance from the unit direction `dir` per W·m⁻² of diffuse horizontal
    /// irradiance, sr⁻¹ (≥ 0, finite).
    pub fn relative_radiance(&self, dir: DVec3) -> f64 {
        let l = self.unit.radiance(dir);
        if l.is_finite() { l.max(0.0) } else { 0.0 }
    }

    /// The irradiance the whole sky sends onto an unoccluded surface whose receiving side
    /// has the unit normal `normal`, W·m⁻² per channel: `∫ L·max(0, n·ω) dω` over the upper
    /// hemisphere by a 90 × 180 midpoint quadrature (exactly the diffuse horizontal
    /// irradiance for an upward normal).
    pub fn irradiance_on(&self, normal: DVec3) -> Rgb64 {
        let share: f64 = self
            .quadrature
            .iter()
            .map(|&(d, w)| w * normal.dot(d).max(0.0))
            .sum();
        self.diffuse_horizontal.to_f64() * share
    }

    /// `∫ L dω` over the upper hemisphere, W·m⁻² per channel: the power the sky sends through
    /// a unit area of a disc held across its light from each direction, summed over them.
    pub fn radiance_integral(&self) -> Rgb64 {
        self.diffuse_horizontal.to_f64() * self.radiance_integral
    }

    /// A direction light arrives from (pointing toward the sky), drawn for the uniform
    /// numbers `u` with density nearly in proportion to the radiance, and the weight
    /// `L(ω) / (p(ω) · ∫ L dω)` (about 1) that makes the draw exact; `None` for a black sky.
    pub fn sample_arrival(&self, u: [f64; 2]) -> Option<(DVec3, f64)> {
        let sample = self.arrivals.sample(u)?;
        let weight =
            self.relative_radiance(sample.direction) / (sample.pdf * self.radiance_integral);
        weight.is_finite().then_some((sample.direction, weight))
    }

    /// A direction light arrives from through a horizontal surface (the top of a periodic
    /// plot), drawn for the uniform numbers `u` with density nearly in proportion to
    /// `L·cos θ`, and the weight `L(ω)·cos θ / (p(ω) · E_dh)` (about 1, mean 1 over the
    /// draws) that makes the draw exact; `None` for a black sky.
    pub fn sample_arrival_horizontal(&self, u: [f64; 2]) -> Option<(DVec3, f64)> {
        let sample = self.horizontal_arrivals.sample(u)?;
        let d = sample.direction;
        let weight = self.relative_radiance(d) * d.y / sample.pdf;
        weight.is_finite().then_some((d, weight))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sky::direction_from_angles;

    #[test]
    fn an_upward_surface_gets_the_diffuse_horizontal_irradiance_and_a_downward_one_none() {
        for sky_type in [CieSkyType::OvercastSteep, CieSkyType::ClearLowTurbidity] {
            let sun = direction_from_angles(60.0, 135.0).as_vec3();
            let sky = CompiledCieSky::new(sky_type, sun, Rgb::new(100.0, 50.0, 10.0));
            let up = sky.irradiance_on(DVec3::Y);
            assert!((up.r - 100.0).abs() < 1e-9 && (up.b - 10.0).abs() < 1e-10);
            assert_eq!(sky.irradiance_on(-DVec3::Y), Rgb64::BLACK);
            assert_eq!(sky.radiance(-Vec3::Y), Rgb::BLACK);
        }
    }

    #[test]
    fn arrivals_through_a_horizontal_surface_weigh_about_one_and_average_one() {
        let sun = direction_from_angles(30.0, 200.0).as_vec3();
        let sky = CompiledCieSky::new(CieSkyType::ClearLowTurbidity, sun, Rgb::WHITE);
        let n = 256;
        let (mut sum, mut largest) = (0.0, 0.0f64);
        for i in 0..n {
            for j in 0..n {
                let u = [(i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64];
                let (d, w) = sky.sample_arrival_horizontal(u).expect("a bright sky");
                assert!(d.y > 0.0);
                sum += w;
                largest = largest.max((w - 1.0).abs());
            }
        }
        let mean = sum / (n * n) as f64;
        assert!((mean - 1.0).abs() < 2e-3, "{mean}");
        assert!(largest < 0.5, "{largest}");
    }

    #[test]
    fn drawn_arrivals_weigh_to_the_radiance_integral() {
        // E[w·cos θ]·∫L dω over the draws is ∫L cos θ dω = 1 for the unit sky.
        let sun = direction_from_angles(30.0, 200.0).as_vec3();
        let sky = CompiledCieSky::new(CieSkyType::ClearLowTurbidity, sun, Rgb::WHITE);
        let n = 256;
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..n {
                let u = [(i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64];
                let (d, w) = sky.sample_arrival(u).expect("a bright sky");
                sum += w * d.y;
            }
        }
        let horizontal = sum / (n * n) as f64 * sky.radiance_integral().g;
        assert!((horizontal - 1.0).abs() < 2e-3, "{horizontal}");
    }
}
