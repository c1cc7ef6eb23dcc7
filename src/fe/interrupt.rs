//! A caller's request to stop a solve mid-iteration: a flag the caller owns (another thread
//! sets it, e.g. on Ctrl-C), watched by the solves that run inside [`watching`] on this thread.
//! Every Newton iteration and every linear solve (`SparseSystem::solve_switching_rows`) reads
//! it ([`requested`]) and, once set, fails at once, so a solve stops after the factorisation
//! under way rather than after its load step (the stepping's retries of a failed step then
//! fail at once too). Without [`watching`] nothing is watched and the solver runs as before,
//! to the same bits (the flag only ends a solve).

use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

thread_local! {
    /// The flag watched by the solves of this thread, if any.
    static WATCHED: RefCell<Option<Arc<AtomicBool>>> = const { RefCell::new(None) };
}

/// The reason a Newton iteration gives when it stops on the caller's request.
pub const INTERRUPTED: &str = "interrupted by the caller";

/// Runs `f` with `flag` watched by every solve it starts on this thread; the previous watch
/// (if any) is restored afterwards, also when `f` panics.
pub fn watching<R>(flag: Arc<AtomicBool>, f: impl FnOnce() -> R) -> R {
    struct Restore(Option<Arc<AtomicBool>>);
    impl Drop for Restore {
        fn drop(&mut self) {
            let previous = self.0.take();
            WATCHED.with(|w| *w.borrow_mut() = previous);
        }
    }
    let _restore = Restore(WATCHED.with(|w| w.borrow_mut().replace(flag)));
    f()
}

/// True when the watched flag of this thread is set.
pub fn requested() -> bool {
    WATCHED.with(|w| {
        w.borrow()
            .as_ref()
            .is_some_and(|f| f.load(Ordering::Relaxed))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_a_watched_set_flag_is_requested_and_the_watch_ends_with_its_scope() {
        assert!(!requested());
        let flag = Arc::new(AtomicBool::new(false));
        watching(flag.clone(), || {
            assert!(!requested());
            flag.store(true, Ordering::Relaxed);
            assert!(requested());
        });
        assert!(!requested());
        // another thread's flag is not this thread's
        let other = Arc::new(AtomicBool::new(true));
        let seen = std::thread::spawn(move || watching(other, requested))
            .join()
            .unwrap();
        assert!(seen && !requested());
    }

    #[test]
    fn a_solve_watching_a_set_flag_fails_at_its_first_newton_iteration() {
        use crate::fe::test_problems::coarse_sinusoid;
        use crate::fe::{self, Interface};
        let (problem, options) = coarse_sinusoid(0.1, Interface::Frictionless);
        let mut steps = 0;
        let failure = watching(Arc::new(AtomicBool::new(true)), || {
            fe::solve_curve(&problem, &options, &mut |_| {
                steps += 1;
                std::ops::ControlFlow::Continue(())
            })
        })
        .unwrap_err();
        assert_eq!(steps, 0);
        assert!(failure.points.is_empty());
        assert!(
            failure.error.to_string().contains(INTERRUPTED),
            "{}",
            failure.error
        );
        // unwatched, the same solve converges its steps
        assert!(fe::solve_curve(
            &problem,
            &options,
            &mut |_| std::ops::ControlFlow::Continue(())
        )
        .is_ok());
    }
}
