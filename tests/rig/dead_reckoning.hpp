#pragma once
// The simplest navigation system there is, for tests of the rig: a dead-reckoning baseline that
// moves the arm straight from the start's surveyed position to the goal's and claims the goal under
// the tool without looking. Its success hangs on the survey and the arm's errors alone. Its
// options make systems that differ from it in known ways.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "rig/navigation_system.hpp"

namespace neopipe::test {

namespace rig = neopipe::rig;

struct DeadReckoningOptions {
  double reach = 1e9;                  ///< pairs farther apart are unreachable
  bool gives_up_on_odd_goals = false;  ///< stops lost before moving whenever the goal's id is odd
  bool l_shaped = false;               ///< moves along x first, then along y
};

class DeadReckoning final : public rig::NavigationSystem {
 public:
  explicit DeadReckoning(std::vector<Eigen::Vector2d> survey, const DeadReckoningOptions& options = {})
      : survey_(std::move(survey)), options_(options) {}

  [[nodiscard]] std::string name() const override { return "dead-reckoning"; }
  [[nodiscard]] rig::CameraRequest camera() const override { return {64, 20}; }
  [[nodiscard]] std::unique_ptr<rig::Plan> plan(std::uint32_t from, std::uint32_t to) const override {
    if ((survey_.at(to) - survey_.at(from)).norm() > options_.reach) throw rig::UnreachableGoal("too far");
    auto p = std::make_unique<rig::Plan>();
    p->start = from;
    p->goal = to;
    p->landmarks = {from, to};
    p->planned_distance = (survey_[to] - survey_[from]).norm();
    return p;
  }
  rig::Travel travel(const rig::Plan& plan, rig::Equipment& equipment, rig::Witness& witness) const override {
    witness.landmark_claimed(0, Eigen::Vector2d::Zero());
    if (options_.gives_up_on_odd_goals && plan.goal % 2 == 1) {
      rig::Travel t;
      t.ending = rig::Ending::lost;
      t.reason = "gives up on odd goals";
      return t;
    }
    const Eigen::Vector2d d = survey_[plan.goal] - survey_[plan.start];
    if (options_.l_shaped) {
      (void)equipment.arm.move_relative(d.x(), 0, 0);
      (void)equipment.arm.move_relative(0, d.y(), 0);
    } else {
      (void)equipment.arm.move_relative(d.x(), d.y(), 0);
    }
    witness.landmark_claimed(1, Eigen::Vector2d::Zero());
    return {};
  }

 private:
  std::vector<Eigen::Vector2d> survey_;
  DeadReckoningOptions options_;
};

}  // namespace neopipe::test
