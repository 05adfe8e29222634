#pragma once
/// @file
/// `associateKnownIds`: data association when the sensor front end already identifies each
/// landmark (a simulator's ground-truth ids, fiducial markers, a tree detector that tracks
/// trunks). Measurement i is paired with `reported_ids[i]` if the filter holds that id;
/// otherwise the result is `std::nullopt`, which marks a landmark seen for the first time
/// (the caller initializes it with `Ekf::add`).
///
/// Two measurements may report the same id; both are then paired with it (two independent
/// observations of one landmark are legitimate for a batched update). O(k) expected time for
/// k reported ids. The filter is not changed.

#include <optional>
#include <vector>

#include "sylva/core/types.hpp"

namespace sylva {

template <class EkfT>
std::vector<std::optional<Id>> associateKnownIds(const EkfT& ekf,
                                                 const std::vector<Id>& reported_ids) {
  std::vector<std::optional<Id>> pairing;
  pairing.reserve(reported_ids.size());
  for (const Id id : reported_ids) {
    pairing.push_back(ekf.contains(id) ? std::optional<Id>(id) : std::nullopt);
  }
  return pairing;
}

}  // namespace sylva
