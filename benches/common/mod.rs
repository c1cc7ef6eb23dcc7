//! What the solver bench (`benches/solver.rs`), the speed table (`examples/speed_table.rs`)
//! and the Fig. 3 work count (`examples/fig3_work.rs`) share.

use wavy::fe::{Interface, Kinematics, LayerProblem};

/// Peak resident memory of this process (`VmHWM`, kB), if `/proc` has it.
#[allow(dead_code)] // not every user of this module needs it
pub fn peak_memory_kb() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// The finite-strain layer problem at aspect ratio `ar`, frictional when `τ_max/E*` > 0 (μ,
/// the stick regularisation and the rest at the project's defaults): Fig. 3's physics.
#[allow(dead_code)] // not every user of this module needs it
pub fn finite_layer_problem(ar: f64, tau_max_over_estar: f64) -> LayerProblem {
    LayerProblem {
        kinematics: Kinematics::Finite,
        interface: Interface::coulomb_orowan(
            wavy::defaults::friction_coefficient(),
            tau_max_over_estar,
            wavy::defaults::elastic_slip_over_element(),
        ),
        ..wavy::defaults::layer_problem(ar)
    }
}
