//! Scenes built from arrays (a plant model's organs handed over without files): triangles
//! grouped into named objects, a diffuse reflectance and translucency per object, and a sun
//! and a uniform or a CIE standard sky; optionally a periodic plot (a field).

use glam::{Mat4, Vec3, Vec4};
use strahl::scene::{
    CieSkyType, ENERGY_TOLERANCE, Light, LightKind, Material, Periodic, PolygonMesh, Scene, Shape,
    Transform,
};

/// What Python hands over, decoded: little-endian `f32` / `u32` arrays.
pub struct Arrays {
    /// Vertex positions, scene units.
    pub vertices: Vec<Vec3>,
    /// Vertex indices of each triangle.
    pub triangles: Vec<[u32; 3]>,
    /// The object of each triangle (an index into `names`).
    pub object_ids: Vec<u32>,
    /// Object names.
    pub names: Vec<String>,
    /// Diffuse reflectance per object, RGB in [0, 1].
    pub reflectance: Vec<[f32; 3]>,
    /// Diffuse translucency per object (light leaving the other side), RGB, ρ + τ ≤ 1.
    pub translucency: Vec<[f32; 3]>,
    /// Whether each triangle of an object is reported on its own (as `per_face` objects).
    pub per_face: bool,
    /// A sun: the direction its light travels and the irradiance on a surface facing it,
    /// W·m⁻².
    pub sun: Option<([f32; 3], [f32; 3])>,
    /// A uniform sky's radiance, W·sr⁻¹·m⁻².
    pub sky: Option<[f32; 3]>,
    /// A CIE standard general sky: its type (1–15), the direction toward the sun (above the
    /// horizon) and the diffuse irradiance on an open horizontal surface, W·m⁻².
    pub cie_sky: Option<(u8, [f32; 3], [f32; 3])>,
    /// The plot `[x₀, x₁, z₀, z₁]` (scene units) that repeats without end in x and z: the
    /// scene stands for a field of copies of it.
    pub periodic: Option<[f32; 4]>,
    /// Objects placed many times: an object's index and a row-major 3 × 4 affine matrix
    /// (`[R | t]`) per placement. The object becomes one object per placement, `name[i]`, all
    /// sharing its triangles (kept once where there are 8 or more).
    pub placements: Vec<(usize, Vec<[f32; 12]>)>,
}

/// `bytes` as little-endian 4-byte words, `width` to a row; an error names `what`.
pub fn rows<const N: usize, T>(
    bytes: &[u8],
    what: &str,
    word: fn([u8; 4]) -> T,
) -> Result<Vec<[T; N]>, String>
where
    T: Copy + Default,
{
    if !bytes.len().is_multiple_of(4 * N) {
        return Err(format!(
            "{what}: {} bytes are not rows of {N} numbers",
            bytes.len()
        ));
    }
    Ok(bytes
        .chunks_exact(4 * N)
        .map(|row| {
            let mut out = [T::default(); N];
            for (k, w) in row.chunks_exact(4).enumerate() {
                out[k] = word([w[0], w[1], w[2], w[3]]);
            }
            out
        })
        .collect())
}

/// The scene `name` the arrays describe, checked: indices in range, finite vertices,
/// reflectance and translucency in [0, 1] with ρ + τ ≤ 1, a periodic plot of finite,
/// non-empty ranges.
pub fn scene(name: &str, a: Arrays) -> Result<Scene, String> {
    let objects = a.names.len();
    if a.reflectance.len() != objects || a.translucency.len() != objects {
        return Err(format!(
            "{objects} names but {} reflectances and {} translucencies (one of each per object)",
            a.reflectance.len(),
            a.translucency.len()
        ));
    }
    if a.object_ids.len() != a.triangles.len() {
        return Err(format!(
            "{} triangles but {} object ids (one per triangle)",
            a.triangles.len(),
            a.object_ids.len()
        ));
    }
    if let Some(k) = a.vertices.iter().position(|v| !v.is_finite()) {
        return Err(format!("vertex {k} is not finite"));
    }
    let n = a.vertices.len() as u32;
    if let Some(t) = a.triangles.iter().position(|t| t.iter().any(|&i| i >= n)) {
        return Err(format!(
            "triangle {t} names vertex {:?} of {n}",
            a.triangles[t]
        ));
    }
    if let Some(t) = a.object_ids.iter().position(|&o| o as usize >= objects) {
        return Err(format!(
            "triangle {t} is of object {} of {objects}",
            a.object_ids[t]
        ));
    }
    let mut scene = Scene::empty(name);
    let mut per_object: Vec<Vec<[u32; 3]>> = vec![Vec::new(); objects];
    for (t, &o) in a.triangles.iter().zip(&a.object_ids) {
        per_object[o as usize].push(*t);
    }
    // Per object, the index of each shared vertex in the object's own list (u32::MAX: not
    // in it yet).
    let mut local = vec![u32::MAX; a.vertices.len()];
    for (k, triangles) in per_object.iter().enumerate() {
        let (rho, tau) = (a.reflectance[k], a.translucency[k]);
        for c in 0..3 {
            let fine = (0.0..=1.0).contains(&rho[c])
                && (0.0..=1.0).contains(&tau[c])
                && rho[c] + tau[c] <= 1.0 + ENERGY_TOLERANCE;
            if !fine {
                return Err(format!(
                    "object '{}': reflectance {rho:?} and translucency {tau:?} must lie in \
                     [0, 1] and add up to at most 1 per channel",
                    a.names[k]
                ));
            }
        }
        if triangles.is_empty() {
            continue;
        }
        let mut material = Material::diffuse(&a.names[k], rho.into());
        material.translucency = tau.into();
        let material = scene.add_material(material);
        let mesh = own_vertices(&a.vertices, triangles, &mut local);
        mesh.validate()
            .map_err(|e| format!("object '{}': {e}", a.names[k]))?;
        let mesh = std::sync::Arc::new(mesh);
        let placed = a.placements.iter().find(|(object, _)| *object == k);
        match placed {
            None => scene.add_object(&a.names[k], Shape::Mesh(mesh), material),
            Some((_, matrices)) => {
                for (i, m) in matrices.iter().enumerate() {
                    let name = format!("{}[{i}]", a.names[k]);
                    let transform = placement(m).ok_or_else(|| {
                        format!(
                            "placement {i} of '{}' is not finite and invertible",
                            a.names[k]
                        )
                    })?;
                    scene.add_object(&name, Shape::Mesh(mesh.clone()), material);
                    if let Some(object) = scene.objects.last_mut() {
                        object.transform = transform;
                    }
                }
            }
        }
        if a.per_face {
            let placed = placed.map_or(1, |(_, m)| m.len());
            let first = scene.objects.len() - placed;
            scene.objects[first..]
                .iter_mut()
                .for_each(|o| o.per_face = true);
        }
    }
    if let Some((k, _)) = a.placements.iter().find(|(k, _)| *k >= objects) {
        return Err(format!("placements name object {k} of {objects}"));
    }
    let light = |what: &str, rgb: [f32; 3]| {
        if rgb.iter().all(|v| v.is_finite() && *v >= 0.0) {
            Ok(rgb)
        } else {
            Err(format!(
                "the {what} must be finite and not negative ({rgb:?})"
            ))
        }
    };
    if let Some((direction, irradiance)) = a.sun {
        let irradiance = light("sun's irradiance", irradiance)?;
        let direction = Vec3::from(direction)
            .try_normalize()
            .ok_or("the sun's direction must not be zero")?;
        scene.lights.push(Light {
            name: Some("sun".into()),
            kind: LightKind::Directional {
                direction,
                irradiance: irradiance.into(),
            },
        });
    }
    if let Some(radiance) = a.sky {
        let radiance = light("sky's radiance", radiance)?;
        scene.lights.push(Light {
            name: Some("sky".into()),
            kind: LightKind::Sky {
                radiance: radiance.into(),
            },
        });
    }
    if let Some((number, sun, diffuse_horizontal)) = a.cie_sky {
        let sky = CieSkyType::from_number(number)
            .ok_or_else(|| format!("the CIE sky's type must be 1 to 15 (got {number})"))?;
        let sun = Vec3::from(sun)
            .try_normalize()
            .filter(|d| d.y > 0.0)
            .ok_or("the CIE sky's sun must point above the horizon (y > 0)")?;
        scene.lights.push(Light {
            name: Some("sky".into()),
            kind: LightKind::CieSky {
                sky,
                sun,
                diffuse_horizontal: light("CIE sky's diffuse irradiance", diffuse_horizontal)?
                    .into(),
            },
        });
    }
    if let Some([x0, x1, z0, z1]) = a.periodic {
        let plot = Periodic::new([x0, x1], [z0, z1]).map_err(|e| format!("periodic: {e}"))?;
        scene.periodic = Some(plot);
    }
    aim_camera(&mut scene, &a.vertices);
    Ok(scene)
}

/// The transform of a row-major 3 × 4 affine matrix `[R | t]`, when finite and invertible.
fn placement(m: &[f32; 12]) -> Option<Transform> {
    let matrix = Mat4::from_cols(
        Vec4::new(m[0], m[4], m[8], 0.0),
        Vec4::new(m[1], m[5], m[9], 0.0),
        Vec4::new(m[2], m[6], m[10], 0.0),
        Vec4::new(m[3], m[7], m[11], 1.0),
    );
    let det = matrix.determinant();
    (det.is_finite() && det.abs() >= 1e-20)
        .then(|| Transform::from_matrix(matrix))
        .flatten()
}

/// A mesh of `triangles` (indices into the shared `vertices`) holding only the vertices they
/// use; `local` is all `u32::MAX` before and after.
fn own_vertices(vertices: &[Vec3], triangles: &[[u32; 3]], local: &mut [u32]) -> PolygonMesh {
    let mut positions = Vec::new();
    let mut used = Vec::new();
    let own: Vec<[u32; 3]> = triangles
        .iter()
        .map(|t| {
            t.map(|i| {
                let slot = &mut local[i as usize];
                if *slot == u32::MAX {
                    *slot = positions.len() as u32;
                    positions.push(vertices[i as usize]);
                    used.push(i);
                }
                *slot
            })
        })
        .collect();
    for i in used {
        local[i as usize] = u32::MAX;
    }
    PolygonMesh::from_triangles(positions, &own)
}

/// Points the camera at the vertices' bounding box from above and in front (for renders).
fn aim_camera(scene: &mut Scene, vertices: &[Vec3]) {
    let (lo, hi) = vertices.iter().fold(
        (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
        |(lo, hi), &v| (lo.min(v), hi.max(v)),
    );
    if lo.cmple(hi).all() {
        let centre = 0.5 * (lo + hi);
        let size = (hi - lo).length().max(1e-3);
        scene.camera.look_at = centre;
        scene.camera.position = centre + Vec3::new(0.0, 0.6, 1.2) * size;
    }
}
