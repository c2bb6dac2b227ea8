// demlight options --json (hidden): every command's options as JSON, for programs that drive the
// CLI (the QGIS provider in qgis/ builds its algorithms from it), so that no option, default or
// help text is written a second time outside the command that declares it.
#include "cli/commands.h"

#include <nlohmann/json.hpp>

#include <iostream>

namespace demlight::cli {
namespace {

// The output options every command spells alike: -o,--output, and --of, which addOutputOptions
// (cli/common.cpp) adds with -o to the commands that write a GDAL raster.
constexpr const char* kOutputOption = "output";
constexpr const char* kRasterFormatOption = "of";

/// An option's values per use: {min, max}, max -1 when unbounded (repeatable, or "FLOAT ...").
std::pair<int, int> valueCount(const CLI::Option& opt) {
    const int most = opt.get_items_expected_max();
    return {opt.get_items_expected_min(), most >= CLI::detail::expected_max_vector_size ? -1 : most};
}

/// "FLOAT:[0, 20]" -> FLOAT; "TEXT:{auto,full}" -> TEXT and the choices auto, full.
void describeType(const std::string& typeName, nlohmann::json& j) {
    j["type"] = typeName.substr(0, typeName.find_first_of(": "));
    nlohmann::json choices = nlohmann::json::array();
    const auto open = typeName.find('{'), close = typeName.find('}');
    if (open != std::string::npos && close != std::string::npos && close > open) {
        const std::string list = typeName.substr(open + 1, close - open - 1);
        for (std::size_t begin = 0; begin <= list.size();) {
            const std::size_t end = std::min(list.find(',', begin), list.size());
            choices.push_back(list.substr(begin, end - begin));
            begin = end + 1;
        }
    }
    j["choices"] = choices;
}

/// The option's name without dashes: its first long name, else its short or positional name.
std::string plainName(const CLI::Option& opt) {
    if (opt.get_positional()) return opt.get_name(true);
    if (!opt.get_lnames().empty()) return opt.get_lnames().front();
    return opt.get_snames().front();
}

nlohmann::json describeOption(const CLI::Option& opt) {
    nlohmann::json j;
    j["name"] = plainName(opt);
    nlohmann::json flags = nlohmann::json::array();
    for (const std::string& s : opt.get_snames()) flags.push_back("-" + s);
    for (const std::string& l : opt.get_lnames()) flags.push_back("--" + l);
    j["flags"] = flags;
    j["positional"] = opt.get_positional();
    j["description"] = opt.get_description();
    j["default"] = opt.get_default_str().empty() ? nlohmann::json() : nlohmann::json(opt.get_default_str());
    j["required"] = opt.get_required();
    const auto [least, most] = valueCount(opt);
    j["flag"] = most == 0;  // takes no value
    describeType(opt.get_type_name(), j);
    j["type_name"] = opt.get_type_name();  // as --help shows it, with its check: "FLOAT:[0, 20]"
    j["min_values"] = least;
    j["max_values"] = most;
    nlohmann::json excludes = nlohmann::json::array();
    for (const CLI::Option* other : opt.get_excludes()) excludes.push_back(plainName(*other));
    j["excludes"] = excludes;
    return j;
}

nlohmann::json describeCommand(const CLI::App& cmd, const CliContext& ctx) {
    nlohmann::json j;
    j["name"] = cmd.get_name();
    j["description"] = cmd.get_description();
    j["help"] = cmd.help(cmd.get_parent() ? cmd.get_parent()->get_name() : std::string());  // "Usage: demlight sun ..."
    nlohmann::json options = nlohmann::json::array();
    bool writesRaster = false, hasOutput = false;
    for (const CLI::Option* opt : cmd.get_options()) {
        if (opt == cmd.get_help_ptr()) continue;
        const std::string name = plainName(*opt);
        writesRaster = writesRaster || name == kRasterFormatOption;
        hasOutput = hasOutput || name == kOutputOption;
        options.push_back(describeOption(*opt));
    }
    j["options"] = options;
    const auto declared = ctx.outputs.find(cmd.get_name());
    const CommandOutputs outputs = declared == ctx.outputs.end() ? CommandOutputs{} : declared->second;
    j["output"] = !hasOutput               ? nlohmann::json()
                  : !outputs.kind.empty() ? nlohmann::json(outputs.kind)
                  : writesRaster          ? nlohmann::json("raster")
                                          : nlohmann::json("file");
    j["companions"] = outputs.companionKeys;
    return j;
}

}  // namespace

std::string optionsJson(const CLI::App& app, const CliContext& ctx) {
    nlohmann::json commands = nlohmann::json::array();
    for (const CLI::App* sub : app.get_subcommands({}))
        if (!sub->get_group().empty()) commands.push_back(describeCommand(*sub, ctx));
    nlohmann::json root;
    root["version"] = DEMLIGHT_VERSION;
    root["commands"] = commands;
    return root.dump(1);
}

void registerOptions(CLI::App& app, CliContext& ctx) {
    auto json = std::make_shared<bool>(false);
    CLI::App* cmd = app.add_subcommand("options", "Every command's options as JSON, for programs that drive demlight");
    cmd->group("");  // hidden from demlight --help and from the list of commands
    cmd->add_flag("--json", *json, "Print JSON (the only form)")->required();
    cmd->callback([json, &app, &ctx] {  // holds the flag's storage as long as the command
        std::cout << optionsJson(app, ctx) << "\n";
    });
}

}  // namespace demlight::cli
