// demlight sequence FIT.tif -o OUT.tif --time T: reconstructs sun_irradiance at any instant of a
// time-lapse's sequence fit (demlight/products/sequence.h).
#include "cli/common.h"
#include "cli/declared.h"
#include "demlight/products/sequence.h"

namespace demlight::cli {
namespace {

struct SequenceOptions {
    ParameterSet set{"sequence", "Reconstruct a lightmap at any instant from the sequence_fit.tif of a time-lapse with a fit degree"};
    std::string fitPath;
    OutputOptions out;
    std::string time, tz;
};

void runSequence(const SequenceOptions& o, const CliContext& ctx) {
    SequenceRequest request;
    request.fitPath = o.fitPath;
    request.time = parseTimeOptions(o.time, o.tz);
    checkOutputPath(o.out, o.fitPath);
    const ProductResult result = sequenceProduct(request);
    writeResult(result, o.out, runContext(ctx), o.fitPath);
    note(ctx, "wrote " + o.out.path + " (sun_irradiance at " + formatInstant(request.time.utc, request.time.zone) +
                  " from degree-" + result.metadata.at("DEMLIGHT_FIT_DEGREE") + " polynomials)");
}

}  // namespace

void registerSequence(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<SequenceOptions>();
    ParameterSet& set = o->set;
    set.add("fit", o->fitPath, "Sequence fit raster",
            "sequence_fit.tif written by a time-lapse with a fit degree (demlight timelapse)")
        .positionalAs("FIT")
        .mandatory();
    declareOutput(set, o->out);
    declareTime(set, o->time, o->tz);
    notInPython(set);
    CLI::App* cmd = addDeclaredCommand(app, set, ctx);
    cmd->callback([o, &ctx] { runSequence(*o, ctx); });
}

}  // namespace demlight::cli
