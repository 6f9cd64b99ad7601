//! What a method measured in a scene's wavelength bands: per band, the power and photon flux
//! every reported surface and sensor received, read out of the channels of the band groups'
//! runs ([`crate::scene::Scene::band_groups`]).

use super::{SensorReading, SurfacePower};
use crate::color::Band;
use crate::scene::{BandChannel, BandQuantity, Spectral};

/// One reported surface's light in one band: W, or µmol·s⁻¹ for photon flux.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BandValues {
    /// Arriving on either side.
    pub incident: f64,
    /// Absorbed.
    pub absorbed: f64,
    /// The part of `incident` straight from the lights, where the solver tells it apart.
    pub direct: Option<f64>,
    /// Standard error of `incident` (Monte Carlo solvers).
    pub incident_standard_error: Option<f64>,
}

/// One sensor's irradiance in one band: W·m⁻², or µmol·m⁻²·s⁻¹ for photon flux (PPFD
/// in the PAR band).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SensorBand {
    /// Irradiance on the sensor's side.
    pub irradiance: f64,
    /// The part straight from the lights.
    pub direct: f64,
    /// Standard error of `irradiance` (Monte Carlo solvers).
    pub standard_error: Option<f64>,
}

/// One band's figures, per reported surface and per sensor, in the order of the run's
/// surface table and of the scene's sensors.
#[derive(Clone, Debug, PartialEq)]
pub struct BandFigures {
    /// The band.
    pub band: Band,
    /// Power per surface, W.
    pub power: Vec<BandValues>,
    /// Photon flux per surface, µmol·s⁻¹.
    pub photons: Vec<BandValues>,
    /// Irradiance per sensor, W·m⁻².
    pub sensor_power: Vec<SensorBand>,
    /// Photon irradiance per sensor, µmol·m⁻²·s⁻¹.
    pub sensor_photons: Vec<SensorBand>,
}

/// Every band's figures.
#[derive(Clone, Debug, PartialEq)]
pub struct BandMeasurement {
    /// One per band of the scene, in its order.
    pub bands: Vec<BandFigures>,
}

/// What the run of one band group measured.
#[derive(Clone, Copy, Debug)]
pub struct GroupMeasurement<'a> {
    /// What its three channels carry.
    pub channels: &'a [BandChannel],
    /// Power per reported surface (`None` for methods that measure only sensors).
    pub power: Option<&'a SurfacePower>,
    /// Its sensors' readings.
    pub sensors: &'a [SensorReading],
}

/// How the standard errors of the channels that add up to one band's figure combine.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ChannelErrors {
    /// The channels' estimates are independent (the light model's paths traced together: a
    /// photon carries light for the channels of its own light only), so their errors add
    /// in quadrature.
    Independent,
    /// They may be correlated (runs one after another on the same random numbers): their
    /// errors add, the bound for any correlation.
    Correlated,
}

impl BandMeasurement {
    /// The bands of `spectral` read out of the runs of all its band groups, a band's
    /// channels added as [`Spectral::channels`] split it, their errors as `errors` says.
    pub fn new(
        spectral: &Spectral,
        groups: &[GroupMeasurement<'_>],
        errors: ChannelErrors,
    ) -> Self {
        let bands = spectral
            .bands
            .iter()
            .enumerate()
            .map(|(b, band)| {
                let classes = spectral.photon_classes(b);
                // The channels of the band's power, each with its µmol per joule.
                let mut power = Vec::new();
                let mut photons = None;
                for (g, group) in groups.iter().enumerate() {
                    for (c, ch) in group.channels.iter().enumerate() {
                        if ch.band != b {
                            continue;
                        }
                        match ch.quantity {
                            BandQuantity::Power => {
                                let f = classes.first().map_or(0.0, |k| k.micromoles_per_joule);
                                power.push((g, c, f));
                            }
                            BandQuantity::ClassPower(k) => {
                                power.push((g, c, classes[k].micromoles_per_joule));
                            }
                            BandQuantity::Photons => photons = Some((g, c, 1.0)),
                        }
                    }
                }
                let read = |parts: &[(usize, usize, f64)], photon: bool| {
                    let scaled = parts
                        .iter()
                        .map(|&(g, c, f)| (&groups[g], c, if photon { f } else { 1.0 }));
                    channels(scaled, errors)
                };
                let (power_figures, sensor_power) = read(&power, false);
                let (photon_figures, sensor_photons) = match photons {
                    Some(p) => read(&[p], true),
                    None => read(&power, true),
                };
                BandFigures {
                    band: band.clone(),
                    power: power_figures,
                    photons: photon_figures,
                    sensor_power,
                    sensor_photons,
                }
            })
            .collect();
        BandMeasurement { bands }
    }
}

/// The sum of `parts` (group, channel, scale): each group's channel times its scale, their
/// standard errors combined as `errors` says.
fn channels<'a>(
    parts: impl Iterator<Item = (&'a GroupMeasurement<'a>, usize, f64)>,
    errors: ChannelErrors,
) -> (Vec<BandValues>, Vec<SensorBand>) {
    let add_error = |sum: Option<f64>, e: Option<f64>| match (sum, e) {
        (Some(s), Some(e)) => Some(match errors {
            ChannelErrors::Independent => s.hypot(e),
            ChannelErrors::Correlated => s + e,
        }),
        _ => None,
    };
    let mut surfaces: Vec<BandValues> = Vec::new();
    let mut sensors: Vec<SensorBand> = Vec::new();
    for (k, (g, c, scale)) in parts.enumerate() {
        let first = k == 0;
        if let Some(power) = g.power {
            surfaces.resize(power.table().len(), BandValues::default());
            for (e, out) in surfaces.iter_mut().enumerate() {
                let b = power.balance(e);
                let error = power.standard_error(e).map(|s| s[c] * scale);
                out.incident += b.incident[c] * scale;
                out.absorbed += b.absorbed[c] * scale;
                out.direct = match (first, out.direct, b.direct) {
                    (true, _, d) => d.map(|d| d[c] * scale),
                    (false, Some(s), Some(d)) => Some(s + d[c] * scale),
                    _ => None,
                };
                out.incident_standard_error = if first {
                    error
                } else {
                    add_error(out.incident_standard_error, error)
                };
            }
        }
        sensors.resize(g.sensors.len(), SensorBand::default());
        for (out, r) in sensors.iter_mut().zip(g.sensors) {
            let error = r.standard_error.map(|s| s[c] * scale);
            out.irradiance += r.irradiance()[c] * scale;
            out.direct += r.direct[c] * scale;
            out.standard_error = if first {
                error
            } else {
                add_error(out.standard_error, error)
            };
        }
    }
    (surfaces, sensors)
}
