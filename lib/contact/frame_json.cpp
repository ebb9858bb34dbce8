#include "contact/frame_json.hpp"

#include <cmath>

#include "contact/spring_support.hpp"
#include "core/error.hpp"
#include "core/json_input.hpp"

namespace slipwalk::contact {

namespace {

using core::InputError;
using nlohmann::json;

// ---- places in the text ---------------------------------------------------------------------
// nlohmann::json keeps no positions, so an error names its place by walking the text (already
// accepted by core::parse_json: valid, shallow, no duplicate keys) along the value's path of keys
// and indices. Only an error pays for it.

/// A step of a path into the document: a key of an object, or an index of an array (key empty).
struct Step {
  std::string_view key;
  std::size_t index = 0;
};

std::size_t skip_space(std::string_view t, std::size_t i) {
  while (i < t.size() && (t[i] == ' ' || t[i] == '\t' || t[i] == '\n' || t[i] == '\r')) {
    ++i;
  }
  return i;
}

/// Past the string whose opening quote is at i.
std::size_t skip_string(std::string_view t, std::size_t i) {
  for (++i; i < t.size() && t[i] != '"'; ++i) {
    i += t[i] == '\\' ? 1 : 0;
  }
  return i + 1;
}

/// Past the value starting at i: a string, a scalar (up to the next space, ',' or bracket) or
/// a bracketed value (brackets counted, strings skipped: no recursion).
std::size_t skip_value(std::string_view t, std::size_t i) {
  int depth = 0;
  while (i < t.size()) {
    const char c = t[i];
    if (c == '"') {
      i = skip_string(t, i);
      if (depth == 0) {
        return i;
      }
      continue;
    }
    if (c == '[' || c == '{') {
      ++depth;
    } else if (c == ']' || c == '}') {
      if (depth == 0) {
        return i;
      }
      if (--depth == 0) {
        return i + 1;
      }
    } else if (depth == 0 && (c == ',' || c == ' ' || c == '\t' || c == '\n' || c == '\r')) {
      return i;
    }
    ++i;
  }
  return i;
}

/// The byte where the value (or, with `at_key`, the last step's key) of `path` starts; the
/// start of the document where the path leaves the text.
std::size_t locate(std::string_view t, std::initializer_list<Step> path, bool at_key = false) {
  std::size_t i = skip_space(t, 0);
  const std::size_t top = i;
  std::size_t n = 0;
  for (const Step& step : path) {
    const bool last = ++n == path.size();
    if (i >= t.size() || (t[i] != '{' && t[i] != '[')) {
      return top;
    }
    const bool object = t[i] == '{';
    i = skip_space(t, i + 1);
    for (std::size_t k = 0;; ++k) {
      if (i >= t.size() || t[i] == '}' || t[i] == ']') {
        return top;
      }
      bool here = !object && k == step.index;
      if (object) {
        const std::size_t key = i;
        const std::size_t end = skip_string(t, i);
        here = t.substr(key + 1, end - key - 2) == step.key;
        if (here && last && at_key) {
          return key;
        }
        i = skip_space(t, end);
        i = skip_space(t, i + 1);  // past ':'
      }
      if (here) {
        break;
      }
      i = skip_space(t, skip_value(t, i));
      i = skip_space(t, i + 1);  // past ','
    }
  }
  return i;
}

/// "<source>:<line>:<col>" of byte `offset` (1-based, columns in bytes).
std::string place(std::string_view t, const std::string& source, std::size_t offset) {
  std::size_t line = 1;
  std::size_t col = 1;
  for (std::size_t i = 0; i < offset && i < t.size(); ++i) {
    col = t[i] == '\n' ? 1 : col + 1;
    line += t[i] == '\n' ? 1 : 0;
  }
  std::string where = source;
  where.append(":").append(std::to_string(line)).append(":").append(std::to_string(col));
  return where;
}

/// "K[3]" or "q[2][0]": the name of a value in messages.
std::string name_of(std::string_view key, int j = -1, int i = -1) {
  std::string name(key);
  for (const int index : {j, i}) {
    if (index >= 0) {
      name.append("[").append(std::to_string(index)).append("]");
    }
  }
  return name;
}

/// One document and its text, for errors that name `file:line:col` and the value.
struct Doc {
  std::string_view text;
  const std::string& source;
  json root;

  /// InputError at the value key[j][i] (j, i < 0: not indexed), its message led by its name.
  [[noreturn]] void fail(std::string_view key, int j, int i, const std::string& what) const {
    std::size_t at = 0;
    const auto uj = static_cast<std::size_t>(j);
    const auto ui = static_cast<std::size_t>(i);
    if (j < 0) {
      at = locate(text, {{key}});
    } else if (i < 0) {
      at = locate(text, {{key}, {{}, uj}});
    } else {
      at = locate(text, {{key}, {{}, uj}, {{}, ui}});
    }
    throw InputError(place(text, source, at), name_of(key, j, i) + ": " + what);
  }

  [[noreturn]] void fail_key(std::string_view key, const std::string& what) const {
    throw InputError(place(text, source, locate(text, {{key}}, true)),
                     core::text_excerpt(key) + ": " + what);
  }

  /// A number in `range` (`friction`: 0 or in `range`, as μ).
  double number(const json& v, std::string_view key, int j, int i, const core::Range& range,
                bool friction = false) const {
    if (!v.is_number()) {
      fail(key, j, i, "expected a number, got " + core::json_excerpt(v));
    }
    const double x = v.get<double>();
    if (!range.contains(x) && !(friction && x == 0.0)) {
      std::string what = friction ? "must be 0 or in " : "must be in ";
      what.append(range.describe()).append(", got ").append(core::format_double(x));
      fail(key, j, i, what);
    }
    return x;
  }

  const json& array(const char* key) const {
    const json& a = root.at(key);
    if (!a.is_array()) {
      fail(key, -1, -1, "expected an array, got " + core::json_excerpt(a));
    }
    return a;
  }

  /// n vectors of `width` numbers in `range` (q, qdot, w).
  void vectors(const char* key, int width, int n, const core::Range& range,
               Eigen::MatrixXd& out) const {
    const json& a = array(key);
    if (static_cast<int>(a.size()) != n) {
      fail(key, -1, -1, "has " + std::to_string(a.size()) + " entries, q has " + std::to_string(n));
    }
    out.resize(width, n);
    for (int j = 0; j < n; ++j) {
      const json& v = a[static_cast<std::size_t>(j)];
      if (!v.is_array() || static_cast<int>(v.size()) != width) {
        fail(key, j, -1,
             "expected " + std::to_string(width) + " numbers, got " + core::json_excerpt(v));
      }
      for (int i = 0; i < width; ++i) {
        out(i, j) = number(v[static_cast<std::size_t>(i)], key, j, i, range);
      }
    }
  }

  /// n numbers in `range`, `fallback` each when the key is absent (K, mu).
  void scalars(const char* key, int n, double fallback, const core::Range& range,
               Eigen::VectorXd& out, bool friction = false) const {
    out = Eigen::VectorXd::Constant(n, fallback);
    if (!root.contains(key)) {
      return;
    }
    const json& a = array(key);
    if (static_cast<int>(a.size()) != n) {
      fail(key, -1, -1,
           "has " + std::to_string(a.size()) + " entries, " + std::to_string(n) + " legs");
    }
    for (int j = 0; j < n; ++j) {
      out(j) = number(a[static_cast<std::size_t>(j)], key, j, -1, range, friction);
    }
  }

  /// A single number in `range`, `fallback` when absent (Mg, theta).
  double scalar(const char* key, double fallback, const core::Range& range) const {
    return root.contains(key) ? number(root.at(key), key, -1, -1, range) : fallback;
  }

  void check_keys(std::initializer_list<const char*> allowed) const {
    for (const auto& [k, v] : root.items()) {
      bool ok = false;
      for (const char* a : allowed) {
        ok = ok || k == a;
      }
      if (!ok) {
        std::string list;
        for (const char* a : allowed) {
          list += list.empty() ? "" : ", ";
          list += a;
        }
        fail_key(k, "unknown key; expected " + list);
      }
    }
  }

  /// Robot fields for n legs (1 ≤ n ≤ limits::kMaxLegs), each checked against its range where
  /// it stands, so that validate() below finds nothing left.
  [[nodiscard]] Robot robot(int n) const {
    Robot r;
    scalars("K", n, 1.0, limits::kStiffness, r.K);
    scalars("mu", n, 1.0, limits::kFriction, r.mu, true);
    r.w = Eigen::Matrix2Xd::Zero(2, n);
    if (root.contains("w")) {
      Eigen::MatrixXd w;
      vectors("w", 2, n, limits::kAnisotropy, w);
      r.w = w;
    }
    r.Mg = scalar("Mg", 1.0, limits::kWeight);
    validate(r);  // finds nothing left: every value was checked where it stands
    return r;
  }
};

Doc parse_object(std::string_view text, const std::string& source) {
  json root = core::parse_json(text, source);
  if (!root.is_object()) {
    throw InputError(place(text, source, skip_space(text, 0)), "expected a JSON object");
  }
  return Doc{text, source, std::move(root)};
}

/// The leg count of an array key: 1 to limits::kMaxLegs.
int leg_count(const Doc& doc, const char* key) {
  const std::size_t n = doc.array(key).size();
  if (n < 1 || n > static_cast<std::size_t>(limits::kMaxLegs)) {
    doc.fail(key, -1, -1,
             "needs 1 to " + std::to_string(limits::kMaxLegs) + " legs, got " + std::to_string(n));
  }
  return static_cast<int>(n);
}

}  // namespace

FrameInput parse_frame_json(std::string_view text, const std::string& source) {
  const Doc doc = parse_object(text, source);
  doc.check_keys({"q", "qdot", "K", "Mg", "mu", "w", "theta"});
  for (const char* key : {"q", "qdot"}) {
    if (!doc.root.contains(key)) {
      throw InputError(place(text, source, skip_space(text, 0)),
                       std::string(key) + ": missing (required)");
    }
  }
  const int n = leg_count(doc, "q");
  FrameInput in(doc.robot(n));
  Eigen::MatrixXd m;
  doc.vectors("q", 3, n, limits::kPosition, m);
  in.frame.q = m;
  doc.vectors("qdot", 3, n, limits::kVelocity, m);
  in.frame.qdot = m;
  in.frame.theta = doc.scalar("theta", 0.0, limits::kYaw);
  return in;
}

Robot parse_robot_json(std::string_view text, const std::string& source) {
  const Doc doc = parse_object(text, source);
  doc.check_keys({"legs", "K", "Mg", "mu", "w"});
  int n = 0;
  if (doc.root.contains("K")) {
    n = leg_count(doc, "K");
  } else if (doc.root.contains("legs")) {
    const json& v = doc.root.at("legs");
    const double legs = v.is_number() ? v.get<double>() : 0.0;
    if (!v.is_number() || !(legs >= 1) || legs != std::floor(legs) || legs > limits::kMaxLegs) {
      doc.fail("legs", -1, -1,
               "expected a whole number of legs in [1, " + std::to_string(limits::kMaxLegs) +
                   "], got " + core::json_excerpt(v));
    }
    n = static_cast<int>(legs);
  } else {
    throw InputError(place(text, source, skip_space(text, 0)),
                     "a robot needs \"K\" (one stiffness per leg) or \"legs\"");
  }
  return doc.robot(n);
}

json frame_to_json(const Robot& robot, const Frame& f, bool with_connection) {
  const int n = robot.legs();
  // JSON has no NaN or inf (nlohmann would write null): a non-finite result is no result.
  const double outputs = f.alpha + f.beta + f.z + f.Fz.sum() + f.v_body.sum() + f.Fxy.sum() +
                         f.support.residual + f.friction.residual + f.friction.dissipation +
                         f.friction.certificate;
  if (!std::isfinite(outputs) || (with_connection && !f.A.allFinite())) {
    throw core::ComputationError(
        "the model's result is not finite (spring support: " +
        std::string(status_name(f.support.status)) +
        (f.friction.message.empty() ? std::string() : "; friction: " + f.friction.message) + ")");
  }
  json out;
  out["alpha"] = f.alpha;
  out["beta"] = f.beta;
  out["z"] = f.z;
  json contact = json::array();
  json fz = json::array();
  json fxy = json::array();
  for (int j = 0; j < n; ++j) {
    contact.push_back(f.contact[static_cast<std::size_t>(j)] != 0);
    fz.push_back(f.Fz(j));
    fxy.push_back({f.Fxy(0, j), f.Fxy(1, j)});
  }
  out["contact"] = contact;
  out["Fz"] = fz;
  out["v_body"] = {f.v_body(0), f.v_body(1), f.v_body(2)};
  out["Fxy"] = fxy;
  if (with_connection) {
    json a = json::array();
    for (int r = 0; r < 3; ++r) {
      json row = json::array();
      for (int c = 0; c < 2 * n; ++c) {
        row.push_back(f.A(r, c));
      }
      a.push_back(row);
    }
    out["A"] = a;
  } else {
    out["A"] = nullptr;
  }
  static constexpr const char* kStatus[] = {"balanced",        "line",      "point", "unsupported",
                                            "iteration_limit", "non_finite"};
  out["support"] = {{"status", kStatus[static_cast<int>(f.support.status)]},
                    {"iterations", f.support.iterations},
                    {"residual", f.support.residual},
                    {"message", f.support.message}};
  out["friction"] = {
      {"converged", f.friction.converged},     {"iterations", f.friction.iterations},
      {"residual", f.friction.residual},       {"certificate", f.friction.certificate},
      {"unique", f.friction.unique},           {"static_feet", f.friction.static_feet},
      {"dissipation", f.friction.dissipation}, {"message", f.friction.message}};
  return out;
}

}  // namespace slipwalk::contact
