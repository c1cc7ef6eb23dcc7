//! The shape docs/architecture.md promises of `src/`: no two files import each other, directly or
//! through others (an import circle), no file is longer than [`MAX_LINES`] and no function longer
//! than [`MAX_FUNCTION_LINES`].
//!
//! A file's imports are the `crate::…` and `super::…` paths in its code (comments and its
//! `#[cfg(test)]` part left out), each resolved to the longest module path that is a file of the
//! crate (`src/a/b.rs` is `a::b`, `src/a/mod.rs` is `a`).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The largest source file, in lines: one concept per file, read in one sitting.
const MAX_LINES: usize = 600;

type ModulePath = Vec<String>;

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Every `.rs` file under `src/` with its module path (`lib.rs` and `main.rs` are the root).
fn modules() -> BTreeMap<ModulePath, PathBuf> {
    let mut out = BTreeMap::new();
    let mut stack = vec![src()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("src/ is readable").flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            if path.extension().is_none_or(|x| x != "rs") {
                continue;
            }
            let relative = path
                .strip_prefix(src())
                .expect("under src/")
                .with_extension("");
            let mut module: ModulePath = relative
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            if module.last().is_some_and(|m| m == "mod") {
                module.pop();
            }
            if module == ["lib"] || module == ["main"] {
                module.clear();
            }
            out.insert(module, path);
        }
    }
    out
}

/// The code of a file: comments stripped, its `#[cfg(test)]` part (the tests module at its
/// end) left out.
fn code_of(path: &Path) -> String {
    let text = std::fs::read_to_string(path).expect("a readable source file");
    let mut code = String::new();
    for line in text.lines() {
        if line.trim_start().starts_with("#[cfg(test)]") {
            break;
        }
        code.push_str(line.split("//").next().unwrap_or(""));
        code.push('\n');
    }
    code
}

/// The paths a file names after `crate::` or `super::`, as segments relative to the crate
/// root; a group `a::{b, c::d}` gives one path per item.
fn referenced_paths(code: &str, module: &ModulePath) -> Vec<ModulePath> {
    // `super` is the parent module: `a` from `a/b.rs` (module a::b), the root from `a/mod.rs`
    // (module a)
    let parent: ModulePath = module[..module.len().saturating_sub(1)].to_vec();
    let mut paths = Vec::new();
    for (prefix, base) in [("crate::", Vec::new()), ("super::", parent)] {
        let mut rest = code;
        while let Some(i) = rest.find(prefix) {
            let before = rest[..i].chars().last();
            rest = &rest[i + prefix.len()..];
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
                continue;
            }
            let end = rest
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':' || c == '{'))
                .unwrap_or(rest.len());
            let head = &rest[..end];
            let mut segments = base.clone();
            let (stem, group) = match head.find('{') {
                Some(j) => (&head[..j], Some(&rest[j + 1..])),
                None => (head, None),
            };
            segments.extend(
                stem.split("::")
                    .filter(|s| !s.is_empty() && *s != "super")
                    .map(str::to_owned),
            );
            match group {
                Some(group) => {
                    let group = group.split('}').next().unwrap_or("");
                    for item in group.split(',') {
                        let mut path = segments.clone();
                        path.extend(
                            item.trim()
                                .split("::")
                                .filter(|s| !s.is_empty())
                                .map(str::to_owned),
                        );
                        paths.push(path);
                    }
                }
                None => paths.push(segments),
            }
        }
    }
    paths
}

/// The longest prefix of `path` that is a module of the crate.
fn resolve<'a>(
    path: &ModulePath,
    modules: &'a BTreeMap<ModulePath, PathBuf>,
) -> Option<&'a ModulePath> {
    (1..=path.len())
        .rev()
        .find_map(|k| modules.get_key_value(&path[..k]).map(|(m, _)| m))
}

/// Which files each file imports.
fn import_graph() -> BTreeMap<ModulePath, BTreeSet<ModulePath>> {
    let modules = modules();
    let mut graph = BTreeMap::new();
    for (module, path) in &modules {
        let imports = referenced_paths(&code_of(path), module)
            .iter()
            .filter_map(|p| resolve(p, &modules))
            .filter(|m| *m != module)
            .cloned()
            .collect();
        graph.insert(module.clone(), imports);
    }
    graph
}

/// The files reachable from `start` through imports.
fn reachable(
    graph: &BTreeMap<ModulePath, BTreeSet<ModulePath>>,
    start: &ModulePath,
) -> BTreeSet<ModulePath> {
    let mut seen = BTreeSet::new();
    let mut stack: Vec<&ModulePath> = graph[start].iter().collect();
    while let Some(m) = stack.pop() {
        if seen.insert(m.clone()) {
            stack.extend(graph.get(m).into_iter().flatten());
        }
    }
    seen
}

#[test]
fn no_file_imports_a_file_that_imports_it_back() {
    let graph = import_graph();
    let circles: Vec<String> = graph
        .keys()
        .filter(|m| reachable(&graph, m).contains(*m))
        .map(|m| m.join("::"))
        .collect();
    assert!(circles.is_empty(), "files on an import circle: {circles:?}");
}

/// The check itself: two files that import each other are found.
#[test]
fn a_circle_is_found() {
    let module = |s: &str| -> ModulePath { s.split("::").map(str::to_owned).collect() };
    let a = referenced_paths("use super::b::Thing;\n", &module("fe::a"));
    let b = referenced_paths("use crate::fe::{a::run, c};\n", &module("fe::b"));
    let mut modules = BTreeMap::new();
    for m in ["fe", "fe::a", "fe::b", "fe::c"] {
        modules.insert(module(m), PathBuf::new());
    }
    let resolved = |paths: &[ModulePath]| -> BTreeSet<ModulePath> {
        paths
            .iter()
            .filter_map(|p| resolve(p, &modules))
            .cloned()
            .collect()
    };
    let mut graph = BTreeMap::new();
    graph.insert(module("fe::a"), resolved(&a));
    graph.insert(module("fe::b"), resolved(&b));
    graph.insert(module("fe::c"), BTreeSet::new());
    graph.insert(module("fe"), BTreeSet::new());
    assert!(graph[&module("fe::b")].contains(&module("fe::c")));
    assert!(reachable(&graph, &module("fe::a")).contains(&module("fe::a")));
    assert!(!reachable(&graph, &module("fe::c")).contains(&module("fe::c")));
}

#[test]
fn no_source_file_is_longer_than_the_bound() {
    let long: Vec<String> = modules()
        .values()
        .filter_map(|path| {
            let lines = std::fs::read_to_string(path)
                .expect("readable")
                .lines()
                .count();
            (lines > MAX_LINES).then(|| format!("{} ({lines} lines)", path.display()))
        })
        .collect();
    assert!(long.is_empty(), "longer than {MAX_LINES} lines: {long:?}");
}

/// The longest function, in lines from its `fn` line to its closing brace: a function longer
/// than this is to be split into named steps.
const MAX_FUNCTION_LINES: usize = 120;

/// A function of a source file: its name, the line of its `fn` (from 1) and its length in lines.
#[derive(Debug, PartialEq)]
struct FunctionSpan {
    name: String,
    line: usize,
    lines: usize,
}

/// The name of the function a line declares: the line is blanks, then optionally
/// `pub`/`pub(…)`, `const`, `async`, `unsafe` (in that order, each followed by blanks), then
/// `fn`, blanks and the name.
fn declared_function(line: &str) -> Option<&str> {
    let word_char = |c: char| c.is_alphanumeric() || c == '_';
    // `keyword` followed by at least one blank, the rest after the blanks
    let keyword = |rest: &'_ str, keyword: &str| -> Option<usize> {
        let after = rest.strip_prefix(keyword)?;
        let blanks = after.len() - after.trim_start().len();
        (blanks > 0).then_some(rest.len() - after.len() + blanks)
    };
    let mut rest = line.trim_start();
    if let Some(after) = rest.strip_prefix("pub") {
        let after = match after.strip_prefix('(') {
            Some(inner) => inner.find(')').map(|k| &inner[k + 1..]),
            None => Some(after),
        };
        if let Some(after) = after {
            let trimmed = after.trim_start();
            if trimmed.len() < after.len() {
                rest = trimmed;
            }
        }
    }
    for k in ["const", "async", "unsafe"] {
        if let Some(skip) = keyword(rest, k) {
            rest = &rest[skip..];
        }
    }
    let rest = &rest[keyword(rest, "fn")?..];
    let end = rest.find(|c: char| !word_char(c)).unwrap_or(rest.len());
    (end > 0).then_some(&rest[..end])
}

/// A line's code for brace counting: the text before its first `//`, every string literal
/// `"…"` (with `\` escapes) replaced by `""`.
fn brace_code(line: &str) -> String {
    let chars: Vec<char> = line.split("//").next().unwrap_or("").chars().collect();
    let mut out = String::new();
    let mut k = 0;
    while k < chars.len() {
        if chars[k] == '"' {
            // the closing quote of a literal opened here, if any
            let mut m = k + 1;
            let close = loop {
                match chars.get(m) {
                    None => break None,
                    Some('"') => break Some(m),
                    Some('\\') if m + 1 < chars.len() => m += 2,
                    Some('\\') => break None,
                    Some(_) => m += 1,
                }
            };
            if let Some(close) = close {
                out.push_str("\"\"");
                k = close + 1;
                continue;
            }
        }
        out.push(chars[k]);
        k += 1;
    }
    out
}

/// The functions of a source text and their lengths, by brace counting: a function runs from its
/// `fn` line to the line where the braces opened since it close again (counted outside
/// comments and string literals); a declaration that ends in `;` before any brace has no body.
/// A function inside another is part of it, not counted apart, and the text from the first
/// `#[cfg(test)]` line on (the inline tests module) is left out.
fn function_spans(text: &str) -> Vec<FunctionSpan> {
    let lines: Vec<&str> = text.split('\n').collect();
    let mut spans = vec![];
    let mut i = 0;
    while i < lines.len() {
        if lines[i].trim().starts_with("#[cfg(test)]") {
            break;
        }
        let Some(name) = declared_function(lines[i]) else {
            i += 1;
            continue;
        };
        let (mut depth, mut started, mut j) = (0i64, false, i);
        while j < lines.len() {
            let code = brace_code(lines[j]);
            depth += code.matches('{').count() as i64 - code.matches('}').count() as i64;
            started |= code.contains('{');
            if code.trim_end().ends_with(';') && !started {
                break;
            }
            if started && depth <= 0 {
                spans.push(FunctionSpan {
                    name: name.to_owned(),
                    line: i + 1,
                    lines: j - i + 1,
                });
                break;
            }
            j += 1;
        }
        i = if started { j + 1 } else { i + 1 };
    }
    spans
}

/// Every function of every file under `src/`: its place (`src/…:line`) and span.
fn all_functions() -> Vec<(String, FunctionSpan)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut out = vec![];
    for path in modules().values() {
        let text = std::fs::read_to_string(path).expect("readable");
        let file = path.strip_prefix(root).expect("under the crate").display();
        for span in function_spans(&text) {
            out.push((format!("{file}:{}", span.line), span));
        }
    }
    out
}

#[test]
fn no_function_is_longer_than_the_bound() {
    let long: Vec<String> = all_functions()
        .into_iter()
        .filter(|(_, span)| span.lines > MAX_FUNCTION_LINES)
        .map(|(place, span)| format!("{place} {} ({} lines)", span.name, span.lines))
        .collect();
    assert!(
        long.is_empty(),
        "functions longer than {MAX_FUNCTION_LINES} lines (split them into named steps): {long:#?}"
    );
}

/// The counting itself: braces in strings and comments, nested functions, declarations without
/// a body, multi-line signatures and the tests module.
#[test]
fn function_lengths_are_counted_from_fn_to_closing_brace() {
    let text = r#"
pub(crate) const fn one() -> &'static str {
    "}}" // }
}
trait T {
    fn declared(&self);
    unsafe fn with_default(&self) {}
}
pub async fn outer(
    x: u8,
) {
    fn inner() {
        let _ = "\"{";
    }
}
fn not_fnord() {}
#[cfg(test)]
fn ignored() {}
"#;
    let spans: Vec<(String, usize, usize)> = function_spans(text)
        .into_iter()
        .map(|s| (s.name, s.line, s.lines))
        .collect();
    assert_eq!(
        spans,
        [
            ("one".to_owned(), 2, 3),
            ("with_default".to_owned(), 7, 1),
            ("outer".to_owned(), 9, 7),
            ("not_fnord".to_owned(), 16, 1),
        ]
    );
    assert_eq!(declared_function("    fnord();"), None);
    assert_eq!(declared_function("pub(super) fn f<T>()"), Some("f"));
    assert_eq!(declared_function("pubfn f()"), None);
}
