// libFuzzer target: the --time / --tz parser (demlight/geo/time.h). Input: the time text, then after the
// first newline the zone name (may be empty). Properties checked on every accepted input:
//  - the local day of the instant contains it and is a non-empty interval;
//  - the instant written back (formatInstant) parses to the same instant, with the same zone,
//    whenever the zone's offset is a whole number of minutes (the only offsets the text form
//    has; local mean times before 1900 have seconds);
//  - decimalYear and julianDay are finite.
// Rejections must be demlight::Error; anything else escaping is a finding.
#include "demlight/geo/time.h"
#include "demlight/core/error.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

[[noreturn]] void fail(const char* what, const std::string& text, const std::string& tz) {
    std::fprintf(stderr, "time_fuzz: %s for time '%s', tz '%s'\n", what, text.c_str(), tz.c_str());
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace demlight;
    const std::string input(reinterpret_cast<const char*>(data), size);
    const std::size_t newline = input.find('\n');
    const std::string text = input.substr(0, newline);
    const std::string tz = newline == std::string::npos ? std::string() : input.substr(newline + 1);

    ZonedInstant z;
    try {
        z = parseZonedInstant(text, tz);
    } catch (const Error&) {
        return 0;
    }
    const LocalDay day = localDayOf(z.utc, z.zone);
    if (!(day.startUtc <= z.utc && z.utc < day.endUtc)) fail("local day does not contain the instant", text, tz);
    if (!std::isfinite(decimalYear(z.utc)) || !std::isfinite(julianDay(z.utc))) fail("non-finite year or JD", text, tz);

    const std::chrono::seconds offset = z.zone.offsetAt(z.utc);
    if (offset.count() % 60 != 0) return 0;
    const std::string written = formatInstant(z.utc, z.zone);
    try {
        const ZonedInstant back = parseZonedInstant(written, z.zone.ianaName());
        if (back.utc != z.utc) fail(("'" + written + "' reads back as another instant").c_str(), text, tz);
    } catch (const Error& e) {
        fail(("'" + written + "' does not read back: " + e.what()).c_str(), text, tz);
    }
    return 0;
}
