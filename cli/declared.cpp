#include "cli/declared.h"

#include <cstdlib>
#include <map>

namespace demlight::cli {

namespace {

std::string joined(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ",") + n;
    return out;
}

}  // namespace

Naming messageNaming() {
    const char* names = std::getenv("DEMLIGHT_PARAMETER_NAMES");
    return names && std::string(names) == "qgis" ? Naming::Qgis : Naming::CommandLine;
}

CLI::App* addDeclaredCommand(CLI::App& app, ParameterSet& set, CliContext& ctx) {
    CLI::App* cmd = app.add_subcommand(set.command(), set.description());
    // Run by the QGIS provider, a bad value is reported as the library's errors are, naming the
    // parameter by its label (main's describeError), not as CLI11's usage error naming a flag.
    const bool labels = messageNaming() == Naming::Qgis;
    ctx.declarations[set.command()] = &set;
    std::map<std::string, CLI::Option*> made;
    for (Parameter& p : set.parameters()) {
        if (!p.shownIn(kCommandLine)) continue;
        const std::string help = renderNames(p.help, &set, Naming::CommandLine);
        const std::string flags = p.positional ? p.cliFlags : joined(p.commandLineNames());
        CLI::Option* opt = nullptr;
        if (p.kind == ValueKind::Flag) {
            opt = cmd->add_flag_callback(flags, [&p] { p.store({}); }, help);
        } else {
            opt = cmd->add_option(
                flags,
                [&p](const CLI::results_t& values) {
                    p.store(values);
                    return true;
                },
                help);
            opt->type_name(p.typeName);
            if (p.maxValues < 0) {
                opt->expected(p.minValues, -1)->allow_extra_args(true);
                opt->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
            } else {
                opt->expected(p.minValues, p.maxValues);
            }
            if (p.defaultText) opt->default_str(*p.defaultText);
            const Parameter* param = &p;
            opt->check(CLI::Validator(
                [param, labels, &ctx, &set](std::string& v) {
                    std::string problem = param->problem(v);
                    if (!problem.empty() && labels) {
                        ctx.running = &set;
                        throw ParameterError("{" + param->name + "}: " + problem);
                    }
                    return problem;
                },
                p.checkText()));
        }
        if (p.required) opt->required();
        made[p.name] = opt;
    }
    for (const Parameter& p : set.parameters())
        for (const std::string& other : p.excludes)
            if (made.count(p.name) && made.count(other)) made[p.name]->excludes(made[other]);
    for (const Parameter& p : set.parameters())
        for (const std::string& other : p.needs)
            if (made.count(p.name) && made.count(other)) made[p.name]->needs(made[other]);
    cmd->parse_complete_callback([&ctx, &set] { ctx.running = &set; });
    return cmd;
}

}  // namespace demlight::cli
