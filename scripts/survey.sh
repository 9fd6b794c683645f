#!/usr/bin/env bash
# Runs the main job on every mesh of a directory with three bundled swatches at the default scale
# and prints one table row per run (time, peak memory, output, coverage, density ranges per base
# area, by count (whole elements; "threads" where none are counted) and on the shell's middle
# surface, element sizes over their swatch elements', removed).
#   scripts/survey.sh [MESH_DIR] [SWATCHES...]    (default: ../shared/data/meshes; pebbles rivets chainmail)
# Needs a build in build/ (or MESHQUILT_BUILD_DIR). Outputs go to a temporary directory, or are
# kept in MESHQUILT_SURVEY_KEEP (a directory) as MESH-SWATCH.obj and MESH-SWATCH.json.
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
echo "| base | swatch | seconds | peak MB | faces | elements | coverage | region density | by count | on the middle surface | element sizes (off 1.5) | removed | patches shrunk |"
echo "|---|---|---:|---:|---:|---:|---:|---|---|---|---|---:|---:|"
for mesh in "$DIR"/*.obj; do
  for sw in "${SWATCHES[@]}"; do
    name="$(basename "$mesh" .obj)"
    if /usr/bin/time -f "%e %M" -o "$TMP/time" "$BUILD/meshquilt" -q "$mesh" "$ROOT/swatches/$sw.obj" \
        -o "$TMP/out.obj" --report "$TMP/r.json" 2> "$TMP/err"; then
      read -r secs kb < "$TMP/time"
      if [ -n "${MESHQUILT_SURVEY_KEEP:-}" ]; then
        mkdir -p "$MESHQUILT_SURVEY_KEEP"
        cp "$TMP/out.obj" "$MESHQUILT_SURVEY_KEEP/$name-$sw.obj"
        cp "$TMP/r.json" "$MESHQUILT_SURVEY_KEEP/$name-$sw.json"
      fi
      python3 - "$TMP/r.json" "$name" "$sw" "$secs" "$kb" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); s = j["surface"]
# Threads (cut and stitched to any length) are not measured.
sizes = f"{s['element_size_min']:.2f}-{s['element_size_max']:.2f} ({s['elements_off_size']})" if s["elements_sized"] else "threads"
count = f"{s['region_count_density_min']:.3f}-{s['region_count_density_max']:.3f}" if s["region_count_density_max"] > 0 else "threads"
print(f"| {sys.argv[2]} | {sys.argv[3]} | {float(sys.argv[4]):.1f} | {int(sys.argv[5]) // 1024} | {j['faces']:,} | {j['elements']:,} | "
      f"{s['coverage']:.3f} | {s['region_density_min']:.3f}-{s['region_density_max']:.3f} ({s['regions']} regions) | {count} | "
      f"{s['region_density_mid_min']:.3f}-{s['region_density_mid_max']:.3f} | "
      f"{sizes} | "
      f"{j['elements_removed']} | {s['patches_shrunk']}/{j['patches']} |")
PY
    else
      echo "| $name | $sw | failed: $(head -c 200 "$TMP/err" | tr '\n' ' ') | | | | | | | | | |"
    fi
  done
done
