#include "sweeps/engine/mpi/mpi_run.hpp"

#include <gsl/gsl_errno.h>
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <list>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "sweeps/engine/coordinator.hpp"
#include "sweeps/engine/timing.hpp"

namespace slipwalk::sweeps::mpi {

namespace {

constexpr int kResults = 1;  // rank r -> 0
constexpr int kWork = 2;     // rank 0 -> r
/// A worker sends its outbox in messages of at most this many bytes (a message's size is an int).
constexpr std::size_t kMaxMessageBytes = std::size_t{16} << 20;
/// How long a rank sleeps when nothing happened, at most: the added latency of an idle poll.
constexpr auto kMaxPause = std::chrono::microseconds(1000);
constexpr auto kMinPause = std::chrono::microseconds(20);
/// A worker keeps enough points queued for this long per thread (at least one each), so that
/// its threads do not wait for a round trip to rank 0 between fast points.
constexpr double kQueueSeconds = 0.02;
constexpr std::size_t kMaxAhead = 4096;

enum class Status : std::uint8_t { kOk = 0, kFailed = 1, kThrew = 2 };

// ---- byte buffers ----------------------------------------------------------------------------

template <class T>
void put(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}
void put_text(std::string& out, const std::string& text) {
  put<std::uint64_t>(out, text.size());
  out += text;
}

class Reader {
 public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  template <class T>
  T get() {
    need(sizeof(T));
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof value);
    at_ += sizeof value;
    return value;
  }
  std::string text() {
    const auto n = static_cast<std::size_t>(get<std::uint64_t>());
    need(n);
    std::string out = bytes_.substr(at_, n);
    at_ += n;
    return out;
  }
  [[nodiscard]] bool done() const { return at_ == bytes_.size(); }

 private:
  void need(std::size_t n) const {
    if (bytes_.size() - at_ < n) {
      throw std::logic_error("mpi sweep: a truncated message");
    }
  }
  const std::string& bytes_;
  std::size_t at_ = 0;
};

/// One finished point as a worker sends it.
struct Entry {
  std::uint64_t index = 0;
  Status status = Status::kOk;
  Finished finished;  // rows, message (the error for kThrew), seconds
};

void put_entry(std::string& out, const Entry& e) {
  put<std::uint64_t>(out, e.index);
  put<std::uint8_t>(out, static_cast<std::uint8_t>(e.status));
  put<double>(out, e.finished.seconds);
  put_text(out, e.finished.rows);
  put_text(out, e.finished.message);
}

Entry get_entry(Reader& in) {
  Entry e;
  e.index = in.get<std::uint64_t>();
  e.status = static_cast<Status>(in.get<std::uint8_t>());
  e.finished.seconds = in.get<double>();
  e.finished.rows = in.text();
  e.finished.message = in.text();
  e.finished.failed = e.status == Status::kFailed;
  return e;
}

// ---- sends that never block ------------------------------------------------------------------

/// Non-blocking sends whose buffers live until MPI is done with them.
class Outgoing {
 public:
  void send(std::string bytes, int to, int tag) {
    sends_.emplace_back();
    Pending& p = sends_.back();
    p.bytes = std::move(bytes);
    MPI_Isend(p.bytes.data(), static_cast<int>(p.bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD,
              &p.request);
    // The analyzer's MPI checker follows requests in locals only; these live in sends_ and are
    // tested in reap() and waited for in wait_all().
  }  // NOLINT(clang-analyzer-optin.mpi.MPI-Checker)
  /// Frees the buffers of completed sends.
  void reap() {
    for (auto it = sends_.begin(); it != sends_.end();) {
      int done = 0;
      MPI_Test(&it->request, &done, MPI_STATUS_IGNORE);  // NOLINT(clang-analyzer-optin.mpi.*)
      it = done != 0 ? sends_.erase(it) : std::next(it);
    }
  }
  void wait_all() {
    for (Pending& p : sends_) {
      MPI_Wait(&p.request, MPI_STATUS_IGNORE);  // NOLINT(clang-analyzer-optin.mpi.*)
    }
    sends_.clear();
  }

 private:
  struct Pending {
    std::string bytes;
    MPI_Request request = MPI_REQUEST_NULL;
  };
  std::list<Pending> sends_;  // a list: a buffer's address must not move while MPI reads it
};

/// Receives a waiting message of `tag` from `from` (MPI_ANY_SOURCE: anyone), if there is one.
std::optional<std::pair<int, std::string>> receive(int from, int tag) {
  int flag = 0;
  MPI_Status status;
  MPI_Iprobe(from, tag, MPI_COMM_WORLD, &flag, &status);
  if (flag == 0) {
    return std::nullopt;
  }
  int count = 0;
  MPI_Get_count(&status, MPI_BYTE, &count);
  std::string bytes(static_cast<std::size_t>(count), '\0');
  MPI_Recv(bytes.data(), count, MPI_BYTE, status.MPI_SOURCE, tag, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  return std::pair{status.MPI_SOURCE, std::move(bytes)};
}

/// Sleeps a little longer each time nothing happened, and not at all after something did.
class Pause {
 public:
  void reset() { pause_ = kMinPause; }
  std::chrono::microseconds next() {
    const auto p = pause_;
    pause_ = std::min(pause_ * 2, kMaxPause);
    return p;
  }

 private:
  std::chrono::microseconds pause_ = kMinPause;
};

unsigned threads_of(unsigned jobs) {
  return jobs != 0 ? jobs : std::max(1U, std::thread::hardware_concurrency());
}

// ---- setup: every rank agrees, one reports ----------------------------------------------------

/// Collective: when any rank has an error, rank 0 throws the first failing rank's and the others
/// QuietExit with its exit code.
void agree(const Session& session, const std::exception_ptr& error) {
  int code = 0;
  std::string message;
  if (error) {
    try {
      std::rethrow_exception(error);
    } catch (const core::InputError& e) {
      code = 2;
      message = e.what();
    } catch (const std::exception& e) {
      code = 1;
      message = e.what();
    }
  }
  int first = code != 0 ? session.rank() : session.size();
  int lowest = session.size();
  MPI_Allreduce(&first, &lowest, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (lowest == session.size()) {
    return;
  }
  MPI_Bcast(&code, 1, MPI_INT, lowest, MPI_COMM_WORLD);
  if (lowest != 0 && session.rank() == lowest) {
    MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, kResults,
             MPI_COMM_WORLD);
  }
  if (session.rank() != 0) {
    throw QuietExit{code};
  }
  if (lowest == 0) {
    std::rethrow_exception(error);
  }
  MPI_Status status;
  MPI_Probe(lowest, kResults, MPI_COMM_WORLD, &status);
  int count = 0;
  MPI_Get_count(&status, MPI_CHAR, &count);
  std::string theirs(static_cast<std::size_t>(count), '\0');
  MPI_Recv(theirs.data(), count, MPI_CHAR, lowest, kResults, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  const std::string where = "rank " + std::to_string(lowest);
  if (code == 2) {
    throw core::InputError(where, theirs);
  }
  throw core::ComputationError(where + ": " + theirs);
}

template <class F>
std::exception_ptr attempt(F&& f) {
  try {
    f();
  } catch (...) {
    return std::current_exception();
  }
  return nullptr;
}

// ---- rank 0 ----------------------------------------------------------------------------------

struct RemoteRank {
  std::size_t owed = 0;         // points it asked for and has not been sent
  std::size_t outstanding = 0;  // points it was sent and has not returned
  unsigned threads = 0;
  bool stop_sent = false;
  bool finished = false;
};

RunSummary coordinate(const Session& session, const PreparedSweep& sweep, Coordinator& coordinator,
                      const Options& options) {
  const unsigned own = options.coordinator_jobs >= 0
                           ? static_cast<unsigned>(options.coordinator_jobs)
                           : threads_of(options.run.jobs);
  coordinator.describe_workers(std::to_string(session.size()) + " ranks");
  std::thread local([&] { compute_on_threads(coordinator, sweep, own, options.run.timing); });

  std::vector<RemoteRank> ranks(static_cast<std::size_t>(session.size()));
  ranks[0].finished = true;
  ranks[0].threads = own;
  Outgoing outgoing;
  Pause pause;
  long long messages = 0;
  long long remote_points = 0;
  const double cpu0 = thread_cpu_seconds();
  const auto all_finished = [&] {
    return std::all_of(ranks.begin(), ranks.end(), [](const RemoteRank& r) { return r.finished; });
  };
  // The most points a rank may hold (queued or running): its threads, and its threads' part of
  // half of what is left to hand out (guided self-scheduling). A rank that asks for many cheap
  // points cannot take the costly ones the others would have shared, and at the end every rank
  // holds no more than it is computing.
  const auto share = [&](const RemoteRank& r) {
    std::size_t threads = own;
    for (std::size_t k = 1; k < ranks.size(); ++k) {
      threads += std::max(1U, ranks[k].threads);
    }
    const std::size_t mine = std::max(1U, r.threads);
    return mine + mine * coordinator.pending() / (2 * std::max<std::size_t>(1, threads));
  };
  while (!all_finished()) {
    bool busy = false;
    while (auto message = receive(MPI_ANY_SOURCE, kResults)) {
      busy = true;
      ++messages;
      RemoteRank& r = ranks[static_cast<std::size_t>(message->first)];
      Reader in(message->second);
      r.owed += in.get<std::uint32_t>();
      r.threads = in.get<std::uint32_t>();
      r.finished = in.get<std::uint8_t>() != 0;
      const auto count = in.get<std::uint32_t>();
      std::vector<std::pair<std::size_t, Finished>> finished;
      finished.reserve(count);
      for (std::uint32_t i = 0; i < count; ++i) {
        Entry e = get_entry(in);
        if (e.status == Status::kThrew) {
          coordinator.fail(e.index, e.finished.message);
        } else {
          finished.emplace_back(e.index, std::move(e.finished));
        }
      }
      r.outstanding -= std::min<std::size_t>(r.outstanding, count);
      remote_points += count;
      coordinator.give(finished);
    }
    for (std::size_t k = 1; k < ranks.size(); ++k) {
      RemoteRank& r = ranks[k];
      if (r.finished || r.stop_sent) {
        continue;
      }
      if (coordinator.stopping() || (coordinator.exhausted() && r.outstanding == 0)) {
        outgoing.send(std::string(), static_cast<int>(k), kWork);  // empty: stop
        r.stop_sent = true;
        busy = true;
      } else if (r.owed > 0 && r.outstanding < share(r)) {
        const std::vector<std::size_t> work =
            coordinator.take_now(std::min(r.owed, share(r) - r.outstanding));
        if (!work.empty()) {
          std::string bytes;
          for (const std::size_t i : work) {
            put<std::uint64_t>(bytes, i);
          }
          outgoing.send(std::move(bytes), static_cast<int>(k), kWork);
          r.owed -= work.size();
          r.outstanding += work.size();
          busy = true;
        }
      }
    }
    outgoing.reap();
    if (busy) {
      pause.reset();
    } else {
      std::this_thread::sleep_for(pause.next());
    }
  }
  const double cpu_s = thread_cpu_seconds() - cpu0;
  outgoing.wait_all();
  local.join();
  nlohmann::json threads = nlohmann::json::array();
  for (const RemoteRank& r : ranks) {
    threads.push_back(r.threads);
  }
  RunSummary summary = coordinator.finish(
      {{"threads", own},
       {"ranks", session.size()},
       {"threads_per_rank", threads},
       {"coordinator",
        {{"messages", messages}, {"remote_points", remote_points}, {"cpu_s", cpu_s}}}});
  summary.ranks = static_cast<unsigned>(session.size());
  summary.jobs = own;
  return summary;
}

// ---- ranks 1 ... R-1 ---------------------------------------------------------------------------

/// A worker rank's threads and the main thread that talks to rank 0 for them.
class Worker {
 public:
  Worker(const PreparedSweep& sweep, unsigned threads, bool timing)
      : sweep_(sweep), threads_(threads), timing_(timing) {}

  void run() {
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads_; ++t) {
      pool.emplace_back([this] { compute(); });
    }
    talk();
    {
      const std::lock_guard lock(mutex_);
      stop_ = true;
      queue_.clear();
    }
    work_ready_.notify_all();
    for (auto& t : pool) {
      t.join();
    }
  }

 private:
  void compute() {
    for (;;) {
      std::size_t index = 0;
      {
        std::unique_lock lock(mutex_);
        work_ready_.wait(lock, [&] { return stop_ || !queue_.empty(); });
        if (queue_.empty()) {
          return;
        }
        index = queue_.front();
        queue_.pop_front();
        ++running_;
      }
      Entry e;
      e.index = index;
      try {
        e.finished = compute_point(sweep_, sweep_.points[index], timing_);
        e.status = e.finished.failed ? Status::kFailed : Status::kOk;
      } catch (const std::exception& error) {
        e.status = Status::kThrew;
        e.finished.message = error.what();
      }
      {
        const std::lock_guard lock(mutex_);
        seconds_sum_ += e.finished.seconds;
        ++seconds_count_;
        outbox_.push_back(std::move(e));
        --running_;
      }
      results_ready_.notify_one();
    }
  }

  /// Points this rank wants queued or running: one per thread, and enough more to last
  /// kQueueSeconds at the mean point time seen so far.
  [[nodiscard]] std::size_t target() const {  // under mutex_
    const double mean =
        seconds_count_ > 0 ? seconds_sum_ / static_cast<double>(seconds_count_) : kQueueSeconds;
    const double ahead =
        std::clamp(kQueueSeconds / std::max(mean, 1e-9), 1.0, static_cast<double>(kMaxAhead));
    return static_cast<std::size_t>(threads_) * (1 + static_cast<std::size_t>(ahead));
  }

  void talk() {
    Outgoing outgoing;
    Pause pause;
    std::size_t requested = 0;  // asked for, not yet received
    bool stop_received = false;
    for (;;) {
      bool busy = false;
      while (auto message = receive(0, kWork)) {
        busy = true;
        if (message->second.empty()) {
          stop_received = true;
          const std::lock_guard lock(mutex_);
          queue_.clear();
          continue;
        }
        Reader in(message->second);
        std::size_t count = 0;
        {
          const std::lock_guard lock(mutex_);
          while (!in.done()) {
            queue_.push_back(static_cast<std::size_t>(in.get<std::uint64_t>()));
            ++count;
          }
        }
        requested -= std::min(requested, count);
        work_ready_.notify_all();
      }
      std::vector<Entry> finished;
      std::size_t want = 0;
      bool last = false;
      {
        std::unique_lock lock(mutex_);
        if (!busy && outbox_.empty()) {
          results_ready_.wait_for(lock, pause.next(), [&] { return !outbox_.empty(); });
        }
        finished.swap(outbox_);
        const std::size_t have = queue_.size() + running_ + requested;
        want = stop_received ? 0 : target() - std::min(target(), have);
        last = stop_received && running_ == 0;
      }
      if (!finished.empty() || want > 0 || last) {
        send_results(outgoing, finished, want, last);
        requested += want;
        busy = true;
      }
      outgoing.reap();
      if (last) {
        outgoing.wait_all();
        return;
      }
      if (busy) {
        pause.reset();
      }
    }
  }

  void send_results(Outgoing& outgoing, const std::vector<Entry>& finished, std::size_t want,
                    bool last) const {
    std::size_t from = 0;
    do {
      std::string body;
      std::uint32_t count = 0;
      for (; from < finished.size() && (count == 0 || body.size() < kMaxMessageBytes); ++from) {
        put_entry(body, finished[from]);
        ++count;
      }
      const bool final_part = from == finished.size();
      std::string bytes;
      put<std::uint32_t>(bytes, final_part ? static_cast<std::uint32_t>(want) : 0U);
      put<std::uint32_t>(bytes, threads_);
      put<std::uint8_t>(bytes, final_part && last ? 1 : 0);
      put<std::uint32_t>(bytes, count);
      bytes += body;
      outgoing.send(std::move(bytes), 0, kResults);
    } while (from < finished.size());
  }

  const PreparedSweep& sweep_;
  unsigned threads_;
  bool timing_;
  std::mutex mutex_;
  std::condition_variable work_ready_;
  std::condition_variable results_ready_;
  std::deque<std::size_t> queue_;
  std::vector<Entry> outbox_;
  std::size_t running_ = 0;
  bool stop_ = false;
  double seconds_sum_ = 0.0;
  long long seconds_count_ = 0;
};

}  // namespace

bool available() { return true; }

Session::Session() {
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  // The launcher's marks are read at MPI_Init and no later; gone, a `slipwalk` that a point kind
  // starts as a child (the hostile-input campaign, the scaling benchmark) runs on its own
  // instead of taking itself for a rank.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
    ::unsetenv(name);  // NOLINT(concurrency-mt-unsafe): before any thread of ours
  }
  if (provided < MPI_THREAD_FUNNELED) {
    MPI_Finalize();
    throw core::InputError("MPI",
                           "the MPI library gives no MPI_THREAD_FUNNELED threading, which "
                           "a sweep's threads inside a rank need");
  }
}

Session::~Session() { MPI_Finalize(); }

void Session::barrier() const { MPI_Barrier(MPI_COMM_WORLD); }

RunSummary run_sweep(const Session& session, const Setup& setup, const Options& options) {
  gsl_set_error_handler_off();  // a GSL failure is a failed point, never an abort()
  std::optional<PreparedSweep> sweep;
  agree(session, attempt([&] {
          sweep.emplace(setup.prepare());
          if (session.rank() == 0) {
            setup.check_outputs(*sweep);
          }
        }));
  // Every rank must hand the same index the same point.
  std::string print = fingerprint(*sweep);
  std::string root = print;
  root.resize(16);
  MPI_Bcast(root.data(), 16, MPI_CHAR, 0, MPI_COMM_WORLD);
  agree(session, attempt([&] {
          if (root != print) {
            throw core::InputError(sweep->spec.path,
                                   "rank " + std::to_string(session.rank()) +
                                       " read other points from this spec than rank 0; are the "
                                       "spec and the files it names the same on every node?");
          }
        }));
  std::unique_ptr<Coordinator> coordinator;
  agree(session, attempt([&] {
          if (session.rank() == 0) {
            coordinator = std::make_unique<Coordinator>(*sweep, options.run);
          }
        }));
  if (session.rank() != 0) {
    Worker(*sweep, threads_of(options.run.jobs), options.run.timing).run();
    // Rank 0 says whether the run failed; a worker mirrors its exit code.
    int code = 0;
    MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (code != 0) {
      throw QuietExit{code};
    }
    return {};
  }
  core::set_signal_farewell(
      "slipwalk: error: [" + sweep->spec.study + "/" + sweep->spec.name +
          "] stopped by a signal (a rank died, or the job was cancelled); the points finished "
          "so far are kept in " +
          coordinator->checkpoint_path().string() +
          "; run the same command again with --resume (on any number of ranks or threads)",
      1);
  int code = 0;
  std::exception_ptr error;
  RunSummary summary;
  try {
    summary = coordinate(session, *sweep, *coordinator, options);
  } catch (const core::InputError&) {
    code = 2;
    error = std::current_exception();
  } catch (...) {
    code = 1;
    error = std::current_exception();
  }
  core::set_signal_farewell("", 1);
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (error) {
    std::rethrow_exception(error);
  }
  return summary;
}

}  // namespace slipwalk::sweeps::mpi
