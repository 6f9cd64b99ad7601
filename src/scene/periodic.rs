//! A periodic scene: a plot that repeats without end in x and z, so that a small plot stands
//! for a field (light leaving through one side of the plot enters through the opposite one).

use glam::{Vec2, Vec3};

/// The plot of a periodic scene: the rectangle `x ∈ [x₀, x₁]`, `z ∈ [z₀, z₁]` (scene units,
/// y up) whose contents repeat with periods `x₁ − x₀` and `z₁ − z₀` over the whole
/// horizontal plane. Geometry may reach over the plot's sides: what lies beyond a side is
/// seen through the opposite one, as its copy in the neighbouring plot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Periodic {
    /// `[x₀, x₁]`, scene units, `x₀ < x₁`.
    pub x: [f32; 2],
    /// `[z₀, z₁]`, scene units, `z₀ < z₁`.
    pub z: [f32; 2],
}

impl Periodic {
    /// The plot `x ∈ [x[0], x[1]]`, `z ∈ [z[0], z[1]]`; refused (with the reason) unless both
    /// ranges are finite and of positive width.
    pub fn new(x: [f32; 2], z: [f32; 2]) -> Result<Periodic, String> {
        for (axis, [lo, hi]) in [("x", x), ("z", z)] {
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(format!(
                    "the plot's {axis} range must be two finite numbers, the first below the \
                     second (got [{lo}, {hi}])"
                ));
            }
        }
        Ok(Periodic { x, z })
    }

    /// The periods `(x₁ − x₀, z₁ − z₀)`, scene units.
    pub fn period(&self) -> Vec2 {
        Vec2::new(self.x[1] - self.x[0], self.z[1] - self.z[0])
    }

    /// The plot's area, square scene units.
    pub fn area(&self) -> f32 {
        let p = self.period();
        p.x * p.y
    }

    /// `p` moved by whole periods into the plot (`x ∈ [x₀, x₁)`, `z ∈ [z₀, z₁)`; y kept).
    pub fn wrap(&self, p: Vec3) -> Vec3 {
        let period = self.period();
        let wrap = |v: f32, lo: f32, width: f32| {
            let w = lo + (v - lo).rem_euclid(width);
            // `rem_euclid` may round up to the width itself.
            if w >= lo + width { lo } else { w }
        };
        Vec3::new(
            wrap(p.x, self.x[0], period.x),
            p.y,
            wrap(p.z, self.z[0], period.y),
        )
    }

    /// The point `(x, z)` of the plot at the fractions `u ∈ [0, 1]²` of its sides, at height
    /// `y`.
    pub fn point(&self, u: Vec2, y: f32) -> Vec3 {
        let period = self.period();
        Vec3::new(self.x[0] + u.x * period.x, y, self.z[0] + u.y * period.y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_wrap_into_the_plot_and_bad_plots_are_refused() {
        let plot = Periodic::new([-1.0, 3.0], [0.0, 2.0]).unwrap();
        assert_eq!(plot.area(), 8.0);
        assert_eq!(
            plot.wrap(Vec3::new(3.5, 7.0, -0.5)),
            Vec3::new(-0.5, 7.0, 1.5)
        );
        assert_eq!(
            plot.wrap(Vec3::new(3.0, 0.0, 2.0)),
            Vec3::new(-1.0, 0.0, 0.0)
        );
        assert_eq!(
            plot.wrap(Vec3::new(1.0, 0.0, 1.0)),
            Vec3::new(1.0, 0.0, 1.0)
        );
        let tiny = plot.wrap(Vec3::new(-1.0 - 1e-9, 0.0, 0.0));
        assert!(tiny.x >= -1.0 && tiny.x < 3.0);
        assert!(Periodic::new([1.0, 1.0], [0.0, 1.0]).is_err());
        assert!(Periodic::new([0.0, 1.0], [0.0, f32::NAN]).is_err());
        assert!(Periodic::new([0.0, 1.0], [2.0, 1.0]).is_err());
    }
}
