#include "cli/commands.h"
namespace demlight::cli {
void registerSun(CLI::App&, CliContext&) {}
}  // namespace demlight::cli
