# vct: `make demo` renders the embedded Cornell box to vct.png; `make test` runs every test
# (lavapipe, validation on). Both install missing system packages first.
SHELL := /bin/bash
# Outside the clone, so dependencies are built once per machine and shared by its clones.
export CARGO_TARGET_DIR ?= $(HOME)/.cache/vct/target
export XDG_RUNTIME_DIR ?= /tmp
# A stale Mesa shader cache can corrupt images: keep it off for tests and timings.
export MESA_SHADER_CACHE_DISABLE := true

.PHONY: deps demo test
deps:
	@scripts/install-deps.sh

demo: deps
	cargo run --quiet --bin vct -- render --out vct.png

test: deps
	VCT_VALIDATION=1 cargo test --no-fail-fast --lib --bins --tests
