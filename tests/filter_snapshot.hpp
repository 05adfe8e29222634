#pragma once
// Test helpers for "bad input leaves the filter bit-identical": a snapshot of a filter's
// mean, covariance and slots, compared bit for bit, and `requireRejected`, which runs an
// operation, requires it to throw sylva::Error with a given code and message fragment, and
// requires the filter to be unchanged.

#include <string>
#include <vector>

#include <Eigen/Core>
#include <sylva/core/error.hpp>
#include <sylva/filter/ekf.hpp>

#include "sylva_catch.hpp"

namespace sylva_test {

/// The filter's mean, covariance and slots, compared bit for bit.
struct Snapshot {
  Eigen::VectorXd mean;
  Eigen::MatrixXd covariance;
  std::vector<sylva::LandmarkSlot> slots;
  template <typename F>
  explicit Snapshot(const F& ekf) : mean(ekf.mean()), covariance(ekf.covariance()), slots(ekf.slots()) {}
  bool operator==(const Snapshot& o) const {
    if (mean.size() != o.mean.size() || slots.size() != o.slots.size()) return false;
    for (std::size_t i = 0; i < slots.size(); ++i)
      if (slots[i].id != o.slots[i].id || slots[i].offset != o.slots[i].offset ||
          slots[i].type_index != o.slots[i].type_index)
        return false;
    return (mean.array() == o.mean.array()).all() && (covariance.array() == o.covariance.array()).all();
  }
};

/// Runs `operation`, requires it to throw sylva::Error with `code` and a message containing
/// `fragment`, and requires the filter to be unchanged.
template <typename F, typename Operation>
void requireRejected(const F& ekf, sylva::ErrorCode code, const std::string& fragment, Operation&& operation) {
  const Snapshot before(ekf);
  bool thrown = false;
  try {
    operation();
  } catch (const sylva::Error& e) {
    thrown = true;
    INFO("message: " << e.what());
    CHECK(e.code() == code);
    CHECK(std::string(e.what()).find(fragment) != std::string::npos);
  }
  CHECK(thrown);
  CHECK(Snapshot(ekf) == before);
}

}  // namespace sylva_test
