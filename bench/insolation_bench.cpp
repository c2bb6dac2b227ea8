// Error of the binned insolation (demlight/products/insolation.h) against the exact per-instant integral,
// over the number of azimuth sectors N and the elevation band of the bins: the chart of
// docs/accuracy.md#insolation-accuracy. The reference is `irradiance` at every instant of the day
// (10-minute steps, trapezoid weights, 64 sky directions), as tests/insolation_test.cpp takes it.
//
// Usage: demlight_insolation_bench DEM TZ OUT.csv DAY [DAY ...]
// Writes one CSV row per (day, N, band): the global's mean absolute error relative to its mean,
// the beam's, the global's 99th percentile absolute error (kWh m-2), the bins and the binned run's
// wall time (s).
#include "demlight/geo/dem_source.h"
#include "demlight/geo/time.h"
#include "demlight/products/insolation.h"
#include "demlight/products/irradiance.h"
#include "demlight/core/error.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using namespace demlight;

constexpr auto kStep = std::chrono::minutes(10);
constexpr std::size_t kReferenceSkyDirections = 64;
constexpr std::size_t kDirections[] = {8, 16, 32, 64, 128};
constexpr double kBandsDeg[] = {0.5, 1, 2, 4, 8};
constexpr double kWhPerKWh = 1000;

struct Totals {
    std::vector<double> beam, global;
};

Totals exactDay(const DemSource& dem, const LocalDay& day, const TimeZoneSpec& zone) {
    Totals out;
    out.beam.assign(dem.width() * dem.height(), 0.0);
    out.global = out.beam;
    const double hours = std::chrono::duration<double, std::ratio<3600>>(kStep).count();
    for (UtcInstant t = day.startUtc; t <= day.endUtc; t += kStep) {
        const double w = (t == day.startUtc || t == day.endUtc) ? hours / 2 : hours;  // trapezoid
        IrradianceRequest r;
        r.time = {t, zone};
        r.skyDirections = kReferenceSkyDirections;
        const IrradianceResult ir = irradianceProduct(dem, dem.whole(), r);
        for (std::size_t k = 0; k < out.beam.size(); ++k) {
            out.beam[k] += w * ir.band("beam").values.data()[k] / kWhPerKWh;
            out.global[k] += w * ir.band("global").values.data()[k] / kWhPerKWh;
        }
    }
    return out;
}

struct BinError {
    double maeRelative = 0, p99 = 0;
};

BinError errorOf(const std::vector<double>& exact, const Grid<float>& binned) {
    std::vector<double> abs;
    double sum = 0, absSum = 0;
    for (std::size_t k = 0; k < exact.size(); ++k) {
        const double b = binned.data()[k];
        if (std::isnan(b) || std::isnan(exact[k])) continue;
        sum += exact[k];
        absSum += std::fabs(b - exact[k]);
        abs.push_back(std::fabs(b - exact[k]));
    }
    std::sort(abs.begin(), abs.end());
    return {absSum / sum, abs[static_cast<std::size_t>(0.99 * static_cast<double>(abs.size() - 1))]};
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 5) {
        std::fprintf(stderr, "usage: demlight_insolation_bench DEM TZ OUT.csv DAY [DAY ...]\n");
        return 2;
    }
    try {
        const DemSource dem = DemSource::open(argv[1]);
        const TimeZoneSpec zone = TimeZoneSpec::iana(argv[2]);
        std::FILE* csv = std::fopen(argv[3], "w");
        if (!csv) throw demlight::Error(std::string("cannot write ") + argv[3]);
        std::fprintf(csv, "day,directions,band_deg,bins,seconds,global_mae_rel,beam_mae_rel,global_p99_kwh\n");
        for (int a = 4; a < argc; ++a) {
            const auto date = parseDate(argv[a]);
            const Totals exact = exactDay(dem, localDay(date, zone), zone);
            for (const std::size_t n : kDirections)
                for (const double band : kBandsDeg) {
                    InsolationRequest r;
                    r.zone = zone;
                    r.firstDay = r.lastDay = date;
                    r.step = kStep;
                    r.directions = n;
                    r.elevationBandDeg = band;
                    const auto t0 = std::chrono::steady_clock::now();
                    const InsolationResult binned = insolationProduct(dem, dem.whole(), r);
                    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                    const BinError g = errorOf(exact.global, binned.band("global").values);
                    const BinError b = errorOf(exact.beam, binned.band("beam").values);
                    std::fprintf(csv, "%s,%zu,%g,%zu,%.3f,%.6f,%.6f,%.5f\n", argv[a], n, band, binned.bins, seconds,
                                 g.maeRelative, b.maeRelative, g.p99);
                    std::fflush(csv);
                }
        }
        std::fclose(csv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "demlight_insolation_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
