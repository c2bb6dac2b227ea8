// End-to-end tests of `demlight sunpos`: runs the built binary (DEMLIGHT_CLI_PATH).
#include "cli_runner.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>

namespace {

using demlight::testing::RunResult;

/// Runs `demlight sunpos ARGS`.
RunResult runSunpos(const std::string& args) { return demlight::testing::runDemlight("sunpos " + args); }

const char* kSpaCase =
    "--time 2003-10-17T12:30:30-07:00 --lat 39.742476 --lon -105.1786 --elevation 1830.14 "
    "--pressure 820 --temperature 11 --delta-t 67";

}  // namespace

TEST(SunposCli, SpaReportCaseAsJson) {
    const RunResult r = runSunpos(std::string(kSpaCase) + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_NEAR(j.at("zenith_deg").get<double>(), 50.111622, 1e-4);
    EXPECT_NEAR(j.at("azimuth_deg").get<double>(), 194.340241, 1e-4);
    EXPECT_NEAR(j.at("elevation_deg").get<double>(), 90 - 50.111622, 1e-4);
    EXPECT_EQ(j.at("delta_t_s").get<double>(), 67);
    EXPECT_EQ(j.at("utc"), "2003-10-17T19:30:30Z");
    EXPECT_EQ(j.at("sunrise"), "2003-10-17T06:12:43-07:00");
    EXPECT_EQ(j.at("transit"), "2003-10-17T11:46:05-07:00");  // 11:46:04.96
    EXPECT_EQ(j.at("sunset"), "2003-10-17T17:18:52-07:00");   // of 17 Oct local (see SPA tests)
    EXPECT_TRUE(j.at("polar").is_null());
}

TEST(SunposCli, TextOutputHasSixDecimalsAndEvents) {
    const RunResult r = runSunpos(kSpaCase);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("50.111622"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("194.340241"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("67.000000 s"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("sunrise           2003-10-17T06:12:43-07:00"), std::string::npos) << r.out;
    EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(SunposCli, IanaZoneAndPolarDayNight) {
    RunResult r = runSunpos("--time '2024-06-21 01:00' --tz Arctic/Longyearbyen --lat 78.22 "
                            "--lon 15.65 --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j.at("polar"), "day");
    EXPECT_TRUE(j.at("sunrise").is_null());
    EXPECT_TRUE(j.at("sunset").is_null());
    EXPECT_EQ(j.at("utc"), "2024-06-20T23:00:00Z");
    EXPECT_EQ(j.at("transit").get<std::string>().substr(0, 11), "2024-06-21T");
    EXPECT_GT(j.at("delta_t_s").get<double>(), 60);  // the estimate, none given

    r = runSunpos("--time 2024-12-21T12:00:00+01:00 --lat 78.22 --lon 15.65");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("sunrise           none (polar night"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("sunset            none (polar night"), std::string::npos) << r.out;
}

TEST(SunposCli, BadInputsFailWithAClearMessage) {
    struct Bad {
        const char* args;
        const char* message;
    };
    const Bad cases[] = {
        {"--time 2024-06-21T12:00 --lat 45 --lon 7", "has no zone"},
        {"--time 2024-06-21T12:00 --tz Europe/Atlantis --lat 45 --lon 7",
         "unknown time zone 'Europe/Atlantis'"},
        {"--time 2023-02-30T12:00Z --lat 45 --lon 7", "day 30 does not exist"},
        {"--time 2024-03-31T02:30 --tz Europe/Zurich --lat 47 --lon 8", "does not exist in Europe/Zurich"},
        {"--time 2024-10-27T02:30 --tz Europe/Zurich --lat 47 --lon 8", "ambiguous"},
        {"--time 2024-06-21T12:00Z --lat 91 --lon 7", "--lat"},
        {"--time 2024-06-21T12:00Z --lat 45 --lon -181", "--lon"},
        {"--time 2024-06-21T12:00Z --lat nan --lon 7", "finite"},
        {"--time 2024-06-21T12:00Z --lat 45 --lon 7 --pressure 6000", "--pressure"},
        {"--time 2024-06-21T12:00Z --lat 45 --lon 7 --pressure -5", "--pressure"},
        {"--time 2024-06-21T12:00Z --lat 45 --lon 7 --temperature -300", "--temperature"},
        {"--time 2024-06-21T12:00Z --lat 45 --lon 7 --delta-t 1e6", "--delta-t"},
        {"--time 2024-06-21T12:00Z --lon 7", "--lat"},
        {"--lat 45 --lon 7", "--time"},
    };
    for (const Bad& b : cases) {
        SCOPED_TRACE(b.args);
        const RunResult r = runSunpos(b.args);
        EXPECT_NE(r.exitCode, 0);
        EXPECT_NE(r.err.find(b.message), std::string::npos) << r.err;
        EXPECT_TRUE(r.out.empty()) << r.out;
    }
}
