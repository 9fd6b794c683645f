// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Shared by the benchmark programs.

#include "meshquilt/io.h"

#include <sys/resource.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

namespace meshquilt::bench {

/// A shared test mesh by name ("bunny": `name`.obj in MESHQUILT_MESHES, by default
/// ../shared/data/meshes beside the checkout), read once; null when it is missing.
inline const Mesh* shared_mesh(const std::string& name) {
    static std::map<std::string, Mesh> cache;
    auto it = cache.find(name);
    if (it != cache.end()) return &it->second;
    const char* env = std::getenv("MESHQUILT_MESHES");
    const std::string dir = env ? env : std::string(MQ_SOURCE_DIR) + "/../shared/data/meshes";
    const std::string path = dir + "/" + name + ".obj";
    if (!std::filesystem::exists(path)) return nullptr;
    return &cache.emplace(name, read_mesh(path)).first->second;
}

/// Peak resident memory of this process so far, in MB (max RSS).
inline double peak_rss_mb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_maxrss) / 1024.0;
}

}  // namespace meshquilt::bench
