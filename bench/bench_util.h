// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Shared by the benchmark programs.

#include <sys/resource.h>

namespace meshquilt::bench {

/// Peak resident memory of this process so far, in MB (max RSS).
inline double peak_rss_mb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_maxrss) / 1024.0;
}

}  // namespace meshquilt::bench
