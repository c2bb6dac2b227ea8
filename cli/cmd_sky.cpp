// Placeholder: the 'sky' subcommand is not registered yet (work in progress).
#include "cli/commands.h"

namespace demlight::cli {

void registerSky(CLI::App&, CliContext&) {}

}  // namespace demlight::cli
