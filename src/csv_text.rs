//! A CSV table as text cells, read by column name: how the committed speed–accuracy
//! measurements and the tables `wavy diff` compares are read (the measured data points and the
//! tier timings still read their files with `csv::Reader` directly). Parses text; no I/O.

/// A CSV table as text cells.
#[derive(Debug, Clone, PartialEq)]
pub struct CsvTable {
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

impl CsvTable {
    /// Parses CSV text (header first).
    pub fn parse(text: &str) -> Result<CsvTable, csv::Error> {
        let mut r = csv::ReaderBuilder::new()
            .has_headers(true)
            .from_reader(text.as_bytes());
        let header = r.headers()?.iter().map(String::from).collect();
        let rows = r
            .records()
            .map(|rec| rec.map(|r| r.iter().map(String::from).collect()))
            .collect::<Result<_, _>>()?;
        Ok(CsvTable { header, rows })
    }

    /// The index of column `name`.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    /// The cell of row `row` (0-based, after the header) in column `name`.
    pub fn cell(&self, row: usize, name: &str) -> Option<&str> {
        self.rows
            .get(row)?
            .get(self.column(name)?)
            .map(String::as_str)
    }
}
