#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on a bundled example: spot the cow
# (tests/data/surface/spot.obj, CC0) covered with rivet heads grown from swatches/rivets.obj.
# Output: out/spot_rivets.obj (decoration + base, one OBJ group each), out/spot_rivets.json, and
# out/spot_rivets.3mf, the decorated cow as one watertight solid 80 mm long, ready for a slicer.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_missing
build -DMESHQUILT_BUILD_TESTS=OFF -DMESHQUILT_BUILD_BENCH=OFF
mkdir -p "$ROOT/out"
"$BUILD/meshquilt" "$ROOT/tests/data/surface/spot.obj" "$ROOT/swatches/rivets.obj" --scale 0.12 --seed 1 --with-base \
  -o "$ROOT/out/spot_rivets.obj" --report "$ROOT/out/spot_rivets.json" \
  --print "$ROOT/out/spot_rivets.3mf" --size-mm 80 --print-report "$ROOT/out/spot_rivets_print.json"
"$BUILD/meshquilt" inspect "$ROOT/out/spot_rivets.obj" | head -12
