#pragma once
// The planar filters and the range-bearing reading noise that the fault-injection tests
// (tests/filter/fault_injection*.test.cpp) fail allocations in.

#include <sylva/filter.hpp>
#include <sylva/landmarks/point2.hpp>
#include <sylva/measurements/range_bearing.hpp>
#include <sylva/motion/unicycle_2d.hpp>
#include <sylva/noise/gaussian.hpp>

namespace sylva_test::fault_injection {

using Planar = sylva::Ekf<sylva::Unicycle2D, sylva::Point2>;
using PlanarJoseph = sylva::JosephEkf<sylva::Unicycle2D, sylva::Point2>;
inline const auto kReading = sylva::Gaussian<2>::sigmas(sylva::Vec<2>(0.1, 0.02));

}  // namespace sylva_test::fault_injection
