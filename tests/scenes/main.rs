//! Every scene through the runner: the snapshots of their outputs, the test-size speed–accuracy,
//! two-scale and many-scale scenes, the fingertip scenes, `wavy check`, random specs, and `wavy diff`'s review.
//!
//! One test binary per concern, each module one file as it was before the grouping (fewer binaries
//! link faster, and the tests of a binary share its threads).

mod check;
mod fingertip;
mod fuzz_specs;
mod many_scale;
mod review;
mod snapshots;
mod speed_accuracy;
mod two_scale;

/// Runs `assertions` with insta's snapshots in `tests/snapshots/`, each named as the assertion
/// names it in full (`<file>__<name>`, the file of this folder that asserts it): the names the
/// snapshots had when each file was a test binary of its own.
pub fn in_snapshot_folder<R>(assertions: impl FnOnce() -> R) -> R {
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path("../snapshots");
    settings.set_prepend_module_to_snapshot(false);
    settings.bind(assertions)
}
