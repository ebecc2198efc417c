#pragma once
// The panoramic sensor's compass as a navigator reads it: the tool's heading with its error.
// Qualnav uses it (qualnav.md §2); the qualitative relational map must not (qrm.md §9), and the rig
// hands it only to a system that asked for the panoramic sensor.

namespace neopipe::nav {

struct CompassReading {
  double heading_deg = 0;  ///< the tool's +x axis, counter-clockwise from the world's +x axis, [0, 360)
  double sigma_deg = 0;    ///< the sd of its error
};

class Compass {
 public:
  virtual ~Compass() = default;
  /// One reading now; each carries a fresh error.
  virtual CompassReading read() = 0;

 protected:
  Compass() = default;
  Compass(const Compass&) = default;
  Compass& operator=(const Compass&) = default;
};

}  // namespace neopipe::nav
