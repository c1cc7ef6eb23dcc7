//! `wavy check` must catch a regression: a recomputed table that drifts from its golden file.

use wavy::runner::run_spec_file;

fn fig2() -> wavy::table::Table {
    let spec = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("experiments/fig2_correction_surfaces.toml");
    run_spec_file(&spec, &Default::default())
        .unwrap()
        .tables
        .remove(0)
}

#[test]
fn identical_golden_passes() {
    let t = fig2();
    let c = t.compare(&t.to_csv(), 1e-5, 0.0).unwrap();
    assert_eq!(c.failures, 0);
    assert!(c.numbers > 400);
}

#[test]
fn a_drifted_number_fails_and_is_listed_first() {
    let t = fig2();
    let golden = t.to_csv();
    // Row 3 of the data, column correction_b: 1.09848 in the golden file; make it 1.1 (1.4 % off).
    let line = golden.lines().nth(3).unwrap().to_string();
    let drifted_line = line.replace(",1.09848,", ",1.1,");
    assert_ne!(
        line, drifted_line,
        "the golden row changed: update this test's literal"
    );
    let drifted = golden.replacen(&line, &drifted_line, 1);
    let c = t.compare(&drifted, 1e-5, 0.0).unwrap();
    assert_eq!(c.failures, 1);
    let worst = &c.deviations[0];
    assert_eq!(
        (worst.row, worst.column.as_str(), worst.pass),
        (3, "correction_b", false)
    );
    assert!((worst.relative - (1.1 - 1.09848) / 1.1).abs() < 1e-6);
}

#[test]
fn changed_columns_or_rows_are_errors() {
    let t = fig2();
    let golden = t.to_csv();
    let renamed = golden.replacen("correction_b", "correction_c", 1);
    assert!(t.compare(&renamed, 1e-5, 0.0).is_err());
    let shorter: String = golden.lines().take(10).map(|l| format!("{l}\n")).collect();
    assert!(t.compare(&shorter, 1e-5, 0.0).is_err());
}
