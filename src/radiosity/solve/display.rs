//! Display of a radiosity solution (seed 000 §9.4, seed 001): camera rays hit the leaf
//! patches (as triangles, under a BVH) and show the radiance `B/π` of a Lambertian surface,
//! flat per leaf or smooth from the interpolated corner values ([`RadiosityLookup`]), with
//! the patch edges optionally drawn as black lines one pixel wide. Each side of a patch shows
//! its own radiosity; a textured surface shows its texture at full resolution, lit by the
//! irradiance on the mesh. Surfaces that are not in the mesh (infinite planes) are not shown.
//! The same rays give a [`ValueImage`] of illuminance or luminance per pixel, for false
//! colour.

use super::lookup::{RadiosityLookup, Shading};
use super::solution::{LinkSegment, Solution};
use super::system::RadiositySystem;
use crate::color::LUMINOUS_EFFICACY;
use crate::color::Rgb;
use crate::geometry::Ray;
use crate::measure::{Film, Photometric, ValueImage};
use crate::progress::{Cancel, ProgressListener};
use crate::scene::{Camera, CameraRays};
use glam::DVec3;
use rayon::prelude::*;
use std::f64::consts::PI;

/// Wireframe line half-width in pixels.
const LINE_HALF_WIDTH_PIXELS: f64 = 0.6;

/// Image settings of the display.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DisplaySettings {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Flat or smooth.
    pub shading: Shading,
    /// Draw the leaf patch edges.
    pub wireframe: bool,
    /// Camera rays per pixel and axis (a regular grid; `n²` rays per pixel).
    pub samples_per_axis: u32,
    /// Which links of a hierarchical solution to draw over the image.
    pub links: LinkDisplay,
}

/// Which links the display draws (seed 000's figures of links), as lines from the centroid
/// of the receiving node to that of the emitting node, over everything else.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LinkDisplay {
    /// None.
    #[default]
    None,
    /// Every link of the solution.
    All,
    /// The links that receive on or emit from the object with this index.
    Object(u32),
}

impl LinkDisplay {
    fn shows(self, link: &LinkSegment) -> bool {
        match self {
            LinkDisplay::None => false,
            LinkDisplay::All => true,
            LinkDisplay::Object(o) => {
                link.receiver_object == Some(o) || link.emitter_object == Some(o)
            }
        }
    }
}

/// Renders `solution` (its display radiosity, ambient term included) through `camera` at
/// the settings' resolution as linear radiance, W·sr⁻¹·m⁻². `None` when the camera is
/// degenerate. Rows are rendered in parallel; `cancel` leaves the remaining rows black.
pub fn render_solution(
    system: &RadiositySystem,
    solution: &Solution,
    camera: &Camera,
    settings: &DisplaySettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Option<Film> {
    let rays = camera
        .with_resolution(settings.width, settings.height)
        .rays()?;
    let lookup = solution.display_lookup(system, settings.shading);
    let view = Viewer {
        lookup: &lookup,
        wireframe: settings.wireframe,
        pixel_angle: 2.0 * (camera.fov_degrees.to_radians() as f64 * 0.5).tan()
            / settings.height as f64,
    };
    let n = settings.samples_per_axis.max(1);
    let pixels = by_rows(settings, Rgb::BLACK, progress, cancel, |x, y| {
        let sum = samples(x, y, n).fold(Rgb::BLACK, |sum, (px, py)| {
            sum + view.radiance(&rays.ray(px, py))
        });
        sum / (n * n) as f32
    });
    let mut film = Film::from_pixels(settings.width, settings.height, pixels)?;
    if settings.links != LinkDisplay::None {
        draw_links(&mut film, &rays, solution, settings.links);
    }
    Some(film)
}

/// `quantity` seen through `camera` at the settings' resolution and rays per pixel (its
/// shading; wireframe and links are not drawn): illuminance from the solution's irradiance
/// on the side each ray meets, or luminance from its radiance `B/π` (textures at full
/// resolution), both × 683 lm/W on the luminance weighting. A pixel where fewer than half
/// its rays meet a surface has no value; the others hold the mean over the rays that met
/// one. `None` when the camera is degenerate; `cancel` leaves the remaining rows without
/// values.
pub fn value_image(
    system: &RadiositySystem,
    solution: &Solution,
    camera: &Camera,
    settings: &DisplaySettings,
    quantity: Photometric,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Option<ValueImage> {
    let rays = camera
        .with_resolution(settings.width, settings.height)
        .rays()?;
    let (lookup, scale) = match quantity {
        Photometric::Illuminance => (
            RadiosityLookup::new(system, solution.display_irradiance(), settings.shading),
            LUMINOUS_EFFICACY * PI,
        ),
        Photometric::Luminance => (
            solution.display_lookup(system, settings.shading),
            LUMINOUS_EFFICACY,
        ),
    };
    let n = settings.samples_per_axis.max(1);
    let values = by_rows(settings, None, progress, cancel, |x, y| {
        let (mut sum, mut hits) = (0.0f64, 0u32);
        for (px, py) in samples(x, y, n) {
            if let Some(hit) = lookup.hit(&rays.ray(px, py)) {
                sum += f64::from(hit.radiance.luminance().max(0.0));
                hits += 1;
            }
        }
        (2 * hits >= n * n).then(|| (sum / f64::from(hits) * scale) as f32)
    });
    Some(ValueImage {
        width: settings.width,
        height: settings.height,
        quantity,
        values,
    })
}

/// What a ray meets on a solution ([`Probe::at`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProbeHit {
    /// The scene object hit (its index).
    pub object: u32,
    /// The point hit, scene units.
    pub point: DVec3,
    /// Distance along the ray, scene units.
    pub distance: f64,
    /// Illuminance there, on the side the ray meets, lux.
    pub illuminance: f64,
    /// Luminance there, seen along the ray, cd·m⁻².
    pub luminance: f64,
}

/// Reads a solution along any ray: the illuminance and luminance where the ray meets the
/// leaf mesh, looked up as the display shows them (`shading`).
pub struct Probe<'s> {
    irradiance: RadiosityLookup<'s>,
    radiance: RadiosityLookup<'s>,
}

impl<'s> Probe<'s> {
    /// The probe of `solution` on `system`.
    pub fn new(system: &'s RadiositySystem, solution: &Solution, shading: Shading) -> Self {
        Probe {
            irradiance: RadiosityLookup::new(system, solution.display_irradiance(), shading),
            radiance: solution.display_lookup(system, shading),
        }
    }

    /// What `ray` meets first, `None` when it meets no surface of the mesh.
    pub fn at(&self, ray: &Ray) -> Option<ProbeHit> {
        let hit = self.irradiance.hit(ray)?;
        let luminance = self
            .radiance
            .hit(ray)
            .map_or(0.0, |h| f64::from(h.radiance.luminance()));
        Some(ProbeHit {
            object: hit.patch.object,
            point: hit.point,
            distance: hit.distance,
            illuminance: LUMINOUS_EFFICACY * PI * f64::from(hit.radiance.luminance()),
            luminance: LUMINOUS_EFFICACY * luminance,
        })
    }
}

/// `pixel(x, y)` for every pixel of the settings' image, row by row, the rows in parallel;
/// `progress` counts the rows, and the rows begun after `cancel` take `blank`.
fn by_rows<T: Clone + Send + Sync>(
    settings: &DisplaySettings,
    blank: T,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
    pixel: impl Fn(u32, u32) -> T + Sync,
) -> Vec<T> {
    progress.start(settings.height as u64);
    let pixels = (0..settings.height)
        .into_par_iter()
        .flat_map_iter(|y| {
            let row: Vec<T> = if cancel.is_requested() {
                vec![blank.clone(); settings.width as usize]
            } else {
                (0..settings.width).map(|x| pixel(x, y)).collect()
            };
            progress.advance(1);
            row
        })
        .collect();
    progress.finish();
    pixels
}

/// The image positions of an `n × n` grid of samples inside pixel (`x`, `y`), pixels.
fn samples(x: u32, y: u32, n: u32) -> impl Iterator<Item = (f32, f32)> {
    (0..n).flat_map(move |i| {
        (0..n).map(move |j| {
            (
                x as f32 + (i as f32 + 0.5) / n as f32,
                y as f32 + (j as f32 + 0.5) / n as f32,
            )
        })
    })
}

/// Draws the links `which` selects as one-pixel lines in a light cyan twice as bright as
/// the image's mean luminance (so tone mapping keeps them visible).
fn draw_links(film: &mut Film, rays: &CameraRays, solution: &Solution, which: LinkDisplay) {
    let (width, height) = (film.width() as i64, film.height() as i64);
    let mean =
        film.pixels().iter().map(|p| p.luminance()).sum::<f32>() / film.pixels().len() as f32;
    let colour = Rgb::new(0.3, 1.0, 1.0) * (2.0 * mean.max(f32::MIN_POSITIVE));
    let pixels = film.pixels_mut();
    for link in solution.link_segments.iter().filter(|l| which.shows(l)) {
        let ends = (
            rays.project(link.receiver.as_vec3()),
            rays.project(link.emitter.as_vec3()),
        );
        let (Some((x0, y0)), Some((x1, y1))) = ends else {
            continue;
        };
        let steps = (x1 - x0).abs().max((y1 - y0).abs()).ceil().clamp(1.0, 1e5) as usize;
        for k in 0..=steps {
            let t = k as f32 / steps as f32;
            let (x, y) = ((x0 + (x1 - x0) * t) as i64, (y0 + (y1 - y0) * t) as i64);
            if (0..width).contains(&x) && (0..height).contains(&y) {
                pixels[(y * width + x) as usize] = colour;
            }
        }
    }
}

/// What one camera ray sees.
struct Viewer<'a> {
    lookup: &'a RadiosityLookup<'a>,
    /// Draw the leaf patch edges.
    wireframe: bool,
    /// Angle one pixel subtends (radians, small-angle).
    pixel_angle: f64,
}

impl Viewer<'_> {
    fn radiance(&self, ray: &Ray) -> Rgb {
        let Some(hit) = self.lookup.hit(ray) else {
            return Rgb::BLACK;
        };
        let width = LINE_HALF_WIDTH_PIXELS * self.pixel_angle * hit.distance;
        if self.wireframe && edge_distance(hit.patch.corners(), hit.point) < width {
            return Rgb::BLACK;
        }
        hit.radiance
    }
}

/// Distance from `p` to the nearest edge of the polygon `corners`.
fn edge_distance(corners: &[DVec3], p: DVec3) -> f64 {
    (0..corners.len())
        .map(|i| {
            let (a, b) = (corners[i], corners[(i + 1) % corners.len()]);
            let ab = b - a;
            let t = ((p - a).dot(ab) / ab.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
            p.distance(a + ab * t)
        })
        .fold(f64::INFINITY, f64::min)
}
