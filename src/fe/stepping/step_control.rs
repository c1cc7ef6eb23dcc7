//! The two ways the solver finds a slab displacement: regula falsi (Illinois) on a residual
//! that changes sign, and cutting a failed step back towards its start.
//!
//! The edge-event search ([`crate::fe::stepping::event_search`]) finds the displacement at which the
//! target node's gap vanishes; the landing on a pressure target
//! ([`crate::fe::stepping::pressure_target`]) the one at which the mean pressure equals the target. The
//! event search, the pressure landing and the unloading steps retry a failed step from its
//! start with the increment cut ([`StepCuts`]).

use crate::fe::error::StepFail;

/// A failed increment is cut by this factor before it is retried
/// ([`crate::fe::StepOptions::max_step_cuts`] counts the cuts): halving.
pub(crate) const STEP_CUT_FACTOR: f64 = 0.5;

/// Illinois modification of regula falsi: when the same end of the bracket is kept twice,
/// its residual is scaled by this factor (Dowell & Jarratt 1971); the value defines the
/// method (superlinear, order ≈ 1.44, instead of the linear order of plain regula falsi).
const ILLINOIS_FACTOR: f64 = 0.5;

/// The cuts of a failed step, at most `max` in a row, none to an increment below `floor`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StepCuts {
    made: usize,
    max: usize,
    floor: f64,
}

impl StepCuts {
    /// No cut made yet, at most `max` allowed, with no floor on the increment.
    pub(crate) fn new(max: usize) -> Self {
        Self::with_floor(max, 0.0)
    }

    /// No cut made yet, at most `max` allowed in a row, and none that would leave an
    /// increment (`|to − from|` after the cut, units of λ) below `floor`: where a step that
    /// converges resets the count, the floor is what ends a run of cuts that makes no
    /// progress.
    pub(crate) fn with_floor(max: usize, floor: f64) -> Self {
        Self {
            made: 0,
            max,
            floor,
        }
    }

    /// The slab displacement a cut step reaches from `from` towards the failed `to`
    /// (`from + ½ (to − from)`), counting the cut; `None` once `max` cuts have been made or
    /// when the cut increment would be below the floor.
    pub(crate) fn cut(&mut self, from: f64, to: f64) -> Option<f64> {
        let increment = STEP_CUT_FACTOR * (to - from);
        if self.made == self.max || increment.abs() < self.floor {
            return None;
        }
        self.made += 1;
        Some(from + increment)
    }

    /// After the trial from `from` to `to` failed: the displacement to try next ([`Self::cut`]),
    /// the failure's Newton iterations added to `spent`; with no cut left, the failure, counting
    /// `spent` too.
    pub(crate) fn after_failure(
        &mut self,
        (from, to): (f64, f64),
        failed: StepFail,
        spent: &mut usize,
    ) -> Result<f64, StepFail> {
        match self.cut(from, to) {
            Some(next) => {
                *spent += failed.iterations();
                Ok(next)
            }
            None => Err(failed.after(*spent)),
        }
    }

    /// A step converged: the next failure starts counting again.
    pub(crate) fn reset(&mut self) {
        self.made = 0;
    }

    /// Cuts made in a row so far.
    pub(crate) fn made(&self) -> usize {
        self.made
    }
}

/// A trial of a regula-falsi search: its slab displacement `x`, its residual `f` and what
/// it carries (the converged state).
#[derive(Clone, Debug)]
pub(crate) struct Trial<S> {
    /// Slab displacement (units of λ).
    pub x: f64,
    /// Residual: positive before the root, zero or negative beyond it.
    pub f: f64,
    /// What the trial carries.
    pub at: S,
}

/// End of the bracket kept by the last update (Illinois).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum KeptEnd {
    /// The positive end was replaced, the non-positive one kept.
    NonPositive,
    /// The non-positive end was replaced, the positive one kept.
    Positive,
}

/// Regula falsi with the Illinois modification on a residual that is positive before the
/// root and non-positive beyond it, bracketed once a non-positive trial is known.
#[derive(Clone, Debug)]
pub(crate) struct RegulaFalsi<S> {
    /// Last trial with a positive residual.
    pub below: Trial<S>,
    /// The positive trial before it, if any (for a secant extrapolation before the root is
    /// bracketed).
    pub below_prev: Option<Trial<S>>,
    /// Last trial with a non-positive residual (`x`, `f`), once one is known.
    pub beyond: Option<(f64, f64)>,
    last_kept: Option<KeptEnd>,
}

impl<S> RegulaFalsi<S> {
    /// A search from the positive trial `below` (and the one before it, if any).
    pub(crate) fn new(below: Trial<S>, below_prev: Option<Trial<S>>) -> Self {
        Self {
            below,
            below_prev,
            beyond: None,
            last_kept: None,
        }
    }

    /// Insert a trial; the Illinois modification scales the residual of an end kept twice
    /// in a row by [`ILLINOIS_FACTOR`].
    pub(crate) fn insert(&mut self, trial: Trial<S>) {
        if trial.f > 0.0 {
            let old = std::mem::replace(&mut self.below, trial);
            self.below_prev = Some(old);
            if self.last_kept == Some(KeptEnd::NonPositive) {
                if let Some(beyond) = self.beyond.as_mut() {
                    beyond.1 *= ILLINOIS_FACTOR;
                }
            }
            self.last_kept = Some(KeptEnd::NonPositive);
        } else {
            if self.last_kept == Some(KeptEnd::Positive) {
                self.below.f *= ILLINOIS_FACTOR;
            }
            self.last_kept = Some(KeptEnd::Positive);
            self.beyond = Some((trial.x, trial.f));
        }
    }

    /// The regula-falsi point inside the bracket, its fraction of the bracket bounded to
    /// `[min_fraction, max_fraction]`; `None` before the root is bracketed.
    pub(crate) fn next(&self, min_fraction: f64, max_fraction: f64) -> Option<f64> {
        let (x_beyond, f_beyond) = self.beyond?;
        let t = self.below.f / (self.below.f - f_beyond);
        Some(self.below.x + t.clamp(min_fraction, max_fraction) * (x_beyond - self.below.x))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(x: f64, f: f64) -> Trial<()> {
        Trial { x, f, at: () }
    }

    /// Regula falsi inside the bracket, and the Illinois scaling of an end kept twice.
    #[test]
    fn regula_falsi_brackets_with_illinois() {
        let mut search = RegulaFalsi::new(at(1.0, 1.0), Some(at(0.0, 2.0)));
        assert_eq!(search.next(0.0, 1.0), None);
        search.insert(at(2.0, -1.0));
        // between (1, 1) and (2, −1)
        assert_eq!(search.next(0.0, 1.0), Some(1.5));
        search.insert(at(1.5, -0.5));
        // the positive end is kept twice: its residual is scaled
        assert_eq!(search.below.f, ILLINOIS_FACTOR);
        let t = ILLINOIS_FACTOR / (ILLINOIS_FACTOR + 0.5);
        assert_eq!(search.next(0.0, 1.0), Some(1.0 + t * 0.5));
        // the fraction bounds keep the trial inside the bracket
        assert_eq!(search.next(0.9, 0.98), Some(1.0 + 0.9 * 0.5));
    }

    /// Cuts halve towards the start, at most `max` in a row, and count again after a reset.
    #[test]
    fn step_cuts_halve_at_most_max_times() {
        let mut cuts = StepCuts::new(2);
        assert_eq!(cuts.cut(1.0, 2.0), Some(1.5));
        assert_eq!(cuts.cut(1.0, 1.5), Some(1.25));
        assert_eq!(cuts.made(), 2);
        assert_eq!(cuts.cut(1.0, 1.25), None);
        cuts.reset();
        assert_eq!(cuts.cut(0.0, 1.0), Some(0.5));
    }

    /// With a floor, a run of cuts that converge and reset the count still ends: no cut
    /// leaves an increment below the floor, whichever way the step goes.
    #[test]
    fn step_cuts_stop_at_their_floor_across_resets() {
        let mut cuts = StepCuts::with_floor(12, 0.1);
        let (mut from, to) = (1.0, 0.0);
        let mut converged = 0;
        while let Some(next) = cuts.cut(from, to) {
            // the cut step converges, the retry of the target fails again
            from = next;
            cuts.reset();
            converged += 1;
        }
        assert_eq!(
            converged, 3,
            "increments 0.5, 0.25, 0.125; 0.0625 is below the floor"
        );
        assert!((from - 0.125).abs() < 1e-15);
        assert_eq!(cuts.cut(0.3, 0.5), Some(0.4));
        assert_eq!(cuts.cut(0.3, 0.45), None);
    }
}
