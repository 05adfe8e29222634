#pragma once
/// @file
/// `LandmarkSlot` and `detail::SlotTable`: where each landmark lives in the filter's state.
///
/// The table keeps the slots in state order (each slot's block follows the previous one's)
/// and an index from user id to slot. It knows nothing of means or covariances: the filter
/// moves those, and tells the table what it moved. Every change that can allocate is split
/// so that the filter can do it before it writes anything of its own (`reserveOne`, then
/// `append`, whose only allocation is the index entry and which changes nothing if it
/// fails); removing and moving slots allocates nothing.

#include <algorithm>
#include <cstddef>
#include <string>
#include <unordered_map>
#include <vector>

#include "sylva/core/error.hpp"
#include "sylva/core/types.hpp"

namespace sylva {

/// Where a landmark lives in the state.
struct LandmarkSlot {
  Id id;
  int type_index;  ///< index into the filter's `Landmarks...`
  int offset;      ///< first row of the block in the state
  int dim;         ///< block size
};

namespace detail {

class SlotTable {
 public:
  int size() const { return static_cast<int>(slots_.size()); }
  const std::vector<LandmarkSlot>& slots() const { return slots_; }
  bool contains(Id id) const { return index_.count(id) != 0; }

  /// The position of landmark `id` in `slots()` (throws kUnknownId).
  std::size_t indexOf(Id id) const {
    const auto it = index_.find(id);
    if (it == index_.end()) fail(ErrorCode::kUnknownId, "no landmark with id " + std::to_string(id));
    return it->second;
  }
  /// The slot of `id`, or nullptr.
  const LandmarkSlot* find(Id id) const {
    const auto it = index_.find(id);
    return it == index_.end() ? nullptr : &slots_[it->second];
  }
  const LandmarkSlot& operator[](std::size_t k) const { return slots_[k]; }

  /// Room for one more slot (doubling), so that `append` cannot fail for want of it.
  void reserveOne() {
    if (slots_.size() == slots_.capacity()) slots_.reserve(std::max<std::size_t>(8, 2 * slots_.capacity()));
  }

  /// Appends `slot` (after `reserveOne`). Its index entry is the one allocation: if it
  /// fails, the table is unchanged.
  void append(const LandmarkSlot& slot) {
    index_.emplace(slot.id, slots_.size());
    slots_.push_back(slot);  // room reserved by reserveOne
  }

  /// Removes slot k, whose block left the state: the slots after it move up by its size.
  /// Allocates nothing.
  void erase(std::size_t k) {
    const LandmarkSlot s = slots_[k];
    index_.erase(s.id);
    closeGap(k, s.dim);
  }

  /// Moves slot k to index `to` (counted without it) as `moved` (same id, at `moved.offset`,
  /// where the filter put its new block: a reparametrization). Allocates nothing.
  void moveTo(std::size_t k, const LandmarkSlot& moved, std::size_t to) {
    closeGap(k, slots_[k].dim);
    slots_.insert(slots_.begin() + static_cast<std::ptrdiff_t>(to), moved);  // one slot fewer than before
    for (std::size_t j = to; j < slots_.size(); ++j) {
      if (j > to) slots_[j].offset += moved.dim;
      index_[slots_[j].id] = j;  // the entry exists: no allocation
    }
  }

  /// Inserts `slot` (after `reserveOne`) as slot k, at its offset: the slots from k on move
  /// down by its size. Its index entry is the one allocation, made first: if it fails, the
  /// table is unchanged.
  void insertAt(std::size_t k, const LandmarkSlot& slot) {
    index_.emplace(slot.id, k);
    slots_.insert(slots_.begin() + static_cast<std::ptrdiff_t>(k), slot);  // room reserved
    for (std::size_t j = k + 1; j < slots_.size(); ++j) {
      slots_[j].offset += slot.dim;
      index_[slots_[j].id] = j;  // the entry exists: no allocation
    }
  }

  /// Exchanges slots a and b, which have the same size and whose blocks the filter has
  /// exchanged: each takes the other's place and offset. Allocates nothing.
  void swapPositions(std::size_t a, std::size_t b) {
    std::swap(slots_[a].offset, slots_[b].offset);
    std::swap(slots_[a], slots_[b]);
    index_[slots_[a].id] = a;  // the entries exist: no allocation
    index_[slots_[b].id] = b;
  }

  /// Lays the slots out in the order of `order` (the same slots, each once), from offset
  /// `first`. Allocates nothing (`order` has the table's size).
  void reorder(const std::vector<LandmarkSlot>& order, int first) {
    slots_ = order;  // same size: the vector keeps its storage
    int offset = first;
    for (std::size_t j = 0; j < slots_.size(); ++j) {
      slots_[j].offset = offset;
      offset += slots_[j].dim;
      index_[slots_[j].id] = j;  // the entry exists: no allocation
    }
  }

 private:
  /// Drops slot k from the list and moves the ones after it up by `dim` rows.
  void closeGap(std::size_t k, int dim) {
    slots_.erase(slots_.begin() + static_cast<std::ptrdiff_t>(k));
    for (std::size_t j = k; j < slots_.size(); ++j) {
      slots_[j].offset -= dim;
      index_[slots_[j].id] = j;  // the entry exists: no allocation
    }
  }

  std::vector<LandmarkSlot> slots_;
  std::unordered_map<Id, std::size_t> index_;
};

}  // namespace detail
}  // namespace sylva
