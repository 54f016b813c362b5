#!/usr/bin/env bash
# Renders the built-in scenes into screenshots/ with `raylab render`; each PNG gets its
# sidecar JSON, so `raylab render --params screenshots/NAME.png.json -o again.png` redoes it.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
render() { ./target/release/raylab render "$@"; }
render default -o screenshots/default.png --spp 64
# Metals and dielectrics.
render metals -o screenshots/metals.png --spp 64
render glazed -o screenshots/glazed.png --spp 64
render glass -o screenshots/glass.png --spp 64
render tir -o screenshots/tir.png --spp 64
render tir -o screenshots/tir-ior-1.35.png --spp 64 --set ior=1.35
render ray-tree -o screenshots/ray-tree.png --spp 64
render ray-tree -o screenshots/ray-tree-depth-2.png --spp 64 --set max_depth=2
# Distribution.
render antialiasing -o screenshots/antialiasing-1spp.png --spp 1 --set pattern=regular
render antialiasing -o screenshots/antialiasing-16spp.png --spp 16 --set pattern=sobol
render soft-shadows -o screenshots/soft-shadows.png --spp 64
render soft-shadows -o screenshots/soft-shadows-point.png --spp 64 --set light_size=0
render glossy -o screenshots/glossy.png --spp 64
render frosted -o screenshots/frosted.png --spp 256
render depth-of-field -o screenshots/depth-of-field.png --spp 64
render motion-blur -o screenshots/motion-blur.png --spp 64
# Beyond the slides.
render polarization -o screenshots/polarization-vertical.png --spp 64 --set polarizer=90
render polarization -o screenshots/polarization-horizontal.png --spp 64 --set polarizer=0
render dispersion -o screenshots/dispersion.png
# A real mesh.
render bunny -o screenshots/bunny.png --spp 64
