//! MGF import: the Materials and Geometry Format (Greg Ward, LBNL; version 2.0), the scene
//! language of Radiance's and RenderPark's scene corpus.
//!
//! The file is read entity by entity as the specification defines them, with its contexts:
//! the current vertex (`v`, `p`, `n`), colour (`c`, `cxy`, `cspec`, `cct`, `cmix`) and
//! material (`m`, `sides`, `rd`, `td`, `ed`, `rs`, `ts`, `ir`), each named or unnamed, with
//! templates; the object stack (`o NAME` … `o`); the transform stack (`xf` with `-t`, `-rx`,
//! `-ry`, `-rz`, `-s`, `-mx`, `-my`, `-mz`, `-i N` and arrays `-a N`); includes (`i FILE
//! [transform]`, relative to the including file). Geometry (`f`, `fh`, `sph`, `cyl`, `cone`,
//! `ring`, `torus`, `prism`) takes the vertices' positions at the time it is given, through the
//! transform then in effect (faces are turned over by transforms that mirror); curved
//! primitives are tessellated (`mgf_shapes.rs`: 32 segments around every circle). Colours and
//! materials become strahl's as `mgf_color.rs` describes (`docs/scene-format.md`, "MGF
//! files", has both). Every face goes to the object named by the object stack joined with
//! dots (`room.table`; array instances add `a0`, `a1`, … as MGF's parser does), faces outside
//! every object to one named after the file's stem. Lengths are metres.
//!
//! Entities MGF does not define, and `ies` luminaires, are ignored with one warning per
//! keyword; so are vertex normals on faces (faces are flat). Errors name the file, the line and
//! the entity (and field): `mesh file "room.mgf": line 12: rd: rho_d: 1.2 is outside [0, 1]`.
//! Hostile input is bounded: [`MAX_INCLUDE_DEPTH`], [`MAX_NESTING`], [`MAX_FACES`],
//! [`MAX_ENTITIES`], [`MAX_FILE_BYTES`], 65,536 bytes per entity, 10⁶ instances per array
//! transform and 512 corners per face with seams.

use super::ImportError;
use super::mgf_color::{MaterialKey, to_strahl};
use super::mgf_context::Named;
use super::mgf_shapes::{self, Polygon};
use super::mgf_syntax::{Entities, Entity, XfSpec, arity, number};
use crate::scene::polygon::{self, PLANARITY_TOLERANCE, PolygonError, Shape};
use crate::scene::{Material, PolygonMesh};
use glam::{DAffine3, DVec3, Vec3};
use std::collections::{HashMap, HashSet};
use std::io::Read;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// How deep includes may nest (the file named by the user is depth 1).
pub const MAX_INCLUDE_DEPTH: usize = 16;

/// How deep objects (`o`) and transforms (`xf`, include transforms and array instances) may
/// each nest.
pub const MAX_NESTING: usize = 64;

/// The most different materials a file may give its faces.
pub const MAX_MATERIALS: usize = 65_536;

/// The most faces a file may make, arrays, includes and tessellated primitives counted.
pub const MAX_FACES: usize = 4_000_000;

/// The most entities reading a file may interpret, each repetition by an array or include
/// counted.
pub const MAX_ENTITIES: u64 = 20_000_000;

/// The most bytes the file and the files it includes may have together (each file counted
/// once, however often it is included).
pub const MAX_FILE_BYTES: u64 = 1 << 28;

/// An MGF file read into memory: one mesh per MGF object, in metres, and the materials their
/// faces use.
#[derive(Clone, Debug, PartialEq)]
pub struct MgfScene {
    /// The objects that have faces, in the order of their first face.
    pub objects: Vec<MgfObject>,
    /// The materials the faces use, each once: an MGF material changed after use comes again
    /// as `NAME#2`, `NAME#3`, …; faces given with the unnamed material use `unnamed`.
    pub materials: Vec<Material>,
    /// Problems that did not stop the import (ignored entities, split or empty faces, colours
    /// clipped to the RGB gamut), each naming its file and line.
    pub warnings: Vec<String>,
}

/// The faces of one MGF object.
#[derive(Clone, Debug, PartialEq)]
pub struct MgfObject {
    /// The object stack joined with dots (`room.table`), or the file's stem.
    pub name: String,
    /// The faces in world coordinates (metres), counter-clockwise seen from the front, convex
    /// and planar (others split into triangles); `face_materials` is `None`.
    pub mesh: PolygonMesh,
    /// Per face: index into [`MgfScene::materials`].
    pub face_materials: Vec<u32>,
}

/// Reads the MGF file at `path` with everything it includes.
pub fn load(path: &Path) -> Result<MgfScene, ImportError> {
    let canonical = path
        .canonicalize()
        .map_err(|e| ImportError::unreadable(path, e))?;
    let text = read(&canonical, MAX_FILE_BYTES).map_err(|e| ImportError::unreadable(path, e))?;
    let stem = path
        .file_stem()
        .map_or_else(|| "mgf".to_string(), |s| s.to_string_lossy().into_owned());
    let mut reader = Reader::new(stem);
    reader.bytes_read = text.len() as u64;
    let source = reader.parse(path, &text)?;
    reader.includes.push(canonical);
    reader.run_range(&source, 0..source.entities.len())?;
    Ok(reader.finish())
}

/// The text of the file at `path`: a regular file of at most `most` bytes, bytes that are not
/// UTF-8 replaced.
fn read(path: &Path, most: u64) -> Result<String, String> {
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    if !file.metadata().map_err(|e| e.to_string())?.is_file() {
        return Err("not a regular file".into());
    }
    let mut bytes = Vec::new();
    file.take(most + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| e.to_string())?;
    if bytes.len() as u64 > most {
        return Err(format!(
            "more than the {MAX_FILE_BYTES} bytes a file and its includes may have together"
        ));
    }
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// A file's entities and the path its errors name.
struct Source {
    path: PathBuf,
    entities: Rc<Entities>,
}

/// The faces of one object being gathered, with its vertices shared by position.
struct ObjectBuilder {
    object: MgfObject,
    vertices: HashMap<[u32; 3], u32>,
}

/// Counted occurrences of something warned about once: where it was first seen, how often.
type Tally = (String, usize);

/// Where an entity is, for warnings: `FILE: line N`.
struct Here<'a> {
    path: &'a Path,
    line: usize,
}

impl std::fmt::Display for Here<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: line {}", self.path.display(), self.line)
    }
}

/// The reader's state while it interprets a file and its includes.
struct Reader {
    stem: String,
    named: Named,
    /// Total transforms, innermost last.
    transforms: Vec<DAffine3>,
    objects: Vec<String>,
    /// Transforms and objects below these depths belong to an enclosing file or array.
    floors: (usize, usize),
    /// Canonical paths of the files being read, outermost first.
    includes: Vec<PathBuf>,
    parsed: HashMap<PathBuf, Rc<Entities>>,
    /// Bytes read and entities parsed so far, over every file.
    bytes_read: u64,
    entities_parsed: u64,
    built: Vec<ObjectBuilder>,
    by_name: HashMap<String, usize>,
    out_materials: Vec<Material>,
    /// Materials converted so far by MGF name and values (`MgfMaterial::key`), how many
    /// versions each name has, and the names given to them.
    versions: HashMap<(String, MaterialKey), u32>,
    version_counts: HashMap<String, usize>,
    labels: HashSet<String>,
    warnings: Vec<String>,
    /// Ignored keywords with why, in the order first met, and their index there.
    ignored: Vec<(String, Tally)>,
    ignored_index: HashMap<String, usize>,
    /// Faces with no area left out, bent faces split, vertex normals met.
    empty: Option<Tally>,
    bent: Option<Tally>,
    normals: Option<Tally>,
    faces: usize,
    interpreted: u64,
}

impl Reader {
    fn new(stem: String) -> Self {
        Reader {
            stem,
            named: Named::new(),
            transforms: Vec::new(),
            objects: Vec::new(),
            floors: (0, 0),
            includes: Vec::new(),
            parsed: HashMap::new(),
            bytes_read: 0,
            entities_parsed: 0,
            built: Vec::new(),
            by_name: HashMap::new(),
            out_materials: Vec::new(),
            versions: HashMap::new(),
            version_counts: HashMap::new(),
            labels: HashSet::new(),
            warnings: Vec::new(),
            ignored: Vec::new(),
            ignored_index: HashMap::new(),
            empty: None,
            bent: None,
            normals: None,
            faces: 0,
            interpreted: 0,
        }
    }

    /// The entities of `text`, the content of the file `path`, within what is left of
    /// [`MAX_ENTITIES`].
    fn parse(&mut self, path: &Path, text: &str) -> Result<Source, ImportError> {
        let entities = Entities::parse(text, MAX_ENTITIES - self.entities_parsed)
            .map_err(|e| ImportError::invalid(path, e))?;
        self.entities_parsed += entities.len() as u64;
        Ok(Source {
            path: path.to_path_buf(),
            entities: Rc::new(entities),
        })
    }

    /// Interprets the entities `range` of `source`. Transforms and objects it leaves open are
    /// closed at its end, with a warning.
    fn run_range(&mut self, source: &Source, range: Range<usize>) -> Result<(), ImportError> {
        let floors = self.floors;
        self.floors = (self.transforms.len(), self.objects.len());
        let mut i = range.start;
        while i < range.end {
            let e = source.entities.get(i);
            let at = |message: String| {
                ImportError::invalid(
                    &source.path,
                    format!("line {}: {}: {message}", e.line, e.keyword()),
                )
            };
            self.interpreted += 1;
            if self.interpreted > MAX_ENTITIES {
                return Err(at(format!(
                    "more than {MAX_ENTITIES} entities to interpret (arrays and includes \
                     repeat theirs)"
                )));
            }
            i += 1;
            match e.keyword() {
                "xf" if !e.args().is_empty() => {
                    let spec = XfSpec::parse(e.args()).map_err(at)?;
                    if spec.array_sizes().is_empty() {
                        self.push_transform(spec.transform(&[])).map_err(at)?;
                    } else {
                        let end = closing_xf(&source.entities, i - 1).ok_or_else(|| {
                            at("an array (-a) needs its closing xf in the same file".into())
                        })?;
                        let body = i..end;
                        self.instances(&spec, &at, &mut |r| r.run_range(source, body.clone()))?;
                        i = end + 1;
                    }
                }
                "i" => self.include(source, &e, &at)?,
                _ => {
                    let here = Here {
                        path: &source.path,
                        line: e.line,
                    };
                    self.entity(&e, &here).map_err(at)?;
                }
            }
        }
        let open = (
            self.transforms.len() - self.floors.0,
            self.objects.len() - self.floors.1,
        );
        if open != (0, 0) {
            self.warnings.push(format!(
                "{}: {} transform(s) (xf) and {} object(s) (o) not ended: ended at the end of \
                 the file",
                source.path.display(),
                open.0,
                open.1
            ));
            self.transforms.truncate(self.floors.0);
            self.objects.truncate(self.floors.1);
        }
        self.floors = floors;
        Ok(())
    }

    /// Runs `body` once per instance of the transform `spec` (once when it makes no array),
    /// each with the instance's transform and, in arrays, inside an object `aI.J…`.
    fn instances(
        &mut self,
        spec: &XfSpec,
        at: &dyn Fn(String) -> ImportError,
        body: &mut dyn FnMut(&mut Reader) -> Result<(), ImportError>,
    ) -> Result<(), ImportError> {
        let sizes = spec.array_sizes();
        let mut index = vec![0u64; sizes.len()];
        loop {
            let depths = (self.transforms.len(), self.objects.len());
            if !sizes.is_empty() {
                let name = index
                    .iter()
                    .map(u64::to_string)
                    .collect::<Vec<_>>()
                    .join(".");
                self.push_object(format!("a{name}")).map_err(at)?;
            }
            self.push_transform(spec.transform(&index)).map_err(at)?;
            let result = body(self);
            self.transforms.truncate(depths.0);
            self.objects.truncate(depths.1);
            result?;
            let mut d = sizes.len();
            loop {
                if d == 0 {
                    return Ok(());
                }
                d -= 1;
                index[d] += 1;
                if index[d] < sizes[d] {
                    break;
                }
                index[d] = 0;
            }
        }
    }

    /// `i FILE [transform]`: the file, relative to the including one's folder, read inside
    /// the transform.
    fn include(
        &mut self,
        source: &Source,
        e: &Entity,
        at: &dyn Fn(String) -> ImportError,
    ) -> Result<(), ImportError> {
        let args = e.args();
        arity(args, 1, usize::MAX, "i FILE [transform]").map_err(at)?;
        let name = Path::new(args[0]);
        if name.is_absolute() {
            return Err(at(format!(
                "\"{}\": MGF forbids absolute paths (give it relative to this file)",
                args[0]
            )));
        }
        let path = source.path.parent().unwrap_or(Path::new("")).join(name);
        let canonical = path
            .canonicalize()
            .map_err(|err| at(format!("cannot read \"{}\": {err}", path.display())))?;
        if let Some(k) = self.includes.iter().position(|p| *p == canonical) {
            let cycle: Vec<String> = self.includes[k..]
                .iter()
                .chain([&canonical])
                .map(|p| {
                    p.file_name()
                        .map_or_else(String::new, |f| f.to_string_lossy().into_owned())
                })
                .collect();
            return Err(at(format!("include cycle: {}", cycle.join(" → "))));
        }
        if self.includes.len() >= MAX_INCLUDE_DEPTH {
            return Err(at(format!("includes nest deeper than {MAX_INCLUDE_DEPTH}")));
        }
        let entities = match self.parsed.get(&canonical) {
            Some(entities) => entities.clone(),
            None => {
                let text = read(&canonical, MAX_FILE_BYTES - self.bytes_read)
                    .map_err(|err| at(format!("cannot read \"{}\": {err}", path.display())))?;
                self.bytes_read += text.len() as u64;
                let parsed = self.parse(&path, &text)?.entities;
                self.parsed.insert(canonical.clone(), parsed.clone());
                parsed
            }
        };
        let included = Source { path, entities };
        let spec = XfSpec::parse(&args[1..]).map_err(at)?;
        self.includes.push(canonical);
        let n = included.entities.len();
        let result = self.instances(&spec, at, &mut |r| r.run_range(&included, 0..n));
        self.includes.pop();
        result
    }

    fn push_transform(&mut self, step: DAffine3) -> Result<(), String> {
        if self.transforms.len() >= MAX_NESTING {
            return Err(format!("transforms nest deeper than {MAX_NESTING}"));
        }
        self.transforms.push(self.transform() * step);
        Ok(())
    }

    fn push_object(&mut self, name: String) -> Result<(), String> {
        if self.objects.len() >= MAX_NESTING {
            return Err(format!("objects nest deeper than {MAX_NESTING}"));
        }
        self.objects.push(name);
        Ok(())
    }

    /// The transform in effect.
    fn transform(&self) -> DAffine3 {
        self.transforms
            .last()
            .copied()
            .unwrap_or(DAffine3::IDENTITY)
    }

    /// Interprets one entity other than `i` and `xf` with arguments; `location` (file and
    /// line) is for warnings.
    fn entity(&mut self, e: &Entity, location: &Here<'_>) -> Result<(), String> {
        let args = e.args();
        let keyword = e.keyword();
        let warnings = &mut self.warnings;
        let mut warn = |w: String| warnings.push(format!("{location}: {w}"));
        if self.named.entity(keyword, args, &mut warn)? {
            return Ok(());
        }
        match keyword {
            "o" => match args {
                [] if self.objects.len() > self.floors.1 => {
                    self.objects.pop();
                }
                [] => return Err("no object to end (this file or array began none)".into()),
                [name] => self.push_object(name.to_string())?,
                _ => arity(args, 0, 1, "o [NAME]")?,
            },
            "xf" if self.transforms.len() > self.floors.0 => {
                self.transforms.pop();
            }
            "xf" => return Err("no transform to end (this file began none)".into()),
            "f" => {
                arity(args, 3, usize::MAX, "f v1 v2 v3 …")?;
                let corners = self.corners(args, location)?;
                self.emit(vec![corners], location)?;
            }
            "fh" => {
                let face = self.face_with_holes(args, location)?;
                self.emit(vec![face], location)?;
            }
            "sph" => {
                arity(args, 2, 2, "sph vc radius")?;
                let centre = self.named.vertex(args[0])?.p;
                let polygons = mgf_shapes::sphere(centre, number(args[1], "radius")?)?;
                self.emit(polygons, location)?;
            }
            "cyl" | "cone" => {
                let (ends, radii) = if keyword == "cyl" {
                    arity(args, 3, 3, "cyl v1 radius v2")?;
                    let r = number(args[1], "radius")?;
                    if r == 0.0 {
                        return Err("radius: a cylinder's radius must not be 0".into());
                    }
                    ((args[0], args[2]), (r, r))
                } else {
                    arity(args, 4, 4, "cone v1 rad1 v2 rad2")?;
                    (
                        (args[0], args[2]),
                        (number(args[1], "rad1")?, number(args[3], "rad2")?),
                    )
                };
                let (p1, p2) = (self.named.vertex(ends.0)?.p, self.named.vertex(ends.1)?.p);
                self.emit(mgf_shapes::cone(p1, radii.0, p2, radii.1)?, location)?;
            }
            "ring" | "torus" => {
                arity(args, 3, 3, &format!("{keyword} vc rmin rmax"))?;
                let centre = self.named.vertex(args[0])?;
                let (rmin, rmax) = (number(args[1], "rmin")?, number(args[2], "rmax")?);
                let polygons = if keyword == "ring" {
                    mgf_shapes::ring(centre.p, centre.n, rmin, rmax)?
                } else {
                    mgf_shapes::torus(centre.p, centre.n, rmin, rmax)?
                };
                self.emit(polygons, location)?;
            }
            "prism" => {
                arity(args, 4, usize::MAX, "prism v1 v2 v3 … length")?;
                let (length, names) = args.split_last().ok_or("no arguments")?;
                let base: Vec<DVec3> = names
                    .iter()
                    .map(|n| self.named.vertex(n).map(|v| v.p))
                    .collect::<Result<_, _>>()?;
                self.emit(
                    mgf_shapes::prism(&base, number(length, "length")?)?,
                    location,
                )?;
            }
            "ies" => self.ignore(keyword, location, "IES luminaire files are not supported"),
            _ => self.ignore(keyword, location, "not an MGF entity"),
        }
        Ok(())
    }

    /// The positions of the vertices `names` (a face's corners); a note when one has a normal.
    fn corners(&mut self, names: &[&str], location: &Here<'_>) -> Result<Polygon, String> {
        let vertices = names
            .iter()
            .map(|n| self.named.vertex(n))
            .collect::<Result<Vec<_>, _>>()?;
        if vertices.iter().any(|v| v.n != DVec3::ZERO) {
            tally(&mut self.normals, location);
        }
        Ok(vertices.iter().map(|v| v.p).collect())
    }

    /// `fh v1 v2 v3 … - h1 h2 h3 … - …`: the outline and its holes as one face with seams,
    /// each hole joined to the outline's last vertex.
    fn face_with_holes(&mut self, args: &[&str], location: &Here<'_>) -> Result<Polygon, String> {
        let mut contours = args.split(|w| w.starts_with('-'));
        let mut face = self.corners(contours.next().unwrap_or(&[]), location)?;
        if face.len() < 3 {
            return Err("the outline needs at least 3 vertices".into());
        }
        let joint = face[face.len() - 1];
        for hole in contours {
            let hole = self.corners(hole, location)?;
            let Some(&last) = hole.last().filter(|_| hole.len() >= 3) else {
                return Err("every hole needs at least 3 vertices".into());
            };
            face.push(last);
            face.extend(hole);
            face.push(joint);
        }
        Ok(face)
    }

    /// Warns once per `keyword` that it is ignored (`why`), counting its occurrences.
    fn ignore(&mut self, keyword: &str, location: &Here<'_>, why: &str) {
        match self.ignored_index.get(keyword) {
            Some(&k) => self.ignored[k].1.1 += 1,
            None => {
                self.ignored_index
                    .insert(keyword.to_string(), self.ignored.len());
                let what = format!("\"{keyword}\" ({why})");
                self.ignored.push((what, (location.to_string(), 1)));
            }
        }
    }

    /// Adds `polygons` (untransformed) to the current object with the current material,
    /// through the current transform.
    fn emit(&mut self, polygons: Vec<Polygon>, location: &Here<'_>) -> Result<(), String> {
        let material = self.material_id(location)?;
        let transform = self.transform();
        let mirrored = transform.matrix3.determinant() < 0.0;
        let object = self.object_index();
        for polygon in polygons {
            let mut corners: Vec<Vec3> = polygon
                .iter()
                .map(|&p| transform.transform_point3(p).as_vec3())
                .collect();
            if mirrored {
                corners.reverse();
            }
            if corners.iter().any(|c| !c.is_finite()) {
                return Err(
                    "a vertex, placed by the transform in effect, is beyond single precision"
                        .into(),
                );
            }
            let exact: Vec<DVec3> = corners.iter().map(|c| c.as_dvec3()).collect();
            let exact = mgf_shapes::without_repeats(&exact);
            let corners: Vec<Vec3> = exact.iter().map(|c| c.as_vec3()).collect();
            if mgf_shapes::has_seam(&exact) {
                let triangles = mgf_shapes::split_seams(&exact)?;
                if triangles.is_empty() {
                    tally(&mut self.empty, location);
                }
                for t in triangles {
                    self.add_face(object, &t.map(|k| corners[k]), material)?;
                }
                continue;
            }
            match polygon::classify(&corners) {
                Ok(Shape::Convex) => self.add_face(object, &corners, material)?,
                Ok(shape) => {
                    if matches!(shape, Shape::NonPlanar { .. }) {
                        tally(&mut self.bent, location);
                    }
                    for t in polygon::triangulate(&corners) {
                        self.add_face(object, &t.map(|k| corners[k]), material)?;
                    }
                }
                Err(
                    PolygonError::ZeroArea | PolygonError::Coincide(..) | PolygonError::TooFew(_),
                ) => {
                    tally(&mut self.empty, location);
                }
                Err(e) => return Err(e.to_string()),
            }
        }
        Ok(())
    }

    /// Index of the object the current object stack names, created on first use.
    fn object_index(&mut self) -> usize {
        let name = if self.objects.is_empty() {
            self.stem.clone()
        } else {
            self.objects.join(".")
        };
        *self.by_name.entry(name.clone()).or_insert_with(|| {
            self.built.push(ObjectBuilder {
                object: MgfObject {
                    name,
                    mesh: PolygonMesh::default(),
                    face_materials: Vec::new(),
                },
                vertices: HashMap::new(),
            });
            self.built.len() - 1
        })
    }

    /// Adds one face to object `object`, sharing vertices at the same position.
    fn add_face(&mut self, object: usize, corners: &[Vec3], material: u32) -> Result<(), String> {
        self.faces += 1;
        if self.faces > MAX_FACES {
            return Err(format!(
                "the file makes more than {MAX_FACES} faces (arrays, includes and tessellated \
                 primitives counted)"
            ));
        }
        let b = &mut self.built[object];
        for c in corners {
            let key = c.to_array().map(f32::to_bits);
            let positions = &mut b.object.mesh.positions;
            let index = *b.vertices.entry(key).or_insert_with(|| {
                positions.push(*c);
                positions.len() as u32 - 1
            });
            b.object.mesh.indices.push(index);
        }
        b.object.mesh.face_sizes.push(corners.len() as u32);
        b.object.face_materials.push(material);
        Ok(())
    }

    /// Index in the output of the current material as it is now, converted on first use.
    fn material_id(&mut self, location: &Here<'_>) -> Result<u32, String> {
        let name = self
            .named
            .materials
            .current
            .clone()
            .unwrap_or_else(|| "unnamed".into());
        let value = *self.named.materials.get();
        let key = (name, value.key());
        if let Some(&id) = self.versions.get(&key) {
            return Ok(id);
        }
        if self.out_materials.len() >= MAX_MATERIALS {
            return Err(format!(
                "more than {MAX_MATERIALS} different materials (a material changed between \
                 faces counts once per change)"
            ));
        }
        let name = &key.0;
        let count = self.version_counts.entry(name.clone()).or_default();
        let mut label = name.clone();
        while self.labels.contains(&label) {
            *count += 1;
            label = format!("{name}#{}", *count + 1);
        }
        let warnings = &mut self.warnings;
        let material = to_strahl(&label, &value, &mut |w| {
            warnings.push(format!("{location}: {w}"))
        })?;
        let id = self.out_materials.len() as u32;
        self.out_materials.push(material);
        self.labels.insert(label);
        self.versions.insert(key, id);
        Ok(id)
    }

    /// The scene read, with the warnings gathered along the way.
    fn finish(mut self) -> MgfScene {
        for (what, (location, count)) in &self.ignored {
            self.warnings.push(format!(
                "{location}: entity {what} ignored ({count} in all)"
            ));
        }
        let notes = [
            (&self.empty, "face(s) with no area left out".to_string()),
            (
                &self.bent,
                format!(
                    "face(s) not planar within {PLANARITY_TOLERANCE:.0e} of their size split \
                     into triangles"
                ),
            ),
            (
                &self.normals,
                "face(s) with vertex normals (n): the normals are not used, faces are flat"
                    .to_string(),
            ),
        ];
        for (tally, what) in notes {
            if let Some((location, count)) = tally {
                self.warnings
                    .push(format!("{location}: {count} {what} (the first here)"));
            }
        }
        MgfScene {
            objects: self.built.into_iter().map(|b| b.object).collect(),
            materials: self.out_materials,
            warnings: self.warnings,
        }
    }
}

/// Counts one more occurrence, remembering where the first was.
fn tally(counter: &mut Option<Tally>, location: &Here<'_>) {
    counter.get_or_insert_with(|| (location.to_string(), 0)).1 += 1;
}

/// Index of the bare `xf` that closes the `xf` with arguments at `open`, in the same file.
fn closing_xf(entities: &Entities, open: usize) -> Option<usize> {
    let mut depth = 0usize;
    for k in open + 1..entities.len() {
        let e = entities.get(k);
        if e.keyword() != "xf" {
            continue;
        }
        if !e.args().is_empty() {
            depth += 1;
        } else if depth == 0 {
            return Some(k);
        } else {
            depth -= 1;
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::polygon_area;

    /// A fresh folder for one test.
    fn folder(test: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("strahl-mgf-{}-{test}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// Writes `text` as `name` in `dir` (folders created) and returns its path.
    fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, text).unwrap();
        path
    }

    /// Reads `text` as the file `scene.mgf` of a folder of its own (removed afterwards).
    fn read_text(test: &str, text: &str) -> Result<MgfScene, ImportError> {
        let dir = folder(test);
        let scene = load(&write(&dir, "scene.mgf", text));
        std::fs::remove_dir_all(&dir).unwrap();
        scene
    }

    fn object<'a>(scene: &'a MgfScene, name: &str) -> &'a MgfObject {
        scene
            .objects
            .iter()
            .find(|o| o.name == name)
            .unwrap_or_else(|| panic!("no object {name} in {:?}", names(scene)))
    }

    fn names(scene: &MgfScene) -> Vec<&str> {
        scene.objects.iter().map(|o| o.name.as_str()).collect()
    }

    /// Every face of `o` as its corners.
    fn faces(o: &MgfObject) -> Vec<Vec<Vec3>> {
        o.mesh
            .faces()
            .map(|f| f.iter().map(|&i| o.mesh.positions[i as usize]).collect())
            .collect()
    }

    fn area(o: &MgfObject) -> f64 {
        faces(o).iter().map(|f| f64::from(polygon_area(f))).sum()
    }

    fn normal(face: &[Vec3]) -> Vec3 {
        (face[1] - face[0]).cross(face[2] - face[0]).normalize()
    }

    const TRIANGLE: &str = "v a =\n p 0 0 0\nv b =\n p 1 0 0\nv c =\n p 0 1 0\n";

    #[test]
    fn objects_contexts_and_materials_follow_the_specification() {
        let text = "c red =\n cxy .64 .33\nm paint =\n sides 1\n c red\n rd .2\n c\n rs .05 0\n\
                    m lamp =\n c\n ed 2145.71\n\
                    v a =\n p 0 0 0\nv b =\n p 1 0 0\nv c =\n p 1 1 0\nv d =\n p 0 1 0\n\
                    m paint\nf a b c d\n\
                    o room\n o table\n  f a b c\n  v c\n   p 2 2 0\n  f a b c\n o\n m lamp\n f a b d\no\n\
                    o room\n m paint\n f a c d\no\nm paint\n rd .3\nf a b c\n";
        let scene = read_text("contexts", text).unwrap();
        assert_eq!(names(&scene), vec!["scene", "room.table", "room"]);
        let table = object(&scene, "room.table");
        // The second face took vertex c as redefined (the first kept the old one).
        assert!((area(table) - 1.5).abs() < 1e-6, "{}", area(table));
        let room = object(&scene, "room");
        let used: Vec<&str> = room
            .face_materials
            .iter()
            .map(|&m| scene.materials[m as usize].name.as_str())
            .collect();
        assert_eq!(used, vec!["lamp", "paint"]);
        // Materials once each, and a material changed after use once more.
        let all: Vec<&str> = scene.materials.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(all, vec!["paint", "lamp", "paint#2"]);
        let paint = &scene.materials[0];
        assert!(paint.one_sided && !paint.two_sided);
        assert!(
            paint.diffuse.r > 0.5 && paint.diffuse.g.abs() < 1e-6 && paint.diffuse.b.abs() < 1e-6
        );
        assert!((paint.mirror.g - 0.05).abs() < 1e-6 && paint.specular.is_black());
        let lamp = &scene.materials[1];
        assert!(
            (lamp.emission.r - 1.0).abs() < 1e-4 && !lamp.one_sided && !lamp.two_sided,
            "{lamp:?}"
        );
        assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    }

    #[test]
    fn transforms_nest_mirror_and_make_arrays() {
        let text = format!(
            "{TRIANGLE}xf -t 10 0 0\n f a b c\n xf -rz 90 -s 2\n  f a b c\n xf\n xf -mx\n  f a b c\n xf\nxf\n\
             o row\nxf -a 3 -t 0 0 1\n f a b c\nxf\no\n"
        );
        let scene = read_text("transforms", &text).unwrap();
        let plain = faces(object(&scene, "scene"));
        assert_eq!(plain.len(), 3);
        assert_eq!(
            plain[0],
            vec![
                Vec3::new(10., 0., 0.),
                Vec3::new(11., 0., 0.),
                Vec3::new(10., 1., 0.)
            ]
        );
        // Rotated a quarter turn and doubled, then moved: b = (1,0,0) → (0,2,0) → (10,2,0).
        assert!(
            plain[1]
                .iter()
                .any(|p| p.distance(Vec3::new(10., 2., 0.)) < 1e-5)
        );
        // The mirrored face keeps facing +z: its corners are taken in reverse.
        assert!(plain[2].contains(&Vec3::new(9., 0., 0.)));
        assert!(plain.iter().all(|f| normal(f).z > 0.999));
        for k in 0..3 {
            let instance = faces(object(&scene, &format!("row.a{k}")));
            assert!(instance[0].iter().all(|p| p.z == k as f32));
        }
    }

    #[test]
    fn includes_are_relative_transformed_and_guarded() {
        let dir = folder("includes");
        write(&dir, "sub/part.mgf", "f a b c\ni leaf.mgf\n");
        write(&dir, "sub/leaf.mgf", "f a c b\n");
        let main = write(
            &dir,
            "main.mgf",
            &format!(
                "{TRIANGLE}i sub/part.mgf -t 0 0 5\no twice\ni sub/part.mgf -a 2 -t 1 0 0\no\n"
            ),
        );
        let scene = load(&main).unwrap();
        assert_eq!(names(&scene), vec!["main", "twice.a0", "twice.a1"]);
        assert!(
            faces(object(&scene, "main"))
                .iter()
                .flatten()
                .all(|p| p.z == 5.0)
        );
        let second = faces(object(&scene, "twice.a1"));
        assert_eq!(second.len(), 2);
        assert!(second.iter().flatten().all(|p| p.x >= 1.0));

        write(&dir, "loop1.mgf", "# first\ni loop2.mgf\n");
        let e = load(&write(&dir, "loop2.mgf", "i loop1.mgf\n"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("loop1.mgf\": line 2: i: include cycle: loop2.mgf → loop1.mgf → loop2.mgf"),
            "{e}"
        );
        let e = load(&write(&dir, "missing.mgf", "\ni nowhere.mgf\n"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("missing.mgf\": line 2: i: cannot read"), "{e}");
        for k in 0..=MAX_INCLUDE_DEPTH {
            write(
                &dir,
                &format!("deep{k}.mgf"),
                &format!("i deep{}.mgf\n", k + 1),
            );
        }
        let e = load(&dir.join("deep0.mgf")).unwrap_err().to_string();
        assert!(
            e.contains("deep15.mgf\": line 1: i: includes nest deeper than 16"),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn tessellated_primitives_have_their_area_within_the_stated_tolerance() {
        let text = "v c =\n p 0 0 0\n n 0 0 1\nv t =\n p 0 0 1\n\
                    v q0 =\n p 0 0 0\nv q1 =\n p 0 1 0\nv q2 =\n p 1 1 0\nv q3 =\n p 1 0 0\n\
                    xf -s 2\n\
                    o sph\n sph c 1\no\no cyl\n cyl c 0.5 t\no\no cone\n cone c 1 t 0\no\n\
                    o ring\n ring c 0.5 1\no\no torus\n torus c 1 3\no\no prism\n prism q0 q1 q2 q3 1\no\nxf\n";
        let scene = read_text("primitives", text).unwrap();
        let pi = std::f64::consts::PI;
        // Closed forms at scale 2 (areas × 4), and the relative tolerance each is held to.
        let cases = [
            ("sph", 4.0 * pi, 0.0085),
            ("cyl", 2.0 * pi * 0.5, 0.0017),
            ("cone", pi * 2f64.sqrt(), 0.0065),
            ("ring", pi * 0.75, 0.0065),
            ("torus", 4.0 * pi * pi * 2.0, 0.011),
            ("prism", 6.0, 1e-6),
        ];
        for (name, exact, tolerance) in cases {
            let got = area(object(&scene, name)) / 4.0;
            assert!(
                (got - exact).abs() <= tolerance * exact,
                "{name}: {got} vs {exact}"
            );
        }
    }

    #[test]
    fn cornell_colours_read_back_to_strahls_within_the_scripts_tolerance() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/cornell.mgf");
        let scene = load(&path).unwrap();
        let colors = crate::scene::builtin::cornell::colors().unwrap();
        let material = |name: &str| scene.materials.iter().find(|m| m.name == name).unwrap();
        let close = |got: crate::color::Rgb, want: crate::color::Rgb| {
            (0..3).all(|c| (got[c] - want[c]).abs() <= 1e-6 * want[c].abs().max(1e-3))
        };
        assert!(close(material("white").diffuse, colors.white));
        assert!(close(material("red").diffuse, colors.red));
        assert!(close(material("green").diffuse, colors.green));
        // The script writes the lamp for RenderPark's 183.07 lm/W; strahl reads lumens at 683.
        let lamp = colors.light * (183.07 / crate::color::LUMINOUS_EFFICACY) as f32;
        assert!(close(material("light").emission, lamp));
        assert!(close(
            material("light").diffuse,
            crate::color::Rgb::splat(0.78)
        ));
        assert!(scene.materials.iter().all(|m| m.one_sided));
    }

    #[test]
    fn faces_with_seams_and_holes_leave_the_hole_open() {
        let corners = "v o0 =\n p 0 0 0\nv o1 =\n p 4 0 0\nv o2 =\n p 4 4 0\nv o3 =\n p 0 4 0\n\
                       v h0 =\n p 1 3 0\nv h1 =\n p 3 3 0\nv h2 =\n p 3 1 0\nv h3 =\n p 1 1 0\n";
        let text = format!(
            "{corners}o seam\n f o0 o1 o2 o3 h0 h1 h2 h3 h0 o3\no\no holes\n fh o0 o1 o2 o3 - h0 h1 h2 h3\no\n"
        );
        let scene = read_text("seams", &text).unwrap();
        for name in ["seam", "holes"] {
            let o = object(&scene, name);
            assert!((area(o) - 12.0).abs() < 1e-5, "{name}: {}", area(o));
            assert!(faces(o).iter().all(|f| normal(f).z > 0.999));
        }
    }

    #[test]
    fn what_renderpark_s_scenes_hold_beyond_the_specification_is_read_with_warnings() {
        // As in RenderPark's own corpus: rd + rs above 1 (cube.mgf), cxy with x = 0
        // (corridor.mgf) or y = 0 (the hospital), a measured spectrum with negative noise
        // (illums.mgf). MGF's reference parser reads them; so does strahl, saying what it did.
        let text = format!(
            "{TRIANGLE}m over =\n rd .7\n rs .5 .1\nf a b c\n\
             m cyan =\n c\n cxy 0 .38\n rd .5\nf a b c\n\
             m purple =\n c\n cxy .4 0\n rd .5\nf a b c\n\
             m noisy =\n c\n cspec 380 780 1 1 -0.01 1 1\n rd .5\nf a b c\n\
             m clean =\n c\n cspec 380 780 1 1 0 1 1\n rd .5\nf a b c\n"
        );
        let scene = read_text("beyond", &text).unwrap();
        let material = |name: &str| scene.materials.iter().find(|m| m.name == name).unwrap();
        // Both lobes scaled by 1/1.2, so that they add up to 1.
        let over = material("over");
        assert!(
            (over.diffuse.g - 0.7 / 1.2).abs() < 1e-6,
            "{:?}",
            over.diffuse
        );
        assert!(
            (over.specular.g - 0.5 / 1.2).abs() < 1e-6,
            "{:?}",
            over.specular
        );
        assert!(material("cyan").diffuse.r == 0.0 && material("cyan").diffuse.b > 0.0);
        assert_eq!(material("purple").diffuse, crate::color::Rgb::BLACK);
        assert_eq!(material("noisy").diffuse, material("clean").diffuse);
        let w = scene.warnings.join("\n");
        for says in [
            "line 10: material \"over\" reflects and transmits more than it receives: rd + \
             td + rs + ts = 1.2; each was scaled down by 1/1.2",
            "line 15: material \"cyan\": a colour outside the RGB gamut was clipped to it",
            "line 20: material \"purple\": a colour with y = 0 (below 0.000001) has no luminance",
            "line 23: cspec: 1 negative value(s) taken as 0 (the first: value 3, -0.01)",
        ] {
            assert!(w.contains(says), "{says}\n{w}");
        }
    }

    #[test]
    fn unknown_entities_are_ignored_with_one_warning_each() {
        let text = format!("{TRIANGLE}zap 1\nzap 2\nies lamp.ies\nf a b c\nzip\n");
        let scene = read_text("unknown", &text).unwrap();
        assert_eq!(scene.objects.len(), 1);
        let w = &scene.warnings;
        assert_eq!(w.len(), 3, "{w:?}");
        assert!(
            w[0].contains("line 7: entity \"zap\" (not an MGF entity) ignored (2 in all)"),
            "{w:?}"
        );
        assert!(w[1].contains("\"ies\" (IES luminaire files are not supported)"));
        assert!(w[2].contains("line 11: entity \"zip\""));
    }

    #[test]
    fn empty_and_bent_faces_and_vertex_normals_are_noted_once() {
        let text = format!(
            "{TRIANGLE}v d =\n p 1 1 1\n n 0 0 1\nf a b b\nf a b a c\nf a b d c\nf a b d c\nf a d c\n"
        );
        let scene = read_text("notes", &text).unwrap();
        let faces = &scene.objects[0].mesh.face_sizes;
        // The empty face is left out; the bent quad is split in two, twice; the rest is kept.
        assert_eq!(faces, &vec![3, 3, 3, 3, 3]);
        let w = &scene.warnings;
        assert_eq!(w.len(), 3, "{w:?}");
        assert!(
            w[0].contains("line 10: 2 face(s) with no area left out"),
            "{w:?}"
        );
        assert!(
            w[1].contains("line 12: 2 face(s) not planar within 1e-3"),
            "{w:?}"
        );
        assert!(
            w[2].contains("line 12: 3 face(s) with vertex normals"),
            "{w:?}"
        );
    }

    #[test]
    fn malformed_input_is_refused_with_file_line_and_entity() {
        let cases = [
            (
                "m x =\nrd 1.2\n",
                "line 2: rd: rho_d: 1.2 is outside [0, 1]",
            ),
            ("f a b c\n", "line 1: f: vertex \"a\" is not defined"),
            (
                "m l =\n ed 1e30\nv a =\n p 0 0 0\nv b =\n p 1 0 0\nv c =\n p 0 1 0\nf a b c\n",
                "line 9: f: material \"l\": ed 1e30 lm/m² is a radiance of",
            ),
            ("v a =\n p 1 x 3\n", "line 2: p: p y: \"x\" is not a number"),
            ("xf -q 1\n", "line 1: xf: unknown transform argument \"-q\""),
            ("xf\n", "line 1: xf: no transform to end"),
            ("o\n", "line 1: o: no object to end"),
            (
                "m nosuch\n",
                "line 1: m: material \"nosuch\" is not defined",
            ),
            ("\n\nsides 3\n", "line 3: sides: 1 or 2 expected, got \"3\""),
            (
                "c\n cxy .8 .5\n",
                "line 2: cxy: (0.8, 0.5) is not a chromaticity",
            ),
            (
                "v c =\nsph c 0\n",
                "line 2: sph: radius: a sphere's radius must not be 0",
            ),
            (
                "v c =\nring c 0 1\n",
                "line 2: ring: the centre vertex has no normal",
            ),
            (
                "v a =\nxf -a 2 -t 1 0 0\nf a a a\n",
                "line 2: xf: an array (-a) needs its closing xf",
            ),
            (
                "v a =\n p 0 0 0\nv b =\n p 1 1 0\nv c =\n p 1 0 0\nv d =\n p 0 1 0\nf a b c d\n",
                "line 9: f: edges 0–1 and 2–3 cross",
            ),
            ("v a =\n\u{1}\n", "line 2: control character U+0001"),
            (
                "i /etc/hosts\n",
                "line 1: i: \"/etc/hosts\": MGF forbids absolute paths",
            ),
            (
                "cmix 1 red\n",
                "line 1: cmix: colour \"red\" is not defined",
            ),
            (
                "v a = b\n",
                "line 1: v: template vertex \"b\" is not defined",
            ),
        ];
        for (k, (text, says)) in cases.iter().enumerate() {
            let e = read_text(&format!("bad{k}"), text).unwrap_err().to_string();
            assert!(
                e.contains("scene.mgf\": ") && e.contains(says),
                "{text:?}: {e}"
            );
        }
    }

    #[test]
    fn hostile_repetition_is_bounded() {
        let text = "xf -a 1000 -a 1000\nxf -a 1000 -a 1000\nc\nxf\nxf\n";
        let e = read_text("hostile", text).unwrap_err().to_string();
        assert!(e.contains("line 3: c: more than 20000000 entities"), "{e}");
    }
}
