// The editor's camera moves, on raybudget::Camera: orbit around the target, dolly towards
// it, fly (position and target move together) and look around from the position. Pitch
// stays 1 degree short of the poles so the view never degenerates.
#pragma once
#include "raybudget/camera.h"

namespace raybudget::editor {

// Turns the position around the target: yaw about the up axis, pitch towards it (radians).
Camera orbit(const Camera& camera, float yaw, float pitch);
// Moves the position towards the target by `factor` of their distance (< 0 moves away);
// never closer than 1% of the distance.
Camera dolly(const Camera& camera, float factor);
// Moves position and target along the view's forward, right and up axes (world units).
Camera fly(const Camera& camera, float forward, float right, float up);
// Turns the view about the position: the target moves (radians).
Camera look(const Camera& camera, float yaw, float pitch);

}  // namespace raybudget::editor
