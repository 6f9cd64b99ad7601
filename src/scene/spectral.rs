//! A scene's wavelength bands: the bands it reports light in, the spectra of its lights and
//! of its materials' diffuse reflectance and translucency, and the three-channel scenes that
//! carry the bands through every method.
//!
//! Every method works on three channels. A scene with bands is solved as scenes whose three
//! channels are three of its bands ([`Scene::band_groups`]): in each, a material's diffuse
//! reflectance and translucency are their spectra's means over the band, weighted by the
//! lights' spectra (each scaled to a total of 1), and a light's strength is its share of its
//! spectrum's total within the band. A band's photon flux (µmol s⁻¹) is its power times the
//! µmol per joule of the light in it. Where the lights' spectra differ in that figure the
//! band is carried by more channels, so that the figure is exact for any mix of lights: for
//! two photon classes (lights of one µmol per joule each, such as a sun and a sky), each
//! class's power in a channel of its own, converted by its class's figure; for more, the
//! power of all and the photon flux of all, each light's strength converted by its own
//! spectrum.

use super::{ENERGY_TOLERANCE, Material, MaterialId, Scene};
use crate::color::{Band, MAX_WAVELENGTH_NM, Rgb, Spectrum};

/// Relative difference below which two lights' µmol per joule in a band count as one.
const SAME_PHOTON_FACTOR: f64 = 1e-9;

/// The bands of a scene and the spectra that give its lights and materials their values in
/// them.
#[derive(Clone, Debug, PartialEq)]
pub struct Spectral {
    /// The bands reported, in order.
    pub bands: Vec<Band>,
    /// The emission spectrum of every light, in the order of [`Scene::lights`]: its shape
    /// only, the light's (grey) strength being the spectrum's total.
    pub lights: Vec<Spectrum>,
    /// Materials with a diffuse or translucency spectrum; the others are grey.
    pub materials: Vec<MaterialSpectra>,
}

/// The spectra of one material's diffuse lobes, dimensionless in `[0, 1]` per nm.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialSpectra {
    /// Which material.
    pub material: MaterialId,
    /// Spectrum of the diffuse reflectance ρ(λ), or `None` for the material's grey `diffuse`.
    pub diffuse: Option<Spectrum>,
    /// Spectrum of the translucency τ(λ), or `None` for the material's grey `translucency`.
    pub translucency: Option<Spectrum>,
}

/// What a channel of a band group carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BandQuantity {
    /// Power of every light (W, and W·m⁻² per area).
    Power,
    /// Photon flux of every light, µmol·s⁻¹ where power is in W.
    Photons,
    /// Power (W) of the lights of the band's photon class `k` ([`Spectral::photon_classes`]).
    ClassPower(usize),
}

/// The lights that shine in a band with one µmol per joule there.
#[derive(Clone, Debug, PartialEq)]
pub struct PhotonClass {
    /// Their µmol per joule in the band.
    pub micromoles_per_joule: f64,
    /// Indices into [`Scene::lights`], in order.
    pub lights: Vec<usize>,
}

/// One channel of a band group: a band and what of it the channel carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BandChannel {
    /// Index into [`Spectral::bands`].
    pub band: usize,
    /// Power or photon flux.
    pub quantity: BandQuantity,
}

/// A three-channel scene carrying up to three band channels: solve it with any method and
/// read channel `c` of every result as `channels[c]`.
#[derive(Clone, Debug)]
pub struct BandGroup {
    /// What its channels carry (one to three; the remaining channels are dark).
    pub channels: Vec<BandChannel>,
    /// The scene with the band values in its channels.
    pub scene: Scene,
}

/// Why a scene's bands cannot be solved.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SpectralError {
    /// A scene with bands but no band.
    #[error("the scene declares spectra but no band")]
    NoBands,
    /// A band that is not a positive interval up to 10⁶ nm, or a name given twice.
    #[error("band \"{0}\" must have a unique name and 0 < from < to ≤ 10⁶ (nm)")]
    BadBand(String),
    /// Spectra for another number of lights than the scene has.
    #[error("the scene has {scene} lights but spectra for {spectra}")]
    LightCount {
        /// Lights in the scene.
        scene: usize,
        /// Spectra given.
        spectra: usize,
    },
    /// A light whose colour is not grey.
    #[error(
        "{light}: in a scene with bands a light's spectrum gives its colour, so its strength \
         must be grey (one number)"
    )]
    ColouredLight {
        /// The light's name or index.
        light: String,
    },
    /// An emitting material.
    #[error(
        "material \"{0}\" emits: emitting surfaces are not solved in bands yet; use a light \
         with a spectrum"
    )]
    EmittingMaterial(String),
    /// A textured material.
    #[error("material \"{0}\" has a texture: textures are RGB and have no value in a band")]
    Textured(String),
    /// A lobe's weight not grey without a spectrum.
    #[error(
        "material \"{material}\": {field} is not grey; in a scene with bands give \
         {field}_spectrum or one number"
    )]
    NotGrey {
        /// The material's name.
        material: String,
        /// The lobe's field.
        field: &'static str,
    },
    /// A material spectrum that does not reach over a band.
    #[error(
        "material \"{material}\": its {field} spectrum covers {from_nm}–{to_nm} nm, not all of \
         band \"{band}\""
    )]
    Uncovered {
        /// The material's name.
        material: String,
        /// The lobe's field.
        field: &'static str,
        /// The band.
        band: String,
        /// First wavelength of the spectrum, nm.
        from_nm: f64,
        /// Last wavelength of the spectrum, nm.
        to_nm: f64,
    },
    /// Reflectance and transmittance summing over 1 in a band.
    #[error("material \"{material}\" reflects more than it receives in band \"{band}\": {sum:.4}")]
    CreatesLight {
        /// The material's name.
        material: String,
        /// The band.
        band: String,
        /// The sum of its lobes' weights there.
        sum: f64,
    },
}

impl Spectral {
    /// The photon classes of band `band`: its lights grouped by their µmol per joule in it
    /// (equal within a relative 10⁻⁹), in the order of their first light; lights without
    /// light in the band belong to none, so a band no light shines in has none.
    pub fn photon_classes(&self, band: usize) -> Vec<PhotonClass> {
        let b = &self.bands[band];
        let mut classes: Vec<PhotonClass> = Vec::new();
        for (light, spectrum) in self.lights.iter().enumerate() {
            let Some(f) = spectrum.micromoles_per_joule(b) else {
                continue;
            };
            let same = |c: &&mut PhotonClass| {
                (c.micromoles_per_joule - f).abs() <= SAME_PHOTON_FACTOR * c.micromoles_per_joule
            };
            match classes.iter_mut().find(same) {
                Some(class) => class.lights.push(light),
                None => classes.push(PhotonClass {
                    micromoles_per_joule: f,
                    lights: vec![light],
                }),
            }
        }
        classes
    }

    /// Every channel the bands need, per band: its power where its lights are of one photon
    /// class (or none); each class's power where there are two; the power and the photon
    /// flux of all its lights where there are more. Channels of the same lights are side by
    /// side, so that three to a group, each group is lit by as few lights as can be (the light
    /// model's photons carry light only for the groups their light shines in).
    pub fn channels(&self) -> Vec<BandChannel> {
        let mut channels = Vec::new();
        for band in 0..self.bands.len() {
            let channel = |quantity| BandChannel { band, quantity };
            let classes = self.photon_classes(band);
            match classes.len() {
                0 | 1 => channels.push(channel(BandQuantity::Power)),
                2 => channels.extend((0..2).map(|k| channel(BandQuantity::ClassPower(k)))),
                _ => channels.extend([BandQuantity::Power, BandQuantity::Photons].map(channel)),
            }
        }
        channels.sort_by_cached_key(|c| self.lights_of(c));
        channels
    }

    /// The lights whose light channel `channel` carries, in order.
    fn lights_of(&self, channel: &BandChannel) -> Vec<usize> {
        let classes = self.photon_classes(channel.band);
        match channel.quantity {
            BandQuantity::ClassPower(k) => classes[k].lights.clone(),
            BandQuantity::Power | BandQuantity::Photons => {
                let mut all: Vec<usize> = classes.into_iter().flat_map(|c| c.lights).collect();
                all.sort_unstable();
                all
            }
        }
    }

    fn spectra_of(&self, material: MaterialId) -> Option<&MaterialSpectra> {
        self.materials.iter().find(|m| m.material == material)
    }

    /// Checks what every band group needs of `scene`.
    fn check(&self, scene: &Scene) -> Result<(), SpectralError> {
        if self.bands.is_empty() {
            return Err(SpectralError::NoBands);
        }
        for (i, b) in self.bands.iter().enumerate() {
            let valid = b.from_nm > 0.0 && b.to_nm > b.from_nm && b.to_nm <= MAX_WAVELENGTH_NM;
            if !valid || self.bands[..i].iter().any(|a| a.name == b.name) {
                return Err(SpectralError::BadBand(b.name.clone()));
            }
        }
        if self.lights.len() != scene.lights.len() {
            return Err(SpectralError::LightCount {
                scene: scene.lights.len(),
                spectra: self.lights.len(),
            });
        }
        for (i, light) in scene.lights.iter().enumerate() {
            let mut kind = light.kind.clone();
            if !is_grey(*kind.strength_mut()) {
                let light = match &light.name {
                    Some(name) => format!("light \"{name}\""),
                    None => format!("lights[{i}]"),
                };
                return Err(SpectralError::ColouredLight { light });
            }
        }
        for (id, m) in scene.materials.iter().enumerate() {
            let name = || m.name.clone();
            if !m.emission.is_black() || m.emission_texture.is_some() {
                return Err(SpectralError::EmittingMaterial(name()));
            }
            if m.diffuse_texture.is_some() || m.alpha_texture.is_some() {
                return Err(SpectralError::Textured(name()));
            }
            let spectra = self.spectra_of(id as MaterialId);
            let lobes = [
                (
                    "diffuse",
                    m.diffuse,
                    spectra.and_then(|s| s.diffuse.as_ref()),
                ),
                (
                    "translucency",
                    m.translucency,
                    spectra.and_then(|s| s.translucency.as_ref()),
                ),
                ("specular", m.specular, None),
                ("mirror", m.mirror, None),
                ("transmission", m.transmission, None),
            ];
            for (field, weight, spectrum) in lobes {
                let Some(spectrum) = spectrum else {
                    if !is_grey(weight) {
                        return Err(SpectralError::NotGrey {
                            material: name(),
                            field,
                        });
                    }
                    continue;
                };
                if let Some((from_nm, to_nm)) = spectrum.range()
                    && let Some(b) = self
                        .bands
                        .iter()
                        .find(|b| b.from_nm < from_nm || b.to_nm > to_nm)
                {
                    return Err(SpectralError::Uncovered {
                        material: name(),
                        field,
                        band: b.name.clone(),
                        from_nm,
                        to_nm,
                    });
                }
            }
        }
        Ok(())
    }

    /// The weights of material means: every light's spectrum scaled to a total of 1.
    fn weights(&self) -> Vec<(&Spectrum, f64)> {
        self.lights
            .iter()
            .filter_map(|s| {
                let total = s.total();
                (total > 0.0).then(|| (s, 1.0 / total))
            })
            .collect()
    }

    /// The diffuse reflectance and translucency of material `m` (id `id`) in the bands of
    /// `channels` (one to three; the remaining channels 0), weighted by `weights`; refused
    /// where its lobes sum over 1 in a band.
    fn diffuse_lobes(
        &self,
        (id, m): (usize, &Material),
        channels: &[BandChannel],
        weights: &[(&Spectrum, f64)],
    ) -> Result<(Rgb, Rgb), SpectralError> {
        let spectra = self.spectra_of(id as MaterialId);
        let mean = |spectrum: Option<&Spectrum>, grey: Rgb| {
            let mut v = [0.0f32; 3];
            for (c, channel) in channels.iter().enumerate() {
                let band = &self.bands[channel.band];
                v[c] = spectrum.map_or(grey.r, |s| s.weighted_mean(band, weights) as f32);
            }
            Rgb::from(v)
        };
        let diffuse = mean(spectra.and_then(|s| s.diffuse.as_ref()), m.diffuse);
        let translucency = mean(
            spectra.and_then(|s| s.translucency.as_ref()),
            m.translucency,
        );
        let sum = diffuse + translucency + m.specular + m.mirror + m.transmission;
        match (0..channels.len()).find(|&c| sum[c] > 1.0 + ENERGY_TOLERANCE) {
            Some(c) => Err(SpectralError::CreatesLight {
                material: m.name.clone(),
                band: self.bands[channels[c].band].name.clone(),
                sum: f64::from(sum[c]),
            }),
            None => Ok((diffuse, translucency)),
        }
    }

    /// Checks that every band of `scene` can be solved: what [`Scene::band_groups`] refuses,
    /// without building the scenes.
    pub fn validate(&self, scene: &Scene) -> Result<(), SpectralError> {
        self.check(scene)?;
        let weights = self.weights();
        for channels in self.channels().chunks(3) {
            for m in scene.materials.iter().enumerate() {
                self.diffuse_lobes(m, channels, &weights)?;
            }
        }
        Ok(())
    }

    /// The three-channel scene of `channels` (one to three).
    fn group_scene(&self, scene: &Scene, channels: &[BandChannel]) -> Result<Scene, SpectralError> {
        let mut out = scene.clone();
        out.spectral = None;
        let weights = self.weights();
        for (m, original) in out
            .materials
            .iter_mut()
            .zip(scene.materials.iter().enumerate())
        {
            (m.diffuse, m.translucency) = self.diffuse_lobes(original, channels, &weights)?;
        }
        let carried: Vec<Vec<usize>> = channels.iter().map(|c| self.lights_of(c)).collect();
        for (i, (light, spectrum)) in out.lights.iter_mut().zip(&self.lights).enumerate() {
            let strength = light.kind.strength_mut();
            let (grey, total) = (f64::from(strength.r), spectrum.total());
            let mut v = [0.0f32; 3];
            for (c, channel) in channels.iter().enumerate() {
                if !carried[c].contains(&i) {
                    continue;
                }
                let band = &self.bands[channel.band];
                let share = if total > 0.0 {
                    spectrum.integral(band) / total
                } else {
                    0.0
                };
                let unit = match channel.quantity {
                    BandQuantity::Power | BandQuantity::ClassPower(_) => 1.0,
                    BandQuantity::Photons => spectrum.micromoles_per_joule(band).unwrap_or(0.0),
                };
                v[c] = (grey * share * unit) as f32;
            }
            *strength = Rgb::from(v);
        }
        Ok(out)
    }
}

/// True when the three channels are equal.
fn is_grey(c: Rgb) -> bool {
    c.r == c.g && c.g == c.b
}

impl Scene {
    /// The three-channel scenes that carry this scene's bands ([`Spectral::channels`],
    /// three to a scene, in order); empty for a scene without bands.
    pub fn band_groups(&self) -> Result<Vec<BandGroup>, SpectralError> {
        let Some(spectral) = &self.spectral else {
            return Ok(Vec::new());
        };
        spectral.check(self)?;
        spectral
            .channels()
            .chunks(3)
            .map(|channels| {
                Ok(BandGroup {
                    channels: channels.to_vec(),
                    scene: spectral.group_scene(self, channels)?,
                })
            })
            .collect()
    }
}
