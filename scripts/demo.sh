#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on a bundled swatch.
# Output: out/pebbles_plane.obj (+ a JSON report next to it).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_missing
build -DMESHQUILT_BUILD_TESTS=OFF -DMESHQUILT_BUILD_BENCH=OFF
mkdir -p "$ROOT/out"
"$BUILD/meshquilt" plane "$ROOT/swatches/pebbles.obj" --size 40 40 --seed 1 \
  -o "$ROOT/out/pebbles_plane.obj" --report "$ROOT/out/pebbles_plane.json"
"$BUILD/meshquilt" inspect "$ROOT/out/pebbles_plane.obj" | head -12
