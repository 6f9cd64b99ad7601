//! Every setting of every method by name, for front ends that take settings as keywords (the
//! Python package's `scene.solve("hierarchical", error=1e-5, oracle="lischinski")`) rather
//! than as typed flags. The names are the command line's options without their dashes
//! (`max-bounces`, `mesh-size`, `spp`), so an error names a setting alike in both; the
//! command line's negative switches (`--no-clustering`) are positive settings here
//! (`clustering`, default on). Ranges are checked by [`Method::check`], not when a value is
//! set.

use super::{LinkSelection, Method, RadiositySettings, SettingError};
use crate::choice::Choice;
use crate::radiosity::{MeshSize, VisRays};

/// A setting's value as a front end hands it over.
#[derive(Clone, Debug, PartialEq)]
pub enum SettingValue {
    /// A switch.
    Bool(bool),
    /// A whole number (also taken where a real number is asked for).
    Int(i64),
    /// A real number.
    Float(f64),
    /// A name (`oracle="lischinski"`), or a value written as text (`mesh-size="levels:2"`).
    Text(String),
}

/// Settings of the image methods' size.
const SIZE: [&str; 2] = ["width", "height"];

/// Settings of every radiosity solve: mesh, form factors, visibility, light links and each
/// solver's iteration and refinement (see `strahl solve --help` for what each does).
const RADIOSITY: [&str; 23] = [
    "mesh-size",
    "segments",
    "linking",
    "form-factor",
    "receiver-samples",
    "vis-rays",
    "shaft-culling",
    "link-samples",
    "periodic-margin",
    "iteration",
    "tolerance",
    "max-iterations",
    "max-shots",
    "overshoot",
    "oracle",
    "error",
    "surface-error",
    "min-area",
    "refine-pass",
    "max-rounds",
    "clustering",
    "near-rays-from",
    "fine-gather",
];

/// The final gather at the reported surfaces (the radiosity solvers' reports).
const SURFACE_GATHER: [&str; 2] = ["surface-gather", "gather-below"];

impl Method {
    /// The names of the settings this method takes (`seed` first), as [`Method::set`] takes
    /// them.
    pub fn setting_names(&self) -> Vec<&'static str> {
        let own: &[&'static str] = match self {
            Method::RayTrace(_) => &[
                "depth",
                "light-samples",
                "shadows",
                "aa",
                "spp",
                "aa-threshold",
            ],
            Method::PathTrace(_) => &["depth", "first-hit-paths", "spp", "time-limit"],
            Method::RadiosityImage(_) => &["shading", "wireframe", "links", "spp"],
            Method::FinalGather(_) => &[
                "shading",
                "light-samples",
                "gather-rays",
                "aa",
                "spp",
                "aa-threshold",
            ],
            Method::SensorTrace(_) => &["samples", "paths"],
            Method::LightTrace(_) => &["photons", "max-bounces"],
            Method::SurfaceTrace(_) => &["points", "standard-error"],
            Method::Radiosity(_) => &SURFACE_GATHER,
        };
        let mut names = vec!["seed"];
        let image = matches!(
            self,
            Method::RayTrace(_)
                | Method::PathTrace(_)
                | Method::RadiosityImage(_)
                | Method::FinalGather(_)
        );
        if image {
            names.extend(SIZE);
        }
        names.extend(own);
        if self.radiosity().is_some() {
            names.extend(RADIOSITY);
        }
        names
    }

    /// Sets the setting called `name` (one of [`Method::setting_names`]) to `value`. An
    /// unknown name, or a value of the wrong kind (text for a count, a fraction for a count,
    /// a count beyond its type), is refused with the setting named; whether the value lies in
    /// its range is for [`Method::check`] to say.
    pub fn set(&mut self, name: &str, value: &SettingValue) -> Result<(), SettingError> {
        let names = self.setting_names();
        let Some(&name) = names.iter().find(|&&n| n == name) else {
            return Err(SettingError::new(
                self.kind().name(),
                format!(
                    "takes no setting '{name}' (its settings: {})",
                    names.join(", ")
                ),
            ));
        };
        let v = Value { name, value };
        if name == "seed" {
            *self = self.clone().with_seed(v.count64()?);
            return Ok(());
        }
        if RADIOSITY.contains(&name) {
            let settings = match self {
                Method::RadiosityImage(s) => &mut s.radiosity,
                Method::FinalGather(s) => &mut s.radiosity,
                Method::Radiosity(s) => s,
                _ => unreachable!("only radiosity methods list radiosity settings"),
            };
            return set_radiosity(settings, v);
        }
        match self {
            Method::RayTrace(s) => match name {
                "width" => s.size.width = Some(v.count()?),
                "height" => s.size.height = Some(v.count()?),
                "depth" => s.max_depth = v.count()?,
                "light-samples" => s.light_samples = v.count()?,
                "shadows" => s.shadows = v.choice()?,
                "aa" => s.antialias.mode = v.choice()?,
                "spp" => s.antialias.samples_per_pixel = v.count()?,
                _ => s.antialias.threshold = v.real()? as f32,
            },
            Method::PathTrace(s) => match name {
                "width" => s.size.width = Some(v.count()?),
                "height" => s.size.height = Some(v.count()?),
                "depth" => s.max_depth = v.count()?,
                "first-hit-paths" => s.first_hit_paths = v.count()?,
                "spp" => s.samples_per_pixel = v.count()?,
                _ => s.time_limit = Some(v.real()?),
            },
            Method::RadiosityImage(s) => match name {
                "width" => s.size.width = Some(v.count()?),
                "height" => s.size.height = Some(v.count()?),
                "shading" => s.shading = v.choice()?,
                "wireframe" => s.wireframe = v.switch()?,
                "links" => s.links = v.links()?,
                _ => s.samples_per_pixel = v.count()?,
            },
            Method::FinalGather(s) => match name {
                "width" => s.size.width = Some(v.count()?),
                "height" => s.size.height = Some(v.count()?),
                "shading" => s.shading = v.choice()?,
                "light-samples" => s.light_samples = v.count()?,
                "gather-rays" => s.gather_rays = v.count()?,
                "aa" => s.antialias.mode = v.choice()?,
                "spp" => s.antialias.samples_per_pixel = v.count()?,
                _ => s.antialias.threshold = v.real()? as f32,
            },
            Method::SensorTrace(s) => match name {
                "samples" => s.samples = v.count()?,
                _ => s.paths = v.count()?,
            },
            Method::LightTrace(s) => match name {
                "photons" => s.photons = v.count64()?,
                _ => s.max_bounces = v.count()?,
            },
            Method::SurfaceTrace(s) => match name {
                "points" => s.points = v.count()?,
                _ => s.standard_error = v.real()?,
            },
            Method::Radiosity(s) => match name {
                "surface-gather" => s.surface_gather.error = v.real()?,
                _ => s.surface_gather.below_share = v.real()?,
            },
        }
        Ok(())
    }
}

/// Sets the radiosity setting `v.name` (one of [`RADIOSITY`]).
fn set_radiosity(s: &mut RadiositySettings, v: Value<'_>) -> Result<(), SettingError> {
    let system = &mut s.system;
    let h = &mut s.hierarchical;
    match v.name {
        "mesh-size" => system.mesh.size = v.mesh_size()?,
        "segments" => system.mesh.segments = v.count()?,
        "linking" => {
            system.mesh.contact_splits = match v.text()? {
                "asymmetric" => true,
                "normal" => false,
                other => {
                    return Err(v.refuse(format!("'{other}' is not one of: normal, asymmetric")));
                }
            }
        }
        "form-factor" => system.form_factor.method = v.choice()?,
        "receiver-samples" => system.form_factor.receiver_samples = v.count()?,
        "vis-rays" => system.visibility.rays = v.vis_rays()?,
        "shaft-culling" => system.visibility.shaft_culling = v.switch()?,
        "link-samples" => system.link_samples = v.count()?,
        "periodic-margin" => system.periodic_margin = Some(v.real()? as f32),
        "iteration" => s.matrix.iteration = v.choice()?,
        "tolerance" => *s = s.with_tolerance(v.real()?),
        "max-iterations" => s.matrix.max_iterations = v.count()?,
        "max-shots" => s.shooting.max_shots = v.count64()?,
        "overshoot" => s.shooting.overshoot = v.switch()?,
        "oracle" => h.oracle = v.choice()?,
        "error" => h.error = v.real()?,
        "surface-error" => h.surface_error = v.real()?,
        "min-area" => h.min_area = v.real()?,
        "refine-pass" => h.refine_pass = v.choice()?,
        "max-rounds" => h.max_rounds = v.count()?,
        "clustering" => h.clustering = v.switch()?,
        "near-rays-from" => h.near_rays_from = v.count64()? as usize,
        _ => h.fine_gather = v.switch()?,
    }
    Ok(())
}

/// A value handed over for the setting `name`, read as the kind that setting needs.
#[derive(Clone, Copy)]
struct Value<'a> {
    name: &'static str,
    value: &'a SettingValue,
}

impl<'a> Value<'a> {
    /// The setting refused for `problem`.
    fn refuse(self, problem: impl Into<String>) -> SettingError {
        SettingError::new(self.name, problem)
    }

    /// The value described for an error message.
    fn shown(self) -> String {
        match self.value {
            SettingValue::Bool(b) => b.to_string(),
            SettingValue::Int(n) => n.to_string(),
            SettingValue::Float(x) => x.to_string(),
            SettingValue::Text(t) => format!("'{t}'"),
        }
    }

    /// A count of at most `u64::MAX`.
    fn count64(self) -> Result<u64, SettingError> {
        match self.value {
            SettingValue::Int(n) if *n >= 0 => Ok(*n as u64),
            _ => Err(self.refuse(format!(
                "must be a whole number, 0 or more (got {})",
                self.shown()
            ))),
        }
    }

    /// A count of at most `u32::MAX`.
    fn count(self) -> Result<u32, SettingError> {
        let n = self.count64()?;
        u32::try_from(n).map_err(|_| self.refuse(format!("must be at most {} (got {n})", u32::MAX)))
    }

    /// A real number (a whole number taken as one).
    fn real(self) -> Result<f64, SettingError> {
        match self.value {
            SettingValue::Float(x) => Ok(*x),
            SettingValue::Int(n) => Ok(*n as f64),
            _ => Err(self.refuse(format!("must be a number (got {})", self.shown()))),
        }
    }

    /// A switch.
    fn switch(self) -> Result<bool, SettingError> {
        match self.value {
            SettingValue::Bool(b) => Ok(*b),
            _ => Err(self.refuse(format!("must be true or false (got {})", self.shown()))),
        }
    }

    /// Text.
    fn text(self) -> Result<&'a str, SettingError> {
        match self.value {
            SettingValue::Text(t) => Ok(t),
            _ => Err(self.refuse(format!("must be a name (got {})", self.shown()))),
        }
    }

    /// One of `T`'s named values.
    fn choice<T: Choice>(self) -> Result<T, SettingError> {
        crate::choice::parse(self.text()?).map_err(|e| self.refuse(e.to_string()))
    }

    /// `levels:N` as text, or the longest patch edge as a number.
    fn mesh_size(self) -> Result<MeshSize, SettingError> {
        match self.value {
            SettingValue::Text(t) => t.parse().map_err(|e: String| self.refuse(e)),
            _ => Ok(MeshSize::MaxEdge(self.real()?)),
        }
    }

    /// A ray count, or `adaptive`.
    fn vis_rays(self) -> Result<VisRays, SettingError> {
        match self.value {
            SettingValue::Text(t) => t.parse().map_err(|e: String| self.refuse(e)),
            _ => match self.count()? {
                0 => Err(self.refuse("must be a positive count or 'adaptive' (got 0)")),
                n => Ok(VisRays::Fixed(n)),
            },
        }
    }

    /// `true` (every link), `false` (none) or an object's name.
    fn links(self) -> Result<LinkSelection, SettingError> {
        match self.value {
            SettingValue::Bool(true) => Ok(LinkSelection::All),
            SettingValue::Bool(false) => Ok(LinkSelection::None),
            SettingValue::Text(t) => Ok(LinkSelection::Object(t.clone())),
            _ => Err(self.refuse(format!(
                "must be true (every link), false or an object's name (got {})",
                self.shown()
            ))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::method::{MethodKind, Oracle, SolverKind};

    fn text(t: &str) -> SettingValue {
        SettingValue::Text(t.to_string())
    }

    #[test]
    fn every_listed_setting_of_every_method_is_set() {
        let kinds = MethodKind::IMAGES
            .into_iter()
            .chain(MethodKind::SURFACE_SOLVERS)
            .chain([MethodKind::Direct]);
        for kind in kinds {
            let defaults = kind.with_defaults();
            for name in defaults.setting_names() {
                // Some value of some kind is taken and changes the method: every name listed
                // reaches a field.
                let mut values = choice_names(name);
                values.extend([
                    SettingValue::Int(2),
                    SettingValue::Bool(false),
                    SettingValue::Bool(true),
                    SettingValue::Float(0.5),
                    text("levels:1"),
                    text("normal"),
                    text("links-of"),
                ]);
                let changes = values.iter().any(|v| {
                    let mut m = defaults.clone();
                    m.set(name, v).is_ok() && m != defaults
                });
                assert!(changes, "{}: no value changes {name}", kind.name());
            }
        }
    }

    /// Every name the choice setting `name` takes (none for the others).
    fn choice_names(name: &str) -> Vec<SettingValue> {
        use crate::method::{
            AntialiasMode, FormFactorMethod, Iteration, RefinePass, Shading, ShadowMode,
        };
        fn all<T: Choice>() -> Vec<SettingValue> {
            T::VALUES.iter().map(|(_, n, _)| text(n)).collect()
        }
        match name {
            "shadows" => all::<ShadowMode>(),
            "aa" => all::<AntialiasMode>(),
            "shading" => all::<Shading>(),
            "form-factor" => all::<FormFactorMethod>(),
            "iteration" => all::<Iteration>(),
            "oracle" => all::<Oracle>(),
            "refine-pass" => all::<RefinePass>(),
            _ => Vec::new(),
        }
    }

    #[test]
    fn values_reach_their_fields() {
        let mut m = MethodKind::Radiosity(SolverKind::Hierarchical).with_defaults();
        m.set("error", &SettingValue::Float(1e-5)).unwrap();
        m.set("mesh-size", &text("levels:2")).unwrap();
        m.set("clustering", &SettingValue::Bool(false)).unwrap();
        m.set("tolerance", &SettingValue::Float(1e-6)).unwrap();
        m.set("max-shots", &SettingValue::Int(7)).unwrap();
        m.set("refine-pass", &text("all")).unwrap();
        m.set("seed", &SettingValue::Int(9)).unwrap();
        m.set("surface-gather", &SettingValue::Int(0)).unwrap();
        let Method::Radiosity(s) = &m else {
            unreachable!()
        };
        assert_eq!(s.hierarchical.error, 1e-5);
        assert_eq!(s.system.mesh.size, MeshSize::Levels(2));
        assert!(!s.hierarchical.clustering);
        assert_eq!(
            (
                s.hierarchical.tolerance,
                s.matrix.tolerance,
                s.shooting.tolerance
            ),
            (1e-6, 1e-6, 1e-6)
        );
        assert_eq!(s.shooting.max_shots, 7);
        assert_eq!(s.hierarchical.refine_pass, crate::method::RefinePass::All);
        assert_eq!(s.system.visibility.seed, 9);
        assert_eq!(s.surface_gather.error, 0.0);

        let mut p = MethodKind::PathTrace.with_defaults();
        p.set("spp", &SettingValue::Int(3)).unwrap();
        p.set("width", &SettingValue::Int(40)).unwrap();
        p.set("time-limit", &SettingValue::Int(2)).unwrap();
        let Method::PathTrace(s) = &p else {
            unreachable!()
        };
        assert_eq!(
            (s.samples_per_pixel, s.size.width, s.time_limit),
            (3, Some(40), Some(2.0))
        );
    }

    #[test]
    fn refusals_name_the_setting() {
        let mut m = MethodKind::LightTrace.with_defaults();
        let e = m.set("error", &SettingValue::Float(1e-3)).unwrap_err();
        assert_eq!(
            e.to_string(),
            "light-trace takes no setting 'error' (its settings: seed, photons, max-bounces)"
        );
        let e = m.set("photons", &SettingValue::Float(1.5)).unwrap_err();
        assert_eq!(
            e.to_string(),
            "photons must be a whole number, 0 or more (got 1.5)"
        );
        let e = m.set("photons", &SettingValue::Int(-1)).unwrap_err();
        assert_eq!(e.setting, "photons");
        let e = m
            .set("max-bounces", &SettingValue::Int(1 << 40))
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            format!(
                "max-bounces must be at most {} (got {})",
                u32::MAX,
                1u64 << 40
            )
        );
        let mut h = MethodKind::Radiosity(SolverKind::Hierarchical).with_defaults();
        let e = h.set("oracle", &text("best")).unwrap_err();
        assert!(
            e.to_string().starts_with("oracle 'best' is not one of: "),
            "{e}"
        );
        let e = h.set("mesh-size", &text("levels:x")).unwrap_err();
        assert!(
            e.to_string().starts_with("mesh-size mesh size 'levels:x'"),
            "{e}"
        );
        let e = h.set("clustering", &SettingValue::Int(1)).unwrap_err();
        assert_eq!(e.to_string(), "clustering must be true or false (got 1)");
        // Ranges are the check's.
        h.set("error", &SettingValue::Float(0.0)).unwrap();
        assert_eq!(h.check().unwrap_err().setting, "error");
    }
}
