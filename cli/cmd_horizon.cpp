#include "cli/commands.h"
namespace demlight::cli {
void registerHorizon(CLI::App&, CliContext&) {}
}  // namespace demlight::cli
