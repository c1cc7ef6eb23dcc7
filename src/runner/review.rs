//! Reviewing a change of results: a figure's CSV tables at a base revision against the working
//! tree, as a summary of what moved per panel and an overlay of the panels (base grey and
//! dashed under the new data). No I/O: the caller reads both versions (`wavy diff` asks git).
//!
//! Tables carry no layout of their own, so the columns are read by role, in one place
//! ([`ColumnRoles`]): the abscissa of a curve (`a_over_lambda`, `load_n`, `x_over_lambda`; else
//! `tau_max_mpa` for the correction surfaces A and B), the keys that name a
//! panel or series (`tier`, `aspect_ratio`, `tau_max_mpa`, `model`, `estar_mpa`, `reading`,
//! `coefficient`), identifiers (`node`), and values (every other column). Values of a curve are
//! compared at the same abscissa, the base interpolated linearly to the new one's points
//! (FE points move along a/λ when the physics changes); values of a table without abscissa
//! are compared row by row within their panel.

use crate::numfmt;
use crate::plot::{padded_range, palette, Figure, LegendPosition, Panel, Series};
use std::collections::BTreeMap;
use std::fmt::Write;

/// Columns that are the abscissa of a curve, in order of preference.
const ABSCISSAE: [&str; 3] = ["a_over_lambda", "load_n", "x_over_lambda"];
/// Columns that name a panel or a series (the hysteresis tables name a loop by its series,
/// shear strength, thickness and branch: several loops share an aspect ratio).
const KEYS: [&str; 11] = [
    "tier",
    "aspect_ratio",
    "tau_max_mpa",
    "model",
    "estar_mpa",
    "reading",
    "coefficient",
    "series",
    "tau_max_over_estar",
    "thickness_over_lambda",
    "branch",
];
/// Columns that identify a row without being a value.
const IDENTIFIERS: [&str; 1] = ["node"];
/// Panels drawn at most in one overlay figure (the ones that moved most).
const MAX_PANELS: usize = 24;

pub use crate::csv_text::CsvTable;

/// How the columns of a table are read ([`review`](self) module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct ColumnRoles {
    pub x: Option<String>,
    pub keys: Vec<String>,
    pub values: Vec<String>,
}

impl ColumnRoles {
    pub fn of(header: &[String]) -> ColumnRoles {
        let has = |c: &str| header.iter().any(|h| h == c);
        let x = ABSCISSAE
            .iter()
            .find(|c| has(c))
            .map(|c| c.to_string())
            .or_else(|| {
                // the correction surfaces A, B are curves against τ_max, one per AR
                (has("correction_a") && has("tau_max_mpa")).then(|| "tau_max_mpa".to_string())
            });
        let keys: Vec<String> = header
            .iter()
            .filter(|h| KEYS.contains(&h.as_str()) && Some(*h) != x.as_ref())
            .cloned()
            .collect();
        let values = header
            .iter()
            .filter(|h| {
                Some(*h) != x.as_ref() && !keys.contains(h) && !IDENTIFIERS.contains(&h.as_str())
            })
            .cloned()
            .collect();
        ColumnRoles { x, keys, values }
    }
}

/// The largest change of one value column within one panel.
#[derive(Debug, Clone, PartialEq)]
pub struct ColumnChange {
    pub column: String,
    pub max_abs: f64,
    pub max_rel: f64,
    /// Outside `abs_tol + rel_tol·|base|` somewhere.
    pub moved: bool,
    /// Old and new value when the panel has one row (e.g. an MSE), for the summary.
    pub single: Option<(String, String)>,
}

/// What changed in one panel (the rows sharing the key values).
#[derive(Debug, Clone, PartialEq)]
pub struct PanelChange {
    /// The key values, e.g. `aspect_ratio 0.3, tau_max_mpa 0.2` (empty for a keyless table).
    pub panel: String,
    pub columns: Vec<ColumnChange>,
    pub rows_added: usize,
    pub rows_removed: usize,
    /// Text cells (status, flags) that differ.
    pub text_changes: Vec<String>,
}

impl PanelChange {
    pub fn moved(&self) -> bool {
        self.rows_added > 0
            || self.rows_removed > 0
            || !self.text_changes.is_empty()
            || self.columns.iter().any(|c| c.moved)
    }

    fn largest_rel(&self) -> f64 {
        self.columns.iter().map(|c| c.max_rel).fold(0.0, f64::max)
    }
}

/// One table compared with its base.
#[derive(Debug, Clone, PartialEq)]
pub struct TableChange {
    pub file: String,
    pub roles: ColumnRoles,
    pub header_changed: Option<(String, String)>,
    pub panels: Vec<PanelChange>,
}

impl TableChange {
    pub fn moved(&self) -> bool {
        self.header_changed.is_some() || self.panels.iter().any(PanelChange::moved)
    }
}

/// Rows of a table grouped by their key values, in first-seen order.
fn panels(t: &CsvTable, keys: &[String]) -> BTreeMap<String, Vec<usize>> {
    let idx: Vec<usize> = keys.iter().filter_map(|k| t.column(k)).collect();
    let mut groups: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for (i, row) in t.rows.iter().enumerate() {
        let name = idx
            .iter()
            .map(|&j| format!("{} {}", t.header[j], row[j]))
            .collect::<Vec<_>>()
            .join(", ");
        groups.entry(name).or_default().push(i);
    }
    groups
}

/// `(x, y)` of column `y` over the rows, numeric cells only, sorted by x.
fn curve(t: &CsvTable, rows: &[usize], x: usize, y: usize) -> Vec<(f64, f64)> {
    let mut pts: Vec<(f64, f64)> = rows
        .iter()
        .filter_map(|&i| Some((t.rows[i][x].parse().ok()?, t.rows[i][y].parse().ok()?)))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts
}

/// Linear interpolation of a sorted curve at `x`; `None` outside its range.
fn interpolate(c: &[(f64, f64)], x: f64) -> Option<f64> {
    let k = c.partition_point(|p| p.0 < x);
    if k < c.len() && c[k].0 == x {
        return Some(c[k].1);
    }
    if k == 0 || k == c.len() {
        return None;
    }
    let (a, b) = (c[k - 1], c[k]);
    Some(a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0))
}

/// Accumulates the largest change of one column.
struct Extremes {
    max_abs: f64,
    max_rel: f64,
    moved: bool,
}

impl Extremes {
    fn new() -> Self {
        Extremes {
            max_abs: 0.0,
            max_rel: 0.0,
            moved: false,
        }
    }
    fn add(&mut self, base: f64, new: f64, rel_tol: f64, abs_tol: f64) {
        let abs = (new - base).abs();
        let same = base == new || (base.is_nan() && new.is_nan());
        if same {
            return;
        }
        self.max_abs = self.max_abs.max(abs);
        self.max_rel = self
            .max_rel
            .max(if base != 0.0 { abs / base.abs() } else { abs });
        // a NaN on one side only is a change too
        let within = abs <= abs_tol + rel_tol * base.abs();
        self.moved |= !within;
    }
}

/// Compares `new` with `base` for the file `file`, with the spec's `[check]` tolerances.
pub fn compare(
    file: &str,
    base: &CsvTable,
    new: &CsvTable,
    rel_tol: f64,
    abs_tol: f64,
) -> TableChange {
    let roles = ColumnRoles::of(&new.header);
    let header_changed =
        (base.header != new.header).then(|| (base.header.join(","), new.header.join(",")));
    let (base_panels, new_panels) = (panels(base, &roles.keys), panels(new, &roles.keys));
    let mut out = vec![];
    let names: std::collections::BTreeSet<&String> =
        base_panels.keys().chain(new_panels.keys()).collect();
    for name in names {
        let sides = PanelSides {
            base,
            new,
            base_rows: base_panels.get(name).map_or(&[][..], |v| &v[..]),
            new_rows: new_panels.get(name).map_or(&[][..], |v| &v[..]),
        };
        let mut change = PanelChange {
            panel: name.clone(),
            columns: vec![],
            rows_added: sides.new_rows.len().saturating_sub(sides.base_rows.len()),
            rows_removed: sides.base_rows.len().saturating_sub(sides.new_rows.len()),
            text_changes: vec![],
        };
        for column in &roles.values {
            let (Some(bj), Some(nj)) = (base.column(column), new.column(column)) else {
                continue;
            };
            if !sides.numeric((bj, nj)) {
                for (b, n) in sides.cells((bj, nj)) {
                    if b != n && change.text_changes.len() < 3 {
                        change.text_changes.push(format!("{column}: {b} → {n}"));
                    }
                }
                continue;
            }
            let ex = sides.extremes(&roles, (bj, nj), (rel_tol, abs_tol));
            let single = (sides.base_rows.len() == 1
                && sides.new_rows.len() == 1
                && ex.max_abs > 0.0)
                .then(|| {
                    (
                        base.rows[sides.base_rows[0]][bj].clone(),
                        new.rows[sides.new_rows[0]][nj].clone(),
                    )
                });
            change.columns.push(ColumnChange {
                column: column.clone(),
                max_abs: ex.max_abs,
                max_rel: ex.max_rel,
                moved: ex.moved,
                single,
            });
        }
        out.push(change);
    }
    TableChange {
        file: file.into(),
        roles,
        header_changed,
        panels: out,
    }
}

/// One panel's rows in the base and the new table.
struct PanelSides<'a> {
    base: &'a CsvTable,
    new: &'a CsvTable,
    base_rows: &'a [usize],
    new_rows: &'a [usize],
}

impl PanelSides<'_> {
    /// Whether the column (index in the base, in the new table) holds numbers or empty cells on
    /// both sides.
    fn numeric(&self, (bj, nj): (usize, usize)) -> bool {
        let numeric = |t: &CsvTable, rows: &[usize], j: usize| {
            rows.iter()
                .all(|&i| t.rows[i][j].is_empty() || t.rows[i][j].parse::<f64>().is_ok())
        };
        numeric(self.base, self.base_rows, bj) && numeric(self.new, self.new_rows, nj)
    }

    /// The column's cells, base and new, row by row.
    fn cells(&self, (bj, nj): (usize, usize)) -> impl Iterator<Item = (&String, &String)> {
        (self.base_rows.iter().zip(self.new_rows))
            .map(move |(&bi, &ni)| (&self.base.rows[bi][bj], &self.new.rows[ni][nj]))
    }

    /// The largest changes of a numeric column: against the base curve interpolated at the new
    /// points' x where the table has an x column, else row by row.
    fn extremes(
        &self,
        roles: &ColumnRoles,
        (bj, nj): (usize, usize),
        (rel_tol, abs_tol): (f64, f64),
    ) -> Extremes {
        let mut ex = Extremes::new();
        let bx = roles.x.as_ref().and_then(|x| self.base.column(x));
        let nx = roles.x.as_ref().and_then(|x| self.new.column(x));
        if let (Some(bx), Some(nx)) = (bx, nx) {
            let bc = curve(self.base, self.base_rows, bx, bj);
            for (x, y) in curve(self.new, self.new_rows, nx, nj) {
                if let Some(b) = interpolate(&bc, x) {
                    ex.add(b, y, rel_tol, abs_tol);
                }
            }
        } else {
            for (b, n) in self.cells((bj, nj)) {
                if let (Ok(b), Ok(n)) = (b.parse::<f64>(), n.parse::<f64>()) {
                    ex.add(b, n, rel_tol, abs_tol);
                }
            }
        }
        ex
    }
}

/// A table that exists on one side only.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Presence {
    Added,
    Removed,
}

/// The summary of one figure, in Markdown: per table, the panels that changed and by how much.
pub fn summary(stem: &str, changes: &[TableChange], presence: &[(String, Presence)]) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "## {stem}\n");
    for (file, p) in presence {
        let _ = writeln!(
            s,
            "- `{file}`: {}",
            match p {
                Presence::Added => "new table (not in the base)",
                Presence::Removed => "removed (only in the base)",
            }
        );
    }
    for t in changes {
        if let Some((old, new)) = &t.header_changed {
            let _ = writeln!(s, "- `{}`: columns changed: `{old}` → `{new}`", t.file);
        }
        let moved: Vec<&PanelChange> = t
            .panels
            .iter()
            .filter(|p| p.moved() || p.columns.iter().any(|c| c.max_abs > 0.0))
            .collect();
        if moved.is_empty() {
            continue;
        }
        let _ = writeln!(
            s,
            "\n`{}` ({} of {} panels changed; beyond the spec's tolerance: {})\n",
            t.file,
            moved.len(),
            t.panels.len(),
            t.panels.iter().filter(|p| p.moved()).count()
        );
        let _ = writeln!(
            s,
            "| panel | column | largest abs. change | largest rel. change | old → new |"
        );
        let _ = writeln!(s, "|---|---|---|---|---|");
        for p in moved {
            let panel = if p.panel.is_empty() {
                "(whole table)".to_string()
            } else {
                p.panel.clone()
            };
            for c in p.columns.iter().filter(|c| c.max_abs > 0.0) {
                let _ = writeln!(
                    s,
                    "| {panel}{} | {} | {} | {} | {} |",
                    if c.moved { " **moved**" } else { "" },
                    c.column,
                    numfmt::sig_digits(c.max_abs, 3),
                    numfmt::sig_digits(c.max_rel, 3),
                    c.single
                        .as_ref()
                        .map_or(String::new(), |(o, n)| format!("{o} → {n}"))
                );
            }
            if p.rows_added + p.rows_removed > 0 {
                let _ = writeln!(
                    s,
                    "| {panel} | (rows) | +{} / −{} | | |",
                    p.rows_added, p.rows_removed
                );
            }
            for t in &p.text_changes {
                let _ = writeln!(s, "| {panel} | (text) | {t} | | |");
            }
        }
    }
    s.push('\n');
    s
}

/// The overlay of one figure: a panel per key group of its curve tables (the ones that moved
/// most, at most [`MAX_PANELS`]), base grey and dashed under the new data.
pub fn overlay(stem: &str, tables: &[(String, CsvTable, CsvTable, TableChange)]) -> Option<Figure> {
    let panels = overlay_panels(tables);
    if panels.is_empty() {
        return None;
    }
    let total = panels.len();
    let chosen = most_moved(panels);
    let cols = chosen.len().min(3);
    let rows = chosen.len().div_ceil(cols);
    let panels = chosen
        .into_iter()
        .map(|(name, panel)| overlay_panel(stem, name, panel))
        .collect();
    Some(Figure {
        width: 460 * cols as u32,
        height: 340 * rows as u32 + 120,
        caption: format!("{stem}: base (grey, dashed) under the working tree"),
        grid: (rows, cols),
        panels,
        footer: vec![if total > MAX_PANELS {
            format!("The {MAX_PANELS} panels that moved most of {total}; every panel is in review/summary.md.")
        } else {
            format!("{total} panels; the numbers are in review/summary.md.")
        }],
        font_px: 14,
    })
}

/// The overlay's panels by name: for each panel of each table's change, the base curve (grey,
/// dashed) and the new one of every value column.
fn overlay_panels(
    tables: &[(String, CsvTable, CsvTable, TableChange)],
) -> BTreeMap<String, OverlayPanel> {
    let mut panels: BTreeMap<String, OverlayPanel> = BTreeMap::new();
    for (file, base, new, change) in tables {
        let Some(x) = &change.roles.x else { continue };
        let (Some(bx), Some(nx)) = (base.column(x), new.column(x)) else {
            continue;
        };
        let (bp, np) = (
            panels_of(base, &change.roles),
            panels_of(new, &change.roles),
        );
        for p in &change.panels {
            let entry = panels.entry(p.panel.clone()).or_insert(OverlayPanel {
                largest_rel: 0.0,
                series: vec![],
                x: x.clone(),
            });
            entry.largest_rel = entry.largest_rel.max(p.largest_rel());
            let many = change.roles.values.len() > 1;
            for column in &change.roles.values {
                let (Some(bj), Some(nj)) = (base.column(column), new.column(column)) else {
                    continue;
                };
                let b = curve(base, bp.get(&p.panel).map_or(&[][..], |v| v), bx, bj);
                let n = curve(new, np.get(&p.panel).map_or(&[][..], |v| v), nx, nj);
                if n.is_empty() && b.is_empty() {
                    continue;
                }
                let markers = file.ends_with("_fe_points.csv");
                let color = palette::CYCLE[(entry.series.len() / 2) % palette::CYCLE.len()];
                let label = if many {
                    column.clone()
                } else {
                    format!("{column} ({file})")
                };
                entry.series.push(Series::dashed(None, palette::GREY, 1, b));
                entry.series.push(if markers {
                    Series::markers(Some(label), color, 3, n)
                } else {
                    Series::line(Some(label), color, 2, n)
                });
            }
        }
    }
    panels
}

/// The [`MAX_PANELS`] panels that moved most (all of them if there are no more), by name.
fn most_moved(panels: BTreeMap<String, OverlayPanel>) -> Vec<(String, OverlayPanel)> {
    let mut chosen: Vec<(String, OverlayPanel)> = panels.into_iter().collect();
    if chosen.len() > MAX_PANELS {
        chosen.sort_by(|a, b| {
            b.1.largest_rel
                .total_cmp(&a.1.largest_rel)
                .then(a.0.cmp(&b.0))
        });
        chosen.truncate(MAX_PANELS);
        chosen.sort_by(|a, b| a.0.cmp(&b.0));
    }
    chosen
}

/// The plotted panel `name` of the figure `stem` (titled by the stem when the table has a
/// single unnamed panel), its ranges padded around its series.
fn overlay_panel(stem: &str, name: String, panel: OverlayPanel) -> Panel {
    let OverlayPanel {
        largest_rel,
        series,
        x,
    } = panel;
    let xs = padded_range(series.iter().flat_map(|s| s.points.iter().map(|p| p.0)));
    let ys = padded_range(series.iter().flat_map(|s| s.points.iter().map(|p| p.1)));
    Panel {
        title: if name.is_empty() {
            stem.to_string()
        } else {
            name
        },
        x_label: x,
        y_label: "value".into(),
        x_range: xs,
        y_range: ys,
        series,
        notes: vec![format!(
            "largest rel. change {}",
            numfmt::sig_digits(largest_rel, 2)
        )],
        log_scale: (false, false),
        legend: Some(LegendPosition::UpperLeft),
    }
}

/// One panel of an overlay: its series and the largest relative change of its values.
struct OverlayPanel {
    largest_rel: f64,
    series: Vec<Series>,
    x: String,
}

fn panels_of(t: &CsvTable, roles: &ColumnRoles) -> BTreeMap<String, Vec<usize>> {
    panels(t, &roles.keys)
}
