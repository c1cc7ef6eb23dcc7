//! Issue #9 (2): a run killed at any moment (a real SIGKILL of the child process) leaves no
//! partial or temporary file beside its outputs, and the next run removes the temporaries the
//! killed one left in `.wavy-tmp/`.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Instant;

fn wavy(dir: &Path) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_wavy"));
    c.args(["run", "big.toml", "--out", "out", "--cache", "cache"])
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::null());
    c
}

#[test]
fn killed_runs_leave_nothing_partial_and_the_next_run_cleans_up() {
    let dir = tempfile::tempdir().unwrap();
    // Fig. 2 on a 400 × 400 grid: a 6.6 MB CSV, so a kill often lands in a write.
    let spec = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments/fig2_correction_surfaces.toml"),
    )
    .unwrap()
    .replace("count = 21 }", "count = 400 }");
    std::fs::write(dir.path().join("big.toml"), spec).unwrap();
    let out = dir.path().join("out");

    // reference outputs, and how long a whole run takes
    let t = Instant::now();
    assert!(wavy(dir.path()).status().unwrap().success());
    let whole = t.elapsed();
    let reference: Vec<(String, Vec<u8>)> = ["big.svg", "big.csv"]
        .iter()
        .map(|f| (f.to_string(), std::fs::read(out.join(f)).unwrap()))
        .collect();
    std::fs::remove_dir_all(&out).unwrap();

    let kills = 40;
    let mut left_temporaries = 0;
    for i in 0..kills {
        let mut child = wavy(dir.path()).spawn().unwrap();
        std::thread::sleep(whole.mul_f64(1.2 * i as f64 / kills as f64));
        let _ = child.kill(); // SIGKILL
        let _ = child.wait();
        let Ok(entries) = std::fs::read_dir(&out) else {
            continue; // killed before the output folder existed
        };
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            if name == ".wavy-tmp" {
                let n = walk_files(&e.path());
                left_temporaries += usize::from(n > 0);
                continue;
            }
            let (_, bytes) = reference
                .iter()
                .find(|(f, _)| *f == name)
                .unwrap_or_else(|| panic!("kill {i}: unexpected file {name} beside the outputs"));
            assert_eq!(
                &std::fs::read(e.path()).unwrap(),
                bytes,
                "kill {i}: {name} is partial"
            );
        }
    }
    println!(
        "{kills} runs killed (SIGKILL) at 0–120 % of a whole run ({whole:?}); {left_temporaries} left temporaries in .wavy-tmp/"
    );
    // the next run removes what the killed ones left, and its own temporaries
    assert!(wavy(dir.path()).status().unwrap().success());
    assert!(
        !out.join(".wavy-tmp").exists(),
        "{:?}",
        std::fs::read_dir(out.join(".wavy-tmp")).map(|d| d.count())
    );
    for (f, bytes) in &reference {
        assert_eq!(&std::fs::read(out.join(f)).unwrap(), bytes);
    }
}

fn walk_files(dir: &Path) -> usize {
    std::fs::read_dir(dir).map_or(0, |d| {
        d.flatten()
            .map(|e| {
                if e.path().is_dir() {
                    walk_files(&e.path())
                } else {
                    1
                }
            })
            .sum()
    })
}

#[test]
fn a_rerun_cleans_up_after_a_kill_in_the_cache_folder_too() {
    // a killed sweep's temporaries sit in the cache folder's .wavy-tmp/; the next sweep
    // (any spec with FE cases) removes them. Simulate the leftover of a dead process.
    let dir = tempfile::tempdir().unwrap();
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname")
        .map(|h| h.trim().to_string())
        .unwrap_or_else(|_| "localhost".into());
    let stale = dir
        .path()
        .join("cache/.wavy-tmp")
        .join(format!("{host}-4000000000"));
    std::fs::create_dir_all(&stale).unwrap();
    std::fs::write(stale.join(".tmpXYZ"), b"half a curve").unwrap();
    let spec = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments/fig3_fe_vs_model.toml"),
    )
    .unwrap()
    .replace("aspect_ratios = [0.1, 0.18, 0.3]", "aspect_ratios = [0.1]")
    .replace(
        "tau_max_mpa = [0.0, 0.01, 0.05, 0.1, 0.15, 0.2]  # every panel",
        "tau_max_mpa = [0.0]  # one panel",
    )
    .replace("[fe_vs_model.fe]", "[fe_vs_model.fe]\nmesh = \"16\"")
    .replace("until_a_over_lambda = 0.45", "until_a_over_lambda = 0.2");
    std::fs::write(dir.path().join("big.toml"), spec).unwrap();
    let status = wavy(dir.path()).status().unwrap();
    assert!(status.success());
    assert!(!dir.path().join("cache/.wavy-tmp").exists());
}
