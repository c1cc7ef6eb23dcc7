//! The docs cannot drift from the CSVs they restate, the README stays a first page, and no
//! relative link is dead.
//!
//! Reads README.md, CONTRIBUTING.md and docs/*.md, and the CSVs their tables name; nothing outside
//! the repository.
//!
//! # Marking a table that restates a CSV
//!
//! An HTML comment directly above the table (blank lines between are allowed) names the CSV and
//! says how each checked cell is computed from it:
//!
//! ```text
//! <!-- from figures/fig3_fe_vs_model_mse.csv
//! rows: tau_max_mpa=0 | tau_max_mpa=0.01
//! col 1: {tau_max_mpa:v}
//! col 2: {mse_wnl[aspect_ratio=0.1]:e1} / {mse_westergaard[aspect_ratio=0.1]:e1}
//! -->
//! | τ_max (MPa) | AR = 0.1 |
//! |---|---|
//! | 0 | 1.1e-5 / 1.8e-5 |
//! | 0.01 | 4.2e-6 / 3.6e-5 |
//! ```
//!
//! - `from PATH`: the CSV, relative to the repository root. Lines starting with `#` before its
//!   header are skipped; fields may be quoted.
//! - `rows: F | F | …`: one filter per body row of the table, in order (several `rows:` lines are
//!   joined). A filter is `column=value,column=value` (values compared as numbers when both parse,
//!   else as text; `column=` matches an empty field; a value in double quotes may hold commas; a
//!   value ending in `*` matches every field that starts with what precedes the `*`) or `*`
//!   (every CSV row).
//! - `col N: TEMPLATE`: the text of column N (1-based) in every body row. Columns without a `col`
//!   line are not checked (labels that are not in the CSV). A template is literal text with
//!   placeholders `{EXPR:FORMAT}` or `{EXPR:FORMAT|TEXT}` (TEXT when the field is empty).
//! - `EXPR` is evaluated on the CSV rows that pass the row's filter:
//!   - `column` or `column[filter]`: the one row left after the extra filter (more or fewer than
//!     one is an error in the marker);
//!   - `min(column[filter])`, `max(column[filter])`: over every row left, empty fields skipped;
//!   - `count(column[filter])`: how many rows left have a non-empty field;
//!   - `rel(A; B)`: A / B − 1, A and B as above.
//! - `FORMAT` is an optional flag `z` (|x| < 1e-9 prints `0`, the unit kept), an optional flag `+`
//!   (a sign on positive values too), then one kind:
//!   - `v`: the CSV text unchanged;
//!   - `eN`: scientific with N decimals, as Rust's `{:.Ne}` (`1.1e-5`);
//!   - `fN`: N decimals;
//!   - `sN`: N significant digits (digits left of the point are never rounded away), trailing
//!     zeros kept;
//!   - `pN`: ×100 with N significant digits, trailing zeros dropped, then ` %`;
//!   - `pfN`: ×100 with N decimals, then ` %`;
//!   - `tN`: a time in seconds, N significant digits, in µs below 1 ms, else in s.
//!
//!   Rounding is Rust's (the decimal nearest to the binary value). In the doc, `−` (U+2212)
//!   reads as `-`, and runs of spaces as one.
//!
//! A failure names the doc, the table's line, the row, the column, the doc's text and the text
//! the CSV gives.
//!
//! # Marking a number in a sentence
//!
//! An HTML comment `<!-- = PATH: TEMPLATE -->` placed right after the number (no space between;
//! rendered Markdown shows nothing of it) says which CSV holds the number and how it is computed:
//!
//! ```text
//! mesh 96 alone has 0.274 %<!-- = figures/speed_accuracy.csv:
//!   {max_rel_error[tier=fe-finite-96,aspect_ratio=0.18,tau_max_mpa=0.1]:p3} --> with friction
//! ```
//!
//! PATH and TEMPLATE are those of a table marker; the comment may span lines (runs of white space
//! read as one space). The expressions are evaluated on every row of the CSV, so each reference
//! needs a filter that leaves one row (or is an aggregate: `min`, `max`, `count`). The TEMPLATE,
//! filled in, must be the end of the text before the comment (after the `−` and white-space
//! normalisation of the tables); markup such as `**` goes outside the pair, as in
//! `**0.274 %<!-- = … -->**`. A failure names the doc, the comment's line, the end of the doc's
//! text and the text the CSV gives. `WAVY_DOC_TABLES=update` does not rewrite these: a number in a
//! sentence usually carries a claim, which the author rereads. Each doc in `MUST_HAVE_INLINE`
//! holds at least one.
//!
//! # Marking a finding
//!
//! A sentence that compares numbers (a finding: "A fits best", "the error falls as n grows") carries
//! `<!-- ? PATH: CONDITION -->`, anywhere in it. CONDITION is one comparison or several joined by
//! `&&`, each `OPERAND OP OPERAND` with OP one of `<`, `<=`, `>`, `>=`, `==`; an OPERAND is a
//! number, an expression as above (`column[filter]`, `min`, `max`, `count`, `rel`) evaluated on
//! every row of the CSV, or `NUMBER * EXPRESSION`:
//!
//! ```text
//! refitted, bracket-2x fits best<!-- ? figures/table1_refit_fit.csv:
//!   mse_ours[reading=bracket-2x] == min(mse_ours) -->
//! ```
//!
//! Every comparison must hold; a failure names the doc, the comment's line, the comparison and the
//! two values. Every bullet of the README's "What we found" holds at least one, so that a finding
//! cannot change its meaning, or be added, without saying what it rests on.
//!
//! # A table of a Markdown doc as the CSV
//!
//! PATH may be `DOC.md#anchor`: the first table under the heading with that anchor, its header cells
//! the column names (`docs/performance.md#current-values`, the durations a newcomer is told).
//!
//! # Also checked
//!
//! README.md ≤ 12 288 bytes without its HTML comments (what a reader sees; the markers are free);
//! every relative link `[…](path)` or `![…](path)` in README.md,
//! CONTRIBUTING.md and docs/*.md points to a file or folder inside the repository, and its
//! `#anchor`, if any (`#anchor` alone: the same doc), is the slug of a heading of the target
//! Markdown file, by GitHub's rule (the heading's text lower-cased, every character but letters,
//! digits, `_`, `-` and spaces dropped, each space a `-`; a repeated slug gets `-1`, `-2`, …); at
//! least one marked table per CSV listed in `MUST_BE_CHECKED`.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Component, Path, PathBuf};

/// The README's length as read (HTML comments left out, so that a marker costs nothing): a first
/// page, the depth in docs/.
const README_MAX_BYTES: usize = 12_288;

/// CSVs restated by a doc table; each must be named by at least one marker (so that the test
/// never passes because the markers were deleted).
const MUST_BE_CHECKED: &[&str] = &[
    "figures/fig3_fe_vs_model_mse.csv",
    "figures/table1_refit.csv",
    "figures/table1_refit_fit.csv",
    "figures/fingertip_fe_errors.csv",
    "figures/fig5_warman_ennos.csv",
    "figures/hysteresis_dissipation.csv",
    "figures/speed_accuracy.csv",
    "figures/speed_accuracy_bands.csv",
    "figures/speed_accuracy_reference.csv",
    "figures/speed_accuracy_trade.csv",
    "figures/two_scale_errors.csv",
    "figures/two_scale_separation_errors.csv",
    "figures/many_scale_errors.csv",
    "experiments/data/robustness_grid.csv",
];

/// Docs that restate CSV numbers in sentences; each must hold at least one inline marker.
const MUST_HAVE_INLINE: &[&str] = &[
    "README.md",
    "CONTRIBUTING.md",
    "docs/replication.md",
    "docs/results.md",
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// README.md, CONTRIBUTING.md and docs/*.md, as paths relative to the root.
fn doc_files() -> Vec<String> {
    let mut docs = vec!["README.md".to_string(), "CONTRIBUTING.md".to_string()];
    let mut in_docs: Vec<String> = fs::read_dir(root().join("docs"))
        .expect("docs/ exists")
        .map(|e| e.expect("readable docs/ entry").file_name())
        .filter_map(|n| n.to_str().map(str::to_string))
        .filter(|n| n.ends_with(".md"))
        .map(|n| format!("docs/{n}"))
        .collect();
    in_docs.sort();
    docs.extend(in_docs);
    docs
}

fn read_doc(rel: &str) -> String {
    fs::read_to_string(root().join(rel)).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

/// A path named in a doc or marker, checked to stay inside the repository.
fn inside_repo(base_dir: &Path, target: &str) -> Option<PathBuf> {
    let mut parts: Vec<Component> = Vec::new();
    if Path::new(target).is_absolute() {
        return None;
    }
    let joined = base_dir.join(target);
    for c in joined.components() {
        match c {
            Component::ParentDir => {
                parts.pop()?;
            }
            Component::CurDir => {}
            c => parts.push(c),
        }
    }
    Some(parts.iter().collect())
}

// ---------------------------------------------------------------- CSV

struct Csv {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

fn parse_csv_line(line: &str) -> Vec<String> {
    let mut fields = Vec::new();
    let mut field = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => fields.push(std::mem::take(&mut field)),
            (c, _) => field.push(c),
        }
    }
    fields.push(field);
    fields
}

fn read_csv(rel: &str) -> Result<Csv, String> {
    let (file, anchor) = match rel.split_once('#') {
        Some((file, anchor)) => (file, Some(anchor)),
        None => (rel, None),
    };
    let path = inside_repo(Path::new(""), file).ok_or(format!("{rel}: outside the repository"))?;
    let text = fs::read_to_string(root().join(path)).map_err(|e| format!("{rel}: {e}"))?;
    match anchor {
        None => parse_csv(rel, &text),
        Some(anchor) if file.ends_with(".md") => markdown_table(rel, &text, anchor),
        Some(_) => Err(format!(
            "{rel}: `#anchor` names a table of a Markdown file only"
        )),
    }
}

/// The first table under the heading whose anchor is `anchor` (before the next heading), as a CSV:
/// its header cells are the column names, its body rows the rows.
fn markdown_table(rel: &str, text: &str, anchor: &str) -> Result<Csv, String> {
    let mut seen = BTreeSet::new();
    let mut lines = text.lines();
    let mut found = false;
    for line in lines.by_ref() {
        if let Some(slug) = heading_slug(line, &mut seen) {
            if slug == anchor {
                found = true;
                break;
            }
        }
    }
    if !found {
        return Err(format!("{rel}: no heading whose anchor is `#{anchor}`"));
    }
    let mut table = lines
        .take_while(|l| !l.starts_with('#'))
        .skip_while(|l| !l.trim_start().starts_with('|'))
        .take_while(|l| l.trim_start().starts_with('|'));
    let header = table_cells(
        table
            .next()
            .ok_or(format!("{rel}: no table under the heading"))?,
    );
    let rows = table.skip(1).map(table_cells).collect();
    Ok(Csv { header, rows })
}

fn parse_csv(rel: &str, text: &str) -> Result<Csv, String> {
    let mut lines = text.lines().skip_while(|l| l.starts_with('#'));
    let header = parse_csv_line(lines.next().ok_or(format!("{rel}: no header"))?);
    let rows = lines
        .filter(|l| !l.is_empty())
        .map(parse_csv_line)
        .collect();
    Ok(Csv { header, rows })
}

impl Csv {
    fn column(&self, name: &str) -> Result<usize, String> {
        self.header
            .iter()
            .position(|h| h == name)
            .ok_or(format!("no column `{name}`"))
    }
}

// ---------------------------------------------------------------- filters and expressions

type Filter = Vec<(String, String)>;

fn parse_filter(text: &str) -> Result<Filter, String> {
    let text = text.trim();
    if text == "*" || text.is_empty() {
        return Ok(Vec::new());
    }
    split_outside_quotes(text)
        .into_iter()
        .map(|kv| {
            let (k, v) = kv
                .split_once('=')
                .ok_or(format!("filter `{kv}` is not column=value"))?;
            let v = v.trim();
            let v = v
                .strip_prefix('"')
                .and_then(|v| v.strip_suffix('"'))
                .unwrap_or(v);
            Ok((k.trim().to_string(), v.to_string()))
        })
        .collect()
}

/// `text` split at the commas that are not inside double quotes (a quoted value may hold commas).
fn split_outside_quotes(text: &str) -> Vec<&str> {
    let mut parts = Vec::new();
    let (mut start, mut quoted) = (0, false);
    for (i, c) in text.char_indices() {
        match c {
            '"' => quoted = !quoted,
            ',' if !quoted => {
                parts.push(&text[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&text[start..]);
    parts
}

fn same_value(field: &str, want: &str) -> bool {
    if let Some(prefix) = want.strip_suffix('*') {
        return field.starts_with(prefix);
    }
    match (field.parse::<f64>(), want.parse::<f64>()) {
        (Ok(a), Ok(b)) => a == b,
        _ => field == want,
    }
}

fn select<'a>(
    csv: &Csv,
    rows: &[&'a Vec<String>],
    filter: &Filter,
) -> Result<Vec<&'a Vec<String>>, String> {
    let cols = filter
        .iter()
        .map(|(k, v)| Ok((csv.column(k)?, v.as_str())))
        .collect::<Result<Vec<_>, String>>()?;
    Ok(rows
        .iter()
        .copied()
        .filter(|r| cols.iter().all(|(i, v)| same_value(&r[*i], v)))
        .collect())
}

/// `column` or `column[filter]`.
fn parse_ref(text: &str) -> Result<(String, Filter), String> {
    let text = text.trim();
    match text.split_once('[') {
        None => Ok((text.to_string(), Vec::new())),
        Some((col, rest)) => {
            let inner = rest
                .strip_suffix(']')
                .ok_or(format!("`{text}`: missing `]`"))?;
            Ok((col.trim().to_string(), parse_filter(inner)?))
        }
    }
}

/// The field a reference names, in the one row it selects.
fn one_field(csv: &Csv, rows: &[&Vec<String>], reference: &str) -> Result<String, String> {
    let (col, filter) = parse_ref(reference)?;
    let picked = select(csv, rows, &filter)?;
    if picked.len() != 1 {
        return Err(format!(
            "`{reference}` selects {} CSV rows, not one",
            picked.len()
        ));
    }
    Ok(picked[0][csv.column(&col)?].clone())
}

fn number(field: &str, what: &str) -> Result<f64, String> {
    field
        .parse::<f64>()
        .map_err(|_| format!("`{what}`: `{field}` is not a number"))
}

/// The value of an expression: `Ok(None)` when its field is empty.
fn evaluate(csv: &Csv, rows: &[&Vec<String>], expr: &str) -> Result<Option<Value>, String> {
    let expr = expr.trim();
    for (name, take_max) in [("min(", false), ("max(", true)] {
        if let Some(inner) = expr.strip_prefix(name).and_then(|e| e.strip_suffix(')')) {
            let (col, filter) = parse_ref(inner)?;
            let i = csv.column(&col)?;
            let mut values = Vec::new();
            for r in select(csv, rows, &filter)? {
                if !r[i].is_empty() {
                    values.push(number(&r[i], expr)?);
                }
            }
            let folded = values
                .into_iter()
                .reduce(|a, b| if take_max == (b > a) { b } else { a });
            return Ok(folded.map(Value::Number));
        }
    }
    if let Some(inner) = expr
        .strip_prefix("count(")
        .and_then(|e| e.strip_suffix(')'))
    {
        let (col, filter) = parse_ref(inner)?;
        let i = csv.column(&col)?;
        let n = select(csv, rows, &filter)?
            .iter()
            .filter(|r| !r[i].is_empty())
            .count();
        return Ok(Some(Value::Number(n as f64)));
    }
    if let Some(inner) = expr.strip_prefix("rel(").and_then(|e| e.strip_suffix(')')) {
        let (a, b) = inner.split_once(';').ok_or(format!(
            "`{expr}`: rel takes two references separated by `;`"
        ))?;
        let (a, b) = (one_field(csv, rows, a)?, one_field(csv, rows, b)?);
        if a.is_empty() || b.is_empty() {
            return Ok(None);
        }
        return Ok(Some(Value::Number(
            number(&a, expr)? / number(&b, expr)? - 1.0,
        )));
    }
    let field = one_field(csv, rows, expr)?;
    Ok((!field.is_empty()).then_some(Value::Text(field)))
}

enum Value {
    Text(String),
    Number(f64),
}

// ---------------------------------------------------------------- formats

/// N significant digits, never rounding digits left of the point away.
fn significant(x: f64, n: usize) -> String {
    if x == 0.0 {
        return "0".to_string();
    }
    let magnitude = x.abs().log10().floor() as i64;
    let decimals = (n as i64 - 1 - magnitude).max(0) as usize;
    format!("{x:.decimals$}")
}

fn trim_zeros(s: String) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

fn format_value(value: Value, format: &str) -> Result<String, String> {
    let mut spec = format.trim();
    let zero_flag = spec.starts_with('z');
    spec = spec.trim_start_matches('z');
    let plus_flag = spec.starts_with('+');
    spec = spec.trim_start_matches('+');
    let x = match value {
        Value::Text(t) if spec == "v" => return Ok(t),
        Value::Text(t) => number(&t, format)?,
        Value::Number(x) => x,
    };
    let digits = |prefix: &str| -> Result<usize, String> {
        spec[prefix.len()..]
            .parse::<usize>()
            .map_err(|_| format!("format `{format}`: digits expected after `{prefix}`"))
    };
    let (body, unit) = if let Some(kind) = ["pf", "p", "e", "f", "s", "t"]
        .into_iter()
        .find(|k| spec.starts_with(k))
    {
        let n = digits(kind)?;
        match kind {
            "pf" => (format!("{:.n$}", x * 100.0), " %"),
            "p" => (trim_zeros(significant(x * 100.0, n)), " %"),
            "e" => (format!("{x:.n$e}"), ""),
            "f" => (format!("{x:.n$}"), ""),
            "s" => (significant(x, n), ""),
            _ if x.abs() < 1e-3 => (significant(x * 1e6, n), " µs"),
            _ => (significant(x, n), " s"),
        }
    } else if spec == "v" {
        (x.to_string(), "")
    } else {
        return Err(format!("unknown format `{format}`"));
    };
    if zero_flag && x.abs() < 1e-9 {
        return Ok(format!("0{unit}"));
    }
    let sign = if plus_flag && x > 0.0 { "+" } else { "" };
    Ok(format!("{sign}{body}{unit}"))
}

/// A template with its placeholders filled from the rows of one table row.
fn render(csv: &Csv, rows: &[&Vec<String>], template: &str) -> Result<String, String> {
    let mut out = String::new();
    let mut rest = template;
    while let Some(open) = rest.find('{') {
        out.push_str(&rest[..open]);
        let close = rest[open..]
            .find('}')
            .ok_or(format!("`{template}`: unclosed `{{`"))?
            + open;
        let placeholder = &rest[open + 1..close];
        let (body, fallback) = match placeholder.split_once('|') {
            Some((b, f)) => (b, Some(f)),
            None => (placeholder, None),
        };
        let (expr, format) = body
            .rsplit_once(':')
            .ok_or(format!("`{{{placeholder}}}`: no `:FORMAT`"))?;
        match (evaluate(csv, rows, expr)?, fallback) {
            (Some(v), _) => out.push_str(&format_value(v, format)?),
            (None, Some(f)) => out.push_str(f),
            (None, None) => return Err(format!("`{expr}` is empty and has no `|TEXT`")),
        }
        rest = &rest[close + 1..];
    }
    out.push_str(rest);
    Ok(out)
}

fn normalise(cell: &str) -> String {
    cell.replace('\u{2212}', "-")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

// ---------------------------------------------------------------- markers and tables

struct Marker {
    csv: String,
    rows: Vec<String>,
    cols: Vec<(usize, String)>,
}

fn parse_marker(comment: &str) -> Result<Marker, String> {
    let mut lines = comment.lines();
    let csv = lines
        .next()
        .and_then(|l| l.trim().strip_prefix("from "))
        .ok_or("first line is not `from PATH`")?
        .trim()
        .to_string();
    let mut rows = Vec::new();
    let mut cols = Vec::new();
    for line in lines.map(str::trim).filter(|l| !l.is_empty()) {
        if let Some(r) = line.strip_prefix("rows:") {
            rows.extend(r.split('|').map(|f| f.trim().to_string()));
        } else if let Some(c) = line.strip_prefix("col ") {
            let (n, template) = c.split_once(':').ok_or(format!("`{line}`: no `:`"))?;
            let n: usize = n
                .trim()
                .parse()
                .map_err(|_| format!("`{line}`: column number expected"))?;
            if n == 0 {
                return Err(format!("`{line}`: columns count from 1"));
            }
            cols.push((n, template.trim().to_string()));
        } else {
            return Err(format!("`{line}`: expected `rows:` or `col N:`"));
        }
    }
    if cols.is_empty() {
        return Err("no `col N:` line".to_string());
    }
    Ok(Marker { csv, rows, cols })
}

fn table_cells(line: &str) -> Vec<String> {
    let inner = line.trim().trim_start_matches('|');
    let inner = inner.strip_suffix('|').unwrap_or(inner);
    inner.split('|').map(|c| c.trim().to_string()).collect()
}

/// Every marked table of a doc: (1-based line of the marker, marker text, table lines, 0-based
/// line of the table's first line).
fn marked_tables(text: &str) -> Vec<(usize, String, Vec<String>, usize)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut found = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let Some(first) = lines[i].trim().strip_prefix("<!-- from ") else {
            i += 1;
            continue;
        };
        let start = i;
        let mut comment = format!("from {first}");
        while !comment.trim_end().ends_with("-->") && i + 1 < lines.len() {
            i += 1;
            comment.push('\n');
            comment.push_str(lines[i]);
        }
        let comment = comment.trim_end().trim_end_matches("-->").to_string();
        i += 1;
        while i < lines.len() && lines[i].trim().is_empty() {
            i += 1;
        }
        let table_start = i;
        let mut table = Vec::new();
        while i < lines.len() && lines[i].trim_start().starts_with('|') {
            table.push(lines[i].to_string());
            i += 1;
        }
        found.push((start + 1, comment, table, table_start));
    }
    found
}

/// With `WAVY_DOC_TABLES=update` the test rewrites every checked cell that differs from what its
/// CSV gives instead of reporting it (the docs' tables regenerated from the data after `make
/// bless`; the prose around them is the author's to reread); markers and filters are checked as
/// usual.
#[test]
fn doc_tables_match_their_csvs() {
    let update = std::env::var("WAVY_DOC_TABLES").is_ok_and(|v| v == "update");
    let mut failures = Vec::new();
    let mut checked_csvs = BTreeSet::new();
    let mut cells = 0usize;
    for doc in doc_files() {
        let text = read_doc(&doc);
        let mut lines: Vec<String> = text.lines().map(String::from).collect();
        let mut rewritten = false;
        for (line, comment, table, table_start) in marked_tables(&text) {
            let at = format!("{doc}, table at line {line}");
            let marker = match parse_marker(&comment) {
                Ok(m) => m,
                Err(e) => {
                    failures.push(format!("{at}: marker: {e}"));
                    continue;
                }
            };
            let at = format!("{at} (from {})", marker.csv);
            let csv = match read_csv(&marker.csv) {
                Ok(c) => c,
                Err(e) => {
                    failures.push(format!("{at}: {e}"));
                    continue;
                }
            };
            checked_csvs.insert(marker.csv.clone());
            if table.len() < 3 {
                failures.push(format!(
                    "{at}: no table (header, separator, rows) below the marker"
                ));
                continue;
            }
            let header = table_cells(&table[0]);
            let body = &table[2..];
            if body.len() != marker.rows.len() {
                failures.push(format!(
                    "{at}: {} body rows but {} row filters",
                    body.len(),
                    marker.rows.len()
                ));
                continue;
            }
            let all: Vec<&Vec<String>> = csv.rows.iter().collect();
            for (r, (row_line, filter)) in body.iter().zip(&marker.rows).enumerate() {
                let doc_cells = table_cells(row_line);
                let label = doc_cells.first().cloned().unwrap_or_default();
                let rows = match parse_filter(filter).and_then(|f| select(&csv, &all, &f)) {
                    Ok(rows) if !rows.is_empty() => rows,
                    Ok(_) => {
                        failures.push(format!(
                            "{at}, row {} (`{label}`): filter `{filter}` selects no CSV row",
                            r + 1
                        ));
                        continue;
                    }
                    Err(e) => {
                        failures.push(format!("{at}, row {} (`{label}`): {e}", r + 1));
                        continue;
                    }
                };
                for (c, template) in &marker.cols {
                    let column = header.get(c - 1).cloned().unwrap_or_default();
                    let place = format!("{at}, row {} (`{label}`), column {c} (`{column}`)", r + 1);
                    let want = match render(&csv, &rows, template) {
                        Ok(w) => normalise(&w),
                        Err(e) => {
                            failures.push(format!("{place}: {e}"));
                            continue;
                        }
                    };
                    let have = doc_cells.get(c - 1).map(|s| normalise(s));
                    if update && have.as_deref() != Some(want.as_str()) && *c <= doc_cells.len() {
                        let at_line = table_start + 2 + r;
                        let mut cells_now = table_cells(&lines[at_line]);
                        cells_now[c - 1] = want.clone();
                        lines[at_line] = format!("| {} |", cells_now.join(" | "));
                        rewritten = true;
                        continue;
                    }
                    cells += 1;
                    if have.as_deref() != Some(want.as_str()) {
                        failures.push(format!(
                            "{place}: the doc has `{}`, the CSV gives `{want}`",
                            have.unwrap_or_else(|| "(no cell)".to_string())
                        ));
                    }
                }
            }
        }
        if rewritten {
            let mut new = lines.join("\n");
            new.push('\n');
            fs::write(root().join(&doc), new).unwrap_or_else(|e| panic!("{doc}: {e}"));
        }
    }
    for csv in MUST_BE_CHECKED {
        if !checked_csvs.contains(*csv) {
            failures.push(format!("no doc table is marked `from {csv}`"));
        }
    }
    println!("{cells} cells checked against {} CSVs", checked_csvs.len());
    assert!(
        failures.is_empty(),
        "{} mismatches:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

// ---------------------------------------------------------------- numbers in sentences

/// An inline marker `<!-- = PATH: TEMPLATE -->`: its 1-based line, PATH, TEMPLATE and the doc's
/// text before it.
struct InlineMarker<'a> {
    line: usize,
    csv: String,
    template: String,
    before: &'a str,
}

const INLINE_OPEN: &str = "<!-- =";

/// Byte ranges of the fenced code blocks of a doc (markers there are examples, not markers).
fn fenced_ranges(text: &str) -> Vec<std::ops::Range<usize>> {
    let mut ranges = Vec::new();
    let (mut at, mut open) = (0, None);
    for line in text.split_inclusive('\n') {
        if line.trim_start().starts_with("```") {
            match open.take() {
                Some(start) => ranges.push(start..at + line.len()),
                None => open = Some(at),
            }
        }
        at += line.len();
    }
    if let Some(start) = open {
        ranges.push(start..text.len());
    }
    ranges
}

/// A comment marker `OPEN PATH: REST -->` outside fenced code: its line, where it starts, its
/// path and the rest (runs of white space read as one space).
struct RawMarker {
    line: usize,
    start: usize,
    path: String,
    rest: String,
}

/// Every marker opened by `open` in `text`; `form` names the marker's form in the message of one
/// that is not `PATH: REST`.
fn raw_markers(text: &str, open: &str, form: &str) -> Result<Vec<RawMarker>, String> {
    let fenced = fenced_ranges(text);
    let mut found = Vec::new();
    let mut from = 0;
    while let Some(found_at) = text[from..].find(open) {
        let start = from + found_at;
        let line = text[..start].matches('\n').count() + 1;
        let body_start = start + open.len();
        let Some(end) = text[body_start..].find("-->") else {
            return Err(format!("line {line}: `{open}` without `-->`"));
        };
        from = body_start + end + 3;
        if fenced.iter().any(|r| r.contains(&start)) {
            continue;
        }
        let body = text[body_start..body_start + end]
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ");
        let Some((path, rest)) = body.split_once(':') else {
            return Err(format!("line {line}: marker `{body}` is not `{form}`"));
        };
        found.push(RawMarker {
            line,
            start,
            path: path.trim().to_string(),
            rest: rest.trim().to_string(),
        });
    }
    Ok(found)
}

fn inline_markers(text: &str) -> Result<Vec<InlineMarker<'_>>, String> {
    Ok(raw_markers(text, INLINE_OPEN, "= PATH: TEMPLATE")?
        .into_iter()
        .map(|m| InlineMarker {
            line: m.line,
            csv: m.path,
            template: m.rest,
            before: &text[..m.start],
        })
        .collect())
}

/// Checks the inline markers of one doc against the CSVs `load` gives: the number of markers
/// checked and a message per failure (doc, line, the end of the doc's text, what the CSV gives).
fn check_inline(
    doc: &str,
    text: &str,
    load: &mut dyn FnMut(&str) -> Result<Csv, String>,
) -> (usize, Vec<String>) {
    check_each(
        doc,
        inline_markers(text),
        |m| (m.line, format!("inline marker (from {})", m.csv)),
        |m| {
            let csv = load(&m.csv)?;
            let all: Vec<&Vec<String>> = csv.rows.iter().collect();
            let want = normalise(&render(&csv, &all, &m.template)?);
            let have = normalise(m.before);
            if want.is_empty() || !have.ends_with(&want) {
                let chars: Vec<char> = have.chars().collect();
                let shown = want.chars().count() + 40;
                let tail: String = chars[chars.len().saturating_sub(shown)..].iter().collect();
                return Ok(Some(format!(
                    "the text before the marker ends `…{tail}`, the CSV gives `{want}`"
                )));
            }
            Ok(None)
        },
    )
}

/// Checks each of a doc's markers (or reports why they could not be read): the number checked
/// and a message per failure, `doc:line: what: why`. `check` gives `Ok(Some(why))` for a marker
/// the doc contradicts and `Err` for one that cannot be evaluated.
fn check_each<M>(
    doc: &str,
    markers: Result<Vec<M>, String>,
    locate: impl Fn(&M) -> (usize, String),
    mut check: impl FnMut(&M) -> Result<Option<String>, String>,
) -> (usize, Vec<String>) {
    let markers = match markers {
        Ok(m) => m,
        Err(e) => return (0, vec![format!("{doc}: {e}")]),
    };
    let mut failures = Vec::new();
    for m in &markers {
        let (line, what) = locate(m);
        match check(m) {
            Ok(None) => {}
            Ok(Some(why)) | Err(why) => failures.push(format!("{doc}:{line}: {what}: {why}")),
        }
    }
    (markers.len(), failures)
}

#[test]
fn inline_numbers_match_their_csvs() {
    let mut failures = Vec::new();
    let mut total = 0;
    let mut csvs = BTreeSet::new();
    for doc in doc_files() {
        let text = read_doc(&doc);
        let mut load = |rel: &str| {
            csvs.insert(rel.to_string());
            read_csv(rel)
        };
        let (n, f) = check_inline(&doc, &text, &mut load);
        if n == 0 && MUST_HAVE_INLINE.contains(&doc.as_str()) {
            failures.push(format!(
                "{doc}: no inline marker (it must hold at least one)"
            ));
        }
        total += n;
        failures.extend(f);
    }
    println!(
        "{total} numbers in sentences checked against {} CSVs",
        csvs.len()
    );
    assert!(
        failures.is_empty(),
        "{} mismatches:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// A right number passes, a wrong one fails naming doc, line, text and the CSV's value; the
/// marker may span lines; `count` and a `*` prefix filter count rows.
#[test]
fn a_wrong_inline_number_fails() {
    let csv_text = "# a comment line\ntier,aspect_ratio,max_rel_error\n\
                    fe-finite-48,0.18,0.0053\nfe-finite-96,0.18,0.00274\nwnl,0.18,0.2\n";
    let mut load = |rel: &str| parse_csv(rel, csv_text);
    let right = "Intro.\n\nMesh 96 gets 0.274 %<!-- = t.csv:\n  \
                 {max_rel_error[tier=fe-finite-96,\n  aspect_ratio=0.18]:p3} --> and there are \
                 2<!-- = t.csv: {count(tier[tier=fe-*]):v} --> FE rows.\n\n```text\n\
                 an example, not checked: 9 %<!-- = t.csv: {x:v} -->\n```\n";
    assert_eq!(check_inline("doc.md", right, &mut load), (2, Vec::new()));

    let wrong = "Intro.\n\nWith friction no mesh gets below 0.3 %<!-- = t.csv:\n\
                 {min(max_rel_error[tier=fe-*]):p3} -->.\n";
    let (n, failures) = check_inline("doc.md", wrong, &mut load);
    assert_eq!(n, 1);
    assert_eq!(failures.len(), 1, "{failures:?}");
    let f = &failures[0];
    for part in [
        "doc.md:3:",
        "t.csv",
        "no mesh gets below 0.3 %`",
        "the CSV gives `0.274 %`",
    ] {
        assert!(f.contains(part), "`{part}` missing from: {f}");
    }

    let (_, failures) = check_inline(
        "doc.md",
        "x 1<!-- = t.csv: {max_rel_error:v} -->",
        &mut load,
    );
    assert!(failures[0].contains("selects 3 CSV rows"), "{failures:?}");
}

// ---------------------------------------------------------------- findings

/// A finding marker `<!-- ? PATH: CONDITION -->`: its 1-based line, PATH and CONDITION.
struct FindingMarker {
    line: usize,
    csv: String,
    condition: String,
}

const FINDING_OPEN: &str = "<!-- ?";

fn finding_markers(text: &str) -> Result<Vec<FindingMarker>, String> {
    Ok(raw_markers(text, FINDING_OPEN, "? PATH: CONDITION")?
        .into_iter()
        .map(|m| FindingMarker {
            line: m.line,
            csv: m.path,
            condition: m.rest,
        })
        .collect())
}

/// The comparison operators of a condition, the two-character ones first.
const COMPARISONS: [&str; 5] = ["<=", ">=", "==", "<", ">"];

/// `left OP right` split at its operator outside `[…]` and `(…)` (where filters hold `=`).
fn split_comparison(text: &str) -> Result<(&str, &'static str, &str), String> {
    let mut depth = 0i32;
    for (i, c) in text.char_indices() {
        match c {
            '[' | '(' => depth += 1,
            ']' | ')' => depth -= 1,
            _ if depth == 0 => {
                if let Some(op) = COMPARISONS.iter().find(|op| text[i..].starts_with(**op)) {
                    return Ok((&text[..i], op, &text[i + op.len()..]));
                }
            }
            _ => {}
        }
    }
    Err(format!("`{text}` has no comparison (<, <=, >, >=, ==)"))
}

/// An operand: a number, or an expression of the tables (`column[filter]`, `min(…)`, `max(…)`,
/// `count(…)`, `rel(…; …)`) evaluated on every row of the CSV, optionally `NUMBER * EXPR`.
fn operand(csv: &Csv, text: &str) -> Result<f64, String> {
    let text = text.trim();
    if let Ok(x) = text.parse::<f64>() {
        return Ok(x);
    }
    let (factor, expr) = match text.split_once('*') {
        Some((f, e)) if f.trim().parse::<f64>().is_ok() => {
            (f.trim().parse::<f64>().unwrap_or(1.0), e)
        }
        _ => (1.0, text),
    };
    let all: Vec<&Vec<String>> = csv.rows.iter().collect();
    match evaluate(csv, &all, expr)? {
        Some(Value::Number(x)) => Ok(factor * x),
        Some(Value::Text(t)) => Ok(factor * number(&t, expr)?),
        None => Err(format!("`{expr}` is empty")),
    }
}

/// Whether every `A OP B` of a condition (joined by `&&`) holds: `Ok(None)` when it does, else the
/// first comparison that does not, with the values it compared.
fn check_condition(csv: &Csv, condition: &str) -> Result<Option<String>, String> {
    for clause in condition.split("&&") {
        let (a, op, b) = split_comparison(clause.trim())?;
        let (x, y) = (operand(csv, a)?, operand(csv, b)?);
        let holds = match op {
            "<=" => x <= y,
            ">=" => x >= y,
            "==" => x == y,
            "<" => x < y,
            _ => x > y,
        };
        if !holds {
            return Ok(Some(format!("`{}` is false: {x} {op} {y}", clause.trim())));
        }
    }
    Ok(None)
}

/// Checks the finding markers of one doc: the number checked and a message per failure (doc,
/// line, CSV, the comparison that does not hold and its values).
fn check_findings(
    doc: &str,
    text: &str,
    load: &mut dyn FnMut(&str) -> Result<Csv, String>,
) -> (usize, Vec<String>) {
    check_each(
        doc,
        finding_markers(text),
        |m| (m.line, format!("finding (from {})", m.csv)),
        |m| load(&m.csv).and_then(|csv| check_condition(&csv, &m.condition)),
    )
}

/// The bullets of a doc's section `## TITLE` (each `- ` line with the indented lines under it)
/// that hold no finding marker, by their first line; an error when the section or its bullets
/// are missing.
fn bullets_without_finding(text: &str, title: &str) -> Result<Vec<String>, String> {
    let heading = format!("## {title}");
    let section: Vec<&str> = text
        .lines()
        .skip_while(|l| l.trim_end() != heading)
        .skip(1)
        .take_while(|l| !l.starts_with("## "))
        .collect();
    let mut bullets: Vec<(String, String)> = Vec::new();
    for line in section {
        if let Some(first) = line.strip_prefix("- ") {
            bullets.push((first.to_string(), line.to_string()));
        } else if let Some((_, body)) = bullets.last_mut().filter(|_| line.starts_with(' ')) {
            body.push('\n');
            body.push_str(line);
        } else if !line.trim().is_empty() && !bullets.is_empty() {
            break;
        }
    }
    if bullets.is_empty() {
        return Err(format!("no section `{heading}` with bullets"));
    }
    Ok(bullets
        .into_iter()
        .filter(|(_, body)| !body.contains(FINDING_OPEN))
        .map(|(first, _)| first)
        .collect())
}

/// Every finding marker of every doc holds against its CSV, and every bullet of the README's
/// "What we found" carries at least one.
#[test]
fn findings_hold() {
    let mut failures = Vec::new();
    let mut total = 0;
    for doc in doc_files() {
        let text = read_doc(&doc);
        let (n, f) = check_findings(&doc, &text, &mut read_csv);
        total += n;
        failures.extend(f);
    }
    match bullets_without_finding(&read_doc("README.md"), "What we found") {
        Ok(bare) => failures.extend(bare.into_iter().map(|b| {
            format!("README.md, What we found: a finding without `{FINDING_OPEN} PATH: CONDITION -->`: {b}")
        })),
        Err(e) => failures.push(format!("README.md: {e}")),
    }
    println!("{total} findings checked");
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// A finding that the CSV supports passes; one it contradicts fails naming doc, line, the
/// comparison and its values; a README bullet without a marker is named.
#[test]
fn a_wrong_finding_fails() {
    let csv_text = "reading,mse_ours,mse_paper\nbracket-sq,5.4e-5,2.0e-4\n\
                    bracket-2x,1.4e-5,9.0e-2\nliteral,3.8e-4,2.4e-2\n";
    let mut load = |rel: &str| parse_csv(rel, csv_text);
    let right = "Refitted, bracket-2x fits best<!-- ? t.csv: mse_ours[reading=bracket-2x] ==\n\
                 min(mse_ours) && 100 * mse_paper[reading=bracket-sq] < mse_paper[reading=literal] -->.\n";
    assert_eq!(check_findings("doc.md", right, &mut load), (1, Vec::new()));

    let wrong = "Intro.\n\nThe literal reading is worst either way<!-- ? t.csv:\n\
                 mse_ours[reading=literal] == max(mse_ours) &&\n\
                 mse_paper[reading=literal] == max(mse_paper) -->.\n";
    let (n, failures) = check_findings("doc.md", wrong, &mut load);
    assert_eq!(n, 1);
    assert_eq!(failures.len(), 1, "{failures:?}");
    let f = &failures[0];
    for part in [
        "doc.md:3:",
        "t.csv",
        "`mse_paper[reading=literal] == max(mse_paper)` is false",
        "0.024 == 0.09",
    ] {
        assert!(f.contains(part), "`{part}` missing from: {f}");
    }

    let (_, failures) = check_findings("doc.md", "x<!-- ? t.csv: mse_ours -->", &mut load);
    assert!(failures[0].contains("no comparison"), "{failures:?}");

    let readme = "# r\n\n## What we found\n\n- A finding<!-- ? t.csv: 1 < 2 -->, on\n  two lines.\n\
                  - Another, unmarked,\n  on two lines.\n\nMore text.\n\n## Next\n\n- not a finding\n";
    assert_eq!(
        bullets_without_finding(readme, "What we found").unwrap(),
        vec!["Another, unmarked,".to_string()]
    );
    assert!(bullets_without_finding("# r\n", "What we found").is_err());
}

/// `PATH#anchor` reads the first table under that heading of a Markdown file as a CSV.
#[test]
fn a_markdown_table_is_a_csv() {
    let doc = "# Log\n\n## Current values\n\nText.\n\n| what | time |\n|---|---|\n\
               | `make test`, clean clone | 5 min 27 s |\n| `make stale` | 6 min 48 s |\n\n\
               ## Current values\n\n| what | time |\n|---|---|\n| x | 1 s |\n";
    let csv = markdown_table("p.md#current-values", doc, "current-values").unwrap();
    assert_eq!(csv.header, ["what", "time"]);
    let all: Vec<&Vec<String>> = csv.rows.iter().collect();
    assert_eq!(
        render(&csv, &all, r#"{time[what="`make test`, clean*"]:v}"#).unwrap(),
        "5 min 27 s"
    );
    let second = markdown_table("p.md", doc, "current-values-1").unwrap();
    assert_eq!(second.rows, [["x", "1 s"]]);
    assert!(markdown_table("p.md", doc, "nothing").is_err());
}

/// The bytes of a doc that a reader sees: its text less the HTML comments (the markers, which
/// rendered Markdown does not show).
fn visible_bytes(text: &str) -> usize {
    let mut rest = text;
    let mut bytes = 0;
    while let Some(open) = rest.find("<!--") {
        bytes += open;
        rest = match rest[open..].find("-->") {
            Some(close) => &rest[open + close + 3..],
            None => "",
        };
    }
    bytes + rest.len()
}

#[test]
fn readme_is_a_first_page() {
    let bytes = visible_bytes(&read_doc("README.md"));
    println!("README.md: {bytes} bytes without its HTML comments (at most {README_MAX_BYTES})");
    assert!(
        bytes <= README_MAX_BYTES,
        "README.md is {bytes} bytes without its HTML comments, more than {README_MAX_BYTES}"
    );
    assert_eq!(
        visible_bytes("ab<!-- = x: {y:v} -->c<!-- ? x: 1 < 2 -->"),
        3
    );
    assert_eq!(visible_bytes("a<!-- unclosed"), 1);
}

/// Targets of `[text](target)` and `![alt](target)`, outside code spans and fenced blocks.
fn link_targets(text: &str) -> Vec<(usize, String)> {
    let mut targets = Vec::new();
    let mut fenced = false;
    for (n, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        // Drop code spans so that `a](b)` in code is not read as a link.
        let prose: String = line
            .split('`')
            .enumerate()
            .filter(|(i, _)| i % 2 == 0)
            .map(|(_, s)| s)
            .collect::<Vec<_>>()
            .join(" ");
        let mut rest = prose.as_str();
        while let Some(at) = rest.find("](") {
            let after = &rest[at + 2..];
            let Some(end) = after.find(')') else { break };
            targets.push((n + 1, after[..end].trim().to_string()));
            rest = &after[end + 1..];
        }
    }
    targets
}

/// One relative link of a doc: the doc, its folder, the line and the target (its first word; web
/// and mail links left out).
struct RelativeLink<'a> {
    doc: &'a str,
    base: &'a Path,
    line: usize,
    target: &'a str,
}

/// Calls `check` on every relative link of every doc.
fn for_each_relative_link(mut check: impl FnMut(RelativeLink<'_>)) {
    for doc in doc_files() {
        let text = read_doc(&doc);
        let base = Path::new(&doc).parent().unwrap_or(Path::new(""));
        for (line, target) in link_targets(&text) {
            let target = target.split_whitespace().next().unwrap_or("");
            if target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            check(RelativeLink {
                doc: &doc,
                base,
                line,
                target,
            });
        }
    }
}

#[test]
fn relative_links_point_to_files() {
    let mut dead = Vec::new();
    let mut count = 0;
    for_each_relative_link(|link| {
        let RelativeLink {
            doc,
            base,
            line,
            target,
        } = link;
        if target.is_empty() || target.starts_with('#') {
            return;
        }
        let path = target.split('#').next().unwrap_or(target);
        count += 1;
        match inside_repo(base, path) {
            Some(p) if root().join(&p).exists() => {}
            Some(_) => dead.push(format!("{doc}:{line}: `{target}` does not exist")),
            None => dead.push(format!("{doc}:{line}: `{target}` leaves the repository")),
        }
    });
    println!("{count} relative links checked");
    assert!(dead.is_empty(), "dead links:\n{}", dead.join("\n"));
}

/// GitHub's anchor for a heading's text: inline markup and HTML comments removed, lower-cased,
/// every character but letters (with their combining marks), digits, `_`, `-` and spaces dropped,
/// each space a `-`.
fn slug(heading: &str) -> String {
    let mut text = heading.to_string();
    while let Some(open) = text.find("<!--") {
        let close = text[open..]
            .find("-->")
            .map_or(text.len(), |c| open + c + 3);
        text.replace_range(open..close, "");
    }
    // A link's target is not part of the heading's text.
    while let Some(at) = text.find("](") {
        let close = text[at..].find(')').map_or(text.len(), |c| at + c + 1);
        text.replace_range(at + 1..close, "");
    }
    text.trim()
        .to_lowercase()
        .chars()
        .filter(|&c| {
            c.is_alphanumeric()
                || matches!(c, '_' | '-' | ' ')
                || ('\u{0300}'..='\u{036f}').contains(&c)
        })
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchor of an ATX heading line (`#` to `######`), given the anchors of the headings above it
/// (a repeated slug gets `-1`, `-2`, … as on GitHub), which it joins; `None` for any other line.
fn heading_slug(line: &str, anchors: &mut BTreeSet<String>) -> Option<String> {
    let hashes = line.chars().take_while(|&c| c == '#').count();
    if hashes == 0 || hashes > 6 || !line[hashes..].starts_with(' ') {
        return None;
    }
    let title = line[hashes..].trim().trim_end_matches('#').trim_end();
    let base = slug(title);
    let mut candidate = base.clone();
    let mut n = 0;
    while anchors.contains(&candidate) {
        n += 1;
        candidate = format!("{base}-{n}");
    }
    anchors.insert(candidate.clone());
    Some(candidate)
}

/// The anchors of a doc's ATX headings (outside fenced blocks).
fn heading_anchors(text: &str) -> BTreeSet<String> {
    let mut anchors = BTreeSet::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if !fenced {
            heading_slug(line, &mut anchors);
        }
    }
    anchors
}

#[test]
fn slugs_follow_github() {
    assert_eq!(
        slug("Fig. 3 against our finite elements"),
        "fig-3-against-our-finite-elements"
    );
    assert_eq!(
        slug("Hysteresis: what a loading–unloading cycle dissipates"),
        "hysteresis-what-a-loadingunloading-cycle-dissipates"
    );
    assert_eq!(
        slug("The finite-element model (`src/fe/`)"),
        "the-finite-element-model-srcfe"
    );
    assert_eq!(
        slug("2026-11-25: Richardson tier (0366115, a6297e7)"),
        "2026-11-25-richardson-tier-0366115-a6297e7"
    );
    assert_eq!(
        slug("R5. The WNL model (τ_max, p̄)"),
        "r5-the-wnl-model-τ_max-p̄"
    );
    let anchors = heading_anchors("# A\n\n## Notes\n\n```\n# not a heading\n```\n## Notes\n#tag\n");
    let want: BTreeSet<String> = ["a", "notes", "notes-1"].map(String::from).into();
    assert_eq!(anchors, want);
}

/// Every `#anchor` of a relative link names a heading of its target (the same doc for `#anchor`
/// alone), so that a renamed section cannot leave a link that lands at the top of the page.
#[test]
fn anchors_name_headings() {
    let mut dead = Vec::new();
    let mut count = 0;
    for_each_relative_link(|link| {
        let RelativeLink {
            doc,
            base,
            line,
            target,
        } = link;
        let Some((path, anchor)) = target.split_once('#') else {
            return;
        };
        let file = if path.is_empty() {
            PathBuf::from(doc)
        } else {
            match inside_repo(base, path) {
                Some(p) => p,
                None => return, // reported by relative_links_point_to_files
            }
        };
        if file.extension().and_then(|e| e.to_str()) != Some("md") {
            dead.push(format!(
                "{doc}:{line}: `{target}`: an anchor into a file that is not Markdown"
            ));
            return;
        }
        count += 1;
        let Ok(target_text) = fs::read_to_string(root().join(&file)) else {
            dead.push(format!(
                "{doc}:{line}: `{target}`: {} not readable",
                file.display()
            ));
            return;
        };
        if !heading_anchors(&target_text).contains(anchor) {
            dead.push(format!(
                "{doc}:{line}: `{target}`: {} has no heading whose anchor is `#{anchor}`",
                file.display()
            ));
        }
    });
    println!("{count} anchors checked");
    assert!(dead.is_empty(), "dead anchors:\n{}", dead.join("\n"));
}

/// A quoted filter value keeps its commas; unquoted ones split.
#[test]
fn quoted_filter_values_hold_commas() {
    let f = parse_filter(r#"profile="1:0.1,8:0.05",tau_max_mpa=0"#).unwrap();
    assert_eq!(
        f,
        vec![
            ("profile".to_string(), "1:0.1,8:0.05".to_string()),
            ("tau_max_mpa".to_string(), "0".to_string())
        ]
    );
    assert_eq!(parse_filter("a=1,b=2").unwrap().len(), 2);
}
