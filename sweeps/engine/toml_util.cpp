#include "sweeps/engine/toml_util.hpp"

#include <sstream>
#include <string>

namespace slipwalk::sweeps {

std::string origin_of(const toml::source_region& region, const std::string& path) {
  return path + ":" + std::to_string(region.begin.line) + ":" + std::to_string(region.begin.column);
}

nlohmann::json toml_to_json(const toml::node& node) {
  if (const auto* t = node.as_table()) {
    nlohmann::json out = nlohmann::json::object();
    for (auto&& [k, v] : *t) {
      out[std::string(k.str())] = toml_to_json(v);
    }
    return out;
  }
  if (const auto* a = node.as_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& v : *a) {
      out.push_back(toml_to_json(v));
    }
    return out;
  }
  if (const auto* i = node.as_integer()) {
    return i->get();
  }
  if (const auto* f = node.as_floating_point()) {
    return f->get();
  }
  if (const auto* s = node.as_string()) {
    return s->get();
  }
  if (const auto* b = node.as_boolean()) {
    return b->get();
  }
  std::ostringstream text;  // dates and times: their TOML spelling
  if (const auto* d = node.as_date()) {
    text << d->get();
  } else if (const auto* tm = node.as_time()) {
    text << tm->get();
  } else if (const auto* dt = node.as_date_time()) {
    text << dt->get();
  }
  return text.str();
}

}  // namespace slipwalk::sweeps
