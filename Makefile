# wavy — every figure and number from experiments/*.toml.
# `make reproduce` needs cargo (the toolchain is pinned in rust-toolchain.toml; crates come from crates.io);
# `make test` also needs python3 with its venv module (the Python package's tests install the tools pinned in
# python/requirements-test.txt from PyPI into target/python-venv).

CARGO ?= cargo
export CARGO_TERM_COLOR ?= never

.PHONY: all reproduce test python-test lint fmt-check clippy check bless stale bench bench-solver bench-tiers reference robustness mesh-study fuzz clean

all: reproduce

## Rebuild every figure (figures/*.svg) and the numbers behind it (figures/*.csv).
## The first run compiles first (cargo shows its progress); times in docs/performance.md.
reproduce:
	$(CARGO) build --release --locked
	$(CARGO) run --release --locked --quiet -- reproduce

## Every test (release mode: the finite-element tests need it), after formatting and lints; then the
## Python package's tests. `--tests`: the library's and the binary's unit tests and the integration tests
## (tests/<concern>/main.rs, one binary per concern); the examples and benches are compiled by clippy in
## `lint`, and the crate has no doctests (its code blocks are `text`). The tests, the binary and the wheel
## share one release build (Cargo.toml, "One build"; docs/performance.md).
test: lint
	INSTA_UPDATE=no $(CARGO) test --release --locked --tests
	$(MAKE) --no-print-directory python-test

## The Python package (python/, docs/python.md): a virtual environment in target/ with the tools of
## python/requirements-test.txt from PyPI (maturin, pytest, numpy, pandas for Result.to_pandas, numpydoc
## for the docstring checks, dask[distributed] for the sweep on a LocalCluster), the wheel built
## (release, reusing target/) and installed, then pytest, which compares the package
## with the binary built here. Exit 5 (no tests collected) fails like any other.
PYTHON ?= python3
VENV ?= target/python-venv
python-test:
	$(CARGO) build --release --locked
	test -x $(VENV)/bin/python || $(PYTHON) -m venv $(VENV)
	$(VENV)/bin/python -m pip install --quiet --disable-pip-version-check -r python/requirements-test.txt
	PATH="$(CURDIR)/$(VENV)/bin:$$PATH" $(VENV)/bin/python -m pip install --quiet --disable-pip-version-check --no-build-isolation --force-reinstall --no-deps ./python
	cd python/tests && ../../$(VENV)/bin/python -m pytest -q -p no:cacheprovider

## Formatting of every Rust file git tracks (rustfmt on each file too, so that no module escapes
## `cargo fmt`; an untracked scratch file is not the project's), then clippy over every target of the
## workspace, the Python bindings included.
RUST_FILES = $(shell git ls-files '*.rs' 2>/dev/null || find src tests benches examples python/src -name '*.rs')
lint: fmt-check clippy

fmt-check:
	$(CARGO) fmt --all --check
	@echo 'rustfmt --check --edition 2021 <every Rust file git tracks>'
	@rustfmt --check --edition 2021 $(RUST_FILES)

clippy:
	$(CARGO) clippy --release --locked --workspace --all-targets --quiet -- -D warnings

## Recompute every spec and compare with expected/ within each spec's [check] tolerances.
check:
	$(CARGO) run --release --locked --quiet -- check

## Accept an intended change of results in one command: figures, expected/ (golden numbers), the
## refit coefficient sets (generated from expected/table1_refit.csv at build time, so a second
## pass draws Fig. 3 with the new refit) and the snapshots; then list what changed. Review it with
## `wavy diff --base HEAD` (review/summary.md) before committing.
bless:
	$(CARGO) build --release --locked
	$(CARGO) run --release --locked --quiet -- reproduce
	cp figures/*.csv expected/
	$(CARGO) run --release --locked --quiet -- reproduce
	cp figures/*.csv expected/
	INSTA_UPDATE=always $(CARGO) test --release --locked --test scenes
	@echo "changed by bless:"; git status --short -- figures expected tests/snapshots

## Fails, naming the files, when a committed figure or golden table is not what the code computes now,
## or when no spec produces it any more (CI runs it after make test). reproduce's "wrote …" lines, kept in
## target/reproduce.out, are what the specs produce.
stale:
	$(CARGO) build --release --locked
	$(CARGO) run --release --locked --quiet -- reproduce > target/reproduce.out
	@cat target/reproduce.out
	@bash .ci/stale-figures target/reproduce.out

## The frictional-speed table (docs/performance.md): per default-mesh curve the median wall time of 3 runs,
## DOFs, load steps, Newton iterations, factorisations; frictional/frictionless ratio per AR; the Fig. 3 sweep from
## an empty cache on all cores; the cost growth from mesh 16 to 192 with its exponent and peak memory
## (BENCH_MAX_MESH=128 leaves out the slow mesh-192 curves; its duration: docs/performance.md). Then the criterion
## medians of the model laws.
BENCH_MAX_MESH ?= 192
bench:
	$(CARGO) build --release --locked
	$(CARGO) run --release --locked --quiet --example speed_table -- --wavy target/release/wavy --max-mesh $(BENCH_MAX_MESH)
	$(CARGO) bench --locked --bench models
	$(CARGO) run --release --locked --quiet --example bench_medians

## Criterion medians of whole solver curves per mesh level (duration: docs/performance.md).
bench-solver:
	$(CARGO) bench --locked --bench solver
	$(CARGO) run --release --locked --quiet --example bench_medians

## Wall time of every tier of experiments/speed_accuracy.toml (one thread, median of 3 runs), written
## to experiments/data/speed_accuracy_timings.csv, the cost axis of figures/speed_accuracy.svg
## (duration: docs/performance.md; run it on an otherwise idle machine, then `make reproduce` and commit both).
bench-tiers:
	$(CARGO) build --release --locked
	$(CARGO) run --release --locked --quiet -- time-tiers

## The converged reference of experiments/speed_accuracy.toml: every case on its reference_meshes (up to
## 192 elements along the face, on all cores), the limit p0 + c1/n + c2/n^2 per a/λ, written to
## experiments/data/speed_accuracy_reference.csv (docs/replication.md R11; duration: docs/performance.md).
## Rerun it, then `make bless`, when a physics default changes: the scene refuses a file of other physics.
reference:
	$(CARGO) build --release --locked
	$(CARGO) run --release --locked --quiet -- refine-reference

## The robustness grid (issue 42, goal 6): AR × μ × τ_max loaded to a/λ 0.45 and unloaded at each mesh of
## ROBUSTNESS_MESHES and τ_max of ROBUSTNESS_TAUS (MPa), one case per core, each stopped after ROBUSTNESS_TIMEOUT_S seconds, written to
## ROBUSTNESS_CSV, by default experiments/data/robustness_grid.csv (table and duration:
## docs/verification.md, "Robustness grid"; the cheap meshes of its test went to
## experiments/data/robustness_grid_cheap.csv).
ROBUSTNESS_MESHES ?= 48,96,160
ROBUSTNESS_TAUS ?= 0,0.05,0.1,0.2,0.3
ROBUSTNESS_TIMEOUT_S ?= 1200
ROBUSTNESS_CSV ?= experiments/data/robustness_grid.csv
robustness:
	$(CARGO) build --release --locked
	$(CARGO) run --release --locked --quiet --example robustness_grid -- --wavy target/release/wavy --mesh $(ROBUSTNESS_MESHES) --tau-max-mpa $(ROBUSTNESS_TAUS) --timeout-s $(ROBUSTNESS_TIMEOUT_S) > $(ROBUSTNESS_CSV).tmp
	mv $(ROBUSTNESS_CSV).tmp $(ROBUSTNESS_CSV)

## A mesh study, one curve per core (docs/replication.md R11, "Friction on fine meshes"; docs/performance.md):
## each case AR:τ_max[:finest mesh] of MESH_STUDY_CASES on the meshes of MESH_STUDY_MESHES, its curves kept in
## .wavy-tmp/mesh_study (a curve there is read, not solved again), the summary written to MESH_STUDY_CSV.
MESH_STUDY_CASES ?= 0.3:0.1,0.3:0.2,0.18:0.1,0.18:0.2,0.3:0:192,0.18:0:192
MESH_STUDY_MESHES ?= 48,64,96,128,160,192,256,320
MESH_STUDY_LIMIT_MESHES ?= 64,96,128,160,192,256
MESH_STUDY_TIMEOUT_S ?= 450
MESH_STUDY_CSV ?= experiments/data/mesh_study.csv
mesh-study:
	$(CARGO) build --release --locked
	$(CARGO) run --release --locked --quiet --example mesh_study -- --wavy target/release/wavy --cases $(MESH_STUDY_CASES) --mesh $(MESH_STUDY_MESHES) --limit-meshes $(MESH_STUDY_LIMIT_MESHES) --timeout-s $(MESH_STUDY_TIMEOUT_S) > $(MESH_STUDY_CSV).tmp
	mv $(MESH_STUDY_CSV).tmp $(MESH_STUDY_CSV)

## The property and fuzz suites with 10⁶ cases each (make test runs 10⁴); WAVY_FUZZ_SEED picks another seed.
fuzz:
	WAVY_FUZZ_CASES=1000000 $(CARGO) test --release --locked --test models --test scenes -- --nocapture extremes_models fuzz_specs
	WAVY_FUZZ_CASES=1000000 $(CARGO) test --release --locked --bin wavy -- --nocapture

clean:
	$(CARGO) clean
