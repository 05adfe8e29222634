#pragma once
/// @file
/// `smallestNis`: the smallest normalized innovation squared (eq. 2.46) of one measurement
/// over a list of candidate landmarks. It is the usual test before a measurement that paired
/// with nothing starts a new landmark: only when even the closest candidate is far beyond
/// the association gate (`smallestNis(...) > chiSquareGate(dim, p)`, p close to 1) is the
/// measurement a new landmark rather than an ambiguous sighting of a mapped one.
///
/// Returns +infinity for an empty candidate list. Errors are those of `Ekf::innovation`
/// (unknown id, wrong landmark type, S not positive definite, non-finite values). The filter
/// is never changed.

#include <algorithm>
#include <limits>

#include "sylva/core/types.hpp"
#include "sylva/noise/gaussian.hpp"

namespace sylva {

template <typename Filter, typename Model, typename IdRange>
double smallestNis(const Filter& ekf,
                   const Model& model,
                   const Vec<Model::kDim>& z,
                   const Gaussian<Model::kDim>& noise,
                   const IdRange& candidates) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const Id id : candidates) smallest = std::min(smallest, ekf.innovation(model, id, z, noise).nis());
  return smallest;
}

}  // namespace sylva
