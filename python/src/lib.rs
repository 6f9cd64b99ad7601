//! The `strahl` Python package's extension module (`strahl._strahl`): scenes opened by name
//! or file, every method run through the library's method API with the GIL released,
//! Ctrl-C (`KeyboardInterrupt`) and a progress callback looked at every 50 ms, results as
//! the report's JSON and images as raw `f32` bytes (the Python side turns both into numpy
//! arrays: `python/strahl/__init__.py`).

mod arrays;

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;
use strahl::method::{
    AccelKind, Cancel, Choice, ImageSize, Method, MethodKind, NoProgress, Outcome,
    ProgressListener, World,
};
use strahl::report::Report;

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
/// direction its light travels, the irradiance facing it in W·m⁻²) and a uniform sky
/// (radiance, W·sr⁻¹·m⁻²). With `per_face`, every triangle is reported on its own.
#[pyfunction]
#[pyo3(signature = (name, vertices, triangles, object_ids, names, reflectance, translucency, per_face, sun, sky))]
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
        };
        let scene = arrays::scene(name, given)?;
        World::new(scene, AccelKind::Bvh).map_err(|e| format!("scene '{name}': {e}"))
    });
    Ok(Scene {
        world: Arc::new(world.map_err(PyValueError::new_err)?),
    })
}

/// The scene named `name` (built-in or a file), compiled.
fn open_world(name: &str) -> Result<World, String> {
    let scene = strahl::scene::open(name, &Default::default()).map_err(|e| e.to_string())?;
    World::new(scene, AccelKind::Bvh).map_err(|e| format!("scene '{name}': {e}"))
}

/// Batch `index` of `count` of a light-model run of `photons` photons on the scene `name`
/// (built-in or a file, opened here: this runs where the batch is sent), as JSON for
/// [`merge_batches`]. The GIL is released while it traces.
#[pyfunction]
#[pyo3(signature = (name, photons, seed, index, count, threads=0))]
fn light_trace_batch(
    py: Python<'_>,
    name: &str,
    photons: u64,
    seed: u64,
    index: u32,
    count: u32,
    threads: usize,
) -> PyResult<String> {
    let pool = rayon_pool(threads)?;
    py.detach(|| -> Result<String, String> {
        let world = open_world(name)?;
        let method = Method::LightTrace(strahl::method::LightTraceSettings {
            photons,
            seed,
            ..Default::default()
        });
        let batch = strahl::method::Batch { index, count };
        let partial = pool
            .install(|| {
                strahl::method::run_batch(&world, &method, batch, &NoProgress, &Cancel::new())
            })
            .map_err(|e| e.to_string())?;
        serde_json::to_string(&partial).map_err(|e| e.to_string())
    })
    .map_err(PyValueError::new_err)
}

/// The report (JSON) of the whole run on the scene `name` from the JSON `partials` of all
/// its batches: the one a single run with the same settings gives, but for the seconds.
#[pyfunction]
fn merge_batches(py: Python<'_>, name: &str, partials: Vec<String>) -> PyResult<String> {
    py.detach(|| -> Result<String, String> {
        let world = open_world(name)?;
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
        serde_json::to_string(&Report::new(&world.scene.name, &measured)).map_err(|e| e.to_string())
    })
    .map_err(PyValueError::new_err)
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

/// The settings a run takes from Python's keywords.
struct Asked {
    seed: u64,
    photons: Option<u64>,
    error: Option<f64>,
    samples_per_pixel: Option<u32>,
    size: Option<(u32, u32)>,
}

/// `kind` at its defaults with what `asked` sets; an error names a setting the method does
/// not take.
fn method(kind: &str, asked: &Asked) -> PyResult<Method> {
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
    let mut method = kind.with_defaults().with_seed(asked.seed);
    let refuse = |setting: &str| {
        PyValueError::new_err(format!("method '{}' takes no {setting}", kind.name()))
    };
    if let Some(photons) = asked.photons {
        match &mut method {
            Method::LightTrace(s) => s.photons = photons,
            _ => return Err(refuse("photons")),
        }
    }
    if let Some(error) = asked.error {
        match &mut method {
            Method::Radiosity(s) => s.hierarchical.error = error,
            _ => return Err(refuse("error")),
        }
    }
    if let Some(spp) = asked.samples_per_pixel {
        match &mut method {
            Method::PathTrace(s) => s.samples_per_pixel = spp,
            _ => return Err(refuse("samples_per_pixel")),
        }
    }
    if let Some((width, height)) = asked.size {
        let size = ImageSize {
            width: Some(width),
            height: Some(height),
        };
        match &mut method {
            Method::PathTrace(s) => s.size = size,
            Method::RayTrace(s) => s.size = size,
            Method::RadiosityImage(s) => s.size = size,
            Method::FinalGather(s) => s.size = size,
            _ => return Err(refuse("image size")),
        }
    }
    method
        .check()
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(method)
}

impl Scene {
    /// Runs `method` on `threads` threads (0: one per core) with the GIL released; looks at
    /// Ctrl-C and calls `progress(phase, done, total)` every [`POLL`] meanwhile.
    fn run(
        &self,
        py: Python<'_>,
        method: &Method,
        threads: usize,
        progress: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Outcome> {
        let pool = rayon_pool(threads)?;
        let (listener, cancel) = (Progress::default(), Cancel::new());
        let (done, finished) = std::sync::mpsc::channel::<()>();
        // Behind a lock: the wait runs with the GIL released, which asks for a shareable one.
        let finished = Mutex::new(finished);
        std::thread::scope(|scope| {
            let work = scope.spawn(|| {
                let outcome =
                    pool.install(|| strahl::method::run(&self.world, method, &listener, &cancel));
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
                .map_err(|e| PyValueError::new_err(e.to_string()))
        })
    }
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

    /// Runs a method that reports the light on every surface (`light-trace`, `matrix`,
    /// `progressive`, `hierarchical`, `hierarchical-shooting`) and returns its report as
    /// JSON (the `strahl solve --report` file).
    #[pyo3(signature = (method, *, seed=0, threads=0, photons=None, error=None, progress=None))]
    #[allow(clippy::too_many_arguments)]
    fn solve(
        &self,
        py: Python<'_>,
        method: &str,
        seed: u64,
        threads: usize,
        photons: Option<u64>,
        error: Option<f64>,
        progress: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<String> {
        let asked = Asked {
            seed,
            photons,
            error,
            samples_per_pixel: None,
            size: None,
        };
        let method = self::method(method, &asked)?;
        if !method.kind().reports_surfaces() {
            return Err(PyValueError::new_err(format!(
                "method '{}' makes an image: use render()",
                method.kind().name()
            )));
        }
        let outcome = self.run(py, &method, threads, progress)?;
        let measured = outcome
            .measurement
            .ok_or_else(|| PyRuntimeError::new_err("the method measured no surfaces"))?;
        let report = Report::new(&self.world.scene.name, &measured);
        serde_json::to_string(&report).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// Renders an image (`pathtrace`, `raytrace`, `radiosity`, `final-gather`): returns its
    /// width, height and linear radiance as little-endian `f32` RGB, rows from the top,
    /// W·sr⁻¹·m⁻².
    #[pyo3(signature = (method, *, width=None, height=None, samples_per_pixel=None, seed=0, threads=0, progress=None))]
    #[allow(clippy::too_many_arguments)]
    fn render<'py>(
        &self,
        py: Python<'py>,
        method: &str,
        width: Option<u32>,
        height: Option<u32>,
        samples_per_pixel: Option<u32>,
        seed: u64,
        threads: usize,
        progress: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<(u32, u32, Bound<'py, PyBytes>)> {
        let camera = &self.world.scene.camera;
        let size = match (width, height) {
            (None, None) => None,
            (w, h) => Some((w.unwrap_or(camera.width), h.unwrap_or(camera.height))),
        };
        let asked = Asked {
            seed,
            photons: None,
            error: None,
            samples_per_pixel,
            size,
        };
        let method = self::method(method, &asked)?;
        let outcome = self.run(py, &method, threads, progress)?;
        let film = outcome.image.ok_or_else(|| {
            PyValueError::new_err(format!(
                "method '{}' makes no image: use solve()",
                method.kind().name()
            ))
        })?;
        let bytes: Vec<u8> = film
            .pixels()
            .iter()
            .flat_map(|p| p.to_array())
            .flat_map(f32::to_le_bytes)
            .collect();
        Ok((film.width(), film.height(), PyBytes::new(py, &bytes)))
    }
}

/// The extension module.
#[pymodule]
fn _strahl(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Scene>()?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(scene_from_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(light_trace_batch, m)?)?;
    m.add_function(wrap_pyfunction!(merge_batches, m)?)?;
    Ok(())
}
