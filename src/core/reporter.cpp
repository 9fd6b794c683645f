// SPDX-License-Identifier: AGPL-3.0-or-later
#include "meshquilt/errors.h"
#include "meshquilt/reporter.h"

namespace meshquilt {

void Reporter::report(const std::string& stage, double fraction) const {
    if (progress && !progress(stage, fraction)) throw Cancelled("cancelled during " + stage);
}

}  // namespace meshquilt
