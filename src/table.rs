//! The tables behind every figure, their CSV text, and their comparison with golden files.

use crate::numfmt;
use std::fmt;
use thiserror::Error;

/// One cell: a number (written through [`numfmt::sig`]), a word, or nothing.
#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    Num(f64),
    Text(String),
    Empty,
}

impl From<f64> for Cell {
    fn from(x: f64) -> Self {
        Cell::Num(x)
    }
}
impl From<&str> for Cell {
    fn from(s: &str) -> Self {
        Cell::Text(s.into())
    }
}
impl From<String> for Cell {
    fn from(s: String) -> Self {
        Cell::Text(s)
    }
}
impl From<bool> for Cell {
    fn from(b: bool) -> Self {
        Cell::Text(if b { "true" } else { "false" }.into())
    }
}
impl From<Option<f64>> for Cell {
    fn from(x: Option<f64>) -> Self {
        x.map_or(Cell::Empty, Cell::Num)
    }
}

impl fmt::Display for Cell {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Cell::Num(x) => f.write_str(&numfmt::sig(*x)),
            Cell::Text(s) => f.write_str(s),
            Cell::Empty => Ok(()),
        }
    }
}

/// A named table with a header row.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// File-name suffix: `""` for the scene's main table (`<stem>.csv`), else `<stem>_<name>.csv`.
    pub name: String,
    pub header: Vec<String>,
    pub rows: Vec<Vec<Cell>>,
}

impl Table {
    pub fn new(name: &str, header: &[&str]) -> Self {
        Self {
            name: name.into(),
            header: header.iter().map(|s| s.to_string()).collect(),
            rows: vec![],
        }
    }

    pub fn push(&mut self, row: Vec<Cell>) {
        assert_eq!(
            row.len(),
            self.header.len(),
            "row width must match the header of table `{}`",
            self.name
        );
        self.rows.push(row);
    }

    /// Row `i` (0-based) named by the values of its `keys` columns, e.g.
    /// `aspect_ratio 0.3, tau_max_mpa 0.2`.
    pub fn panel_name(&self, i: usize, keys: &[String]) -> String {
        keys.iter()
            .filter_map(|k| {
                let j = self.header.iter().position(|h| h == k)?;
                Some(format!("{k} {}", self.rows.get(i)?[j]))
            })
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The file name of this table for a scene called `stem`.
    pub fn file_name(&self, stem: &str) -> String {
        if self.name.is_empty() {
            format!("{stem}.csv")
        } else {
            format!("{stem}_{}.csv", self.name)
        }
    }

    /// CSV text: the header, then one line per row, numbers with six significant digits.
    pub fn to_csv(&self) -> String {
        let mut w = csv::WriterBuilder::new()
            .terminator(csv::Terminator::Any(b'\n'))
            .from_writer(vec![]);
        w.write_record(&self.header)
            .expect("writing to memory cannot fail");
        for row in &self.rows {
            w.write_record(row.iter().map(|c| c.to_string()))
                .expect("writing to memory cannot fail");
        }
        String::from_utf8(w.into_inner().expect("flushing memory cannot fail"))
            .expect("CSV of UTF-8 text is UTF-8")
    }

    /// Compares this (freshly computed) table with golden CSV text. Numbers pass when
    /// |new − expected| ≤ abs_tol + rel_tol·|expected|; words and empty cells must match exactly.
    pub fn compare(
        &self,
        expected_csv: &str,
        rel_tol: f64,
        abs_tol: f64,
    ) -> Result<Comparison, CompareError> {
        let expected = self.expected_records(expected_csv)?;
        let mut out = Comparison {
            deviations: vec![],
            failures: 0,
            numbers: 0,
        };
        for (i, (row, rec)) in self.rows.iter().zip(&expected).enumerate() {
            for (j, (cell, want)) in row.iter().zip(rec.iter()).enumerate() {
                let column = self.header[j].clone();
                let deviation = match (cell, want.parse::<f64>()) {
                    (Cell::Num(x), Ok(e)) => {
                        out.numbers += 1;
                        number_deviation(*x, (want, e), (rel_tol, abs_tol), i + 1, column)
                    }
                    _ => {
                        let found = cell.to_string();
                        Deviation {
                            row: i + 1,
                            panel: String::new(),
                            column,
                            pass: found == want,
                            relative: if found == want { 0.0 } else { f64::INFINITY },
                            expected: want.into(),
                            found,
                        }
                    }
                };
                if !deviation.pass {
                    out.failures += 1;
                }
                out.deviations.push(deviation);
            }
        }
        out.deviations.sort_by(|a, b| {
            (a.pass, -a.relative)
                .partial_cmp(&(b.pass, -b.relative))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        Ok(out)
    }

    /// The rows of the golden CSV text, after checking that its header is this table's and that
    /// it has as many rows.
    fn expected_records(&self, expected_csv: &str) -> Result<Vec<csv::StringRecord>, CompareError> {
        let mut r = csv::ReaderBuilder::new()
            .has_headers(true)
            .from_reader(expected_csv.as_bytes());
        let header: Vec<String> = r
            .headers()
            .map_err(|e| CompareError::Malformed(e.to_string()))?
            .iter()
            .map(String::from)
            .collect();
        if header != self.header {
            return Err(CompareError::Header {
                expected: header.join(","),
                found: self.header.join(","),
            });
        }
        let expected: Vec<csv::StringRecord> = r
            .records()
            .collect::<Result<_, _>>()
            .map_err(|e| CompareError::Malformed(e.to_string()))?;
        if expected.len() != self.rows.len() {
            return Err(CompareError::RowCount {
                expected: expected.len(),
                found: self.rows.len(),
            });
        }
        Ok(expected)
    }
}

/// The deviation of the number `found` from the golden cell `(text, value)` in data row `row` of
/// `column`: it passes within `abs_tol + rel_tol·|expected|`, or where both are NaN.
fn number_deviation(
    found: f64,
    (text, expected): (&str, f64),
    (rel_tol, abs_tol): (f64, f64),
    row: usize,
    column: String,
) -> Deviation {
    let abs = (found - expected).abs();
    let allowed = abs_tol + rel_tol * expected.abs();
    let both_nan = found.is_nan() && expected.is_nan();
    Deviation {
        row,
        panel: String::new(),
        column,
        expected: text.into(),
        found: numfmt::sig(found),
        relative: if both_nan {
            0.0
        } else if expected != 0.0 {
            abs / expected.abs()
        } else {
            abs
        },
        pass: both_nan || abs <= allowed,
    }
}

/// One compared cell.
#[derive(Debug, Clone, PartialEq)]
pub struct Deviation {
    /// 1-based data row.
    pub row: usize,
    /// The panel or series the row belongs to, named by its key columns
    /// (`aspect_ratio 0.3, tau_max_mpa 0.2`; empty for a table without keys).
    pub panel: String,
    pub column: String,
    pub expected: String,
    pub found: String,
    /// |new − expected| / |expected| (absolute when expected is 0; ∞ for a changed word).
    pub relative: f64,
    pub pass: bool,
}

/// The cells of a table, failures first, then by decreasing relative deviation.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    pub deviations: Vec<Deviation>,
    pub failures: usize,
    pub numbers: usize,
}

#[derive(Debug, Error, PartialEq)]
pub enum CompareError {
    #[error("expected file is not valid CSV: {0}")]
    Malformed(String),
    #[error("columns differ: expected `{expected}`, computed `{found}`")]
    Header { expected: String, found: String },
    #[error("row counts differ: expected {expected}, computed {found}")]
    RowCount { expected: usize, found: usize },
}
