#pragma once
// IWYU pragma: begin_exports
#include "sylva/diff/auto_diff.hpp"
#include "sylva/diff/numeric_diff.hpp"
// IWYU pragma: end_exports
