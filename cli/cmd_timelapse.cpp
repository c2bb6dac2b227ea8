// Placeholder: the 'timelapse' subcommand is not registered yet (work in progress).
#include "cli/commands.h"

namespace demlight::cli {

void registerTimelapse(CLI::App&, CliContext&) {}

}  // namespace demlight::cli
