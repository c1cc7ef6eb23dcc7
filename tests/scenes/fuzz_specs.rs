//! Specs mutated at random from the committed ones (numbers, strings, lines, bytes) go through
//! the parser and validator: nothing panics, every rejection names the file and the field (or
//! says the document itself is malformed), and a rejected spec run by the binary exits 2 and
//! writes nothing.
//!
//! Case counts: `WAVY_FUZZ_CASES` (default 10 000 mutations; `make fuzz` sets 1 000 000).

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestCaseError, TestRunner};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use wavy::runner::Spec;
use wavy::spec::SpecError;

fn cases() -> u32 {
    std::env::var("WAVY_FUZZ_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(10_000)
}

/// A fixed seed (reproducible runs) unless `WAVY_FUZZ_SEED` names another.
fn seed() -> RngSeed {
    RngSeed::Fixed(
        std::env::var("WAVY_FUZZ_SEED")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(0x5eed),
    )
}

fn committed_specs() -> Vec<(String, String)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("experiments");
    let mut specs: Vec<(String, String)> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| {
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                std::fs::read_to_string(&p).unwrap(),
            )
        })
        .collect();
    specs.sort();
    assert!(specs.len() >= 5);
    specs
}

/// Values that break ranges, types and syntax.
const NASTY: &[&str] = &[
    "-1",
    "0",
    "-0.0",
    "1e308",
    "-1e-3",
    "nan",
    "inf",
    "-inf",
    "0.5",
    "0.4999999",
    "1e-320",
    "100001",
    "2",
    "\"x\"",
    "\"\"",
    "[]",
    "[1, 2",
    "{}",
    "true",
    "18446744073709551616",
    "\"coarse\"",
    "\"3\"",
    "\"2049\"",
    "\"fine\"",
    "\"linear\"",
    "\"nonsense\"",
    "[0.1, -0.2]",
    "{ min = 0.3, max = 0.1, count = 5 }",
    "{ min = 0, max = 1, count = 1 }",
];

/// One random edit of a spec's text.
#[derive(Debug, Clone)]
enum Mutation {
    /// Replace the `n`-th value (right of an `=`) by a nasty one.
    Value(usize, &'static str),
    /// Delete line `n`.
    DeleteLine(usize),
    /// Duplicate line `n`.
    DuplicateLine(usize),
    /// Add an unknown field after line `n`.
    UnknownField(usize),
    /// Cut the text at byte `n` (on a character boundary).
    Truncate(usize),
    /// Insert a character at byte `n`.
    Insert(usize, char),
}

fn apply(text: &str, m: &Mutation) -> String {
    let lines: Vec<&str> = text.lines().collect();
    if lines.is_empty() {
        return format!("{text}x");
    }
    let pick = |n: usize| n % lines.len().max(1);
    let boundary = |n: usize| {
        let mut i = n % (text.len() + 1);
        while !text.is_char_boundary(i) {
            i -= 1;
        }
        i
    };
    match m {
        Mutation::Value(n, v) => {
            let with_value: Vec<usize> = (0..lines.len())
                .filter(|&i| lines[i].contains(" = "))
                .collect();
            let Some(&target) = with_value.get(n % with_value.len().max(1)) else {
                return text.into();
            };
            lines
                .iter()
                .enumerate()
                .map(|(i, l)| {
                    if i == target {
                        let (key, _) = l.split_once(" = ").unwrap();
                        format!("{key} = {v}")
                    } else {
                        l.to_string()
                    }
                })
                .collect::<Vec<_>>()
                .join("\n")
        }
        Mutation::DeleteLine(n) => {
            let k = pick(*n);
            lines
                .iter()
                .enumerate()
                .filter(|(i, _)| *i != k)
                .map(|(_, l)| *l)
                .collect::<Vec<_>>()
                .join("\n")
        }
        Mutation::DuplicateLine(n) => {
            let k = pick(*n);
            let mut v: Vec<&str> = lines.clone();
            v.insert(k, lines[k]);
            v.join("\n")
        }
        Mutation::UnknownField(n) => {
            let k = pick(*n);
            let mut v: Vec<&str> = lines.clone();
            v.insert(k + 1, "surprise_field = 1");
            v.join("\n")
        }
        Mutation::Truncate(n) => text[..boundary(*n)].to_string(),
        Mutation::Insert(n, c) => {
            let i = boundary(*n);
            format!("{}{c}{}", &text[..i], &text[i..])
        }
    }
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<usize>(), prop::sample::select(NASTY)).prop_map(|(n, v)| Mutation::Value(n, v)),
        1 => any::<usize>().prop_map(Mutation::DeleteLine),
        1 => any::<usize>().prop_map(Mutation::DuplicateLine),
        1 => any::<usize>().prop_map(Mutation::UnknownField),
        1 => any::<usize>().prop_map(Mutation::Truncate),
        1 => (any::<usize>(), prop::sample::select(vec!['[', ']', '"', '=', '\n', '#', 'é', '\u{0}'])).prop_map(|(n, c)| Mutation::Insert(n, c)),
    ]
}

/// The rejection names the file and a field (`(document)` for text that is not TOML,
/// `(top level)` / `(scene table)` for the whole file).
fn names_file_and_field(e: &SpecError, origin: &str) -> bool {
    let text = e.to_string();
    text.starts_with(&format!("{origin}: ")) && text.contains("field `")
}

#[test]
fn mutated_specs_are_accepted_or_rejected_with_file_and_field() {
    let specs = committed_specs();
    let (accepted, rejected) = (AtomicUsize::new(0), AtomicUsize::new(0));
    let mut runner = TestRunner::new(Config {
        cases: cases(),
        failure_persistence: None,
        rng_seed: seed(),
        ..Config::default()
    });
    runner
        .run(
            &(0..specs.len(), prop::collection::vec(mutation(), 1..4)),
            |(which, ms)| {
                let (name, text) = &specs[which];
                let mutated = ms.iter().fold(text.clone(), |t, m| apply(&t, m));
                let origin = format!("fuzz/{name}");
                match Spec::parse(&mutated, &origin) {
                    Ok(_) => {
                        accepted.fetch_add(1, Ordering::Relaxed);
                    }
                    Err(e) => {
                        rejected.fetch_add(1, Ordering::Relaxed);
                        if !names_file_and_field(&e, &origin) {
                            return Err(TestCaseError::fail(format!(
                                "rejection without file and field: {e}\n--- spec ---\n{mutated}"
                            )));
                        }
                        if e.to_string().len() > 4000 {
                            return Err(TestCaseError::fail(format!(
                                "message of {} bytes",
                                e.to_string().len()
                            )));
                        }
                    }
                }
                Ok(())
            },
        )
        .unwrap();
    let (a, r) = (accepted.into_inner(), rejected.into_inner());
    println!("{} mutated specs: {a} accepted, {r} rejected", a + r);
    assert!(r > a / 10, "the mutations should mostly break something");
}

/// A sample of rejected mutations run through the binary: exit 2, nothing written.
#[test]
fn rejected_specs_exit_2_and_write_nothing() {
    let specs = committed_specs();
    let mut runner = TestRunner::new(Config {
        cases: 200,
        failure_persistence: None,
        rng_seed: seed(),
        ..Config::default()
    });
    let ran = AtomicUsize::new(0);
    runner
        .run(&(0..specs.len(), mutation()), |(which, m)| {
            let (name, text) = &specs[which];
            let mutated = apply(text, &m);
            if Spec::parse(&mutated, name).is_ok() {
                return Ok(());
            }
            ran.fetch_add(1, Ordering::Relaxed);
            let dir = tempfile::tempdir().unwrap();
            let spec = dir.path().join(name);
            std::fs::write(&spec, &mutated).unwrap();
            let o = std::process::Command::new(env!("CARGO_BIN_EXE_wavy"))
                .args(["run", name, "--out", "out", "--cache", "cache"])
                .current_dir(dir.path())
                .output()
                .unwrap();
            prop_assert_eq!(
                o.status.code(),
                Some(2),
                "{}",
                String::from_utf8_lossy(&o.stderr)
            );
            prop_assert!(o.stdout.is_empty());
            let left: Vec<_> = std::fs::read_dir(dir.path())
                .unwrap()
                .flatten()
                .map(|e| e.file_name())
                .collect();
            prop_assert_eq!(left.len(), 1, "only the spec: {:?}", left);
            Ok(())
        })
        .unwrap();
    println!("{} rejected specs run by the binary", ran.into_inner());
}
