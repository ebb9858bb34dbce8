#include "contact/frame_json.hpp"

#include <cmath>

#include "core/error.hpp"
#include "core/json_input.hpp"

namespace slipwalk::contact {

namespace {

using core::InputError;
using nlohmann::json;

json parse_object(std::string_view text, const std::string& source) {
  json doc = core::parse_json(text, source);
  if (!doc.is_object()) {
    throw InputError(source, "expected a JSON object");
  }
  return doc;
}

std::string key_at(const std::string& source, const char* key, int j = -1) {
  // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on long operator+ chains.
  std::string where = source;
  where.append(": ").append(key);
  if (j >= 0) {
    where.append("[").append(std::to_string(j)).append("]");
  }
  return where;
}

double number(const json& v, const std::string& where) {
  if (!v.is_number()) {
    throw InputError(where, "expected a number, got " + core::json_excerpt(v));
  }
  const double x = v.get<double>();
  if (!std::isfinite(x)) {
    throw InputError(where, "expected a finite number");
  }
  return x;
}

/// An array of n numbers (or n arrays of `width` numbers when width > 0).
const json& array_of(const json& doc, const char* key, const std::string& source) {
  const json& a = doc.at(key);
  if (!a.is_array()) {
    throw InputError(key_at(source, key), "expected an array, got " + core::json_excerpt(a));
  }
  return a;
}

void read_vectors(const json& doc, const char* key, const std::string& source, int width, int n,
                  Eigen::MatrixXd& out) {
  const json& a = array_of(doc, key, source);
  if (static_cast<int>(a.size()) != n) {
    throw InputError(key_at(source, key),
                     "has " + std::to_string(a.size()) + " entries, q has " + std::to_string(n));
  }
  out.resize(width, n);
  for (int j = 0; j < n; ++j) {
    const json& v = a[static_cast<std::size_t>(j)];
    if (!v.is_array() || static_cast<int>(v.size()) != width) {
      throw InputError(key_at(source, key, j), "expected " + std::to_string(width) +
                                                   " numbers, got " + core::json_excerpt(v));
    }
    for (int i = 0; i < width; ++i) {
      out(i, j) = number(v[static_cast<std::size_t>(i)], key_at(source, key, j));
    }
  }
}

void read_scalars(const json& doc, const char* key, const std::string& source, int n,
                  double fallback, Eigen::VectorXd& out) {
  out = Eigen::VectorXd::Constant(n, fallback);
  if (!doc.contains(key)) {
    return;
  }
  const json& a = array_of(doc, key, source);
  if (static_cast<int>(a.size()) != n) {
    throw InputError(key_at(source, key), "has " + std::to_string(a.size()) + " entries, " +
                                              std::to_string(n) + " legs");
  }
  for (int j = 0; j < n; ++j) {
    out(j) = number(a[static_cast<std::size_t>(j)], key_at(source, key, j));
  }
}

void check_keys(const json& doc, const std::string& source,
                std::initializer_list<const char*> allowed) {
  for (const auto& [k, v] : doc.items()) {
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
      // A key is quoted as an excerpt: it may be any length.
      throw InputError(key_at(source, core::text_excerpt(k).c_str()),
                       "unknown key; expected " + list);
    }
  }
}

/// Robot fields of `doc` for n legs; InputError names source and key.
Robot read_robot(const json& doc, const std::string& source, int n) {
  Robot r;
  read_scalars(doc, "K", source, n, 1.0, r.K);
  read_scalars(doc, "mu", source, n, 1.0, r.mu);
  r.w = Eigen::Matrix2Xd::Zero(2, n);
  if (doc.contains("w")) {
    Eigen::MatrixXd w;
    read_vectors(doc, "w", source, 2, n, w);
    r.w = w;
  }
  r.Mg = doc.contains("Mg") ? number(doc.at("Mg"), key_at(source, "Mg")) : 1.0;
  try {
    validate(r);
  } catch (const InputError& e) {
    const std::string what = e.what();
    throw InputError(source + ": " + e.where(), what.substr(e.where().size() + 2));
  }
  return r;
}

}  // namespace

FrameInput parse_frame_json(std::string_view text, const std::string& source) {
  const json doc = parse_object(text, source);
  check_keys(doc, source, {"q", "qdot", "K", "Mg", "mu", "w", "theta"});
  for (const char* key : {"q", "qdot"}) {
    if (!doc.contains(key)) {
      throw InputError(key_at(source, key), "missing (required)");
    }
  }
  const int n = static_cast<int>(array_of(doc, "q", source).size());
  if (n < 1) {
    throw InputError(key_at(source, "q"), "needs at least one foot");
  }
  FrameInput in(read_robot(doc, source, n));
  Eigen::MatrixXd m;
  read_vectors(doc, "q", source, 3, n, m);
  in.frame.q = m;
  read_vectors(doc, "qdot", source, 3, n, m);
  in.frame.qdot = m;
  in.frame.theta = doc.contains("theta") ? number(doc.at("theta"), key_at(source, "theta")) : 0.0;
  return in;
}

Robot parse_robot_json(std::string_view text, const std::string& source) {
  const json doc = parse_object(text, source);
  check_keys(doc, source, {"legs", "K", "Mg", "mu", "w"});
  int n = 0;
  if (doc.contains("K")) {
    n = static_cast<int>(array_of(doc, "K", source).size());
  } else if (doc.contains("legs")) {
    const double legs = number(doc.at("legs"), key_at(source, "legs"));
    if (legs < 1 || legs != std::floor(legs) || legs > 100000) {
      throw InputError(key_at(source, "legs"), "expected a whole number of legs ≥ 1");
    }
    n = static_cast<int>(legs);
  } else {
    throw InputError(source, "a robot needs \"K\" (one stiffness per leg) or \"legs\"");
  }
  return read_robot(doc, source, n);
}

json frame_to_json(const Robot& robot, const Frame& f, bool with_connection) {
  const int n = robot.legs();
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
  static constexpr const char* kStatus[] = {"balanced", "line", "point", "unsupported",
                                            "iteration_limit"};
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
