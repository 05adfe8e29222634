#pragma once
// IWYU pragma: private
/// @file
/// Input checks shared by the association algorithms (compatibility_table.hpp, jcbb.hpp,
/// joint_compatibility.hpp).

#include <sstream>
#include <unordered_set>
#include <vector>

#include <Eigen/Core>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

namespace sylva::detail {

/// Throws kInvalidArgument unless 0 < p < 1 (NaN fails too).
inline void checkGateProbability(double p, const char* who) {
  if (!(p > 0.0 && p < 1.0)) {
    std::ostringstream os;
    os << who << ": gate_probability = " << p << " must lie strictly between 0 and 1";
    fail(ErrorCode::kInvalidArgument, os.str());
  }
}

/// Every measurement finite (kNonFinite).
template <int M>
void checkMeasurements(const std::vector<Vec<M>>& measurements, const char* who) {
  for (std::size_t i = 0; i < measurements.size(); ++i) {
    if (!measurements[i].allFinite()) {
      std::ostringstream os;
      os << who << ": measurement " << i << " is not finite";
      fail(ErrorCode::kNonFinite, os.str());
    }
  }
}

/// Every candidate is in the filter (kUnknownId) and appears once (kInvalidArgument).
template <typename EkfT>
void checkCandidates(const EkfT& ekf, const std::vector<Id>& candidates, const char* who) {
  std::unordered_set<Id> seen;
  seen.reserve(candidates.size());
  for (const Id id : candidates) {
    if (!ekf.contains(id)) {
      std::ostringstream os;
      os << who << ": candidate landmark id " << id << " is not in the filter";
      fail(ErrorCode::kUnknownId, os.str());
    }
    if (!seen.insert(id).second) {
      std::ostringstream os;
      os << who << ": candidate landmark id " << id << " is listed more than once";
      fail(ErrorCode::kInvalidArgument, os.str());
    }
  }
}

}  // namespace sylva::detail
