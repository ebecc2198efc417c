#include "nav/qrm/relational_map.hpp"

#include <algorithm>
#include <string>

#include "nav/qrm/operators.hpp"

namespace neopipe::nav::qrm {

RelationalMap::RelationalMap(const CompositionTable& table) : table_(&table) {}

namespace {

// read(), write() and restrict() run hundreds of millions of times while a 100-landmark map is
// built: they are forced inline into the propagation where the compiler would not.
#if defined(__GNUC__)
#define NEOPIPE_QRM_MAP_HOT [[gnu::always_inline]] inline
#else
#define NEOPIPE_QRM_MAP_HOT inline
#endif

// The unordered triples {i < j < k} in the order landmarks join the map (all of k's after all of
// k - 1's): C(k, 3) + C(j, 2) + i, the combinatorial number system.
std::size_t qrm_triple_rank(int i, int j, int k) {
  const auto a = static_cast<std::size_t>(i);
  const auto b = static_cast<std::size_t>(j);
  const auto c = static_cast<std::size_t>(k);
  return c * (c - 1) * (c - 2) / 6 + b * (b - 1) / 2 + a;
}

// The pairs {i < j} likewise: C(j, 2) + i.
std::size_t qrm_pair_rank(int i, int j) {
  const auto a = static_cast<std::size_t>(i);
  const auto b = static_cast<std::size_t>(j);
  return b * (b - 1) / 2 + a;
}

// Rows are widened in steps of this many landmarks: each widening copies the map, and a step
// leaves at most this many unused entries per row.
constexpr std::size_t kQrmRowStep = 32;

}  // namespace

void RelationalMap::add_landmark(LandmarkId id) {
  if (index_.contains(id)) throw std::invalid_argument("landmark " + std::to_string(id) + " is already in the map");
  const std::size_t k = ids_.size();
  ids_.push_back(id);
  index_.emplace(id, static_cast<int>(k));
  const std::size_t n = ids_.size();
  candidates_.resize(n);
  // The new landmark is the largest index: its triples {i < j < k} come last, none pending.
  pending_.resize(qrm_triple_rank(0, 0, static_cast<int>(n)), 0);
  const std::size_t pairs = n * (n - 1) / 2;
  if (n <= stride_) {
    // k's pairs {i < k} come last by rank, every relation "all".
    rows_.resize(3 * pairs * stride_, StateSet::kAllMask);
    return;
  }
  const std::size_t stride = (n + kQrmRowStep - 1) / kQrmRowStep * kQrmRowStep;
  std::vector<Mask> wider(3 * pairs * stride, StateSet::kAllMask);
  for (std::size_t r = 0; r < (stride_ == 0 ? 0 : rows_.size() / stride_); ++r) {
    std::copy_n(rows_.begin() + static_cast<std::ptrdiff_t>(r * stride_), stride_,
                wider.begin() + static_cast<std::ptrdiff_t>(r * stride));
  }
  rows_ = std::move(wider);
  stride_ = stride;
}

int RelationalMap::index_of(LandmarkId id) const {
  const auto it = index_.find(id);
  if (it == index_.end()) throw std::invalid_argument("landmark " + std::to_string(id) + " is not in the map");
  return it->second;
}

NEOPIPE_QRM_MAP_HOT RelationalMap::Mask* RelationalMap::row(int i, int j, int w) {
  return rows_.data() + (3 * qrm_pair_rank(i, j) + static_cast<std::size_t>(w)) * stride_;
}

NEOPIPE_QRM_MAP_HOT const RelationalMap::Mask* RelationalMap::row(int i, int j, int w) const {
  return rows_.data() + (3 * qrm_pair_rank(i, j) + static_cast<std::size_t>(w)) * stride_;
}

NEOPIPE_QRM_MAP_HOT StateSet RelationalMap::read(int p, int q, int r) const {
  const auto d = static_cast<std::size_t>(r);
  // qp:r = I(pq:r): the pair's first row holds the order with the smaller landmark first.
  return p < q ? StateSet::from_mask(row(p, q, 0)[d]) : inverse(StateSet::from_mask(row(q, p, 0)[d]));
}

NEOPIPE_QRM_MAP_HOT void RelationalMap::write(int p, int q, int r, StateSet value) {
  const Mask v = value.mask();
  const Mask iv = inverse(value).mask();
  // With the rows ij:d, jd:i, di:j of a pair {i < j}: pq:r is ij:d of {p, q} (d = r) when p < q,
  // di:j of {q, r} (d = p) when q < r, else I of jd:i; I of di:j of {p, r} (d = q) when p < r,
  // else jd:i.
  if (p < q) {
    row(p, q, 0)[r] = v;
  } else {
    row(q, p, 0)[r] = iv;
  }
  if (q < r) {
    row(q, r, 2)[p] = v;
  } else {
    row(r, q, 1)[p] = iv;
  }
  if (p < r) {
    row(p, r, 2)[q] = iv;
  } else {
    row(r, p, 1)[q] = v;
  }
}

StateSet RelationalMap::relation(LandmarkId p, LandmarkId q, LandmarkId r) const {
  const int a = index_of(p);
  const int b = index_of(q);
  const int c = index_of(r);
  if (a == b || b == c || a == c) throw std::invalid_argument("a relation needs three distinct landmarks");
  return read(a, b, c);
}

NEOPIPE_QRM_MAP_HOT bool RelationalMap::restrict(int a, int b, int c, StateSet states) {
  if (states.is_all()) return true;
  const StateSet current = read(a, b, c);
  const StateSet next = current & states;
  if (next == current) return true;
  if (next.empty()) return false;
  journal_.push_back({{a, b, c}, current});
  write(a, b, c, next);
  const int x = std::min({a, b, c});
  const int z = std::max({a, b, c});
  const int y = a + b + c - x - z;
  // ab:c is xy:z or its inverse when c = z, yz:x or zy:x when c = x, else zx:y or xz:y.
  const unsigned which = c == z ? 0U : (c == x ? 1U : 2U);
  std::uint8_t& bits = pending_[qrm_triple_rank(x, y, z)];
  if (bits == 0) queue_.push_back({x, y, z});
  bits = static_cast<std::uint8_t>(bits | (1U << which));
  return true;
}

bool RelationalMap::close_triple(const Triple& sorted, unsigned& changed) {
  const auto [x, y, z] = sorted;
  // m[0] = xy:z, m[1] = yz:x, m[2] = zx:y: L takes each to the next, R to the one before.
  const std::array<Triple, 3> orders{{{x, y, z}, {y, z, x}, {z, x, y}}};
  std::array<StateSet, 3> m{};
  for (std::size_t w = 0; w < 3; ++w) m[w] = read(orders[w][0], orders[w][1], orders[w][2]);
  const std::array<StateSet, 3> before = m;
  for (bool again = true; again;) {
    again = false;
    for (std::size_t w = 0; w < 3; ++w) {
      StateSet& next = m[(w + 1) % 3];
      StateSet& previous = m[(w + 2) % 3];
      const StateSet left = next & left_shift(m[w]);
      const StateSet right = previous & right_shift(m[w]);
      again = again || left != next || right != previous;
      next = left;
      previous = right;
    }
  }
  for (std::size_t w = 0; w < 3; ++w) {
    if (m[w].empty()) return false;
  }
  for (std::size_t w = 0; w < 3; ++w) {
    if (m[w] == before[w]) continue;
    journal_.push_back({orders[w], before[w]});
    write(orders[w][0], orders[w][1], orders[w][2], m[w]);
    changed |= 1U << w;
  }
  return true;
}

const RelationalMap::Informative& RelationalMap::informative(StateSet x) {
  const Mask key = x.mask();
  // Fibonacci hashing: the top bits of the product spread the 20-bit masks over the slots.
  InformativeSlot& slot = informative_[(key * 0x9E3779B1U) >> (32 - kInformativeBits)];
  if (slot.key == key) return slot.value;
  Informative out{0, 0};
  for (State s = 1; s <= kStateCount; ++s) {
    if (!(*table_)(x, StateSet{s}).is_all()) out.right |= Mask{1} << s;
    if (!(*table_)(StateSet{s}, x).is_all()) out.left |= Mask{1} << s;
  }
  slot = {key, out};
  return slot.value;
}

NEOPIPE_QRM_MAP_HOT int RelationalMap::scan_row(const Mask* row, Mask skip, int n) {
  // Most values are "all" or hold a useless state, unpredictably: branch-free, the few that pass
  // are listed without a mispredicted jump per landmark (out[found] is overwritten until one does).
  int found = 0;
  int* out = candidates_.data();
  for (int d = 0; d < n; ++d) {
    const Mask m = row[d];
    out[found] = d;
    found += static_cast<int>(m != StateSet::kAllMask && (m & skip) == 0);
  }
  return found;
}

bool RelationalMap::propagate_order(int p, int q, int r) {
  const CompositionTable& comp = *table_;
  const StateSet pqr = read(p, q, r);
  if (pqr.is_all()) return true;  // comp(all, s) = comp(s, all) = all: nothing to learn
  // comp(pqr, qr:d) is "all" as soon as qr:d holds a state y with comp(pqr, {y}) = all (the union
  // contains it), and likewise comp(dp:q, pqr): such compositions are skipped without composing.
  const Informative& useful = informative(pqr);
  const auto n = static_cast<int>(ids_.size());
  // Neither half restricts a relation the other reads (they restrict pq:d and dp:r, and read qr:d
  // and dp:q, d a fourth landmark), nor one it reads itself, so the halves run one after the other.
  if (useful.right != 0) {
    // AB:C = pq:r, BC:D = qr:d  ->  AB:D = pq:d. The row holds qr:d, or rq:d = I(qr:d) when r < q;
    // I maps "all" to "all" and the useless states to I of them, so the row is tested as stored.
    const bool flipped = r < q;
    const Mask* qr = flipped ? row(r, q, 0) : row(q, r, 0);
    const StateSet useless = StateSet::from_mask(StateSet::kAllMask & ~useful.right);
    const Mask skip = (flipped ? inverse(useless) : useless).mask();
    const int found = scan_row(qr, skip, n);
    for (int c = 0; c < found; ++c) {
      const int d = candidates_[static_cast<std::size_t>(c)];
      if (d == p) continue;
      const StateSet stored = StateSet::from_mask(qr[d]);
      if (!restrict(p, q, d, comp(pqr, flipped ? inverse(stored) : stored))) return false;
    }
  }
  if (useful.left != 0) {
    // AB:C = dp:q, BC:D = pq:r  ->  AB:D = dp:r. The row holds dp:q (di:j of {p, q}) when p < q,
    // else pd:q = I(dp:q) (jd:i of {q, p}).
    const bool flipped = q < p;
    const Mask* dp = flipped ? row(q, p, 1) : row(p, q, 2);
    const StateSet useless = StateSet::from_mask(StateSet::kAllMask & ~useful.left);
    const Mask skip = (flipped ? inverse(useless) : useless).mask();
    const int found = scan_row(dp, skip, n);
    for (int c = 0; c < found; ++c) {
      const int d = candidates_[static_cast<std::size_t>(c)];
      if (d == r) continue;
      const StateSet stored = StateSet::from_mask(dp[d]);
      if (!restrict(d, p, r, comp(flipped ? inverse(stored) : stored, pqr))) return false;
    }
  }
  return true;
}

bool RelationalMap::process(const Triple& sorted) {
  const auto [x, y, z] = sorted;
  std::uint8_t& pending = pending_[qrm_triple_rank(x, y, z)];
  unsigned changed = pending;
  // Composition never restricts the triple it reads pq:r from (d is a fourth landmark), so nothing
  // below queues this triple again: what the closure changes is composed in this visit.
  pending = 0;
  if (!close_triple(sorted, changed)) return false;
  // Relation w is read by two orders, pq:r and qp:r = I(pq:r).
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
    for (const Triple& t : queue_) pending_[qrm_triple_rank(t[0], t[1], t[2])] = 0;
    // Newest first, so a relation changed twice ends at its value before the measurement.
    for (std::size_t e = journal_.size(); e-- > 0;) {
      const auto& [p, q, r] = journal_[e].order;
      write(p, q, r, journal_[e].before);
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
