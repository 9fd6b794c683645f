#!/usr/bin/env bash
# Installs what is missing, builds everything, and runs every test.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
# The print tests check our files with real slicer software.
install_missing prusa-slicer admesh
build
cd "$BUILD"
ctest --output-on-failure -j"$(nproc)" --timeout 1500
