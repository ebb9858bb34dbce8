// Point functions of the multi-legged model (thesis ch. 3); see point_functions.hpp.
#include "sweeps/point_functions.hpp"

namespace slipwalk::sweeps {

std::vector<PointFunction> legged_point_functions() { return {}; }

}  // namespace slipwalk::sweeps
