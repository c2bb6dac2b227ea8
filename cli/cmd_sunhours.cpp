// Placeholder: the 'sunhours' subcommand is not registered yet (work in progress).
#include "cli/commands.h"

namespace demlight::cli {

void registerSunhours(CLI::App&, CliContext&) {}

}  // namespace demlight::cli
