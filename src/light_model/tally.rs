//! Fixed-point tallies of photon power: integer sums do not depend on the order of addition,
//! so a fixed seed gives identical totals for any thread count.

use crate::sampling::{pack, unpack};

/// Fixed-point power triple.
pub(super) type Fixed = [i128; 3];

/// Per-entry quantities in a tally: incident (of it, direct), absorbed, emitted and
/// reflected power, and the sum of the squares of each photon's incident power.
#[derive(Clone, Copy, Debug, Default)]
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
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct FixedSensor {
    pub direct: Fixed,
    pub indirect: Fixed,
    pub squares: Fixed,
}

/// What one worker has accumulated. Serialized with its integers packed
/// ([`crate::sampling::pack`]; see [`PackedTally`]), so a batch's partial result is a few bytes
/// per figure.
#[derive(Clone, Debug)]
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

/// Integers per report entry in a packed tally: six triples.
const PER_ENTRY: usize = 18;
/// Integers per sensor in a packed tally: three triples.
const PER_SENSOR: usize = 9;

/// [`Tally`] as it is serialized: the counts, and every fixed-point sum in one packed string —
/// each entry's incident, direct, absorbed, emitted, reflected power and incident squares, each
/// sensor's direct, indirect and squares, then the total squares (all, indirect), the light
/// emission and the escaped power, three channels each.
#[derive(serde::Serialize, serde::Deserialize)]
struct PackedTally {
    entries: usize,
    sensors: usize,
    sums: String,
    rays: u64,
    escaped_photons: u64,
    truncated_paths: u64,
}

impl serde::Serialize for Tally {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let entries = self.entries.iter().flat_map(|e| {
            [
                e.incident,
                e.direct,
                e.absorbed,
                e.emitted,
                e.reflected,
                e.incident_squares,
            ]
        });
        let sensors = self
            .sensors
            .iter()
            .flat_map(|s| [s.direct, s.indirect, s.squares]);
        let totals = [
            self.total_squares[0],
            self.total_squares[1],
            self.light_emission,
            self.escaped,
        ];
        let triples = entries.chain(sensors).chain(totals);
        PackedTally {
            entries: self.entries.len(),
            sensors: self.sensors.len(),
            sums: pack(triples.flatten()),
            rays: self.rays,
            escaped_photons: self.escaped_photons,
            truncated_paths: self.truncated_paths,
        }
        .serialize(serializer)
    }
}

impl<'de> serde::Deserialize<'de> for Tally {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let packed = PackedTally::deserialize(deserializer)?;
        let values = unpack(&packed.sums)
            .ok_or_else(|| serde::de::Error::custom("the sums are not packed integers"))?;
        let expected = packed
            .entries
            .checked_mul(PER_ENTRY)
            .and_then(|e| e.checked_add(packed.sensors.checked_mul(PER_SENSOR)?))
            .and_then(|n| n.checked_add(12));
        if expected != Some(values.len()) {
            return Err(serde::de::Error::custom(format!(
                "{} sums for {} entries and {} sensors",
                values.len(),
                packed.entries,
                packed.sensors
            )));
        }
        let triple = |at: usize| -> Fixed { [values[at], values[at + 1], values[at + 2]] };
        let entries = (0..packed.entries)
            .map(|e| {
                let at = e * PER_ENTRY;
                FixedBalance {
                    incident: triple(at),
                    direct: triple(at + 3),
                    absorbed: triple(at + 6),
                    emitted: triple(at + 9),
                    reflected: triple(at + 12),
                    incident_squares: triple(at + 15),
                }
            })
            .collect();
        let first_sensor = packed.entries * PER_ENTRY;
        let sensors = (0..packed.sensors)
            .map(|k| {
                let at = first_sensor + k * PER_SENSOR;
                FixedSensor {
                    direct: triple(at),
                    indirect: triple(at + 3),
                    squares: triple(at + 6),
                }
            })
            .collect();
        let at = first_sensor + packed.sensors * PER_SENSOR;
        Ok(Tally {
            entries,
            sensors,
            total_squares: [triple(at), triple(at + 3)],
            light_emission: triple(at + 6),
            escaped: triple(at + 9),
            rays: packed.rays,
            escaped_photons: packed.escaped_photons,
            truncated_paths: packed.truncated_paths,
        })
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tally_comes_back_from_its_packed_form_exactly_and_a_short_one_is_refused() {
        let mut tally = Tally::new(3, 2);
        let mut v: i128 = 7;
        for e in &mut tally.entries {
            for triple in [
                &mut e.incident,
                &mut e.direct,
                &mut e.absorbed,
                &mut e.emitted,
                &mut e.reflected,
                &mut e.incident_squares,
            ] {
                *triple = [v, -v, v.wrapping_mul(1_000_003)];
                v = v.wrapping_mul(1_000_000_007).wrapping_add(12_345);
            }
        }
        tally.sensors[1].squares = [i128::MAX, 0, i128::MIN];
        tally.total_squares[1] = [1, 2, 3];
        tally.light_emission = [4, 5, 6];
        tally.escaped = [-7, 8, 9];
        (tally.rays, tally.escaped_photons, tally.truncated_paths) = (10, 11, 12);
        let json = serde_json::to_string(&tally).unwrap();
        let back: Tally = serde_json::from_str(&json).unwrap();
        assert_eq!(serde_json::to_string(&back).unwrap(), json);
        assert_eq!(
            back.entries[2].incident_squares,
            tally.entries[2].incident_squares
        );
        assert_eq!(back.sensors[1].squares, [i128::MAX, 0, i128::MIN]);
        assert_eq!((back.escaped, back.truncated_paths), ([-7, 8, 9], 12));
        let short = json.replace("\"entries\":3", "\"entries\":4");
        let error = serde_json::from_str::<Tally>(&short).expect_err("refused");
        assert!(error.to_string().contains("sums for 4 entries"), "{error}");
    }
}
