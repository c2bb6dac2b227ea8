// Wall-clock helpers shared by the benchmarks (timings are printed, never asserted): the
// library's (demlight/core/timing.h), under the benchmarks' namespace.
#pragma once

#include "demlight/core/timing.h"

namespace demlight::bench {

using demlight::medianSeconds;
using demlight::secondsSince;

}  // namespace demlight::bench
