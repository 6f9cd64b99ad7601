//! `cornell`: the Cornell box as measured by the Cornell University Program of Computer
//! Graphics ("Cornell Box Data", <https://www.graphics.cornell.edu/online/box/data.html>,
//! provided for public use). Origin and licence of the data: `data/cornell_box/SOURCE.md`.
//!
//! **Geometry.** The published vertices in millimetres (the variant with the ceiling split
//! into four quads around the light's hole, the light coplanar with the ceiling at
//! y = 548.8 mm), converted to metres. The measured room is not quite rectangular: the floor
//! and back wall are planar trapezoids and the red wall is not planar (its fourth vertex is
//! 3.2 mm off the plane of the other three), so the red wall is two triangles. Every face is
//! wound so that its front side faces into the room, or out of the blocks; the blocks have no
//! bottom faces (as published). Objects: `floor`, `ceiling` (mesh of 4 quads), `back_wall`,
//! `red_wall` (mesh of 2 triangles, at x ≈ 0.55 m), `green_wall` (at x = 0), `short_block`
//! and `tall_block` (meshes of 5 quads), `light` (quad, front face down).
//!
//! **Camera.** As published: position (0.278, 0.273, −0.800) m looking along +z, up +y,
//! focal length 35 mm on a 25 × 25 mm film, so the vertical field of view is
//! 2·atan(12.5/35) = 39.3077°; 512 × 512 pixels.
//!
//! **Reflectances.** The measured spectra (400–700 nm every 4 nm,
//! `data/cornell_box/cornell_box_reflectance.csv`, embedded) converted to linear Rec.709 by
//! [`super::spectrum::spectrum_to_rgb`] when the scene is built (CIE 1931 2° matching
//! functions, equal-energy illuminant, Bradford to D65). Rounded to 3 decimals:
//!
//! | material | R | G | B |
//! |---|---|---|---|
//! | white | 0.738 | 0.736 | 0.738 |
//! | green | 0.052 | 0.397 | 0.086 |
//! | red | 0.524 | 0.050 | 0.050 |
//!
//! **Light.** The published relative emission spectrum (400/500/600/700 nm = 0, 8, 15.6,
//! 18.4, linear in between, resampled on the same 4 nm grid) converted the same way gives the
//! warm-white chromaticity; it is scaled so that the luminance of the emitted radiance is
//! [`LIGHT_LUMINANCE`] = 25 W·sr⁻¹·m⁻², giving L = (36.558, 23.437, 6.446) W·sr⁻¹·m⁻²
//! (the published scale is arbitrary). The value was chosen by what the box then looks like:
//! ignoring the tall block's shadow, the floor under the light's centre receives
//! E ≈ 1.12 W·m⁻² directly and reflects a luminance of ≈ 0.26 from that alone; a Monte Carlo estimate of this geometry with all
//! bounces gives floor luminances of ≈ 0.28 right under the light (partly shadowed by the
//! tall block), 0.26–0.32 on the open floor and ≈ 0.50 on top of the short block. So the box
//! reads right with plain linear tone mapping at exposure 0 (a luminance of 20 would leave the
//! floor near 0.22). The light's own diffuse reflectance is 0.78 (grey).

use super::spectrum::{resample_linear, spectrum_to_rgb};
use crate::color::Rgb;
use crate::scene::{Camera, Material, PolygonMesh, Scene, Shape};
use glam::Vec3;
use std::sync::Arc;

/// Luminance `Y` of the light's emitted radiance, W·sr⁻¹·m⁻² (linear Rec.709 luminance).
pub const LIGHT_LUMINANCE: f32 = 25.0;

/// Diffuse reflectance of the light fixture itself (grey).
pub const LIGHT_REFLECTANCE: f32 = 0.78;

/// Millimetres to metres.
const MM: f32 = 0.001;

/// A quad of published vertices, millimetres.
type QuadMm = [[f32; 3]; 4];

// Vertices in millimetres, transcribed from the Cornell page (see data/cornell_box/SOURCE.md),
// each face counter-clockwise seen from the room / from outside the block.

/// Floor, y = 0.
const FLOOR: QuadMm = [
    [552.8, 0.0, 0.0],
    [0.0, 0.0, 0.0],
    [0.0, 0.0, 559.2],
    [549.6, 0.0, 559.2],
];

/// Back wall, z = 559.2 mm.
const BACK_WALL: QuadMm = [
    [549.6, 0.0, 559.2],
    [0.0, 0.0, 559.2],
    [0.0, 548.8, 559.2],
    [556.0, 548.8, 559.2],
];

/// Green wall, x = 0.
const GREEN_WALL: QuadMm = [
    [0.0, 0.0, 559.2],
    [0.0, 0.0, 0.0],
    [0.0, 548.8, 0.0],
    [0.0, 548.8, 559.2],
];

/// Red wall, x ≈ 550–556 mm (not planar: triangulated as (0, 1, 2), (0, 2, 3)).
const RED_WALL: QuadMm = [
    [552.8, 0.0, 0.0],
    [549.6, 0.0, 559.2],
    [556.0, 548.8, 559.2],
    [556.0, 548.8, 0.0],
];

/// Ceiling, y = 548.8 mm, four quads around the light's hole.
const CEILING: [QuadMm; 4] = [
    [
        [556.0, 548.8, 0.0],
        [556.0, 548.8, 227.0],
        [0.0, 548.8, 227.0],
        [0.0, 548.8, 0.0],
    ],
    [
        [556.0, 548.8, 332.0],
        [556.0, 548.8, 559.2],
        [0.0, 548.8, 559.2],
        [0.0, 548.8, 332.0],
    ],
    [
        [213.0, 548.8, 227.0],
        [213.0, 548.8, 332.0],
        [0.0, 548.8, 332.0],
        [0.0, 548.8, 227.0],
    ],
    [
        [556.0, 548.8, 227.0],
        [556.0, 548.8, 332.0],
        [343.0, 548.8, 332.0],
        [343.0, 548.8, 227.0],
    ],
];

/// The light, 130 × 105 mm in the ceiling's hole, front face down.
const LIGHT: QuadMm = [
    [343.0, 548.8, 227.0],
    [343.0, 548.8, 332.0],
    [213.0, 548.8, 332.0],
    [213.0, 548.8, 227.0],
];

/// Short block: top, then four sides.
const SHORT_BLOCK: [QuadMm; 5] = [
    [
        [130.0, 165.0, 65.0],
        [82.0, 165.0, 225.0],
        [240.0, 165.0, 272.0],
        [290.0, 165.0, 114.0],
    ],
    [
        [290.0, 0.0, 114.0],
        [290.0, 165.0, 114.0],
        [240.0, 165.0, 272.0],
        [240.0, 0.0, 272.0],
    ],
    [
        [130.0, 0.0, 65.0],
        [130.0, 165.0, 65.0],
        [290.0, 165.0, 114.0],
        [290.0, 0.0, 114.0],
    ],
    [
        [82.0, 0.0, 225.0],
        [82.0, 165.0, 225.0],
        [130.0, 165.0, 65.0],
        [130.0, 0.0, 65.0],
    ],
    [
        [240.0, 0.0, 272.0],
        [240.0, 165.0, 272.0],
        [82.0, 165.0, 225.0],
        [82.0, 0.0, 225.0],
    ],
];

/// Tall block: top, then four sides.
const TALL_BLOCK: [QuadMm; 5] = [
    [
        [423.0, 330.0, 247.0],
        [265.0, 330.0, 296.0],
        [314.0, 330.0, 456.0],
        [472.0, 330.0, 406.0],
    ],
    [
        [423.0, 0.0, 247.0],
        [423.0, 330.0, 247.0],
        [472.0, 330.0, 406.0],
        [472.0, 0.0, 406.0],
    ],
    [
        [472.0, 0.0, 406.0],
        [472.0, 330.0, 406.0],
        [314.0, 330.0, 456.0],
        [314.0, 0.0, 456.0],
    ],
    [
        [314.0, 0.0, 456.0],
        [314.0, 330.0, 456.0],
        [265.0, 330.0, 296.0],
        [265.0, 0.0, 296.0],
    ],
    [
        [265.0, 0.0, 296.0],
        [265.0, 330.0, 296.0],
        [423.0, 330.0, 247.0],
        [423.0, 0.0, 247.0],
    ],
];

/// Measured reflectance spectra: `wavelength_nm,white,green,red`, `#` comments.
const REFLECTANCE_CSV: &str = include_str!("../../../data/cornell_box/cornell_box_reflectance.csv");

/// Relative light emission spectrum: `wavelength_nm,relative_emission`, `#` comments.
const LIGHT_SPECTRUM_CSV: &str =
    include_str!("../../../data/cornell_box/cornell_box_light_spectrum.csv");

/// The Cornell box colours in linear Rec.709, derived from the measured spectra.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornellColors {
    /// Reflectance of the white surfaces (floor, ceiling, back wall, blocks).
    pub white: Rgb,
    /// Reflectance of the green wall.
    pub green: Rgb,
    /// Reflectance of the red wall.
    pub red: Rgb,
    /// Emitted radiance of the light, W·sr⁻¹·m⁻², with luminance [`LIGHT_LUMINANCE`].
    pub light: Rgb,
}

/// Reads the numeric rows of a `#`-commented CSV with a header line; each row must have
/// `columns` numbers.
fn read_table(text: &str, columns: usize) -> Result<Vec<Vec<f64>>, String> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    reader
        .records()
        .map(|record| {
            let record = record.map_err(|e| format!("Cornell box data: {e}"))?;
            if record.len() != columns {
                return Err(format!(
                    "Cornell box data: expected {columns} columns, found {}",
                    record.len()
                ));
            }
            record
                .iter()
                .map(|field| {
                    field
                        .trim()
                        .parse::<f64>()
                        .map_err(|e| format!("Cornell box data: '{field}': {e}"))
                })
                .collect()
        })
        .collect()
}

/// The colours of the box, computed from the embedded measured spectra.
pub fn colors() -> Result<CornellColors, String> {
    let rows = read_table(REFLECTANCE_CSV, 4)?;
    let column = |c: usize| -> Vec<(f64, f64)> { rows.iter().map(|r| (r[0], r[c])).collect() };
    let white = spectrum_to_rgb(&column(1))?;
    let green = spectrum_to_rgb(&column(2))?;
    let red = spectrum_to_rgb(&column(3))?;

    let points: Vec<(f64, f64)> = read_table(LIGHT_SPECTRUM_CSV, 2)?
        .into_iter()
        .map(|r| (r[0], r[1]))
        .collect();
    let grid: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    let relative = spectrum_to_rgb(&resample_linear(&points, &grid)?)?;
    let light = relative * (LIGHT_LUMINANCE / relative.luminance());
    Ok(CornellColors {
        white,
        green,
        red,
        light,
    })
}

/// Vertices of a published face in metres.
fn metres(face: &[[f32; 3]]) -> Vec<Vec3> {
    face.iter().map(|&v| Vec3::from(v) * MM).collect()
}

/// A mesh of quads (published millimetres) in metres.
fn quad_mesh(quads: &[QuadMm]) -> PolygonMesh {
    PolygonMesh {
        positions: quads.iter().flat_map(|q| metres(q)).collect(),
        indices: (0..4 * quads.len() as u32).collect(),
        face_sizes: vec![4; quads.len()],
        ..Default::default()
    }
}

/// A planar quad (published millimetres) as a polygon in metres.
fn quad(face: &QuadMm) -> Shape {
    Shape::Polygon {
        vertices: metres(face),
        uvs: None,
    }
}

/// The published camera, 512 × 512.
fn camera() -> Camera {
    let position = Vec3::new(0.278, 0.273, -0.800);
    Camera {
        position,
        look_at: position + Vec3::Z,
        up: Vec3::Y,
        fov_degrees: 2.0 * (12.5f32 / 35.0).atan().to_degrees(),
        width: 512,
        height: 512,
    }
}

/// The measured Cornell box (see the module documentation).
pub fn scene() -> Result<Scene, String> {
    let colors = colors()?;
    let mut scene = Scene::empty("cornell");
    scene.camera = camera();
    let white = scene.add_material(Material::diffuse("white", colors.white));
    let red = scene.add_material(Material::diffuse("red", colors.red));
    let green = scene.add_material(Material::diffuse("green", colors.green));
    let light = scene.add_material(Material::emitter(
        "light",
        Rgb::splat(LIGHT_REFLECTANCE),
        colors.light,
    ));

    let red_wall = PolygonMesh::from_triangles(metres(&RED_WALL), &[[0, 1, 2], [0, 2, 3]]);
    scene.add_object("floor", quad(&FLOOR), white);
    scene.add_object("ceiling", Shape::Mesh(Arc::new(quad_mesh(&CEILING))), white);
    scene.add_object("back_wall", quad(&BACK_WALL), white);
    scene.add_object("red_wall", Shape::Mesh(Arc::new(red_wall)), red);
    scene.add_object("green_wall", quad(&GREEN_WALL), green);
    scene.add_object(
        "short_block",
        Shape::Mesh(Arc::new(quad_mesh(&SHORT_BLOCK))),
        white,
    );
    scene.add_object(
        "tall_block",
        Shape::Mesh(Arc::new(quad_mesh(&TALL_BLOCK))),
        white,
    );
    scene.add_object("light", quad(&LIGHT), light);
    Ok(scene)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Object, polygon_area};

    fn object<'a>(scene: &'a Scene, name: &str) -> &'a Object {
        scene
            .objects
            .iter()
            .find(|o| o.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("no object {name}"))
    }

    /// Every face of an object as its vertex list (meshes: per face, polygons: one face).
    fn faces(shape: &Shape) -> Vec<Vec<Vec3>> {
        match shape {
            Shape::Polygon { vertices, .. } => vec![vertices.clone()],
            Shape::Mesh(m) => m
                .faces()
                .map(|f| f.iter().map(|&i| m.positions[i as usize]).collect())
                .collect(),
            other => panic!("unexpected shape {}", other.kind_name()),
        }
    }

    /// Geometric normal of the first triangle of a face (the winding's front side).
    fn front_normal(face: &[Vec3]) -> Vec3 {
        (face[1] - face[0]).cross(face[2] - face[0]).normalize()
    }

    fn centroid(points: &[Vec3]) -> Vec3 {
        points.iter().sum::<Vec3>() / points.len() as f32
    }

    #[test]
    fn floor_and_light_areas_match_published_values() {
        let scene = scene().unwrap();
        let floor = faces(&object(&scene, "floor").shape);
        assert!((polygon_area(&floor[0]) - 0.30823).abs() < 1e-4);
        let light = faces(&object(&scene, "light").shape);
        assert!((polygon_area(&light[0]) - 0.013650).abs() < 1e-6);
        assert!((light[0][0].y - 0.5488).abs() < 1e-6);
        assert!(front_normal(&light[0]).y < -0.999);
    }

    #[test]
    fn room_faces_point_into_the_room_and_block_faces_out_of_the_blocks() {
        let scene = scene().unwrap();
        let room_centre = Vec3::new(0.278, 0.2744, 0.2796);
        let room = [
            "floor",
            "ceiling",
            "back_wall",
            "red_wall",
            "green_wall",
            "light",
        ];
        let mut count = 0;
        for name in room {
            for face in faces(&object(&scene, name).shape) {
                let n = front_normal(&face);
                assert!(n.dot(room_centre - centroid(&face)) > 0.0, "{name}");
                count += 1;
            }
        }
        for name in ["short_block", "tall_block"] {
            let block = faces(&object(&scene, name).shape);
            assert_eq!(block.len(), 5);
            let all: Vec<Vec3> = block.iter().flatten().copied().collect();
            let centre = centroid(&all);
            for face in &block {
                let n = front_normal(face);
                assert!(n.dot(centroid(face) - centre) > 0.0, "{name}");
                count += 1;
            }
        }
        // 1 + 4 + 1 + 2 + 1 + 1 room faces, 10 block faces.
        assert_eq!(count, 20);
    }

    #[test]
    fn measured_colors_match_the_documented_table() {
        let c = colors().unwrap();
        let table = [
            (c.white, [0.738, 0.736, 0.738]),
            (c.green, [0.052, 0.397, 0.086]),
            (c.red, [0.524, 0.050, 0.050]),
            (c.light, [36.558, 23.437, 6.446]),
        ];
        for (got, expected) in table {
            for (g, e) in got.to_array().iter().zip(expected) {
                assert!((g - e).abs() <= 0.0005 + 1e-6, "{got:?} vs {expected:?}");
            }
        }
        assert!((c.light.luminance() - LIGHT_LUMINANCE).abs() < 1e-4);
    }

    #[test]
    fn camera_is_the_published_one() {
        let cam = scene().unwrap().camera;
        assert!((cam.fov_degrees - 39.3077).abs() < 1e-3);
        assert_eq!((cam.width, cam.height), (512, 512));
        assert_eq!(cam.position, Vec3::new(0.278, 0.273, -0.8));
    }

    /// Irradiance at a point of a surface with normal `n` from a uniform Lambertian polygon
    /// of radiance `radiance` (Lambert's contour integral).
    fn irradiance_from_polygon(point: Vec3, n: Vec3, polygon: &[Vec3], radiance: f32) -> f32 {
        let k = polygon.len();
        let sum: f32 = (0..k)
            .map(|i| {
                let a = (polygon[i] - point).normalize();
                let b = (polygon[(i + 1) % k] - point).normalize();
                let gamma = a.cross(b).normalize();
                a.angle_between(b) * gamma.dot(n)
            })
            .sum();
        0.5 * radiance * sum.abs()
    }

    #[test]
    fn direct_light_on_the_floor_under_the_lamp_is_as_documented() {
        let scene = scene().unwrap();
        let light = faces(&object(&scene, "light").shape).remove(0);
        let below = Vec3::new(0.278, 0.0, 0.2795);
        let e = irradiance_from_polygon(below, Vec3::Y, &light, LIGHT_LUMINANCE);
        // Numerical integration over the light gives 1.1158 W·m⁻² (the small-source
        // estimate L·A/d² = 25 · 0.01365 / 0.5488² = 1.133).
        assert!((e - 1.1158).abs() < 1e-3, "E = {e}");
        let white = colors().unwrap().white.luminance();
        let reflected = white / std::f32::consts::PI * e;
        assert!((reflected - 0.2616).abs() < 2e-3, "L = {reflected}");
    }
}
