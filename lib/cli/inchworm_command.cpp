#include "cli/commands.hpp"

namespace slipwalk::cli {
void add_inchworm_command(CLI::App& app) {
  app.add_subcommand("inchworm", "(not yet implemented)");
}
}  // namespace slipwalk::cli
