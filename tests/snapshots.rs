//! Pins every experiment's numbers and figure: one snapshot per spec for each CSV table (numbers
//! through the shared six-significant-digit formatter, `wavy::numfmt`) and one for its SVG.
//! A snapshot only says "did our output change?"; review changes with `cargo insta review`.

#[test]
fn experiment_outputs() {
    insta::glob!("../experiments", "*.toml", |path| {
        let out = wavy::runner::run_spec_file(path, &Default::default())
            .unwrap_or_else(|e| panic!("{}: {e:#}", path.display()));
        for table in &out.tables {
            let name = if table.name.is_empty() {
                "csv".to_string()
            } else {
                format!("csv_{}", table.name)
            };
            insta::assert_snapshot!(name, table.to_csv());
        }
        insta::assert_snapshot!("svg", out.svg);
    });
}

#[test]
fn outputs_are_byte_identical_across_runs() {
    let spec =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments/fig5_warman_ennos.toml");
    let a = wavy::runner::run_spec_file(&spec, &Default::default()).unwrap();
    let b = wavy::runner::run_spec_file(&spec, &Default::default()).unwrap();
    assert_eq!(a.svg, b.svg);
    assert_eq!(a.tables, b.tables);
}
