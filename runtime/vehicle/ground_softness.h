#pragma once
// GroundSoftness: how far a tyre sinks into the ground under a point, for
// the rolling drag of soft ground (mud, sand, grass). Softness s is
// unitless: 0 hard (asphalt, rock, ice, any body unless told otherwise),
// 0.4 grass, 0.7 mud; a tyre adds tyre.soft_ground_drag * s to its rolling
// resistance coefficient (vehicle_system.cpp, 3.). It is a property of the
// surface of its own, not inferred from friction: ice is slippery but hard.
//
// The world's height field may also implement this interface (the app's
// terrain does, from the terrain's softness layer); VehicleSystem asks the
// height field for it with a dynamic_cast once per substep, so physics'
// HeightField interface stays as it is. A height field without it is hard.
#include "core/math.h"

namespace tumble::vehicle {

class GroundSoftness {
 public:
  virtual ~GroundSoftness() = default;
  /// Softness of the ground at (x, z), unitless, >= 0.
  virtual Real softnessAt(Real x_m, Real z_m) const = 0;
};

}  // namespace tumble::vehicle
