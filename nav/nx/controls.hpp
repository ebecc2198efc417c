#pragma once
// NX's control strategies in the dots world (qualnav.md §9, Decision): hill-climbing to a place,
// the local maximum of −(spread of the three smallest ranges), which is a Voronoi vertex of the
// marbles; and following an edge, the locus equidistant from the two nearest marbles, to the next
// place.
//
// Hill-climbing takes Newton steps on the two equations r1 = r2 = r3 linearised with the measured
// gradients (each step at most max_climb_step_mm), so that it ends on the vertex, not merely near
// it. Edge following advances step_mm along the edge and corrects across it toward r1 = r2; it
// hill-climbs once the third range comes within arrival_gap_mm of the nearest while that gap
// shrinks (near the next place, whose triple of marbles is then the nearest three). An edge that leaves the sensor's
// reach (fewer than two marbles in view) or runs longer than max_edge_mm is open (the open world's edges run to
// infinity); one that passes within clearance_mm of a marble, or hits the arm's limit, is blocked.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "nav/nx/robot.hpp"

namespace neopipe::nav::nx {

enum class ClimbEnding { place, too_few_marbles, too_close, no_convergence };

struct Climb {
  ClimbEnding ending = ClimbEnding::no_convergence;
  double spread = 0;  ///< of the three smallest ranges where it stopped, mm
  int steps = 0;
  Eigen::Vector2d moved = Eigen::Vector2d::Zero();  ///< net move, tool frame
};

/// Climbs to the place of the neighbourhood the robot is in.
Climb climb_to_place(Robot& robot);

/// A place as NX describes it where it stands: the mean of its three ranges, the compass headings of
/// its edges (slots, one per pair of the three marbles) and of the three marbles.
struct PlaceView {
  double range = 0;
  std::vector<double> slots;            ///< compass headings of the edges, degrees in (−180, 180]
  std::vector<double> marble_bearings;  ///< compass bearings of the three nearest marbles
  std::vector<double> marble_ranges;
};

/// nullopt when fewer than three marbles with gradients are in view. Re-reads the compass first.
std::optional<PlaceView> describe_place(Robot& robot, int reads = 0);

enum class EdgeEnding { arrived, open, blocked };

struct EdgeRun {
  EdgeEnding ending = EdgeEnding::open;
  double length = 0;                   ///< mm advanced along the edge
  double dtheta_deg = 0;               ///< net change of the direction of travel, compass degrees
  double arrival_heading_deg = 0;      ///< direction of travel at the end, compass degrees
  std::vector<Eigen::Vector2d> moves;  ///< every move made (tool frame), the final climb's included
  Eigen::Vector2d displacement = Eigen::Vector2d::Zero();
};

/// Follows the edge that leaves the current place at compass heading `heading_deg`.
EdgeRun follow_edge(Robot& robot, double heading_deg);

/// Undoes a run's moves (a return by dead reckoning), then hill-climbs at the place it left.
Climb retrace(Robot& robot, const EdgeRun& run);

/// Whether two compass headings agree within `tolerance_deg`.
bool headings_agree(double a_deg, double b_deg, double tolerance_deg);

/// The slot of `view` whose heading is nearest `heading_deg`, and how far it is (degrees).
std::pair<int, double> nearest_slot(const PlaceView& view, double heading_deg);

}  // namespace neopipe::nav::nx
