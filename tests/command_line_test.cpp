// The command tree of cli/command_line.cpp against the user docs: every command and option that
// `--help` lists is in docs/commands.md (in its command's own section) and every command in the
// README's table, so the reference cannot drift from the program; usage lines and argument
// errors read in the order a user types.
#include "cli/commands.h"
#include "cli_runner.h"
#include "demlight/geo/raster.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace demlight::cli {
namespace {

const std::string kDocsDir = DEMLIGHT_DOCS_DIR;
const std::string kReadme = DEMLIGHT_README_PATH;

std::string readText(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/// The part of commands.md that documents `command`: from its heading "### `demlight COMMAND"
/// to the next heading of that level or above (outside code blocks, whose shell comments also
/// start with "# "). Empty when there is no such heading.
std::string commandSection(const std::string& doc, const std::string& command) {
    const std::string heading = "### `demlight " + command + " ";
    std::istringstream lines(doc);
    std::string section, line;
    bool inside = false, inCode = false;
    while (std::getline(lines, line)) {
        if (line.starts_with("```")) inCode = !inCode;
        const bool isHeading = !inCode && (line.starts_with("# ") || line.starts_with("## ") || line.starts_with("### "));
        if (isHeading && inside) break;
        if (isHeading && line.starts_with(heading)) inside = true;
        if (inside) section += line + "\n";
    }
    return section;
}

/// Whether `text` names the option spelling `flag` (`--sky` is not named by `--sky-directions`).
bool namesFlag(const std::string& text, const std::string& flag) {
    for (std::size_t at = text.find(flag); at != std::string::npos; at = text.find(flag, at + 1)) {
        const bool startsWord = at == 0 || !(std::isalnum(static_cast<unsigned char>(text[at - 1])) || text[at - 1] == '-');
        const std::size_t end = at + flag.size();
        const bool endsWord = end == text.size() || !(std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '-');
        if (startsWord && endsWord) return true;
    }
    return false;
}

/// Every spelling of the options of `app` (positionals by their name), but --help.
std::vector<std::string> optionSpellings(const CLI::App& app) {
    std::vector<std::string> spellings;
    for (const CLI::Option* o : app.get_options()) {
        if (o == app.get_help_ptr()) continue;
        if (o->get_positional()) spellings.push_back(o->get_name());
        for (const std::string& s : o->get_snames()) spellings.push_back("-" + s);
        for (const std::string& l : o->get_lnames()) spellings.push_back("--" + l);
    }
    return spellings;
}

std::string joined(const std::vector<std::string>& words) {
    std::string s;
    for (const std::string& w : words) s += (s.empty() ? "" : ", ") + w;
    return s;
}

TEST(CommandsDoc, DocumentsEveryCommandAndOptionInItsSection) {
    CLI::App app;
    CliContext ctx;
    registerCommands(app, ctx);
    const std::string doc = readText(kDocsDir + "/commands.md");
    ASSERT_FALSE(doc.empty()) << kDocsDir << "/commands.md";

    // The global flags, before the first command's section.
    const std::string intro = doc.substr(0, doc.find("\n### `demlight "));
    for (const std::string& flag : optionSpellings(app))
        EXPECT_TRUE(namesFlag(intro, flag)) << "docs/commands.md does not name the global flag " << flag;

    const std::vector<CLI::App*> commands = app.get_subcommands({});
    ASSERT_GE(commands.size(), 13u);
    for (const CLI::App* command : commands) {
        const std::string name = command->get_name();
        const std::string section = commandSection(doc, name);
        if (section.empty()) {
            ADD_FAILURE() << "docs/commands.md has no section \"### `demlight " << name << " ...`\"";
            continue;
        }
        std::vector<std::string> missing;
        for (const std::string& spelling : optionSpellings(*command))
            if (!namesFlag(section, spelling)) missing.push_back(spelling);
        EXPECT_TRUE(missing.empty()) << "docs/commands.md, section of `demlight " << name
                                     << "`, does not name: " << joined(missing);
    }
}

/// The commands `demlight --help` lists: all but the hidden ones (group ""), such as `options`,
/// which programs call, not people.
std::vector<const CLI::App*> listedCommands(const CLI::App& app) {
    std::vector<const CLI::App*> out;
    for (const CLI::App* command : app.get_subcommands({}))
        if (!command->get_group().empty()) out.push_back(command);
    return out;
}

TEST(CommandsDoc, ReadmeTableHasEveryCommand) {
    CLI::App app;
    CliContext ctx;
    registerCommands(app, ctx);
    const std::string readme = readText(kReadme);
    ASSERT_FALSE(readme.empty()) << kReadme;
    for (const CLI::App* command : listedCommands(app))
        EXPECT_NE(readme.find("\n| `demlight " + command->get_name() + " "), std::string::npos)
            << "README.md's command table has no row for " << command->get_name();
}

// Every metadata key and band the raster commands write is named in docs/commands.md: each
// command runs once on a small sample and its outputs are read back.
TEST(CommandsDoc, DocumentsEveryMetadataKeyAndBandWritten) {
    namespace fs = std::filesystem;
    const std::string doc = readText(kDocsDir + "/commands.md");
    ASSERT_FALSE(doc.empty());
    // Named by process: two runs of the suite at once (CI beside a developer's) never share it.
    const fs::path dir = fs::temp_directory_path() / ("demlight_commands_doc_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string dem = std::string(DEMLIGHT_SAMPLES_DIR) + "/rocky_mountain_np_dem.tif";
    const std::string time = " --time 2024-06-21T14:00Z";
    const std::string day = " --date 2024-06-21 --tz UTC --step 2h";
    auto out = [&](const std::string& name) { return " -o " + (dir / name).string(); };
    const std::vector<std::string> runs = {
        "horizon " + dem + out("horizon.tif") + " --directions 2",
        "sun " + dem + out("sun.tif") + time,
        "sky " + dem + out("sky.tif") + " --patches sectors:2",
        "aperture " + dem + out("aperture.tif"),
        "light " + dem + out("light.tif") + time + " --sky-color 1,1,1",
        "irradiance " + dem + out("irradiance.tif") + time,
        "insolation " + dem + out("insolation.tif") + day,
        "sunhours " + dem + out("sunhours.tif") + day,
        "timelapse " + dem + out("tl") + " --start 2024-06-21T14:00Z --end 2024-06-21T15:00Z --step 1h --formats tif --fit-degree 1",
        "sequence " + (dir / "tl" / "sequence_fit.tif").string() + out("sequence.tif") + time,
    };
    for (const std::string& run : runs) {
        const auto r = testing::runDemlight("-q " + run);
        ASSERT_EQ(r.exitCode, 0) << run << "\n" << r.err;
    }
    std::vector<std::string> missing;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        if (entry.path().extension() != ".tif") continue;
        const RasterSummary summary = inspectRaster(entry.path().string());
        for (const auto& [key, value] : summary.metadata)
            if (key.starts_with("DEMLIGHT_") && !namesFlag(doc, key)) missing.push_back(key + " (" + entry.path().filename().string() + ")");
        for (const std::string& band : summary.descriptions) {
            // A band named per azimuth or patch ("horizon_azimuth=90") or numbered
            // ("sun_irradiance_legendre_1") is documented by its stem.
            std::string name = band.substr(0, band.find('=') + (band.find('=') == std::string::npos ? 0 : 1));
            while (!name.empty() && std::isdigit(static_cast<unsigned char>(name.back()))) name.pop_back();
            if (doc.find("`" + name) == std::string::npos) missing.push_back("band " + band + " (" + entry.path().filename().string() + ")");
        }
    }
    fs::remove_all(dir);
    EXPECT_TRUE(missing.empty()) << "docs/commands.md does not name: " << joined(missing);
}

// The man page (docs/man.cmake, built with the tests) holds every command's help.
TEST(CommandsDoc, ManPageHasEveryCommand) {
#ifndef DEMLIGHT_MAN_PAGE
    GTEST_SKIP() << "help2man was not found when this build was configured: no man page";
#else
    CLI::App app;
    CliContext ctx;
    registerCommands(app, ctx);
    const std::string page = readText(DEMLIGHT_MAN_PAGE);
    ASSERT_FALSE(page.empty()) << DEMLIGHT_MAN_PAGE;
    for (const CLI::App* command : listedCommands(app)) {
        const std::string name = command->get_name();
        EXPECT_NE(page.find(".SS demlight " + name + "\n"), std::string::npos) << "no section for " << name;
        EXPECT_NE(page.find("Usage: demlight " + name + " "), std::string::npos) << "no usage line for " << name;
    }
#endif
}

// The checks above find a missing option: an option deleted from a section is reported.
TEST(CommandsDoc, SectionCheckSeesADeletedOption) {
    const std::string doc = "### `demlight sky DEM -o OUT.tif`\n\n`--albedo C`\n\n```sh\n# a comment\n```\n\n"
                            "`--sky-directions N`\n\n### `demlight sun DEM`\n\n`--sun-diameter`\n";
    const std::string sky = commandSection(doc, "sky");
    EXPECT_TRUE(namesFlag(sky, "--albedo"));
    EXPECT_TRUE(namesFlag(sky, "--sky-directions"));  // a shell comment in a code block ends no section
    EXPECT_TRUE(namesFlag(sky, "-o"));
    EXPECT_FALSE(namesFlag(sky, "--sky"));           // a prefix of another option is not it
    EXPECT_FALSE(namesFlag(sky, "--sun-diameter"));  // the next command's section is not this one's
    EXPECT_FALSE(namesFlag(sky, "--directions"));    // nor a suffix of another option
}

std::string helpOf(CLI::App& app, const std::string& command) {
    std::vector<std::string> args = parserArguments({command, "--help"});
    try {
        app.parse(args);
    } catch (const CLI::ParseError& e) {
        std::ostringstream out, err;
        app.exit(e, out, err);
        return out.str();
    }
    return {};
}

TEST(CommandLine, UsageNamesTheProgramAndTheCommandInTypedOrder) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"sun", "Usage: demlight sun DEM -o OUT.tif --time TIME [OPTIONS]\n"},
        {"sky", "Usage: demlight sky DEM -o OUT.tif [OPTIONS]\n"},
        {"render", "Usage: demlight render DEM -o OUT.png --time TIME [OPTIONS]\n"},
        {"timelapse", "Usage: demlight timelapse DEM -o DIR [OPTIONS]\n"},
        {"sunpos", "Usage: demlight sunpos --time TIME --lat DEG --lon DEG [OPTIONS]\n"},
        {"sequence", "Usage: demlight sequence FIT -o OUT.tif --time TIME [OPTIONS]\n"},
    };
    for (const auto& [command, usage] : cases) {
        CLI::App app;
        CliContext ctx;
        registerCommands(app, ctx);
        const std::string help = helpOf(app, command);
        EXPECT_NE(help.find(usage), std::string::npos) << help;
    }
    CLI::App app;
    CliContext ctx;
    registerCommands(app, ctx);
    std::vector<std::string> args = parserArguments({"--help"});
    try {
        app.parse(args);
        ADD_FAILURE() << "--help did not end parsing";
    } catch (const CLI::ParseError& e) {
        std::ostringstream out, err;
        app.exit(e, out, err);
        EXPECT_NE(out.str().find("Usage: demlight [OPTIONS] COMMAND\n"), std::string::npos) << out.str();
    }
}

// Arguments no option takes are listed as typed: "90 --azimuth 3" was reported "3 --azimuth 90".
TEST(CommandLine, UnexpectedArgumentsAreListedInTypedOrder) {
    CLI::App app;
    CliContext ctx;
    registerCommands(app, ctx);
    // The commands' callbacks stay (they own the options' storage); extra arguments stop the
    // parse before any of them runs.
    std::vector<std::string> args =
        parserArguments({"sun", "dem.tif", "-o", "out.tif", "--time", "2024-06-21T10:00Z", "90", "--azimuth", "3"});
    try {
        app.parse(args);
        ADD_FAILURE() << "extra arguments were accepted";
    } catch (const CLI::ParseError& e) {
        std::ostringstream out, err;
        EXPECT_EQ(app.exit(e, out, err), static_cast<int>(CLI::ExitCodes::ExtrasError));
        EXPECT_NE(err.str().find("not expected: 90 --azimuth 3\n"), std::string::npos) << err.str();
        EXPECT_NE(err.str().find("Run 'demlight sun --help'"), std::string::npos) << err.str();
    }
}

}  // namespace
}  // namespace demlight::cli
