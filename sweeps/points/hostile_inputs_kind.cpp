// hostile_inputs: the hostile-input campaign (hostile_inputs.hpp) as a point kind. One point runs
// `count` cases of one class, from case `first`, generated from `seed`, each by the slipwalk
// binary that runs the sweep (/proc/self/exe) in its own temporary folder; its row counts the
// outcomes and gives the first bad case as a line to replay. A point with a bad case is marked
// failed (the sweep goes on and counts it).
#include <filesystem>
#include <string>
#include <vector>

#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/points/families.hpp"
#include "sweeps/points/hostile_inputs.hpp"
#include "sweeps/points/subprocess.hpp"

namespace slipwalk::sweeps::points {

namespace {

const std::vector<std::string_view> kKeys = {"class", "seed", "first", "count"};

struct CampaignRow {
  long long id = 0;
  std::string cls;
  std::string title;
  std::string what;
  long long seed = 0;
  long long first = 0;
  long long tried = 0;
  long long ok = 0;
  long long crashes = 0;
  long long hangs = 0;
  long long wrong_exit = 0;
  long long no_place = 0;
  long long false_success = 0;
  long long clobbered = 0;
  long long leftovers = 0;
  double max_wall_s = 0.0;
  std::string first_failure;

  static std::vector<Column<CampaignRow>> columns() {
    using R = CampaignRow;
    return {value("id", &R::id),
            value("class", &R::cls),
            value("title", &R::title),
            value("what", &R::what),
            value("seed", &R::seed),
            value("first", &R::first),
            value("tried", &R::tried),
            value("ok", &R::ok),
            value("crashes", &R::crashes),
            value("hangs", &R::hangs),
            value("wrong_exit", &R::wrong_exit),
            value("no_place", &R::no_place),
            value("false_success", &R::false_success),
            value("clobbered", &R::clobbered),
            value("leftovers", &R::leftovers),
            timing("max_wall_s", &R::max_wall_s, "s"),
            value("first_failure", &R::first_failure)};
  }
};

struct Inputs {
  const hostile::HostileClass* cls = nullptr;
  long long seed = 1;
  long long first = 0;
  long long count = 10;
};

Inputs read_inputs(const Point& point) {
  const Reader r(point, "hostile_inputs", kKeys);
  Inputs in;
  std::vector<std::string_view> ids;
  for (const hostile::HostileClass& c : hostile::classes()) {
    ids.emplace_back(c.id);
  }
  in.cls = hostile::find_class(r.choice("class", ids));
  in.seed = r.integer("seed", in.seed, 0, 1'000'000'000'000LL);
  in.first = r.integer("first", in.first, 0, 1'000'000'000LL);
  in.count = r.integer("count", in.count, 1, 100'000);
  return in;
}

Rows<CampaignRow> run_point(const Point& point) {
  const Inputs in = read_inputs(point);
  const std::filesystem::path binary = self_executable();
  const std::filesystem::path scratch = std::filesystem::temp_directory_path();
  hostile::Tally tally;
  for (long long i = in.first; i < in.first + in.count; ++i) {
    const hostile::Case c = in.cls->generate(static_cast<std::uint64_t>(in.seed), i);
    tally.add(i, c, hostile::run_case(binary, c, scratch));
  }
  Rows<CampaignRow> out;
  out.rows.push_back({point.id, in.cls->id, in.cls->title, in.cls->what, in.seed, in.first,
                      tally.tried, tally.ok, tally.crashes, tally.hangs, tally.wrong_exit,
                      tally.no_place, tally.false_success, tally.clobbered, tally.leftovers,
                      tally.max_wall_s, tally.first_failure});
  if (tally.ok != tally.tried) {
    out.failed = true;
    out.message = std::to_string(tally.tried - tally.ok) + " of " + std::to_string(tally.tried) +
                  " cases broke the contract";
  }
  return out;
}

}  // namespace

std::vector<PointKind> hostile_input_kinds() {
  return {make_point_kind<CampaignRow>(
      "hostile_inputs",
      "runs the slipwalk binary on generated hostile inputs of one class (depth, runaway, "
      "magnitude, signals, paths, loss) and counts what broke the command-line contract",
      Timed::kNo, [](const Point& p) { (void)read_inputs(p); }, run_point)};
}

}  // namespace slipwalk::sweeps::points
