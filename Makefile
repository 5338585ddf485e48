# NMEA spec generator. `make` generates everything from spec/; `make test` runs every test.
SHELL := /bin/bash
.DEFAULT_GOAL := generate

VENV    := .venv
PY      := $(VENV)/bin/python
STAMP   := $(VENV)/.installed
CC      ?= gcc
CFLAGS  ?= -std=c99 -Wall -Wextra -Werror -pedantic -O2
BIN     := build/bin
TEST_BIN := build/test-bin
CARGO_TARGET := build/rust-target
# The tests build the generated crate once (its default features and std, unoptimized) for its own
# tests, the tests' Rust tool and the fuzz targets' replay: from the fuzz targets' workspace, where
# the crate is a path dependency with std. Cargo keys a path dependency's build by its path from the
# workspace's root, so two workspaces could not share it.
SHARED_RUST := --manifest-path fuzz/rust/Cargo.toml --target-dir $(CARGO_TARGET)

# Python keeps the bytecode it compiles under build/, even where the environment asks it not to
# (PYTHONDONTWRITEBYTECODE=1): a test run starts hundreds of Python processes, and compiling the
# generator, the package and pytest again in each took a fifth of their time.
unexport PYTHONDONTWRITEBYTECODE
export PYTHONPYCACHEPREFIX ?= $(CURDIR)/build/pycache

.PHONY: generate validate check build test-bin footprint release-check changelog test test-quick test-steps system-deps test-runtimes test-generator test-python test-c test-c-memory test-rust test-rust-lint test-tools test-workflows docs-site clean \
        bench test-bench-smoke \
        fuzz fuzz-smoke fuzz-seeds fuzz-c fuzz-c-ubx fuzz-python fuzz-rust fuzz-rust-replay fuzz-inprocess fuzz-differential fuzz-faults fuzz-memory

# --no-compile: Python compiles the modules a run imports as it imports them, not every module ahead.
$(STAMP): requirements.txt
	python3 -m venv $(VENV)
	$(PY) -m pip install --quiet --disable-pip-version-check --no-compile -r requirements.txt
	touch $@

generate: $(STAMP)
	$(PY) -m generator generate

validate: $(STAMP)
	$(PY) -m generator validate

check: $(STAMP)
	$(PY) -m generator check

# --- the three command-line tools -------------------------------------------------------------

build: $(BIN)/nmea-py $(BIN)/nmea-c $(BIN)/nmea-rs

PY_SOURCES   = $(shell find generated/python -name '*.py' 2>/dev/null)
RUST_SOURCES = $(shell find generated/rust -name '*.rs' -o -name Cargo.toml 2>/dev/null)
C_PAIR       := generated/c/nmea.c generated/c/nmea.h
C_AIS        := generated/c/nmea_ais.c generated/c/nmea_ais.h

# The interpreter itself, not a launcher in front of it (pyenv's shims take 0.15 s a call), and
# without site-packages (-S): the package needs nothing beyond the standard library.
PYTHON3 = $(shell python3 -c 'import sys; print(sys.executable)')
$(BIN)/nmea-py $(TEST_BIN)/nmea-py: $(PY_SOURCES)
	@mkdir -p $(@D)
	printf '#!/bin/sh\nPYTHONPATH="%s" exec "%s" -S -m nmeaspec "$$@"\n' "$(CURDIR)/generated/python" "$(PYTHON3)" > $@
	chmod +x $@

$(BIN)/nmea-c: $(C_PAIR) $(C_AIS) generated/c/nmea_ubx.c generated/c/nmea_rtcm3.c generated/c/nmea_tool.c
	@mkdir -p $(BIN)
	$(CC) $(CFLAGS) -o $@ generated/c/nmea.c generated/c/nmea_ais.c generated/c/nmea_ubx.c generated/c/nmea_rtcm3.c generated/c/nmea_tool.c

$(BIN)/nmea-rs: $(RUST_SOURCES)
	@mkdir -p $(BIN)
	cargo build --quiet --profile tools --manifest-path generated/rust/Cargo.toml --features std --bin nmea-rs --target-dir $(CARGO_TARGET)
	cp $(CARGO_TARGET)/tools/nmea-rs $@

# --- the docs as a static HTML site (mkdocs, its built-in search) -----------------------------

DOCS_VENV  := .venv-docs
DOCS_STAMP := $(DOCS_VENV)/.installed

$(DOCS_STAMP): docs/requirements-docs.txt
	python3 -m venv $(DOCS_VENV)
	$(DOCS_VENV)/bin/pip install --quiet --disable-pip-version-check --no-compile -r docs/requirements-docs.txt
	touch $@

docs-site: $(DOCS_STAMP)
	$(DOCS_VENV)/bin/mkdocs build --strict --quiet --config-file mkdocs.yml

# --- tests -----------------------------------------------------------------------------------

# Two at a time (the CI machine has two cores; most steps use one), each step's output kept together.
# tools/system_deps.sh first installs (or names) the system packages the steps need.
# Every Rust crate of the run (the generated one in its configurations, the fuzz targets, the users'
# crates of the workflows) is built once from scratch and only tested: without incremental data,
# debug information and 256 codegen units an unoptimized build of the generated crate takes half
# the CPU (measured: 122 -> 54 s for its library). `make test-rust` alone keeps cargo's defaults.
TEST_CARGO_ENV := CARGO_INCREMENTAL=0 CARGO_PROFILE_DEV_DEBUG=0 CARGO_PROFILE_DEV_CODEGEN_UNITS=16
test: system-deps
	$(TEST_CARGO_ENV) $(MAKE) --no-print-directory -j2 --output-sync=target test-steps

system-deps:
	tools/system_deps.sh

# The longest first, so that the two lanes end together.
test-steps: test-rust test-workflows test-rust-lint test-generator fuzz-smoke test-tools test-c-memory check test-c \
        test-bench-smoke release-check test-runtimes test-python

test-generator: $(STAMP)
	$(PY) -m pytest -q --durations=8 tests/generator

# The edit loop (under two minutes): generated/ up to date, the generator's tests and golden files
# without the ones that build or generate whole copies, the manuals' examples and the AIS codec in Python.
test-quick: $(STAMP)
	$(PY) -m generator check
	$(PY) -m pytest -q -m "not slow" tests/generator
	cd generated/python && ../../$(PY) -m pytest -q tests
	$(PY) -m pytest -q tests/ais tests/ubx tests/rtcm3 tests/shapes tests/export

# The hand-written runtimes on their own, where they live (runtime/README.md): the C runtime's unit
# tests under the sanitizers and without JSON, the Rust runtime crate's tests, clippy and rustfmt
# with and without std, and the Python runtime's tests. Nothing generated is needed.
test-runtimes: $(STAMP)
	@mkdir -p build/c
	$(CC) $(SANITIZE) -o build/c/test_runtime runtime/c/test_runtime.c
	build/c/test_runtime
	$(CC) $(CFLAGS) -DNMEA_NO_JSON -DNMEA_NO_TAG_BLOCKS -DNMEA_DIGITS_32 -o build/c/test_runtime_small runtime/c/test_runtime.c
	build/c/test_runtime_small
	cargo test --quiet --manifest-path runtime/rust/Cargo.toml --features time,chrono --target-dir $(CARGO_TARGET)
	cargo test --quiet --manifest-path runtime/rust/Cargo.toml --no-default-features --target-dir $(CARGO_TARGET)
	cargo clippy --quiet --manifest-path runtime/rust/Cargo.toml --all-targets --features time,chrono --target-dir $(CARGO_TARGET) \
		-- -D warnings
	cargo clippy --quiet --manifest-path runtime/rust/Cargo.toml --all-targets --no-default-features \
		--target-dir $(CARGO_TARGET) -- -D warnings
	cargo fmt --manifest-path runtime/rust/Cargo.toml --check
	$(PY) -m pytest -q runtime/python/tests

test-python: $(STAMP)
	cd generated/python && ../../$(PY) -m pytest -q tests
	$(PY) -m pytest -q tests/ais tests/ubx tests/rtcm3 tests/shapes tests/export

# --- the test builds: each binary built once, shared by the steps that run it -----------------
# nmea.c compiled once per set of flags: the test object (-O2, NMEA_TEST_HOOKS: the programs also
# check every fast-path parse against the general path) for the examples, the tools the tests run
# and valgrind; the sanitized object (clang: AddressSanitizer, UndefinedBehaviorSanitizer and
# libFuzzer's coverage counters) for the examples, the tool over every real log and the C fuzz
# target. The tests' Rust tool is the dev build `cargo test` shares; the tests need answers, not
# speed (`make build` gives the optimized tools).
SANITIZE := -std=c99 -Wall -Wextra -Werror -pedantic -O0 -g -fsanitize=address,undefined -fno-sanitize-recover=all \
            -fno-omit-frame-pointer -DNMEA_TEST_HOOKS
CLANG ?= clang

test-bin: $(TEST_BIN)/nmea-c $(TEST_BIN)/nmea-rs $(TEST_BIN)/nmea-py

build/c/nmea-test.o: $(C_PAIR)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -DNMEA_TEST_HOOKS -c -o $@ generated/c/nmea.c

build/c/test_examples: build/c/nmea-test.o generated/c/tests/test_examples.c
	$(CC) $(CFLAGS) -DNMEA_TEST_HOOKS -o $@ $^

$(TEST_BIN)/nmea-c: build/c/nmea-test.o generated/c/nmea_ais.c generated/c/nmea_ubx.c generated/c/nmea_rtcm3.c generated/c/nmea_tool.c
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -DNMEA_TEST_HOOKS -o $@ $^

$(TEST_BIN)/nmea-rs: $(RUST_SOURCES)
	@mkdir -p $(@D)
	cargo build --quiet $(SHARED_RUST) -p nmeaspec --bin nmea-rs
	cp $(CARGO_TARGET)/debug/nmea-rs $@

# The general path alone, unoptimized (the examples only need answers).
build/c/test_examples_general: $(C_PAIR) generated/c/tests/test_examples.c
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -O0 -DNMEA_NO_FAST_PATH -o $@ generated/c/nmea.c generated/c/tests/test_examples.c

# The smallest build must compile without a warning too (every option a firmware sets for flash).
SMALLEST := -DNMEA_NO_JSON -DNMEA_NO_FAST_PATH -DNMEA_NO_PROBLEMS -DNMEA_TERSE_ERRORS -DNMEA_NO_TAG_BLOCKS -DNMEA_DIGITS_32 \
            -DNMEA_NO_BINARY_FRAMES
build/c/nmea-small.o: $(C_PAIR)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -O0 $(SMALLEST) -c -o $@ generated/c/nmea.c

build/c/nmea-san.o: $(C_PAIR)
	@mkdir -p $(@D)
	$(CLANG) $(SANITIZE) -fsanitize=fuzzer-no-link -c -o $@ generated/c/nmea.c

build/c/test_examples_san: build/c/nmea-san.o generated/c/tests/test_examples.c
	$(CLANG) $(SANITIZE) -o $@ $^

build/c/nmea-c-san: build/c/nmea-san.o generated/c/nmea_ais.c generated/c/nmea_ubx.c generated/c/nmea_rtcm3.c generated/c/nmea_tool.c
	$(CLANG) $(SANITIZE) -o $@ $^

# The five-sentence firmware of issue 32: its subset with the default NMEA_MAX_LINE (the longest
# line those sentences can have) reading a byte stream fed one byte at a time and pushed in chunks of
# every size (tests/c/test_stream.c), under the sanitizers, as it is and in its smallest build.
FIRMWARE_SUBSET := GGA,RMC,GSV,GSA,VTG
build/c/subset/c/nmea.c: $(C_PAIR) $(STAMP)
	$(PY) -m generator generate --quiet --only $(FIRMWARE_SUBSET) --out build/c/subset

# Its small build (-DNMEA_SMALL, at -Os as a firmware builds it; renamed sml_ beside the default
# build of the same subset, the reference) over the shared vectors' lines of the five sentences
# (tests/c/small_lines.py), fed one byte at a time and pushed in chunks of every size, and its small
# reader (runtime/c/small.c) against its general one (SML_TEST_HOOKS) on those lines mutated
# (tests/c/test_small.c); under the sanitizers in test-c-memory.
build/c/subset-sml/c/sml.c: $(C_PAIR) $(STAMP)
	$(PY) -m generator generate --quiet --only $(FIRMWARE_SUBSET) --prefix sml --out build/c/subset-sml

build/c/small_lines.txt: $(C_PAIR) tests/c/small_lines.py tests/agreement/edge_cases.txt $(STAMP)
	@mkdir -p $(@D)
	$(PY) tests/c/small_lines.py > $@

SMALL_TEST := -I build/c/subset/c -I build/c/subset-sml/c -DSML_SMALL -DSML_TEST_HOOKS build/c/subset-sml/c/sml.c \
              tests/c/test_small.c
build/c/test_small: build/c/subset/c/nmea.c build/c/subset-sml/c/sml.c tests/c/test_small.c
	$(CC) $(CFLAGS) -c -o build/c/test_small_reference.o build/c/subset/c/nmea.c
	$(CC) $(CFLAGS) -Os -o $@ build/c/test_small_reference.o $(SMALL_TEST)

build/c/test_small_san: build/c/subset/c/nmea.c build/c/subset-sml/c/sml.c tests/c/test_small.c
	$(CC) $(SANITIZE) -c -o build/c/test_small_reference_san.o build/c/subset/c/nmea.c
	$(CC) $(SANITIZE) -Os -o $@ build/c/test_small_reference_san.o $(SMALL_TEST)

# The AIS pair's tests, once more with the two slots of an assembly case.
build/c/test_ais build/c/test_ais_2_slots: build/c/nmea-test.o generated/c/nmea_ais.c generated/c/nmea_ais.h \
        runtime/c/test_ais.c
	@mkdir -p build/c
	$(CC) $(CFLAGS) -O0 $(if $(findstring 2_slots,$@),-DNMEA_AIS_SLOTS=2) -I generated/c -o $@ \
		build/c/nmea-test.o generated/c/nmea_ais.c runtime/c/test_ais.c

build/c/test_stream: build/c/subset/c/nmea.c tests/c/test_stream.c
	$(CC) $(SANITIZE) -I build/c/subset/c -o $@ $^

build/c/test_stream_smallest: build/c/subset/c/nmea.c tests/c/test_stream.c
	$(CC) $(SANITIZE) $(SMALLEST) -I build/c/subset/c -o $@ $^

# The UBX pair's tests (runtime/c/test_ubx.c): the shared vectors, then every UBX frame the framer
# finds in gpsd's logs decoded and encoded back byte for byte. test_ubx decodes through the
# generated straight-line readers; test_ubx_8 (NMEA_UBX_MAX_ENTRIES=8) without them
# (NMEA_UBX_NO_FAST_READ), so that the interpreter reads every payload too.
UBX_LOGS := $(sort $(wildcard tests/data/ubx/*.log)) $(sort $(wildcard tests/data/rtcm3/*.log))
# The logs of the other protocols the UBX pair types (SkyTraq, SiRF, CASIC, SBF, Unicore), with their vectors.
BINARY_LOGS := generated/vectors/binary.jsonl $(sort $(wildcard tests/data/skytraq/*.log)) \
        $(sort $(wildcard tests/data/sirf/*.log)) $(sort $(wildcard tests/data/casic/*.log)) \
        $(sort $(wildcard tests/data/sbf/*.sbf)) $(sort $(wildcard tests/data/unicore/*.log))
build/c/test_ubx: build/c/nmea-test.o generated/c/nmea_ubx.c generated/c/nmea_ubx.h runtime/c/test_ubx.c
	@mkdir -p build/c
	$(CC) $(CFLAGS) -O0 -I generated/c -o $@ build/c/nmea-test.o generated/c/nmea_ubx.c runtime/c/test_ubx.c

# ... and with every group's array lowered to 8 entries: what has more is refused as too_many_entries.
build/c/test_ubx_8: build/c/nmea-test.o generated/c/nmea_ubx.c generated/c/nmea_ubx.h runtime/c/test_ubx.c
	$(CC) $(CFLAGS) -O0 -DNMEA_UBX_MAX_ENTRIES=8 -DNMEA_UBX_NO_FAST_READ -I generated/c -o $@ build/c/nmea-test.o \
		generated/c/nmea_ubx.c runtime/c/test_ubx.c

build/c/test_ubx_san: build/c/nmea-san.o generated/c/nmea_ubx.c generated/c/nmea_ubx.h runtime/c/test_ubx.c
	$(CLANG) $(SANITIZE) -I generated/c -o $@ build/c/nmea-san.o generated/c/nmea_ubx.c runtime/c/test_ubx.c

# The RTCM 3 pair's tests (runtime/c/test_rtcm3.c): the shared vectors, then every RTCM 3 frame of the
# logs decoded and encoded back byte for byte, the first of each number cut at every length.
RTCM3_LOGS := $(sort $(wildcard tests/data/rtcm3/*.log)) $(sort $(wildcard tests/data/ubx/*.log))
build/c/test_rtcm3: generated/c/nmea_rtcm3.c generated/c/nmea_rtcm3.h runtime/c/test_rtcm3.c
	@mkdir -p build/c
	$(CC) $(CFLAGS) -O0 -I generated/c -o $@ generated/c/nmea_rtcm3.c runtime/c/test_rtcm3.c

build/c/test_rtcm3_san: generated/c/nmea_rtcm3.c generated/c/nmea_rtcm3.h runtime/c/test_rtcm3.c
	@mkdir -p build/c
	$(CLANG) $(SANITIZE) -I generated/c -o $@ generated/c/nmea_rtcm3.c runtime/c/test_rtcm3.c

test-c: build/c/test_examples build/c/test_examples_general build/c/nmea-small.o build/c/test_stream \
        build/c/test_stream_smallest build/c/test_small build/c/small_lines.txt build/c/test_ais build/c/test_ais_2_slots \
        build/c/test_ubx build/c/test_ubx_8 build/c/test_rtcm3
	build/c/test_examples
	build/c/test_rtcm3 generated/vectors/rtcm3.jsonl $(RTCM3_LOGS)
	build/c/test_ubx generated/vectors/ubx.jsonl $(UBX_LOGS) $(BINARY_LOGS)
	build/c/test_ubx_8 generated/vectors/ubx.jsonl $(UBX_LOGS) $(BINARY_LOGS)
	build/c/test_ais generated/vectors/ais.jsonl tests/data/ais/assembly_cases.jsonl
	build/c/test_ais_2_slots generated/vectors/ais.jsonl tests/data/ais/assembly_cases.jsonl
	build/c/test_examples_general
	build/c/test_stream
	build/c/test_stream_smallest
	build/c/test_small build/c/small_lines.txt

# The C test program and the C tool under the sanitizers over the examples, the edge cases and
# every real log (encode, which reads each line on its own, over the distinct lines that decode and
# the lenient stream wrote: half of them), and under valgrind over the examples, the edge cases and
# the first five lines of each kind (sentence and address, or error) of every real log.
MEMORY_INPUTS := tests/agreement/edge_cases.txt $(sort $(wildcard ../shared/corpus/real/*/*.nmea))

test-c-memory: build/c/test_examples_san build/c/nmea-c-san build/c/test_examples $(TEST_BIN)/nmea-c $(STAMP) \
        build/c/test_ubx_san build/c/test_ubx build/c/test_small_san build/c/small_lines.txt build/c/test_rtcm3_san
	build/c/test_examples_san
	build/c/test_rtcm3_san generated/vectors/rtcm3.jsonl $(RTCM3_LOGS)
	build/c/test_small_san build/c/small_lines.txt
	build/c/test_ubx_san generated/vectors/ubx.jsonl $(UBX_LOGS) $(BINARY_LOGS)
	valgrind -q --error-exitcode=1 --leak-check=full build/c/test_ubx generated/vectors/ubx.jsonl $(UBX_LOGS) > /dev/null
	@cat $(MEMORY_INPUTS) > build/c/memory.nmea
	build/c/nmea-c-san decode < build/c/memory.nmea > build/c/asan.jsonl
	build/c/nmea-c-san decode --values < build/c/memory.nmea > /dev/null
	build/c/nmea-c-san stream --lenient < build/c/memory.nmea > build/c/asan-lenient.jsonl
	LC_ALL=C sort -u build/c/asan.jsonl build/c/asan-lenient.jsonl | build/c/nmea-c-san encode > /dev/null
	build/c/nmea-c-san stream --require-checksum < tests/agreement/stream_cases.bin > /dev/null
	cat tests/data/ubx/*.log tests/data/rtcm3/*.log tests/data/skytraq/*.log tests/data/sirf/*.log tests/data/casic/*.log \
		| build/c/nmea-c-san stream > /dev/null
	build/c/nmea-c-san fixes < build/c/memory.nmea > /dev/null
	valgrind -q --error-exitcode=1 --leak-check=full build/c/test_examples > /dev/null
	$(PY) tools/distinct_lines.py 5 < build/c/asan.jsonl > build/c/valgrind.jsonl
	valgrind -q --error-exitcode=1 --leak-check=full $(TEST_BIN)/nmea-c decode < tests/agreement/edge_cases.txt > /dev/null
	valgrind -q --error-exitcode=1 --leak-check=full $(TEST_BIN)/nmea-c encode < build/c/valgrind.jsonl > /dev/null

# The generated crate's tests (SHARED_RUST: the build the tests' tool and the fuzz replay share) and its doc examples,
# and apart, so that the two run side by side, its lints: clippy with every feature and with none,
# each receiver feature (default: all of them) on its own, rustfmt. The lints have their own target
# directory: they share no build with the tests, and one directory would hold one cargo at a time.
# The crate's unit tests are the runtime's (src/runtime): test-runtimes runs them, with and without
# std, in the runtime's own crate (and clippy reads them there), so neither the tests nor the lints
# with every feature build the whole library a second time for them (without a receiver feature, the
# library is small). A receiver feature on its own needs rustc's
# warnings (an item its gate leaves unused, a name it leaves out); clippy's lints read the same code
# in the run with every feature. Each feature is checked on a crate that gives every gated item the
# gate it has in the whole crate but holds only the standard sentences that make shared items
# ungated (tools/rust_feature_subset.py): the others, never gated, are not type-checked 21 times.
RUST_VENDORS = $(shell sed -n 's/^\([a-z0-9_]*\) = \[\]$$/\1/p' generated/rust/Cargo.toml | grep -vx std)
LINT_TARGET := build/rust-lint-target
FEATURE_CRATE := build/rust-features

test-rust:
	cargo test --quiet $(SHARED_RUST) -p nmeaspec --test '*'
	cargo test --quiet $(SHARED_RUST) -p nmeaspec --doc

test-rust-lint: $(STAMP)
	cargo clippy --quiet --manifest-path generated/rust/Cargo.toml --lib --bins --test '*' --features std,serde,time,chrono \
		--target-dir $(LINT_TARGET) -- -D warnings
	cargo clippy --quiet --manifest-path generated/rust/Cargo.toml --all-targets --no-default-features --target-dir $(LINT_TARGET) -- -D warnings
	$(PY) -m generator generate --quiet --only "$$($(PY) tools/rust_feature_subset.py)" --out $(FEATURE_CRATE)
	$(PY) tools/rust_feature_subset.py --check $(FEATURE_CRATE)/rust
	set -e; for vendor in $(RUST_VENDORS); do \
		RUSTFLAGS="-D warnings" cargo check --quiet --manifest-path $(FEATURE_CRATE)/rust/Cargo.toml --lib --no-default-features \
			--features $$vendor --target-dir $(LINT_TARGET); \
	done
	cargo fmt --manifest-path generated/rust/Cargo.toml --check
	rustfmt --edition 2021 --check fuzz/rust/build.rs fuzz/rust/src/*.rs fuzz/rust/fuzz_targets/*.rs

test-tools: test-bin $(STAMP)
	NMEA_TOOLS=$(TEST_BIN) NMEA_C_OBJECT=build/c/nmea-test.o $(PY) -m pytest -q --durations=8 tests/agreement tests/fixes

# The benchmark harness for our implementations only, at a tiny size (no peers, nothing fetched).
test-bench-smoke: build/c/nmea-test.o $(STAMP)
	NMEA_C_OBJECT=build/c/nmea-test.o $(PY) -m pytest -q tests/bench

# The users' workflows from fresh temporary directories: the C pair in a CMake project and a plain
# build, the Rust crate as a path dependency with vendor features and serde, the Python package
# pip-installed into a new venv (mypy --strict on a user script), the `nmea` CLI, the docs' links
# and the HTML site in headless Chromium.
test-workflows: $(STAMP) $(DOCS_STAMP)
	$(PY) -m pytest -q --durations=8 tests/workflows

# --- releases ---------------------------------------------------------------------------------
# `make release-check` (part of `make test`): one version (VERSION) and one license everywhere, the
# Python sdist and wheel built, `twine check`ed and installed into a fresh venv, `cargo package`
# of the crate (tools/release_check.py; from copies in build/release). `make changelog` rewrites
# CHANGELOG.md from the git history: the spec diff of each release against the one before.
release-check: test-bin $(STAMP)
	NMEA_TOOLS=$(TEST_BIN) $(PY) tools/release_check.py

changelog: $(STAMP)
	$(PY) tools/changelog.py

# --- benchmarks ------------------------------------------------------------------------------
# `make bench` (not part of `make test`): ours in C, Rust and Python, the ceiling and the peers
# (installed by bench/run.py from crates.io and PyPI) over a corpus built from the real logs.
# Writes build/bench/results.{json,md} and docs/performance.md. Takes several minutes.
BENCH_ROUNDS   ?= 5
BENCH_LINES    ?= 1000000
BENCH_PY_LINES ?= 100000

bench: build
	python3 bench/run.py --rounds $(BENCH_ROUNDS) --lines $(BENCH_LINES) --python-lines $(BENCH_PY_LINES)

# `make footprint` (not part of `make test`): the C pair's flash, RAM and worst-case stack for the
# five-sentence firmware of issue 32 and the whole spec, on x86-64 and, when arm-none-eabi-gcc is
# installed (apt-get install gcc-arm-none-eabi libnewlib-arm-none-eabi), Cortex-M4 (tools/footprint.py).
footprint: $(STAMP)
	$(PY) tools/footprint.py --symbols 30

# --- fuzzing ---------------------------------------------------------------------------------
# `make fuzz FUZZ_SECONDS=N` runs each coverage-guided target for N seconds (C, Rust, the C and Rust
# codecs side by side in one process, Python; `make -j2 fuzz` runs two at a time), then replays
# what they found through the three tools (fuzz/differential.py), damages every real log the way a
# serial line does (fuzz-faults) and streams 1 GB through the three stream readers (fuzz-memory).
# The targets mutate sentences field by field (fuzz/c/field_mutator.c). `make fuzz-smoke` is the
# short run of `make test` (whose test-tools runs the short fault injection and memory check).
# Crashes land in build/fuzz/crash-*; copy each into fuzz/regressions/.
FUZZ_SECONDS ?= 300
FUZZ := build/fuzz
FUZZ_FLAGS = -max_total_time=$(FUZZ_SECONDS) -max_len=1100 -timeout=10 -print_final_stats=1

# The smoke run fuzzes the C pair (whose sanitized object the other steps build anyway) and the
# Python package for 10 seconds each, replays the seeds and every regression through the two Rust
# targets built without coverage instrumentation (fuzz-rust-replay), then through the three tools
# (fuzz-differential). The coverage-guided Rust runs are the campaign's (`make fuzz`): their
# instrumented build of the whole crate took more CPU than the rest of the smoke run together. What
# the smoke shares with the other steps of `make test` is built first, by this make, so that the
# two makes never build one file at once.
fuzz-smoke: test-bin build/c/nmea-san.o
	$(MAKE) --no-print-directory fuzz-c fuzz-python fuzz-rust-replay FUZZ_SECONDS=10 SEED_FLAGS=--no-corpus
	$(MAKE) --no-print-directory fuzz-differential

# Each input a file of its own, run once by the targets built without libFuzzer (a plain program
# each, fuzz/rust/src/lib.rs), which stop at the first that fails.
fuzz-rust-replay: fuzz-seeds
	cargo build --quiet $(SHARED_RUST) -p nmeaspec-fuzz --bins --no-default-features
	set -e; for target in nmea differential; do \
		find $(FUZZ)/seeds fuzz/regressions -type f -size +0 -print0 | \
			xargs -0 $(CARGO_TARGET)/debug/$$target 2> $(FUZZ)/replay-$$target.log \
			|| { tail -n 40 $(FUZZ)/replay-$$target.log; exit 1; }; \
	done

# The long runs of what `make test` checks briefly (fault injection, bounded memory).
FUZZ_LONG ?= fuzz-faults fuzz-memory
# The replay comes after the runs whose findings it replays.
fuzz: fuzz-c fuzz-rust fuzz-inprocess fuzz-python
	$(MAKE) --no-print-directory fuzz-differential $(FUZZ_LONG)

# The C UBX pair on its own (fuzz/c/fuzz_ubx.c), seeded with every UBX frame of the logs as class,
# id and payload; not part of the smoke run.
fuzz-c-ubx: $(STAMP)
	@mkdir -p $(FUZZ)/corpus-ubx $(FUZZ)/seeds-ubx
	PYTHONPATH=generated/python $(PY) -c 'import sys, pathlib; from nmeaspec import ubx; \
		[pathlib.Path(sys.argv[1], f"{log.stem}-{pos}").write_bytes(bytes((f.msg_class, f.msg_id)) + f.payload) \
		 for log in map(pathlib.Path, sys.argv[2:]) for pos, f in ubx.split_frames(log.read_bytes())]' \
		$(FUZZ)/seeds-ubx $(UBX_LOGS)
	$(CLANG) $(SANITIZE) -fsanitize=fuzzer -Igenerated/c -o $(FUZZ)/fuzz-c-ubx generated/c/nmea_ubx.c fuzz/c/fuzz_ubx.c
	$(FUZZ)/fuzz-c-ubx $(subst -max_len=1100,-max_len=2100,$(FUZZ_FLAGS)) -artifact_prefix=$(FUZZ)/crash-c-ubx- $(FUZZ)/corpus-ubx \
		$(FUZZ)/seeds-ubx

fuzz-seeds: $(STAMP)
	@rm -rf $(FUZZ)/seeds
	$(PY) fuzz/seeds.py $(FUZZ)/seeds $(SEED_FLAGS)

fuzz-c: fuzz-seeds build/c/nmea-san.o
	@mkdir -p $(FUZZ)/corpus-c
	$(CLANG) $(SANITIZE) -fsanitize=fuzzer -Igenerated/c -o $(FUZZ)/fuzz-c build/c/nmea-san.o generated/c/nmea_ais.c \
		fuzz/c/fuzz_nmea.c fuzz/c/field_mutator.c
	$(FUZZ)/fuzz-c $(FUZZ_FLAGS) -artifact_prefix=$(FUZZ)/crash-c- $(FUZZ)/corpus-c $(FUZZ)/seeds

fuzz-python: fuzz-seeds
	@mkdir -p $(FUZZ)/corpus-python
	PYTHONPATH=generated/python $(PY) fuzz/python/fuzz_nmea.py $(FUZZ_FLAGS) -artifact_prefix=$(FUZZ)/crash-python- \
		$(FUZZ)/corpus-python $(FUZZ)/seeds

CARGO_FUZZ_VERSION := 0.13.2
# The Rust targets are built optimized; CARGO_FUZZ_BUILD="--dev" builds them faster, for a short run.
CARGO_FUZZ_BUILD ?=
# The Rust targets' sanitizer: AddressSanitizer by default; the crate forbids unsafe code, so a long
# campaign may take `none` for more executions (the C pair has its own ASan target).
CARGO_FUZZ_SANITIZER ?= address

fuzz-rust: fuzz-seeds
	@command -v cargo-fuzz >/dev/null || cargo install --quiet --locked cargo-fuzz --version $(CARGO_FUZZ_VERSION)
	@mkdir -p $(FUZZ)/corpus-rust
	RUSTC_BOOTSTRAP=1 CARGO_TARGET_DIR=$(CURDIR)/$(FUZZ)/rust-target cargo fuzz run $(CARGO_FUZZ_BUILD) -s $(CARGO_FUZZ_SANITIZER) --fuzz-dir fuzz/rust nmea -- \
		$(FUZZ_FLAGS) -artifact_prefix=$(CURDIR)/$(FUZZ)/crash-rust- $(CURDIR)/$(FUZZ)/corpus-rust $(CURDIR)/$(FUZZ)/seeds

# The in-process differential: the C pair (built by fuzz/rust/build.rs) and the Rust crate in one
# target, every answer compared byte for byte (fuzz/rust/fuzz_targets/differential.rs).
fuzz-inprocess: fuzz-seeds
	@command -v cargo-fuzz >/dev/null || cargo install --quiet --locked cargo-fuzz --version $(CARGO_FUZZ_VERSION)
	@mkdir -p $(FUZZ)/corpus-inprocess
	RUSTC_BOOTSTRAP=1 CARGO_TARGET_DIR=$(CURDIR)/$(FUZZ)/rust-target cargo fuzz run $(CARGO_FUZZ_BUILD) -s $(CARGO_FUZZ_SANITIZER) --fuzz-dir fuzz/rust differential -- \
		$(FUZZ_FLAGS) -artifact_prefix=$(CURDIR)/$(FUZZ)/crash-inprocess- $(CURDIR)/$(FUZZ)/corpus-inprocess $(CURDIR)/$(FUZZ)/seeds \
		$(CURDIR)/fuzz/regressions

fuzz-differential: test-bin $(STAMP)
	NMEA_TOOLS=$(TEST_BIN) $(PY) fuzz/differential.py $(FUZZ)/seeds $(FUZZ)/corpus-c $(FUZZ)/corpus-python $(FUZZ)/corpus-rust $(FUZZ)/corpus-inprocess \
		fuzz/regressions

# Fault injection over every real log (fuzz/faults.py, tests/agreement/test_faults.py): each kind of
# damage with seeds 1..FAULT_SEEDS, every rate times FAULT_RATE; the figures go to
# build/reports/faults.md (docs/reliability.md). About three minutes a seed on two cores.
FAULT_SEEDS ?= 3
FAULT_RATE  ?= 1

fuzz-faults: build $(STAMP)
	FAULT_LOGS=all FAULT_SEEDS=$(FAULT_SEEDS) FAULT_RATE=$(FAULT_RATE) $(PY) -m pytest -q tests/agreement/test_faults.py

# Bounded memory: a generated stream of MEMORY_SIZE (real lines, garbage, overlong lines, a last
# line that never ends) through the three `stream` verbs, peak RSS against a 16 MB stream's
# (fuzz/bounded_memory.py; tests/agreement/test_bounded_memory.py is the short run).
MEMORY_SIZE ?= 1G
fuzz-memory: build $(STAMP)
	$(PY) fuzz/bounded_memory.py --size 16M --size $(MEMORY_SIZE)

clean:
	rm -rf build
