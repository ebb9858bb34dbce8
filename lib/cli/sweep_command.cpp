#include "cli/commands.hpp"

namespace slipwalk::cli {
void add_sweep_command(CLI::App& app) { app.add_subcommand("sweep", "(not yet implemented)"); }
}  // namespace slipwalk::cli
