//! The closed forms the suite's expected values come from. Form factors are from a
//! differential area to a rectangle; the corner formulas are the standard ones of radiative
//! transfer (J. R. Howell, *A Catalog of Radiation Heat Transfer Configuration Factors*,
//! cases B-3 and B-4; also CIE 171:2006 §5.3 and §5.4), extended to any rectangle by
//! superposition of signed corner rectangles.

use std::f64::consts::PI;

/// Form factor from a differential area to a parallel rectangle whose corner lies on the
/// area's normal (Howell B-3): the rectangle `a × b` at distance `c`,
/// `F = 1/2π · [X/√(1+X²)·atan(Y/√(1+X²)) + Y/√(1+Y²)·atan(X/√(1+Y²))]`, `X = a/c`,
/// `Y = b/c`. Odd in `a` and in `b`, so signed sides superpose.
pub fn parallel_corner(a: f64, b: f64, c: f64) -> f64 {
    let (x, y) = (a / c, b / c);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * PI)
}

/// Form factor from a differential area to the parallel rectangle `[x0, x1] × [y0, y1]` at
/// distance `c`, coordinates measured in the rectangle's plane from the foot of the area's
/// normal.
pub fn parallel_rectangle((x0, x1): (f64, f64), (y0, y1): (f64, f64), c: f64) -> f64 {
    parallel_corner(x1, y1, c) - parallel_corner(x0, y1, c) - parallel_corner(x1, y0, c)
        + parallel_corner(x0, y0, c)
}

/// Form factor from a differential area to a rectangle in a perpendicular plane whose edge
/// of length `a` lies on the two planes' line of intersection, starting at the foot of the
/// perpendicular from the area to that line (Howell B-4): the rectangle rises `b` from the
/// line, the area lies at distance `c` from it,
/// `F = 1/2π · [atan(a/c) − c/√(b²+c²)·atan(a/√(b²+c²))]`. Odd in `a`.
pub fn perpendicular_corner(a: f64, b: f64, c: f64) -> f64 {
    let r = (b * b + c * c).sqrt();
    ((a / c).atan() - c / r * (a / r).atan()) / (2.0 * PI)
}

/// Form factor from a differential area to the rectangle of a perpendicular plane spanning
/// `[a0, a1]` along the line of intersection (from the foot of the perpendicular) and
/// `[h0, h1]` (`0 ≤ h0 ≤ h1`) above the area's plane, the area at distance `c` from the
/// line.
pub fn perpendicular_rectangle((a0, a1): (f64, f64), (h0, h1): (f64, f64), c: f64) -> f64 {
    let band = |h: f64| perpendicular_corner(a1, h, c) - perpendicular_corner(a0, h, c);
    band(h1) - band(h0)
}

/// Illuminance (lux, with `intensity` in cd) under a Lambertian point source of axial
/// intensity `intensity` aimed straight down from height `h`, at the angle `θ` from the
/// nadir: `E = I₀·cos θ · cos θ / d² = I₀·cos⁴θ/h²` (CIE 171:2006 §5.1).
pub fn lambertian_point(intensity: f64, h: f64, theta: f64) -> f64 {
    intensity * theta.cos().powi(4) / (h * h)
}

/// Illuminance (lux) under an isotropic point source of intensity `intensity` (cd) at height
/// `h`, at the angle `θ` from the nadir: `E = I·cos³θ/h²` (CIE 171:2006 §5.1).
pub fn isotropic_point(intensity: f64, h: f64, theta: f64) -> f64 {
    intensity * theta.cos().powi(3) / (h * h)
}

/// Mean illuminance on the inside of a closed room of surface `area` and uniform reflectance
/// `rho` lit by a source of flux `flux` (lm): direct `Φ/S` and in all `Φ/(S·(1 − ρ))`, since
/// every reflection passes on `ρ` of what arrives and nothing leaves (CIE 171:2006 §5.10).
pub fn enclosure_mean(flux: f64, area: f64, rho: f64) -> (f64, f64) {
    (flux / area, flux / (area * (1.0 - rho)))
}

/// Beer's law for the direct beam: the fraction of a beam arriving at zenith angle θ
/// (`mu = cos θ`) that passes a homogeneous canopy of leaf area index `lai` with spherical leaf
/// angles (G = ½) unintercepted, `exp(−lai / (2μ))`.
pub fn beer_beam(lai: f64, mu: f64) -> f64 {
    (-0.5 * lai / mu).exp()
}

/// Beer's law for a sky of uniform radiance: the fraction of its horizontal irradiance that
/// passes the canopy of [`beer_beam`], `2·∫₀¹ exp(−x/μ)·μ dμ = 2·E₃(x)` with `x = lai/2`, and
/// `E₃(x) = ½·[e⁻ˣ·(1 − x) + x²·E₁(x)]`, `E₁(x) = −γ − ln x − Σₖ (−x)ᵏ/(k·k!)` (the exponential
/// integrals; the series converges for the leaf area indices of canopies, to 10⁻¹⁵ in 40
/// terms for x ≤ 5).
pub fn beer_uniform_sky(lai: f64) -> f64 {
    const EULER_GAMMA: f64 = 0.577_215_664_901_532_9;
    let x = 0.5 * lai;
    let (mut term, mut sum) = (1.0, 0.0);
    for k in 1..=60 {
        term *= -x / f64::from(k);
        sum += term / f64::from(k);
    }
    let e1 = -EULER_GAMMA - x.ln() - sum;
    let e3 = 0.5 * ((-x).exp() * (1.0 - x) + x * x * e1);
    2.0 * e3
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `∫ cos θ cos θ' / (π r²) dA` over a rectangle, by the midpoint rule on a fine grid:
    /// the form factor from the area at the origin with unit normal `n` to the rectangle
    /// `origin + s·u + t·v` (`s, t ∈ [0, 1]`) whose normal is `m`.
    fn quadrature(n: [f64; 3], origin: [f64; 3], u: [f64; 3], v: [f64; 3], m: [f64; 3]) -> f64 {
        let steps = 1000;
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let cross = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let da = dot(cross, cross).sqrt() / (steps * steps) as f64;
        let mut sum = 0.0;
        for i in 0..steps {
            for j in 0..steps {
                let (s, t) = (
                    (i as f64 + 0.5) / steps as f64,
                    (j as f64 + 0.5) / steps as f64,
                );
                let p = [0, 1, 2].map(|k| origin[k] + s * u[k] + t * v[k]);
                let r2 = dot(p, p);
                let cos = dot(n, p).max(0.0) / r2.sqrt();
                let cos2 = (-dot(m, p)).max(0.0) / r2.sqrt();
                sum += cos * cos2 / (PI * r2) * da;
            }
        }
        sum
    }

    #[test]
    fn corner_formulas_agree_with_quadrature() {
        // Parallel: a 2 × 3 rectangle 1.5 above, one corner over the area.
        let f = parallel_corner(2.0, 3.0, 1.5);
        let q = quadrature(
            [0.0, 0.0, 1.0],
            [0.0, 0.0, 1.5],
            [2.0, 0.0, 0.0],
            [0.0, 3.0, 0.0],
            [0.0, 0.0, -1.0],
        );
        assert!((f - q).abs() < 1e-5 * f, "{f} vs {q}");
        // Parallel, off to one side: x ∈ [0.5, 2], y ∈ [-1, 1].
        let f = parallel_rectangle((0.5, 2.0), (-1.0, 1.0), 1.0);
        let q = quadrature(
            [0.0, 0.0, 1.0],
            [0.5, -1.0, 1.0],
            [1.5, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.0, 0.0, -1.0],
        );
        assert!((f - q).abs() < 1e-5 * f, "{f} vs {q}");
        // Perpendicular: area facing +z at the origin, wall x = 2 facing −x, y ∈ [-1, 3],
        // z ∈ [0.5, 2].
        let f = perpendicular_rectangle((-1.0, 3.0), (0.5, 2.0), 2.0);
        let q = quadrature(
            [0.0, 0.0, 1.0],
            [2.0, -1.0, 0.5],
            [0.0, 4.0, 0.0],
            [0.0, 0.0, 1.5],
            [-1.0, 0.0, 0.0],
        );
        assert!((f - q).abs() < 1e-5 * f, "{f} vs {q}");
    }

    #[test]
    fn limits_are_the_known_ones() {
        // An infinite parallel plane takes everything; a perpendicular half-plane a quarter.
        assert!((parallel_rectangle((-1e9, 1e9), (-1e9, 1e9), 1.0) - 1.0).abs() < 1e-6);
        assert!((perpendicular_rectangle((-1e9, 1e9), (0.0, 1e9), 1.0) - 0.5).abs() < 1e-6);
        assert_eq!(enclosure_mean(6.0, 6.0, 0.5), (1.0, 2.0));
    }

    #[test]
    fn beers_law_for_a_uniform_sky_is_twice_e3() {
        // E₃(0.5) = 0.2216043 and E₃(1) = 0.1096920 (Abramowitz & Stegun, table 5.2).
        assert!((beer_uniform_sky(1.0) - 2.0 * 0.221_604_3).abs() < 2e-7);
        assert!((beer_uniform_sky(2.0) - 2.0 * 0.109_692_0).abs() < 2e-7);
        // Against a midpoint sum of 2·∫ exp(−x/μ)·μ dμ.
        let n = 200_000;
        let sum: f64 = (0..n)
            .map(|i| {
                let mu = (i as f64 + 0.5) / n as f64;
                (-1.5 / mu).exp() * mu
            })
            .sum();
        assert!((beer_uniform_sky(3.0) - 2.0 * sum / n as f64).abs() < 1e-9);
        assert!((beer_beam(2.0, 0.5) - (-2.0f64).exp()).abs() < 1e-15);
    }
}
