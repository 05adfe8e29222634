#pragma once
// IWYU pragma: begin_exports
#include "sylva/measurements/range_bearing.hpp"
// IWYU pragma: end_exports
