#!/usr/bin/env bash
# The system packages `make test` needs beyond Python 3.11, Rust, gcc and make: clang with its
# libFuzzer and sanitizer runtimes, valgrind, cmake (the C package test) and chromium (the docs
# site test). Installs the missing ones with apt-get when it can (as root or through sudo),
# otherwise names them in one line and fails. Prints nothing when everything is there.
set -euo pipefail
missing=()
command -v clang >/dev/null || missing+=(clang)
# libFuzzer and the sanitizers' runtimes are a package of their own on Debian.
probe=$(mktemp -d)
trap 'rm -rf "$probe"' EXIT
printf '#include <stddef.h>\n#include <stdint.h>\nint LLVMFuzzerTestOneInput(const uint8_t *d, size_t n) { (void)d; (void)n; return 0; }\n' > "$probe/probe.c"
command -v clang >/dev/null && clang -fsanitize=fuzzer,address,undefined -o "$probe/probe" "$probe/probe.c" 2>/dev/null ||
  missing+=(libclang-rt-dev)
for tool in valgrind cmake chromium; do
  command -v "$tool" >/dev/null || missing+=("$tool")
done
((${#missing[@]})) || exit 0
sudo=none
if [[ $(id -u) == 0 ]]; then sudo=; elif command -v sudo >/dev/null && sudo -n true 2>/dev/null; then sudo='sudo -n'; fi
if command -v apt-get >/dev/null && [[ $sudo != none ]]; then
  echo "installing ${missing[*]} (apt-get)" >&2
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  exit 0
fi
echo "make test needs these packages: ${missing[*]} (Debian: sudo apt-get install ${missing[*]})" >&2
exit 1
