//! The TOML scene format as serde structures (documented in `docs/scene-format.md`).
//!
//! Every field that is checked after parsing is [`Spanned`] so its error can name a line.
//! Objects and lights are flat tables: each `type` uses a subset of the fields, and
//! [`ObjectEntry::shape_fields`] / [`LightEntry::kind_fields`] list which ones were given so
//! fields that do not belong to the type are reported.

use super::value::{Coords, Exact, TextureEntry, Triple};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::ops::Range;
use toml::Spanned;

/// A whole scene file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SceneFile {
    pub camera: Option<Spanned<CameraEntry>>,
    #[serde(default)]
    pub materials: BTreeMap<Spanned<String>, Spanned<MaterialEntry>>,
    #[serde(default)]
    pub objects: Vec<Spanned<ObjectEntry>>,
    #[serde(default)]
    pub lights: Vec<Spanned<LightEntry>>,
    #[serde(default)]
    pub sensors: Vec<Spanned<SensorEntry>>,
    pub periodic: Option<Spanned<PeriodicEntry>>,
    #[serde(default)]
    pub bands: Vec<Spanned<BandEntry>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BandEntry {
    pub name: Option<Spanned<String>>,
    pub from_nm: Option<Spanned<f64>>,
    pub to_nm: Option<Spanned<f64>>,
}

/// `[periodic]`: the plot that repeats in x and z (`x = [x0, x1]`, `z = [z0, z1]`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PeriodicEntry {
    pub x: Option<Spanned<[f32; 2]>>,
    pub z: Option<Spanned<[f32; 2]>>,
}

/// `[[sensors]]`: one measuring point, or a grid of them when `edge_u`, `edge_v` and
/// `count` are given.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SensorEntry {
    pub name: Option<String>,
    pub position: Option<Spanned<Coords>>,
    pub normal: Option<Spanned<Coords>>,
    pub edge_u: Option<Spanned<Coords>>,
    pub edge_v: Option<Spanned<Coords>>,
    pub count: Option<Spanned<[u32; 2]>>,
}

/// `[camera]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CameraEntry {
    pub position: Option<Spanned<Coords>>,
    pub look_at: Option<Spanned<Coords>>,
    pub up: Option<Spanned<Coords>>,
    pub fov: Option<Spanned<f32>>,
    pub width: Option<Spanned<u32>>,
    pub height: Option<Spanned<u32>>,
}

/// `[materials.NAME]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MaterialEntry {
    pub diffuse: Option<Spanned<Triple>>,
    pub diffuse_texture: Option<Spanned<TextureEntry>>,
    pub emission: Option<Spanned<Triple>>,
    pub luminance_cd_m2: Option<Spanned<f32>>,
    pub emission_color: Option<Spanned<Triple>>,
    pub emission_texture: Option<Spanned<TextureEntry>>,
    pub two_sided: Option<bool>,
    pub specular: Option<Spanned<Triple>>,
    pub shininess: Option<Spanned<f32>>,
    pub mirror: Option<Spanned<Triple>>,
    pub transmission: Option<Spanned<Triple>>,
    pub translucency: Option<Spanned<Triple>>,
    pub ior: Option<Spanned<f32>>,
    pub alpha_texture: Option<Spanned<TextureEntry>>,
    pub one_sided: Option<bool>,
    pub diffuse_spectrum: Option<Spanned<toml::Value>>,
    pub translucency_spectrum: Option<Spanned<toml::Value>>,
}

/// The `type` of an object.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum ObjectType {
    Triangle,
    Polygon,
    Quad,
    Parallelogram,
    Mesh,
    Sphere,
    Box,
    Cylinder,
    Cone,
    Frustum,
    Plane,
}

impl ObjectType {
    /// The name as written in files.
    pub fn name(self) -> &'static str {
        match self {
            ObjectType::Triangle => "triangle",
            ObjectType::Polygon => "polygon",
            ObjectType::Quad => "quad",
            ObjectType::Parallelogram => "parallelogram",
            ObjectType::Mesh => "mesh",
            ObjectType::Sphere => "sphere",
            ObjectType::Box => "box",
            ObjectType::Cylinder => "cylinder",
            ObjectType::Cone => "cone",
            ObjectType::Frustum => "frustum",
            ObjectType::Plane => "plane",
        }
    }

    /// The shape fields this type accepts.
    pub fn fields(self) -> &'static [&'static str] {
        match self {
            ObjectType::Triangle | ObjectType::Polygon | ObjectType::Quad => &["vertices", "uvs"],
            ObjectType::Parallelogram => &["origin", "edge_u", "edge_v"],
            ObjectType::Mesh => &["file", "placements"],
            ObjectType::Sphere => &["center", "radius"],
            ObjectType::Box => &["min", "max"],
            ObjectType::Cylinder => &["base", "top", "radius", "caps"],
            ObjectType::Cone => &["base", "apex", "radius", "cap"],
            ObjectType::Frustum => &["base", "top", "base_radius", "top_radius", "caps"],
            ObjectType::Plane => &["point", "normal"],
        }
    }
}

/// One step of an object's `transform` list.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum TransformStep {
    /// `{ translate = [x, y, z] }`.
    Translate(Coords),
    /// `{ rotate = { axis = [x, y, z], degrees = a } }`.
    Rotate(Rotation),
    /// `{ scale = [x, y, z] }` or `{ scale = s }`.
    Scale(Triple),
    /// `{ matrix = [[..4..], [..], [..], [..]] }`, row-major.
    Matrix(Exact<Exact<f32, 4>, 4>),
}

/// The table of a rotation step.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct Rotation {
    pub axis: Coords,
    pub degrees: f32,
}

/// `[[objects]]`: common fields plus the shape fields of every type.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ObjectEntry {
    #[serde(rename = "type")]
    pub kind: Spanned<ObjectType>,
    pub name: Option<String>,
    pub material: Option<Spanned<String>>,
    pub per_face: Option<bool>,
    pub transform: Option<Spanned<Vec<Spanned<TransformStep>>>>,
    pub vertices: Option<Spanned<Vec<Coords>>>,
    pub uvs: Option<Spanned<Vec<Exact<f32, 2>>>>,
    pub origin: Option<Spanned<Coords>>,
    pub edge_u: Option<Spanned<Coords>>,
    pub edge_v: Option<Spanned<Coords>>,
    pub file: Option<Spanned<String>>,
    pub center: Option<Spanned<Coords>>,
    pub radius: Option<Spanned<f32>>,
    pub min: Option<Spanned<Coords>>,
    pub max: Option<Spanned<Coords>>,
    pub base: Option<Spanned<Coords>>,
    pub top: Option<Spanned<Coords>>,
    pub apex: Option<Spanned<Coords>>,
    pub base_radius: Option<Spanned<f32>>,
    pub top_radius: Option<Spanned<f32>>,
    pub caps: Option<Spanned<bool>>,
    pub cap: Option<Spanned<bool>>,
    pub point: Option<Spanned<Coords>>,
    pub normal: Option<Spanned<Coords>>,
    pub placements: Option<Spanned<toml::Value>>,
}

impl ObjectEntry {
    /// The shape fields present, with the span of each value.
    pub fn shape_fields(&self) -> Vec<(&'static str, Range<usize>)> {
        let mut out = Vec::new();
        let mut add = |name: &'static str, span: Option<Range<usize>>| {
            if let Some(span) = span {
                out.push((name, span));
            }
        };
        add("vertices", self.vertices.as_ref().map(Spanned::span));
        add("uvs", self.uvs.as_ref().map(Spanned::span));
        add("origin", self.origin.as_ref().map(Spanned::span));
        add("edge_u", self.edge_u.as_ref().map(Spanned::span));
        add("edge_v", self.edge_v.as_ref().map(Spanned::span));
        add("file", self.file.as_ref().map(Spanned::span));
        add("center", self.center.as_ref().map(Spanned::span));
        add("radius", self.radius.as_ref().map(Spanned::span));
        add("min", self.min.as_ref().map(Spanned::span));
        add("max", self.max.as_ref().map(Spanned::span));
        add("base", self.base.as_ref().map(Spanned::span));
        add("top", self.top.as_ref().map(Spanned::span));
        add("apex", self.apex.as_ref().map(Spanned::span));
        add("base_radius", self.base_radius.as_ref().map(Spanned::span));
        add("top_radius", self.top_radius.as_ref().map(Spanned::span));
        add("caps", self.caps.as_ref().map(Spanned::span));
        add("cap", self.cap.as_ref().map(Spanned::span));
        add("point", self.point.as_ref().map(Spanned::span));
        add("normal", self.normal.as_ref().map(Spanned::span));
        add("placements", self.placements.as_ref().map(Spanned::span));
        out
    }
}

/// The `type` of a light.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum LightType {
    Point,
    Lambertian,
    Spot,
    Directional,
    Sky,
    #[serde(rename = "cie_sky")]
    CieSky,
    Day,
}

impl LightType {
    /// The name as written in files.
    pub fn name(self) -> &'static str {
        match self {
            LightType::Point => "point",
            LightType::Lambertian => "lambertian",
            LightType::Spot => "spot",
            LightType::Directional => "directional",
            LightType::Sky => "sky",
            LightType::CieSky => "cie_sky",
            LightType::Day => "day",
        }
    }

    /// The fields this type accepts besides `type` and `name`.
    pub fn fields(self) -> Vec<&'static str> {
        let amount = ["intensity", "intensity_cd", "flux_lm", "color", "spectrum"];
        let aimed = [&["position", "direction", "look_at"][..], &amount[..]].concat();
        match self {
            LightType::Point => [&["position"][..], &amount[..]].concat(),
            LightType::Lambertian => aimed,
            LightType::Spot => [&aimed[..], &["inner_degrees", "outer_degrees"][..]].concat(),
            LightType::Directional => dated(
                &[
                    "direction",
                    "irradiance",
                    "illuminance_lux",
                    "color",
                    "spectrum",
                ],
                true,
            ),
            LightType::Sky => vec!["radiance", "luminance_cd_m2", "color", "spectrum"],
            LightType::CieSky => dated(
                &[
                    "sky_type",
                    "sun_direction",
                    "diffuse_horizontal",
                    "illuminance_lux",
                    "color",
                    "spectrum",
                ],
                true,
            ),
            LightType::Day => dated(&["sky_type", "states", "spectrum", "sky_spectrum"], false),
        }
    }
}

/// `fields` and the fields that place the sun by date and site, `time` among them if asked.
fn dated(fields: &[&'static str], time: bool) -> Vec<&'static str> {
    let time: &[&str] = if time { &["date", "time"] } else { &["date"] };
    [fields, time, &SITE[..]].concat()
}

/// The fields that place the sun at a site, besides its date and time.
const SITE: [&str; 7] = [
    "utc_offset_hours",
    "latitude_deg",
    "longitude_deg",
    "elevation_m",
    "pressure_mbar",
    "temperature_c",
    "delta_t_s",
];

/// `[[lights]]`: the fields of every light type.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct LightEntry {
    #[serde(rename = "type")]
    pub kind: Spanned<LightType>,
    pub name: Option<String>,
    pub position: Option<Spanned<Coords>>,
    pub direction: Option<Spanned<Coords>>,
    pub look_at: Option<Spanned<Coords>>,
    pub intensity: Option<Spanned<Triple>>,
    pub inner_degrees: Option<Spanned<f32>>,
    pub outer_degrees: Option<Spanned<f32>>,
    pub irradiance: Option<Spanned<Triple>>,
    pub radiance: Option<Spanned<Triple>>,
    pub intensity_cd: Option<Spanned<f32>>,
    pub flux_lm: Option<Spanned<f32>>,
    pub illuminance_lux: Option<Spanned<f32>>,
    pub luminance_cd_m2: Option<Spanned<f32>>,
    pub color: Option<Spanned<Triple>>,
    pub sky_type: Option<Spanned<i64>>,
    pub sun_direction: Option<Spanned<Coords>>,
    pub diffuse_horizontal: Option<Spanned<Triple>>,
    pub date: Option<Spanned<String>>,
    pub time: Option<Spanned<String>>,
    pub utc_offset_hours: Option<Spanned<f64>>,
    pub latitude_deg: Option<Spanned<f64>>,
    pub longitude_deg: Option<Spanned<f64>>,
    pub elevation_m: Option<Spanned<f64>>,
    pub pressure_mbar: Option<Spanned<f64>>,
    pub temperature_c: Option<Spanned<f64>>,
    pub delta_t_s: Option<Spanned<f64>>,
    pub states: Option<Spanned<Vec<Spanned<DayStateEntry>>>>,
    pub spectrum: Option<Spanned<toml::Value>>,
    pub sky_spectrum: Option<Spanned<toml::Value>>,
}

/// One state of a `day` light: `{ time = "HH:MM", direct_normal = …, diffuse_horizontal = … }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct DayStateEntry {
    pub time: Option<Spanned<String>>,
    pub direct_normal: Option<Spanned<Triple>>,
    pub diffuse_horizontal: Option<Spanned<Triple>>,
}

impl LightEntry {
    /// The type-specific fields present, with the span of each value.
    pub fn kind_fields(&self) -> Vec<(&'static str, Range<usize>)> {
        let triple = |v: &Option<Spanned<Triple>>| v.as_ref().map(Spanned::span);
        let coords = |v: &Option<Spanned<Coords>>| v.as_ref().map(Spanned::span);
        let number = |v: &Option<Spanned<f32>>| v.as_ref().map(Spanned::span);
        let text = |v: &Option<Spanned<String>>| v.as_ref().map(Spanned::span);
        let real = |v: &Option<Spanned<f64>>| v.as_ref().map(Spanned::span);
        let spectrum = |v: &Option<Spanned<toml::Value>>| v.as_ref().map(Spanned::span);
        [
            ("position", coords(&self.position)),
            ("direction", coords(&self.direction)),
            ("look_at", coords(&self.look_at)),
            ("intensity", triple(&self.intensity)),
            ("inner_degrees", number(&self.inner_degrees)),
            ("outer_degrees", number(&self.outer_degrees)),
            ("irradiance", triple(&self.irradiance)),
            ("radiance", triple(&self.radiance)),
            ("intensity_cd", number(&self.intensity_cd)),
            ("flux_lm", number(&self.flux_lm)),
            ("illuminance_lux", number(&self.illuminance_lux)),
            ("luminance_cd_m2", number(&self.luminance_cd_m2)),
            ("color", triple(&self.color)),
            ("sky_type", self.sky_type.as_ref().map(Spanned::span)),
            ("sun_direction", coords(&self.sun_direction)),
            ("diffuse_horizontal", triple(&self.diffuse_horizontal)),
            ("date", text(&self.date)),
            ("time", text(&self.time)),
            ("utc_offset_hours", real(&self.utc_offset_hours)),
            ("latitude_deg", real(&self.latitude_deg)),
            ("longitude_deg", real(&self.longitude_deg)),
            ("elevation_m", real(&self.elevation_m)),
            ("pressure_mbar", real(&self.pressure_mbar)),
            ("temperature_c", real(&self.temperature_c)),
            ("delta_t_s", real(&self.delta_t_s)),
            ("states", self.states.as_ref().map(Spanned::span)),
            ("spectrum", spectrum(&self.spectrum)),
            ("sky_spectrum", spectrum(&self.sky_spectrum)),
        ]
        .into_iter()
        .filter_map(|(name, span)| span.map(|span| (name, span)))
        .collect()
    }
}
