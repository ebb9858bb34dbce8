// Running one hostile case: a fresh folder, the binary as a subprocess (fork + exec, its own
// process group so a kill reaches anything it starts), a wall-time limit and a bound on what it
// may write, then the judges of hostile_inputs.hpp.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "sweeps/points/hostile_inputs.hpp"

namespace slipwalk::sweeps::hostile {

namespace fs = std::filesystem;

namespace {

/// A run writing more than this (stdout and its folder together) is stopped as a runaway: no
/// case of the campaign asks for an output near this size, so one that grows past it would fill
/// the disk (the tool must estimate an output's size before writing it).
constexpr std::uintmax_t kMaxBytes = 256ULL << 20;
/// An error message longer than this re-serialises its input instead of naming a place.
constexpr std::size_t kMaxMessage = 4096;

struct Outcome {
  int exit_code = -1;   ///< when it exited
  int term_signal = 0;  ///< when a signal ended it
  bool timed_out = false;
  bool runaway = false;
  bool sent = false;  ///< our signal was delivered while it ran
  double wall_s = 0.0;
  std::string out;
  std::string err;
};

/// The file's first `limit` bytes (a runaway output is judged by its size, never read whole).
std::string read_text(const fs::path& path, std::uintmax_t limit = 64ULL << 20) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  std::string text(static_cast<std::size_t>(ec ? 0 : std::min(size, limit)), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return text;
}

std::uintmax_t bytes_under(const fs::path& dir) {
  std::uintmax_t total = 0;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    if (it->is_regular_file(ec)) {
      total += it->file_size(ec);
    }
  }
  return total;
}

/// Everything under `dir` (folders included, links not followed), relative, sorted.
std::vector<std::string> entries_under(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    out.push_back(fs::relative(it->path(), dir, ec).string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

Outcome invoke(const fs::path& binary, const Invocation& inv, const fs::path& dir,
               const fs::path& capture, double limit_s) {
  // Everything the child needs is built before fork: after it, only async-signal-safe calls.
  std::vector<std::string> argv_text = {"slipwalk"};
  argv_text.insert(argv_text.end(), inv.args.begin(), inv.args.end());
  std::vector<char*> argv;
  argv.reserve(argv_text.size() + 1);
  for (std::string& a : argv_text) {
    argv.push_back(a.data());
  }
  argv.push_back(nullptr);
  const std::string exe = binary.string();
  const std::string cwd = dir.string();
  const std::string in_path =
      inv.stdin_file.empty() ? "/dev/null" : (dir / inv.stdin_file).string();
  const fs::path out_file = capture / "out";
  const fs::path err_file = capture / "err";
  const std::string out_path = inv.stdout_to.empty() ? out_file.string() : inv.stdout_to;
  const std::string err_path = err_file.string();

  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) {
    throw std::runtime_error("hostile inputs: fork failed");
  }
  if (pid == 0) {
    ::setpgid(0, 0);
    const int in = ::open(in_path.c_str(), O_RDONLY);
    const int out = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in < 0 || out < 0 || err < 0 || ::dup2(in, 0) < 0 || ::dup2(out, 1) < 0 ||
        ::dup2(err, 2) < 0 || ::chdir(cwd.c_str()) != 0) {
      ::_exit(126);
    }
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  ::setpgid(pid, pid);  // also here: whichever of the two runs first, the group exists

  Outcome o;
  int status = 0;
  auto pause = std::chrono::microseconds(200);
  auto last_size_check = t0;
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    const auto now = std::chrono::steady_clock::now();
    const double t = std::chrono::duration<double>(now - t0).count();
    if (done == pid) {
      o.wall_s = t;
      break;
    }
    if (inv.signal != 0 && !o.sent && t >= inv.signal_after_s) {
      ::kill(-pid, inv.signal);
      o.sent = true;
    }
    if (t > limit_s) {
      o.timed_out = true;
    } else if (now - last_size_check > std::chrono::milliseconds(100)) {
      last_size_check = now;
      std::error_code ec;
      const std::uintmax_t out_size =
          inv.stdout_to.empty() ? fs::file_size(out_file, ec) : std::uintmax_t{0};
      o.runaway = (ec ? 0 : out_size) + bytes_under(dir) > kMaxBytes;
    }
    if (o.timed_out || o.runaway) {
      ::kill(-pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      o.wall_s = t;
      break;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(5000));
  }
  if (WIFEXITED(status)) {
    o.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    o.term_signal = WTERMSIG(status);
  }
  o.err = read_text(err_file);
  if (inv.stdout_to.empty()) {
    o.out = read_text(out_file);
  }
  return o;
}

// ---- judges of an output ------------------------------------------------------------------

bool is_nonfinite_token(std::string t) {
  std::transform(t.begin(), t.end(), t.begin(), [](unsigned char c) { return std::tolower(c); });
  while (!t.empty() && (t.front() == '-' || t.front() == '+')) {
    t.erase(t.begin());
  }
  return t == "nan" || t == "inf" || t == "infinity" || t == "null";
}

/// The first non-finite number of a JSON document; null is allowed only at `alpha` of the
/// instant swap model (it has no α) and `A` under Coulomb friction (no local connection).
std::string json_nonfinite(const nlohmann::json& j, const std::string& path,
                           const nlohmann::json& root) {
  if (j.is_null()) {
    const bool alpha = path == "/alpha" && root.value("model", "") == "instant";
    const bool coulomb_a = path == "/A" && root.contains("friction");
    return alpha || coulomb_a ? "" : path + " is null";
  }
  if (j.is_number_float() && !std::isfinite(j.get<double>())) {
    return path + " is not finite";
  }
  if (j.is_object() || j.is_array()) {
    std::size_t i = 0;
    for (auto it = j.begin(); it != j.end(); ++it, ++i) {
      std::string child = path;
      child.append("/").append(j.is_object() ? it.key() : std::to_string(i));
      std::string bad = json_nonfinite(*it, child, root);
      if (!bad.empty()) {
        return bad;
      }
    }
  }
  return "";
}

bool json_says_not_converged(const nlohmann::json& j) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      if (it.key() == "converged" && it->is_boolean() && !it->get<bool>()) {
        return true;
      }
      if (json_says_not_converged(*it)) {
        return true;
      }
    }
  }
  return false;
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, sep)) {
    out.push_back(cell);
  }
  return out;
}

/// The first non-finite cell of a CSV (rows whose `converged` column is 0 are exempt).
std::string csv_nonfinite(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line)) {
    return "no header";
  }
  const std::vector<std::string> header = split(line, ',');
  std::vector<std::size_t> flags;
  for (std::size_t j = 0; j < header.size(); ++j) {
    if (header[j].find("converged") != std::string::npos) {
      flags.push_back(j);
    }
  }
  long long row = 1;
  while (std::getline(in, line)) {
    ++row;
    const std::vector<std::string> cells = split(line, ',');
    const bool exempt = std::any_of(flags.begin(), flags.end(), [&](std::size_t j) {
      return j < cells.size() && cells[j] == "0";
    });
    for (std::size_t j = 0; j < cells.size() && !exempt; ++j) {
      if (is_nonfinite_token(cells[j])) {
        return "row " + std::to_string(row) + " column " +
               (j < header.size() ? header[j] : std::to_string(j)) + " = " + cells[j];
      }
    }
  }
  return row == 1 ? "no rows" : "";
}

std::string text_nonfinite(const std::string& text) {
  std::string token;
  for (const char c : text + " ") {
    if (std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' || c == '+') {
      token.push_back(c);
    } else {
      if (is_nonfinite_token(token)) {
        return "'" + token + "' in the output";
      }
      token.clear();
    }
  }
  return "";
}

/// Why an exit-0 output is not a success ("" when it is one).
std::string output_fault(const Case& c, const fs::path& dir, const Outcome& o) {
  if (c.output_kind == Output::kNone) {
    return "";
  }
  std::string text = o.out;
  if (!c.output.empty()) {
    std::error_code ec;
    if (!fs::is_regular_file(dir / c.output, ec)) {
      return "";  // judged as a missing output
    }
    text = read_text(dir / c.output);
  }
  switch (c.output_kind) {
    case Output::kJson: {
      const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
      if (j.is_discarded()) {
        return "the output is not JSON";
      }
      return json_says_not_converged(j) ? "" : json_nonfinite(j, "", j);
    }
    case Output::kCsv:
      return csv_nonfinite(text);
    case Output::kText:
      return text.find("converged    no") != std::string::npos ? "" : text_nonfinite(text);
    case Output::kNone:
      break;
  }
  return "";
}

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.rfind(prefix, 0) == 0;
}

/// The entries of `now` that are neither in `before` nor allowed (an allowed path brings its
/// parent folders with it).
std::vector<std::string> extra_entries(const std::vector<std::string>& now,
                                       const std::vector<std::string>& before,
                                       const std::vector<std::string>& allowed_files,
                                       const std::vector<std::string>& allowed_prefixes) {
  std::vector<std::string> extra;
  for (const std::string& e : now) {
    if (std::find(before.begin(), before.end(), e) != before.end()) {
      continue;
    }
    bool ok = false;
    for (const std::string& a : allowed_files) {
      ok = ok || e == a || starts_with(a, e + "/");
    }
    for (const std::string& p : allowed_prefixes) {
      ok = ok || starts_with(e, p) || starts_with(p, e + "/");
    }
    if (!ok) {
      extra.push_back(e);
    }
  }
  return extra;
}

std::string describe(const Outcome& o) {
  if (o.timed_out) {
    return "still running after " + std::to_string(o.wall_s) + " s";
  }
  if (o.runaway) {
    return "wrote more than 256 MB";
  }
  if (o.term_signal != 0) {
    return "killed by signal " + std::to_string(o.term_signal);
  }
  return "exit " + std::to_string(o.exit_code);
}

std::string first_line(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  if (line.size() > 200) {
    line = line.substr(0, 200) + "...";
  }
  return line;
}

void fault(Verdict& v, bool& flag, const std::string& what) {
  if (!flag && v.detail.empty()) {
    v.detail = what;
  } else if (!flag) {
    v.detail += "; " + what;
  }
  flag = true;
}

/// Judges one invocation's ending (crash, hang, exit code, message), not its files.
void judge_ending(const Case& c, const Invocation& inv, const Outcome& o, Verdict& v) {
  v.wall_s = std::max(v.wall_s, o.wall_s);
  if (o.timed_out || o.runaway) {
    fault(v, v.hang, describe(o));
    return;
  }
  const bool ours =
      inv.signal != 0 && o.sent && (o.term_signal == inv.signal || o.exit_code == 128 + inv.signal);
  if (ours && inv.signal != SIGKILL) {
    return;  // ended by our signal, as asked: the files say whether it cleaned up
  }
  if (ours) {
    return;
  }
  if (o.term_signal != 0 || o.exit_code >= 128 || o.exit_code < 0) {
    fault(v, v.crash, describe(o) + ": " + first_line(o.err));
    return;
  }
  if (c.exits.count(o.exit_code) == 0) {
    fault(v, v.wrong_exit, describe(o) + ": " + first_line(o.err));
    return;
  }
  if (o.exit_code != 0) {
    const bool message = o.err.find("slipwalk: error: ") != std::string::npos;
    if (!message) {
      fault(v, v.no_place, describe(o) + " without a `slipwalk: error:` message");
    } else if (o.err.size() > kMaxMessage) {
      fault(v, v.no_place,
            describe(o) + " with a message of " + std::to_string(o.err.size()) + " bytes");
    } else if (o.exit_code == 2 && !c.place.empty()) {
      const std::size_t at = o.err.find(c.place);
      const bool line_ok =
          at != std::string::npos &&
          (!c.place_line ||
           (at + c.place.size() + 1 < o.err.size() && o.err[at + c.place.size()] == ':' &&
            std::isdigit(static_cast<unsigned char>(o.err[at + c.place.size() + 1]))));
      const bool also_ok = std::any_of(c.also.begin(), c.also.end(), [&](const std::string& p) {
        return o.err.find(p) != std::string::npos;
      });
      if (!line_ok && !also_ok) {
        fault(v, v.no_place,
              "exit 2 not naming " + c.place + (c.place_line ? ":<line>" : "") + ": " +
                  first_line(o.err));
      }
    }
  }
}

long long csv_rows_with_unique_ids(const std::string& text, bool& unique) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  std::set<std::string> ids;
  long long rows = 0;
  unique = true;
  while (std::getline(in, line)) {
    ++rows;
    unique = ids.insert(line.substr(0, line.find(','))).second && unique;
  }
  return rows;
}

void write_case_files(const Case& c, const fs::path& dir) {
  for (const std::string& f : c.folders) {
    fs::create_directories(dir / f);
  }
  for (const InputFile& f : c.files) {
    fs::create_directories((dir / f.name).parent_path());
    std::ofstream out(dir / f.name, std::ios::binary);
    out << f.text;
  }
  for (const std::string& f : c.fifos) {
    ::mkfifo((dir / f).c_str(), 0644);
  }
  for (const auto& [link, target] : c.symlinks) {
    std::error_code ec;
    fs::create_symlink(target, dir / link, ec);
  }
}

}  // namespace

Verdict run_case(const fs::path& binary, const Case& c, const fs::path& scratch) {
  std::string pattern = (scratch / "hostile_XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    throw std::runtime_error("hostile inputs: cannot make a folder under " + scratch.string());
  }
  const fs::path root = pattern;
  const fs::path dir = root / "case";
  const fs::path capture = root / "capture";
  fs::create_directories(dir);
  fs::create_directories(capture);
  write_case_files(c, dir);
  const std::vector<std::string> before = entries_under(dir);
  std::map<std::string, std::string> inputs;
  for (const InputFile& f : c.files) {
    inputs[f.name] = f.text;
  }

  Verdict v;
  const Outcome o = invoke(binary, c.run, dir, capture, c.limit_s);
  judge_ending(c, c.run, o, v);
  const bool ours = c.run.signal != 0 && o.sent &&
                    (o.term_signal == c.run.signal || o.exit_code == 128 + c.run.signal);
  const bool finished = !o.timed_out && !o.runaway && o.term_signal == 0;

  // Success must be real: the outputs there, finite, and a full stdout is no success.
  if (finished && o.exit_code == 0) {
    if (c.run.stdout_to == "/dev/full") {
      fault(v, v.false_success, "exit 0 although stdout went to /dev/full");
    }
    for (const std::string& out : c.outputs) {
      std::error_code ec;
      if (!fs::is_regular_file(dir / out, ec) || fs::file_size(dir / out, ec) == 0) {
        fault(v, v.false_success, "exit 0 but " + out + " missing or empty");
      }
    }
    const std::string bad = output_fault(c, dir, o);
    if (!bad.empty()) {
      fault(v, v.false_success, "exit 0 with " + bad);
    }
  }
  for (const auto& [name, text] : inputs) {
    if (std::find(c.outputs.begin(), c.outputs.end(), name) != c.outputs.end()) {
      continue;  // an existing file the command was asked to replace
    }
    std::error_code ec;
    if (!fs::is_regular_file(dir / name, ec) || read_text(dir / name) != text) {
      fault(v, v.clobbered, "input " + name + " changed");
    }
  }
  // What may stay: the outputs on success; after our SIGINT/SIGTERM a sweep's checkpoint; after
  // SIGKILL the temporaries (the twin run must then remove them).
  std::vector<std::string> allowed_files;
  std::vector<std::string> allowed_prefixes;
  if (finished && o.exit_code == 0) {
    allowed_files = c.outputs;
  }
  // A signal that lands after the last rename but before the exit finds the work done: the whole
  // set of outputs (a CSV with its sidecar) may stay, never a part of it.
  if (ours && !c.outputs.empty() &&
      std::all_of(c.outputs.begin(), c.outputs.end(), [&](const std::string& out) {
        std::error_code ec;
        return fs::is_regular_file(dir / out, ec);
      })) {
    allowed_files = c.outputs;
  }
  if (ours || (o.sent && finished && o.exit_code == 0)) {
    allowed_prefixes = c.after_signal;
  }
  if (ours && c.run.signal == SIGKILL) {
    allowed_prefixes.emplace_back("");  // anything: the twin run judges what remains
  }
  if (!v.hang) {
    const std::vector<std::string> extra =
        extra_entries(entries_under(dir), before, allowed_files, allowed_prefixes);
    if (!extra.empty()) {
      fault(v, v.leftovers,
            "left " + extra.front() +
                (extra.size() > 1 ? " and " + std::to_string(extra.size() - 1) + " more" : "") +
                " after " + describe(o));
    }
  }

  if (c.twin != Twin::kNone && v.clean()) {
    const bool killed = ours && c.run.signal == SIGKILL;
    if (c.twin == Twin::kCleanAfterKill || c.twin == Twin::kResume) {
      const Outcome t = invoke(binary, c.second, dir, capture, c.limit_s);
      Case twin_case = c;
      twin_case.exits = {0};
      judge_ending(twin_case, c.second, t, v);
      if (v.clean()) {
        const std::vector<std::string> extra =
            extra_entries(entries_under(dir), before, c.outputs, {});
        if (!extra.empty()) {
          fault(v, v.leftovers,
                "left " + extra.front() + " after the " +
                    (killed ? "rerun that follows SIGKILL" : "second run"));
        }
        for (const std::string& out : c.outputs) {
          std::error_code ec;
          if (!fs::is_regular_file(dir / out, ec)) {
            fault(v, v.false_success, "the second run left no " + out);
          }
        }
      }
      if (v.clean() && c.twin == Twin::kResume && !c.outputs.empty()) {
        bool unique = false;
        const long long rows = csv_rows_with_unique_ids(read_text(dir / c.outputs.front()), unique);
        if (rows != c.resume_points || !unique) {
          fault(v, v.false_success,
                "resumed sweep has " + std::to_string(rows) + " rows" +
                    (unique ? "" : " with repeated ids") + ", expected " +
                    std::to_string(c.resume_points));
        }
      }
    } else if (c.twin == Twin::kSameOutput && finished && o.exit_code == 0) {
      const std::string first = c.output.empty() ? o.out : read_text(dir / c.output);
      const Outcome t = invoke(binary, c.second, dir, capture, c.limit_s);
      Case twin_case = c;
      twin_case.exits = {0};
      judge_ending(twin_case, c.second, t, v);
      const std::string second = c.twin_output.empty() ? t.out : read_text(dir / c.twin_output);
      if (v.clean() && first != second) {
        fault(v, v.false_success, "CRLF input gives another output than the LF one");
      }
    }
  }
  std::error_code ec;
  fs::remove_all(root, ec);
  return v;
}

// ---- replay lines --------------------------------------------------------------------------

namespace {

std::string quote(const std::string& s) {
  std::string out = "'";
  for (const char ch : s) {
    if (ch == '\'') {
      out += "'\\''";
    } else if (ch == '\r') {
      out += "'$'\\r''";
    } else {
      out.push_back(ch);
    }
  }
  return out + "'";
}

/// A Python literal of `s` inside a shell double-quoted argument.
std::string py_literal(const std::string& s) {
  std::string out = "'";
  for (const char ch : s) {
    switch (ch) {
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\'':
        out += "\\'";
        break;
      case '"':
      case '$':
      case '`':
        out += std::string("\\") + ch;
        break;
      default:
        out.push_back(ch);
    }
  }
  return out + "'";
}

/// A shell line writing `text` with its long runs of one character compressed ('x' * 100000),
/// or "" when the rest is still too long to read.
std::string run_length_recipe(const std::string& text) {
  std::string expr;
  std::string literal;
  std::size_t shown = 0;
  for (std::size_t i = 0; i < text.size();) {
    std::size_t j = i;
    while (j < text.size() && text[j] == text[i]) {
      ++j;
    }
    if (j - i > 50) {
      expr += (expr.empty() ? "" : " + ") + py_literal(literal) + " + " +
              py_literal(std::string(1, text[i])) + " * " + std::to_string(j - i);
      shown += literal.size();
      literal.clear();
    } else {
      literal.append(text, i, j - i);
    }
    i = j;
  }
  shown += literal.size();
  expr += (expr.empty() ? "" : " + ") + py_literal(literal);
  if (shown > 1500) {
    return "";
  }
  return "python3 -c \"import sys; sys.stdout.write(" + expr + ")\"";
}

std::string command_line(const Invocation& inv) {
  std::string line = "slipwalk";
  for (const std::string& a : inv.args) {
    const bool plain = !a.empty() && a.find_first_not_of(
                                         "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                         "0123456789-_./=+:") == std::string::npos;
    line += " " + (plain ? a
                         : quote(a.size() > 300 ? a.substr(0, 40) + "...(" +
                                                      std::to_string(a.size()) + " chars)"
                                                : a));
  }
  if (!inv.stdin_file.empty()) {
    line += " < " + inv.stdin_file;
  }
  if (!inv.stdout_to.empty()) {
    line += " > " + inv.stdout_to;
  }
  if (inv.signal != 0) {
    line += " & sleep " + std::to_string(inv.signal_after_s).substr(0, 5) + "; kill -" +
            std::to_string(inv.signal) + " $!; wait $!";
  }
  return line;
}

}  // namespace

std::string replay_line(const Case& c) {
  std::string line = "cd \"$(mktemp -d)\"";
  for (const std::string& f : c.folders) {
    line += " && mkdir -p " + quote(f);
  }
  for (const InputFile& f : c.files) {
    if (!f.recipe.empty()) {
      line += " && " + f.recipe + " > " + quote(f.name);
    } else if (f.text.size() <= 600) {
      line += " && printf '%s' " + quote(f.text) + " > " + quote(f.name);
    } else if (const std::string r = run_length_recipe(f.text); !r.empty()) {
      line += " && " + r + " > " + quote(f.name);
    } else {
      line += " && : " + quote(f.name) + " is " + std::to_string(f.text.size()) + " bytes";
    }
  }
  for (const std::string& f : c.fifos) {
    line += " && mkfifo " + quote(f);
  }
  for (const auto& [link, target] : c.symlinks) {
    line += " && ln -s " + quote(target) + " " + quote(link);
  }
  line += " && " + command_line(c.run);
  if (c.twin != Twin::kNone) {
    line += "; " + command_line(c.second);
  }
  return line + "; echo \"exit $?\"; ls -A";
}

void Tally::add(long long index, const Case& c, const Verdict& v) {
  ++tried;
  ok += v.clean() ? 1 : 0;
  crashes += v.crash ? 1 : 0;
  hangs += v.hang ? 1 : 0;
  wrong_exit += v.wrong_exit ? 1 : 0;
  no_place += v.no_place ? 1 : 0;
  false_success += v.false_success ? 1 : 0;
  clobbered += v.clobbered ? 1 : 0;
  leftovers += v.leftovers ? 1 : 0;
  max_wall_s = std::max(max_wall_s, v.wall_s);
  if (!v.clean() && first_failure.empty()) {
    first_failure = "case " + std::to_string(index) + " (" + c.title + "): " + v.detail + " | " +
                    replay_line(c);
  }
}

}  // namespace slipwalk::sweeps::hostile
