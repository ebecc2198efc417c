#pragma once
// The qualitative relational map (spec qrm.md §7): a 3-uniform hypergraph over landmark ids whose
// edge {i < j < k} stores the states still possible for ij:k, jk:i and ki:j; every other order is
// read through I. Measurements are fused by restriction and propagated (operators and composition)
// to the greatest fixpoint; a measurement that empties a relation is rolled back whole.

#include <array>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "nav/qrm/composition.hpp"
#include "nav/qrm/state_set.hpp"

namespace neopipe::nav::qrm {

using LandmarkId = std::uint32_t;

/// What fusing a measurement did.
enum class FuseOutcome {
  unchanged,     ///< the map already implied it
  refined,       ///< some relation lost states
  inconsistent,  ///< it contradicted the map: rolled back, the map is as before
};

class RelationalMap {
 public:
  /// `table` must outlive the map.
  explicit RelationalMap(const CompositionTable& table = composition_table());

  /// Adds a landmark related to every pair of the others by all 20 states (nothing to propagate:
  /// comp with "all" is "all"). Throws std::invalid_argument if `id` is already there.
  void add_landmark(LandmarkId id);
  bool has_landmark(LandmarkId id) const { return index_.contains(id); }
  /// In the order they were added.
  const std::vector<LandmarkId>& landmarks() const { return ids_; }
  std::size_t size() const { return ids_.size(); }

  /// pq:r, for three distinct landmarks of the map.
  StateSet relation(LandmarkId p, LandmarkId q, LandmarkId r) const;

  /// Restricts ab:c to `states` and propagates to the fixpoint (spec §7, LIFO). On an inconsistency
  /// every change of this measurement is undone and counted.
  FuseOutcome fuse(LandmarkId a, LandmarkId b, LandmarkId c, StateSet states);

  /// Measurements rolled back so far.
  int inconsistencies() const { return inconsistencies_; }

  /// Same landmarks and the same states in every relation (whatever order the landmarks came in).
  bool same_relations(const RelationalMap& other) const;

 private:
  // A stored mask and whether reading it as the asked order needs I.
  struct Slot {
    std::uint32_t mask_index;
    bool inverse;
  };
  using Triple = std::array<int, 3>;

  using Word = std::uint64_t;
  static constexpr int kWordBits = 64;

  int index_of(LandmarkId id) const;
  Slot slot(int p, int q, int r) const;
  StateSet read(int p, int q, int r) const;
  /// false when the restriction empties the relation.
  bool restrict(int a, int b, int c, StateSet states);
  /// Stores a changed mask of the triple {x < y < z}: journalled and known, not queued.
  void store(std::uint32_t mask_index, StateSet::Mask next, int x, int y, int z);
  /// The triple {x < y < z} (by rank) changed its stored mask `which`: queued unless it is already.
  void mark_changed(std::size_t rank, int which, int x, int y, int z);
  /// Closes the triple's own relations under L and R in place; false on an empty relation. The
  /// stored masks that changed are added to `changed` (bit 0: xy:z, 1: yz:x, 2: zx:y).
  bool close_triple(const Triple& sorted, std::size_t rank, unsigned& changed);
  /// Composes one order's pq:r with every known neighbour relation; false on an inconsistency.
  bool propagate_order(int p, int q, int r);
  bool process(const Triple& sorted);
  /// The bitset of third landmarks d for which {i, j, d} is known (i != j, either order).
  Word* known(int i, int j) { return known_.data() + pair_rank(i, j) * words_; }
  static std::size_t pair_rank(int i, int j);
  /// Marks, or clears, {x, y, z} in the three pairs' bitsets.
  void set_known(int x, int y, int z);
  void clear_known(int x, int y, int z);

  const CompositionTable* table_;
  std::vector<LandmarkId> ids_;
  std::unordered_map<LandmarkId, int> index_;
  /// Three masks per unordered triple {i < j < k}: ij:k, jk:i, ki:j, the triples by rank.
  std::vector<StateSet::Mask> masks_;
  /// Per unordered pair {i < j} (by rank), `words_` words: bit d is set when some relation of the
  /// triple {i, j, d} is not "all". Propagation composes only with known relations (composition
  /// with "all" is "all" and is skipped), so it visits these d only instead of every landmark.
  std::vector<Word> known_;
  std::size_t words_ = 0;
  int inconsistencies_ = 0;
  // Scratch of one fuse, kept to reuse its memory: a changed mask's index, its value before, and
  // the triple it belongs to (to clear the known bits again on a rollback).
  struct JournalEntry {
    std::uint32_t mask_index;
    StateSet::Mask before;
    Triple sorted;
  };
  std::vector<JournalEntry> journal_;
  /// Per value of a relation X (its mask): the states y with comp(X, {y}) not "all", and the states
  /// x with comp({x}, X) not "all". A composition with a state outside them is "all" and restricts
  /// nothing, so propagation skips it without composing. Depends only on the table.
  struct Informative {
    StateSet::Mask right;
    StateSet::Mask left;
  };
  const Informative& informative(StateSet x);
  std::unordered_map<StateSet::Mask, Informative> informative_;
  /// Sorted triples waiting to be processed, each at most once: a triple's `pending_` bits are the
  /// stored masks that changed since it was last processed (bit 0: xy:z, 1: yz:x, 2: zx:y), and it
  /// is in the queue exactly while some are set. Only the orders reading a changed mask are composed
  /// again when it is processed; the others were composed with the same value before.
  std::vector<Triple> queue_;
  std::vector<std::uint8_t> pending_;
};

}  // namespace neopipe::nav::qrm
