#include "residual/trial.hpp"
