//! What a method measured in a scene's wavelength bands: per band, the power and photon flux
//! every reported surface and sensor received, read out of the channels of the band groups'
//! runs ([`crate::scene::Scene::band_groups`]).

use super::{SensorReading, SurfacePower};
use crate::color::Band;
use crate::scene::{BandChannel, BandQuantity, PhotonFactor, Spectral};

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

impl BandMeasurement {
    /// The bands of `spectral` read out of the runs of all its band groups.
    pub fn new(spectral: &Spectral, groups: &[GroupMeasurement<'_>]) -> Self {
        let find = |band: usize, quantity: BandQuantity| {
            groups.iter().find_map(|g| {
                let c = g
                    .channels
                    .iter()
                    .position(|ch| *ch == BandChannel { band, quantity })?;
                Some((g, c))
            })
        };
        let bands = spectral
            .bands
            .iter()
            .enumerate()
            .map(|(b, band)| {
                let (power, sensor_power) = find(b, BandQuantity::Power)
                    .map_or_else(Default::default, |(g, c)| channel(g, c, 1.0));
                let (photons, sensor_photons) = match spectral.photon_factor(b) {
                    PhotonFactor::Uniform(f) => find(b, BandQuantity::Power)
                        .map_or_else(Default::default, |(g, c)| channel(g, c, f)),
                    PhotonFactor::PerLight => find(b, BandQuantity::Photons)
                        .map_or_else(Default::default, |(g, c)| channel(g, c, 1.0)),
                };
                BandFigures {
                    band: band.clone(),
                    power,
                    photons,
                    sensor_power,
                    sensor_photons,
                }
            })
            .collect();
        BandMeasurement { bands }
    }
}

/// Channel `c` of group `g`'s figures, times `scale`.
fn channel(g: &GroupMeasurement<'_>, c: usize, scale: f64) -> (Vec<BandValues>, Vec<SensorBand>) {
    let surfaces = g.power.map_or_else(Vec::new, |power| {
        (0..power.table().len())
            .map(|e| {
                let b = power.balance(e);
                BandValues {
                    incident: b.incident[c] * scale,
                    absorbed: b.absorbed[c] * scale,
                    direct: b.direct.map(|d| d[c] * scale),
                    incident_standard_error: power.standard_error(e).map(|s| s[c] * scale),
                }
            })
            .collect()
    });
    let sensors = g
        .sensors
        .iter()
        .map(|r| SensorBand {
            irradiance: r.irradiance()[c] * scale,
            direct: r.direct[c] * scale,
            standard_error: r.standard_error.map(|s| s[c] * scale),
        })
        .collect();
    (surfaces, sensors)
}
