// scene_cost: what each effect of a scene costs per step (unused effects must cost nothing,
// DESIGN.md: "Only the effects a scene calls for"). One point times, in one run and interleaved,
// the hand-written flat isotropic viscous kernel (scene/reference_kernel.hpp) and composed
// simulators of BigANT's tripod with exactly one effect each: none (flat isotropic viscous),
// anisotropic friction, Coulomb friction, the inertia filter, the residual B, measurement noise,
// a slope, stairs. Each repeat runs every case once (CPU time of the calling thread, the runs'
// buffers included, as in `slipwalk run`), so a slow moment of a shared machine hits every case
// alike; ratios are taken per repeat and their median reported. The kind is timed: the runner
// runs its points one at a time, whatever --jobs says.
//
// Rows, one per case: the median and quartiles of the time per step, the median ratio to the
// hand-written kernel, and the median extra time per step over the composed flat viscous scene
// with its share of that scene's time.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "scene/reference_kernel.hpp"
#include "scene/scene.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/engine/timing.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps::points {

namespace {

const std::vector<std::string_view> kKeys = {"steps", "repeats", "frequency"};

/// One row per case. Every number is a measured time or computed from measured times.
struct CaseRow {
  long long id = 0;
  std::string effect;  ///< the case: the effect it adds
  std::string kernel;  ///< the kernel the composed simulator runs
  long long steps = 0;
  long long repeats = 0;
  double ns_per_step = 0.0;  ///< median over the repeats
  double ns_per_step_p25 = 0.0;
  double ns_per_step_p75 = 0.0;
  double ratio_to_handwritten = 0.0;  ///< median over the repeats of the ratio of the times
  double extra_ns_per_step = 0.0;     ///< median over the repeats, over the composed flat scene
  double share_of_flat = 0.0;         ///< extra_ns_per_step / the flat scene's ns_per_step

  static std::vector<Column<CaseRow>> columns() {
    using R = CaseRow;
    return {value("id", &R::id),
            value("case", &R::effect),
            value("kernel", &R::kernel),
            value("steps", &R::steps),
            value("repeats", &R::repeats),
            timing("ns_per_step", &R::ns_per_step, "ns"),
            timing("ns_per_step_p25", &R::ns_per_step_p25, "ns"),
            timing("ns_per_step_p75", &R::ns_per_step_p75, "ns"),
            timing("ratio_to_handwritten", &R::ratio_to_handwritten, ""),
            timing("extra_ns_per_step", &R::extra_ns_per_step, "ns"),
            timing("share_of_flat", &R::share_of_flat, "")};
  }
};

struct Case {
  std::string name;       ///< the effect it adds ("handwritten", "none", "anisotropic", ...)
  std::string table;      ///< the scene's extra text: [friction] and effect tables
  bool residual = false;  ///< add a residual B (built here, no file needed)
};

const std::vector<Case>& cases() {
  static const std::vector<Case> all = {
      {"handwritten", "[friction]\nlaw = \"viscous\"\n", false},
      {"none", "[friction]\nlaw = \"viscous\"\n", false},
      {"anisotropic", "[friction]\nlaw = \"anisotropic\"\nw = [0.8, 0.3]\n", false},
      {"coulomb", "[friction]\nlaw = \"coulomb\"\n", false},
      {"filter", "[friction]\nlaw = \"viscous\"\n[filter]\ngamma = 0.15\n", false},
      {"residual", "[friction]\nlaw = \"viscous\"\n", true},
      {"noise", "[friction]\nlaw = \"viscous\"\n[noise]\nsigma = 0.001\nsigma_theta = 0.01\n",
       false},
      {"slope", "[friction]\nlaw = \"viscous\"\n[terrain]\nkind = \"slope\"\nangle_deg = 10.0\n",
       false},
      {"stairs",
       "[friction]\nlaw = \"viscous\"\n[terrain]\nkind = \"stairs\"\ntread = 0.3\nriser = 0.12\n",
       false},
  };
  return all;
}

struct Inputs {
  long long steps = 2000;
  long long repeats = 21;
  double frequency = 0.5;
};

Inputs read_inputs(const Point& point) {
  const Reader r(point, "scene_cost", kKeys);
  Inputs in;
  in.steps = r.integer("steps", in.steps, 1, 10'000'000);
  in.repeats = r.integer("repeats", in.repeats, 1, 100'000);
  in.frequency = r.number("frequency", in.frequency, 1e-6, 100.0);
  // Every repeat runs every case (nine) for steps + 1 frames.
  r.limit_work("repeats", "steps · repeats",
               static_cast<double>(in.steps) * static_cast<double>(in.repeats), 1e8);
  return in;
}

scene::Scene scene_of(const Case& c, const Inputs& in) {
  const std::string text =
      "[robot]\nname = \"bigant\"\n[gait]\nkind = \"tripod\"\nfrequency = " +
      std::to_string(in.frequency) + "\n[run]\nsteps = " + std::to_string(in.steps) +
      "\nduration = " + std::to_string(0.01 * static_cast<double>(in.steps)) + "\n" + c.table;
  scene::Scene s = scene::parse_scene(text, "scene_cost:" + c.name);
  if (c.residual) {
    // A B of the size of thesis Fig. 5.5's corrections: a few percent of the connection.
    scene::ResidualEffect r;
    r.file = "(built in)";
    r.B = Eigen::Matrix<double, 3, Eigen::Dynamic>::Constant(3, 12, 0.01);
    r.B.row(1) *= -1.0;
    s.residual = r;
  }
  return s;
}

Rows<CaseRow> run_point(const Point& point) {
  const Inputs in = read_inputs(point);
  std::vector<scene::Scene> scenes;
  std::vector<scene::Simulator> sims;
  for (const Case& c : cases()) {
    scenes.push_back(scene_of(c, in));
    sims.push_back(scene::compose(scenes.back()));
  }
  // The sink reads what a CSV writer would and keeps it observable.
  double observed = 0.0;
  const connection::TrajectorySink sink = [&observed](const connection::TrajectoryStep& s) {
    observed += s.measured.x + s.v_body(0) + s.slip(0, 0) + s.frame.Fz(0);
  };
  const std::size_t n = cases().size();
  std::vector<std::vector<double>> ns(n);
  const double per_run = static_cast<double>(in.steps + 1);
  for (long long r = -1; r < in.repeats; ++r) {  // r = −1 warms up
    for (std::size_t i = 0; i < n; ++i) {
      const double t0 = thread_cpu_seconds();
      if (i == 0) {
        connection::TrajectoryData data(sims[0].walker.robot);
        (void)scene::run_flat_viscous(sims[0].walker, sims[0].options, data, sink);
      } else {
        (void)sims[i].run(sink);
      }
      const double s = thread_cpu_seconds() - t0;
      if (r >= 0) {
        ns[i].push_back(1e9 * s / per_run);
      }
    }
  }
  Rows<CaseRow> out;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<double> ratio;
    std::vector<double> extra;
    for (std::size_t r = 0; r < ns[i].size(); ++r) {
      ratio.push_back(ns[i][r] / ns[0][r]);
      extra.push_back(ns[i][r] - ns[1][r]);
    }
    const double extra_ns = median(extra);
    out.rows.push_back({point.id, cases()[i].name,
                        i == 0 ? std::string("handwritten") : sims[i].kernel_name, in.steps,
                        in.repeats, median(ns[i]), quantile(ns[i], 0.25), quantile(ns[i], 0.75),
                        median(ratio), extra_ns, extra_ns / median(ns[1])});
  }
  if (!(observed == observed)) {  // a NaN in the outputs: say so rather than time garbage
    out.failed = true;
    out.message = "a run produced NaN";
  }
  return out;
}

}  // namespace

std::vector<PointKind> scene_cost_kinds() {
  return {make_point_kind<CaseRow>(
      "scene_cost",
      "time per step of BigANT's tripod through the hand-written flat isotropic viscous kernel "
      "and composed scenes with one effect each (one row per case)",
      Timed::kYes, [](const Point& p) { (void)read_inputs(p); }, run_point)};
}

}  // namespace slipwalk::sweeps::points
