//! Named WNL coefficient sets, selectable from specs and the command line.

use crate::models::Coefficients;

/// Names of every coefficient set, in the order they are listed in error messages.
pub const NAMES: &[&str] = &["paper-table1"];

/// The coefficient set called `name`, if there is one.
pub fn by_name(name: &str) -> Option<Coefficients> {
    match name {
        "paper-table1" => Some(Coefficients::PAPER_TABLE1),
        _ => None,
    }
}
