#include "object_rows.h"

#include <algorithm>
#include <cctype>
#include <sstream>

#include "raybudget/error.h"

namespace raybudget::editor {
namespace {

std::string lower(std::string s) {
  for (char& ch : s) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

double value(const ObjectRow& r) { return double(r.metrics.itemBenefit[0]) + r.metrics.itemBenefit[1] + r.metrics.itemBenefit[2]; }

double sortKey(const ObjectRow& r, Column c) {
  const ObjectMetrics& m = r.metrics;
  switch (c) {
    case Column::K: return r.K;
    case Column::Q: return r.Q;
    case Column::I: return r.I;
    case Column::A: return m.A;
    case Column::P: return m.P;
    case Column::D: return m.D;
    case Column::V: return m.V;
    case Column::C: return m.C;
    case Column::R: return m.R;
    case Column::S: return r.selectedLastFrame ? 1 : 0;
    case Column::Items: return m.selectedItems;
    case Column::Value: return value(r);
    case Column::PredictedMs: return r.predictedTotal();
    case Column::MeasuredMs: return r.measuredTotal();
    default: return r.id;
  }
}

glm::vec3 heat(float t) {  // blue, cyan, yellow, red
  t = std::clamp(t, 0.0f, 1.0f);
  if (t < 0.33f) return glm::mix(glm::vec3(0.1f, 0.2f, 1.0f), glm::vec3(0.0f, 0.9f, 0.9f), t / 0.33f);
  if (t < 0.66f) return glm::mix(glm::vec3(0.0f, 0.9f, 0.9f), glm::vec3(1.0f, 0.9f, 0.0f), (t - 0.33f) / 0.33f);
  return glm::mix(glm::vec3(1.0f, 0.9f, 0.0f), glm::vec3(1.0f, 0.1f, 0.05f), (t - 0.66f) / 0.34f);
}

std::vector<glm::vec4> heatTints(const std::vector<ObjectRow>& rows, double (*measure)(const ObjectRow&)) {
  double most = 0.0;
  for (const ObjectRow& r : rows) most = std::max(most, measure(r));
  std::vector<glm::vec4> tints(rows.size(), glm::vec4(0.0f));
  if (most <= 0.0) return tints;
  for (size_t i = 0; i < rows.size(); ++i) {
    const double v = measure(rows[i]);
    if (v > 0.0) tints[i] = glm::vec4(heat(float(v / most)), 0.6f);
  }
  return tints;
}

// The cost heat map: the predicted milliseconds where the cost model has them, else the paper's C.
double predictedCost(const ObjectRow& r) { return r.predictedTotal() > 0.0 ? r.predictedTotal() : r.metrics.C; }
// The benefit heat map: the learned benefit per pixel where `benefit` learned one, else the
// display error the traced items removed per pixel this frame.
double measuredBenefit(const ObjectRow& r) {
  if (value(r) > 0.0) return value(r);
  const ObjectMetrics& m = r.metrics;
  return m.pixels ? (double(m.itemError[0]) + m.itemError[1] + m.itemError[2]) / m.pixels : 0.0;
}

}  // namespace

std::vector<ObjectRow> buildRows(const Scene& scene, const std::vector<RayBudgetParams>& params, const std::vector<ObjectMetrics>& metrics,
                                 const std::vector<ObjectMetrics>& previous, const CostModel& costModel, const FrameTiming& timing, uint32_t renderWidth,
                                 uint32_t renderHeight) {
  std::vector<ObjectRow> rows(scene.objects.size());
  const double msPerWork = costModel.msPerWorkUnit > 0.0 ? costModel.msPerWorkUnit : priorMsPerWorkUnit(renderWidth, renderHeight);
  uint64_t ticks = 0;
  for (const ObjectMetrics& m : metrics)
    for (uint64_t t : m.itemTicks) ticks += t;
  for (size_t i = 0; i < rows.size(); ++i) {
    ObjectRow& r = rows[i];
    r.id = uint32_t(i);
    r.name = scene.objects[i].name;
    if (i < params.size()) {
      r.K = params[i].importanceK.value_or(0.0f);
      r.Q = params[i].raysQ.value_or(0.0f);
      r.I = params[i].hysteresisI.value_or(0.0f);
    }
    if (i < metrics.size()) r.metrics = metrics[i];
    r.selectedLastFrame = i < previous.size() && previous[i].selected;
    const ObjectMetrics& m = r.metrics;
    const std::array<uint32_t, 3> itemPixels{m.pixels, m.reflectionPixels, m.refractionPixels};
    for (int e = 0; e < 3; ++e) {
      r.predictedMs[e] = double(m.itemCostPerPixel[e]) * itemPixels[e] * msPerWork;
      r.measuredMs[e] = ticks ? timing.measuredTraceMs * double(m.itemTicks[e]) / double(ticks) : 0.0;
    }
  }
  return rows;
}

const char* columnName(Column column) {
  static const char* names[] = {"name", "K", "Q", "I", "A", "P", "D", "V", "C", "R", "S", "items", "value", "pred ms", "meas ms"};
  return names[size_t(column)];
}

std::vector<const ObjectRow*> visibleRows(const std::vector<ObjectRow>& rows, const std::string& filter, Column column, bool ascending) {
  std::vector<const ObjectRow*> out;
  const std::string want = lower(filter);
  for (const ObjectRow& r : rows)
    if (want.empty() || lower(r.name).find(want) != std::string::npos) out.push_back(&r);
  std::stable_sort(out.begin(), out.end(), [&](const ObjectRow* a, const ObjectRow* b) {
    if (column == Column::Name) return ascending ? a->name < b->name : a->name > b->name;
    const double ka = sortKey(*a, column), kb = sortKey(*b, column);
    return ascending ? ka < kb : ka > kb;
  });
  return out;
}

std::string rowsCsv(const std::vector<ObjectRow>& rows) {
  std::ostringstream s;
  s << "id,name,K,Q,I,pixels,A,P,D,V,C,R,S,candidate,selected";
  for (const char* item : kItemNames) s << ',' << item << "_traced," << item << "_value," << item << "_predicted_ms," << item << "_measured_ms";
  s << '\n';
  for (const ObjectRow& r : rows) {
    const ObjectMetrics& m = r.metrics;
    s << r.id << ',' << r.name << ',' << r.K << ',' << r.Q << ',' << r.I << ',' << m.pixels << ',' << m.A << ',' << m.P << ',' << m.D << ','
      << m.V << ',' << m.C << ',' << m.R << ',' << int(r.selectedLastFrame) << ',' << int(m.candidate) << ',' << int(m.selected);
    for (int e = 0; e < 3; ++e)
      s << ',' << int((m.selectedItems >> e) & 1u) << ',' << m.itemBenefit[e] << ',' << r.predictedMs[e] << ',' << r.measuredMs[e];
    s << '\n';
  }
  return s.str();
}

const char* overlayName(Overlay overlay) {
  static const char* names[] = {"none", "items", "cost", "benefit", "ids", "traced"};
  return names[size_t(overlay)];
}

Overlay parseOverlay(const std::string& name) {
  for (Overlay o : {Overlay::None, Overlay::Items, Overlay::Cost, Overlay::Benefit, Overlay::Ids, Overlay::Traced})
    if (name == overlayName(o)) return o;
  throw Error("overlay must be none, items, cost, benefit, ids or traced, got '" + name + "'");
}

std::string itemsText(const ObjectMetrics& m) {
  std::string s;
  const char letters[3] = {'S', 'R', 'T'};
  for (size_t e = 0; e < 3; ++e) {
    const bool traced = (m.selectedItems >> e) & 1u;
    s += !traced ? '-' : m.itemTileShare[e] < 1.0f ? char(std::tolower(letters[e])) : letters[e];
  }
  return s;
}

glm::vec3 effectColour(uint32_t itemBits) {
  glm::vec3 c(0.0f);
  if (itemBits & 1u) c += glm::vec3(0.25f, 0.45f, 1.0f);  // shadows: blue
  if (itemBits & 2u) c += glm::vec3(1.0f, 0.3f, 0.25f);   // reflections: red
  if (itemBits & 4u) c += glm::vec3(0.3f, 1.0f, 0.4f);    // refractions: green
  return c / std::max(1.0f, std::max(c.r, std::max(c.g, c.b)));
}

std::vector<glm::vec4> overlayTints(Overlay overlay, const std::vector<ObjectRow>& rows) {
  std::vector<glm::vec4> tints(rows.size(), glm::vec4(0.0f));
  switch (overlay) {
    case Overlay::None:
    case Overlay::Traced: break;  // per pixel, in the overlay shader
    case Overlay::Items:
      for (size_t i = 0; i < rows.size(); ++i)
        if (const uint32_t bits = rows[i].metrics.selectedItems & 7u) {
          // The largest share of tiles among its traced items (1 but for a lone partial item).
          float share = 0.0f;
          for (size_t e = 0; e < 3; ++e)
            if ((bits >> e) & 1u) share = std::max(share, rows[i].metrics.itemTileShare[e]);
          tints[i] = glm::vec4(effectColour(bits), 0.5f * share);
        }
      break;
    case Overlay::Cost: return heatTints(rows, predictedCost);
    case Overlay::Benefit: return heatTints(rows, measuredBenefit);
    case Overlay::Ids:
      for (size_t i = 0; i < rows.size(); ++i) {
        uint32_t h = uint32_t(i) * 2654435761u;
        h ^= h >> 15;
        tints[i] = glm::vec4(float(h & 255u) / 255.0f, float((h >> 8) & 255u) / 255.0f, float((h >> 16) & 255u) / 255.0f, 0.85f);
      }
      break;
  }
  return tints;
}

}  // namespace raybudget::editor
