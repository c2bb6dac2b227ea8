// Wall-clock helpers shared by the benchmarks (timings are printed, never asserted): the
// library's (src/timing.h), under the benchmarks' namespace.
#pragma once

#include "src/timing.h"

namespace demlight::bench {

using demlight::medianSeconds;
using demlight::secondsSince;

}  // namespace demlight::bench
