//! wavy: contact of a soft solid on a rigid wavy surface (Westergaard, WNL, finite elements).
pub mod fe;
