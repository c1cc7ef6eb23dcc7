//! The `wavy` binary driven as a user would with spec files: `run`, `reproduce` and `check`
//! on bad specs, bad data files, unwritable targets and incomplete FE curves, with the message
//! text checked and nothing written.

use crate::common::{here, stderr, stdout, wavy};
use std::path::Path;
use std::process::Command;

/// Writes a variant of a committed spec into a temporary folder, runs it, and checks the
/// message and that no output appeared.
fn bad_spec(source: &str, from: &str, to: &str, expected: &[&str]) {
    let text = std::fs::read_to_string(here().join("experiments").join(source)).unwrap();
    assert!(text.contains(from), "{source} no longer contains `{from}`");
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("bad.toml"), text.replacen(from, to, 1)).unwrap();
    let o = wavy(&["run", "bad.toml", "--out", "out"], dir.path());
    assert_eq!(o.status.code(), Some(2), "exit code for {to}");
    let err = stderr(&o);
    for part in expected {
        assert!(
            err.contains(part),
            "message for `{to}` lacks `{part}`:\n{err}"
        );
    }
    assert!(
        !dir.path().join("out").exists(),
        "bad input must write nothing"
    );
}

#[test]
fn spec_with_unknown_field_names_it_with_line_and_column() {
    bad_spec(
        "fig2_correction_surfaces.toml",
        "title =",
        "colour = \"red\"\ntitle =",
        &["bad.toml", "unknown field `colour`", "line 2, column 1"],
    );
}

#[test]
fn spec_with_wrong_type_names_field_and_type() {
    bad_spec(
        "fig3_fe_vs_model.toml",
        "count = 101",
        "count = \"many\"",
        &[
            "bad.toml",
            "fe_vs_model.a_over_lambda.count",
            "invalid type: string \"many\", expected usize",
            "line 7",
        ],
    );
}

#[test]
fn spec_with_missing_field_names_it() {
    bad_spec(
        "fig3_fe_vs_model.toml",
        "draw = [\"westergaard\", \"wnl\"]",
        "",
        &["bad.toml", "fe_vs_model.models", "missing field `draw`"],
    );
    bad_spec(
        "fig5_warman_ennos.toml",
        "amplitude_mm = 0.04",
        "",
        &["bad.toml", "fingertip_area", "missing field `amplitude_mm`"],
    );
}

#[test]
fn spec_values_out_of_physical_range_name_field_value_and_range() {
    // λ ≤ 0
    bad_spec(
        "fig5_warman_ennos.toml",
        "wavelength_mm = 0.5",
        "wavelength_mm = -0.5",
        &[
            "bad.toml",
            "fingertip_area.wavelength_mm",
            "line 5, column 17",
            "value -0.5 is out of range; allowed: > 0",
        ],
    );
    // AR < 0
    bad_spec(
        "fig3_fe_vs_model.toml",
        "aspect_ratios = [0.1,",
        "aspect_ratios = [-0.1,",
        &[
            "fe_vs_model.aspect_ratios[0]",
            "value -0.1 is out of range; allowed: > 0",
        ],
    );
    // E* ≤ 0
    bad_spec(
        "fig5_warman_ennos.toml",
        "estar_mpa = 0.15",
        "estar_mpa = 0",
        &[
            "fingertip_area.estar_mpa",
            "value 0 is out of range; allowed: > 0",
        ],
    );
    // τ_max < 0
    bad_spec(
        "fig5_warman_ennos.toml",
        "tau_max_mpa = 0.05",
        "tau_max_mpa = -0.05",
        &[
            "fingertip_area.tau_max_mpa",
            "value -0.05 is out of range; allowed: >= 0",
        ],
    );
    bad_spec(
        "fig3_fe_vs_model.toml",
        "tau_max_mpa = [0.0,",
        "tau_max_mpa = [-0.01,",
        &["fe_vs_model.tau_max_mpa[0]", "allowed: >= 0"],
    );
    // a/λ ∉ [0, 0.5]
    bad_spec(
        "fig3_fe_vs_model.toml",
        "max = 0.5, count",
        "max = 0.6, count",
        &[
            "fe_vs_model.a_over_lambda.max",
            "(line 7, column 36)",
            "value 0.6 is out of range; allowed: [0, 0.5]",
        ],
    );
    // a Richardson tier's meshes are tiers (its time is theirs), coarse before fine
    bad_spec(
        "speed_accuracy.toml",
        "\"fe-richardson-48-96\"",
        "\"fe-richardson-48-128\"",
        &[
            "speed_accuracy.tiers[11]",
            "fe-finite-48 and fe-finite-128 among the tiers too",
        ],
    );
    bad_spec(
        "speed_accuracy.toml",
        "\"fe-richardson-48-96\"",
        "\"fe-richardson-96-48\"",
        &[
            "speed_accuracy.tiers",
            "value \"fe-richardson-96-48\" is not a tier",
        ],
    );
}

#[test]
fn reproduce_with_one_bad_spec_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let exp = dir.path().join("experiments");
    std::fs::create_dir(&exp).unwrap();
    for f in ["fig2_correction_surfaces.toml", "fig3_fe_vs_model.toml"] {
        std::fs::copy(here().join("experiments").join(f), exp.join(f)).unwrap();
    }
    let bad = std::fs::read_to_string(exp.join("fig3_fe_vs_model.toml"))
        .unwrap()
        .replace("count = 101", "count = 1");
    std::fs::write(exp.join("fig3_fe_vs_model.toml"), bad).unwrap();
    let o = wavy(&["reproduce"], dir.path());
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("fe_vs_model.a_over_lambda.count"),
        "{}",
        stderr(&o)
    );
    assert!(
        stderr(&o).contains("value 1 is out of range; allowed: [2, 100000]"),
        "{}",
        stderr(&o)
    );
    assert!(
        !dir.path().join("figures").exists(),
        "no figure of the good spec either"
    );
}

/// A spec in a scratch folder, with the given text (or bytes) under `name`.
fn scratch_spec(name: &std::ffi::OsStr, bytes: &[u8]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join(name), bytes).unwrap();
    dir
}

fn fig5_text() -> String {
    std::fs::read_to_string(here().join("experiments/fig5_warman_ennos.toml")).unwrap()
}

/// Issue #9 (6, 7): bad spec files and data files are input errors (exit 2) that say where,
/// in a message of bounded size, and nothing is written.
#[test]
fn bad_spec_and_data_files_exit_2_with_bounded_messages() {
    use std::os::unix::ffi::OsStrExt;
    let run = |dir: &Path, spec: &std::ffi::OsStr| {
        let o = Command::new(env!("CARGO_BIN_EXE_wavy"))
            .arg("run")
            .arg(spec)
            .args(["--out", "out"])
            .current_dir(dir)
            .output()
            .unwrap();
        assert!(!dir.join("out").exists(), "nothing written");
        o
    };
    // a 10⁶-element array with one bad value
    let text = std::fs::read_to_string(here().join("experiments/fig3_fe_vs_model.toml"))
        .unwrap()
        .replacen(
            "aspect_ratios = [0.1, 0.18, 0.3]",
            &format!("aspect_ratios = [{}-0.5]", "0.1,".repeat(1_000_000)),
            1,
        );
    let name = std::ffi::OsStr::new("big.toml");
    let d = scratch_spec(name, text.as_bytes());
    let o = run(d.path(), name);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).len() < 4000, "{} bytes", stderr(&o).len());
    assert!(
        stderr(&o).contains("big.toml: field `fe_vs_model.aspect_ratios[1000000]`"),
        "{}",
        stderr(&o)
    );
    // invalid UTF-8, named by byte, line and column
    let mut bytes = fig5_text().into_bytes();
    let at = bytes.iter().position(|&b| b == b'\n').unwrap() + 1;
    bytes.insert(at, 0xff);
    let name = std::ffi::OsStr::new("latin.toml");
    let d = scratch_spec(name, &bytes);
    let o = run(d.path(), name);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains(&format!("not valid UTF-8 at byte {at} (line 2, column 1)")),
        "{}",
        stderr(&o)
    );
    // a spec whose name is not UTF-8
    let name = std::ffi::OsStr::from_bytes(b"fig\xff.toml");
    let d = scratch_spec(name, fig5_text().as_bytes());
    let o = run(d.path(), name);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("file name is not valid UTF-8"),
        "{}",
        stderr(&o)
    );
    // a measured-data file without provenance, and a folder in its place
    let name = std::ffi::OsStr::new("fig5.toml");
    let d = scratch_spec(name, fig5_text().as_bytes());
    std::fs::create_dir(d.path().join("data")).unwrap();
    std::fs::write(
        d.path().join("data/warman_ennos_2009.csv"),
        "load_n,area_mm2\n1,2\n",
    )
    .unwrap();
    let o = run(d.path(), name);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("cannot use the data file"),
        "{}",
        stderr(&o)
    );
    assert!(stderr(&o).contains("provenance"), "{}", stderr(&o));
    std::fs::remove_file(d.path().join("data/warman_ennos_2009.csv")).unwrap();
    std::fs::create_dir(d.path().join("data/warman_ennos_2009.csv")).unwrap();
    let o = run(d.path(), name);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("cannot use the data file"),
        "{}",
        stderr(&o)
    );
}

/// Issue #9 (7): every output target is checked before the first is written: a folder in
/// place of the CSV leaves the SVG as it was.
#[test]
fn an_unwritable_target_leaves_every_output_as_it_was() {
    let name = std::ffi::OsStr::new("fig5.toml");
    let d = scratch_spec(name, fig5_text().as_bytes());
    let out = d.path().join("out");
    std::fs::create_dir_all(out.join("fig5.csv")).unwrap();
    std::fs::write(out.join("fig5.svg"), "old").unwrap();
    let o = wavy(&["run", "fig5.toml", "--out", "out"], d.path());
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("a folder is in its place"),
        "{}",
        stderr(&o)
    );
    assert_eq!(
        std::fs::read_to_string(out.join("fig5.svg")).unwrap(),
        "old"
    );
}

/// Issue #9 (1): a scene whose FE curve stops short of its target says so in the CSV, on the
/// figure and in the run's output, exits 1, and `wavy check` fails on it.
#[test]
fn an_incomplete_fe_curve_is_marked_and_fails_run_and_check() {
    let text = std::fs::read_to_string(here().join("experiments/fig3_fe_vs_model.toml"))
        .unwrap()
        .replace("aspect_ratios = [0.1, 0.18, 0.3]", "aspect_ratios = [0.1]")
        .replace(
            "tau_max_mpa = [0.0, 0.01, 0.05, 0.1, 0.15, 0.2]",
            "tau_max_mpa = [0.0]",
        )
        // the contact is complete at a/λ = 0.435, the edge rule's place in the valley element
        .replace("[fe_vs_model.fe]", "[fe_vs_model.fe]\nmesh = \"4\"");
    let d = tempfile::tempdir().unwrap();
    std::fs::create_dir(d.path().join("experiments")).unwrap();
    std::fs::write(d.path().join("experiments/coarse.toml"), text).unwrap();
    let o = wavy(
        &[
            "run",
            "experiments/coarse.toml",
            "--out",
            "out",
            "--cache",
            "cache",
        ],
        d.path(),
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("stopped short of their target"),
        "{}",
        stderr(&o)
    );
    assert!(stdout(&o).contains("INCOMPLETE (coarse)"), "{}", stdout(&o));
    let mse = std::fs::read_to_string(d.path().join("out/coarse_mse.csv")).unwrap();
    assert!(
        mse.contains("incomplete: the contact is complete at a/λ = 0.4354"),
        "{mse}"
    );
    let svg = std::fs::read_to_string(d.path().join("out/coarse.svg")).unwrap();
    assert!(svg.contains("INCOMPLETE"));
    let o = wavy(
        &["check", "--expected", "out", "--cache", "cache"],
        d.path(),
    );
    assert_eq!(o.status.code(), Some(1), "{}", stdout(&o));
    assert!(
        stdout(&o).contains("FAIL coarse: incomplete finite-element curve"),
        "{}",
        stdout(&o)
    );
}

/// A single-case FE scene takes `aspect_ratio` or `profile`, exactly one; a profile is refused
/// with a tolerance, and where the mesh cannot resolve it, naming the harmonic; a profile may be
/// the command line's text, a Weierstrass profile too.
#[test]
fn a_surface_is_an_aspect_ratio_or_a_profile() {
    bad_spec(
        "deformed_mesh_ar030.toml",
        "aspect_ratio = 0.3",
        "aspect_ratio = 0.3\nprofile = [[1, 0.1], [8, 0.05]]",
        &[
            "deformed_mesh.aspect_ratio",
            "both of aspect_ratio and profile",
            "exactly one",
        ],
    );
    bad_spec(
        "deformed_mesh_ar030.toml",
        "aspect_ratio = 0.3",
        "",
        &[
            "deformed_mesh.aspect_ratio",
            "neither of aspect_ratio and profile",
        ],
    );
    bad_spec(
        "deformed_mesh_ar030.toml",
        "aspect_ratio = 0.3\n\n[deformed_mesh.fe]",
        "profile = [[1, 0.1], [4, 0.05]]\n\n[deformed_mesh.fe]\ntolerance = 0.005",
        &["deformed_mesh.fe.tolerance", "absent with a profile"],
    );
    bad_spec(
        "deformed_mesh_ar030.toml",
        "aspect_ratio = 0.3",
        "profile = [[1, 0.1], [64, 0.05]]",
        &["deformed_mesh.profile", "harmonic 64"],
    );
    bad_spec(
        "hysteresis.toml",
        "confinement = { aspect_ratio = 0.3,",
        "confinement = { profile = [[2, 0.1]],",
        &["hysteresis.confinement.profile", "order 2"],
    );
    // the command line's text, a Weierstrass profile among them: its harmonics are checked as
    // the pairs are (γ 3, K 3: harmonic 9 is beyond the default mesh's coarsest elements)
    bad_spec(
        "deformed_mesh_ar030.toml",
        "aspect_ratio = 0.3",
        "profile = \"weierstrass:0.05,3,1.3,3\"",
        &[
            "deformed_mesh.profile",
            "weierstrass:0.05,3,1.3,3",
            "harmonic 9",
        ],
    );
    bad_spec(
        "deformed_mesh_ar030.toml",
        "aspect_ratio = 0.3",
        "profile = \"weierstrass:0.05,3\"",
        &["deformed_mesh.profile", "weierstrass"],
    );
    bad_spec(
        "deformed_mesh_ar030.toml",
        "aspect_ratio = 0.3",
        "profile = 5",
        &[
            "profile",
            "a list of [order, aspect ratio] pairs, or a profile text",
        ],
    );
}

/// The deformed-mesh scene of a two-scale profile: the FE solve reaches the target with the
/// contact in patches, and the figure names the profile.
#[test]
fn the_deformed_mesh_of_a_profile() {
    let text = std::fs::read_to_string(here().join("experiments/deformed_mesh_ar030.toml"))
        .unwrap()
        .replace("aspect_ratio = 0.3", "profile = [[1, 0.1], [4, 0.1]]")
        // the crests at x = 0 and λ/4 in contact, not yet merged (they merge near a/λ = 0.29)
        .replace("until_a_over_lambda = 0.45", "until_a_over_lambda = 0.26");
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("profile.toml"), text).unwrap();
    let o = wavy(
        &["run", "profile.toml", "--out", "out", "--cache", "cache"],
        d.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let svg = std::fs::read_to_string(d.path().join("out/profile.svg")).unwrap();
    assert!(
        svg.contains("profile 1:0.1,4:0.1"),
        "the figure names the profile"
    );
    let csv = std::fs::read_to_string(d.path().join("out/profile.csv")).unwrap();
    // the face nodes in contact: more than one run of them
    let in_contact: Vec<bool> = csv
        .lines()
        .skip_while(|l| !l.starts_with("node,"))
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap().parse::<f64>().unwrap() > 0.0)
        .collect();
    let patches =
        in_contact.windows(2).filter(|w| w[1] && !w[0]).count() + usize::from(in_contact[0]);
    assert_eq!(patches, 2, "patches of the face nodes in contact");
}
