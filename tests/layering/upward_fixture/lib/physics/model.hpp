#pragma once
// A fixture, never compiled: a physics header that includes a driver above it. The layering
// check must reject this tree (tests/CMakeLists.txt: layering_check_rejects_an_upward_include).
#include "sweeps/engine/spec.hpp"
