// Closed and flat meshes built in code for the tracer's robustness tests, and a one-object
// Scene around a mesh (no file involved).
#pragma once
#include "raybudget/scene.h"

namespace raybudget::test {

Mesh icosphere(int subdivisions);        // unit radius, shared vertices: closed and watertight
Mesh subdividedCube(int cellsPerEdge);   // [-1, 1]^3, shared vertices along every edge
Mesh quad(float halfSize);               // the XZ plane, facing +y, two triangles
Mesh texturedQuad(float halfSize);       // quad() with u along +x and v along +z, 0..1 over it
// perAxis^3 small triangles spread through [-1, 1]^3 and `large` triangles cutting through
// the whole cube: triangles of very different sizes whose boxes no object split can
// separate, the mesh spatial splits are for.
Mesh smallAndLargeTriangles(int perAxis, int large);

// A scene holding `mesh` once, placed by `transform`, with a diffuse grey material.
Scene sceneWithMesh(Mesh mesh, const glm::mat4& transform = glm::mat4(1.0f));

// A white metal of `roughness` (0: a mirror).
Material mirror(float roughness = 0.0f);
// A double-sided black emitter of `radiance`: what mirrors and glass show in tests.
Material emitter(const glm::vec3& radiance);
// Clear glass with a volume (thickness 1, IOR 1.5) that halves red over one unit of path.
Material tintedGlass();

// Adds a 2x2 linear normal map holding the tangent-space normal t (|t| = 1) everywhere, and
// returns its texture index.
int addFlatNormalMap(Scene& scene, glm::vec3 t);

// Adds `mesh` with its own `material` as a new object and grows the scene bounds.
void addObject(Scene& scene, Mesh mesh, const glm::mat4& transform, const Material& material);

// Two coplanar floor mirrors (objects 0 and 1) touching at x = 0, 2 units wide, and two
// emitters high up: seen from above, the left mirror reflects the red one, the right mirror
// the green one (reflections keep the view ray's x sign). Coplanar with one normal, so depth
// and normal cannot tell their pixels apart: only the object ID.
Scene twoMirrors();

}  // namespace raybudget::test
