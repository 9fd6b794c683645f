// SPDX-License-Identifier: AGPL-3.0-or-later
#include "meshquilt/analysis.h"

#include <algorithm>
#include <array>

namespace meshquilt {

ThinAxis thin_axis_of(const Box3& box) {
    ThinAxis t;
    if (box.empty()) return t;
    const Vec3 s = box.size();
    std::array<int, 3> order{0, 1, 2};
    std::sort(order.begin(), order.end(), [&](int a, int b) { return s[a] < s[b] || (s[a] == s[b] && a > b); });
    t.axis = order[0];
    t.thickness = s[order[0]];
    t.is_thin = s[order[1]] > 0.0 && s[order[0]] <= kThinRatio * s[order[1]];
    return t;
}

}  // namespace meshquilt
