#include "nav/tour/schemas.hpp"

#include <unordered_set>

namespace neopipe::nav::tour {
namespace {

bool same_schema(const Schema& a, const Schema& b) {
  const bool actions =
      a.action.has_value() == b.action.has_value() && (!a.action.has_value() || same_action(*a.action, *b.action));
  return a.goal == b.goal && a.situation == b.situation && actions && a.result == b.result;
}

}  // namespace

void ProceduralMap::add(const Schema& schema) {
  for (Stored& s : schemas_) {
    if (same_schema(s.schema, schema)) {
      ++s.count;
      return;
    }
  }
  schemas_.push_back({schema, 1});
}

void ProceduralMap::add_route(const std::vector<ViewId>& views, const std::vector<Action>& actions) {
  if (views.empty()) return;
  const ViewId goal = views.back();
  for (std::size_t i = 0; i < actions.size() && i + 1 < views.size(); ++i) {
    add({goal, views[i], actions[i], views[i + 1]});
  }
}

template <class Pred>
const Schema* ProceduralMap::most_common(Pred pred) const {
  const Schema* best = nullptr;
  int best_count = 0;
  for (const Stored& s : schemas_) {
    if (pred(s.schema) && s.count > best_count) {
      best = &s.schema;
      best_count = s.count;
    }
  }
  return best;
}

std::optional<std::pair<Action, ViewId>> ProceduralMap::follow_and_describe(ViewId goal, ViewId view) const {
  const Schema* s = most_common([&](const Schema& x) {
    return x.goal == goal && x.situation == view && x.action.has_value() && x.result.has_value();
  });
  if (s == nullptr) return std::nullopt;
  return std::make_pair(*s->action, *s->result);
}

std::optional<Action> ProceduralMap::follow(ViewId goal, ViewId view) const {
  const Schema* s =
      most_common([&](const Schema& x) { return x.goal == goal && x.situation == view && x.action.has_value(); });
  if (s == nullptr) return std::nullopt;
  return s->action;
}

std::optional<ViewId> ProceduralMap::predict(ViewId view, const Action& action) const {
  const Schema* s = most_common([&](const Schema& x) {
    return x.situation == view && x.action.has_value() && same_action(*x.action, action) && x.result.has_value();
  });
  if (s == nullptr) return std::nullopt;
  return s->result;
}

bool ProceduralMap::known(ViewId view) const {
  for (const Stored& s : schemas_) {
    if (s.schema.situation == view || s.schema.result == view) return true;
  }
  return false;
}

std::vector<RouteStep> ProceduralMap::describe(ViewId goal, ViewId view, std::size_t max_steps) const {
  std::vector<RouteStep> steps;
  std::unordered_set<ViewId> seen{view};
  ViewId at = view;
  while (at != goal && steps.size() < max_steps) {
    const auto next = follow_and_describe(goal, at);
    if (!next || !seen.insert(next->second).second) return {};
    steps.push_back({at, next->first, next->second});
    at = next->second;
  }
  return at == goal ? steps : std::vector<RouteStep>{};
}

}  // namespace neopipe::nav::tour
