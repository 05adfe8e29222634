#pragma once
/// @file
/// From detected objects to people and tracks (for the pictures and the real-data counts;
/// not part of the thesis' detector).
///
/// People: detected objects whose hull centroids are within `pair_distance_m` of each other
/// are grouped (single linkage); a group is one person candidate at the mean of its
/// centroids. Like the black stars of the thesis' Fig. 4.9, a group of two legs is the
/// "possible torso position".
///
/// Tracks: global nearest neighbour, greedily: the (track, candidate) pairs within
/// `gate_m` are taken in order of increasing distance; an unpaired candidate starts a track;
/// a track missing for more than `max_misses` scans ends. A track is confirmed once it has
/// `confirm_hits` candidates. Deterministic.

#include <algorithm>
#include <tuple>
#include <vector>

#include "sylva/core/types.hpp"

#include "sylva/laser/moving_object_detector.hpp"

namespace sylva::laser {

struct PersonCandidate {
  Vec<2> position;
  int legs = 0;  ///< detected objects in the group
};

inline std::vector<PersonCandidate> groupPeople(const std::vector<DetectedObject>& objects, double pair_distance_m) {
  const std::size_t n = objects.size();
  std::vector<std::size_t> parent(n);
  for (std::size_t i = 0; i < n; ++i) parent[i] = i;
  const auto root = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if ((objects[i].hull_centroid - objects[j].hull_centroid).norm() <= pair_distance_m)
        parent[root(j)] = root(i);
  std::vector<PersonCandidate> out;
  std::vector<std::size_t> slot(n, n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t r = root(i);
    if (slot[r] == n) {
      slot[r] = out.size();
      out.push_back(PersonCandidate{Vec<2>::Zero(), 0});
    }
    PersonCandidate& c = out[slot[r]];
    c.position += objects[i].hull_centroid;
    ++c.legs;
  }
  for (PersonCandidate& c : out) c.position /= c.legs;
  return out;
}

struct Track {
  int id = 0;
  std::vector<double> times;
  std::vector<Vec<2>> positions;
  int misses = 0;
  bool ended = false;
};

struct TrackerOptions {
  double gate_m = 0.8;
  int max_misses = 5;
  int confirm_hits = 3;
};

class NearestNeighborTracker {
 public:
  explicit NearestNeighborTracker(const TrackerOptions& o = {}) : o_(o) {}

  void update(double time, const std::vector<Vec<2>>& candidates) {
    struct Pair {
      double distance;
      std::size_t track;
      std::size_t candidate;
    };
    std::vector<Pair> pairs;
    for (std::size_t t = 0; t < tracks_.size(); ++t) {
      if (tracks_[t].ended) continue;
      for (std::size_t c = 0; c < candidates.size(); ++c) {
        const double d = (tracks_[t].positions.back() - candidates[c]).norm();
        if (d <= o_.gate_m) pairs.push_back({d, t, c});
      }
    }
    std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
      return std::tie(a.distance, a.track, a.candidate) < std::tie(b.distance, b.track, b.candidate);
    });
    std::vector<char> track_taken(tracks_.size(), 0), candidate_taken(candidates.size(), 0);
    for (const Pair& p : pairs) {
      if (track_taken[p.track] || candidate_taken[p.candidate]) continue;
      track_taken[p.track] = candidate_taken[p.candidate] = 1;
      tracks_[p.track].times.push_back(time);
      tracks_[p.track].positions.push_back(candidates[p.candidate]);
      tracks_[p.track].misses = 0;
    }
    for (std::size_t t = 0; t < track_taken.size(); ++t)
      if (!track_taken[t] && !tracks_[t].ended && ++tracks_[t].misses > o_.max_misses) tracks_[t].ended = true;
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      if (candidate_taken[c]) continue;
      Track t;
      t.id = static_cast<int>(tracks_.size());
      t.times.push_back(time);
      t.positions.push_back(candidates[c]);
      tracks_.push_back(std::move(t));
    }
  }

  const std::vector<Track>& tracks() const { return tracks_; }
  bool confirmed(const Track& t) const { return static_cast<int>(t.positions.size()) >= o_.confirm_hits; }
  int confirmedCount() const {
    int n = 0;
    for (const Track& t : tracks_) n += confirmed(t) ? 1 : 0;
    return n;
  }
  /// Confirmed tracks that are alive (not ended, seen in the last max_misses scans).
  int activeConfirmed() const {
    int n = 0;
    for (const Track& t : tracks_) n += (!t.ended && confirmed(t)) ? 1 : 0;
    return n;
  }

 private:
  TrackerOptions o_;
  std::vector<Track> tracks_;
};

}  // namespace sylva::laser
