// Geometry of a track's belt loop in the plane of the track (chassis x, z): the loop runs around
// the sprocket, the road wheels (front to rear) and the idler and back over the top to the
// sprocket. Its length is taken as the perimeter of the polygon through the wheel centres (exact
// for equal radii, where the wrap adds the constant 2 pi r; the tangent-length corrections of
// unequal radii change with the geometry only at second order). An elastic belt of stiffness k
// and rest length L0 carries the tension T = k max(0, L - L0); its pull on a wheel centre is the
// virtual work -T dL/dc = T (u_out - u_in), u the unit directions of the loop's spans.
#pragma once

#include "vb/engine/types.h"

namespace vb::vehicles {

constexpr int kMaxBeltWheels = 12;

struct BeltLoop {
  int n = 0;                        // wheel centres in loop order (sprocket, road wheels, idler)
  Vec2 centre[kMaxBeltWheels];      // (x, z) in the chassis frame
};

// Loop length (m) and, per centre, dL/dc (the gradient of the length w.r.t. that centre).
double BeltLength(const BeltLoop& loop, Vec2* gradient);

}  // namespace vb::vehicles
