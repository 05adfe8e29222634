#pragma once
// IWYU pragma: begin_exports
#include "sylva/landmarks/point2.hpp"
// IWYU pragma: end_exports
