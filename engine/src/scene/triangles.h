// Triangle-list clean-up shared by the glTF loader and the SceneBuilder: zero-area triangles
// dropped, and area-weighted vertex normals for meshes without any; and whether triangles
// close a shell.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace raybudget {

// No area at float precision, whatever the triangle's scale.
bool zeroAreaTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);
// `triangles` without its zero-area ones; `dropped` counts them.
std::vector<uint32_t> dropZeroAreaTriangles(std::span<const glm::vec3> positions, std::span<const uint32_t> triangles, size_t& dropped);
// Per vertex, the unnormalised sum of its triangles' area-weighted normals.
std::vector<glm::vec3> areaWeightedNormals(std::span<const glm::vec3> positions, std::span<const uint32_t> triangles);
// Whether the triangles (some) close a shell: with vertices welded by equal position (meshes
// split them at UV and normal seams), every edge of a triangle with area is shared by an even
// number of them, where a sheet's border edges have one.
bool closedSurface(std::span<const glm::vec3> positions, std::span<const uint32_t> triangles);

}  // namespace raybudget
