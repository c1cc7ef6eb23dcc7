//! Unit tests of [`crate::runner::review`]: panels, their changes and the summary.

use crate::runner::review::*;

const BASE: &str = "aspect_ratio,tau_max_mpa,a_over_lambda,p_over_estar_wnl,wnl_extrapolated\n\
    0.1,0,0,0,false\n0.1,0,0.25,0.1,false\n0.1,0,0.5,0.3,false\n\
    0.3,0.2,0,0,false\n0.3,0.2,0.25,0.5,false\n0.3,0.2,0.5,0.9,false\n";

#[test]
fn a_known_change_is_named_by_its_panel_and_size() {
    let new = BASE.replace("0.3,0.2,0.25,0.5,", "0.3,0.2,0.25,0.55,");
    let (b, n) = (
        CsvTable::parse(BASE).unwrap(),
        CsvTable::parse(&new).unwrap(),
    );
    let c = compare("fig.csv", &b, &n, 1e-5, 1e-9);
    assert_eq!(c.roles.x.as_deref(), Some("a_over_lambda"));
    assert_eq!(c.roles.keys, ["aspect_ratio", "tau_max_mpa"]);
    let moved: Vec<&PanelChange> = c.panels.iter().filter(|p| p.moved()).collect();
    assert_eq!(moved.len(), 1);
    assert_eq!(moved[0].panel, "aspect_ratio 0.3, tau_max_mpa 0.2");
    let col = &moved[0].columns[0];
    assert_eq!(col.column, "p_over_estar_wnl");
    assert!((col.max_abs - 0.05).abs() < 1e-12 && (col.max_rel - 0.1).abs() < 1e-12);
    let md = summary("fig", std::slice::from_ref(&c), &[]);
    assert!(
        md.contains(
            "| aspect_ratio 0.3, tau_max_mpa 0.2 **moved** | p_over_estar_wnl | 0.05 | 0.1 |"
        ),
        "{md}"
    );
    let fig = overlay("fig", &[("fig.csv".into(), b, n, c)]).unwrap();
    assert_eq!(fig.panels.len(), 2);
    assert_eq!(fig.panels[1].series.len(), 2);
}

#[test]
fn loops_that_share_an_aspect_ratio_are_panels_of_their_own() {
    // two loops at one aspect ratio, each a loading and an unloading branch; the last digit
    // of one point moves: that loop's branch alone changed, and no key column reads as moved
    let base = "series,aspect_ratio,tau_max_over_estar,thickness_over_lambda,branch,a_over_lambda,p_over_estar\n\
        aspect_ratio,0.1,0,1,loading,0.1,0.01\naspect_ratio,0.1,0,1,loading,0.2,0.04\n\
        aspect_ratio,0.1,0,1,unloading,0.2,0.04\naspect_ratio,0.1,0,1,unloading,0.1,0.01\n\
        aspect_ratio,0.1,0.2,1,loading,0.1,0.02\naspect_ratio,0.1,0.2,1,loading,0.2,0.05\n\
        aspect_ratio,0.1,0.2,1,unloading,0.2,0.05\naspect_ratio,0.1,0.2,1,unloading,0.15,0\n";
    let new = base.replace("unloading,0.15,0\n", "unloading,0.15,1e-16\n");
    let (b, n) = (
        CsvTable::parse(base).unwrap(),
        CsvTable::parse(&new).unwrap(),
    );
    let c = compare("hysteresis.csv", &b, &n, 1e-5, 1e-6);
    assert_eq!(c.panels.len(), 4);
    let changed: Vec<&PanelChange> = (c.panels.iter())
        .filter(|p| p.columns.iter().any(|col| col.max_abs > 0.0))
        .collect();
    assert_eq!(changed.len(), 1);
    assert_eq!(
        changed[0].panel,
        "series aspect_ratio, aspect_ratio 0.1, tau_max_over_estar 0.2, thickness_over_lambda 1, branch unloading"
    );
    assert!(!c.moved());
}

#[test]
fn curves_are_compared_at_the_same_abscissa() {
    // the new curve's points moved along x: the base is interpolated to them
    let base = CsvTable::parse("a_over_lambda,p\n0,0\n1,1\n").unwrap();
    let new = CsvTable::parse("a_over_lambda,p\n0.5,0.5\n").unwrap();
    let c = compare("t.csv", &base, &new, 1e-5, 0.0);
    assert!(!c.moved() || c.panels[0].rows_removed == 1);
    assert_eq!(c.panels[0].columns[0].max_abs, 0.0);
}

#[test]
fn within_tolerance_is_not_moved() {
    let new = BASE.replace("0.3,0.2,0.25,0.5,", "0.3,0.2,0.25,0.500001,");
    let c = compare(
        "fig.csv",
        &CsvTable::parse(BASE).unwrap(),
        &CsvTable::parse(&new).unwrap(),
        1e-5,
        0.0,
    );
    assert!(!c.moved());
    assert!(c
        .panels
        .iter()
        .any(|p| p.columns.iter().any(|c| c.max_abs > 0.0)));
}
