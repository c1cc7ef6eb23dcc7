//! Measured load–area points with their provenance (schema: `experiments/data/README.md`).
//!
//! A data file starts with `# key: value` lines that must name `source`, `source_figure`,
//! `digitised_by` and `method`, followed by CSV with the header `load_n,area_mm2`.

use anyhow::{bail, Context, Result};
use std::path::Path;

/// Keys every data file must state.
pub const REQUIRED_PROVENANCE: [&str; 4] = ["source", "source_figure", "digitised_by", "method"];

/// Points and where they come from.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredPoints {
    /// (key, value) provenance lines, in file order.
    pub provenance: Vec<(String, String)>,
    /// (load in N, area in mm²).
    pub points: Vec<(f64, f64)>,
}

impl MeasuredPoints {
    pub fn provenance(&self, key: &str) -> Option<&str> {
        self.provenance
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }
}

/// Reads a data file; `Ok(None)` when there is no file at `path` (errors do not repeat the path).
pub fn read(path: &Path) -> Result<Option<MeasuredPoints>> {
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(e.into()),
    };
    parse(&text).map(Some)
}

/// Splits the text of a measured-data file into its `# key: value` provenance lines and the
/// CSV body, and checks that every key of `required` has a value.
pub fn split_provenance(text: &str, required: &[&str]) -> Result<(Vec<(String, String)>, String)> {
    let mut provenance = vec![];
    let mut body = String::new();
    for line in text.lines() {
        if let Some(rest) = line.strip_prefix('#') {
            if let Some((k, v)) = rest.split_once(':') {
                provenance.push((k.trim().to_string(), v.trim().to_string()));
            }
        } else {
            body.push_str(line);
            body.push('\n');
        }
    }
    for key in required {
        if !provenance.iter().any(|(k, v)| k == key && !v.is_empty()) {
            bail!(
                "provenance line `# {key}: …` is missing; required: {}",
                required.join(", ")
            );
        }
    }
    Ok((provenance, body))
}

/// Parses the text of a data file.
pub fn parse(text: &str) -> Result<MeasuredPoints> {
    let (provenance, body) = split_provenance(text, &REQUIRED_PROVENANCE)?;
    let mut r = csv::Reader::from_reader(body.as_bytes());
    let header: Vec<String> = r.headers()?.iter().map(String::from).collect();
    if header != ["load_n", "area_mm2"] {
        bail!(
            "header is `{}`; expected `load_n,area_mm2`",
            header.join(",")
        );
    }
    let mut points = vec![];
    for (i, rec) in r.records().enumerate() {
        let rec = rec?;
        let value = |j: usize, name: &str| -> Result<f64> {
            let v: f64 = rec[j]
                .trim()
                .parse()
                .with_context(|| format!("data row {}: `{name}` is not a number", i + 1))?;
            if !(v.is_finite() && v >= 0.0) {
                bail!(
                    "data row {}: `{name}` = {v} is out of range; allowed: >= 0",
                    i + 1
                );
            }
            Ok(v)
        };
        points.push((value(0, "load_n")?, value(1, "area_mm2")?));
    }
    if points.is_empty() {
        bail!("the file holds no data rows");
    }
    Ok(MeasuredPoints { provenance, points })
}

#[cfg(test)]
mod tests {
    use super::*;

    // Parser fixtures only: these numbers are not measurements and never reach a figure.
    const HEAD: &str = "# source: fixture\n# source_figure: none\n# digitised_by: nobody\n# method: typed for a parser test\n";

    #[test]
    fn reads_provenance_and_points() {
        let m = parse(&format!("{HEAD}load_n,area_mm2\n1,2\n3.5,4\n")).unwrap();
        assert_eq!(m.points, vec![(1.0, 2.0), (3.5, 4.0)]);
        assert_eq!(m.provenance("digitised_by"), Some("nobody"));
    }

    #[test]
    fn refuses_missing_provenance_wrong_header_and_bad_values() {
        let e = parse("# source: x\nload_n,area_mm2\n1,2\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("`# source_figure: …` is missing"), "{e}");
        let e = parse(&format!("{HEAD}force,area\n1,2\n"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("expected `load_n,area_mm2`"), "{e}");
        let e = format!(
            "{:#}",
            parse(&format!("{HEAD}load_n,area_mm2\n1,-2\n")).unwrap_err()
        );
        assert!(
            e.contains("data row 1: `area_mm2` = -2 is out of range; allowed: >= 0"),
            "{e}"
        );
        let e = parse(&format!("{HEAD}load_n,area_mm2\n"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("no data rows"), "{e}");
    }
}
