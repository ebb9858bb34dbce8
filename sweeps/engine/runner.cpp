#include "sweeps/engine/runner.hpp"

#include <gsl/gsl_errno.h>

#include <algorithm>
#include <ctime>
#include <thread>

#include "core/error.hpp"
#include "sweeps/engine/coordinator.hpp"

namespace slipwalk::sweeps {

std::filesystem::path csv_path(const Spec& spec, const std::filesystem::path& data) {
  return sweep_files(spec, data).csv;
}

std::filesystem::path partial_path(const Spec& spec, const std::filesystem::path& data) {
  return sweep_files(spec, data).partial;
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buffer;
}

PreparedSweep prepare(Spec spec, std::span<const PointKind> kinds) {
  PreparedSweep s;
  s.kind = find_point_kind(kinds, spec.kind);
  if (s.kind == nullptr) {
    throw core::InputError(spec.kind_origin,
                           "unknown kind '" + spec.kind + "'; expected " + point_kind_names(kinds));
  }
  s.points = expand(spec);
  for (const Point& p : s.points) {
    s.kind->check(p);
  }
  // The sizes not run are checked as well: a bad value is bad input whether or not --quick or
  // --full overrides it, and a bad [quick] or [full] value is found by every run.
  for (const OtherVariant& other : spec.others) {
    for (const Point& p : expand_other(spec, other)) {
      try {
        s.kind->check(p);
      } catch (const core::InputError& e) {
        std::string what = e.what();
        what.erase(0, std::min(what.size(), e.where().size() + 2));
        what.append(other.variant == Variant::kDefault
                        ? " (in the spec without --" + std::string(variant_name(spec.variant)) + ")"
                        : " (in the spec under --" + std::string(variant_name(other.variant)) +
                              ")");
        throw core::InputError(e.where(), what);
      }
    }
  }
  s.spec = std::move(spec);
  return s;
}

RunSummary run(const PreparedSweep& sweep, const RunOptions& options) {
  gsl_set_error_handler_off();  // a GSL failure is a failed point, never an abort()
  Coordinator coordinator(sweep, options);
  unsigned jobs = options.jobs != 0 ? options.jobs : std::thread::hardware_concurrency();
  jobs = std::clamp<unsigned>(
      jobs, 1U, static_cast<unsigned>(std::max<std::size_t>(1, coordinator.pending())));
  coordinator.describe_workers(std::to_string(jobs) + (jobs == 1 ? " thread" : " threads"));
  compute_on_threads(coordinator, sweep, jobs, options.timing);
  RunSummary summary = coordinator.finish({{"threads", jobs}, {"ranks", 1}});
  summary.jobs = jobs;
  return summary;
}

}  // namespace slipwalk::sweeps
