//! One solution as the viewer serves it: the scene's camera and report (JSON), the lit mesh,
//! the lightmaps of its textured surfaces and the links (binary), and readings along rays. Made once per solution, read by every
//! request until the next solution replaces it.

use anyhow::{Context, Result};
use serde::Serialize;
use std::sync::{Arc, OnceLock};
use strahl::method::{
    LUMINOUS_EFFICACY, LitMesh, Probe, Ray, RoundSolution, Shading, SolvedRadiosity,
};
use strahl::report::Report;
use strahl::scene::{ALPHA_CUTOFF, Scene, Texture, TextureId, Wrap};

/// The share of the surface area whose illuminance the false-colour range holds.
const TOP_QUANTILE: f64 = 0.99;

/// Most links served for display (a larger solution's links are served by an even stride
/// through them: a browser draws a few hundred thousand lines at interactive rates).
pub const MAX_LINKS: usize = 200_000;

/// Which solution of a solve a snapshot is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Stage {
    /// The solution between two rounds of a solve under way, each leaf lit flat (no report,
    /// no readings: picks read the latest whole solution).
    Round,
    /// A quick, coarser solve shown first after the scene changed.
    Preview,
    /// The solve at the settings asked for, its report still the solution's own while the
    /// final gather at the reported surfaces measures them anew (only when it does).
    Solved,
    /// The solve at the settings asked for, with its report.
    Final,
}

/// One solution, ready to serve.
pub struct Snapshot {
    /// `/api/scene`: the camera, the report and what can be moved, JSON.
    pub scene: Vec<u8>,
    /// `/api/mesh`: the lit mesh, binary ([`mesh_bytes`]).
    pub mesh: Vec<u8>,
    /// `/api/lightmaps`: the textured surfaces' lightmaps and where the mesh lies in them,
    /// binary ([`lightmap_bytes`]; none between rounds).
    pub lightmaps: Vec<u8>,
    /// `/api/links`: the links, binary ([`link_bytes`]; none between rounds).
    pub links: Vec<u8>,
    /// The solution and its probe, made once, read by picks (none between rounds); shared
    /// with the snapshot of the same solution whose report was gathered.
    readings: Option<Arc<Readings>>,
    objects: Vec<String>,
    /// The moves it was solved with, counted from the start.
    moves: u64,
    /// The top of the false-colour range, lux ([`mesh_bytes`]), and the links served and in
    /// the solution.
    brightest: f32,
    links_counted: (usize, usize),
    /// The version whose mesh, lightmaps and links these are.
    mesh_version: u64,
}

self_cell::self_cell!(
    /// A solution and the probe that reads it along rays (which holds a lookup structure
    /// over its leaves: built at the first pick, then kept — a solution shown is not always
    /// read, and on the Cornell box the structure costs the final solution 20–26 ms).
    struct Readings {
        owner: SolvedRadiosity,
        #[not_covariant]
        dependent: LazyProbe,
    }
);

/// The probe of a [`Readings`] solution, once a pick asks for it, and how it reads.
struct LazyProbe<'s> {
    probe: OnceLock<Probe<'s>>,
    shading: Shading,
}

/// What a snapshot says of itself besides the scene.
struct About<'a> {
    version: u64,
    mesh_version: u64,
    moves: u64,
    stage: Stage,
    summary: String,
    report: Option<&'a Report>,
    links: (usize, usize),
}

/// The camera and report the page starts from.
#[derive(Serialize)]
struct SceneInfo<'a> {
    name: &'a str,
    /// Counts the solutions served, from 1.
    version: u64,
    /// The version whose mesh, lightmaps and links `/api/mesh`, `/api/lightmaps` and
    /// `/api/links` serve with it (an earlier one when only the report changed).
    mesh_version: u64,
    /// The moves it was solved with, counted from the start.
    moves: u64,
    /// Preview or final.
    stage: Stage,
    camera: CameraInfo,
    summary: String,
    /// The report (none between rounds).
    report: Option<&'a Report>,
    false_color: FalseColorInfo,
    /// What `/api/move` can move: objects, then placed lights.
    movable: Vec<String>,
    /// Where each of `movable` is (`Scene::movable_positions`, scene units), for a move to a
    /// position; `None` where it has none (an unbounded object).
    positions: Vec<Option<[f32; 3]>>,
    /// Object names by index (the links' ends name objects by index).
    objects: &'a [String],
    /// Links served for display and links in the solution.
    links: (usize, usize),
}

/// The false-colour scale of the page, as `strahl render --false-color` draws it.
#[derive(Serialize)]
struct FalseColorInfo {
    /// Position on the scale (0–1) and sRGB colour (0–255) of each stop.
    stops: Vec<(f32, [u8; 3])>,
    /// The illuminance at the scale's ends, lux: 0 to what 99 % of the area stays at or
    /// below, rounded up (brighter places take the top colour).
    range: (f32, f32),
}

/// The scene camera, scene units and degrees.
#[derive(Serialize)]
struct CameraInfo {
    position: [f32; 3],
    look_at: [f32; 3],
    up: [f32; 3],
    fov_degrees: f32,
}

/// What a pick answers.
#[derive(Serialize)]
pub struct PickInfo {
    /// Whether the ray met a surface (the rest is absent when it did not).
    hit: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    object: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    point: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    illuminance_lux: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    luminance_cd_m2: Option<f64>,
}

impl Snapshot {
    /// Solution `version` of the `stage`, after `moves` moves: `solved` with its `report`,
    /// read by `shading`.
    pub fn new(
        version: u64,
        moves: u64,
        stage: Stage,
        solved: SolvedRadiosity,
        report: &Report,
        shading: Shading,
    ) -> Result<Self> {
        // Textures lit by the solution: each textured surface's lightmap, baked at its
        // texture's resolution (only where the scene has textures: the bake needs a lookup
        // over the leaves).
        let lit = solved.lit_mesh(!solved.world().scene.textures.is_empty());
        let lightmaps = lightmap_bytes(&lit, &solved.world().scene.textures);
        let links = link_bytes(&solved);
        let counted = solved.solution.link_segments.len();
        let links_counted = (counted.min(MAX_LINKS), counted);
        let (mesh, brightest) = mesh_bytes(&lit);
        let about = About {
            version,
            mesh_version: version,
            moves,
            stage,
            summary: solved.summary(),
            report: Some(report),
            links: links_counted,
        };
        let (scene, objects) = described(&solved.world().scene, brightest, about)?;
        Ok(Snapshot {
            scene,
            mesh,
            lightmaps,
            links,
            readings: Some(Arc::new(Readings::new(solved, |_| LazyProbe {
                probe: OnceLock::new(),
                shading,
            }))),
            objects,
            moves,
            brightest,
            links_counted,
            mesh_version: version,
        })
    }

    /// This solution (stage [`Stage::Solved`]) with `report`, its final-gathered report, and
    /// the solve's phrase `summary`, as version `version` of the final stage: the same mesh,
    /// lightmaps, links and readings. Refused for a solution between rounds.
    pub fn with_report(&self, version: u64, report: &Report, summary: String) -> Result<Self> {
        let readings = self.readings.clone().context("a solution between rounds")?;
        let about = About {
            version,
            mesh_version: self.mesh_version,
            moves: self.moves,
            stage: Stage::Final,
            summary,
            report: Some(report),
            links: self.links_counted,
        };
        let scene = &readings.borrow_owner().world().scene;
        let (scene, objects) = described(scene, self.brightest, about)?;
        Ok(Snapshot {
            scene,
            mesh: self.mesh.clone(),
            lightmaps: self.lightmaps.clone(),
            links: self.links.clone(),
            readings: Some(readings),
            objects,
            moves: self.moves,
            brightest: self.brightest,
            links_counted: self.links_counted,
            mesh_version: self.mesh_version,
        })
    }

    /// The solution between rounds `round` of a solve of `scene` (after `moves` moves), as
    /// version `version`.
    pub fn round(version: u64, moves: u64, scene: &Scene, round: &RoundSolution) -> Result<Self> {
        let about = About {
            version,
            mesh_version: version,
            moves,
            stage: Stage::Round,
            summary: format!(
                "round {}: {} links, {} leaves, change {:.3e}",
                round.round, round.links, round.leaves, round.change
            ),
            report: None,
            links: (0, 0),
        };
        let lightmaps = lightmap_bytes(&round.mesh, &scene.textures);
        let (mesh, brightest) = mesh_bytes(&round.mesh);
        let (scene, objects) = described(scene, brightest, about)?;
        Ok(Snapshot {
            scene,
            mesh,
            lightmaps,
            links: 0u32.to_le_bytes().to_vec(),
            readings: None,
            objects,
            moves,
            brightest,
            links_counted: (0, 0),
            mesh_version: version,
        })
    }

    /// The moves it was solved with, counted from the start.
    pub fn moves(&self) -> u64 {
        self.moves
    }

    /// The version whose mesh, lightmaps and links it serves.
    pub fn mesh_version(&self) -> u64 {
        self.mesh_version
    }

    /// Whether picks can read it (false between rounds).
    pub fn readable(&self) -> bool {
        self.readings.is_some()
    }

    /// The solution it shows (none between rounds).
    pub fn solved(&self) -> Option<&SolvedRadiosity> {
        self.readings.as_ref().map(|r| r.borrow_owner())
    }

    /// What the ray from `origin` along the unit `direction` meets.
    pub fn pick(&self, ray: &Ray) -> PickInfo {
        let hit = self.readings.as_ref().and_then(|readings| {
            readings.with_dependent(|solved, lazy| {
                lazy.probe
                    .get_or_init(|| solved.probe(lazy.shading))
                    .at(ray)
            })
        });
        match hit {
            None => PickInfo {
                hit: false,
                object: None,
                point: None,
                illuminance_lux: None,
                luminance_cd_m2: None,
            },
            Some(hit) => PickInfo {
                hit: true,
                object: self.objects.get(hit.object as usize).cloned(),
                point: Some(hit.point.to_array()),
                illuminance_lux: Some(hit.illuminance),
                luminance_cd_m2: Some(hit.luminance),
            },
        }
    }
}

/// `/api/scene` of `scene` (its mesh's false-colour range topped at `brightest` lux),
/// described by `about`, and the object names by index.
fn described(scene: &Scene, brightest: f32, about: About) -> Result<(Vec<u8>, Vec<String>)> {
    let objects: Vec<String> = (0..scene.objects.len())
        .map(|k| scene.object_name(k))
        .collect();
    let c = &scene.camera;
    let info = SceneInfo {
        name: &scene.name,
        version: about.version,
        mesh_version: about.mesh_version,
        moves: about.moves,
        stage: about.stage,
        camera: CameraInfo {
            position: c.position.to_array(),
            look_at: c.look_at.to_array(),
            up: c.up.to_array(),
            fov_degrees: c.fov_degrees,
        },
        summary: about.summary,
        report: about.report,
        false_color: FalseColorInfo {
            stops: strahl::image::STOPS.to_vec(),
            range: (0.0, strahl::image::nice_ceiling(brightest)),
        },
        movable: scene.movable_names(),
        positions: (scene.movable_positions().iter())
            .map(|p| p.map(|p| p.to_array()))
            .collect(),
        objects: &objects,
        links: about.links,
    };
    Ok((serde_json::to_vec(&info)?, objects))
}

/// The lit mesh as the page reads it, little-endian: the vertex count `V` and triangle count
/// `T` (u32 each), `V` positions (3 × f32, scene units), `V` radiances (3 × f32, the
/// radiosity leaving the vertex over π, W·sr⁻¹·m⁻²), `V` illuminances (f32, lux on the
/// vertex's side), `T` triangles (3 × u32 vertex indices, counter-clockwise from the side
/// the light leaves). Each side of a patch is its own polygon, so both sides show their
/// own light. Also returns the illuminance that 99 % of the surface area stays at or below,
/// lux (the top of the false-colour range: the small, bright patches beside a lamp would
/// squeeze the rest into the scale's lowest colours).
fn mesh_bytes(lit: &LitMesh) -> (Vec<u8>, f32) {
    let triangles: Vec<[u32; 3]> = triangles(lit).map(|(t, _)| t).collect();
    let lux: Vec<f32> = lit
        .irradiance
        .iter()
        .map(|e| (LUMINOUS_EFFICACY * e.luminance()).max(0.0) as f32)
        .collect();
    let mut out = Vec::with_capacity(8 + lit.positions.len() * 28 + triangles.len() * 12);
    out.extend((lit.positions.len() as u32).to_le_bytes());
    out.extend((triangles.len() as u32).to_le_bytes());
    for p in &lit.positions {
        p.to_array()
            .iter()
            .for_each(|v| out.extend(v.to_le_bytes()));
    }
    for b in &lit.radiosity {
        b.to_f32()
            .to_array()
            .iter()
            .for_each(|v| out.extend((v / std::f32::consts::PI).to_le_bytes()));
    }
    lux.iter().for_each(|v| out.extend(v.to_le_bytes()));
    for t in &triangles {
        t.iter().for_each(|i| out.extend(i.to_le_bytes()));
    }
    // Each vertex stands for a third of its triangles' area (every polygon has its own).
    let mut weight = vec![0.0f64; lux.len()];
    for t in &triangles {
        let [a, b, c] = t.map(|i| lit.positions[i as usize]);
        let third = f64::from((b - a).cross(c - a).length()) / 6.0;
        t.iter().for_each(|&i| weight[i as usize] += third);
    }
    let mut order: Vec<usize> = (0..lux.len()).collect();
    order.sort_by(|&i, &j| lux[i].total_cmp(&lux[j]));
    let total: f64 = weight.iter().sum();
    let mut below = 0.0;
    let top = order
        .iter()
        .find(|&&i| {
            below += weight[i];
            below >= TOP_QUANTILE * total
        })
        .or(order.last())
        .map_or(0.0, |&i| lux[i]);
    (out, top)
}

/// The triangles of `lit`'s polygons (fans from each polygon's first corner), in the order
/// [`mesh_bytes`] and [`lightmap_bytes`] serve them, with the index of each one's polygon.
fn triangles(lit: &LitMesh) -> impl Iterator<Item = ([u32; 3], usize)> + '_ {
    lit.polygons
        .iter()
        .enumerate()
        .flat_map(|(k, p)| (1..p.len() - 1).map(move |j| ([p[0], p[j], p[j + 1]], k)))
}

/// The lightmaps of `lit`'s textured surfaces as the page reads them, little-endian: the
/// count `S` of surfaces (u32); when `S > 0`, the vertex and triangle counts of the mesh they
/// go with (u32 each: the page checks them against the mesh it drew), per vertex of
/// [`mesh_bytes`] its place in its surface's lightmap (2 × f32; `(0, 0)` off lightmapped surfaces), per triangle the surface
/// it lies on (i32; −1: shown by its corners' radiance), then per surface its width `W` and
/// height `H` (u32 each) and `W × H` texels (3 × f32, linear radiance, W·sr⁻¹·m⁻², the
/// bottom row first, so that the texture coordinate `(0, 0)` is the first texel).
///
/// Then the cut-outs: per vertex its material's texture coordinates (2 × f32), per surface
/// the cut-out mask its material's alpha texture makes (i32, an index into the masks; −1:
/// none), the count `M` of masks (u32) and per mask its width and height (u32 each), its
/// wrapping (u32: 0 repeat, 1 clamp) and a byte per texel, 1 where the surface is present
/// (alpha at least [`ALPHA_CUTOFF`], as ray queries test it) and 0 where it is cut away,
/// the bottom row first. Each alpha texture is sent once, whatever the surfaces using it.
fn lightmap_bytes(lit: &LitMesh, textures: &[Texture]) -> Vec<u8> {
    let mut out = Vec::new();
    out.extend((lit.surfaces.len() as u32).to_le_bytes());
    if lit.surfaces.is_empty() {
        return out;
    }
    let floats = |out: &mut Vec<u8>, values: &[f32]| {
        values.iter().for_each(|v| out.extend(v.to_le_bytes()));
    };
    out.extend((lit.positions.len() as u32).to_le_bytes());
    out.extend((triangles(lit).count() as u32).to_le_bytes());
    for uv in &lit.lightmap_texcoords {
        floats(&mut out, &uv.to_array());
    }
    for (_, polygon) in triangles(lit) {
        let surface = lit.polygon_surface[polygon].map_or(-1, |s| s as i32);
        out.extend(surface.to_le_bytes());
    }
    for surface in &lit.surfaces {
        let map = &surface.lightmap;
        let (w, h) = (map.width(), map.height());
        out.extend(w.to_le_bytes());
        out.extend(h.to_le_bytes());
        for row in (0..h as usize).rev() {
            let texels = &map.pixels()[row * w as usize..(row + 1) * w as usize];
            for t in texels {
                floats(&mut out, &[t.r, t.g, t.b]);
            }
        }
    }
    for uv in &lit.texcoords {
        floats(&mut out, &uv.to_array());
    }
    let mut masks: Vec<TextureId> = Vec::new();
    for surface in &lit.surfaces {
        let mask = surface
            .alpha_texture
            .filter(|&t| (t as usize) < textures.len())
            .map_or(-1, |t| match masks.iter().position(|&m| m == t) {
                Some(k) => k as i32,
                None => {
                    masks.push(t);
                    masks.len() as i32 - 1
                }
            });
        out.extend(mask.to_le_bytes());
    }
    out.extend((masks.len() as u32).to_le_bytes());
    for &t in &masks {
        let texture = &textures[t as usize];
        let (w, h) = (texture.width, texture.height);
        out.extend(w.to_le_bytes());
        out.extend(h.to_le_bytes());
        out.extend(u32::from(texture.wrap == Wrap::Clamp).to_le_bytes());
        for y in (0..i64::from(h)).rev() {
            out.extend((0..i64::from(w)).map(|x| u8::from(texture.texel(x, y)[3] >= ALPHA_CUTOFF)));
        }
    }
    out
}

/// The links of a hierarchical solution as the page draws them, little-endian: the count
/// `N` (u32), then per link the receiver's and the emitter's centre (3 × f32 each, scene
/// units), the receiver's and the emitter's object index (i32 each; −1 for a cluster of
/// patches or a light), the link's level (i32: the quadtree depth of its finer patch, 0
/// between root patches; −1 for a link with a cluster at an end) and the light it brings
/// (i32: the light's index for a link from a lamp, the sun or a sky; −1 otherwise). At most
/// [`MAX_LINKS`], taken at an even stride; none for the other solvers.
fn link_bytes(solved: &SolvedRadiosity) -> Vec<u8> {
    /// Bytes of one link.
    const LINK_BYTES: usize = 40;
    let all = &solved.solution.link_segments;
    let stride = all.len().div_ceil(MAX_LINKS).max(1);
    let shown: Vec<_> = all.iter().step_by(stride).collect();
    let mut out = Vec::with_capacity(4 + LINK_BYTES * shown.len());
    out.extend((shown.len() as u32).to_le_bytes());
    let object = |o: Option<u32>| o.map_or(-1, |o| o as i32);
    for link in shown {
        for p in [link.receiver, link.emitter] {
            p.as_vec3()
                .to_array()
                .iter()
                .for_each(|v| out.extend(v.to_le_bytes()));
        }
        out.extend(object(link.receiver_object).to_le_bytes());
        out.extend(object(link.emitter_object).to_le_bytes());
        out.extend(object(link.level).to_le_bytes());
        out.extend(object(link.light).to_le_bytes());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Vec2, Vec3};
    use strahl::method::{Film, LightmappedSurface, Rgb, Rgb64};

    #[test]
    fn lightmaps_are_served_with_each_vertex_place_and_each_triangle_surface_bottom_row_first() {
        let mut lit = LitMesh::default();
        let b = [Rgb64::splat(1.0); 4];
        let square = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 0.0, 1.0), Vec3::Z];
        // An untextured triangle, then a lightmapped square (two triangles).
        lit.push_polygon(0, &square[..3], Vec3::Y, (&b[..3], &b[..3]));
        let uv = [Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y];
        lit.push_mapped_polygon(1, &square, Vec3::Y, (&b, &b), (&uv, &uv), Some(0));
        let top = Rgb::new(1.0, 2.0, 3.0);
        let bottom = Rgb::new(4.0, 5.0, 6.0);
        lit.surfaces.push(LightmappedSurface {
            name: "square".into(),
            base_texture: None,
            alpha_texture: None,
            lightmap: Film::from_pixels(1, 2, vec![top, bottom]).unwrap(),
        });
        let bytes = lightmap_bytes(&lit, &[]);
        let word = |k: usize| u32::from_le_bytes(bytes[4 * k..4 * k + 4].try_into().unwrap());
        let float = |k: usize| f32::from_le_bytes(bytes[4 * k..4 * k + 4].try_into().unwrap());
        // One surface, for 7 vertices and 3 triangles.
        assert_eq!((word(0), word(1), word(2)), (1, 7, 3));
        // The vertices' places: none for the triangle's three, then the square's corners.
        let places: Vec<f32> = (3..17).map(float).collect();
        assert_eq!(places[..6], [0.0; 6]);
        assert_eq!(places[6..], [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0]);
        // The triangles' surfaces.
        let surfaces: Vec<i32> = (17..20).map(|k| word(k) as i32).collect();
        assert_eq!(surfaces, [-1, 0, 0]);
        // The lightmap: 1 × 2, its bottom row first.
        assert_eq!((word(20), word(21)), (1, 2));
        let texels: Vec<f32> = (22..28).map(float).collect();
        assert_eq!(texels, [4.0, 5.0, 6.0, 1.0, 2.0, 3.0]);
        // The material's texture coordinates (the same as the lightmap's here), no mask.
        let material: Vec<f32> = (28..42).map(float).collect();
        assert_eq!(material, places);
        assert_eq!((word(42) as i32, word(43)), (-1, 0));
        assert_eq!(bytes.len(), 44 * 4);
        // Without textured surfaces: the count alone.
        assert_eq!(lightmap_bytes(&LitMesh::default(), &[]), 0u32.to_le_bytes());

        // Two surfaces cut by one alpha texture (2 × 2: alpha 0.4 and 0.6 in its top row,
        // 0.5 and 0.1 in its bottom row) send it once, as a mask, its bottom row first.
        let alpha = [[0.4, 0.6], [0.5, 0.1]];
        let textures = [Texture::from_fn("leaf", 2, 2, |x, y| {
            [1.0, 1.0, 1.0, alpha[y as usize][x as usize]]
        })];
        lit.surfaces[0].alpha_texture = Some(0);
        lit.surfaces.push(lit.surfaces[0].clone());
        let bytes = lightmap_bytes(&lit, &textures);
        let word = |k: usize| u32::from_le_bytes(bytes[4 * k..4 * k + 4].try_into().unwrap());
        // After the header, places and surfaces (20 words), the two 1 × 2 lightmaps (8 words
        // each) and the material's places (14 words): both surfaces take mask 0, one mask of
        // 2 × 2 texels, repeating.
        assert_eq!((word(50), word(51)), (0, 0));
        assert_eq!((word(52), word(53), word(54), word(55)), (1, 2, 2, 0));
        assert_eq!(bytes[56 * 4..], [1, 0, 0, 1]);
    }

    #[test]
    fn a_round_is_served_flat_without_report_links_or_readings() {
        let scene = strahl::scene::open("cornell", &Default::default()).unwrap();
        let mut mesh = LitMesh::default();
        let square = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 0.0, 1.0), Vec3::Z];
        let b = [Rgb64::splat(std::f64::consts::PI); 4];
        mesh.push_polygon(0, &square, Vec3::Y, (&b, &b));
        let round = RoundSolution {
            round: 3,
            links: 10,
            leaves: 1,
            change: 1e-3,
            mesh,
        };
        let snapshot = Snapshot::round(7, 2, &scene, &round).unwrap();
        let info: serde_json::Value = serde_json::from_slice(&snapshot.scene).unwrap();
        assert_eq!(info["stage"], "round");
        assert_eq!(
            (info["version"].as_u64(), info["moves"].as_u64()),
            (Some(7), Some(2))
        );
        assert!(info["report"].is_null());
        assert_eq!(
            info["summary"],
            "round 3: 10 links, 1 leaves, change 1.000e-3"
        );
        assert_eq!(
            info["movable"].as_array().unwrap().len(),
            scene.objects.len()
        );
        // One square: four vertices, two triangles, each vertex showing B/π = 1.
        let word =
            |k: usize| u32::from_le_bytes(snapshot.mesh[4 * k..4 * k + 4].try_into().unwrap());
        assert_eq!((word(0), word(1)), (4, 2));
        let radiance = f32::from_le_bytes(snapshot.mesh[8 + 48..8 + 52].try_into().unwrap());
        assert!((radiance - 1.0).abs() < 1e-6, "{radiance}");
        assert_eq!(snapshot.links, 0u32.to_le_bytes());
        assert!(!snapshot.readable());
        let ray = Ray::new(Vec3::new(0.5, 1.0, 0.5), Vec3::NEG_Y);
        assert!(!snapshot.pick(&ray).hit);
    }

    #[test]
    fn a_final_solve_shown_before_its_gather_keeps_its_mesh_when_its_report_comes() {
        use std::sync::Arc;
        use strahl::method::{AccelKind, Cancel, Method, NoProgress, RadiositySettings, World};
        let scene = strahl::scene::open("cornell", &Default::default()).unwrap();
        let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
        let settings = RadiositySettings::default();
        let method = Method::Radiosity(settings.without_surface_gather());
        let outcome = strahl::method::run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
        let solved = outcome.radiosity.unwrap();
        let own = Report::new("cornell", &solved.measurement());
        let shown = Snapshot::new(5, 1, Stage::Solved, solved, &own, Shading::Smooth).unwrap();
        let solution = shown.solved().unwrap();
        let (gathered, phrase) = solution
            .gathered_measurement(settings.surface_gather, 0, &NoProgress, &Cancel::new())
            .unwrap();
        let report = Report::new("cornell", &gathered);
        let summary = solution.summary() + &phrase;
        let last = shown.with_report(6, &report, summary).unwrap();
        let info: serde_json::Value = serde_json::from_slice(&last.scene).unwrap();
        assert_eq!(info["stage"], "final");
        assert_eq!(
            (info["version"].as_u64(), info["mesh_version"].as_u64()),
            (Some(6), Some(5))
        );
        assert_eq!(info["moves"].as_u64(), Some(1));
        assert!(
            info["summary"]
                .as_str()
                .unwrap()
                .contains("final gather at")
        );
        assert_eq!(info["report"], serde_json::to_value(&report).unwrap());
        assert_ne!(
            serde_json::to_value(&report).unwrap(),
            serde_json::to_value(&own).unwrap(),
            "the gather measured nothing anew"
        );
        assert_eq!((&last.mesh, &last.links), (&shown.mesh, &shown.links));
        assert_eq!(last.lightmaps, shown.lightmaps);
        // Picks read the same solution.
        let ray = Ray::new(Vec3::new(0.278, 0.3, 0.28), Vec3::NEG_Y);
        let (a, b) = (last.pick(&ray), shown.pick(&ray));
        assert!(a.hit);
        assert_eq!(
            serde_json::to_value(a).unwrap(),
            serde_json::to_value(b).unwrap()
        );
    }
}
