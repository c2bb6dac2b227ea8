// demlight sequence FIT.tif -o OUT.tif --time T: the reader of a compact lightmap sequence
// (timelapse --fit-degree): reconstructs sun_irradiance at any instant of the fitted span.
#include "cli/common.h"
#include "geo/time.h"
#include "lighting/sequence_fit.h"
#include "src/error.h"

#include <algorithm>

namespace demlight::cli {
namespace {

struct SequenceOptions {
    std::string fitPath;
    OutputOptions out;
    std::string time, tz;
};

double unixSeconds(UtcInstant t) { return std::chrono::duration<double>(t.time_since_epoch()).count(); }

void runSequence(const SequenceOptions& o, const CliContext& ctx) {
    const ZonedInstant when = parseZonedInstant(o.time, o.tz);
    checkOutputPath(o.out.path, o.fitPath);
    RasterSummary info;
    std::vector<Grid<float>> bands = readRasterBands(o.fitPath, &info);
    const auto item = [&](const std::string& key) {
        const auto it = info.metadata.find(key);
        if (it == info.metadata.end())
            throw Error("'" + o.fitPath + "' is not a sequence fit (no " + key +
                        "); make one with demlight timelapse --fit-degree N");
        return it->second;
    };
    SequenceFit fit;
    fit.degree = std::stoi(item("DEMLIGHT_FIT_DEGREE"));
    fit.t0Sec = unixSeconds(parseInstant(item("DEMLIGHT_FIT_T0_UTC"), ""));
    fit.t1Sec = unixSeconds(parseInstant(item("DEMLIGHT_FIT_T1_UTC"), ""));
    if (bands.size() < static_cast<std::size_t>(fit.degree) + 1)
        throw Error("'" + o.fitPath + "' has fewer coefficient bands than its degree needs");
    const double t = unixSeconds(when.utc);
    if (t < fit.t0Sec || t > fit.t1Sec)
        throw Error("--time " + o.time + " lies outside the fitted span " + item("DEMLIGHT_FIT_T0_UTC") +
                    " .. " + item("DEMLIGHT_FIT_T1_UTC"));
    bands.resize(static_cast<std::size_t>(fit.degree) + 1);
    fit.coefficients = std::move(bands);
    // Normalised irradiance lies in [0, 1] (max(0, N.s) times visibility); the polynomial
    // overshoots near sunrise, sunset and shadow edges.
    Grid<float> value = evaluateSequence(fit, t);
    for (float& v : value.values()) v = std::clamp(v, 0.0f, 1.0f);  // NaN (nodata) stays NaN

    WriteOptions w;
    w.format = o.out.format;
    w.creationOptions = o.out.creationOptions;
    w.metadata = {{"DEMLIGHT_VERSION", DEMLIGHT_VERSION},
                  {"DEMLIGHT_COMMAND", ctx.commandLine},
                  {"DEMLIGHT_INPUT", o.fitPath},
                  {"DEMLIGHT_PRODUCT", "sequence reconstruction"},
                  {"DEMLIGHT_TIME_UTC", formatInstant(when.utc, std::string())},
                  {"DEMLIGHT_TIME_LOCAL", formatInstant(when.utc, when.zone)},
                  {"DEMLIGHT_FIT_RMS_NOTE", "per-cell RMS residual of the fit: band rms_error of the input"}};
    // The fit's plan and accuracy statement describe this output too.
    for (const char* key : {"DEMLIGHT_QUALITY", "DEMLIGHT_PLAN", "DEMLIGHT_CURVATURE", "DEMLIGHT_EXPECTED_ERROR_DEG",
                            "DEMLIGHT_FIT_DEGREE", "DEMLIGHT_FIT_MEAN_RMS"})
        if (const auto it = info.metadata.find(key); it != info.metadata.end()) w.metadata.insert(*it);
    writeRaster(o.out.path, {{&value, nullptr, "sun_irradiance", "normalised irradiance (reconstructed, clamped to [0, 1])"}},
                info.ref, w, o.fitPath);
    note(ctx, "wrote " + o.out.path + " (sun_irradiance at " + formatInstant(when.utc, when.zone) +
                  " from degree-" + std::to_string(fit.degree) + " polynomials)");
}

}  // namespace

void registerSequence(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<SequenceOptions>();
    CLI::App* cmd = app.add_subcommand("sequence", "Reconstruct a lightmap at any instant from a "
                                                   "timelapse --fit-degree sequence_fit.tif");
    cmd->add_option("FIT", o->fitPath, "sequence_fit.tif written by demlight timelapse --fit-degree")
        ->required()
        ->check(CLI::ExistingFile);
    addOutputOptions(cmd, o->out);
    cmd->add_option("--time", o->time, "Instant (ISO 8601 with offset, or local with --tz)")->required();
    cmd->add_option("--tz", o->tz, "IANA time zone for a local --time");
    cmd->callback([o, &ctx] { runSequence(*o, ctx); });
}

}  // namespace demlight::cli
