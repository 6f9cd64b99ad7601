//! Fixed-point tallies of photon power: integer sums do not depend on the order of addition,
//! so a fixed seed gives identical totals for any thread count.

/// Fixed-point power triple.
pub(super) type Fixed = [i128; 3];

/// Per-entry quantities in a tally: incident (of it, direct), absorbed, emitted and
/// reflected power, and the sum of the squares of each photon's incident power.
#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(super) struct FixedBalance {
    pub incident: Fixed,
    pub direct: Fixed,
    pub absorbed: Fixed,
    pub emitted: Fixed,
    pub reflected: Fixed,
    pub incident_squares: Fixed,
}

/// Per sensor: direct and indirect irradiance, and the sum of the squares of each photon's
/// irradiance.
#[derive(Clone, Copy, Debug, Default, serde::Serialize, serde::Deserialize)]
pub(super) struct FixedSensor {
    pub direct: Fixed,
    pub indirect: Fixed,
    pub squares: Fixed,
}

/// What one worker has accumulated.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub(super) struct Tally {
    /// Per report entry.
    pub entries: Vec<FixedBalance>,
    /// Per sensor of the scene.
    pub sensors: Vec<FixedSensor>,
    /// Sums of the squares of each photon's incident power over all surfaces together, and
    /// of the part after its first hit (indirect).
    pub total_squares: [Fixed; 2],
    /// Emission of lights that are not surfaces.
    pub light_emission: Fixed,
    /// Power that left the scene.
    pub escaped: Fixed,
    /// Closest-hit queries.
    pub rays: u64,
    /// Photons that left the scene.
    pub escaped_photons: u64,
    /// Photons stopped by the bounce limit.
    pub truncated_paths: u64,
}

/// Adds `b` to `a` channel by channel.
pub(super) fn add_fixed(a: &mut Fixed, b: Fixed) {
    a.iter_mut().zip(b).for_each(|(x, y)| *x += y);
}

/// Adds `b` to `a` channel by channel, stopping at the largest value instead of overflowing
/// (for sums of squares, whose single terms may be huge).
pub(super) fn add_fixed_saturating(a: &mut Fixed, b: Fixed) {
    a.iter_mut()
        .zip(b)
        .for_each(|(x, y)| *x = x.saturating_add(y));
}

impl Tally {
    /// Zeros for `entries` report entries and `sensors` sensors.
    pub fn new(entries: usize, sensors: usize) -> Self {
        Tally {
            entries: vec![FixedBalance::default(); entries],
            sensors: vec![FixedSensor::default(); sensors],
            total_squares: [[0; 3]; 2],
            light_emission: [0; 3],
            escaped: [0; 3],
            rays: 0,
            escaped_photons: 0,
            truncated_paths: 0,
        }
    }

    /// Adds everything `o` holds.
    pub fn merge(&mut self, o: &Tally) {
        for (a, b) in self.entries.iter_mut().zip(&o.entries) {
            add_fixed(&mut a.incident, b.incident);
            add_fixed(&mut a.direct, b.direct);
            add_fixed(&mut a.absorbed, b.absorbed);
            add_fixed(&mut a.emitted, b.emitted);
            add_fixed(&mut a.reflected, b.reflected);
            add_fixed_saturating(&mut a.incident_squares, b.incident_squares);
        }
        for (a, b) in self.sensors.iter_mut().zip(&o.sensors) {
            add_fixed(&mut a.direct, b.direct);
            add_fixed(&mut a.indirect, b.indirect);
            add_fixed_saturating(&mut a.squares, b.squares);
        }
        for (a, b) in self.total_squares.iter_mut().zip(o.total_squares) {
            add_fixed_saturating(a, b);
        }
        add_fixed(&mut self.light_emission, o.light_emission);
        add_fixed(&mut self.escaped, o.escaped);
        self.rays += o.rays;
        self.escaped_photons += o.escaped_photons;
        self.truncated_paths += o.truncated_paths;
    }
}
