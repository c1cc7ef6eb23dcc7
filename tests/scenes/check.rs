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

/// A spec that omits a physical parameter takes the default from `src/defaults.rs`: the
/// committed FE specs set none of them, so a changed default shows in the figures.
#[test]
fn specs_take_the_physical_defaults_from_one_place() {
    use wavy::runner::sweep::fe_cases::FePhysics;
    let spec = wavy::runner::load_spec(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments/fig3_fe_vs_model.toml"),
    )
    .unwrap();
    let fe = spec.fe_vs_model.as_ref().unwrap().fe.as_ref().unwrap();
    let physics = FePhysics::from(fe);
    let d = wavy::defaults::layer_problem(0.1);
    assert_eq!(physics.estar_mpa, wavy::defaults::fe_estar_mpa());
    assert_eq!(physics.thickness_over_lambda, d.thickness_over_lambda);
    assert_eq!(physics.kappa_over_g, d.kappa_over_g);
    assert_eq!(physics.kinematics, d.kinematics);
    assert_eq!(
        physics.friction_coefficient,
        wavy::defaults::friction_coefficient()
    );
    assert_eq!(
        physics.elastic_slip_over_element,
        wavy::defaults::elastic_slip_over_element()
    );
    assert_eq!(fe.mesh, None);
    assert_eq!(fe.mesh_for(&[0.1]).unwrap(), wavy::fe::MeshLevel::Default);
    for name in ["fig3_fe_vs_model", "table1_refit", "deformed_mesh_ar030"] {
        let text = std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join(format!("experiments/{name}.toml")),
        )
        .unwrap();
        for field in [
            "estar_mpa =",
            "thickness_over_lambda",
            "kappa_over_g",
            "friction_coefficient",
            "mesh =",
            "kinematics",
        ] {
            assert!(
                !text.lines().any(|l| l.starts_with(field)),
                "{name}.toml pins `{field}`: say why in docs/replication.md or let the default apply"
            );
        }
    }
}
