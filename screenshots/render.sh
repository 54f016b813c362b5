#!/usr/bin/env bash
# Renders the built-in scenes into screenshots/ with `raylab render`; each PNG gets its
# sidecar JSON, so `raylab render --params screenshots/NAME.json -o again.png` redoes it.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
for scene in default bunny; do
  ./target/release/raylab render "$scene" -o "screenshots/$scene.png" --spp 64
done
