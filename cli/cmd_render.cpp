// Placeholder: the 'render' subcommand is not registered yet (work in progress).
#include "cli/commands.h"

namespace demlight::cli {

void registerRender(CLI::App&, CliContext&) {}

}  // namespace demlight::cli
