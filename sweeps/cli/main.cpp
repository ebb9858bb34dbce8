// slipwalk: one binary, subcommands (DESIGN.md: Command line).
// Exit codes: 0 success; 1 the computation failed; 2 bad usage or bad input.
// Errors go to stderr as `slipwalk: error: <where>: <what>`.
#include <CLI/CLI.hpp>
#include <iostream>

#include "core/error.hpp"
#include "sweeps/cli/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"slipwalk: multi-legged locomotion with slipping — reproduce, check, extend"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Show help for every subcommand");
  slipwalk::cli::add_inchworm_command(app);
  slipwalk::cli::add_sweep_command(app);
  slipwalk::cli::add_reproduce_command(app);
  slipwalk::cli::add_model_command(app);
  slipwalk::cli::add_run_command(app);
  slipwalk::cli::add_kinds_command(app);
  try {
    app.parse(argc, argv);
    return 0;
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "slipwalk: error: " << e.what() << "\n";
    return 2;
  } catch (const slipwalk::core::InputError& e) {
    std::cerr << "slipwalk: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "slipwalk: error: " << e.what() << "\n";
    return 1;
  }
}
