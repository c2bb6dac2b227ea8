// The reader of a compact lightmap sequence (a time-lapse's sequence fit): sun_irradiance at any
// instant of the fitted span.
#pragma once

#include "demlight/geo/time.h"
#include "demlight/products/product.h"

#include <string>

namespace demlight {

struct SequenceRequest {
    std::string fitPath;  ///< the fit raster (bands sun_irradiance_legendre_<j>, DEMLIGHT_FIT_* metadata)
    ZonedInstant time;
};

/// Band sun_irradiance reconstructed at the instant, clamped to [0, 1]. Throws Error when the
/// file is not a fit or the instant lies outside its span.
ProductResult sequenceProduct(const SequenceRequest& request);

}  // namespace demlight
