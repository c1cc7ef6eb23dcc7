//! The contact face: the rigid indenter and what touches it.
//!
//! [`indenter`] is the analytic surface (a sinusoid or a profile) the face is pressed on;
//! [`friction`] the Coulomb–Orowan law, its return mapping and tangent rows; [`edge_rule`]
//! where a contact edge lies inside its element, [`patches`] the contact patches of a profile,
//! [`patch_edge`] where each of their edges lies between its own events as the state shows it,
//! [`edge_tracks`] the same by the load once the loading curve knows the next events,
//! [`stick_zone`] where the face sticks, and [`measure`] the point and the deformed state of a converged state.

pub mod edge_rule;
pub mod edge_tracks;
pub mod friction;
pub mod indenter;
pub mod measure;
pub mod patch_edge;
pub mod patches;
pub mod stick_zone;
