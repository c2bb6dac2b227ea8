// Placeholder: the 'light' subcommand is not registered yet (work in progress).
#include "cli/commands.h"

namespace demlight::cli {

void registerLight(CLI::App&, CliContext&) {}

}  // namespace demlight::cli
