#include "demlight/products/sequence.h"

#include "demlight/lighting/sequence_fit.h"
#include "demlight/core/error.h"

#include <algorithm>
#include <limits>

namespace demlight {
namespace {

double unixSeconds(UtcInstant t) { return std::chrono::duration<double>(t.time_since_epoch()).count(); }

}  // namespace

ProductResult sequenceProduct(const SequenceRequest& request) {
    RasterSummary info;
    std::vector<Grid<float>> bands = readRasterBands(request.fitPath, &info);
    const auto item = [&](const std::string& key) {
        const auto it = info.metadata.find(key);
        if (it == info.metadata.end())
            throw Error("'" + request.fitPath + "' is not a sequence fit (no " + key +
                        "); a time-lapse with a fit degree makes one");
        return it->second;
    };
    SequenceFit fit;
    fit.degree = std::stoi(item("DEMLIGHT_FIT_DEGREE"));
    fit.t0Sec = unixSeconds(parseInstant(item("DEMLIGHT_FIT_T0_UTC"), ""));
    fit.t1Sec = unixSeconds(parseInstant(item("DEMLIGHT_FIT_T1_UTC"), ""));
    if (fit.degree < 0 || bands.size() < static_cast<std::size_t>(fit.degree) + 1)
        throw Error("'" + request.fitPath + "' has fewer coefficient bands than its degree needs");
    const double t = unixSeconds(request.time.utc);
    if (t < fit.t0Sec || t > fit.t1Sec)
        throw FieldError("time", " " + formatInstant(request.time.utc, request.time.zone) + " lies outside the fitted span " +
                    item("DEMLIGHT_FIT_T0_UTC") + " .. " + item("DEMLIGHT_FIT_T1_UTC"));
    bands.resize(static_cast<std::size_t>(fit.degree) + 1);
    fit.coefficients = std::move(bands);
    // Normalised irradiance lies in [0, 1] (max(0, N.s) times visibility); the polynomial
    // overshoots near sunrise, sunset and shadow edges.
    Grid<float> value = evaluateSequence(fit, t);
    for (float& v : value.values()) v = std::clamp(v, 0.0f, 1.0f);  // NaN (nodata) stays NaN

    ProductResult out;
    out.ref = info.ref;
    out.nodata = std::numeric_limits<double>::quiet_NaN();
    out.metadata = {{"DEMLIGHT_VERSION", DEMLIGHT_VERSION},
                    {"DEMLIGHT_INPUT", request.fitPath},
                    {"DEMLIGHT_PRODUCT", "sequence reconstruction"},
                    {"DEMLIGHT_TIME_UTC", formatInstant(request.time.utc, std::string())},
                    {"DEMLIGHT_TIME_LOCAL", formatInstant(request.time.utc, request.time.zone)},
                    {"DEMLIGHT_FIT_RMS_NOTE", "per-cell RMS residual of the fit: band rms_error of the input"}};
    // The fit's plan and accuracy statement describe this output too.
    for (const char* key : {"DEMLIGHT_QUALITY", "DEMLIGHT_PLAN", "DEMLIGHT_CURVATURE", "DEMLIGHT_EXPECTED_ERROR_DEG",
                            "DEMLIGHT_FIT_DEGREE", "DEMLIGHT_FIT_MEAN_RMS"})
        if (const auto it = info.metadata.find(key); it != info.metadata.end()) out.metadata.insert(*it);
    out.bands.push_back({"sun_irradiance", "normalised irradiance (reconstructed, clamped to [0, 1])", std::move(value), {}});
    return out;
}

}  // namespace demlight
