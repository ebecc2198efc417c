#pragma once
// TOUR's procedural map (seed 002 "Procedural Behaviors", Table 2): sensorimotor schemas
// <goal, situation, action, result>, some parts possibly lost to a busy working memory, and their
// retrieval by completeness:
//   (G, V) -> (A, V')  follow or describe a route (complete schemas)
//   (G, V) -> A        follow a route in the environment (the result was lost)
//   (V, A) -> V'       predict the result of an action (the goal was lost)
//   V -> known         recognise a familiar view
// Several schemas may answer a question (the goal dropped, a situation evokes several); the most
// frequently stored one wins, the earliest on ties (deterministic).

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "nav/tour/actions.hpp"

namespace neopipe::nav::tour {

struct Schema {
  std::optional<ViewId> goal;
  ViewId situation = 0;
  std::optional<Action> action;
  std::optional<ViewId> result;
};

/// One step of a described route.
struct RouteStep {
  ViewId situation = 0;
  Action action;
  ViewId result = 0;
};

class ProceduralMap {
 public:
  void add(const Schema& schema);
  /// The complete route description {<goal, V_i, A_i, V_i+1>} of an experience V0 A0 V1 ... Vn.
  void add_route(const std::vector<ViewId>& views, const std::vector<Action>& actions);

  /// (G, V) -> (A, V'): needs a schema with goal, action and result.
  [[nodiscard]] std::optional<std::pair<Action, ViewId>> follow_and_describe(ViewId goal, ViewId view) const;
  /// (G, V) -> A: a schema with goal and action (its result may be missing).
  [[nodiscard]] std::optional<Action> follow(ViewId goal, ViewId view) const;
  /// (V, A) -> V': any schema with that situation, that action and a result (goal ignored).
  [[nodiscard]] std::optional<ViewId> predict(ViewId view, const Action& action) const;
  /// V -> known: some schema has it as situation or result.
  [[nodiscard]] bool known(ViewId view) const;
  /// The route from `view` to `goal` told from memory alone, following result pointers; empty when
  /// some step lacks its result or action (then the route can only be followed in the world).
  [[nodiscard]] std::vector<RouteStep> describe(ViewId goal, ViewId view, std::size_t max_steps = 1000) const;

  [[nodiscard]] std::size_t size() const { return schemas_.size(); }

 private:
  struct Stored {
    Schema schema;
    int count = 0;
  };
  template <class Pred>
  [[nodiscard]] const Schema* most_common(Pred pred) const;

  std::vector<Stored> schemas_;
};

}  // namespace neopipe::nav::tour
