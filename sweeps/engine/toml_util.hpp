#pragma once
// Small helpers over toml++ shared by the spec and study readers.
#include <toml++/toml.h>

#include <nlohmann/json.hpp>
#include <string>

namespace slipwalk::sweeps {

/// `path:line:col` of a node, for error messages (DESIGN.md: errors name file:line:col).
[[nodiscard]] std::string origin_of(const toml::source_region& region, const std::string& path);

/// A TOML node as JSON (tables, arrays, numbers, strings, booleans; dates and times as their
/// TOML spelling), for provenance sidecars.
[[nodiscard]] nlohmann::json toml_to_json(const toml::node& node);

}  // namespace slipwalk::sweeps
