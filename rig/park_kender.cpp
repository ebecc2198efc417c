#include "rig/park_kender.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <utility>

namespace neopipe::rig {
namespace {

namespace mm = nav::mapmaker;
namespace nv = nav::navigator;
using Eigen::Vector2d;

Ending ending_of(nv::Ending e) {
  switch (e) {
    case nv::Ending::arrived:
      return Ending::arrived;
    case nv::Ending::lost:
      return Ending::lost;
    case nv::Ending::unrecoverable:
      return Ending::unrecoverable;
  }
  return Ending::lost;
}

// Passes the navigator's "landmark held" to the rig's witness, as an offset from the tool: the
// window is centred on the tool.
class ClaimRelay final : public nv::Observer {
 public:
  ClaimRelay(Witness& witness, double window_side, nv::Observer* next)
      : witness_(witness), half_(window_side / 2), next_(next) {}

  void landmark_held(std::size_t entry, const Vector2d& window_position) override {
    witness_.landmark_claimed(entry, window_position - Vector2d(half_, half_));
    if (next_ != nullptr) next_->landmark_held(entry, window_position);
  }
  void frame_seen(const pipeline::io::SourceFrame& frame, const nv::Sighting& sighting) override {
    if (next_ != nullptr) next_->frame_seen(frame, sighting);
  }

 private:
  Witness& witness_;
  double half_;
  nv::Observer* next_;
};

}  // namespace

ParkKenderSystem::ParkKenderSystem(mm::Workspace survey, const mm::MapMakerOptions& options,
                                   mm::CostCriterion criterion, const nv::NavigatorConfig& navigator,
                                   nv::Observer* observer)
    : maker_(std::move(survey), options), criterion_(criterion), navigator_(navigator), observer_(observer) {
  if (std::abs(navigator.window.side - options.window.side) > 1e-9 ||
      std::abs(navigator.window.margin - options.window.margin) > 1e-9) {
    throw std::invalid_argument("the navigator's view window differs from the map-maker's");
  }
}

CameraRequest ParkKenderSystem::camera() const {
  return {navigator_.camera.side_px, navigator_.window.side};
}

std::unique_ptr<Plan> ParkKenderSystem::plan(std::uint32_t from, std::uint32_t to) const {
  auto p = std::make_unique<ParkKenderPlan>();
  try {
    p->route = maker_.plan(from, to, criterion_);
    if (p->route.forecast < min_reliability_ && criterion_ != mm::CostCriterion::reliability) {
      p->route = maker_.plan(from, to, mm::CostCriterion::reliability);
    }
  } catch (const mm::UnreachableGoal& e) {
    throw UnreachableGoal(e.what());
  }
  if (const double r = p->route.forecast; r < min_reliability_) {
    p->refused =
        fmt::format("route {} -> {}: no route is reliable enough (the most reliable is forecast at {:.3f} < {:.3f})",
                    from, to, r, min_reliability_);
  }
  const mm::Route& r = p->route;
  p->start = r.start;
  p->goal = r.goal;
  p->landmarks.push_back(r.start);
  for (const mm::RouteStep& s : r.steps) p->landmarks.push_back(s.step.landmark);
  // The window holds the start at its corner and is centred on the tool; the offset does not
  // depend on where the start is.
  const nav::WindowModel& w = navigator_.window;
  p->start_offset = w.origin(Vector2d::Zero(), r.start_corner) + Vector2d(w.side / 2, w.side / 2);
  // The forecast that the journey reaches its goal, recoveries included.
  p->planned_reliability = r.forecast;
  p->planned_distance = r.distance;
  return p;
}

Travel ParkKenderSystem::travel(const Plan& plan, Equipment& equipment, Witness& witness) const {
  const mm::Route& route = route_of(plan);
  nv::Eye eye(equipment.camera, navigator_);
  ClaimRelay relay(witness, navigator_.window.side, observer_);
  nv::JourneyReport report = nv::follow(route.custom_map, eye, equipment.arm, navigator_, &relay);
  Travel t;
  t.ending = ending_of(report.ending);
  t.reason = report.reason;
  t.recoveries = report.recoveries;
  t.backtracks = report.backtracks;
  t.frames = report.frames;
  t.details = std::move(report);
  return t;
}

const mm::Route& route_of(const Plan& plan) {
  const auto* p = dynamic_cast<const ParkKenderPlan*>(&plan);
  if (p == nullptr) throw std::invalid_argument("not a plan of Park & Kender's system");
  return p->route;
}

const nv::JourneyReport* navigator_report(const Travel& travel) {
  return std::any_cast<nv::JourneyReport>(&travel.details);
}

}  // namespace neopipe::rig
