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

  /// Restricts ab:c to `states` and propagates to the fixpoint (spec §7). On an inconsistency every
  /// change of this measurement is undone and counted.
  FuseOutcome fuse(LandmarkId a, LandmarkId b, LandmarkId c, StateSet states);

  /// Measurements rolled back so far.
  int inconsistencies() const { return inconsistencies_; }

  /// Same landmarks and the same states in every relation (whatever order the landmarks came in).
  bool same_relations(const RelationalMap& other) const;

 private:
  using Mask = StateSet::Mask;
  using Triple = std::array<int, 3>;

  int index_of(LandmarkId id) const;
  /// Row w (0: ij:d, 1: jd:i, 2: di:j) of the pair {i < j}, indexed by the third landmark d.
  Mask* row(int i, int j, int w);
  const Mask* row(int i, int j, int w) const;
  StateSet read(int p, int q, int r) const;
  /// Writes pq:r into the three rows that hold it.
  void write(int p, int q, int r, StateSet value);
  /// false when the restriction empties the relation.
  bool restrict(int a, int b, int c, StateSet states);
  /// Closes the triple's own relations under L and R in place; false on an empty relation. The
  /// relations that changed are added to `changed` (bit 0: xy:z, 1: yz:x, 2: zx:y).
  bool close_triple(const Triple& sorted, unsigned& changed);
  /// Lists in `candidates_` the d < n whose row value is neither "all" nor holds a state of `skip`;
  /// returns how many.
  int scan_row(const Mask* row, Mask skip, int n);
  /// Composes one order's pq:r with every other relation it meets; false on an inconsistency.
  bool propagate_order(int p, int q, int r);
  bool process(const Triple& sorted);

  const CompositionTable* table_;
  std::vector<LandmarkId> ids_;
  std::unordered_map<LandmarkId, int> index_;
  /// Per unordered pair {i < j} (by rank), three rows of `stride_` masks: ij:d, jd:i and di:j for
  /// every third landmark d (entries d = i, d = j and d past the last landmark hold "all"). Each
  /// relation is thus stored three times, once in the rows of each of its pairs: propagation reads
  /// the relations of a pair with every d, and a row lays them side by side, so that scan is a
  /// plain loop over memory with no index arithmetic, and skips "all" and useless values cheaply.
  std::vector<Mask> rows_;
  std::size_t stride_ = 0;
  int inconsistencies_ = 0;
  // Scratch of one fuse, kept to reuse its memory: a changed relation pq:r and its value before.
  struct JournalEntry {
    Triple order;
    StateSet before;
  };
  std::vector<JournalEntry> journal_;
  /// Per value of a relation X (its mask): the states y with comp(X, {y}) not "all", and the states
  /// x with comp({x}, X) not "all". A composition with a state outside them is "all" and restricts
  /// nothing, so propagation skips it without composing. Depends only on the table.
  struct Informative {
    Mask right;
    Mask left;
  };
  const Informative& informative(StateSet x);
  /// A direct-mapped cache of them (a hash lookup was a tenth of the propagation): slot by a hash of
  /// the mask, replaced on a miss; key 0 marks an empty slot (a relation is never empty).
  struct InformativeSlot {
    Mask key = 0;
    Informative value{0, 0};
  };
  static constexpr int kInformativeBits = 12;
  std::vector<InformativeSlot> informative_ = std::vector<InformativeSlot>(std::size_t{1} << kInformativeBits);
  /// Scratch of propagate_order: the landmarks d whose relation passed the scan.
  std::vector<int> candidates_;
  /// Sorted triples waiting to be processed, each at most once: a triple's `pending_` bits are the
  /// relations that changed since it was last processed (bit 0: xy:z, 1: yz:x, 2: zx:y), and it is
  /// in the queue exactly while some are set. Only the orders reading a changed relation are
  /// composed again when it is processed; the others were composed with the same value before.
  std::vector<Triple> queue_;
  std::vector<std::uint8_t> pending_;
};

}  // namespace neopipe::nav::qrm
