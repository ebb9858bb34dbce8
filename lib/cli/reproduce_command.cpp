#include "cli/commands.hpp"

namespace slipwalk::cli {
void add_reproduce_command(CLI::App& app) {
  app.add_subcommand("reproduce", "(not yet implemented)");
}
}  // namespace slipwalk::cli
