// slipwalk kinds: the point kinds with their column tables as a user reads them — the same names,
// units and timing flags that write the CSV headers and drive `sweep --no-timing`.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli/command.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::cli {
namespace {

using namespace slipwalk::testing;  // NOLINT(google-build-using-namespace): test helpers

TEST(CliKinds, JsonListsEveryKindWithTheColumnsItsCsvWrites) {
  const CommandResult r = run_slipwalk({"kinds", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto out = nlohmann::json::parse(r.out);
  const auto kinds = sweeps::points::all_kinds();
  ASSERT_EQ(out.size(), kinds.size());
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    const auto& k = out[i];
    EXPECT_EQ(k["name"], kinds[i].name);
    EXPECT_EQ(k["timed"], kinds[i].timed == sweeps::Timed::kYes);
    ASSERT_EQ(k["columns"].size(), kinds[i].columns.size()) << kinds[i].name;
    EXPECT_EQ(k["columns"][0]["name"], "id");
    for (std::size_t c = 0; c < kinds[i].columns.size(); ++c) {
      EXPECT_EQ(k["columns"][c]["name"], kinds[i].columns[c].name);
      EXPECT_EQ(k["columns"][c]["unit"], kinds[i].columns[c].unit);
      EXPECT_EQ(k["columns"][c]["timing"], kinds[i].columns[c].timing);
    }
  }
}

TEST(CliKinds, NamedKindsShowTheirUnitsAndTimings) {
  const CommandResult r = run_slipwalk({"kinds", "inchworm_vss", "scene_cost"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("inchworm_vss\n"), 0U) << r.out;
  EXPECT_NE(r.out.find(" v_ss [m/s]"), std::string::npos);
  EXPECT_NE(r.out.find(" wall_s [s, timing]"), std::string::npos);
  EXPECT_NE(r.out.find("scene_cost (timed)"), std::string::npos);
  EXPECT_EQ(r.out.find("legged_1d"), std::string::npos);  // only the kinds named
}

TEST(CliKinds, AnUnknownKindIsBadInputNamingTheKnownOnes) {
  const CommandResult r = run_slipwalk({"kinds", "inchworm_vs"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("KIND: unknown kind 'inchworm_vs'; expected inchworm_vss|"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(r.out.empty());
}

}  // namespace
}  // namespace slipwalk::cli
