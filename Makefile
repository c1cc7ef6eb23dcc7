# wavy — every figure and number from experiments/*.toml.
# Needs only cargo (the toolchain is pinned in rust-toolchain.toml); crates come from crates.io.

CARGO ?= cargo
export CARGO_TERM_COLOR ?= never

.PHONY: all reproduce test lint check bless bench fuzz clean

all: reproduce

## Rebuild every figure (figures/*.svg) and the numbers behind it (figures/*.csv).
reproduce:
	$(CARGO) run --release --locked --quiet -- reproduce

## Every test (release mode: the finite-element tests need it), after formatting and lints.
test: lint
	INSTA_UPDATE=no $(CARGO) test --release --locked

lint:
	$(CARGO) fmt --check
	$(CARGO) clippy --release --locked --all-targets --quiet -- -D warnings

## Recompute every spec and compare with expected/ within each spec's [check] tolerances.
check:
	$(CARGO) run --release --locked --quiet -- check

## Accept the current numbers as golden: copy figures/*.csv into expected/ (review the diff!).
bless: reproduce
	cp figures/*.csv expected/

## Timings (medians) of the solver and the model laws.
bench:
	$(CARGO) bench --locked
	$(CARGO) run --release --locked --quiet --example bench_medians

## The property and fuzz suites with 10⁶ cases each (make test runs 10⁴); WAVY_FUZZ_SEED picks another seed.
fuzz:
	WAVY_FUZZ_CASES=1000000 $(CARGO) test --release --locked --test extremes_models --test fuzz_specs -- --nocapture
	WAVY_FUZZ_CASES=1000000 $(CARGO) test --release --locked --bin wavy -- --nocapture

clean:
	$(CARGO) clean
