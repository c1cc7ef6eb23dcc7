//! The shape docs/architecture.md promises of `src/`: no two files import each other, directly or
//! through others (an import circle), and no file is longer than [`MAX_LINES`].
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
