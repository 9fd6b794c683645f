// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file paths.h
/// Where the tests find bundled swatches and their own fixtures.

#include <string>

namespace meshquilt::test {

/// A bundled swatch: swatches/NAME.obj.
inline std::string swatch_path(const std::string& name) { return std::string(MQ_SWATCH_DIR) + "/" + name + ".obj"; }
/// A base mesh fixture: tests/data/surface/FILE.
inline std::string surface_data_path(const std::string& file) { return std::string(MQ_TEST_DATA_DIR) + "/surface/" + file; }

}  // namespace meshquilt::test
