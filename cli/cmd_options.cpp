// demlight options --json (hidden): every command's declaration (demlight/run/parameters.h) as
// JSON, for programs that drive the CLI (the QGIS provider in qgis/ builds its algorithms from
// it), so that no parameter, default or help text is written a second time.
#include "cli/commands.h"

#include <nlohmann/json.hpp>

#include <iostream>

namespace demlight::cli {

std::string optionsJson(const CLI::App& app, const CliContext& ctx) {
    // The declarations of the listed commands (hidden ones have no group), with what only the
    // command line knows: its --help text and what -o names.
    std::vector<const ParameterSet*> sets;
    std::vector<const CLI::App*> apps;
    for (const CLI::App* sub : app.get_subcommands({})) {
        const auto declared = ctx.declarations.find(sub->get_name());
        if (sub->get_group().empty() || declared == ctx.declarations.end()) continue;
        sets.push_back(declared->second);
        apps.push_back(sub);
    }
    nlohmann::ordered_json root;
    root["version"] = DEMLIGHT_VERSION;
    root["commands"] = nlohmann::ordered_json::parse(declarationsJson(sets))["commands"];
    for (std::size_t i = 0; i < apps.size(); ++i) {
        nlohmann::ordered_json& c = root["commands"][i];
        const CLI::App& cmd = *apps[i];
        c["help"] = cmd.help(cmd.get_parent() ? cmd.get_parent()->get_name() : std::string());  // "Usage: demlight sun ..."
        const auto declared = ctx.outputs.find(cmd.get_name());
        const CommandOutputs outputs = declared == ctx.outputs.end() ? CommandOutputs{} : declared->second;
        const ParameterSet& set = *sets[i];
        c["output"] = !set.find("output")     ? nlohmann::ordered_json()
                      : !outputs.kind.empty() ? nlohmann::ordered_json(outputs.kind)
                      : set.find("format")    ? nlohmann::ordered_json("raster")
                                              : nlohmann::ordered_json("file");
        c["companions"] = outputs.companionKeys;
    }
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
