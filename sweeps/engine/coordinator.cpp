#include "sweeps/engine/coordinator.hpp"

#include <algorithm>
#include <ostream>
#include <thread>

#include "core/error.hpp"
#include "sweeps/engine/timing.hpp"

namespace slipwalk::sweeps {

namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

Coordinator::Coordinator(const PreparedSweep& sweep, const RunOptions& options)
    : sweep_(sweep),
      options_(options),
      label_("[" + sweep.spec.study + "/" + sweep.spec.name +
             (options.shard.whole() ? std::string() : " shard " + options.shard.text()) + "] "),
      header_(header_line(sweep)),
      files_(sweep_files(sweep.spec, options.data_dir, options.shard)),
      checkpoint_(files_.partial, header_, fingerprint(sweep), options.timing,
                  static_cast<long long>(sweep.points.size()), options.resume),
      cap_(sweep.kind->timed == Timed::kYes ? 1 : sweep.points.size() + 1),
      start_(Clock::now()),
      last_progress_(start_) {
  const std::vector<char> member = shard_members(sweep.points.size(), options.shard);
  for (std::size_t i = 0; i < sweep.points.size(); ++i) {
    const long long id = sweep.points[i].id;
    const bool mine = member[static_cast<std::size_t>(id)] != 0;
    total_ += mine ? 1 : 0;
    if (mine && checkpoint_.done().find(id) == checkpoint_.done().end()) {
      pending_.push_back(i);
    }
  }
  if (options.max_points >= 0 && static_cast<long long>(pending_.size()) > options.max_points) {
    pending_.resize(static_cast<std::size_t>(options.max_points));
  }
}

void Coordinator::describe_workers(std::string workers) {
  const std::lock_guard lock(mutex_);
  workers_ = std::move(workers);
}

bool Coordinator::can_take() const {
  return !stopping_ && next_ < pending_.size() && in_flight_ < cap_;
}

std::optional<std::size_t> Coordinator::take_locked() {
  if (!can_take()) {
    return std::nullopt;
  }
  ++in_flight_;
  return pending_[next_++];
}

std::optional<std::size_t> Coordinator::take() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return can_take() || stopping_ || next_ >= pending_.size(); });
  return take_locked();
}

std::vector<std::size_t> Coordinator::take_now(std::size_t most) {
  const std::lock_guard lock(mutex_);
  std::vector<std::size_t> out;
  while (out.size() < most) {
    const auto i = take_locked();
    if (!i) {
      break;
    }
    out.push_back(*i);
  }
  return out;
}

void Coordinator::give(std::vector<std::pair<std::size_t, Finished>>& finished) {
  if (finished.empty()) {
    return;
  }
  std::vector<std::pair<long long, Finished>> by_id;
  by_id.reserve(finished.size());
  for (auto& [index, f] : finished) {
    by_id.emplace_back(sweep_.points[index].id, std::move(f));
  }
  {
    const std::lock_guard lock(mutex_);
    for (const auto& [id, f] : by_id) {
      seconds_.push_back(f.seconds);
    }
    in_flight_ -= std::min(in_flight_, by_id.size());
    computed_ += static_cast<long long>(by_id.size());
    try {
      checkpoint_.append(by_id);
    } catch (const core::ComputationError& e) {  // a full disk: stop, keep what was written
      error_ = error_.empty() ? std::string(e.what()) : error_;
      stopping_ = true;
    }
    progress_locked();
  }
  changed_.notify_all();
}

void Coordinator::fail(std::size_t index, const std::string& error) {
  {
    const std::lock_guard lock(mutex_);
    if (error_.empty()) {
      error_ = "point " + std::to_string(sweep_.points[index].id) + ": " + error;
    }
    in_flight_ -= std::min<std::size_t>(in_flight_, 1);
    stopping_ = true;
  }
  changed_.notify_all();
}

bool Coordinator::exhausted() const {
  const std::lock_guard lock(mutex_);
  return stopping_ || next_ >= pending_.size();
}

bool Coordinator::stopping() const {
  const std::lock_guard lock(mutex_);
  return stopping_;
}

std::size_t Coordinator::in_flight() const {
  const std::lock_guard lock(mutex_);
  return in_flight_;
}

std::size_t Coordinator::pending() const {
  const std::lock_guard lock(mutex_);
  return pending_.size() - next_;
}

void Coordinator::progress_locked() {
  if (options_.progress == nullptr) {
    return;
  }
  const auto now = Clock::now();
  if (std::chrono::duration<double>(now - last_progress_).count() < options_.progress_interval_s) {
    return;
  }
  last_progress_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const auto remaining = static_cast<double>(pending_.size()) - static_cast<double>(computed_);
  *options_.progress << label_ << checkpoint_.done().size() << "/" << total_ << " points, "
                     << seconds_text(elapsed) << ", ETA "
                     << seconds_text(elapsed / static_cast<double>(computed_) * remaining) << " on "
                     << workers_ << std::endl;
}

RunSummary Coordinator::finish(const nlohmann::json& extra) {
  const std::lock_guard lock(mutex_);
  RunSummary summary;
  summary.csv = files_.csv;
  summary.sidecar = files_.sidecar;
  summary.partial = files_.partial;
  const long long shard_points = total_;
  summary.points = shard_points;
  summary.resumed = checkpoint_.resumed();
  summary.computed = computed_;
  summary.wall_s = seconds_since(start_);
  const FinishedPoints& done = checkpoint_.done();
  for (const auto& [id, f] : done) {
    summary.failed += f.failed ? 1 : 0;
    summary.at_budget += f.at_budget ? 1 : 0;
  }
  if (!error_.empty()) {
    checkpoint_.discard_if_empty();
    throw core::ComputationError(
        label_ + error_ +
        (done.empty() ? std::string()
                      : " (finished points are kept in " + files_.partial.string() + ")"));
  }
  if (static_cast<long long>(done.size()) < shard_points) {
    if (options_.progress != nullptr) {
      *options_.progress << label_ << "stopped after " << done.size() << "/" << shard_points
                         << " points; the rest follow with --resume" << std::endl;
    }
    return summary;
  }
  nlohmann::json sidecar = result_sidecar(sweep_, options_.shard, done, options_.timing);
  sidecar["resumed_point_count"] = summary.resumed;
  sidecar["wall_s"] = summary.wall_s;
  sidecar["point_seconds"] = point_seconds_json(seconds_);
  sidecar.update(extra);
  write_result(files_, header_, done, sidecar);
  checkpoint_.remove();
  summary.complete = true;
  return summary;
}

void compute_on_threads(Coordinator& coordinator, const PreparedSweep& sweep, unsigned threads,
                        bool timing) {
  const auto worker = [&] {
    while (const auto index = coordinator.take()) {
      std::vector<std::pair<std::size_t, Finished>> finished(1);
      try {
        finished[0] = {*index, compute_point(sweep, sweep.points[*index], timing)};
      } catch (const std::exception& e) {
        coordinator.fail(*index, e.what());
        return;
      }
      coordinator.give(finished);
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) {
    pool.emplace_back(worker);
  }
  if (threads > 0) {
    worker();
  }
  for (auto& t : pool) {
    t.join();
  }
}

}  // namespace slipwalk::sweeps
