// slipwalk: one binary, subcommands (DESIGN.md: Command line).
// Exit codes: 0 success; 1 the computation failed; 2 bad usage or bad input.
// Errors go to stderr as `slipwalk: error: <where>: <what>`.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/json_input.hpp"
#include "sweeps/cli/commands.hpp"
#include "sweeps/engine/mpi/mpi_run.hpp"

namespace {
/// The longest error message printed: room for a path, a place and a sentence.
constexpr std::size_t kMaxMessageBytes = 1024;
}  // namespace

std::string slipwalk::cli::error_line(const char* what) {
  return "slipwalk: error: " + slipwalk::core::text_excerpt(what, kMaxMessageBytes) + "\n";
}

int main(int argc, char** argv) {
  CLI::App app{"slipwalk: multi-legged locomotion with slipping — reproduce, check, extend"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Show help for every subcommand");
  slipwalk::cli::add_inchworm_command(app);
  slipwalk::cli::add_sweep_command(app);
  slipwalk::cli::add_reproduce_command(app);
  slipwalk::cli::add_model_command(app);
  slipwalk::cli::add_run_command(app);
  slipwalk::cli::add_plan_command(app);
  slipwalk::cli::add_residual_command(app);
  slipwalk::cli::add_calibrate_command(app);
  slipwalk::cli::add_kinds_command(app);
  // An interrupted command leaves no temporary behind; stale ones of killed runs are noted.
  slipwalk::core::install_signal_cleanup();
  slipwalk::core::set_note_stream(&std::cerr);
  // What went to stdout must have arrived: a full device or a closed pipe is a failed command.
  const auto stdout_failed = [] {
    std::cout.flush();
    errno = 0;
    if (std::fflush(stdout) != 0 || std::ferror(stdout) != 0 || !std::cout) {
      std::cerr << "slipwalk: error: <stdout>: write failed"
                << (errno != 0 ? std::string(": ") + std::strerror(errno) : std::string()) << "\n";
      return true;
    }
    return false;
  };
  const auto report = [](const char* what, int code) {
    std::cerr << slipwalk::cli::error_line(what);
    return code;
  };
  // Under an MPI launcher every rank runs this binary: only `slipwalk sweep` shares the work out
  // (and refuses when built without MPI); anything else would run once per rank, each writing the
  // same files. The refusal is printed by rank 0 alone.
  const auto merging = [&] {
    for (int i = 2; i < argc; ++i) {
      if (std::string(argv[i]) == "merge") {
        return true;
      }
    }
    return false;
  };
  if (slipwalk::sweeps::mpi::launched() &&
      (argc < 3 || std::string(argv[1]) != "sweep" || merging())) {
    if (slipwalk::sweeps::mpi::launched_rank() > 0) {
      return 2;
    }
    return report(
        "MPI launcher: only `slipwalk sweep SPEC` runs under mpirun or srun (not "
        "`sweep merge` or another command, which would run once per rank)",
        2);
  }
  try {
    app.parse(argc, argv);
    return stdout_failed() ? 1 : 0;
  } catch (const CLI::CallForHelp& e) {
    const int code = app.exit(e);
    return stdout_failed() ? 1 : code;
  } catch (const CLI::CallForAllHelp& e) {
    const int code = app.exit(e);
    return stdout_failed() ? 1 : code;
  } catch (const CLI::ParseError& e) {
    return report(e.what(), 2);
  } catch (const slipwalk::sweeps::mpi::QuietExit& e) {
    return e.code;  // another rank, rank 0, reported the error
  } catch (const slipwalk::core::InputError& e) {
    return report(e.what(), 2);
  } catch (const std::exception& e) {
    return report(e.what(), 1);
  }
}
