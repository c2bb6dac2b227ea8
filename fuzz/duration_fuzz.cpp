// libFuzzer target: durations (parseDuration, parseDurationOr in demlight/geo/time.h; --step and the
// other duration options). Properties checked on every accepted input: the duration is not
// negative, and text parseDuration accepts is accepted by parseDurationOr with the same value
// (a bare number only adds forms). Rejections must be demlight::Error.
#include "demlight/geo/time.h"
#include "demlight/core/error.h"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string_view>

namespace {

[[noreturn]] void fail(const char* what, std::string_view text) {
    std::fprintf(stderr, "duration_fuzz: %s for '%.*s'\n", what, static_cast<int>(text.size()), text.data());
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace demlight;
    using std::chrono::milliseconds;
    const std::string_view text(reinterpret_cast<const char*>(data), size);

    std::optional<milliseconds> strict;
    try {
        strict = parseDuration(text, "step");
        if (*strict < milliseconds::zero()) fail("negative duration", text);
    } catch (const Error&) {
    }
    try {
        const milliseconds lenient = parseDurationOr(text, "step", std::chrono::minutes(1));
        if (lenient < milliseconds::zero()) fail("negative duration (bare minutes)", text);
        if (strict && lenient != *strict) fail("parseDurationOr differs from parseDuration", text);
    } catch (const Error&) {
        if (strict) fail("parseDurationOr rejects what parseDuration accepts", text);
    }
    return 0;
}
