// closedSurface: whether triangles close a shell, with vertices welded by position (the
// raster fallback tints glass once more for the far wall of a closed thin shell).
#include <gtest/gtest.h>

#include "scene/triangles.h"
#include "support/procedural.h"

namespace raybudget {
namespace {

std::vector<glm::vec3> positions(const Mesh& m) {
  std::vector<glm::vec3> p;
  for (const Vertex& v : m.vertices) p.push_back(v.position);
  return p;
}

// A cube whose six faces have their own four vertices each, as a mesh split at UV seams has.
void splitCube(std::vector<glm::vec3>& p, std::vector<uint32_t>& idx, int faces) {
  const glm::vec3 corner[8] = {{-1, -1, -1}, {1, -1, -1}, {-1, 1, -1}, {1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {-1, 1, 1}, {1, 1, 1}};
  const int quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  for (int f = 0; f < faces; ++f) {
    const uint32_t base = uint32_t(p.size());
    for (int c : quads[f]) p.push_back(corner[c]);
    idx.insert(idx.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
}

TEST(ClosedSurface, ACubeSplitAtEveryFaceIsClosed) {
  std::vector<glm::vec3> p;
  std::vector<uint32_t> idx;
  splitCube(p, idx, 6);
  EXPECT_TRUE(closedSurface(p, idx));
}

TEST(ClosedSurface, ABoxWithoutItsLidIsOpen) {
  std::vector<glm::vec3> p;
  std::vector<uint32_t> idx;
  splitCube(p, idx, 5);
  EXPECT_FALSE(closedSurface(p, idx));
}

TEST(ClosedSurface, ASheetIsOpenAndNothingIsNotClosed) {
  const Mesh sheet = test::quad(1.0f);
  EXPECT_FALSE(closedSurface(positions(sheet), sheet.indices));
  EXPECT_FALSE(closedSurface(positions(sheet), std::vector<uint32_t>{}));
}

TEST(ClosedSurface, ZeroAreaTrianglesDoNotOpenAShell) {
  Mesh ball = test::subdividedCube(4);
  for (Vertex& v : ball.vertices) v.position = glm::normalize(v.position);
  std::vector<uint32_t> idx = ball.indices;
  ASSERT_TRUE(closedSurface(positions(ball), idx));
  idx.insert(idx.end(), {idx[0], idx[1], idx[0]});  // a degenerate triangle on an edge of the shell
  EXPECT_TRUE(closedSurface(positions(ball), idx));
  idx.resize(idx.size() - 6);  // and without a real one: a hole
  EXPECT_FALSE(closedSurface(positions(ball), idx));
}

}  // namespace
}  // namespace raybudget
