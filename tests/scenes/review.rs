//! `wavy diff --base REV` on a real git repository: a deliberate change of results names the
//! panels that moved and by how much, draws the overlay, and exits 1; no change exits 0.

use std::path::Path;
use std::process::{Command, Output};

fn run(dir: &Path, program: &str, args: &[&str]) -> Output {
    Command::new(program)
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap_or_else(|e| panic!("{program}: {e}"))
}

fn wavy(dir: &Path, args: &[&str]) -> Output {
    run(dir, env!("CARGO_BIN_EXE_wavy"), args)
}

fn git(dir: &Path, args: &[&str]) {
    let mut all = vec![
        "-c",
        "user.name=wavy test",
        "-c",
        "user.email=test@wavy.invalid",
        "-c",
        "commit.gpgsign=false",
    ];
    all.extend_from_slice(args);
    let o = run(dir, "git", &all);
    assert!(
        o.status.success(),
        "git {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn a_deliberate_change_is_named_by_panel_and_drawn_over_its_base() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::create_dir(d.join("experiments")).unwrap();
    // Fig. 3's model lines (no FE section: fast), committed as the base
    let spec = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments/fig3_fe_vs_model.toml"),
    )
    .unwrap();
    let spec = spec[..spec.find("[fe_vs_model.fe]").unwrap()].to_string()
        + "[check]\nrel_tol = 1e-5\nabs_tol = 1e-6\n";
    std::fs::write(d.join("experiments/fig3.toml"), &spec).unwrap();
    git(d, &["init", "-q"]);
    assert!(wavy(d, &["reproduce"]).status.success());
    git(d, &["add", "experiments", "figures"]);
    git(d, &["commit", "-q", "-m", "base"]);

    // nothing changed: exit 0
    let o = wavy(d, &["diff", "--base", "HEAD"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let md = std::fs::read_to_string(d.join("review/summary.md")).unwrap();
    assert!(md.contains("No figure table differs."), "{md}");

    // a deliberate change: the WNL line with our refit instead of the paper's Table 1
    std::fs::write(
        d.join("experiments/fig3.toml"),
        spec.replace(
            "coefficients = \"paper-table1\"",
            "coefficients = \"ours-bracket-sq\"",
        ),
    )
    .unwrap();
    assert!(wavy(d, &["reproduce"]).status.success());
    let o = wavy(d, &["diff", "--base", "HEAD"]);
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let md = std::fs::read_to_string(d.join("review/summary.md")).unwrap();
    // every panel's WNL column moved, named by its parameters; Westergaard did not
    for panel in [
        "aspect_ratio 0.1, tau_max_mpa 0 **moved**",
        "aspect_ratio 0.3, tau_max_mpa 0.2 **moved**",
    ] {
        assert!(
            md.contains(&format!("| {panel} | p_over_estar_wnl |")),
            "{panel}:\n{md}"
        );
    }
    assert!(!md.contains("p_over_estar_westergaard"), "{md}");
    assert!(
        md.contains("(18 of 18 panels changed; beyond the spec's tolerance: 18)"),
        "{md}"
    );
    let svg = std::fs::read_to_string(d.join("review/fig3.svg")).unwrap();
    assert!(svg.contains("base (grey, dashed)"));
    println!("{md}");
}
