#include "nav/qrm/relational_map.hpp"

#include <algorithm>
#include <bit>
#include <string>

#include "nav/qrm/operators.hpp"

namespace neopipe::nav::qrm {

RelationalMap::RelationalMap(const CompositionTable& table) : table_(&table) {}

namespace {

// slot(), read() and restrict() run a few hundred million times while a 100-landmark map is built
// (propagation reads every known neighbour of a changed triple): calls to them were a third of the
// time, so they are forced inline into process() where the compiler would not.
#if defined(__GNUC__)
#define NEOPIPE_QRM_MAP_HOT [[gnu::always_inline]] inline
#else
#define NEOPIPE_QRM_MAP_HOT inline
#endif

// The unordered triples {i < j < k} in the order landmarks join the map (all of k's after all of
// k - 1's): C(k, 3) + C(j, 2) + i, the combinatorial number system. A closed form, so a read
// touches no index table, and a map of any size is one flat array of masks.
std::size_t triple_rank(std::size_t i, std::size_t j, std::size_t k) {
  return k * (k - 1) * (k - 2) / 6 + j * (j - 1) / 2 + i;
}

}  // namespace

void RelationalMap::add_landmark(LandmarkId id) {
  if (index_.contains(id)) throw std::invalid_argument("landmark " + std::to_string(id) + " is already in the map");
  const std::size_t k = ids_.size();
  ids_.push_back(id);
  index_.emplace(id, static_cast<int>(k));
  // The new landmark is the largest index: its triples {i < j < k} come last, each unknown.
  masks_.resize(3 * triple_rank(0, 0, k + 1), StateSet::kAllMask);
  pending_.resize(triple_rank(0, 0, k + 1), 0);
  // k's pairs {i < k} come last by rank, with no known triple yet; more landmarks than the bitsets
  // hold widen every pair's bitset (rare: one more word per 64 landmarks).
  const std::size_t words = (ids_.size() + kWordBits - 1) / kWordBits;
  const std::size_t pairs = ids_.size() * (ids_.size() - 1) / 2;
  if (words == words_) {
    known_.resize(pairs * words_, 0);
    return;
  }
  std::vector<Word> wider(pairs * words, 0);
  for (std::size_t pair = 0; pair < (words_ == 0 ? 0 : known_.size() / words_); ++pair) {
    std::copy_n(known_.begin() + static_cast<std::ptrdiff_t>(pair * words_), words_,
                wider.begin() + static_cast<std::ptrdiff_t>(pair * words));
  }
  known_ = std::move(wider);
  words_ = words;
}

std::size_t RelationalMap::pair_rank(int i, int j) {
  const auto lo = static_cast<std::size_t>(std::min(i, j));
  const auto hi = static_cast<std::size_t>(std::max(i, j));
  return hi * (hi - 1) / 2 + lo;
}

void RelationalMap::set_known(int x, int y, int z) {
  const auto bit = [](int d) { return Word{1} << (static_cast<unsigned>(d) % kWordBits); };
  const auto word = [](int d) { return static_cast<std::size_t>(d) / kWordBits; };
  known(x, y)[word(z)] |= bit(z);
  known(y, z)[word(x)] |= bit(x);
  known(x, z)[word(y)] |= bit(y);
}

void RelationalMap::clear_known(int x, int y, int z) {
  const auto bit = [](int d) { return Word{1} << (static_cast<unsigned>(d) % kWordBits); };
  const auto word = [](int d) { return static_cast<std::size_t>(d) / kWordBits; };
  known(x, y)[word(z)] &= ~bit(z);
  known(y, z)[word(x)] &= ~bit(x);
  known(x, z)[word(y)] &= ~bit(y);
}

int RelationalMap::index_of(LandmarkId id) const {
  const auto it = index_.find(id);
  if (it == index_.end()) throw std::invalid_argument("landmark " + std::to_string(id) + " is not in the map");
  return it->second;
}

NEOPIPE_QRM_MAP_HOT RelationalMap::Slot RelationalMap::slot(int p, int q, int r) const {
  // Stored for x < y < z: xy:z (0), yz:x (1), zx:y (2). qp:r = I(pq:r), so first make p < q.
  bool inverse = p > q;
  const int i = std::min(p, q);
  const int j = std::max(p, q);
  int x = i;
  int y = j;
  int z = r;
  std::uint32_t which = 0;  // j < r: ij:r = xy:z
  if (r < i) {              // r < i < j: ij:r = yz:x
    x = r;
    y = i;
    z = j;
    which = 1;
  } else if (r < j) {  // i < r < j: ij:r = xz:y = I(zx:y)
    y = r;
    z = j;
    which = 2;
    inverse = !inverse;
  }
  return {static_cast<std::uint32_t>(
              3 * triple_rank(static_cast<std::size_t>(x), static_cast<std::size_t>(y), static_cast<std::size_t>(z)) +
              which),
          inverse};
}

NEOPIPE_QRM_MAP_HOT StateSet RelationalMap::read(int p, int q, int r) const {
  const Slot s = slot(p, q, r);
  const StateSet stored = StateSet::from_mask(masks_[s.mask_index]);
  return s.inverse ? inverse(stored) : stored;
}

StateSet RelationalMap::relation(LandmarkId p, LandmarkId q, LandmarkId r) const {
  const int a = index_of(p);
  const int b = index_of(q);
  const int c = index_of(r);
  if (a == b || b == c || a == c) throw std::invalid_argument("a relation needs three distinct landmarks");
  return read(a, b, c);
}

NEOPIPE_QRM_MAP_HOT void RelationalMap::store(std::uint32_t mask_index, StateSet::Mask next, int x, int y, int z) {
  journal_.push_back({mask_index, masks_[mask_index], {x, y, z}});
  masks_[mask_index] = next;
  // next is a strict subset of what was stored, so never "all": the triple is known from now on.
  set_known(x, y, z);
}

NEOPIPE_QRM_MAP_HOT void RelationalMap::mark_changed(std::size_t rank, int which, int x, int y, int z) {
  std::uint8_t& bits = pending_[rank];
  if (bits == 0) queue_.push_back({x, y, z});
  bits = static_cast<std::uint8_t>(bits | (1U << static_cast<unsigned>(which)));
}

NEOPIPE_QRM_MAP_HOT bool RelationalMap::restrict(int a, int b, int c, StateSet states) {
  if (states.is_all()) return true;
  const Slot s = slot(a, b, c);
  const StateSet stored = StateSet::from_mask(masks_[s.mask_index]);
  const StateSet current = s.inverse ? inverse(stored) : stored;
  const StateSet next = current & states;
  if (next == current) return true;
  if (next.empty()) return false;
  const int x = std::min({a, b, c});
  const int z = std::max({a, b, c});
  const int y = a + b + c - x - z;
  store(s.mask_index, (s.inverse ? inverse(next) : next).mask(), x, y, z);
  mark_changed(s.mask_index / 3, static_cast<int>(s.mask_index % 3), x, y, z);
  return true;
}

bool RelationalMap::close_triple(const Triple& sorted, std::size_t rank, unsigned& changed) {
  // m[0] = xy:z, m[1] = yz:x, m[2] = zx:y: L takes each to the next, R to the one before.
  std::array<StateSet, 3> m{};
  for (std::size_t w = 0; w < 3; ++w) m[w] = StateSet::from_mask(masks_[3 * rank + w]);
  for (bool again = true; again;) {
    again = false;
    for (std::size_t w = 0; w < 3; ++w) {
      StateSet& next = m[(w + 1) % 3];
      StateSet& before = m[(w + 2) % 3];
      const StateSet left = next & left_shift(m[w]);
      const StateSet right = before & right_shift(m[w]);
      again = again || left != next || right != before;
      next = left;
      before = right;
    }
  }
  for (std::size_t w = 0; w < 3; ++w) {
    if (m[w].empty()) return false;
  }
  for (std::size_t w = 0; w < 3; ++w) {
    const auto index = static_cast<std::uint32_t>(3 * rank + w);
    if (m[w].mask() == masks_[index]) continue;
    store(index, m[w].mask(), sorted[0], sorted[1], sorted[2]);
    changed |= 1U << w;
  }
  return true;
}

const RelationalMap::Informative& RelationalMap::informative(StateSet x) {
  const auto found = informative_.find(x.mask());
  if (found != informative_.end()) return found->second;
  Informative out{0, 0};
  for (State s = 1; s <= kStateCount; ++s) {
    if (!(*table_)(x, StateSet{s}).is_all()) out.right |= StateSet::Mask{1} << s;
    if (!(*table_)(StateSet{s}, x).is_all()) out.left |= StateSet::Mask{1} << s;
  }
  return informative_.emplace(x.mask(), out).first->second;
}

bool RelationalMap::propagate_order(int p, int q, int r) {
  const CompositionTable& comp = *table_;
  const StateSet pqr = read(p, q, r);
  if (pqr.is_all()) return true;  // comp(all, s) = comp(s, all) = all: nothing to learn
  // comp(pqr, qr:d) is "all" as soon as qr:d holds a state y with comp(pqr, {y}) = all (the union
  // contains it), and likewise comp(dp:q, pqr): such compositions are skipped, and the order
  // itself when none can be informative (relations are never empty).
  const Informative& useful = informative(pqr);
  const StateSet::Mask right_useless = StateSet::kAllMask & ~useful.right;
  const StateSet::Mask left_useless = StateSet::kAllMask & ~useful.left;
  if (useful.right == 0 && useful.left == 0) return true;
  // Every d in increasing order, as a loop over all landmarks would, but only those for which
  // qr:d or dp:q may be known: for the others both reads below are "all" and skipped. Within
  // this loop the restrictions at d change the bits of {q, r} and {p, q} at d only, so a word
  // read once is what the loop over all d would have found.
  const Word* qr_known = known(q, r);
  const Word* pq_known = known(p, q);
  // A half that can learn nothing does not need its landmarks visited (the other half's reads
  // are "all" there, and no restriction of the skipped half can make them known).
  const Word qr_mask = useful.right != 0 ? ~Word{0} : 0;
  const Word pq_mask = useful.left != 0 ? ~Word{0} : 0;
  for (std::size_t w = 0; w < words_; ++w) {
    for (Word bits = (qr_known[w] & qr_mask) | (pq_known[w] & pq_mask); bits != 0; bits &= bits - 1) {
      const int d = static_cast<int>(w * kWordBits) + std::countr_zero(bits);
      if (d == p || d == q || d == r) continue;
      // AB:C = pq:r, BC:D = qr:d  ->  AB:D = pq:d.
      const StateSet qrd = read(q, r, d);
      if (!qrd.is_all() && (qrd.mask() & right_useless) == 0 && !restrict(p, q, d, comp(pqr, qrd))) return false;
      // AB:C = dp:q, BC:D = pq:r  ->  AB:D = dp:r.
      const StateSet dpq = read(d, p, q);
      if (!dpq.is_all() && (dpq.mask() & left_useless) == 0 && !restrict(d, p, r, comp(dpq, pqr))) return false;
    }
  }
  return true;
}

bool RelationalMap::process(const Triple& sorted) {
  const auto [x, y, z] = sorted;
  const std::size_t rank =
      triple_rank(static_cast<std::size_t>(x), static_cast<std::size_t>(y), static_cast<std::size_t>(z));
  unsigned changed = pending_[rank];
  // Composition never restricts the triple it reads pq:r from (d is a fourth landmark), so nothing
  // below queues this triple again: what the closure changes is composed in this visit.
  pending_[rank] = 0;
  if (!close_triple(sorted, rank, changed)) return false;
  // Stored mask w is read by two orders, pq:r and qp:r = I(pq:r).
  const std::array<std::array<Triple, 2>, 3> readers{
      {{{{x, y, z}, {y, x, z}}}, {{{y, z, x}, {z, y, x}}}, {{{z, x, y}, {x, z, y}}}}};
  for (std::size_t w = 0; w < 3; ++w) {
    if ((changed & (1U << w)) == 0) continue;
    for (const auto& [p, q, r] : readers[w]) {
      if (!propagate_order(p, q, r)) return false;
    }
  }
  return true;
}

FuseOutcome RelationalMap::fuse(LandmarkId a, LandmarkId b, LandmarkId c, StateSet states) {
  const int i = index_of(a);
  const int j = index_of(b);
  const int k = index_of(c);
  if (i == j || j == k || i == k) throw std::invalid_argument("a measurement needs three distinct landmarks");
  journal_.clear();
  queue_.clear();
  bool consistent = restrict(i, j, k, states);
  while (consistent && !queue_.empty()) {
    const Triple t = queue_.back();
    queue_.pop_back();
    consistent = process(t);
  }
  if (!consistent) {
    // The triples still queued are abandoned with the measurement.
    for (const Triple& t : queue_) {
      pending_[triple_rank(static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]),
                           static_cast<std::size_t>(t[2]))] = 0;
    }
    // Newest first, so a relation changed twice ends at its value before the measurement.
    for (std::size_t n = journal_.size(); n-- > 0;) masks_[journal_[n].mask_index] = journal_[n].before;
    // A triple all of whose relations are "all" again is unknown again.
    for (const JournalEntry& e : journal_) {
      const std::size_t first = e.mask_index - e.mask_index % 3;
      if (masks_[first] == StateSet::kAllMask && masks_[first + 1] == StateSet::kAllMask &&
          masks_[first + 2] == StateSet::kAllMask) {
        clear_known(e.sorted[0], e.sorted[1], e.sorted[2]);
      }
    }
    journal_.clear();
    queue_.clear();
    ++inconsistencies_;
    return FuseOutcome::inconsistent;
  }
  return journal_.empty() ? FuseOutcome::unchanged : FuseOutcome::refined;
}

bool RelationalMap::same_relations(const RelationalMap& other) const {
  if (ids_.size() != other.ids_.size()) return false;
  for (const LandmarkId id : ids_) {
    if (!other.has_landmark(id)) return false;
  }
  const std::size_t n = ids_.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        const LandmarkId p = ids_[i];
        const LandmarkId q = ids_[j];
        const LandmarkId r = ids_[k];
        if (relation(p, q, r) != other.relation(p, q, r) || relation(q, r, p) != other.relation(q, r, p) ||
            relation(r, p, q) != other.relation(r, p, q)) {
          return false;
        }
      }
    }
  }
  return true;
}

}  // namespace neopipe::nav::qrm
