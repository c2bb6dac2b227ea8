// The parameter declarations (demlight/run/parameters.h): checks and storage of values given as
// text, names spelt per front end, and the walk the house asks for: every field a library error
// can name belongs to a declared parameter, and no message a Python or QGIS user reads names a
// command-line flag.
#include "cli/commands.h"
#include "demlight/run/parameters.h"
#include "demlight/run/raster_commands.h"
#include "demlight/run/sunpos_command.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace demlight {
namespace {

std::string messageOf(const std::function<void()>& f, const ParameterSet* set, Naming naming) {
    try {
        f();
    } catch (const Error& e) {
        return describeError(e, set, naming);
    }
    return {};
}

/// Every command's declaration, as the command line registers them (raster commands, pictures,
/// time-lapses, sunpos, ...).
struct AllDeclarations {
    CLI::App app;
    cli::CliContext ctx;
    AllDeclarations() { cli::registerCommands(app, ctx); }
};

TEST(Parameters, TextIsCheckedStoredAndNamedAsEachFrontEndSpellsIt) {
    double distance = 0;
    std::optional<std::size_t> directions;
    std::vector<double> azimuths{1, 2};
    bool verbose = false;
    ParameterSet set("demo", "A demonstration");
    set.add("max_distance", distance, "Max distance (m)", "Search distance; see {directions}")
        .within(0, std::numeric_limits<double>::infinity(), /*lowOpen=*/true)
        .field("maxDistanceM");
    set.add("sky_directions", directions, "Sky directions", "Directions").within(4, 1024).alias("directions");
    set.add("azimuth", azimuths, "Azimuths", "Azimuths");
    set.add("verbose", verbose, "Verbose", "Notes").only(kCommandLine);

    set.set("max_distance", {"2500"}, kPython);
    set.set("directions", {"16"}, kPython);  // an alias
    set.set("azimuth", {"10", "20", "30"}, kPython);
    EXPECT_EQ(distance, 2500);
    EXPECT_EQ(directions, 16u);
    EXPECT_EQ(azimuths, (std::vector<double>{10, 20, 30}));  // replaced, not appended to the default

    // Range, kind and front end are checked before anything is stored.
    const auto bad = [&](const std::string& name, const std::string& value) {
        return [&set, name, value] { set.set(name, {value}, kPython); };
    };
    EXPECT_EQ(messageOf(bad("max_distance", "0"), &set, Naming::Python), "max_distance: must be > 0, got 0");
    EXPECT_EQ(messageOf(bad("max_distance", "0"), &set, Naming::CommandLine), "--max-distance: must be > 0, got 0");
    EXPECT_EQ(messageOf(bad("max_distance", "0"), &set, Naming::Qgis), "\"Max distance (m)\": must be > 0, got 0");
    EXPECT_EQ(messageOf(bad("sky_directions", "3"), &set, Naming::Python), "sky_directions: value 3 is outside [4, 1024]");
    EXPECT_EQ(messageOf(bad("sky_directions", "4.5"), &set, Naming::Python),
              "sky_directions: expected a whole number, got '4.5'");
    EXPECT_EQ(messageOf(bad("max_distance", "nan"), &set, Naming::Python),
              "max_distance: expected a finite number, got 'nan'");
    EXPECT_NE(messageOf(bad("verbose", ""), &set, Naming::Python).find("has no parameter verbose"), std::string::npos);
    EXPECT_EQ(distance, 2500);

    // A library error about a request field names the parameter that sets it.
    const FieldError field("maxDistanceM", " -3: must be > 0");
    EXPECT_EQ(describeError(field, &set, Naming::CommandLine), "--max-distance -3: must be > 0");
    EXPECT_EQ(describeError(field, &set, Naming::Python), "max_distance -3: must be > 0");
    // Help names other parameters in each front end's spelling; an alias as itself.
    EXPECT_EQ(renderNames(set.find("max_distance")->help, &set, Naming::CommandLine), "Search distance; see --directions");
    EXPECT_EQ(renderNames("{sky_directions} or {max_distance}", &set, Naming::Qgis),
              "\"Sky directions\" or \"Max distance (m)\"");
}

TEST(Parameters, RequiredParametersOfAFrontEndMustBeGiven) {
    SunposCommand sunpos;
    sunpos.declaration().set("time", {"2024-06-21T12:00:00Z"}, kPython);
    EXPECT_EQ(messageOf([&] { sunpos.declaration().checkRequired(kPython); }, &sunpos.declaration(), Naming::Python),
              "lat is required");
}

TEST(Parameters, EveryDeclaredParameterHasAShortLabelAndHelp) {
    AllDeclarations all;
    ASSERT_GE(all.ctx.declarations.size(), 15u);
    for (const auto& [command, set] : all.ctx.declarations) {
        std::set<std::string> names;
        for (const Parameter& p : set->parameters()) {
            EXPECT_TRUE(names.insert(p.name).second) << command << " declares " << p.name << " twice";
            EXPECT_FALSE(p.label.empty()) << command << " " << p.name;
            // At most 40 characters as a form shows it: QGIS adds " [optional]" to optional ones.
            const std::size_t shown = p.label.size() + (p.required ? 0 : std::string(" [optional]").size());
            EXPECT_LE(shown, 40u) << command << " " << p.name << ": " << p.label;
            EXPECT_FALSE(p.help.empty()) << command << " " << p.name;
            for (const std::string& other : p.excludes)
                EXPECT_NE(set->find(other), nullptr) << command << " " << p.name << " excludes " << other;
            // The help a Python or QGIS user reads names no command-line flag.
            if (p.shownIn(kPython)) {
                EXPECT_EQ(renderNames(p.help, set, Naming::Python).find("--"), std::string::npos) << command << " " << p.name;
            }
            if (p.shownIn(kQgis)) {
                EXPECT_EQ(renderNames(p.help, set, Naming::Qgis).find("--"), std::string::npos) << command << " " << p.name;
            }
        }
    }
}

TEST(Parameters, EveryBadValueOfARasterCommandIsNamedAsAKeywordAndALabel) {
    // Each parameter with a range or choices, given a value outside them, through Python's door:
    // the message names the keyword (and, rendered for QGIS, the label), never a flag.
    std::size_t checked = 0;
    for (const std::string& name : rasterCommandNames()) {
        const auto declared = makeRasterCommand(name);
        for (const Parameter& p : declared->declaration().parameters()) {
            if (!p.shownIn(kPython) || (!p.range && p.choices.empty())) continue;
            const std::string value = p.choices.empty() ? "-1e12" : "no-such-choice";
            const auto command = makeRasterCommand(name);
            const ParameterSet& set = command->declaration();
            const auto give = [&] { command->declaration().set(p.name, std::vector<std::string>(std::max(p.minValues, 1), value), kPython); };
            const std::string python = messageOf(give, &set, Naming::Python);
            const std::string qgis = messageOf(give, &set, Naming::Qgis);
            EXPECT_EQ(python.rfind(p.name, 0), 0u) << name << ": " << python;
            EXPECT_EQ(qgis.rfind("\"" + p.label + "\"", 0), 0u) << name << ": " << qgis;
            EXPECT_EQ(python.find("--"), std::string::npos) << name << ": " << python;
            ++checked;
        }
    }
    EXPECT_GT(checked, 60u);
}

TEST(Parameters, ValuesThatDoNotGoTogetherAreNamedAsKeywords) {
    // Checks of the work (raster_commands.cpp, options.cpp), past the single values' checks.
    struct Case {
        const char* command;
        std::vector<std::pair<std::string, std::vector<std::string>>> keywords;
        const char* expected;  // in the Python message
    };
    const Case cases[] = {
        {"horizon", {{"azimuth", {"10"}}, {"directions", {"4"}}}, "give either azimuth DEG [DEG ...] or directions N"},
        {"sky", {{"model", {"hemisphere"}}, {"patches", {"sky"}}}, "patches needs model stewart-langer"},
        {"sun", {{"time", {"2024-06-21T12:00:00"}}}, "or give a time zone (tz, an IANA name"},
        {"light", {{"time", {"2024-06-21T12:00:00Z"}}, {"sun_color", {"1,2"}}}, "sun_color '1,2'"},
        {"insolation", {{"tz", {"UTC"}}}, "give date D, start D end D, month YYYY-MM or year YYYY"},
        {"sunhours", {{"date", {"2024-06-21"}}, {"tz", {"UTC"}}, {"step", {"3h"}}}, "step 3h: must be from 6 s to 2 h"},
        {"irradiance", {{"time", {"2024-06-21T12:00:00Z"}}, {"linke", {"x"}}}, "linke 'x'"},
        {"sunhours", {{"date", {"2024-06-21"}}, {"tz", {"UTC"}}, {"horizon_mode", {"sideways"}}}, "horizon_mode 'sideways'"},
    };
    for (const Case& c : cases) {
        const auto command = makeRasterCommand(c.command);
        const std::string message = messageOf(
            [&] {
                for (const auto& [k, v] : c.keywords) command->declaration().set(k, v, kPython);
                (void)command->work();
            },
            &command->declaration(), Naming::Python);
        EXPECT_NE(message.find(c.expected), std::string::npos) << c.command << ": " << message;
        EXPECT_EQ(message.find("--"), std::string::npos) << c.command << ": " << message;
    }
}

TEST(Parameters, EveryFieldALibraryErrorNamesBelongsToADeclaredParameter) {
    // FieldError("field", ...) anywhere in the library: some command declares the parameter
    // that sets that field, so the message reaches each front end in its own spelling.
    AllDeclarations all;
    const std::regex fieldError(R"re(FieldError\("([A-Za-z_]+)")re");
    std::set<std::string> fields;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(DEMLIGHT_LIBRARY_DIR)) {
        if (entry.path().extension() != ".cpp" && entry.path().extension() != ".h") continue;
        std::ifstream in(entry.path());
        std::stringstream text;
        text << in.rdbuf();
        const std::string source = text.str();
        for (auto it = std::sregex_iterator(source.begin(), source.end(), fieldError); it != std::sregex_iterator(); ++it)
            fields.insert((*it)[1].str());
    }
    ASSERT_GT(fields.size(), 30u);
    for (const std::string& field : fields) {
        bool declared = false;
        for (const auto& [command, set] : all.ctx.declarations) declared = declared || set->forField(field);
        EXPECT_TRUE(declared) << "FieldError(\"" << field << "\") names no declared parameter";
    }
}

}  // namespace
}  // namespace demlight
