//! `[[bands]]`, and the spectra of lights (`spectrum`) and materials (`diffuse_spectrum`,
//! `translucency_spectrum`): samples inline, a CSV file, a black body, or a spectrum strahl
//! ships.

use super::error::{SceneError, Source};
use super::fields::Table;
use super::format::SceneFile;
use super::number_rows::read_number_rows;
use crate::color::{Band, MAX_WAVELENGTH_NM, Rgb, Spectrum, StandardSpectrum};
use crate::scene::{ENERGY_TOLERANCE, MaterialId, MaterialSpectra, Scene, Spectral};
use std::path::Path;
use toml::{Spanned, Value};

/// What a spectrum field may hold, for error messages.
const SPECTRUM_FORMS: &str = "a spectrum is [[nm, value], …], the name of a CSV file of nm,value lines, \
     { blackbody_k = kelvin }, or { standard = \"astm-g173-direct\" } (or -global, -diffuse, \
     -extraterrestrial)";

/// The spectrum in field `field` of table `t`; CSV files are read relative to `base_dir`.
pub(super) fn build_spectrum(
    t: &Table<'_>,
    field: &str,
    v: &Spanned<Value>,
    base_dir: &Path,
) -> Result<Spectrum, SceneError> {
    let error = |message: String| t.error(v.span(), field, message);
    match v.get_ref() {
        Value::String(file) => {
            let path = base_dir.join(file);
            read_csv(&path).map_err(error)
        }
        Value::Array(rows) => {
            let mut samples = Vec::with_capacity(rows.len());
            for (i, row) in rows.iter().enumerate() {
                let pair = row.as_array().filter(|r| r.len() == 2).and_then(|r| {
                    let number =
                        |x: &Value| x.as_float().or_else(|| x.as_integer().map(|i| i as f64));
                    Some((number(&r[0])?, number(&r[1])?))
                });
                samples.push(pair.ok_or_else(|| {
                    error(format!(
                        "sample {i} is not a pair [nm, value]; {SPECTRUM_FORMS}"
                    ))
                })?);
            }
            Spectrum::sampled(samples).map_err(|e| error(e.to_string()))
        }
        Value::Table(table) if table.len() == 1 => {
            if let Some(name) = table.get("standard") {
                return name
                    .as_str()
                    .and_then(StandardSpectrum::from_name)
                    .map(StandardSpectrum::spectrum)
                    .ok_or_else(|| {
                        let known: Vec<&str> =
                            StandardSpectrum::ALL.iter().map(|s| s.name()).collect();
                        error(format!(
                            "unknown standard spectrum {name}; strahl knows {}",
                            known.join(", ")
                        ))
                    });
            }
            let kelvin = table
                .get("blackbody_k")
                .and_then(|k| k.as_float().or_else(|| k.as_integer().map(|i| i as f64)));
            match kelvin {
                Some(k) => Spectrum::blackbody(k).map_err(|e| error(e.to_string())),
                None => Err(error(SPECTRUM_FORMS.to_string())),
            }
        }
        _ => Err(error(SPECTRUM_FORMS.to_string())),
    }
}

/// The spectrum in the CSV file `path`: one `nm,value` pair a line ([`read_number_rows`]).
fn read_csv(path: &Path) -> Result<Spectrum, String> {
    let expected = "two numbers, wavelength nm and value";
    let rows = read_number_rows(path, "spectrum", expected)?;
    let mut samples = Vec::with_capacity(rows.len());
    for (line, numbers) in rows {
        match numbers[..] {
            [nm, value] => samples.push((nm, value)),
            _ => return Err(format!("{}:{line}: expected {expected}", path.display())),
        }
    }
    Spectrum::sampled(samples).map_err(|e| format!("{}: {e}", path.display()))
}

/// Wavelengths of the red, green and blue thirds of the visible, nm: a spectrum's plain means
/// over them are its RGB colour where the material gives none.
const RGB_THIRDS: [(f64, f64); 3] = [(600.0, 700.0), (500.0, 600.0), (400.0, 500.0)];

/// The RGB colour of a reflectance or transmittance spectrum: its plain means over
/// [`RGB_THIRDS`].
fn rgb_of(s: &Spectrum) -> Rgb {
    Rgb::from(RGB_THIRDS.map(|(from_nm, to_nm)| {
        let third = Band {
            name: String::new(),
            from_nm,
            to_nm,
        };
        (s.integral(&third) / (to_nm - from_nm)) as f32
    }))
}

/// The scene's bands and spectra from `file` (a lobe given as a spectrum alone takes its RGB
/// colour from it, [`rgb_of`]), with `light_spectra` (the spectrum given to
/// each of `scene.lights`, with the index of its `[[lights]]` entry); `None` without bands.
/// Checks that every light has a spectrum, that spectra come with bands, and that every
/// band can be solved ([`Spectral::validate`]).
pub(super) fn build_spectral(
    src: Source<'_>,
    file: &SceneFile,
    base_dir: &Path,
    scene: &mut Scene,
    light_spectra: Vec<(usize, Option<Spectrum>)>,
) -> Result<Option<Spectral>, SceneError> {
    let mut materials = Vec::new();
    for (key, entry) in &file.materials {
        let t = Table::new(src, format!("materials.{}", key.get_ref()), key.span());
        let e = entry.get_ref();
        let spectrum = |field: &str, v: Option<&Spanned<Value>>| {
            v.map(|v| {
                if file.bands.is_empty() {
                    return Err(t.error(
                        v.span(),
                        field,
                        "a spectrum needs [[bands]] to report in",
                    ));
                }
                build_spectrum(&t, field, v, base_dir)
            })
            .transpose()
        };
        let diffuse = spectrum("diffuse_spectrum", e.diffuse_spectrum.as_ref())?;
        let translucency = spectrum("translucency_spectrum", e.translucency_spectrum.as_ref())?;
        if (diffuse.is_some() || translucency.is_some())
            && let Some(id) = scene.material_id(key.get_ref())
        {
            // The RGB colour of a lobe given only as a spectrum, for images and the RGB
            // figures.
            let m = &mut scene.materials[id as usize];
            if let (Some(s), None) = (&diffuse, &e.diffuse) {
                m.diffuse = rgb_of(s);
            }
            if let (Some(s), None) = (&translucency, &e.translucency) {
                m.translucency = rgb_of(s);
            }
            let sum = m.albedo_bound();
            if sum > 1.0 + ENERGY_TOLERANCE {
                return Err(t.table_error(format!(
                    "material \"{}\" reflects more than it receives in RGB: the lobes' \
                     weights sum to {sum:.3} (give diffuse and translucency for RGB, ≤ 1 together)",
                    key.get_ref()
                )));
            }
            materials.push(MaterialSpectra {
                material: id as MaterialId,
                diffuse,
                translucency,
            });
        }
    }
    materials.sort_by_key(|m| m.material);
    if file.bands.is_empty() {
        if let Some((i, _)) = light_spectra.iter().find(|(_, s)| s.is_some()) {
            let entry = &file.lights[*i];
            let t = Table::new(src, format!("lights[{i}]"), entry.span());
            let span = entry
                .get_ref()
                .spectrum
                .as_ref()
                .map_or(entry.span(), Spanned::span);
            return Err(t.error(span, "spectrum", "a spectrum needs [[bands]] to report in"));
        }
        return Ok(None);
    }
    let mut bands = Vec::with_capacity(file.bands.len());
    for (i, entry) in file.bands.iter().enumerate() {
        let t = Table::new(src, format!("bands[{i}]"), entry.span());
        let e = entry.get_ref();
        let name = e.name.as_ref().ok_or_else(|| t.missing("name", "a band"))?;
        if bands.iter().any(|b: &Band| &b.name == name.get_ref()) {
            return Err(t.error(
                name.span(),
                "name",
                format!("band \"{}\" is given twice", name.get_ref()),
            ));
        }
        let nm = |field: &str, v: Option<&Spanned<f64>>| {
            let v = v.ok_or_else(|| t.missing(field, "a band"))?;
            let x = *v.get_ref();
            if x > 0.0 && x <= MAX_WAVELENGTH_NM {
                Ok(x)
            } else {
                Err(t.error(
                    v.span(),
                    field,
                    "a wavelength must be a positive number of nm, at most 10⁶ (1 mm)",
                ))
            }
        };
        let (from_nm, to_nm) = (
            nm("from_nm", e.from_nm.as_ref())?,
            nm("to_nm", e.to_nm.as_ref())?,
        );
        if to_nm <= from_nm {
            let span = e.to_nm.as_ref().map_or(entry.span(), Spanned::span);
            return Err(t.error(span, "to_nm", "must be greater than from_nm"));
        }
        bands.push(Band {
            name: name.get_ref().clone(),
            from_nm,
            to_nm,
        });
    }
    let mut lights = Vec::with_capacity(light_spectra.len());
    for (i, spectrum) in light_spectra {
        let entry = &file.lights[i];
        let t = Table::new(src, format!("lights[{i}]"), entry.span());
        lights.push(
            spectrum
                .ok_or_else(|| t.missing("spectrum", "every light of a scene with [[bands]]"))?,
        );
    }
    let spectral = Spectral {
        bands,
        lights,
        materials,
    };
    if let Err(e) = spectral.validate(scene) {
        let t = Table::new(src, "bands", file.bands[0].span());
        return Err(t.table_error(e));
    }
    Ok(Some(spectral))
}
