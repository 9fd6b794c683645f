#!/usr/bin/env bash
# Installs what is missing, builds everything, and runs every test.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
# The print tests check our files with real slicer software.
install_missing prusa-slicer admesh
build -DMESHQUILT_TEST_PYTHON="$BUILD/venv/bin/python"
# The Python module (pip install .) and the Blender add-on are tested in a virtual environment.
python_env
cd "$BUILD"
ctest --output-on-failure -j"$(nproc)" --timeout 1500
