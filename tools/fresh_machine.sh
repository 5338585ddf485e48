#!/usr/bin/env bash
# The README's two commands on a fresh machine: a minimal Debian bookworm chroot with what the
# README's Set-up asks for (Python 3.11, gcc, make, git; Rust copied from this machine's rustup,
# as a fresh machine would have it from rustup) and nothing else, a clean clone of HEAD with
# ../shared beside it, then `make` and `make test` inside, timed. Needs root and debootstrap.
#   tools/fresh_machine.sh [DIR]     (default /tmp/nmeaspec-fresh; reuses DIR/root if it exists)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:-/tmp/nmeaspec-fresh}
root=$dir/root
if [[ ! -x $root/usr/bin/python3 ]]; then
  debootstrap --variant=minbase --include=python3,python3-venv,python3-pip,gcc,libc6-dev,make,git,ca-certificates \
    bookworm "$root" http://deb.debian.org/debian
fi
toolchain=$(rustup show active-toolchain | cut -d' ' -f1)
mkdir -p "$root/root/.rustup/toolchains" "$root/root/.cargo"
[[ -d $root/root/.rustup/toolchains/$toolchain ]] ||
  cp -a "$HOME/.rustup/toolchains/$toolchain" "$HOME/.rustup/settings.toml" "$root/root/.rustup/toolchains/" 
mv -f "$root/root/.rustup/toolchains/settings.toml" "$root/root/.rustup/" 2>/dev/null || true
cp -a "$HOME/.cargo/bin" "$root/root/.cargo/"
cp /etc/resolv.conf "$root/etc/resolv.conf"
# The machine's network settings: its trusted certificates (a TLS proxy's CA, where there is one)
# and the variables that point the tools at them.
cp /etc/ssl/certs/ca-certificates.crt "$root/etc/ssl/certs/ca-certificates.crt"
[[ -f /etc/pip.conf ]] && cp /etc/pip.conf "$root/etc/pip.conf"
network_env=()
for name in SSL_CERT_FILE SSL_CERT_DIR PIP_CERT REQUESTS_CA_BUNDLE CURL_CA_BUNDLE GIT_SSL_CAINFO http_proxy https_proxy HTTP_PROXY HTTPS_PROXY no_proxy NO_PROXY; do
  [[ -n ${!name:-} ]] && network_env+=("$name=${!name}")
done
rm -rf "$root/work" && mkdir -p "$root/work"
git clone -q --branch "$(git -C "$repo" rev-parse --abbrev-ref HEAD)" "$repo" "$root/work/main"
cp -a "$repo/../shared" "$root/work/shared"
for fs in proc sys dev; do mountpoint -q "$root/$fs" || mount --rbind "/$fs" "$root/$fs"; done
trap 'for fs in proc sys dev; do umount -R "$root/$fs" 2>/dev/null || true; done' EXIT
chroot "$root" /usr/bin/env -i HOME=/root PATH=/root/.cargo/bin:/usr/local/bin:/usr/bin:/bin TERM=dumb "${network_env[@]}" \
  bash -c 'cd /work/main && python3 --version && cargo --version && gcc --version | head -1 &&
           time make && time make test' 2>&1 | tee "$dir/make-test.log"
