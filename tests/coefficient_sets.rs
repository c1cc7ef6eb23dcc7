//! The refit coefficient sets in `src/coefficient_sets.rs` are the golden refit of
//! `expected/table1_refit.csv` (written by `experiments/table1_refit.toml`, six significant
//! digits), and the paper's set is Table 1 (docs/replication.md R5).
use wavy::models::CoefficientSet;

#[test]
fn refit_sets_equal_the_golden_refit_table() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/expected/table1_refit.csv");
    let mut reader = csv::Reader::from_path(path).expect("expected/table1_refit.csv");
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let mut checked = 0;
    for record in reader.records() {
        let record = record.unwrap();
        let name = &record[0];
        let (letter, i) = name.split_at(1);
        let i: usize = i.parse().unwrap();
        for (col, value) in header.iter().zip(record.iter()).skip(1) {
            let set = match col.as_str() {
                "paper" => "paper-table1".to_string(),
                c => c.replace('_', "-"),
            };
            let c = set
                .parse::<CoefficientSet>()
                .unwrap_or_else(|e| panic!("{e}"))
                .coefficients();
            let ours = if letter == "a" { c.a[i] } else { c.b[i] };
            let golden: f64 = value.parse().unwrap();
            // six significant digits in the file
            assert!(
                (ours - golden).abs() <= 5e-6 * golden.abs(),
                "{set} {name}: constant {ours} vs golden {golden}"
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 12 * 4);
}
