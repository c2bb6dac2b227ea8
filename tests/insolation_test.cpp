// Period totals by binned sun positions (lighting/insolation.h, products/insolation.h) against the
// exact integral, the irradiance product at every instant of the period summed with the same
// trapezoid weights.
#include "geo/dem_source.h"
#include "geo/time.h"
#include "lighting/insolation.h"
#include "products/insolation.h"
#include "products/irradiance.h"
#include "src/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace demlight {
namespace {

const std::string kHelens = std::string(DEMLIGHT_SAMPLES_DIR) + "/mount_st_helens_1980_usgs.dem";
const std::string kRocky = std::string(DEMLIGHT_SAMPLES_DIR) + "/rocky_mountain_np_dem.tif";

TEST(SunBins, KeepTheTimeAndTheTimeWeightedSunOfEachSectorAndBand) {
    const std::vector<WeightedSun> suns = {
        {0.5, 359.0, 10.2, 1360, 3},  // sector 0 (north, across 0/360)
        {0.5, 1.0, 10.6, 1362, 3},    // sector 0, the same band
        {1.0, 90.0, 30.0, 1361, 3},   // sector 1 of 4 (east)
        {1.0, 90.0, 30.5, 1361, 2},   // the same sector and band, another Linke factor
        {2.0, 200.0, -1.0, 1361, 3},  // below the horizon: left out
    };
    const std::vector<SunBin> bins = binSuns(suns, 4, 2.0);
    ASSERT_EQ(bins.size(), 3u);
    EXPECT_EQ(bins[0].direction, 0u);
    EXPECT_DOUBLE_EQ(bins[0].hours, 1.0);
    EXPECT_NEAR(bins[0].azimuthDeg, 0.0, 1e-12);
    EXPECT_NEAR(bins[0].elevationDeg, 10.4, 1e-12);
    EXPECT_NEAR(bins[0].extraterrestrialWm2, 1361, 1e-9);
    EXPECT_EQ(bins[1].direction, 1u);
    EXPECT_EQ(bins[2].direction, 1u);
    EXPECT_NE(bins[1].linke, bins[2].linke);
}

struct Totals {
    std::vector<double> beam, global;
};

/// The exact integral: irradianceProduct at the instants insolation uses (every `step` from local
/// midnight to midnight, trapezoid weights), in kWh m-2.
Totals exactDay(const DemSource& dem, const std::string& day, const std::string& tz, std::chrono::minutes step,
                std::size_t directions) {
    const TimeZoneSpec zone = TimeZoneSpec::iana(tz);
    const LocalDay d = localDay(parseDate(day), zone);
    Totals out;
    out.beam.assign(dem.width() * dem.height(), 0.0);
    out.global = out.beam;
    const double hours = std::chrono::duration<double, std::ratio<3600>>(step).count();
    for (UtcInstant t = d.startUtc; t <= d.endUtc; t += step) {
        const double w = (t == d.startUtc || t == d.endUtc) ? hours / 2 : hours;
        IrradianceRequest r;
        r.time = {t, zone};
        r.skyDirections = directions;
        r.search.threads = 2;
        const IrradianceResult ir = irradianceProduct(dem, dem.whole(), r);
        for (std::size_t k = 0; k < out.beam.size(); ++k) {
            out.beam[k] += w * ir.bands[0].values.data()[k] / 1000;
            out.global[k] += w * ir.bands[3].values.data()[k] / 1000;
        }
    }
    return out;
}

struct Diff {
    double meanExact = 0, meanBinned = 0, mae = 0, p99 = 0;
};

Diff compare(const std::vector<double>& exact, const Grid<float>& binned) {
    Diff e;
    std::vector<double> abs;
    double se = 0, sb = 0;
    for (std::size_t k = 0; k < exact.size(); ++k) {
        const double b = binned.data()[k];
        if (std::isnan(b)) continue;
        se += exact[k];
        sb += b;
        abs.push_back(std::fabs(b - exact[k]));
    }
    std::sort(abs.begin(), abs.end());
    const double n = static_cast<double>(abs.size());
    e.meanExact = se / n;
    e.meanBinned = sb / n;
    for (double a : abs) e.mae += a / n;
    e.p99 = abs[static_cast<std::size_t>(0.99 * (n - 1))];
    return e;
}

// docs/accuracy.md#insolation-accuracy has the same comparison on St Helens at 20 min steps and the
// default 64 directions; this one is smaller so that it runs with the suite.
TEST(InsolationProduct, BinnedTotalsFollowThePerInstantIntegralOnRealTerrain) {
    const DemSource dem = DemSource::open(kRocky);
    constexpr std::size_t kDirections = 32;
    for (const char* day : {"2024-06-21", "2024-12-21"}) {
        InsolationRequest r;
        r.firstDay = r.lastDay = parseDate(day);
        r.zone = TimeZoneSpec::iana("America/Denver");
        r.step = std::chrono::minutes(30);
        r.directions = kDirections;
        r.search.threads = 2;
        const auto t0 = std::chrono::steady_clock::now();
        const InsolationResult binned = insolationProduct(dem, dem.whole(), r);
        const auto t1 = std::chrono::steady_clock::now();
        const Totals exact = exactDay(dem, day, "America/Denver", std::chrono::minutes(30), kDirections);
        const auto t2 = std::chrono::steady_clock::now();
        std::printf("binned %.2f s, per instant %.2f s\n", std::chrono::duration<double>(t1 - t0).count(),
                    std::chrono::duration<double>(t2 - t1).count());
        const Diff beam = compare(exact.beam, binned.band("beam").values);
        const Diff global = compare(exact.global, binned.band("global").values);
        std::printf("%s beam exact %.4f binned %.4f MAE %.4f p99 %.4f; global exact %.4f binned %.4f MAE %.4f p99 %.4f "
                    "kWh/m2 (%zu bins)\n",
                    day, beam.meanExact, beam.meanBinned, beam.mae, beam.p99, global.meanExact, global.meanBinned,
                    global.mae, global.p99, binned.bins);
        EXPECT_NEAR(global.meanBinned, global.meanExact, 0.005 * global.meanExact) << day;
        EXPECT_LT(global.mae, 0.01 * global.meanExact) << day;
        EXPECT_LT(beam.mae, 0.015 * beam.meanExact) << day;
    }
}

TEST(InsolationProduct, BandsUnitsAndBadRequests) {
    const DemSource dem = DemSource::open(kHelens);
    InsolationRequest r;
    r.firstDay = r.lastDay = parseDate("2024-03-20");
    r.zone = TimeZoneSpec::iana("America/Los_Angeles");
    r.step = std::chrono::minutes(30);
    r.directions = 16;
    r.search.threads = 2;
    const InsolationResult out = insolationProduct(dem, dem.whole(), r);
    const char* names[] = {"beam", "diffuse", "reflected", "global"};
    ASSERT_EQ(out.bands.size(), 4u);
    for (std::size_t b = 0; b < 4; ++b) {
        EXPECT_EQ(out.bands[b].name, names[b]);
        EXPECT_EQ(out.bands[b].unit, "kWh m-2");
    }
    EXPECT_EQ(out.metadata.at("DEMLIGHT_PRODUCT"), "insolation");
    EXPECT_EQ(out.metadata.at("DEMLIGHT_UNITS"), "kWh m-2");
    EXPECT_EQ(out.instants, 49u);
    for (std::size_t k = 0; k < out.bands[3].values.size(); ++k) {
        const float g = out.bands[3].values.data()[k];
        if (std::isnan(g)) continue;
        EXPECT_NEAR(g, out.bands[0].values.data()[k] + out.bands[1].values.data()[k] + out.bands[2].values.data()[k],
                    1e-5f * g + 1e-6f);
    }
    const auto fieldOf = [&](InsolationRequest bad) {
        try {
            insolationProduct(dem, dem.whole(), bad);
        } catch (const FieldError& e) {
            return e.field();
        }
        return std::string("(accepted)");
    };
    InsolationRequest bad = r;
    bad.lastDay = parseDate("2024-03-19");
    EXPECT_EQ(fieldOf(bad), "lastDay");
    bad = r;
    bad.step = std::chrono::hours(3);
    EXPECT_EQ(fieldOf(bad), "step");
    bad = r;
    bad.linke = {3, 3, 3};
    EXPECT_EQ(fieldOf(bad), "linke");
    bad = r;
    bad.elevationBandDeg = 0;
    EXPECT_EQ(fieldOf(bad), "elevationBandDeg");
}

}  // namespace
}  // namespace demlight
