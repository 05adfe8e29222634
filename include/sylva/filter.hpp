#pragma once
// IWYU pragma: begin_exports
#include "sylva/filter/ekf.hpp"
#include "sylva/filter/linearization.hpp"
#include "sylva/filter/update_form.hpp"
// IWYU pragma: end_exports
