// Placeholder: the 'aperture' subcommand is not registered yet (work in progress).
#include "cli/commands.h"

namespace demlight::cli {

void registerAperture(CLI::App&, CliContext&) {}

}  // namespace demlight::cli
