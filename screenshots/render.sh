#!/usr/bin/env bash
# Renders the built-in scenes into screenshots/ with `raylab render`; each PNG gets its
# sidecar JSON, so `raylab render --params screenshots/NAME.json -o again.png` redoes it.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
render() { ./target/release/raylab render "$@" --spp 64; }
render default -o screenshots/default.png
render glazed -o screenshots/glazed.png
render glass -o screenshots/glass.png
render tir -o screenshots/tir.png
render tir -o screenshots/tir-ior-1.35.png --set ior=1.35
render ray-tree -o screenshots/ray-tree.png
render ray-tree -o screenshots/ray-tree-depth-2.png --set max_depth=2
render bunny -o screenshots/bunny.png
