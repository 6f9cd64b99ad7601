//! The `strahl` Python package's extension module (`strahl._strahl`): scenes opened by name
//! or file, every method run through the library's method API with the GIL released,
//! Ctrl-C (`KeyboardInterrupt`) and a progress callback looked at every 50 ms, results as
//! the report's JSON (read into numpy columns by [`table::report_columns`]) and images as raw
//! `f32` bytes (the Python side turns both into arrays: `python/strahl/__init__.py`).

mod arrays;
mod table;

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyFloat, PyString};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;
use strahl::image::ToneMapping;
use strahl::method::{
    AccelKind, Batch, Cancel, Choice, Film, Method, MethodKind, Outcome, ProgressListener,
    SettingValue, World,
};
use strahl::report::{ExportFormat, Report, export_lit_mesh};
use strahl::scene::{LocalTime, Observer};

/// How often the waiting thread looks at Ctrl-C and reports progress.
const POLL: Duration = Duration::from_millis(50);

/// A scene compiled for ray queries, shared by every run on it.
#[pyclass(frozen, module = "strahl._strahl")]
struct Scene {
    world: Arc<World>,
}

/// Opens a built-in scene by name (`cornell`, `canopy:300`, …) or a scene file (`.toml`,
/// `.obj`, `.gltf`/`.glb`, `.mgf`); errors name the file, line and field.
#[pyfunction]
fn load(py: Python<'_>, name: &str) -> PyResult<Scene> {
    let world = py.detach(|| open_world(name));
    Ok(Scene {
        world: Arc::new(world.map_err(PyValueError::new_err)?),
    })
}

/// A scene of triangles grouped into named objects, from arrays as little-endian bytes:
/// `vertices` (n × 3 `f32`, scene units), `triangles` (m × 3 `u32`), `object_ids` (m
/// `u32`), `reflectance` and `translucency` (one RGB `f32` row per name); a sun (the
/// direction its light travels, the irradiance facing it in W·m⁻²), a uniform sky
/// (radiance, W·sr⁻¹·m⁻²) and a CIE standard sky (type 1–15, the direction toward the sun,
/// the diffuse horizontal irradiance in W·m⁻²). With `per_face`, every triangle is reported
/// on its own. With `periodic` (`x₀, x₁, z₀, z₁`, scene units) the plot `x ∈ [x₀, x₁]`,
/// `z ∈ [z₀, z₁]` repeats without end in x and z (y up): geometry reaching over a side is
/// seen through the opposite one; a bad plot raises `ValueError`.
#[pyfunction]
#[pyo3(signature = (name, vertices, triangles, object_ids, names, reflectance, translucency, per_face, sun, sky, cie_sky=None, periodic=None, placements=Vec::new()))]
#[allow(clippy::too_many_arguments)]
fn scene_from_arrays(
    py: Python<'_>,
    name: &str,
    vertices: &[u8],
    triangles: &[u8],
    object_ids: &[u8],
    names: Vec<String>,
    reflectance: &[u8],
    translucency: &[u8],
    per_face: bool,
    sun: Option<([f32; 3], [f32; 3])>,
    sky: Option<[f32; 3]>,
    cie_sky: Option<(u8, [f32; 3], [f32; 3])>,
    periodic: Option<[f32; 4]>,
    placements: Vec<(usize, Vec<u8>)>,
) -> PyResult<Scene> {
    let world = py.detach(|| -> Result<World, String> {
        let float = f32::from_le_bytes;
        let index = u32::from_le_bytes;
        let given = arrays::Arrays {
            vertices: arrays::rows::<3, f32>(vertices, "vertices", float)?
                .into_iter()
                .map(glam::Vec3::from)
                .collect(),
            triangles: arrays::rows::<3, u32>(triangles, "triangles", index)?,
            object_ids: arrays::rows::<1, u32>(object_ids, "object_ids", index)?
                .into_iter()
                .map(|[o]| o)
                .collect(),
            names,
            reflectance: arrays::rows::<3, f32>(reflectance, "reflectance", float)?,
            translucency: arrays::rows::<3, f32>(translucency, "translucency", float)?,
            per_face,
            sun,
            sky,
            cie_sky,
            periodic,
            placements: placements
                .iter()
                .map(|(object, bytes)| {
                    let rows = arrays::rows::<12, f32>(bytes, "placements", float)?;
                    Ok((*object, rows))
                })
                .collect::<Result<_, String>>()?,
        };
        let scene = arrays::scene(name, given)?;
        World::new(scene, AccelKind::Bvh).map_err(|e| format!("scene '{name}': {e}"))
    });
    Ok(Scene {
        world: Arc::new(world.map_err(PyValueError::new_err)?),
    })
}

/// Where the sun is at a local date and time (`utc_offset_hours` from UTC) seen from a site
/// (degrees north and east, metres above the sea, the mean pressure in mbar and temperature
/// in °C for refraction, ΔT = TT − UT1 in seconds), by NREL's Solar Position Algorithm:
/// zenith and azimuth (degrees; azimuth clockwise from north), the unit direction toward the
/// sun in strahl's frame (y up, −z north, +x east) and the Earth–Sun distance in AU.
#[pyfunction]
#[pyo3(signature = (year, month, day, hour, minute, second, utc_offset_hours, latitude_deg, longitude_deg, elevation_m=0.0, pressure_mbar=1013.25, temperature_c=15.0, delta_t_s=69.0))]
#[allow(clippy::too_many_arguments)]
fn sun_position(
    year: i32,
    month: u32,
    day: u32,
    hour: u32,
    minute: u32,
    second: f64,
    utc_offset_hours: f64,
    latitude_deg: f64,
    longitude_deg: f64,
    elevation_m: f64,
    pressure_mbar: f64,
    temperature_c: f64,
    delta_t_s: f64,
) -> PyResult<(f64, f64, [f64; 3], f64)> {
    let finite = [
        second,
        utc_offset_hours,
        latitude_deg,
        longitude_deg,
        elevation_m,
        pressure_mbar,
        temperature_c,
        delta_t_s,
    ]
    .iter()
    .all(|v| v.is_finite());
    if !finite || !(1..=12).contains(&month) || !(1..=31).contains(&day) || hour > 24 || minute > 59
    {
        return Err(PyValueError::new_err(
            "sun_position: a date, time or site out of range or not finite",
        ));
    }
    if !(-90.0..=90.0).contains(&latitude_deg) || !(-180.0..=180.0).contains(&longitude_deg) {
        return Err(PyValueError::new_err(format!(
            "sun_position: latitude {latitude_deg} must lie in −90…90 and longitude \
             {longitude_deg} in −180…180 degrees"
        )));
    }
    let time = LocalTime {
        year,
        month,
        day,
        hour,
        minute,
        second,
        utc_offset_hours,
        delta_ut1_s: 0.0,
        delta_t_s,
    };
    let observer = Observer {
        latitude_deg,
        longitude_deg,
        elevation_m,
        pressure_mbar,
        temperature_c,
        refraction_deg: strahl::scene::SUNRISE_REFRACTION_DEG,
    };
    let sun = strahl::scene::sun_position(&time, &observer);
    Ok((
        sun.zenith_deg,
        sun.azimuth_deg,
        sun.direction().to_array(),
        sun.distance_au,
    ))
}

/// The scene named `name` (built-in or a file), compiled.
fn open_world(name: &str) -> Result<World, String> {
    let scene = strahl::scene::open(name, &Default::default()).map_err(|e| e.to_string())?;
    World::new(scene, AccelKind::Bvh).map_err(|e| format!("scene '{name}': {e}"))
}

/// What a run reports while it works, read by the waiting thread.
#[derive(Default)]
struct Progress {
    phase: Mutex<String>,
    done: AtomicU64,
    total: AtomicU64,
}

impl ProgressListener for Progress {
    fn phase(&self, name: &str) {
        *self.phase.lock().unwrap_or_else(|e| e.into_inner()) = name.to_string();
    }
    fn start(&self, total: u64) {
        self.done.store(0, Ordering::Relaxed);
        self.total.store(total, Ordering::Relaxed);
    }
    fn estimate(&self, total: u64) {
        self.total.store(total, Ordering::Relaxed);
    }
    fn advance(&self, units: u64) {
        self.done.fetch_add(units, Ordering::Relaxed);
    }
    fn finish(&self) {}
}

/// `kind` at its defaults with `settings` set by name (the command line's options without
/// dashes: `error`, `mesh-size`, `spp`; see `Method::set`), seeded by `seed`, checked. `None`
/// values leave a setting at its default.
fn method(kind: &str, seed: u64, settings: &[(String, Bound<'_, PyAny>)]) -> PyResult<Method> {
    let kind = MethodKind::from_name(kind).ok_or_else(|| {
        let known: Vec<&str> = MethodKind::VALUES
            .iter()
            .map(|(_, name, _)| *name)
            .collect();
        PyValueError::new_err(format!(
            "unknown method '{kind}' (known: {})",
            known.join(", ")
        ))
    })?;
    let mut method = kind.with_defaults().with_seed(seed);
    for (name, value) in settings {
        if value.is_none() {
            continue;
        }
        let value = setting_value(name, value)?;
        method
            .set(name, &value)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
    }
    method
        .check()
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(method)
}

/// A Python value (a bool or numpy's, an int or anything with `__index__`, a float, a str)
/// as a setting's value.
fn setting_value(name: &str, value: &Bound<'_, PyAny>) -> PyResult<SettingValue> {
    if let Ok(b) = value.cast::<PyBool>() {
        return Ok(SettingValue::Bool(b.is_true()));
    }
    // numpy's bool scalar (`numpy.bool_`, from a mask or a comparison) is neither a Python
    // bool nor an integer: known by its dtype's kind.
    let numpy_bool = value
        .getattr("dtype")
        .and_then(|dtype| dtype.getattr("kind"))
        .is_ok_and(|kind| kind.extract::<String>().is_ok_and(|k| k == "b"));
    if numpy_bool {
        return Ok(SettingValue::Bool(value.is_truthy()?));
    }
    if value.is_instance_of::<PyString>() {
        return Ok(SettingValue::Text(value.extract()?));
    }
    if !value.is_instance_of::<PyFloat>()
        && let Ok(n) = value.extract::<i64>()
    {
        return Ok(SettingValue::Int(n));
    }
    if let Ok(x) = value.extract::<f64>() {
        return Ok(SettingValue::Float(x));
    }
    Err(PyValueError::new_err(format!(
        "{name}: expected a bool, a number or a str, not {}",
        value.get_type().name()?
    )))
}

impl Scene {
    /// The scene compiled with every face reported on its own (`per_face`) and without its
    /// non-diffuse lobes (`diffuse_only`); itself when neither is asked for.
    fn variant(&self, py: Python<'_>, per_face: bool, diffuse_only: bool) -> PyResult<Arc<World>> {
        if !per_face && !diffuse_only {
            return Ok(Arc::clone(&self.world));
        }
        let mut scene = self.world.scene.clone();
        if per_face {
            for object in &mut scene.objects {
                object.per_face = true;
            }
        }
        if diffuse_only {
            scene.keep_diffuse_lobes();
        }
        let world = py.detach(|| World::new(scene, AccelKind::Bvh));
        Ok(Arc::new(
            world.map_err(|e| PyValueError::new_err(e.to_string()))?,
        ))
    }
}

/// Runs `method` on `world`: [`run_with`] of the library's `run`.
fn run(
    world: &Arc<World>,
    py: Python<'_>,
    method: &Method,
    threads: usize,
    progress: Option<&Bound<'_, PyAny>>,
) -> PyResult<Outcome> {
    run_with(py, threads, progress, |listener, cancel| {
        strahl::method::run(world, method, listener, cancel).map_err(|e| e.to_string())
    })
}

/// Runs `work` on `threads` threads (0: one per core) with the GIL released; looks at Ctrl-C
/// (cancelling the work and raising `KeyboardInterrupt`) and calls `progress(phase, done,
/// total)` every [`POLL`] meanwhile. An error of the work becomes a `ValueError`.
fn run_with<T: Send>(
    py: Python<'_>,
    threads: usize,
    progress: Option<&Bound<'_, PyAny>>,
    work: impl FnOnce(&dyn ProgressListener, &Cancel) -> Result<T, String> + Send,
) -> PyResult<T> {
    let pool = rayon_pool(threads)?;
    let (listener, cancel) = (Progress::default(), Cancel::new());
    let (done, finished) = std::sync::mpsc::channel::<()>();
    // Behind a lock: the wait runs with the GIL released, which asks for a shareable one.
    let finished = Mutex::new(finished);
    std::thread::scope(|scope| {
        let work = scope.spawn(|| {
            let outcome = pool.install(|| work(&listener, &cancel));
            let _ = done.send(());
            outcome
        });
        let mut last = None;
        // Wakes when the work is done, or every POLL to look at Ctrl-C and progress.
        let wait = || {
            let finished = finished.lock().unwrap_or_else(|e| e.into_inner());
            finished.recv_timeout(POLL)
        };
        while py.detach(wait).is_err() {
            if let Err(interrupt) = py.check_signals() {
                cancel.request();
                let _ = py.detach(|| work.join());
                return Err(interrupt);
            }
            if let Some(callback) = progress {
                let phase = listener
                    .phase
                    .lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .clone();
                let now = (
                    phase,
                    listener.done.load(Ordering::Relaxed),
                    listener.total.load(Ordering::Relaxed),
                );
                if last.as_ref() != Some(&now) {
                    callback.call1(now.clone())?;
                    last = Some(now);
                }
            }
        }
        py.detach(|| work.join())
            .map_err(|_| PyRuntimeError::new_err("the run panicked"))?
            .map_err(PyValueError::new_err)
    })
}

/// A pool of `threads` threads (0: one per core).
fn rayon_pool(threads: usize) -> PyResult<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start {threads} threads: {e}")))
}

#[pymethods]
impl Scene {
    /// The scene's name.
    #[getter]
    fn name(&self) -> String {
        self.world.scene.name.clone()
    }

    /// The objects' names, in scene order.
    #[getter]
    fn objects(&self) -> Vec<String> {
        let scene = &self.world.scene;
        (0..scene.objects.len())
            .map(|k| scene.object_name(k))
            .collect()
    }

    /// The plot `(x₀, x₁, z₀, z₁)` (scene units) a periodic scene repeats without end in x
    /// and z; `None` for a scene that is not periodic.
    #[getter]
    fn periodic(&self) -> Option<(f32, f32, f32, f32)> {
        self.world
            .scene
            .periodic
            .map(|p| (p.x[0], p.x[1], p.z[0], p.z[1]))
    }

    /// Runs a method that reports the light on every surface (`light-trace`,
    /// `surface-trace`, `matrix`, `progressive`, `hierarchical`, `hierarchical-shooting`)
    /// with `settings` (name, value)
    /// and returns its report as JSON (the `strahl solve --report` file). `per_face` reports
    /// every face of every object on its own, `diffuse_only` drops the materials'
    /// non-diffuse lobes (`strahl solve --per-face --diffuse-only`). A scene with
    /// `[[bands]]` adds its bands' figures (`bands`, `red_far_red`), a scene with a `day` light
    /// each state's (`states`), by the same method.
    /// With `export` (a `.glb`, `.gltf` or `.ply` path) a radiosity solver's solution is
    /// also written as a mesh with radiosity vertex colours (`strahl solve --export`).
    #[pyo3(signature = (method, *, seed=0, threads=0, settings=Vec::new(), per_face=false, diffuse_only=false, export=None, progress=None))]
    #[allow(clippy::too_many_arguments)]
    fn solve(
        &self,
        py: Python<'_>,
        method: &str,
        seed: u64,
        threads: usize,
        settings: Vec<(String, Bound<'_, PyAny>)>,
        per_face: bool,
        diffuse_only: bool,
        export: Option<std::path::PathBuf>,
        progress: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<String> {
        let method = self::method(method, seed, &settings)?;
        if !method.kind().reports_surfaces() {
            return Err(PyValueError::new_err(format!(
                "method '{}' makes an image: use render()",
                method.kind().name()
            )));
        }
        if export.is_some() && method.radiosity().is_none() {
            return Err(PyValueError::new_err(format!(
                "export writes a radiosity solution's mesh: method '{}' makes none",
                method.kind().name()
            )));
        }
        if let Some(path) = &export {
            ExportFormat::from_path(path).map_err(|e| PyValueError::new_err(e.to_string()))?;
        }
        let world = self.variant(py, per_face, diffuse_only)?;
        // The scene's wavelength bands, when it has any, by the same method.
        let (outcome, parts) = run_with(py, threads, progress, |listener, cancel| {
            strahl::method::run_with_parts(&world, &method, listener, cancel)
                .map_err(|e| e.to_string())
        })?;
        if let (Some(path), Some(solved)) = (&export, &outcome.radiosity) {
            py.detach(|| {
                let lightmaps = ExportFormat::from_path(path)?.carries_lightmaps();
                let mesh = solved.lit_mesh(lightmaps);
                export_lit_mesh(&mesh, &world.scene.textures, &ToneMapping::default(), path)
            })
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        }
        let measured = outcome
            .measurement
            .ok_or_else(|| PyRuntimeError::new_err("the method measured no surfaces"))?;
        let mut report = Report::new(&world.scene.name, &measured).with_states(&parts.states);
        if let Some(bands) = &parts.bands {
            report = report.with_bands(bands);
        }
        serde_json::to_string(&report).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// Batch `index` of `count` of `method`'s run with `settings` — the light model's
    /// photons (`light-trace`) or the path tracer's samples per pixel (`pathtrace`) split —
    /// as JSON for [`Scene::merge_light`] or [`Scene::merge_render`]: run anywhere — another
    /// process, a Dask worker — on the same scene. The GIL is released while it runs; Ctrl-C
    /// stops it.
    #[pyo3(signature = (method, index, count, *, seed=0, threads=0, settings=Vec::new(), per_face=false, diffuse_only=false, progress=None))]
    #[allow(clippy::too_many_arguments)]
    fn batch(
        &self,
        py: Python<'_>,
        method: &str,
        index: u32,
        count: u32,
        seed: u64,
        threads: usize,
        settings: Vec<(String, Bound<'_, PyAny>)>,
        per_face: bool,
        diffuse_only: bool,
        progress: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<String> {
        let method = self::method(method, seed, &settings)?;
        let world = self.variant(py, per_face, diffuse_only)?;
        let batch = Batch { index, count };
        run_with(py, threads, progress, |listener, cancel| {
            let json = if method.kind() == MethodKind::PathTrace {
                let partial =
                    strahl::method::run_render_batch(&world, &method, batch, listener, cancel)
                        .map_err(|e| e.to_string())?;
                serde_json::to_string(&partial)
            } else {
                let partial = strahl::method::run_batch(&world, &method, batch, listener, cancel)
                    .map_err(|e| e.to_string())?;
                serde_json::to_string(&partial)
            };
            json.map_err(|e| e.to_string())
        })
    }

    /// The image of a path-traced render from the JSON `partials` of all its batches
    /// ([`Scene::batch`], each once, any order): width, height and the linear radiance
    /// (W·sr⁻¹·m⁻²) as little-endian `f32` RGB, rows from the top — the image one render
    /// with the same settings gives, bit for bit.
    fn merge_render<'py>(
        &self,
        py: Python<'py>,
        partials: Vec<String>,
    ) -> PyResult<(u32, u32, Bound<'py, PyBytes>)> {
        let film = py
            .detach(|| -> Result<Film, String> {
                let partials = partials
                    .iter()
                    .enumerate()
                    .map(|(k, p)| serde_json::from_str(p).map_err(|e| format!("partial {k}: {e}")))
                    .collect::<Result<Vec<strahl::method::RenderPartial>, String>>()?;
                let outcome = strahl::method::merge_render_batches(&self.world, &partials)
                    .map_err(|e| e.to_string())?;
                outcome
                    .image
                    .ok_or_else(|| "the merge made no image".to_string())
            })
            .map_err(PyValueError::new_err)?;
        Ok(film_bytes(py, &film))
    }

    /// The report (JSON) of a light-model run from the JSON `partials` of all its batches
    /// ([`Scene::batch`], each once, any order): the one a single run with the same settings
    /// gives, but for the seconds. `per_face` and `diffuse_only` as the batches were run.
    #[pyo3(signature = (partials, *, per_face=false, diffuse_only=false))]
    fn merge_light(
        &self,
        py: Python<'_>,
        partials: Vec<String>,
        per_face: bool,
        diffuse_only: bool,
    ) -> PyResult<String> {
        let world = self.variant(py, per_face, diffuse_only)?;
        py.detach(|| -> Result<String, String> {
            let partials = partials
                .iter()
                .enumerate()
                .map(|(k, p)| serde_json::from_str(p).map_err(|e| format!("partial {k}: {e}")))
                .collect::<Result<Vec<strahl::method::LightTracePartial>, String>>()?;
            let outcome =
                strahl::method::merge_batches(&world, &partials).map_err(|e| e.to_string())?;
            let measured = outcome
                .measurement
                .ok_or("the merge measured no surfaces")?;
            serde_json::to_string(&Report::new(&world.scene.name, &measured))
                .map_err(|e| e.to_string())
        })
        .map_err(PyValueError::new_err)
    }

    /// The names of the settings `method` takes (`seed` first), as `solve` and `render` take
    /// them.
    #[staticmethod]
    fn setting_names(method: &str) -> PyResult<Vec<&'static str>> {
        Ok(self::method(method, 0, &[])?.setting_names())
    }

    /// Renders an image (`pathtrace`, `raytrace`, `radiosity`, `final-gather`) with
    /// `settings` (name, value): returns its width, height and linear radiance as
    /// little-endian `f32` RGB, rows from the top, W·sr⁻¹·m⁻².
    #[pyo3(signature = (method, *, seed=0, threads=0, settings=Vec::new(), progress=None))]
    fn render<'py>(
        &self,
        py: Python<'py>,
        method: &str,
        seed: u64,
        threads: usize,
        settings: Vec<(String, Bound<'py, PyAny>)>,
        progress: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<(u32, u32, Bound<'py, PyBytes>)> {
        let method = self::method(method, seed, &settings)?;
        let outcome = run(&self.world, py, &method, threads, progress)?;
        let film = outcome.image.ok_or_else(|| {
            PyValueError::new_err(format!(
                "method '{}' makes no image: use solve()",
                method.kind().name()
            ))
        })?;
        Ok(film_bytes(py, &film))
    }
}

/// A film's width, height and pixels as little-endian `f32` RGB, rows from the top.
fn film_bytes<'py>(py: Python<'py>, film: &Film) -> (u32, u32, Bound<'py, PyBytes>) {
    let bytes: Vec<u8> = film
        .pixels()
        .iter()
        .flat_map(|p| p.to_array())
        .flat_map(f32::to_le_bytes)
        .collect();
    (film.width(), film.height(), PyBytes::new(py, &bytes))
}

/// Writes the report `report` (JSON, as `Scene.solve` returns it) to `path`: `.json` (the
/// whole report) or `.csv` (one row per surface, and the sensors beside it in
/// `NAME.sensors.csv`), as `strahl solve --report` writes them.
#[pyfunction]
fn write_report(report: &str, path: std::path::PathBuf) -> PyResult<()> {
    let report: Report = serde_json::from_str(report)
        .map_err(|e| PyValueError::new_err(format!("not a strahl report: {e}")))?;
    strahl::report::write_report(&report, &path).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// The extension module.
#[pymodule]
fn _strahl(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Scene>()?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(scene_from_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(write_report, m)?)?;
    m.add_function(wrap_pyfunction!(table::report_columns, m)?)?;
    m.add_function(wrap_pyfunction!(sun_position, m)?)?;
    Ok(())
}
