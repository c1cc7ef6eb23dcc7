//! What the examples that run `wavy` as a child process share (`examples/robustness_grid.rs`,
//! `examples/mesh_study.rs`).

use std::process::{Child, ExitStatus};
use std::time::{Duration, Instant};

/// How often a running child is checked for its end or its time limit.
const POLL: Duration = Duration::from_millis(200);

/// The exit status of `child`, started at `start`, or `None` when it was still running after
/// `limit` and was stopped.
pub fn wait_within(child: &mut Child, start: Instant, limit: Duration) -> Option<ExitStatus> {
    loop {
        if let Some(status) = child.try_wait().expect("wait for a child") {
            return Some(status);
        }
        if start.elapsed() > limit {
            child.kill().expect("stop a child past its time limit");
            child.wait().expect("reap a stopped child");
            return None;
        }
        std::thread::sleep(POLL);
    }
}
