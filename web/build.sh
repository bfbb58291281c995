#!/usr/bin/env bash
# Builds rbf studio's page: the engine (rbf-web) for wasm32 and its JavaScript glue in web/pkg.
# Installs what it needs when missing: the wasm32 target (rustup) and wasm-bindgen-cli of the
# exact version rbf-web pins (cargo install --locked: built here, never downloaded prebuilt).
set -euo pipefail
cd "$(dirname "$0")/.."
VERSION=0.2.129
if ! rustup target list --installed | grep -q '^wasm32-unknown-unknown$'; then
    rustup target add wasm32-unknown-unknown
fi
if ! wasm-bindgen --version 2>/dev/null | grep -q " $VERSION\$"; then
    cargo install --locked wasm-bindgen-cli --version "$VERSION"
fi
target="${CARGO_TARGET_DIR:-target}"
cargo build -p rbf-web --release --target wasm32-unknown-unknown
wasm-bindgen --target web --no-typescript --out-dir web/pkg \
    "$target/wasm32-unknown-unknown/release/rbf_web.wasm"
echo "built web/pkg; start the studio with: cargo run --release -p rbf-cli -- studio"
