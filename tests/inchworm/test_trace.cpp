// Traces (Fig. 2.2): every method gives the same motion; each collision row pair shows the
// plastic collision (common velocity) and the swap (CoM jump ρ·d).
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "inchworm/trace.hpp"

namespace slipwalk::inchworm {
namespace {

// Columns: 0 t, 1 x, 2 y, 3 z, 4 com, 5 xdot, 6 ydot, 7 zdot, 8 comdot, 9 phase, 10 slide_x,
// 11 slide_y, 12 side, then the event.
struct Row {
  std::vector<double> v;
  std::string event;
};

std::vector<Row> parse(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "t,x,y,z,com,xdot,ydot,zdot,comdot,phase,slide_x,slide_y,side,event");
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    Row r;
    std::istringstream cells(line);
    std::string cell;
    for (int i = 0; i < 13 && std::getline(cells, cell, ','); ++i) {
      r.v.push_back(std::stod(cell));
    }
    std::getline(cells, r.event);
    rows.push_back(r);
  }
  return rows;
}

std::vector<Row> trace(Method method) {
  Params p;
  p.F = 45.0;
  TraceOptions opt;
  opt.cycles = 3;
  opt.rtol = 1e-11;
  std::ostringstream out;
  write_trace(p, method, opt, out);
  return parse(out.str());
}

TEST(Trace, CollisionsKeepMomentumAndSwapJumpsTheCoM) {
  const Params p;
  const auto rows = trace(Method::kAnalytic);
  int collisions = 0;
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    if (rows[i].event != "collision_before") {
      continue;
    }
    ++collisions;
    const Row& before = rows[i];
    const Row& after = rows[i + 1];
    ASSERT_EQ(after.event, "collision_after");
    EXPECT_NEAR(after.v[8], before.v[8], 1e-14);  // CoM velocity kept (eq. 2.4)
    EXPECT_EQ(after.v[5], after.v[6]);            // common velocity
    const double d = before.v[1] - before.v[2];
    EXPECT_NEAR(after.v[4] - before.v[4], p.swap_ratio() * d, 1e-14);  // CoM jump ρ·d
    EXPECT_EQ(after.v[12], -before.v[12]);                             // next stroke
  }
  EXPECT_EQ(collisions, 6);  // three cycles of two strokes
}

TEST(Trace, EveryMethodTracesTheSameMotion) {
  const auto reference = trace(Method::kAnalytic);
  for (Method m : {Method::kCvode, Method::kOdeint, Method::kGsl}) {
    const auto rows = trace(m);
    ASSERT_EQ(rows.back().event, "collision_after") << method_name(m);
    for (int col : {0, 1, 2, 4, 8}) {
      EXPECT_NEAR(rows.back().v[col], reference.back().v[col], 1e-8)
          << method_name(m) << " column " << col;
    }
  }
}

}  // namespace
}  // namespace slipwalk::inchworm
