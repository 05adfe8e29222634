#pragma once
// IWYU pragma: begin_exports
#include "sylva/core/angles.hpp"
#include "sylva/core/quaternion.hpp"
#include "sylva/core/error.hpp"
#include "sylva/core/jacobian_ref.hpp"
#include "sylva/core/scalar.hpp"
#include "sylva/core/types.hpp"
// IWYU pragma: end_exports
