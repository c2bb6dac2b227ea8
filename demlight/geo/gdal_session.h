// Internal to demlight/geo/: one-time GDAL set-up and error capture.
#pragma once

#include <string>

namespace demlight::detail {

/// Registers GDAL drivers once and routes GDAL's own messages into a buffer instead of stderr.
void ensureGdal();

/// The last message GDAL reported on this thread (empty if none), then clears it.
std::string takeGdalError();

}  // namespace demlight::detail
