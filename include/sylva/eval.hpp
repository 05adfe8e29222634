#pragma once
// IWYU pragma: begin_exports
#include "sylva/eval/association_score.hpp"
#include "sylva/eval/map_errors.hpp"
#include "sylva/eval/rigid_2d.hpp"
#include "sylva/eval/similarity.hpp"
// IWYU pragma: end_exports
