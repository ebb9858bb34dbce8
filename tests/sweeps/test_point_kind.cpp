// Point kinds as the runner sees them: a row type's column table gives the CSV header, the cells
// and the timing flags from one definition, so they agree by construction; timed kinds never run
// two points at once, not even across concurrent sweeps.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "cli/command.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/engine/runner.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps {
namespace {

using testing::read_text;
using testing::ScratchDir;

// --- rows whose cells are known from the point alone ---------------------------------------------

/// A row with a member of every cell type, each a different function of the point's `x`, so that
/// a cell written under the wrong name shows up as a wrong value.
struct MembersInOneOrder {
  long long id = 0;
  double x = 0.0;
  double twice = 0.0;
  long long steps = 0;
  bool odd = false;
  std::string label;
  double wall_s = 0.0;
  std::array<double, 3> leg{};

  static std::vector<Column<MembersInOneOrder>> columns() {
    using R = MembersInOneOrder;
    std::vector<Column<R>> table = {
        value("id", &R::id),         value("x", &R::x),     value("twice", &R::twice, "m"),
        value("steps", &R::steps),   value("odd", &R::odd), value("label", &R::label),
        timing("wall_s", &R::wall_s)};
    for (std::size_t k = 0; k < 3; ++k) {
      table.push_back(value_at("leg_" + std::to_string(k), &R::leg, k, "N"));
    }
    return table;
  }
};

/// The same columns, the members declared in another order: the CSV must not change.
struct MembersInAnotherOrder {
  std::array<double, 3> leg{};
  double wall_s = 0.0;
  std::string label;
  bool odd = false;
  long long steps = 0;
  double twice = 0.0;
  double x = 0.0;
  long long id = 0;

  static std::vector<Column<MembersInAnotherOrder>> columns() {
    using R = MembersInAnotherOrder;
    std::vector<Column<R>> table = {
        value("id", &R::id),         value("x", &R::x),     value("twice", &R::twice, "m"),
        value("steps", &R::steps),   value("odd", &R::odd), value("label", &R::label),
        timing("wall_s", &R::wall_s)};
    for (std::size_t k = 0; k < 3; ++k) {
      table.push_back(value_at("leg_" + std::to_string(k), &R::leg, k, "N"));
    }
    return table;
  }
};

/// The same members with the table listed in another order: header and cells move together.
struct TableInAnotherOrder {
  long long id = 0;
  double x = 0.0;
  double twice = 0.0;
  long long steps = 0;
  bool odd = false;
  std::string label;
  double wall_s = 0.0;
  std::array<double, 3> leg{};

  static std::vector<Column<TableInAnotherOrder>> columns() {
    using R = TableInAnotherOrder;
    std::vector<Column<R>> table = {value("id", &R::id)};
    for (std::size_t k = 3; k-- > 0;) {
      table.push_back(value_at("leg_" + std::to_string(k), &R::leg, k, "N"));
    }
    table.push_back(value("label", &R::label));
    table.push_back(timing("wall_s", &R::wall_s));
    table.push_back(value("odd", &R::odd));
    table.push_back(value("steps", &R::steps));
    table.push_back(value("twice", &R::twice, "m"));
    table.push_back(value("x", &R::x));
    return table;
  }
};

template <class Row>
Row row_of(const Point& p) {
  const Reader r(p, "test", {"x"});
  const double x = r.number("x", 0.0);
  Row row;
  row.id = p.id;
  row.x = x;
  row.twice = 2.0 * x;
  row.steps = static_cast<long long>(x) * 10;
  row.odd = static_cast<long long>(x) % 2 == 1;
  row.label = "x=" + std::to_string(static_cast<long long>(x));
  row.wall_s = 0.25 + x;  // "measured": zeroed under --no-timing
  row.leg = {x + 0.5, x + 1.5, x + 2.5};
  return row;
}

template <class Row>
PointKind kind_of(const std::string& name) {
  return make_point_kind<Row>(
      name, "test rows", Timed::kNo, [](const Point& p) { (void)row_of<Row>(p); },
      [](const Point& p) {
        return Rows<Row>{{row_of<Row>(p)}, false, false, ""};
      });
}

/// The spec text of a sweep over x = 1..n of `kind`.
std::string spec_of(const std::string& kind, int n, const std::string& name = "rows") {
  std::string xs;
  for (int i = 1; i <= n; ++i) {
    xs += (i > 1 ? ", " : "") + std::to_string(i) + ".0";
  }
  return "study = \"t\"\nname = \"" + name + "\"\nkind = \"" + kind + "\"\n[axes]\nx = [" + xs +
         "]\n";
}

/// A CSV as one map from column name to cell text per row.
std::vector<std::map<std::string, std::string>> parse_csv(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  const auto split = [](const std::string& l) {
    std::vector<std::string> cells;
    std::stringstream s(l);
    for (std::string c; std::getline(s, c, ',');) {
      cells.push_back(c);
    }
    return cells;
  };
  std::getline(in, line);
  header = split(line);
  while (std::getline(in, line)) {
    const auto cells = split(line);
    EXPECT_EQ(cells.size(), header.size()) << line;
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < std::min(cells.size(), header.size()); ++i) {
      row[header[i]] = cells[i];
    }
    rows.push_back(row);
  }
  return rows;
}

std::string run_to_csv(const std::vector<PointKind>& kinds, const std::string& kind,
                       const ScratchDir& dir, bool timing) {
  const PreparedSweep sweep = prepare(parse_spec(spec_of(kind, 5, kind), "rows.toml"), kinds);
  RunOptions options;
  options.data_dir = dir.path();
  options.jobs = 2;
  options.timing = timing;
  const RunSummary s = run(sweep, options);
  EXPECT_TRUE(s.complete);
  return read_text(s.csv);
}

TEST(PointKind, HeaderCellsAndTimingFlagsComeFromOneTable) {
  const PointKind k = kind_of<MembersInOneOrder>("one");
  ASSERT_EQ(k.columns.size(), 10U);
  EXPECT_EQ(k.column_names().front(), "id");
  EXPECT_EQ(k.columns[2].unit, "m");
  EXPECT_EQ(k.columns[9].name, "leg_2");
  EXPECT_EQ(k.columns[9].unit, "N");
  for (const ColumnInfo& c : k.columns) {
    EXPECT_EQ(c.timing, c.name == "wall_s") << c.name;
  }
  Point p;
  p.id = 7;
  p.values.emplace_back("x", Value{3.0, false, "here"});
  const PointResult r = k.run(p);
  ASSERT_EQ(r.rows.size(), 1U);
  ASSERT_EQ(r.rows[0].size(), k.columns.size());
  EXPECT_EQ(std::get<long long>(r.rows[0][0]), 7);
  EXPECT_EQ(std::get<double>(r.rows[0][2]), 6.0);
  EXPECT_EQ(std::get<long long>(r.rows[0][4]), 1);  // a bool is written as 0 or 1
  EXPECT_EQ(std::get<std::string>(r.rows[0][5]), "x=3");
  EXPECT_EQ(std::get<double>(r.rows[0][9]), 5.5);
}

TEST(PointKind, ReorderingTheMembersLeavesTheCsvByteIdentical) {
  const std::vector<PointKind> kinds = {kind_of<MembersInOneOrder>("a"),
                                        kind_of<MembersInAnotherOrder>("b")};
  const ScratchDir dir;
  const std::string a = run_to_csv(kinds, "a", dir, true);
  const std::string b = run_to_csv(kinds, "b", dir, true);
  EXPECT_EQ(a, b);
}

TEST(PointKind, ReorderingTheTableMovesEachCellWithItsName) {
  const std::vector<PointKind> kinds = {kind_of<MembersInOneOrder>("a"),
                                        kind_of<TableInAnotherOrder>("c")};
  const ScratchDir dir;
  const auto a = parse_csv(run_to_csv(kinds, "a", dir, true));
  const auto c = parse_csv(run_to_csv(kinds, "c", dir, true));
  ASSERT_EQ(a.size(), 5U);
  ASSERT_EQ(c.size(), 5U);
  EXPECT_EQ(a, c);  // the same cell under every name
  const std::string header_c = read_text(dir.path() / "t" / "c.csv").substr(0, 4);
  EXPECT_EQ(header_c, "id,l");  // and the columns really are in the other order
  EXPECT_EQ(a[2].at("twice"), "6");
  EXPECT_EQ(a[2].at("leg_1"), "4.5");
}

TEST(PointKind, NoTimingZeroesExactlyTheTimingColumns) {
  const std::vector<PointKind> kinds = {kind_of<MembersInOneOrder>("a")};
  const ScratchDir timed;
  const ScratchDir untimed;
  const auto with = parse_csv(run_to_csv(kinds, "a", timed, true));
  const auto without = parse_csv(run_to_csv(kinds, "a", untimed, false));
  ASSERT_EQ(with.size(), without.size());
  for (std::size_t i = 0; i < with.size(); ++i) {
    for (const auto& [name, cell] : with[i]) {
      if (name == "wall_s") {
        EXPECT_NE(cell, "0");
        EXPECT_EQ(without[i].at(name), "0");
      } else {
        EXPECT_EQ(without[i].at(name), cell) << name;
      }
    }
  }
}

struct NoIdFirst {
  double x = 0.0;
  long long id = 0;
  static std::vector<Column<NoIdFirst>> columns() {
    return {value("x", &NoIdFirst::x), value("id", &NoIdFirst::id)};
  }
};

TEST(PointKind, ATableThatDoesNotStartWithIdIsRefused) {
  EXPECT_THROW((void)make_point_kind<NoIdFirst>(
                   "bad", "", Timed::kNo, [](const Point&) {},
                   [](const Point&) { return Rows<NoIdFirst>{}; }),
               std::logic_error);
}

// --- the shipped kinds ---------------------------------------------------------------------------

TEST(PointKind, EveryShippedKindHasUniqueColumnsStartingWithId) {
  std::vector<std::string> names;
  for (const PointKind& k : points::all_kinds()) {
    names.push_back(k.name);
    ASSERT_FALSE(k.columns.empty()) << k.name;
    EXPECT_EQ(k.columns.front().name, "id") << k.name;
    std::vector<std::string> columns = k.column_names();
    std::sort(columns.begin(), columns.end());
    EXPECT_EQ(std::adjacent_find(columns.begin(), columns.end()), columns.end())
        << k.name << " names a column twice";
    EXPECT_FALSE(k.summary.empty()) << k.name;
  }
  std::sort(names.begin(), names.end());
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end());
}

TEST(PointKind, EveryTimedKindWritesAtLeastOneTimingColumn) {
  int timed = 0;
  for (const PointKind& k : points::all_kinds()) {
    if (k.timed == Timed::kYes) {
      ++timed;
      EXPECT_TRUE(std::any_of(k.columns.begin(), k.columns.end(), [](const ColumnInfo& c) {
        return c.timing;
      })) << k.name;
    }
  }
  EXPECT_GE(timed, 1);
}

// --- timed kinds take turns ----------------------------------------------------------------------

struct Interval {
  std::string kind;
  std::chrono::steady_clock::time_point start;
  std::chrono::steady_clock::time_point end;
};

struct IdRow {
  long long id = 0;
  static std::vector<Column<IdRow>> columns() { return {value("id", &IdRow::id)}; }
};

/// A kind whose every point records when it ran and takes `hold` doing it.
PointKind recording_kind(const std::string& name, Timed timed, std::chrono::milliseconds hold,
                         std::vector<Interval>& log, std::mutex& log_mutex) {
  return make_point_kind<IdRow>(
      name, "records its interval", timed, [](const Point&) {},
      [name, hold, &log, &log_mutex](const Point& p) {
        Interval i{name, std::chrono::steady_clock::now(), {}};
        std::this_thread::sleep_for(hold);
        i.end = std::chrono::steady_clock::now();
        const std::lock_guard lock(log_mutex);
        log.push_back(i);
        return Rows<IdRow>{{IdRow{p.id}}, false, false, ""};
      });
}

/// Pairs of intervals that overlap in time.
int overlaps(const std::vector<Interval>& log) {
  int n = 0;
  for (std::size_t i = 0; i < log.size(); ++i) {
    for (std::size_t j = i + 1; j < log.size(); ++j) {
      n += log[i].start < log[j].end && log[j].start < log[i].end ? 1 : 0;
    }
  }
  return n;
}

/// Runs sweeps of `a` and `b` (8 points each, 2 threads each) at the same time on two threads.
void run_two_sweeps_at_once(const std::vector<PointKind>& kinds, const std::string& a,
                            const std::string& b, const ScratchDir& dir) {
  const auto one = [&](const std::string& kind) {
    const PreparedSweep sweep = prepare(parse_spec(spec_of(kind, 8, kind), "t.toml"), kinds);
    RunOptions options;
    options.data_dir = dir.path();
    options.jobs = 2;
    EXPECT_TRUE(run(sweep, options).complete);
  };
  std::thread other(one, b);
  one(a);
  other.join();
}

/// The intervals of two recording kinds `a` and `b` (each timed or not, each point taking `hold`)
/// whose sweeps run at the same time.
std::vector<Interval> log_of_concurrent_sweeps(const std::string& a, Timed timed_a,
                                               const std::string& b, Timed timed_b,
                                               std::chrono::milliseconds hold) {
  std::vector<Interval> log;
  std::mutex log_mutex;
  const std::vector<PointKind> kinds = {recording_kind(a, timed_a, hold, log, log_mutex),
                                        recording_kind(b, timed_b, hold, log, log_mutex)};
  const ScratchDir dir;
  run_two_sweeps_at_once(kinds, a, b, dir);
  return log;
}

TEST(TimedPoints, TwoTimedKindsInConcurrentSweepsNeverOverlapInTime) {
  const std::vector<Interval> log = log_of_concurrent_sweeps(
      "timed_a", Timed::kYes, "timed_b", Timed::kYes, std::chrono::milliseconds(15));
  ASSERT_EQ(log.size(), 16U);
  EXPECT_EQ(overlaps(log), 0);
}

TEST(TimedPoints, UntimedKindsDoRunSideBySideSoTheCheckAboveCanFail) {
  const std::vector<Interval> log = log_of_concurrent_sweeps(
      "free_a", Timed::kNo, "free_b", Timed::kNo, std::chrono::milliseconds(40));
  ASSERT_EQ(log.size(), 16U);
  EXPECT_GT(overlaps(log), 0);
}

TEST(TimedPoints, ATimedKindDoesNotHoldBackUntimedPoints) {
  const std::vector<Interval> log = log_of_concurrent_sweeps(
      "timed", Timed::kYes, "free", Timed::kNo, std::chrono::milliseconds(40));
  std::vector<Interval> timed;
  for (const Interval& i : log) {
    if (i.kind == "timed") {
      timed.push_back(i);
    }
  }
  ASSERT_EQ(timed.size(), 8U);
  EXPECT_EQ(overlaps(timed), 0);
  EXPECT_GT(overlaps(log), 0);
}

}  // namespace
}  // namespace slipwalk::sweeps
