#!/usr/bin/env bash
# Runs the main job on every mesh of a directory with three bundled swatches at the default scale
# and prints one table row per run (time, peak memory, output, coverage, density ranges per base
# area and on the shell's middle surface, removed).
#   scripts/survey.sh [MESH_DIR] [SWATCHES...]    (default: ../shared/data/meshes; pebbles rivets chainmail)
# Needs a build in build/ (or MESHQUILT_BUILD_DIR). Outputs go to a temporary directory.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${MESHQUILT_BUILD_DIR:-$ROOT/build}"
DIR="${1:-$ROOT/../shared/data/meshes}"
shift || true
SWATCHES=("${@:-pebbles rivets chainmail}")
# shellcheck disable=SC2206
SWATCHES=(${SWATCHES[*]})
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
echo "| base | swatch | seconds | peak MB | faces | elements | coverage | region density | on the middle surface | removed | patches shrunk |"
echo "|---|---|---:|---:|---:|---:|---:|---|---|---:|---:|"
for mesh in "$DIR"/*.obj; do
  for sw in "${SWATCHES[@]}"; do
    name="$(basename "$mesh" .obj)"
    if /usr/bin/time -f "%e %M" -o "$TMP/time" "$BUILD/meshquilt" -q "$mesh" "$ROOT/swatches/$sw.obj" \
        -o "$TMP/out.obj" --report "$TMP/r.json" 2> "$TMP/err"; then
      read -r secs kb < "$TMP/time"
      python3 - "$TMP/r.json" "$name" "$sw" "$secs" "$kb" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); s = j["surface"]
print(f"| {sys.argv[2]} | {sys.argv[3]} | {float(sys.argv[4]):.1f} | {int(sys.argv[5]) // 1024} | {j['faces']:,} | {j['elements']:,} | "
      f"{s['coverage']:.3f} | {s['region_density_min']:.2f}-{s['region_density_max']:.2f} ({s['regions']} regions) | "
      f"{s['region_density_mid_min']:.2f}-{s['region_density_mid_max']:.2f} | "
      f"{j['elements_removed']} | {s['patches_shrunk']}/{j['patches']} |")
PY
    else
      echo "| $name | $sw | failed: $(head -c 200 "$TMP/err" | tr '\n' ' ') | | | | | | | | |"
    fi
  done
done
