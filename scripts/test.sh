#!/usr/bin/env bash
# Installs what is missing, builds everything, and runs every test.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
# The print tests check our files with real slicer software.
install_missing prusa-slicer admesh
# The Python module (pip install .) and the Blender add-on are tested in a virtual environment.
if python_is_311; then
  build -DMESHQUILT_TEST_PYTHON="$BUILD/venv/bin/python"
  python_env
else
  echo "meshquilt: WARNING: the Python and Blender tests need Python 3.11 (bpy exists for it only);" \
       "python3 is $(python3 --version): they are left out" >&2
  build -DMESHQUILT_TEST_PYTHON=
fi
cd "$BUILD"
ctest --output-on-failure -j"$(nproc)" --timeout 1500
