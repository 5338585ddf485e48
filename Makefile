# NMEA spec generator. `make` generates everything from spec/; `make test` runs every test.
SHELL := /bin/bash
.DEFAULT_GOAL := generate

VENV    := .venv
PY      := $(VENV)/bin/python
STAMP   := $(VENV)/.installed
CC      ?= gcc
CFLAGS  ?= -std=c99 -Wall -Wextra -Werror -pedantic -O2
BIN     := build/bin
CARGO_TARGET := build/rust-target

.PHONY: generate validate check build test test-generator test-python test-c test-rust test-tools clean

$(STAMP): requirements.txt
	python3 -m venv $(VENV)
	$(PY) -m pip install --quiet --disable-pip-version-check -r requirements.txt
	touch $@

generate: $(STAMP)
	$(PY) -m generator generate

validate: $(STAMP)
	$(PY) -m generator validate

check: $(STAMP)
	$(PY) -m generator check

# --- the three command-line tools -------------------------------------------------------------

build: $(BIN)/nmea-py $(BIN)/nmea-c $(BIN)/nmea-rs

$(BIN)/nmea-py: $(shell find generated/python -name '*.py' 2>/dev/null)
	@mkdir -p $(BIN)
	printf '#!/bin/sh\nPYTHONPATH="%s" exec python3 -m nmeaspec "$$@"\n' "$(CURDIR)/generated/python" > $@
	chmod +x $@

$(BIN)/nmea-c: $(wildcard generated/c/*.c generated/c/*.h)
	@mkdir -p $(BIN)
	$(CC) $(CFLAGS) -o $@ generated/c/nmea.c generated/c/nmea_tool.c

$(BIN)/nmea-rs: $(shell find generated/rust -name '*.rs' -o -name Cargo.toml 2>/dev/null)
	@mkdir -p $(BIN)
	cargo build --quiet --release --manifest-path generated/rust/Cargo.toml --features std --bin nmea-rs --target-dir $(CARGO_TARGET)
	cp $(CARGO_TARGET)/release/nmea-rs $@

# --- tests -----------------------------------------------------------------------------------

test: check test-generator test-python test-c test-rust test-tools

test-generator: $(STAMP)
	$(PY) -m pytest -q tests/generator

test-python: $(STAMP)
	cd generated/python && ../../$(PY) -m pytest -q tests

test-c: $(STAMP)
	@mkdir -p build/c
	$(CC) $(CFLAGS) -o build/c/test_examples generated/c/nmea.c generated/c/tests/test_examples.c
	build/c/test_examples

test-rust:
	cargo test --quiet --manifest-path generated/rust/Cargo.toml --features std --target-dir $(CARGO_TARGET)
	cargo test --quiet --manifest-path generated/rust/Cargo.toml --no-default-features --lib --target-dir $(CARGO_TARGET)
	cargo clippy --quiet --manifest-path generated/rust/Cargo.toml --all-targets --features std --target-dir $(CARGO_TARGET) -- -D warnings

test-tools: build $(STAMP)
	$(PY) -m pytest -q tests/agreement

clean:
	rm -rf build
