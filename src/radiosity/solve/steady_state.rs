//! Scenes without a steady state. Where light is neither absorbed nor lets out — a closed
//! room whose every surface reflects all of it (ρ = 1) — radiosity grows without bound
//! (`B = E/(1 − ρ)`) and an iterative solve never settles. Every solver watches how much of
//! the light each bounce keeps ([`BounceWatch`]); once [`BOUNCES_WATCHED`] bounces in a row
//! keep at least [`MAX_KEPT`] of it, the solve stops:
//! - with [`SolveError::NoSteadyState`] where some surface reflects (and passes) at least
//!   [`MAX_KEPT`] of the light: the answer would take over a thousand bounces of every
//!   photon, and with ρ = 1 in a closed scene it does not exist;
//! - else the light is gained by the discretisation (links whose form factors add up to
//!   more than one, energy conservation bounding a bounce by the largest reflectance
//!   otherwise): [`Bounce::Gaining`], and the solver stops gathering there (hierarchical
//!   radiosity refines its links and goes on; the others end, not converged).

use super::SolveError;

/// Share of the light one bounce may keep, at most (dimensionless): at or above it, light
/// bounces a thousand times on average before it is absorbed or leaves.
pub const MAX_KEPT: f64 = 0.999;

/// Bounces in a row that must keep at least [`MAX_KEPT`] of the light before a solve stops.
pub const BOUNCES_WATCHED: u32 = 8;

/// Changes below this share of the solve's source power are round-off, not light: they are
/// not watched (a tolerance far below it would otherwise look like a bounce keeping all).
const ROUND_OFF: f64 = 1e-12;

/// What a bounce showed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bounce {
    /// The light settles (or not enough bounces are known yet).
    Settling,
    /// Bounces keep at least [`MAX_KEPT`] of the light though no surface reflects that
    /// much: the discretisation gains light (the share the last bounce kept).
    Gaining(f64),
}

/// Watches an iterative solve bounce by bounce (see the module documentation).
#[derive(Debug)]
pub struct BounceWatch {
    /// The largest reflectance plus translucency of any surface, any channel.
    largest_albedo: f64,
    /// What the last bounce carried (power, any fixed unit), none before the first.
    last: Option<f64>,
    /// Bounces in a row that kept at least [`MAX_KEPT`].
    kept_in_a_row: u32,
    /// A shooting solve: the unshot power when the current bounce began.
    bounce_start: Option<f64>,
    /// A shooting solve: the power shot since the current bounce began.
    shot_since: f64,
}

impl BounceWatch {
    /// A watch for a scene whose surfaces reflect and pass at most `largest_albedo` of the
    /// light (the largest over surfaces and channels).
    pub fn new(largest_albedo: f64) -> Self {
        BounceWatch {
            largest_albedo,
            last: None,
            kept_in_a_row: 0,
            bounce_start: None,
            shot_since: 0.0,
        }
    }

    /// A gathering solve after one more gather (one bounce): `change` is the power that
    /// gather changed, `source` the solve's source power (the same unit).
    pub fn gathered(&mut self, change: f64, source: f64) -> Result<Bounce, SolveError> {
        if change.is_nan() || change <= ROUND_OFF * source {
            self.kept_in_a_row = 0;
            self.last = None;
            return Ok(Bounce::Settling);
        }
        let kept = self.last.map(|last| change / last);
        self.last = Some(change);
        self.judge(kept)
    }

    /// A shooting solve after one shot: `shot` is the power the shot sent, `before` and
    /// `after` the unshot power in the scene before and after it (W). Once the shots since
    /// the current bounce began have sent as much as was unshot then, the bounce is done and
    /// keeps `after / unshot then`.
    pub fn shot(&mut self, shot: f64, before: f64, after: f64) -> Result<Bounce, SolveError> {
        let start = *self.bounce_start.get_or_insert(before);
        self.shot_since += shot.abs();
        if start.is_nan() || start <= 0.0 || self.shot_since < start {
            return Ok(Bounce::Settling);
        }
        self.bounce_start = Some(after);
        self.shot_since = 0.0;
        self.judge(Some(after / start))
    }

    /// Counts a bounce that kept `kept` of the light (none: not known yet).
    fn judge(&mut self, kept: Option<f64>) -> Result<Bounce, SolveError> {
        match kept {
            Some(kept) if kept >= MAX_KEPT => {
                self.kept_in_a_row += 1;
                if self.kept_in_a_row < BOUNCES_WATCHED {
                    Ok(Bounce::Settling)
                } else if self.largest_albedo >= MAX_KEPT {
                    Err(SolveError::NoSteadyState { kept })
                } else {
                    self.kept_in_a_row = 0;
                    Ok(Bounce::Gaining(kept))
                }
            }
            _ => {
                self.kept_in_a_row = 0;
                Ok(Bounce::Settling)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_gather_that_keeps_everything_stops_after_the_watched_bounces() {
        let mut watch = BounceWatch::new(1.0);
        // The first gather has nothing to compare with; then eight keep all of it.
        for k in 0..=BOUNCES_WATCHED {
            let outcome = watch.gathered(1.0, 1.0);
            assert_eq!(outcome.is_err(), k == BOUNCES_WATCHED, "gather {k}");
        }
        // Where no surface reflects that much, the discretisation gains the light.
        let mut watch = BounceWatch::new(0.995);
        let outcomes: Vec<Bounce> = (0..=BOUNCES_WATCHED)
            .map(|_| watch.gathered(1.0, 1.0).unwrap())
            .collect();
        assert_eq!(outcomes.last(), Some(&Bounce::Gaining(1.0)));
        assert!(outcomes[..8].iter().all(|&b| b == Bounce::Settling));
    }

    #[test]
    fn a_gather_that_loses_light_never_stops() {
        // ρ = 0.998: light bounces 500 times on average; a bounce keeps 99.8 %.
        let mut watch = BounceWatch::new(1.0);
        let mut change = 1.0;
        for _ in 0..10_000 {
            assert_eq!(watch.gathered(change, 1.0).unwrap(), Bounce::Settling);
            change *= 0.998;
        }
        // Round-off: changes at 10⁻¹³ of the source are not bounces.
        for _ in 0..100 {
            assert_eq!(watch.gathered(1e-13, 1.0).unwrap(), Bounce::Settling);
        }
    }

    #[test]
    fn shots_are_judged_bounce_by_bounce() {
        // Ten patches of equal unshot power; every shot sends one patch's worth.
        let mut closed = BounceWatch::new(1.0);
        let stopped =
            (0..10 * (BOUNCES_WATCHED + 1)).position(|_| closed.shot(1.0, 10.0, 10.0).is_err());
        // Every bounce is ten shots.
        assert_eq!(stopped, Some(10 * BOUNCES_WATCHED as usize - 1));
        // Each shot absorbing half of what it sends.
        let mut open = BounceWatch::new(1.0);
        let mut unshot = 10.0;
        for _ in 0..1000 {
            let (shot, before) = (unshot / 10.0, unshot);
            unshot -= shot / 2.0;
            assert_eq!(open.shot(shot, before, unshot).unwrap(), Bounce::Settling);
        }
    }
}
