// slope_progress and stall_slope (thesis §5.2.1: the slope at which the tripod gait stops making
// progress): BigANT's alternating tripod walking straight up a slope (uphill = its heading),
// composed from a scene exactly as `slipwalk run` would (scene::compose).
//
// Progress per gait cycle: the uphill displacement over cycles 2 … n divided by n − 1 (the first
// cycle starts from the gait's initial pose and is left out). A frame whose Coulomb balance does
// not exist (the load exceeds what friction holds: the robot slides) makes the run "sliding":
// the quasi-static model says nothing about how far it slides, so such a run counts as no
// progress (−∞ for the bisection) and says so in the sliding_frames column.
//
// stall_slope bisects on the sign of the progress between lo_deg (progress > 0) and hi_deg
// (progress ≤ 0) down to tol_deg; one row per probe, every row carrying the final estimate (the
// bracket's midpoint).
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/csv.hpp"
#include "scene/scene.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps::points {

namespace {

// --- one walk up a slope ------------------------------------------------------------------------

struct Walk {
  std::string law = "viscous";
  double frequency = 0.1;      ///< Hz
  long long cycles = 3;        ///< gait cycles simulated (≥ 2)
  long long per_cycle = 1000;  ///< steps per cycle
  double com_height = 0.0;     ///< m
};

struct Probe {
  double progress = 0.0;        ///< m per cycle, uphill
  long long sliding = 0;        ///< frames without a balance (Coulomb: the robot slides)
  long long not_converged = 0;  ///< other frames whose friction solve did not converge
  long long unsupported = 0;
};

Walk read_walk(const Reader& r) {
  Walk w;
  w.law = r.choice("law", {"viscous", "coulomb"});
  // The walk is a scene (scene/ranges.hpp): its frequency and steps must be a scene's.
  w.frequency = r.number("frequency", w.frequency, core::closed(1e-6, 100.0, "Hz"));
  w.cycles = r.integer("cycles", w.cycles, 2, 1000);
  w.per_cycle = r.integer("steps_per_cycle", w.per_cycle, 10, 1'000'000);
  w.com_height = r.number("com_height", w.com_height, 0.0, 10.0, true);
  r.limit_work("steps_per_cycle", "cycles · steps_per_cycle",
               static_cast<double>(w.cycles) * static_cast<double>(w.per_cycle),
               static_cast<double>(scene::kMaxSteps));
  return w;
}

Probe walk_up(const Walk& w, double angle_deg) {
  const double period = 1.0 / w.frequency;
  const long long steps = w.cycles * w.per_cycle;
  const std::string text =
      "[robot]\nname = \"bigant\"\n[gait]\nkind = \"tripod\"\nfrequency = " +
      core::format_double(w.frequency) +
      "\n[run]\nduration = " + core::format_double(period * static_cast<double>(w.cycles)) +
      "\nsteps = " + std::to_string(steps) + "\n[friction]\nlaw = \"" + w.law +
      "\"\n[terrain]\nkind = \"slope\"\nangle_deg = " + core::format_double(angle_deg) +
      "\ncom_height = " + core::format_double(w.com_height) + "\n";
  const scene::Simulator sim = scene::compose(scene::parse_scene(text, "slope_progress"));
  double x_after_first = 0.0;
  double x_end = 0.0;
  Probe p;
  const connection::TrajectorySummary summary = sim.run([&](const connection::TrajectoryStep& s) {
    if (s.n == w.per_cycle) {
      x_after_first = s.pose.x;  // uphill is +x of the plane (heading 0, start facing +x)
    }
    x_end = s.pose.x;
    const contact::FrictionSummary& f = s.frame.friction;
    if (!f.converged && f.message.rfind("sliding", 0) == 0) {
      ++p.sliding;
    }
  });
  p.not_converged = summary.not_converged - p.sliding;
  p.unsupported = summary.unsupported;
  p.progress = (x_end - x_after_first) / static_cast<double>(w.cycles - 1);
  if (summary.non_finite_step >= 0) {
    p.progress = std::numeric_limits<double>::quiet_NaN();  // no result: the walk stopped
  }
  return p;
}

/// The bisection's view of a probe: sliding counts as no progress at all.
double signed_progress(const Probe& p) {
  return p.sliding > 0 ? -std::numeric_limits<double>::infinity() : p.progress;
}

// --- slope_progress -----------------------------------------------------------------------------

const std::vector<std::string_view> kProgressKeys = {"law",    "angle_deg",       "frequency",
                                                     "cycles", "steps_per_cycle", "com_height"};

struct ProgressInputs {
  Walk walk;
  double angle_deg = 0.0;
};

ProgressInputs read_progress(const Point& point) {
  const Reader r(point, "slope_progress", kProgressKeys);
  ProgressInputs in;
  in.walk = read_walk(r);
  in.angle_deg = r.number("angle_deg", 0.0, 0.0, 89.0, true);
  return in;
}

/// One row per point: the walk's uphill progress and its troubled frames.
struct ProgressRow {
  long long id = 0;
  std::string law;
  double angle_deg = 0.0;
  double progress_per_cycle = 0.0;
  long long sliding_frames = 0;
  long long not_converged_frames = 0;
  long long unsupported_frames = 0;

  static std::vector<Column<ProgressRow>> columns() {
    using R = ProgressRow;
    return {value("id", &R::id),
            value("law", &R::law),
            value("angle_deg", &R::angle_deg, "deg"),
            value("progress_per_cycle", &R::progress_per_cycle, "m"),
            value("sliding_frames", &R::sliding_frames),
            value("not_converged_frames", &R::not_converged_frames),
            value("unsupported_frames", &R::unsupported_frames)};
  }
};

Rows<ProgressRow> run_progress(const Point& point) {
  const ProgressInputs in = read_progress(point);
  const Probe p = walk_up(in.walk, in.angle_deg);
  Rows<ProgressRow> out;
  out.rows.push_back(
      {point.id, in.walk.law, in.angle_deg, p.progress, p.sliding, p.not_converged, p.unsupported});
  return out;
}

// --- stall_slope --------------------------------------------------------------------------------

const std::vector<std::string_view> kStallKeys = {
    "law", "lo_deg", "hi_deg", "tol_deg", "frequency", "cycles", "steps_per_cycle", "com_height"};

struct StallInputs {
  Walk walk;
  double lo_deg = 0.0;   ///< the bracket's bottom: progress expected
  double hi_deg = 60.0;  ///< the bracket's top: no progress expected
  double tol_deg = 0.05;
};

StallInputs read_stall(const Point& point) {
  const Reader r(point, "stall_slope", kStallKeys);
  StallInputs in;
  in.walk = read_walk(r);
  in.lo_deg = r.number("lo_deg", in.lo_deg, 0.0, 89.0, true);
  in.hi_deg = r.number("hi_deg", in.hi_deg, 0.0, 89.0, true);
  // The bisection halves hi - lo until it is below tol_deg: at most log2(89 / 1e-6) ≈ 27 probes.
  in.tol_deg = r.number("tol_deg", in.tol_deg, core::closed(1e-6, 45.0, "deg"));
  if (!(in.lo_deg < in.hi_deg)) {
    r.fail("hi_deg", "must be above lo_deg");
  }
  return in;
}

/// One row per probe of the bisection, each with the final bracket and its midpoint.
struct StallRow {
  long long id = 0;
  std::string law;
  long long step = 0;
  double angle_deg = 0.0;
  double progress_per_cycle = 0.0;
  long long sliding_frames = 0;
  long long not_converged_frames = 0;
  long long unsupported_frames = 0;
  double bracket_lo_deg = 0.0;
  double bracket_hi_deg = 0.0;
  double stall_deg = 0.0;

  static std::vector<Column<StallRow>> columns() {
    using R = StallRow;
    return {value("id", &R::id),
            value("law", &R::law),
            value("step", &R::step),
            value("angle_deg", &R::angle_deg, "deg"),
            value("progress_per_cycle", &R::progress_per_cycle, "m"),
            value("sliding_frames", &R::sliding_frames),
            value("not_converged_frames", &R::not_converged_frames),
            value("unsupported_frames", &R::unsupported_frames),
            value("bracket_lo_deg", &R::bracket_lo_deg, "deg"),
            value("bracket_hi_deg", &R::bracket_hi_deg, "deg"),
            value("stall_deg", &R::stall_deg, "deg")};
  }
};

Rows<StallRow> run_stall(const Point& point) {
  const StallInputs in = read_stall(point);
  const Walk& w = in.walk;
  double lo = in.lo_deg;
  double hi = in.hi_deg;
  Rows<StallRow> out;
  struct Done {
    double angle;
    Probe p;
  };
  std::vector<Done> probes;
  const Probe plo = walk_up(w, lo);
  const Probe phi = walk_up(w, hi);
  probes.push_back({lo, plo});
  probes.push_back({hi, phi});
  if (!(signed_progress(plo) > 0.0) || signed_progress(phi) > 0.0) {
    out.failed = true;
    out.message = "the bracket [lo_deg, hi_deg] does not change the sign of the progress";
  } else {
    while (hi - lo > in.tol_deg) {
      const double mid = 0.5 * (lo + hi);
      const Probe pm = walk_up(w, mid);
      probes.push_back({mid, pm});
      (signed_progress(pm) > 0.0 ? lo : hi) = mid;
    }
  }
  const double stall = 0.5 * (lo + hi);
  long long step = 0;
  for (const Done& d : probes) {
    out.rows.push_back({point.id, w.law, step++, d.angle, d.p.progress, d.p.sliding,
                        d.p.not_converged, d.p.unsupported, lo, hi, stall});
  }
  return out;
}

}  // namespace

std::vector<PointKind> slope_kinds() {
  return {make_point_kind<ProgressRow>(
              "slope_progress",
              "§5.2.1: BigANT's tripod straight up a slope, uphill progress per gait cycle (one "
              "row)",
              Timed::kNo, [](const Point& p) { (void)read_progress(p); }, run_progress),
          make_point_kind<StallRow>(
              "stall_slope",
              "§5.2.1: the slope at which BigANT's tripod stops making uphill progress, by "
              "bisection (one row per probe)",
              Timed::kNo, [](const Point& p) { (void)read_stall(p); }, run_stall)};
}

}  // namespace slipwalk::sweeps::points
