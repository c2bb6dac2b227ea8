// Durations (demlight/geo/time.h parseDuration, parseDurationOr): the accepted forms, the rejected ones
// with their messages, and compatibility with the step parser the CLI used before (a bare
// number of minutes), checked against a copy of it on a table and on random text.
#include "demlight/geo/time.h"
#include "demlight/core/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace demlight {
namespace {

using std::chrono::milliseconds;
using std::chrono::minutes;

/// The CLI's former parseStep (cli/cmd_timelapse.cpp) without its 1 s minimum: the total in
/// milliseconds before rounding, or nothing where it threw.
std::optional<double> legacyStepMs(const std::string& text) {
    if (text.empty()) return std::nullopt;
    double totalMs = 0;
    std::size_t i = 0;
    while (i < text.size()) {
        std::size_t used = 0;
        double v;
        try {
            v = std::stod(text.substr(i), &used);
        } catch (const std::exception&) {
            return std::nullopt;
        }
        i += used;
        char unit = i < text.size() ? text[i] : 'm';
        if (i < text.size()) ++i;
        const double scale = unit == 'h' ? 3.6e6 : unit == 'm' ? 6e4 : unit == 's' ? 1e3 : -1;
        if (scale < 0 || !(v >= 0)) return std::nullopt;
        totalMs += v * scale;
    }
    return totalMs;
}

struct Accepted {
    const char* text;
    long long ms;
};

TEST(Duration, AcceptsTermsWithUnits) {
    const std::vector<Accepted> cases = {
        {"10m", 600000},       {"90s", 90000},        {"2h", 7200000},        {"45s", 45000},
        {"1.5h", 5400000},     {"1h30m", 5400000},    {"1h 30m", 5400000},    {" 10m ", 600000},
        {"10 m", 600000},      {"2h15m30s", 8130000}, {".5h", 1800000},       {"5.m", 300000},
        {"1e3s", 1000000},     {"1E-3s", 1},          {"+5m", 300000},        {"0m", 0},
        {"0.0004s", 0},        {"0.0006s", 1},        {"10m10m", 1200000},    {"\t1h\n", 3600000},
    };
    for (const auto& c : cases) {
        EXPECT_EQ(parseDuration(c.text, "step").count(), c.ms) << "'" << c.text << "'";
        EXPECT_EQ(parseDurationOr(c.text, "step", minutes(1)).count(), c.ms) << "'" << c.text << "'";
    }
}

TEST(Duration, TheLongestHeldByMillisecondsIsAccepted) {
    EXPECT_EQ(parseDuration("2562047788015h", "step").count(), std::llround(2562047788015.0 * 3.6e6));
}

TEST(Duration, ABareNumberCountsTheGivenUnit) {
    const std::vector<Accepted> minutesCases = {
        {"10", 600000}, {"1.5", 90000}, {"1h30", 5400000}, {"2h 15", 8100000}, {" 20 ", 1200000}, {"1m30", 1860000},
    };
    for (const auto& c : minutesCases) {
        EXPECT_EQ(parseDurationOr(c.text, "step", minutes(1)).count(), c.ms) << "'" << c.text << "'";
        EXPECT_THROW(parseDuration(c.text, "step"), Error) << "'" << c.text << "' has no unit";
    }
    EXPECT_EQ(parseDurationOr("90", "step", std::chrono::seconds(1)), milliseconds(90000));
    EXPECT_EQ(parseDurationOr("2", "step", std::chrono::hours(1)), milliseconds(7200000));
    EXPECT_THROW(parseDurationOr("2", "step", milliseconds(0)), Error);
}

TEST(Duration, RejectsWhatIsNotADuration) {
    const std::vector<const char*> bad = {
        "",      "   ",   "10x",   "10d",      "10min", "10ms",  "h",     "m10",    "10M",  "1.2.3m",
        "nan",   "NaNm",  "inf",   "infh",     "0x10m", "1e",    "1em",   "10 5m",  "5m+",  ".m",
        "1h,30m", "1_000s",
    };
    for (const char* text : bad) {
        EXPECT_THROW(parseDuration(text, "step"), Error) << "'" << text << "'";
        EXPECT_THROW(parseDurationOr(text, "step", minutes(1)), Error) << "'" << text << "'";
    }
}

TEST(Duration, MessagesNameTheFieldTheTextAndTheForms) {
    struct Case {
        std::string text;
        bool bare;
        std::string message;
    };
    const std::vector<Case> cases = {
        {"10x", false, "step '10x': expected a duration like 15m, 1h, 90s or 1h30m"},
        {"10x", true, "step '10x': expected a duration like 15m, 1h, 90s or 1h30m, or a number of minutes"},
        {"", false, "step '': expected a duration like 15m, 1h, 90s or 1h30m"},
        {"10", false, "step '10': expected a duration like 15m, 1h, 90s or 1h30m"},
        {"-5m", true, "step '-5m': a duration cannot be negative"},
        {"-0m", true, "step '-0m': a duration cannot be negative"},
        {"1h-30m", false, "step '1h-30m': a duration cannot be negative"},
        {"1e400h", false, "step '1e400h': the number is out of range"},
        {"1e300h", false, "step '1e300h': too long a duration"},
        {"2562047788016h", false, "step '2562047788016h': too long a duration"},  // past 2^63 ms
    };
    for (const auto& c : cases) {
        try {
            if (c.bare) {
                parseDurationOr(c.text, "step", minutes(1));
            } else {
                parseDuration(c.text, "step");
            }
            ADD_FAILURE() << "'" << c.text << "' was accepted";
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()), c.message);
        }
    }
}

// parseDurationOr(text, field, minutes) replaces the CLI's step parser: whatever it took, with
// the same milliseconds. Its exceptions by design: a minus sign (it let "-0m" through) and totals
// it turned into undefined behaviour (inf, beyond 2^63 ms), rejected here; and text it refused
// that is unambiguous ("10 m", "10m ", tiny exponents), accepted here.
TEST(Duration, AcceptsEverythingTheOldStepParserDidWithTheSameMilliseconds) {
    const std::vector<std::string> table = {
        "10",  "10m", "1h30m", "1h30", "90s", "1.5h", "1h 30m", " 10m", "+5m", "1e1m", "1E+1m", "5.",
        ".5",  "0",   "2h15m30s", "10m5", "1.5h2", "0.001s", "3600s", "1e2", "  7",
    };
    for (const auto& text : table) {
        const auto legacy = legacyStepMs(text);
        ASSERT_TRUE(legacy) << "'" << text << "' (table entry the old parser should accept)";
        EXPECT_EQ(parseDurationOr(text, "step", minutes(1)).count(), std::llround(*legacy)) << "'" << text << "'";
    }
    // Random text over the characters both grammars use.
    std::mt19937 rng(20240621);
    const std::string alphabet = "0123456789.hms +eE";
    std::uniform_int_distribution<std::size_t> pick(0, alphabet.size() - 1), length(1, 9);
    int compared = 0;
    for (int n = 0; n < 200000; ++n) {
        std::string text(length(rng), ' ');
        for (char& ch : text) ch = alphabet[pick(rng)];
        const auto legacy = legacyStepMs(text);
        if (!legacy) continue;
        if (!(*legacy < 0x1p63)) {
            EXPECT_THROW(parseDurationOr(text, "step", minutes(1)), Error) << "'" << text << "'";
            continue;
        }
        ++compared;
        milliseconds got{-1};
        try {
            got = parseDurationOr(text, "step", minutes(1));
        } catch (const Error& e) {
            ADD_FAILURE() << "'" << text << "' rejected: " << e.what();
            continue;
        }
        EXPECT_EQ(got.count(), std::llround(*legacy)) << "'" << text << "'";
    }
    EXPECT_GT(compared, 1000) << "the random texts should exercise the accepted forms";
}

}  // namespace
}  // namespace demlight
