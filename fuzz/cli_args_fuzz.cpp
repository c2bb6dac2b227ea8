// libFuzzer target: the command line's argument parsing (cli/commands.h registerCommands, as
// main() uses it), stopped once parsing is complete and before any command's callback runs, so
// that parsing, validators, option functions, help and error formatting run and no product does.
//
// Input: arguments separated by NUL bytes (as argv is). An argument that is a single byte of
// 0x80 or more stands for a name the command line knows (a command, or an option of the root or
// of a command, or --help), taken from the app itself, so the fuzzer reaches every option
// without a dictionary. Every other argument is used as it is.
//
// A parse error (CLI::ParseError) or a demlight::Error is a clean rejection; any other
// exception is what main() reports as an "internal error" (exit 2) and is a finding.
#include "cli/commands.h"
#include "demlight/core/error.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <ostream>
#include <string>
#include <vector>

namespace {

using demlight::cli::CliContext;

/// Thrown when parsing is complete: CLI11 runs the root's parse-complete callback after every
/// option is parsed, validated and checked and before the commands' callbacks.
struct ParseComplete {};

/// The root app in parse-only form. (The commands' callbacks stay: they own the options.)
void makeParseOnlyApp(CLI::App& app, CliContext& ctx) {
    demlight::cli::registerCommands(app, ctx);
    app.parse_complete_callback([] { throw ParseComplete{}; });
}

void addOptionNames(const CLI::App& app, std::vector<std::string>& names) {
    for (const CLI::Option* o : app.get_options()) {
        for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
        for (const std::string& n : o->get_snames()) names.push_back("-" + n);
    }
}

/// Every command and option name of the command line, and GDAL's one-dash spellings.
const std::vector<std::string>& knownNames() {
    static const std::vector<std::string> names = [] {
        CliContext ctx;
        CLI::App app;
        makeParseOnlyApp(app, ctx);
        std::vector<std::string> out = {"-of", "-co"};
        addOptionNames(app, out);
        for (const CLI::App* sub : app.get_subcommands({})) {
            out.push_back(sub->get_name());
            addOptionNames(*sub, out);
        }
        return out;
    }();
    return names;
}

std::vector<std::string> splitArguments(const std::uint8_t* data, std::size_t size) {
    const std::vector<std::string>& names = knownNames();
    std::vector<std::string> args;
    std::string current;
    const auto flush = [&] {
        if (current.size() == 1 && static_cast<unsigned char>(current[0]) >= 0x80)
            args.push_back(names[(static_cast<unsigned char>(current[0]) - 0x80) % names.size()]);
        else
            args.push_back(current);
        current.clear();
    };
    for (std::size_t i = 0; i < size; ++i) {
        if (data[i] == 0)
            flush();
        else
            current.push_back(static_cast<char>(data[i]));
    }
    if (size > 0) flush();
    return args;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    namespace cli = demlight::cli;
    std::vector<std::string> args = cli::parserArguments(splitArguments(data, size));
    CliContext ctx;
    CLI::App app;
    makeParseOnlyApp(app, ctx);
    if (cli::unknownCommandMessage(app, args)) return 0;
    std::ostream discard(nullptr);
    try {
        app.parse(args);
        std::fprintf(stderr, "cli_args_fuzz: parsing went on past its end\n");
        std::abort();
    } catch (const ParseComplete&) {
    } catch (const CLI::ParseError& e) {
        app.exit(e, discard, discard);  // formats help, version or the error message
    } catch (const demlight::Error&) {
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cli_args_fuzz: internal error: %s\n", e.what());
        std::abort();
    }
    return 0;
}
