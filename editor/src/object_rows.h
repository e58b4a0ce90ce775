// The editor's object list and its overlays, from one frame's metrics: per object its K, Q,
// I, the paper's A, P, D, V, C, R, S, and per item (shadows, reflections, refractions)
// whether it is traced, its value, its predicted and its measured milliseconds.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "raybudget/scene.h"
#include "raybudget/settings.h"

namespace raybudget::editor {

inline constexpr const char* kItemNames[3] = {"shadows", "reflections", "refractions"};

struct ObjectRow {
  uint32_t id = 0;
  std::string name;
  float K = 0, Q = 0, I = 0;  // what the selection uses (defaults filled in)
  ObjectMetrics metrics;
  bool selectedLastFrame = false;  // S
  // `benefit`: the learned cost per pixel x the item's pixels x the cost model's ms per unit
  // (its prior until learned; 0: no cost learned for the item)
  std::array<double, 3> predictedMs{};
  // The frame's measured trace time shared out by the subgroup clock ticks each item spent
  std::array<double, 3> measuredMs{};
  double predictedTotal() const { return predictedMs[0] + predictedMs[1] + predictedMs[2]; }
  double measuredTotal() const { return measuredMs[0] + measuredMs[1] + measuredMs[2]; }
};

// `params[i]`: object i's K, Q, I as the core reports them (all filled in); `previous`: the
// last frame's metrics (S), empty on the first; the render size gives the prior time scale.
std::vector<ObjectRow> buildRows(const Scene& scene, const std::vector<RayBudgetParams>& params, const std::vector<ObjectMetrics>& metrics,
                                 const std::vector<ObjectMetrics>& previous, const CostModel& costModel, const FrameTiming& timing, uint32_t renderWidth,
                                 uint32_t renderHeight);

enum class Column { Name, K, Q, I, A, P, D, V, C, R, S, Items, Value, PredictedMs, MeasuredMs, Count };
const char* columnName(Column column);
// Rows whose name contains `filter` (case-insensitive), sorted by `column`.
std::vector<const ObjectRow*> visibleRows(const std::vector<ObjectRow>& rows, const std::string& filter, Column column, bool ascending);

// The object list as CSV (a header, then a line per object), for `dump` and the tests.
std::string rowsCsv(const std::vector<ObjectRow>& rows);

// The object list's items column: S, R, T for shadows, reflections, refractions traced on
// the whole object, the lower-case letter for `benefit`'s partial item (traced on a share of
// its tiles), '-' for an item not traced.
std::string itemsText(const ObjectMetrics& m);

// Traced: per pixel, the effects traced there (the core's traced mask: shadows only where
// the classifier found the shadow map uncertain); the others tint whole objects.
enum class Overlay { None, Items, Cost, Benefit, Ids, Traced };
const char* overlayName(Overlay overlay);
Overlay parseOverlay(const std::string& name);  // throws Error naming the choices
// Per object ID the overlay's colour and blend weight: the traced items' effect colours (a
// partial item's weight scaled by its share of tiles, where it is the object's only one),
// a heat ramp of the predicted cost or the measured benefit (each relative to the frame's
// largest), or a colour per object ID.
std::vector<glm::vec4> overlayTints(Overlay overlay, const std::vector<ObjectRow>& rows);
glm::vec3 effectColour(uint32_t itemBits);

}  // namespace raybudget::editor
