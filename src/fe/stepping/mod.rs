//! What one load step does: the load path from one contact event to the next.
//!
//! [`loading`] steps from one contact-edge event to the next, to a contact width or (with
//! [`pressure_target`]) to a mean pressure, carrying a [`load_path`] (the last states, the points,
//! when the step callback sees them), and [`unloading`] back to zero load;
//! [`event_search`] finds which node touches next and at which slab displacement,
//! [`node_events`] the same for a contact in several patches (profiles), and
//! [`release_events`] where a contact node lets go; [`step_control`] holds the one regula falsi
//! and the step cutter; [`predictor`] the load tangent and the predicted state of a step, [`touched_hold`] the nodes that have
//! just touched held in it; [`displacement_step`] the step that predicts and equilibrates, [`slip_front`] an unloading
//! step's prediction through its slip front;
//! [`step_state`] the deformed state of every converged point, built only for a caller that
//! asks; `test_fixtures` the fixtures of their unit tests.

pub mod displacement_step;
pub mod event_search;
pub mod load_path;
pub mod loading;
pub mod node_events;
pub mod predictor;
pub mod pressure_target;
pub mod release_events;
pub mod slip_front;
pub mod step_control;
pub mod step_state;
#[cfg(test)]
pub(crate) mod test_fixtures;
pub mod touched_hold;
pub mod unloading;
