// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file version.h
/// The version of meshquilt these headers belong to (CMakeLists.txt checks that
/// it matches the project version).

#define MESHQUILT_VERSION "0.1.0"
#define MESHQUILT_VERSION_MAJOR 0
#define MESHQUILT_VERSION_MINOR 1
#define MESHQUILT_VERSION_PATCH 0

namespace meshquilt {
/// The library's version ("0.1.0"), for checking that headers and library match.
const char* version();
}  // namespace meshquilt
