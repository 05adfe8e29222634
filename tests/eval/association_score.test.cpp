// AssociationScore: scoring an association without ids against the true ids.

#include "sylva_catch.hpp"

#include <unordered_map>
#include <vector>

#include <sylva/eval/association_score.hpp>

#include "error_helpers.hpp"

using namespace sylva;
using sylva_test::throwsCode;

TEST_CASE("AssociationScore counts each kind of decision") {
  AssociationScore score;
  std::unordered_map<Id, Id> tree_of;
  // Frame 1: trees 10 and 11 start landmarks 0 and 1; tree 12's reading is dropped.
  score.addFrame({10, 11, 12}, {0, 1, -1}, tree_of);
  CHECK(score.new_trees == 2);
  CHECK(score.ambiguous == 1);
  CHECK(tree_of.at(0) == 10);
  CHECK(tree_of.at(1) == 11);
  // Frame 2: tree 10 into its landmark; tree 12 (no landmark yet) into tree 11's landmark: a
  // takeover; tree 11 starts landmark 2, a duplicate.
  score.addFrame({10, 12, 11}, {0, 1, 2}, tree_of);
  CHECK(score.paired_correct == 1);
  CHECK(score.paired_wrong == 1);
  CHECK(score.paired_before_own == 1);
  CHECK(score.duplicates == 1);
  // Frame 3: tree 10 into tree 11's second landmark, while tree 10 has one: wrong, not a
  // takeover; tree 13 starts landmark 3 and is not a duplicate.
  score.addFrame({10, 13}, {2, 3}, tree_of);
  CHECK(score.paired_wrong == 2);
  CHECK(score.paired_before_own == 1);
  CHECK(score.new_trees == 4);
  CHECK(score.duplicates == 1);
  CHECK(score.sightings == 8);
  // Right: 1 correct pairing + 4 new landmarks - 1 duplicate = 4 of 8.
  CHECK(score.correctFraction() == 0.5);
}

TEST_CASE("AssociationScore refuses a frame whose sizes differ and keeps its counts") {
  AssociationScore score;
  std::unordered_map<Id, Id> tree_of;
  score.addFrame({1}, {0}, tree_of);
  CHECK(throwsCode([&] { score.addFrame({1, 2}, {0}, tree_of); }, ErrorCode::kInvalidArgument));
  CHECK(score.sightings == 1);
  CHECK(score.new_trees == 1);
  CHECK(tree_of.size() == 1);
  CHECK(AssociationScore{}.correctFraction() == 1.0);
}
