#pragma once
// IWYU pragma: begin_exports
#include "sylva/noise/gaussian.hpp"
// IWYU pragma: end_exports
