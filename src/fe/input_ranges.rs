//! The range of each input of a solve, one definition each: [`crate::fe::validate`] checks a
//! problem against them under the fields' names, the request layer
//! (`runner::requests::input_checks::within`) under the command line's flags, with the same
//! words for what is allowed.

use crate::fe::error::SolveError;

/// The allowed values of one input: its field name, the range in words, and the test.
#[derive(Clone, Copy)]
pub struct InputRange {
    /// The field's name in [`crate::fe::LayerProblem`], [`crate::fe::SolveOptions`] or their parts.
    pub field: &'static str,
    /// The range in words, as messages print it.
    pub allowed: &'static str,
    test: fn(f64) -> bool,
}

/// `v > 0`.
fn positive(v: f64) -> bool {
    v > 0.0
}

impl InputRange {
    /// A range of the positive values, for the field `field`.
    const fn positive(field: &'static str) -> InputRange {
        InputRange {
            field,
            allowed: "> 0",
            test: positive,
        }
    }

    /// Whether `value` is finite and in the range.
    pub fn holds(&self, value: f64) -> bool {
        value.is_finite() && (self.test)(value)
    }

    /// `Ok` when `value` is in the range, else [`SolveError::InvalidInput`] naming the field.
    pub fn check(&self, value: f64) -> Result<(), SolveError> {
        match self.holds(value) {
            true => Ok(()),
            false => Err(SolveError::InvalidInput {
                field: self.field,
                value,
                allowed: self.allowed,
            }),
        }
    }
}

/// The indenter's aspect ratio `Δ/λ`.
pub const ASPECT_RATIO: InputRange = InputRange::positive("aspect_ratio");

/// The layer's thickness `h/λ`.
pub const THICKNESS_OVER_LAMBDA: InputRange = InputRange::positive("thickness_over_lambda");

/// The bulk-to-shear modulus ratio `κ/G`.
pub const KAPPA_OVER_G: InputRange = InputRange::positive("kappa_over_g");

/// The contact half-width `a/λ` a curve loads to: inside the half period.
pub const UNTIL_A_OVER_LAMBDA: InputRange = InputRange {
    field: "until_a_over_lambda",
    allowed: "(0, 0.5)",
    test: |v| v > 0.0 && v < 0.5,
};

/// The mean pressure `p̄/E*` a curve loads to.
pub const UNTIL_P_OVER_ESTAR: InputRange = InputRange::positive("until_p_over_estar");

/// The contact fraction a curve loads to: short of full contact.
pub const UNTIL_CONTACT_FRACTION: InputRange = InputRange {
    field: "until_contact_fraction",
    allowed: "(0, 1)",
    test: |v| v > 0.0 && v < 1.0,
};

/// The friction coefficient μ of a frictional interface.
pub const FRICTION_COEFFICIENT: InputRange = InputRange::positive("friction_coefficient");

/// The Orowan shear limit `τ_max/E*` of a frictional interface.
pub const TAU_MAX_OVER_ESTAR: InputRange = InputRange::positive("tau_max_over_estar");

/// The stick band `e_c` of a frictional interface, in face elements: 0 is exact stick.
pub const ELASTIC_SLIP_OVER_ELEMENT: InputRange = InputRange {
    field: "elastic_slip_over_element",
    allowed: ">= 0",
    test: |v| v >= 0.0,
};

/// The target advance of `a/λ` per load step.
pub const DA_TARGET: InputRange = InputRange {
    field: "da_target",
    allowed: ">= 0",
    test: |v| v >= 0.0,
};

/// Unloading steps per loading step: a whole number, at least one.
pub const UNLOADING_SUBSTEPS: InputRange = InputRange {
    field: "unloading_substeps",
    allowed: "a whole number >= 1",
    test: |v| v >= 1.0 && v.fract() == 0.0,
};

/// The fraction of its element at which the fraction edge rule places the contact edge.
pub const EDGE_FRACTION: InputRange = InputRange {
    field: "edge_rule.fraction",
    allowed: "[0, 1]",
    test: |v| (0.0..=1.0).contains(&v),
};

/// The mesh grading's ratio of the face spacing at the valley `X = ½` to that at the peak.
pub const PEAK_RATIO: InputRange = InputRange {
    field: "grading.peak_ratio",
    allowed: ">= 1",
    test: |v| v >= 1.0,
};

/// The mesh grading's first layer height over the face spacing.
pub const FIRST_LAYER_OVER_DX: InputRange = InputRange::positive("grading.first_layer_over_dx");

/// The row height over column width at which the mesh's columns are coarsened: below 1 a
/// transition would make elements flatter than they are tall by more than threefold.
pub const COARSEN_AT_ASPECT: InputRange = InputRange {
    field: "grading.coarsen_at_aspect",
    allowed: "0 (no coarsening) or >= 1",
    test: |v| v == 0.0 || v >= 1.0,
};

#[cfg(test)]
mod tests {
    use super::*;

    /// The open ends are open, a NaN or an infinity is never in range, and the error names the
    /// field with the same words for the range.
    #[test]
    fn ranges_are_open_where_they_say_and_name_their_field() {
        assert!(UNTIL_A_OVER_LAMBDA.holds(0.25));
        assert!(!UNTIL_A_OVER_LAMBDA.holds(0.5));
        assert!(!UNTIL_CONTACT_FRACTION.holds(0.0));
        assert!(!ASPECT_RATIO.holds(f64::NAN));
        assert!(!ASPECT_RATIO.holds(f64::INFINITY));
        match KAPPA_OVER_G.check(-1.0) {
            Err(SolveError::InvalidInput { field, allowed, .. }) => {
                assert_eq!((field, allowed), ("kappa_over_g", "> 0"));
            }
            other => panic!("expected InvalidInput, got {other:?}"),
        }
    }
}
