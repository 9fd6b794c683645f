#!/usr/bin/env bash
# Installs what is missing, builds everything, and runs every test.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_missing
build
cd "$BUILD"
ctest --output-on-failure -j"$(nproc)" --timeout 1500
