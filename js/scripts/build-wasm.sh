#!/usr/bin/env bash
# Builds the WebAssembly module of ../wasm into js/pkg (ES module glue, .d.ts, .wasm).
# Installs what is missing: the wasm32-unknown-unknown target (rustup) and the
# wasm-bindgen-cli whose version matches the wasm-bindgen crate in Cargo.lock (cargo install).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
root="$(cd "$here/.." && pwd)"
cd "$root"

if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
  rustup target add wasm32-unknown-unknown
fi
# The version of the wasm-bindgen crate the lock file holds (the CLI must be the same).
version="$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/"/, "", $3); print $3; exit }' Cargo.lock)"
if [ -z "$version" ]; then
  echo "build-wasm: no wasm-bindgen in Cargo.lock" >&2
  exit 1
fi
if ! command -v wasm-bindgen >/dev/null 2>&1 || [ "$(wasm-bindgen --version | awk '{print $2}')" != "$version" ]; then
  echo "build-wasm: installing wasm-bindgen-cli $version" >&2
  cargo install wasm-bindgen-cli --version "$version" --quiet
fi
cargo build -p facesort-wasm --target wasm32-unknown-unknown --profile wasm --quiet
rm -rf "$here/pkg"
wasm-bindgen --target web --out-dir "$here/pkg" --out-name facesort_wasm \
  target/wasm32-unknown-unknown/wasm/facesort_wasm.wasm
echo "build-wasm: $(wc -c < "$here/pkg/facesort_wasm_bg.wasm") bytes, $(gzip -9 -c "$here/pkg/facesort_wasm_bg.wasm" | wc -c) gzipped ($here/pkg)"
