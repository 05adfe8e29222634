#pragma once
/// @file
/// `AssociationScore`: how a run that associates without ids took its readings, scored with
/// the true ids it did not see (a simulator's, or a labelled recording's). A landmark stands
/// for the true object of the reading that started it.

#include <cstddef>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

struct AssociationScore {
  long sightings = 0;       ///< readings scored
  long paired_correct = 0;  ///< readings fused into a landmark of their own object
  long paired_wrong = 0;    ///< ... into a landmark of another object
  /// ... of them, while their own object had no landmark yet: the other object's landmark
  /// took over this object's track (e.g. a trunk that comes out from behind another, where a
  /// young landmark predicts a sighting)
  long paired_before_own = 0;
  long new_trees = 0;   ///< readings that started a landmark
  long duplicates = 0;  ///< ... of an object that already had one
  long ambiguous = 0;   ///< dropped, neither paired nor clearly new

  /// Readings taken correctly: paired with their own object's landmark, or starting the first
  /// landmark of their object.
  double correctFraction() const {
    return sightings > 0 ? static_cast<double>(paired_correct + new_trees - duplicates) / static_cast<double>(sightings)
                         : 1.0;
  }

  /// Adds one frame: `tree[i]` is the true object of reading i, `landmark_of[i]` the landmark
  /// the run took it as (-1: dropped; e.g. slam::FrameReport::landmark_of). A landmark not in
  /// `tree_of` was started by this reading. `tree_of` maps each landmark to the object of the
  /// reading that started it, and gains this frame's new ones. At most one reading per object
  /// in a frame.
  void addFrame(const std::vector<Id>& tree, const std::vector<Id>& landmark_of,
                std::unordered_map<Id, Id>& tree_of) {
    if (landmark_of.size() != tree.size())
      fail(ErrorCode::kInvalidArgument, "AssociationScore::addFrame: " + std::to_string(tree.size()) + " readings but " +
                                            std::to_string(landmark_of.size()) + " landmarks; one per reading expected");
    std::unordered_set<Id> mapped;  // trees with a landmark before this frame's new ones
    for (const auto& entry : tree_of) mapped.insert(entry.second);
    for (std::size_t i = 0; i < tree.size(); ++i) {
      ++sightings;
      const Id landmark = landmark_of[i];
      if (landmark < 0) {
        ++ambiguous;
        continue;
      }
      const auto it = tree_of.find(landmark);
      if (it != tree_of.end()) {
        if (it->second == tree[i]) {
          ++paired_correct;
        } else {
          ++paired_wrong;
          if (mapped.count(tree[i]) == 0) ++paired_before_own;
        }
        continue;
      }
      tree_of.emplace(landmark, tree[i]);
      ++new_trees;
      if (!mapped.insert(tree[i]).second) ++duplicates;
    }
  }
};

}  // namespace sylva
