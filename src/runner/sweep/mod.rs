//! Sweeps of expensive cases: in parallel, cached on disk, resumable, and splittable across
//! machines.
//!
//! Each case is identified by the text of every input that affects its result (its
//! [`SweepCase::key_text`], which must include the solver's version); the SHA-256 of that text
//! names its cache file. A sweep computes only the cases whose file is missing, writes each
//! result atomically as soon as it is known — so an interrupted sweep resumes where it stopped —
//! and, with a [`Shard`] `i/n`, computes only the cases with index ≡ i (mod n), so that n
//! machines sharing the cache folder (a Slurm job array) split the work and a final unsharded run
//! assembles the figure from the cache.

pub mod fe_cases;

use crate::runner::atomic_write::{self, write_atomic};
use anyhow::{bail, Context, Result};
use sha2::{Digest, Sha256};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// One case of a sweep.
pub trait SweepCase: Sync {
    /// Every input that affects the result, as text (exact: floats by their bits or in
    /// shortest round-trip form), including the solver's version.
    fn key_text(&self) -> String;
    /// A short label for progress and error messages.
    fn label(&self) -> String;
    /// Relative cost estimate: cases are started most expensive first, so that the last
    /// ones to finish are short (longest-processing-time-first scheduling).
    fn cost_hint(&self) -> f64 {
        0.0
    }
}

/// A result that can be stored in and read back from a cache file.
pub trait Cacheable: Sized + Send {
    fn to_cache_text(&self) -> String;
    fn from_cache_text(text: &str) -> Option<Self>;
}

/// The part `index` (0-based) of `count` parts of a sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

/// A shard that is not `i/n` with `0 <= i < n`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("value {0} is out of range; allowed: i/n with 0 <= i < n, e.g. 0/4")]
pub struct ShardParseError(pub String);

impl FromStr for Shard {
    type Err = ShardParseError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || ShardParseError(s.into());
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count): (usize, usize) = (
            i.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }
}

/// The cache folder when none is named (`--cache`).
pub const DEFAULT_CACHE_DIR: &str = ".wavy-cache";

/// How to run a sweep.
#[derive(Debug, Clone)]
pub struct SweepOptions {
    /// Worker threads (≥ 1).
    pub jobs: usize,
    pub shard: Option<Shard>,
    /// Folder of the cache files.
    pub cache_dir: PathBuf,
}

impl Default for SweepOptions {
    fn default() -> Self {
        Self {
            jobs: rayon::current_num_threads(),
            shard: None,
            cache_dir: PathBuf::from(DEFAULT_CACHE_DIR),
        }
    }
}

/// The cache file of a case.
pub fn cache_path(dir: &Path, case: &impl SweepCase) -> PathBuf {
    let digest = Sha256::digest(case.key_text().as_bytes());
    let hex: String = digest.iter().map(|b| format!("{b:02x}")).collect();
    dir.join(format!("{hex}.txt"))
}

/// What a sweep returns: per case, its result, or `None` for cases left to other shards.
pub struct SweepResult<R> {
    pub results: Vec<Option<R>>,
    pub computed: usize,
    pub from_cache: usize,
}

/// Runs `compute` for every case of this shard that the cache does not hold.
pub fn run<C: SweepCase, R: Cacheable>(
    cases: &[C],
    opts: &SweepOptions,
    compute: impl Fn(&C) -> R + Sync,
) -> Result<SweepResult<R>> {
    if opts.jobs == 0 {
        bail!("--jobs = 0 is out of range; allowed: >= 1");
    }
    std::fs::create_dir_all(&opts.cache_dir).with_context(|| {
        format!(
            "cannot create the cache folder {}",
            opts.cache_dir.display()
        )
    })?;
    atomic_write::remove_stale_temporaries(&opts.cache_dir)?;
    let mine = |i: usize| opts.shard.is_none_or(|s| i % s.count == s.index);
    let mut results: Vec<Option<R>> = Vec::with_capacity(cases.len());
    let mut todo = vec![];
    for (i, case) in cases.iter().enumerate() {
        let path = cache_path(&opts.cache_dir, case);
        let cached = std::fs::read_to_string(&path)
            .ok()
            .and_then(|t| cached_result::<R>(&t, &case.key_text()));
        if cached.is_none() && mine(i) {
            todo.push(i);
        }
        results.push(cached);
    }
    let from_cache = results.iter().filter(|r| r.is_some()).count();
    let bar = progress_bar(todo.len());
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.jobs)
        .build()
        .context("cannot start worker threads")?;
    // Most expensive first; each worker takes the next case off the shared queue.
    todo.sort_by(|&i, &j| cases[j].cost_hint().total_cmp(&cases[i].cost_hint()));
    let next = std::sync::atomic::AtomicUsize::new(0);
    let done = std::sync::Mutex::new(Vec::with_capacity(todo.len()));
    pool.scope(|scope| {
        for _ in 0..opts.jobs {
            scope.spawn(|_| loop {
                let t = next.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
                let Some(&i) = todo.get(t) else { break };
                let case = &cases[i];
                let r = compute(case);
                let text = format!(
                    "# {}\n{}",
                    case.key_text().replace('\n', "\n# "),
                    r.to_cache_text()
                );
                let stored =
                    write_atomic(&cache_path(&opts.cache_dir, case), text.as_bytes()).map(|_| r);
                if let Some(b) = &bar {
                    b.inc(1);
                    b.set_message(case.label());
                }
                done.lock().expect("no worker panicked").push((i, stored));
            });
        }
    });
    let computed = done.into_inner().expect("no worker panicked");
    atomic_write::remove_own_temporaries(&opts.cache_dir);
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let n = computed.len();
    for (i, r) in computed {
        results[i] = Some(r?);
    }
    Ok(SweepResult {
        results,
        computed: n,
        from_cache,
    })
}

/// A cache file's result, if its key lines match (a hash collision or a stale format reads as a miss).
fn cached_result<R: Cacheable>(text: &str, key_text: &str) -> Option<R> {
    let key_lines = key_text.lines().count();
    let mut lines = text.lines();
    for expected in key_text.lines() {
        if lines.next()? != format!("# {expected}") {
            return None;
        }
    }
    let body: String = text
        .lines()
        .skip(key_lines)
        .map(|l| format!("{l}\n"))
        .collect();
    R::from_cache_text(&body)
}

/// The progress of `len` cases on stderr when it is a terminal (none when piped or with no
/// cases): cases done of total and the elapsed time, redrawn every quarter second so that a
/// long case shows the time going by.
pub fn progress_bar(len: usize) -> Option<indicatif::ProgressBar> {
    if len == 0 || !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = indicatif::ProgressBar::new(len as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} cases  {msg}",
        )
        .expect("a valid template"),
    );
    bar.enable_steady_tick(std::time::Duration::from_millis(250));
    Some(bar)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    struct Case(u32);
    impl SweepCase for Case {
        fn key_text(&self) -> String {
            format!("square v1\nn = {}", self.0)
        }
        fn label(&self) -> String {
            format!("n = {}", self.0)
        }
    }
    #[derive(Debug, PartialEq)]
    struct Square(u64);
    impl Cacheable for Square {
        fn to_cache_text(&self) -> String {
            format!("{}\n", self.0)
        }
        fn from_cache_text(text: &str) -> Option<Self> {
            text.trim().parse().ok().map(Square)
        }
    }

    #[test]
    fn computes_once_resumes_and_shards() {
        let dir = tempfile::tempdir().unwrap();
        let cases: Vec<Case> = (0..10).map(Case).collect();
        let calls = AtomicUsize::new(0);
        let f = |c: &Case| {
            calls.fetch_add(1, Ordering::SeqCst);
            Square(u64::from(c.0) * u64::from(c.0))
        };
        let opts = |shard| SweepOptions {
            jobs: 2,
            shard,
            cache_dir: dir.path().to_path_buf(),
        };
        // Shard 1/3 computes cases 1, 4, 7 only.
        let r = run(&cases, &opts(Some(Shard { index: 1, count: 3 })), f).unwrap();
        assert_eq!(r.computed, 3);
        assert_eq!(r.results.iter().filter(|x| x.is_some()).count(), 3);
        assert_eq!(r.results[4], Some(Square(16)));
        // The unsharded run computes the other 7 and reads 3 from the cache.
        let r = run(&cases, &opts(None), f).unwrap();
        assert_eq!((r.computed, r.from_cache), (7, 3));
        assert_eq!(calls.load(Ordering::SeqCst), 10);
        assert_eq!(r.results[9], Some(Square(81)));
        // Nothing left to do.
        let r = run(&cases, &opts(None), f).unwrap();
        assert_eq!((r.computed, r.from_cache), (0, 10));
        assert_eq!(calls.load(Ordering::SeqCst), 10);
    }

    #[test]
    fn shard_parsing_names_the_flag_and_range() {
        assert_eq!("2/4".parse::<Shard>(), Ok(Shard { index: 2, count: 4 }));
        for bad in ["4/4", "1/0", "a/2", "3"] {
            let e = bad.parse::<Shard>().unwrap_err().to_string();
            assert!(e.contains(&format!("value {bad} is out of range")), "{e}");
        }
    }
}
