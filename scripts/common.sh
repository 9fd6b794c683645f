#!/usr/bin/env bash
# Shared by demo.sh and test.sh: install missing Debian packages, configure and build.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${MESHQUILT_BUILD_DIR:-$ROOT/build}"

PACKAGES=(g++ cmake ninja-build pkg-config ccache python3
  libcgal-dev libeigen3-dev libtbb-dev libmaxflow-dev libcli11-dev nlohmann-json3-dev libnanoflann-dev
  libgtest-dev libbenchmark-dev libopenvdb-dev libboost-iostreams-dev lib3mf-dev
  python3-dev python3-venv pybind11-dev)

install_missing() {
  local missing=()
  for p in "${PACKAGES[@]}" "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "meshquilt: installing ${missing[*]}" >&2
    local sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  fi
}

build() {
  local launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@" >/dev/null
  cmake --build "$BUILD" -j"$(nproc)"
}

# A virtual environment in the build directory with what the Python tests need: numpy < 2, pytest,
# Blender as a module (bpy 4.5, which exists for Python 3.11 only) and meshquilt itself, installed
# the way users install it: `pip install .` (scikit-build-core; the CMake build under
# build-python/ is kept, and ccache serves what the main build already compiled).
python_env() {
  local venv="$BUILD/venv"
  local pip=("$venv/bin/python" -m pip install -q --disable-pip-version-check)
  [ -x "$venv/bin/python" ] || python3 -m venv "$venv"
  "${pip[@]}" "numpy<2" pytest "bpy==4.5.*"
  command -v ccache >/dev/null && export CMAKE_CXX_COMPILER_LAUNCHER=ccache
  "${pip[@]}" "$ROOT"
}

# True when python3 is 3.11, the only version PyPI's bpy 4.5 exists for.
python_is_311() {
  python3 -c 'import sys; sys.exit(sys.version_info[:2] != (3, 11))'
}
