//! The cases of the suite: scenes with closed-form answers after CIE 171:2006's analytic
//! test cases, built in photometric units (intensities in cd, luminances in cd/m², white
//! light, so that every channel carries the same number and lux = 683 × W·m⁻²), each with the
//! quantities to check and their expected values from [`super::closed_forms`]; and one
//! without a closed form, the built-in Cornell box face by face against the light model's
//! recording ([`super::recorded`]).

use super::closed_forms::{
    beer_beam, beer_uniform_sky, enclosure_mean, isotropic_point, lambertian_point,
    parallel_rectangle, perpendicular_rectangle,
};
use super::recorded;
use crate::color::{LUMINOUS_EFFICACY, Rgb};
use crate::scene::builtin::cornell;
use crate::scene::builtin::field::{FieldSpec, field};
use crate::scene::{Camera, CieSkyType, Light, LightKind, Material, Scene, Sensor, Shape};
use glam::Vec3;
use std::f64::consts::PI;

/// What a check compares.
#[derive(Clone, Debug, PartialEq)]
pub enum Quantity {
    /// Illuminance at sensor `k` (lux): direct for methods that count no reflection, else
    /// in all.
    Sensor(usize),
    /// Luminous flux arriving on all surfaces together (lm).
    TotalFlux,
    /// Mean illuminance over all surfaces (lux).
    MeanIlluminance,
    /// Mean indirect illuminance over all surfaces (lux), for methods that tell it apart.
    MeanIndirect,
    /// Illuminance on the reported surface `k` (lux): its incident power over its area, as a
    /// small measuring patch reads it.
    Surface(usize),
    /// Luminous flux arriving on face `face` of object `object` (lm, both sides), the object
    /// reported face by face.
    FaceFlux {
        /// Object index.
        object: u32,
        /// Face of the object.
        face: u32,
    },
}

/// One figure to check.
#[derive(Clone, Debug, PartialEq)]
pub struct Check {
    /// What is checked, as the table shows it (`E(θ = 30°)`, `total flux`, …).
    pub label: String,
    /// Which number of the outcome.
    pub quantity: Quantity,
    /// Expected value when every reflection counts (lux or lm).
    pub expected: f64,
    /// Expected value of the light straight from the sources, when the check applies to
    /// methods that count no reflection.
    pub expected_direct: Option<f64>,
    /// Standard error of `expected` where it is a recorded measurement, not a closed form
    /// (same unit): three of them are added to the tolerance.
    pub expected_error: Option<f64>,
}

/// A scene with its checks.
pub struct Case {
    /// Short name (`lambertian-point`, …).
    pub name: String,
    /// What it tests and from which formula.
    pub description: &'static str,
    /// The scene.
    pub scene: Scene,
    /// The figures to check.
    pub checks: Vec<Check>,
    /// Quadtree levels of the flat radiosity solvers' mesh (the command line's default is
    /// 3; a tessellated sphere needs fewer for the full matrix to stay small).
    pub flat_mesh_levels: u32,
}

/// Luminous intensity of the point sources, cd.
const INTENSITY_CD: f64 = 1000.0;
/// Luminance of the area sources, cd/m².
const LUMINANCE_CD_M2: f64 = 1000.0;

/// Every case; `quick` leaves out the slowest variants (the cube at ρ = 0.95).
pub fn all(quick: bool) -> Vec<Case> {
    let mut cases = vec![
        point_over_plane(true),
        point_over_plane(false),
        area_source_in_black_room(),
        reflected_once(),
        translucent_sheet(),
        occluder(),
        meters(),
    ];
    let reflectances: &[f64] = if quick {
        &[0.05, 0.5]
    } else {
        &[0.05, 0.5, 0.95]
    };
    cases.extend(reflectances.iter().map(|&rho| interreflection_cube(rho)));
    cases.push(furnace_box());
    cases.push(furnace_sphere());
    cases.push(cornell_faces());
    cases.push(beer_canopy());
    cases
}

/// White light of `lux` lux (or cd, cd/m², lm) as radiometric RGB: `lux/683` per channel.
fn white(photometric: f64) -> Rgb {
    Rgb::splat((photometric / LUMINOUS_EFFICACY) as f32)
}

/// An empty scene named `name` with a camera at `eye` looking at `at`.
fn scene(name: &str, eye: Vec3, at: Vec3) -> Scene {
    let mut s = Scene::empty(name);
    s.camera = Camera {
        position: eye,
        look_at: at,
        ..s.camera
    };
    s
}

/// A sensor check of illuminance `expected` (lux) at the sensor just added to `scene`, direct
/// light `direct` (lux) for methods that count no reflection.
fn sensor_check(scene: &mut Scene, sensor: Sensor, expected: f64, direct: Option<f64>) -> Check {
    let label = format!("E({})", sensor.name);
    scene.sensors.push(sensor);
    Check {
        label,
        quantity: Quantity::Sensor(scene.sensors.len() - 1),
        expected,
        expected_direct: direct,
        expected_error: None,
    }
}

/// A sensor named `name` at `p` with unit normal `n`.
fn sensor(name: &str, p: Vec3, n: Vec3) -> Sensor {
    Sensor {
        name: name.to_string(),
        position: p,
        normal: n,
    }
}

/// A point source of 1000 cd two metres above a black floor; illuminance at 0°, 15°, 30°,
/// 45° and 60° from the nadir: `I₀·cos⁴θ/h²` for a Lambertian source aimed down, `I·cos³θ/h²`
/// for an isotropic one (CIE 171:2006 §5.1, 5.2).
fn point_over_plane(lambertian: bool) -> Case {
    let h = 2.0;
    let mut s = scene("point", Vec3::new(0.0, 3.0, 8.0), Vec3::ZERO);
    let black = s.add_material(Material::diffuse("black", Rgb::BLACK));
    s.add_object(
        "floor",
        Shape::Parallelogram {
            origin: Vec3::new(-10.0, 0.0, 10.0),
            edge_u: Vec3::X * 20.0,
            edge_v: Vec3::Z * -20.0,
        },
        black,
    );
    let position = Vec3::Y * h as f32;
    let intensity = white(INTENSITY_CD);
    let kind = if lambertian {
        LightKind::Lambertian {
            position,
            direction: -Vec3::Y,
            intensity,
        }
    } else {
        LightKind::Point {
            position,
            intensity,
        }
    };
    s.lights.push(Light { name: None, kind });
    let checks = [0.0f64, 15.0, 30.0, 45.0, 60.0]
        .iter()
        .map(|&degrees| {
            let theta = degrees.to_radians();
            let x = h * theta.tan();
            let e = if lambertian {
                lambertian_point(INTENSITY_CD, h, theta)
            } else {
                isotropic_point(INTENSITY_CD, h, theta)
            };
            let name = format!("θ={degrees}°");
            sensor_check(
                &mut s,
                sensor(&name, Vec3::new(x as f32, 0.0, 0.0), Vec3::Y),
                e,
                Some(e),
            )
        })
        .collect();
    Case {
        name: if lambertian {
            "lambertian-point"
        } else {
            "isotropic-point"
        }
        .to_string(),
        description: if lambertian {
            "Lambertian point source over a black plane: E = I0 cos^4(theta) / h^2"
        } else {
            "Isotropic point source over a black plane: E = I cos^3(theta) / h^2"
        },
        scene: s,
        checks,
        flat_mesh_levels: 3,
    }
}

/// The six walls of the box `[0, w] × [0, h] × [0, d]` facing inward, named
/// `floor, ceiling, west, east, north, south`, in material `m`; the ceiling left out when
/// `open_top`.
fn room(s: &mut Scene, (w, h, d): (f32, f32, f32), m: u32, open_top: bool) {
    let walls = [
        ("floor", Vec3::ZERO, Vec3::Z * d, Vec3::X * w),
        ("ceiling", Vec3::Y * h, Vec3::X * w, Vec3::Z * d),
        ("west", Vec3::ZERO, Vec3::Y * h, Vec3::Z * d),
        ("east", Vec3::X * w, Vec3::Z * d, Vec3::Y * h),
        ("north", Vec3::ZERO, Vec3::X * w, Vec3::Y * h),
        ("south", Vec3::Z * d, Vec3::Y * h, Vec3::X * w),
    ];
    for (name, origin, edge_u, edge_v) in walls {
        if open_top && name == "ceiling" {
            continue;
        }
        s.add_object(
            name,
            Shape::Parallelogram {
                origin,
                edge_u,
                edge_v,
            },
            m,
        );
    }
}

/// A 4 × 3 × 4 m black room with a 1 × 1 m Lambertian source of 1000 cd/m² in the middle of
/// the ceiling: illuminance `π·L·F` at points of the floor (parallel rectangle) and of a wall
/// (perpendicular rectangle), and the flux of the source, `π·L·A`, arriving on the surfaces
/// in all (CIE 171:2006 §5.3, 5.4).
fn area_source_in_black_room() -> Case {
    let (w, h, d) = (4.0f32, 3.0f32, 4.0f32);
    let mut s = scene("area", Vec3::new(2.0, 1.5, 3.9), Vec3::new(2.0, 1.0, 0.0));
    let black = s.add_material(Material::diffuse("black", Rgb::BLACK));
    let lamp = s.add_material(Material {
        emission: white(LUMINANCE_CD_M2),
        ..Material::diffuse("lamp", Rgb::BLACK)
    });
    room(&mut s, (w, h, d), black, false);
    let below = h - 0.001;
    s.add_object(
        "lamp",
        Shape::Parallelogram {
            origin: Vec3::new(1.5, below, 1.5),
            edge_u: Vec3::X,
            edge_v: Vec3::Z,
        },
        lamp,
    );
    let l = LUMINANCE_CD_M2;
    let c = f64::from(below);
    let mut checks = Vec::new();
    // Floor points (x, z): the lamp spans [1.5, 2.5]² above them.
    for (x, z) in [(2.0, 2.0), (1.0, 2.0), (0.5, 0.5)] {
        let e = PI * l * parallel_rectangle((1.5 - x, 2.5 - x), (1.5 - z, 2.5 - z), c);
        let p = Vec3::new(x as f32, 0.0, z as f32);
        let name = format!("floor {x},{z}");
        checks.push(sensor_check(&mut s, sensor(&name, p, Vec3::Y), e, Some(e)));
    }
    // West-wall points (y, z), facing +x.
    for (y, z) in [(1.5, 2.0), (2.5, 1.0)] {
        // The point faces +x; the lamp lies in the plane y = c, perpendicular to it, the two
        // planes meeting along the line x = 0, y = c; distance from the point to that line
        // is c − y, the lamp spans [1.5, 2.5] away from the line and [1.5 − z, 2.5 − z] along.
        let e = PI * l * perpendicular_rectangle((1.5 - z, 2.5 - z), (1.5, 2.5), c - y);
        let p = Vec3::new(0.0, y as f32, z as f32);
        let name = format!("wall {y},{z}");
        checks.push(sensor_check(&mut s, sensor(&name, p, Vec3::X), e, Some(e)));
    }
    let flux = PI * l * 1.0;
    checks.push(Check {
        label: "total flux".to_string(),
        quantity: Quantity::TotalFlux,
        expected: flux,
        expected_direct: None,
        expected_error: None,
    });
    Case {
        name: "area-source".to_string(),
        description: "Square Lambertian source in the ceiling of a black room: E = pi L F; \
                      all of its flux pi L A reaches the surfaces",
        scene: s,
        checks,
        flat_mesh_levels: 3,
    }
}

/// An open-topped 4 × 3 × 4 m black room whose floor alone reflects (ρ = 0.5), lit straight
/// from above by 1000 lux: the floor's luminous exitance is `M = ρ·E`, so a point facing
/// down at the height of the missing ceiling, or a point of a wall (both in no direct light)
/// receives `M·F` (CIE 171:2006 §5.5).
fn reflected_once() -> Case {
    let (w, h, d) = (4.0f32, 3.0f32, 4.0f32);
    let rho = 0.5;
    let illuminance = 1000.0;
    let mut s = scene(
        "reflected",
        Vec3::new(2.0, 2.5, 3.9),
        Vec3::new(2.0, 0.0, 0.0),
    );
    let black = s.add_material(Material::diffuse("black", Rgb::BLACK));
    let grey = s.add_material(Material::diffuse("floor", Rgb::splat(rho as f32)));
    room(&mut s, (w, h, d), black, true);
    s.objects[0].material = grey;
    s.lights.push(Light {
        name: None,
        kind: LightKind::Directional {
            direction: -Vec3::Y,
            irradiance: white(illuminance),
        },
    });
    let m = rho * illuminance;
    let mut checks = Vec::new();
    for (x, z) in [(2.0, 2.0), (0.5, 1.0)] {
        let e = m * parallel_rectangle((-x, 4.0 - x), (-z, 4.0 - z), f64::from(h));
        let p = Vec3::new(x as f32, h, z as f32);
        let name = format!("ceiling {x},{z}");
        checks.push(sensor_check(&mut s, sensor(&name, p, -Vec3::Y), e, None));
    }
    for (y, z) in [(0.5, 2.0), (2.0, 1.0)] {
        // A west-wall point facing +x at height y: the floor is a perpendicular rectangle
        // below it, spanning [0, 4] away from the wall and [−z, 4 − z] along it.
        let e = m * perpendicular_rectangle((-z, 4.0 - z), (0.0, 4.0), y);
        let p = Vec3::new(0.0, y as f32, z as f32);
        let name = format!("wall {y},{z}");
        checks.push(sensor_check(&mut s, sensor(&name, p, Vec3::X), e, None));
    }
    Case {
        name: "reflected-once".to_string(),
        description: "Black room, floor of reflectance rho lit uniformly: E = rho E_floor F",
        scene: s,
        checks,
        flat_mesh_levels: 3,
    }
}

/// A horizontal 4 × 4 m translucent sheet (reflectance ρ = 0.3, diffuse transmittance
/// τ = 0.5) 3 m above a black floor of the same size, lit by 1000 lux straight from above:
/// the sheet's top sends `ρ·E` up, its underside `τ·E` down, so a floor point facing up
/// receives `τ·E·F` and a point 1 m above the sheet facing down `ρ·E·F`, with `F` the form
/// factor from the point to the sheet (the floor lies in the sheet's shadow).
fn translucent_sheet() -> Case {
    let (w, h) = (4.0f32, 3.0f32);
    let (rho, tau) = (0.3, 0.5);
    let illuminance = 1000.0;
    let mut s = scene(
        "translucent",
        Vec3::new(2.0, 1.5, 9.0),
        Vec3::new(2.0, 1.5, 2.0),
    );
    let black = s.add_material(Material::diffuse("black", Rgb::BLACK));
    let sheet = s.add_material(Material {
        translucency: Rgb::splat(tau as f32),
        ..Material::diffuse("sheet", Rgb::splat(rho as f32))
    });
    for (name, y, material) in [("floor", 0.0, black), ("sheet", h, sheet)] {
        s.add_object(
            name,
            Shape::Parallelogram {
                origin: Vec3::new(0.0, y, w),
                edge_u: Vec3::X * w,
                edge_v: Vec3::NEG_Z * w,
            },
            material,
        );
    }
    s.lights.push(Light {
        name: None,
        kind: LightKind::Directional {
            direction: -Vec3::Y,
            irradiance: white(illuminance),
        },
    });
    let mut checks = Vec::new();
    for (x, z) in [(2.0, 2.0), (0.5, 1.0)] {
        let f = parallel_rectangle((-x, 4.0 - x), (-z, 4.0 - z), f64::from(h));
        let p = Vec3::new(x as f32, 0.0, z as f32);
        let name = format!("floor {x},{z}");
        checks.push(sensor_check(
            &mut s,
            sensor(&name, p, Vec3::Y),
            tau * illuminance * f,
            None,
        ));
    }
    for (x, z) in [(2.0, 2.0), (1.0, 3.5)] {
        let f = parallel_rectangle((-x, 4.0 - x), (-z, 4.0 - z), 1.0);
        let p = Vec3::new(x as f32, h + 1.0, z as f32);
        let name = format!("above {x},{z}");
        checks.push(sensor_check(
            &mut s,
            sensor(&name, p, -Vec3::Y),
            rho * illuminance * f,
            None,
        ));
    }
    Case {
        name: "translucent-sheet".to_string(),
        description: "Translucent sheet (rho, tau) lit from above over a black floor: E = tau E F below, rho E F above",
        scene: s,
        checks,
        flat_mesh_levels: 3,
    }
}

/// A 2 × 2 m wall of luminance 1000 cd/m² (the lit wall of CIE 171:2006 §5.6, as the
/// exitance it would have) seen past a black box 1 m high: points of the opposite wall and of
/// the ground see the part of the wall above the box's silhouette, `E = π·L·F(visible part)`.
fn occluder() -> Case {
    let mut s = scene(
        "occluder",
        Vec3::new(7.0, 2.0, 6.0),
        Vec3::new(2.0, 1.0, 0.0),
    );
    wall_past_a_box(&mut s);
    let (cut, l) = (silhouette_cut, LUMINANCE_CD_M2);
    let mut checks = Vec::new();
    for y in [0.75, 1.25, 1.75] {
        let x = 4.0;
        let e = PI * l * parallel_rectangle((cut(x, y) - y, 2.0 - y), (-1.0, 1.0), x);
        let name = format!("wall y={y}");
        let p = Vec3::new(x as f32, y as f32, 0.0);
        checks.push(sensor_check(&mut s, sensor(&name, p, -Vec3::X), e, Some(e)));
    }
    for x in [8.0, 12.0] {
        let e = PI * l * perpendicular_rectangle((-1.0, 1.0), (cut(x, 0.0), 2.0), x);
        let name = format!("ground x={x}");
        let p = Vec3::new(x as f32, 0.0, 0.0);
        checks.push(sensor_check(&mut s, sensor(&name, p, Vec3::Y), e, Some(e)));
    }
    Case {
        name: "occluder".to_string(),
        description: "Lit wall seen past a black box: E = pi L F of the part above the \
                      box's silhouette",
        scene: s,
        checks,
        flat_mesh_levels: 3,
    }
}

/// The near and far faces and the top of the black box of [`wall_past_a_box`], m.
const BOX_NEAR: f64 = 2.5;
const BOX_FAR: f64 = 1.5;
const BOX_TOP: f64 = 1.0;

/// CIE 171 case 5.7's geometry in `s`: a 2 × 2 m wall of luminance 1000 cd/m² at x = 0 facing
/// +x (y ∈ [0, 2], z ∈ [−1, 1]; object 0) and a black box 1 m high from x = 1.5 to 2.5 m,
/// z ∈ [−3, 3] (object 1), with no ground.
fn wall_past_a_box(s: &mut Scene) {
    let black = s.add_material(Material::diffuse("black", Rgb::BLACK));
    let lit = s.add_material(Material {
        emission: white(LUMINANCE_CD_M2),
        ..Material::diffuse("lit wall", Rgb::BLACK)
    });
    s.add_object(
        "lit wall",
        Shape::Parallelogram {
            origin: Vec3::new(0.0, 0.0, -1.0),
            edge_u: Vec3::Y * 2.0,
            edge_v: Vec3::Z * 2.0,
        },
        lit,
    );
    s.add_object(
        "box",
        Shape::Box {
            min: Vec3::new(BOX_FAR as f32, 0.0, -3.0),
            max: Vec3::new(BOX_NEAR as f32, BOX_TOP as f32, 3.0),
        },
        black,
    );
}

/// Where the box's silhouette edge (the near top edge seen from below its top, the far one
/// from above) cuts the wall of [`wall_past_a_box`], seen from height `y` at distance `x`
/// from the wall, m.
fn silhouette_cut(x: f64, y: f64) -> f64 {
    let edge = if y < BOX_TOP { BOX_NEAR } else { BOX_FAR };
    (y + (BOX_TOP - y) * x / (x - edge)).max(0.0)
}

/// The occluder case read as a user without sensors would: black one-sided 2 × 2 cm
/// measuring patches facing up, 1 mm above the ground line at 6, 8 and 12 m from the wall,
/// each about 10⁻⁷ of the scene's power. Expected: `E = π·L·F` from the patch's centre to the
/// part of the wall above the box's silhouette (the closed form at the centre differs from
/// the patch's mean by well under 0.1 %).
fn meters() -> Case {
    let mut s = scene("meters", Vec3::new(7.0, 2.0, 6.0), Vec3::new(2.0, 1.0, 0.0));
    wall_past_a_box(&mut s);
    let meter = s.add_material(Material {
        one_sided: true,
        ..Material::diffuse("meter", Rgb::BLACK)
    });
    let (height, half) = (0.001f64, 0.01f32);
    let checks = [6.0f64, 8.0, 12.0]
        .into_iter()
        .map(|x| {
            let name = format!("meter x={x}");
            s.add_object(
                &name,
                Shape::Parallelogram {
                    origin: Vec3::new(x as f32 - half, height as f32, half),
                    edge_u: Vec3::X * 2.0 * half,
                    edge_v: Vec3::NEG_Z * 2.0 * half,
                },
                meter,
            );
            let cut = silhouette_cut(x, height);
            let f = perpendicular_rectangle((-1.0, 1.0), (cut - height, 2.0 - height), x);
            Check {
                label: format!("E({name})"),
                quantity: Quantity::Surface(s.objects.len() - 1),
                expected: PI * LUMINANCE_CD_M2 * f,
                expected_direct: None,
                expected_error: None,
            }
        })
        .collect();
    Case {
        name: "meters".to_string(),
        description: "The occluder case read by 2 x 2 cm black patches on the ground: E = pi \
                      L F of the part of the wall above the box's silhouette",
        scene: s,
        checks,
        flat_mesh_levels: 3,
    }
}

/// A closed 4 m cube of uniform reflectance `rho` with an isotropic point source of 1000 cd
/// at its centre: mean direct illuminance `Φ/S` and in all `Φ/(S(1 − ρ))` (CIE 171:2006
/// §5.10).
fn interreflection_cube(rho: f64) -> Case {
    let a = 4.0f32;
    let mut s = scene("cube", Vec3::new(2.0, 2.0, 3.9), Vec3::new(2.0, 2.0, 0.0));
    let wall = s.add_material(Material::diffuse("wall", Rgb::splat(rho as f32)));
    room(&mut s, (a, a, a), wall, false);
    s.lights.push(Light {
        name: None,
        kind: LightKind::Point {
            position: Vec3::splat(a / 2.0),
            intensity: white(INTENSITY_CD),
        },
    });
    let flux = 4.0 * PI * INTENSITY_CD;
    let area = 6.0 * f64::from(a * a);
    let (direct, total) = enclosure_mean(flux, area, rho);
    Case {
        name: format!("cube ρ={rho}"),
        description: "Closed cube, isotropic point source at the centre: mean E = Phi / \
                      (S (1 - rho)), indirect rho Phi / (S (1 - rho))",
        scene: s,
        checks: vec![
            Check {
                label: "mean E".to_string(),
                quantity: Quantity::MeanIlluminance,
                expected: total,
                expected_direct: None,
                expected_error: None,
            },
            Check {
                label: "mean indirect E".to_string(),
                quantity: Quantity::MeanIndirect,
                expected: total - direct,
                expected_direct: None,
                expected_error: None,
            },
        ],
        flat_mesh_levels: 3,
    }
}

/// Reflectance of the furnaces.
const FURNACE_RHO: f64 = 0.5;

/// The sensors at the centre of a furnace, facing the six axis directions: each receives
/// `B = π·L/(1 − ρ)` in all and `π·L` straight from the walls.
fn furnace_checks(s: &mut Scene, centre: Vec3) -> Vec<Check> {
    let b = PI * LUMINANCE_CD_M2 / (1.0 - FURNACE_RHO);
    let direct = PI * LUMINANCE_CD_M2;
    [
        ("+x", Vec3::X),
        ("-x", -Vec3::X),
        ("+y", Vec3::Y),
        ("-y", -Vec3::Y),
        ("+z", Vec3::Z),
        ("-z", -Vec3::Z),
    ]
    .into_iter()
    .map(|(name, n)| sensor_check(s, sensor(name, centre, n), b, Some(direct)))
    .collect()
}

/// A material emitting 1000 cd/m² and reflecting [`FURNACE_RHO`].
fn furnace_material(two_sided: bool) -> Material {
    Material {
        emission: white(LUMINANCE_CD_M2),
        two_sided,
        ..Material::diffuse("furnace", Rgb::splat(FURNACE_RHO as f32))
    }
}

/// A closed 2 m box whose walls all emit `L` and reflect `ρ`: the radiosity is `π·L/(1 − ρ)`
/// everywhere inside, so every sensor reads it and every wall takes it over its area.
fn furnace_box() -> Case {
    let mut s = scene(
        "furnace-box",
        Vec3::new(1.0, 1.0, 1.9),
        Vec3::new(1.0, 1.0, 0.0),
    );
    let m = s.add_material(furnace_material(false));
    room(&mut s, (2.0, 2.0, 2.0), m, false);
    let mut checks = furnace_checks(&mut s, Vec3::splat(1.0));
    let b = PI * LUMINANCE_CD_M2 / (1.0 - FURNACE_RHO);
    checks.push(Check {
        label: "mean E".to_string(),
        quantity: Quantity::MeanIlluminance,
        expected: b,
        expected_direct: None,
        expected_error: None,
    });
    Case {
        name: "furnace-box".to_string(),
        description: "Closed box emitting L and reflecting rho everywhere: B = pi L / (1 - rho)",
        scene: s,
        checks,
        flat_mesh_levels: 3,
    }
}

/// A sphere of radius 1 m emitting `L` from both sides and reflecting `ρ`: inside, the
/// radiosity is `π·L/(1 − ρ)`, read by sensors at the centre (the light it sends outward is
/// lost and not checked).
fn furnace_sphere() -> Case {
    let mut s = scene("furnace-sphere", Vec3::new(0.0, 0.0, 0.9), Vec3::ZERO);
    let m = s.add_material(furnace_material(true));
    s.add_object(
        "sphere",
        Shape::Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        },
        m,
    );
    let checks = furnace_checks(&mut s, Vec3::ZERO);
    Case {
        name: "furnace-sphere".to_string(),
        description: "Inside a sphere emitting L and reflecting rho: B = pi L / (1 - rho)",
        scene: s,
        checks,
        flat_mesh_levels: 1,
    }
}

/// The built-in Cornell box with every face of every object reported on its own (the five
/// visible faces of each block, the ceiling's four pieces around the lamp), each face's
/// luminous incident flux against the light model's recording at 2·10⁸ photons, to 1 % plus
/// three of the recording's standard errors. Its coloured light is not white: the flux is
/// 683 lm/W times the luminance of the three channels.
fn cornell_faces() -> Case {
    let mut scene = cornell::scene().expect("the built-in Cornell box builds");
    for object in &mut scene.objects {
        object.per_face = true;
    }
    let checks = recorded::cornell_faces()
        .iter()
        .filter_map(|f| {
            let object = scene
                .objects
                .iter()
                .position(|o| o.name.as_deref() == Some(f.object.as_str()))?;
            Some(Check {
                label: format!("Φ({}#{})", f.object, f.face),
                quantity: Quantity::FaceFlux {
                    object: object as u32,
                    face: f.face,
                },
                expected: LUMINOUS_EFFICACY * f.incident().luminance(),
                expected_direct: None,
                expected_error: Some(LUMINOUS_EFFICACY * f.incident_error().luminance()),
            })
        })
        .collect();
    Case {
        name: "cornell-faces".to_string(),
        description: "The Cornell box face by face: each face's incident flux against the \
                      light model at 2e8 photons",
        scene,
        checks,
        flat_mesh_levels: 3,
    }
}

/// The built-in field at leaf area index 2 (300,000 leaves of 5 cm with spherical leaf
/// angles on a periodic plot) with black leaves and ground, under a sun 30° from the zenith
/// (10,000 lx on a surface facing it) and a sky of uniform luminance (5,000 lx on the open
/// ground): the ground receives what Beer's law lets through,
/// `E_sun·cos θ·exp(−L/(2 cos θ)) + E_sky·2·E₃(L/2)`. Run through the light model, and in a
/// full run through hierarchical radiosity (the plot with its far field, about two
/// minutes); `tests/field.rs` holds radiosity to the light model on smaller plots.
fn beer_canopy() -> Case {
    let lai = 2.0;
    let mut s = field(&FieldSpec {
        leaves: 300_000,
        lai: lai as f32,
        ..FieldSpec::default()
    });
    for m in &mut s.materials {
        *m = Material::diffuse(&m.name.clone(), Rgb::BLACK);
    }
    let (sun, sky) = (10_000.0, 5_000.0);
    let zenith = 30f32.to_radians();
    let toward_sun = Vec3::new(zenith.sin(), zenith.cos(), 0.0);
    s.lights = vec![
        Light {
            name: Some("sun".into()),
            kind: LightKind::Directional {
                direction: -toward_sun,
                irradiance: white(sun),
            },
        },
        Light {
            name: Some("sky".into()),
            kind: LightKind::CieSky {
                sky: CieSkyType::Uniform,
                sun: toward_sun,
                diffuse_horizontal: white(sky),
            },
        },
    ];
    let mu = f64::from(toward_sun.y);
    let expected = sun * mu * beer_beam(lai, mu) + sky * beer_uniform_sky(lai);
    let ground = s.objects.len() - 1;
    Case {
        name: "beer-canopy".to_string(),
        description: "A periodic canopy of LAI 2 (spherical leaf angles, black leaves) under \
                      a sun at 30 degrees and a uniform sky: the ground gets E_sun cos(t) \
                      exp(-L/(2 cos t)) + E_sky 2 E3(L/2) (Beer's law)",
        scene: s,
        checks: vec![Check {
            label: "E(ground)".into(),
            quantity: Quantity::Surface(ground),
            expected,
            expected_direct: None,
            expected_error: None,
        }],
        flat_mesh_levels: 3,
    }
}
