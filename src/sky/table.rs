//! A sky tabulated over the upper hemisphere, to sample directions in proportion to the
//! irradiance they bring onto a horizontal plane, `L·cos θ`, and to evaluate the density of
//! that sampling (for an integrator's multiple importance sampling).

mod cdf;

use glam::DVec3;

use super::direction::angles_from_direction;

/// Points per cell side at which the radiance is averaged when tabulated.
const SUBSAMPLES: usize = 4;

/// A sky's `L·cos θ` tabulated over a latitude–longitude grid of the upper hemisphere — rows
/// of equal zenith-angle width from the zenith (+y) to the horizon, columns of equal azimuth
/// width clockwise from north (−z) — as a two-dimensional piecewise-constant distribution:
/// a row by its marginal probability, a column in it by its conditional one, and a
/// direction uniformly in the cell's solid angle. The density is then constant over each
/// cell, in sr⁻¹, and zero below the horizon and on cells of no radiance.
#[derive(Clone, Debug)]
pub struct SkyTable {
    rows: usize,
    columns: usize,
    /// The cumulative marginal distribution of the rows.
    row_cdf: Vec<f64>,
    /// Per row, the cumulative distribution of its columns (`columns + 1` values each).
    column_cdfs: Vec<f64>,
    /// The density of every cell, sr⁻¹, row by row.
    densities: Vec<f64>,
    /// The sum of the cells' `L·cos θ·Ω`.
    irradiance: f64,
}

/// A direction drawn from a [`SkyTable`] and the density it was drawn with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkySample {
    /// The unit direction, in the upper hemisphere (y ≥ 0), pointing away from the observer.
    pub direction: DVec3,
    /// The density of the draw with respect to solid angle, sr⁻¹ (> 0).
    pub pdf: f64,
}

impl SkyTable {
    /// Tabulates `radiance` (of unit directions, ≥ 0, per sr; any unit) on `rows × columns`
    /// cells (both ≥ 1): each cell's `L·cos θ` is the mean of 4 × 4 points spread evenly over
    /// its solid angle.
    pub fn new(rows: usize, columns: usize, radiance: impl Fn(DVec3) -> f64) -> SkyTable {
        assert!(rows >= 1 && columns >= 1, "a sky table needs cells");
        let (row_width, column_width) = (
            std::f64::consts::FRAC_PI_2 / rows as f64,
            std::f64::consts::TAU / columns as f64,
        );
        let mut weights = vec![0.0; rows * columns];
        for row in 0..rows {
            let (mu_top, mu_bottom) = mu_bounds(row, row_width);
            for column in 0..columns {
                let mut sum = 0.0;
                for a in 0..SUBSAMPLES {
                    for b in 0..SUBSAMPLES {
                        let s = (a as f64 + 0.5) / SUBSAMPLES as f64;
                        let t = (b as f64 + 0.5) / SUBSAMPLES as f64;
                        let mu = mu_top - s * (mu_top - mu_bottom);
                        let phi = (column as f64 + t) * column_width;
                        let value = radiance(direction(mu, phi));
                        assert!(value >= 0.0, "negative sky radiance {value}");
                        sum += value * mu;
                    }
                }
                let solid_angle = column_width * (mu_top - mu_bottom);
                weights[row * columns + column] =
                    sum / (SUBSAMPLES * SUBSAMPLES) as f64 * solid_angle;
            }
        }
        let mut column_cdfs = Vec::with_capacity(rows * (columns + 1));
        let mut row_weights = Vec::with_capacity(rows);
        for row in weights.chunks(columns) {
            let (cdf, sum) = cdf::cumulative(row);
            column_cdfs.extend(cdf);
            row_weights.push(sum);
        }
        let (row_cdf, irradiance) = cdf::cumulative(&row_weights);
        let densities = weights
            .iter()
            .enumerate()
            .map(|(cell, &w)| {
                let (mu_top, mu_bottom) = mu_bounds(cell / columns, row_width);
                let solid_angle = column_width * (mu_top - mu_bottom);
                if irradiance > 0.0 {
                    w / irradiance / solid_angle
                } else {
                    0.0
                }
            })
            .collect();
        SkyTable {
            rows,
            columns,
            row_cdf,
            column_cdfs,
            densities,
            irradiance,
        }
    }

    /// The irradiance the tabulated sky sends onto a horizontal plane, `Σ L·cos θ·Ω` over
    /// the cells (the radiance's unit times sr: W·m⁻² for W·m⁻²·sr⁻¹), the table's estimate
    /// of `∫ L cos θ dω`.
    pub fn irradiance(&self) -> f64 {
        self.irradiance
    }

    /// A direction for the uniform numbers `u ∈ [0, 1)²`, with density in proportion to the
    /// tabulated `L·cos θ`; `None` for a sky of no radiance.
    pub fn sample(&self, u: [f64; 2]) -> Option<SkySample> {
        if self.irradiance <= 0.0 {
            return None;
        }
        let (row, v) = cdf::invert(&self.row_cdf, u[0]);
        let cdf = &self.column_cdfs[row * (self.columns + 1)..(row + 1) * (self.columns + 1)];
        let (column, w) = cdf::invert(cdf, u[1]);
        let (mu_top, mu_bottom) = mu_bounds(row, std::f64::consts::FRAC_PI_2 / self.rows as f64);
        let mu = mu_top - v * (mu_top - mu_bottom);
        let phi = (column as f64 + w) * std::f64::consts::TAU / self.columns as f64;
        Some(SkySample {
            direction: direction(mu, phi),
            pdf: self.densities[row * self.columns + column],
        })
    }

    /// The density, sr⁻¹, with which [`SkyTable::sample`] draws the unit `direction`: that
    /// of its cell, 0 below the horizon.
    pub fn pdf(&self, direction: DVec3) -> f64 {
        if direction.y < 0.0 {
            return 0.0;
        }
        let (zenith, azimuth) = angles_from_direction(direction);
        let row = ((zenith.to_radians() / std::f64::consts::FRAC_PI_2 * self.rows as f64) as usize)
            .min(self.rows - 1);
        let column = ((azimuth.to_radians() / std::f64::consts::TAU * self.columns as f64)
            as usize)
            .min(self.columns - 1);
        self.densities[row * self.columns + column]
    }
}

/// The cosines of the zenith angles at the top and the bottom of `row`.
fn mu_bounds(row: usize, row_width: f64) -> (f64, f64) {
    (
        (row as f64 * row_width).cos(),
        ((row + 1) as f64 * row_width).cos(),
    )
}

/// The unit direction of `mu = cos θ` and azimuth `phi` (radians, clockwise from −z).
fn direction(mu: f64, phi: f64) -> DVec3 {
    let sin_theta = (1.0 - mu * mu).max(0.0).sqrt();
    DVec3::new(sin_theta * phi.sin(), mu, -sin_theta * phi.cos())
}

#[cfg(test)]
mod tests;
