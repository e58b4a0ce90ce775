#pragma once
// The UI's indices in the order llvmpipe rasterises fastest (editor/src/ui_renderer.h).

#include <cstddef>
#include <cstdint>
#include <vector>

namespace raybudget::editor {

// Appends a draw command's `count` indices (triangles) to `out`, with every quad as Dear
// ImGui emits one ((a, b, c), (a, c, d): a glyph or a rectangle) starting at a multiple of
// 6 indices from where the command starts in `out`, a degenerate triangle (v, v, v) put
// before it where needed and at the end, so the command's share of `out` is a multiple of
// 6. llvmpipe rasterises two triangles that form a rectangle as one, cheaper than two
// triangles, only when it meets them as such an aligned pair in a draw whose index count is
// a multiple of 6. Nothing is reordered, so the blending is as ImGui drew it.
template <typename Index>
void appendPairedQuads(const Index* idx, uint32_t count, std::vector<Index>& out) {
  const size_t start = out.size();
  const auto degenerate = [&out](Index v) { out.insert(out.end(), {v, v, v}); };
  for (uint32_t t = 0; t + 3 <= count;) {
    const bool quad = t + 6 <= count && idx[t] == idx[t + 3] && idx[t + 2] == idx[t + 4];
    const uint32_t n = quad ? 6 : 3;
    if (quad && (out.size() - start) % 6 != 0) degenerate(idx[t]);
    out.insert(out.end(), idx + t, idx + t + n);
    t += n;
  }
  if ((out.size() - start) % 6 != 0) degenerate(out.back());
}

}  // namespace raybudget::editor
