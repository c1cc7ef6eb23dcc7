//! Atomic file writes whose temporaries a rerun can find and remove.
//!
//! A file is written to a temporary in `<folder>/.wavy-tmp/<host>-<pid>/` and renamed into
//! place, so a reader never sees a partial file. A run that is killed (SIGKILL, power loss)
//! leaves its temporaries behind, always in that folder and never beside the outputs: the next
//! run in the same folder removes the temporaries of every process of this host that is no
//! longer running ([`remove_stale_temporaries`]), and a run removes its own empty folder when it
//! is done. Shards on other hosts that share a cache folder are left alone.

use anyhow::{Context, Result};
use std::io::Write;
use std::path::{Path, PathBuf};

/// The folder of temporaries inside an output or cache folder.
pub const TEMPORARIES: &str = ".wavy-tmp";

/// This host's name (for the temporaries of processes that may run on several hosts).
fn host() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .or_else(|_| std::fs::read_to_string("/etc/hostname"))
        .map(|h| h.trim().to_string())
        .ok()
        .filter(|h| !h.is_empty() && !h.contains(['/', '\\']))
        .unwrap_or_else(|| "localhost".into())
}

/// The folder of this process's temporaries in `dir`.
fn own_temporaries(dir: &Path) -> PathBuf {
    dir.join(TEMPORARIES)
        .join(format!("{}-{}", host(), std::process::id()))
}

/// Whether process `pid` of this host is running. Without `/proc` this cannot be told, and
/// every process counts as running (nothing is removed).
fn running(pid: u32) -> bool {
    let proc = Path::new("/proc");
    !proc.join("self").exists() || proc.join(pid.to_string()).exists()
}

/// Removes the temporaries that processes of this host left in `dir` when they were killed;
/// returns how many files were removed. Folders of running processes and of other hosts stay.
pub fn remove_stale_temporaries(dir: &Path) -> Result<usize> {
    let root = dir.join(TEMPORARIES);
    let Ok(entries) = std::fs::read_dir(&root) else {
        return Ok(0);
    };
    let prefix = format!("{}-", host());
    let mut removed = 0;
    for e in entries.flatten() {
        let name = e.file_name();
        let Some(pid) = name
            .to_str()
            .and_then(|n| n.strip_prefix(&prefix))
            .and_then(|p| p.parse::<u32>().ok())
        else {
            continue;
        };
        if pid == std::process::id() || running(pid) {
            continue;
        }
        removed += std::fs::read_dir(e.path()).map_or(0, |d| d.count());
        std::fs::remove_dir_all(e.path()).with_context(|| {
            format!("cannot remove the stale temporaries {}", e.path().display())
        })?;
    }
    let _ = std::fs::remove_dir(&root); // only if empty
    Ok(removed)
}

/// Removes this process's (empty) folder of temporaries in `dir`, and the folder of
/// temporaries itself when nothing else is in it. Call when no write is under way.
pub fn remove_own_temporaries(dir: &Path) {
    let _ = std::fs::remove_dir(own_temporaries(dir));
    let _ = std::fs::remove_dir(dir.join(TEMPORARIES));
}

/// Writes `bytes` to `path` through a temporary file and a rename.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let tmp_dir = own_temporaries(dir);
    std::fs::create_dir_all(&tmp_dir)
        .with_context(|| format!("cannot write in {}", dir.display()))?;
    let mut tmp = tempfile::NamedTempFile::new_in(&tmp_dir)
        .with_context(|| format!("cannot write in {}", dir.display()))?;
    tmp.write_all(bytes)
        .with_context(|| format!("cannot write {}", path.display()))?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        // tempfile creates 0600 files; outputs are ordinary, readable files.
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(0o644))
            .ok();
    }
    tmp.as_file().sync_all().ok();
    tmp.persist(path)
        .with_context(|| format!("cannot replace {}", path.display()))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temporaries_of_dead_processes_go_and_live_ones_stay() {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path().join(TEMPORARIES);
        // a pid far above any pid_max is not running
        let dead = root.join(format!("{}-4000000000", host()));
        let other_host = root.join("some-other-host-1");
        for d in [&dead, &other_host] {
            std::fs::create_dir_all(d).unwrap();
            std::fs::write(d.join(".tmpAbCd"), b"partial").unwrap();
        }
        write_atomic(&dir.path().join("a.csv"), b"x,y\n").unwrap();
        assert_eq!(remove_stale_temporaries(dir.path()).unwrap(), 1);
        assert!(!dead.exists());
        assert!(
            other_host.exists(),
            "another host's shard may still be writing"
        );
        remove_own_temporaries(dir.path());
        assert!(!own_temporaries(dir.path()).exists());
        assert_eq!(std::fs::read(dir.path().join("a.csv")).unwrap(), b"x,y\n");
    }
}
