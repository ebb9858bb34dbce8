#include "residual/template.hpp"
