// slipwalk kinds [KIND...] [--json]: the point kinds a sweep spec may name, each with its summary
// and its columns (unit, and whether a column is a timing, zeroed by `sweep --no-timing`), read
// from the same column tables that write the CSVs.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "sweeps/cli/commands.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::cli {

namespace {

struct KindsCommand {
  std::vector<std::string> names;
  bool json = false;

  void run() const {
    const std::span<const sweeps::PointKind> all = sweeps::points::all_kinds();
    std::vector<sweeps::PointKind> chosen;
    for (const std::string& name : names) {
      const sweeps::PointKind* kind = sweeps::find_point_kind(all, name);
      if (kind == nullptr) {
        throw core::InputError(
            "KIND", "unknown kind '" + name + "'; expected " + sweeps::point_kind_names(all));
      }
      chosen.push_back(*kind);
    }
    const std::span<const sweeps::PointKind> shown =
        names.empty() ? all : std::span<const sweeps::PointKind>(chosen);
    if (json) {
      std::cout << sweeps::kinds_to_json(shown).dump(1) << "\n";
    } else {
      std::cout << sweeps::kinds_to_text(shown);
    }
  }
};

}  // namespace

void add_kinds_command(CLI::App& app) {
  auto cmd = std::make_shared<KindsCommand>();
  auto* sub = app.add_subcommand(
      "kinds", "the point kinds a sweep spec may name, with their columns, units and timings");
  sub->add_option("KIND", cmd->names, "kinds to describe (default: all)");
  sub->add_flag("--json", cmd->json, "print JSON instead of text");
  sub->callback([cmd] { cmd->run(); });
}

}  // namespace slipwalk::cli
