// glTF 2.0 -> Scene: node hierarchy, instancing (nodes and EXT_mesh_gpu_instancing),
// materials (gltf_materials.h), KHR_lights_punctual, cameras and extras.raybudget. Every
// reference is range-checked.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string_view>
#include <map>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "raybudget/error.h"
#include "raybudget/scene.h"
#include "scene/accessor_reader.h"
#include "scene/bounds.h"
#include "scene/gltf_materials.h"
#include "scene/gltf_rules.h"
#include "scene/gltf_values.h"
#include "scene/mesh_builder.h"

namespace raybudget {
namespace {

using gltf::extension;
using gltf::finiteOr;

// tinygltf's reader of external buffers and images, refusing what is not a regular file: its
// own takes the size from seeking to the end, which for a folder reads as 2^63 - 1 on ext4
// (a URI that decodes to the scene's folder asked for that much memory).
bool readRegularFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  std::error_code ec;
  const bool regular = std::filesystem::is_regular_file(path, ec);
  if (regular) {
    const uintmax_t size = std::filesystem::file_size(path, ec);
    std::ifstream in(path, std::ios::binary);
    if (!ec && in) {
      out->resize(size_t(size));
      if (in.read(reinterpret_cast<char*>(out->data()), std::streamsize(size))) return true;
    }
  }
  if (err) *err += (regular ? "cannot read " : "not a regular file: ") + path + "\n";
  return false;
}

// Translations or scales beyond this are treated as a broken file, not a big world: float
// positions there have centimetre-scale spacing and every later pass would misbehave.
constexpr float kMaxTransformElement = 1.0e7f;

// The node's transform: its matrix (which must be affine) or its TRS, the rotation
// normalized with a warning where it is not a unit quaternion (NODE_ROTATION_NON_UNIT).
glm::mat4 localTransform(const tinygltf::Node& n, const std::string& at, std::vector<std::string>& warnings) {
  glm::mat4 m(1.0f);
  if (n.matrix.size() == 16) {
    for (int k = 0; k < 16; ++k) glm::value_ptr(m)[k] = float(n.matrix[size_t(k)]);
    if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f)
      throw Error(at + ": matrix is projective (its last row is not 0, 0, 0, 1); glTF node matrices must decompose into "
                       "translation, rotation and scale (NODE_MATRIX_NON_TRS)");
  } else {
    glm::vec3 t(0.0f), s(1.0f);
    glm::quat r(1.0f, 0.0f, 0.0f, 0.0f);
    if (n.translation.size() == 3) t = glm::vec3(float(n.translation[0]), float(n.translation[1]), float(n.translation[2]));
    if (n.scale.size() == 3) s = glm::vec3(float(n.scale[0]), float(n.scale[1]), float(n.scale[2]));
    if (n.rotation.size() == 4) {
      r = glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2]));
      const float length = glm::length(r);
      if (!std::isfinite(length) || length == 0.0f) throw Error(at + ": rotation is not a finite, non-zero quaternion");
      if (std::fabs(length - 1.0f) > 1e-5f) {
        warnings.push_back(at + ": rotation quaternion has length " + std::to_string(length) + ", normalized (NODE_ROTATION_NON_UNIT)");
        r /= length;
      }
    }
    m = glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(r) * glm::scale(glm::mat4(1.0f), s);
  }
  for (int k = 0; k < 16; ++k) {
    const float e = glm::value_ptr(m)[k];
    if (!std::isfinite(e)) throw Error(at + ": transform has a non-finite element");
    if (std::fabs(e) > kMaxTransformElement)
      throw Error(at + ": transform element " + std::to_string(e) + " exceeds " + std::to_string(kMaxTransformElement) + " (absurd transform)");
  }
  return m;
}

RayBudgetParams readParams(const tinygltf::Value& extras, const std::string& at) {
  RayBudgetParams p;
  if (!extras.IsObject() || !extras.Has("raybudget")) return p;
  const tinygltf::Value& rb = extras.Get("raybudget");
  if (!rb.IsObject()) throw Error(at + ": extras.raybudget must be an object with K, Q, I");
  auto read = [&](const char* key, std::optional<float>& out) {
    if (!rb.Has(key)) return;
    const tinygltf::Value& v = rb.Get(key);
    if (!v.IsNumber()) throw Error(at + ": extras.raybudget." + key + " must be a number");
    const double d = v.GetNumberAsDouble();
    out = std::isfinite(d) && std::fabs(d) < 1e30 ? float(d) : std::numeric_limits<float>::infinity();
  };
  read("K", p.importanceK);
  read("Q", p.raysQ);
  read("I", p.hysteresisI);
  validateRayBudgetParams(p, at + ": extras.raybudget");
  return p;
}

void addObject(Scene& scene, uint32_t mesh, int node, const glm::mat4& world, const std::string& name, const RayBudgetParams& params,
               const std::string& at) {
  const float det = glm::determinant(glm::mat3(world));
  if (!std::isfinite(det)) throw Error(at + ": world transform is not finite");
  if (std::fabs(det) < 1e-30f) {
    scene.warnings.push_back(at + ": zero-scale transform, object skipped (invisible)");
    return;
  }
  const Mesh& m = scene.meshes[mesh];
  if (m.indices.empty()) return;
  Object o;
  o.id = uint32_t(scene.objects.size());
  o.name = name;
  o.mesh = mesh;
  o.gltfNode = node;
  o.transform = world;
  o.params = params;
  worldBounds(m, world, o.boundsMin, o.boundsMax);
  if (!finiteBounds(o.boundsMin, o.boundsMax))
    throw Error(at + ": the mesh placed by its transforms reaches beyond float range (world bounds are not finite)");
  scene.stats.triangles += m.indices.size() / 3;
  scene.objects.push_back(std::move(o));
}

// EXT_mesh_gpu_instancing: one object per instance, local TRS after the node's transform.
std::vector<glm::mat4> gpuInstances(const tinygltf::Model& model, const tinygltf::Node& node, const std::string& at) {
  const auto* ext = extension(node.extensions, "EXT_mesh_gpu_instancing");
  if (!ext || !ext->Has("attributes")) return {glm::mat4(1.0f)};
  const tinygltf::Value& attrs = ext->Get("attributes");
  auto attr = [&](const char* key, glm::vec4 fill) {
    std::vector<glm::vec4> v;
    if (attrs.Has(key) && attrs.Get(key).IsInt()) {
      const int index = attrs.Get(key).GetNumberAsInt();
      gltf::checkInstanceAttributeFormat(model, index, key, at + " instancing " + key);
      v = gltf::readVec4(model, index, at + " instancing " + key, fill);
    }
    return v;
  };
  const auto t = attr("TRANSLATION", glm::vec4(0.0f)), r = attr("ROTATION", glm::vec4(0, 0, 0, 1)), s = attr("SCALE", glm::vec4(1.0f));
  const size_t n = std::max(t.size(), std::max(r.size(), s.size()));
  if ((!t.empty() && t.size() != n) || (!r.empty() && r.size() != n) || (!s.empty() && s.size() != n))
    throw Error(at + ": EXT_mesh_gpu_instancing attributes have different counts");
  std::vector<glm::mat4> out;
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3 ti = t.empty() ? glm::vec3(0.0f) : glm::vec3(t[i]);
    const glm::vec3 si = s.empty() ? glm::vec3(1.0f) : glm::vec3(s[i]);
    const glm::quat ri = r.empty() ? glm::quat(1, 0, 0, 0) : glm::quat(r[i].w, r[i].x, r[i].y, r[i].z);
    out.push_back(glm::translate(glm::mat4(1.0f), ti) * glm::mat4_cast(ri) * glm::scale(glm::mat4(1.0f), si));
  }
  return out;
}

// extras.raybudget.reflectionProbe = true: the node's transform maps [-1, 1]^3 to the
// probe's box; probes past kMaxReflectionProbes are dropped with a warning.
void addReflectionProbe(const tinygltf::Node& node, const glm::mat4& world, const std::string& at, Scene& scene) {
  if (!node.extras.IsObject() || !node.extras.Has("raybudget")) return;
  const tinygltf::Value& rb = node.extras.Get("raybudget");
  if (!rb.IsObject() || !rb.Has("reflectionProbe")) return;
  const tinygltf::Value& v = rb.Get("reflectionProbe");
  if (!v.IsBool()) throw Error(at + ": extras.raybudget.reflectionProbe must be true or false");
  if (!v.Get<bool>()) return;
  ReflectionProbe p;
  p.name = node.name.empty() ? at : node.name;
  p.center = glm::vec3(world[3]);
  p.boxMin = glm::vec3(std::numeric_limits<float>::infinity());
  p.boxMax = -p.boxMin;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec4 c((corner & 1) ? 1.0f : -1.0f, (corner & 2) ? 1.0f : -1.0f, (corner & 4) ? 1.0f : -1.0f, 1.0f);
    const glm::vec3 w(world * c);
    p.boxMin = glm::min(p.boxMin, w);
    p.boxMax = glm::max(p.boxMax, w);
  }
  const glm::vec3 extent = p.boxMax - p.boxMin;
  if (!finiteBounds(p.boxMin, p.boxMax) || extent.x <= 0.0f || extent.y <= 0.0f || extent.z <= 0.0f)
    throw Error(at + ": the reflection probe's box (the node's transform of [-1, 1]^3) has no volume or is not finite");
  if (scene.reflectionProbes.size() >= kMaxReflectionProbes) {
    scene.warnings.push_back(at + ": more than " + std::to_string(kMaxReflectionProbes) + " reflection probes, this one is ignored");
    return;
  }
  scene.reflectionProbes.push_back(p);
}

void addLight(const tinygltf::Model& model, const tinygltf::Node& node, const glm::mat4& world, const std::string& at, Scene& scene) {
  const auto* ext = extension(node.extensions, "KHR_lights_punctual");
  if (!ext || !ext->Has("light")) return;
  const int index = ext->Get("light").GetNumberAsInt();
  if (index < 0 || size_t(index) >= model.lights.size()) throw Error(at + " refers to light " + std::to_string(index) + ", which does not exist");
  const tinygltf::Light& gl = model.lights[size_t(index)];
  const std::string lat = at + " light " + std::to_string(index);
  Light l;
  l.name = gl.name;
  if (gl.type == "directional") l.type = LightType::Directional;
  else if (gl.type == "point") l.type = LightType::Point;
  else if (gl.type == "spot") l.type = LightType::Spot;
  else throw Error(lat + " has unknown type '" + gl.type + "'");
  for (int k = 0; k < 3 && k < int(gl.color.size()); ++k) l.color[k] = std::max(finiteOr(gl.color[size_t(k)], lat + " color"), 0.0f);
  l.intensity = finiteOr(gl.intensity, lat + " intensity");
  if (l.intensity < 0.0f) throw Error(lat + " has negative intensity");
  l.range = std::max(finiteOr(gl.range, lat + " range"), 0.0f);
  l.innerConeAngle = glm::clamp(finiteOr(gl.spot.innerConeAngle, lat + " innerConeAngle"), 0.0f, 1.5707963f);
  l.outerConeAngle = glm::clamp(finiteOr(gl.spot.outerConeAngle, lat + " outerConeAngle"), l.innerConeAngle, 1.5707963f);
  l.position = glm::vec3(world[3]);
  const glm::vec3 dir = glm::vec3(world * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
  l.direction = glm::length(dir) > 0.0f ? glm::normalize(dir) : glm::vec3(0.0f, -1.0f, 0.0f);
  scene.lights.push_back(l);
}

void addCamera(const tinygltf::Model& model, const tinygltf::Node& node, const glm::mat4& world, const std::string& at, Scene& scene) {
  if (node.camera < 0 || scene.camera) return;
  if (size_t(node.camera) >= model.cameras.size()) throw Error(at + " refers to camera " + std::to_string(node.camera) + ", which does not exist");
  const tinygltf::Camera& gc = model.cameras[size_t(node.camera)];
  Camera c;
  if (gc.type == "perspective") {
    c.yfov = glm::clamp(finiteOr(gc.perspective.yfov, at + " camera yfov"), 0.01f, 3.0f);
    c.znear = std::max(finiteOr(gc.perspective.znear, at + " camera znear"), 1e-4f);
    c.zfar = gc.perspective.zfar > 0.0 ? finiteOr(gc.perspective.zfar, at + " camera zfar") : 0.0f;  // 0: from bounds later
    if (c.zfar > 0.0f && c.zfar <= c.znear) {
      scene.warnings.push_back(at + ": camera zfar is not beyond znear; zfar taken from the scene's bounds (CAMERA_ZFAR_LEQUAL_ZNEAR)");
      c.zfar = 0.0f;
    }
  } else {
    scene.warnings.push_back(at + ": orthographic camera rendered as a perspective one with the same pose");
  }
  c.position = glm::vec3(world[3]);
  c.target = c.position + glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
  c.up = glm::normalize(glm::vec3(world * glm::vec4(0, 1, 0, 0)));
  scene.camera = c;
}

Scene loadAndRepair(const std::filesystem::path& path) {
  const std::string file = path.string();
  if (!std::filesystem::exists(path)) throw Error(file + ": file not found");
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&tinygltf::FileExists, &tinygltf::ExpandFilePath, &readRegularFile, &tinygltf::WriteWholeFile, nullptr});
  std::string err, warn;
  // Read once: tinygltf parses the bytes, and the index check reads the same JSON.
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
  std::string_view json = bytes;  // the file's JSON text (a GLB's JSON chunk)
  if (binary) {
    // The header's total length must be the file's (tinygltf tolerates a mismatch).
    uint32_t header[4] = {};  // version, length; the first chunk's length and type
    const size_t got = std::min(sizeof(header), bytes.size() - 4);
    std::memcpy(header, bytes.data() + 4, got);
    if (got >= 8 && header[1] != bytes.size())
      throw Error(file + ": the GLB header declares " + std::to_string(header[1]) + " bytes, the file has " + std::to_string(bytes.size()) +
                  " (GLB_LENGTH_MISMATCH)");
    const bool jsonChunk = got == sizeof(header) && header[3] == 0x4E4F534Au && header[2] <= bytes.size() - 20;
    json = jsonChunk ? std::string_view(bytes).substr(20, header[2]) : std::string_view();
  }
  const std::string baseDir = path.parent_path().string();  // where external buffers and images are
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                                       static_cast<unsigned int>(bytes.size()), baseDir)
                         : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()), baseDir);
  if (!ok || !err.empty()) throw Error(file + ": not a valid glTF file: " + (err.empty() ? "parse failed" : err));

  Scene scene;
  gltf::checkJson(json, file, scene.warnings);
  gltf::checkAssetVersion(model, file);
  gltf::checkSharedVertexBufferViews(model, file);
  scene.path = path;
  if (!warn.empty()) scene.warnings.push_back(file + ": " + warn);
  for (const std::string& ext : model.extensionsRequired) {
    static const char* known[] = {"KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume",
                                  "KHR_materials_emissive_strength", "KHR_materials_unlit", "EXT_mesh_gpu_instancing", "KHR_texture_transform",
                                  "KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_specular"};
    if (std::find_if(std::begin(known), std::end(known), [&](const char* k) { return ext == k; }) == std::end(known))
      throw Error(file + ": requires extension " + ext + ", which raybudget does not support");
  }
  gltf::loadImagesAndTextures(model, file, scene);
  gltf::loadMaterials(model, file, scene);

  // Meshes are built once and shared by every node (and instance) that uses them.
  std::map<int, uint32_t> meshOf;
  auto meshFor = [&](int gltfMesh, const std::string& at) {
    if (gltfMesh < 0 || size_t(gltfMesh) >= model.meshes.size()) throw Error(at + " refers to mesh " + std::to_string(gltfMesh) + ", which does not exist");
    auto it = meshOf.find(gltfMesh);
    if (it != meshOf.end()) return it->second;
    scene.meshes.push_back(gltf::buildMesh(model, gltfMesh, file, scene));
    return meshOf[gltfMesh] = uint32_t(scene.meshes.size() - 1);
  };

  // Roots: the default scene's nodes; without scenes, every node that is nobody's child.
  std::vector<int> roots;
  if (!model.scenes.empty()) {
    if (model.defaultScene >= 0 && size_t(model.defaultScene) >= model.scenes.size())
      throw Error(file + ": scene " + std::to_string(model.defaultScene) + " does not exist (the file has " + std::to_string(model.scenes.size()) +
                  ") (UNRESOLVED_REFERENCE)");
    const int s = model.defaultScene >= 0 ? model.defaultScene : 0;
    roots = model.scenes[size_t(s)].nodes;
  } else {
    std::vector<bool> isChild(model.nodes.size(), false);
    for (const auto& n : model.nodes)
      for (int c : n.children)
        if (c >= 0 && size_t(c) < isChild.size()) isChild[size_t(c)] = true;
    for (size_t i = 0; i < model.nodes.size(); ++i)
      if (!isChild[i]) roots.push_back(int(i));
  }

  // Iterative depth-first walk; a node met twice on one path is a cycle (malformed file).
  struct Item { int node; glm::mat4 parent; int depth; };
  std::vector<Item> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, glm::mat4(1.0f), 0});
  size_t visits = 0;
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    const std::string at = file + ": node " + std::to_string(item.node);
    if (item.node < 0 || size_t(item.node) >= model.nodes.size()) throw Error(at + " does not exist");
    if (item.depth > 256 || ++visits > 4 * model.nodes.size() + 16)
      throw Error(at + ": the node hierarchy has a cycle or is deeper than 256 levels");
    const tinygltf::Node& node = model.nodes[size_t(item.node)];
    const glm::mat4 world = item.parent * localTransform(node, at, scene.warnings);
    if (node.mesh >= 0) {
      const uint32_t mesh = meshFor(node.mesh, at);
      const RayBudgetParams params = readParams(node.extras, at);
      const std::vector<glm::mat4> instances = gpuInstances(model, node, at);
      for (size_t i = 0; i < instances.size(); ++i) {
        std::string name = node.name.empty() ? "node" + std::to_string(item.node) : node.name;
        if (instances.size() > 1) name += "#" + std::to_string(i);
        addObject(scene, mesh, item.node, world * instances[i], name, params, at);
      }
    }
    addLight(model, node, world, at, scene);
    addReflectionProbe(node, world, at, scene);
    addCamera(model, node, world, at, scene);
    for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back({*c, world, item.depth + 1});
  }

  if (scene.objects.empty()) throw Error(file + ": the scene has no triangle geometry to render");
  finishScene(scene);
  if (scene.camera && scene.camera->zfar <= 0.0f) {
    const float extent = glm::length(scene.boundsMax - scene.boundsMin);
    scene.camera->zfar = glm::length(scene.camera->position - 0.5f * (scene.boundsMin + scene.boundsMax)) + 2.0f * extent;
  }
  return scene;
}

}  // namespace

Scene loadScene(const std::filesystem::path& path, const LoadOptions& options) {
  Scene scene = loadAndRepair(path);
  if (options.strict && !scene.warnings.empty())
    throw Error("strict loading refuses what it would repair: " + scene.warnings.front() +
                (scene.warnings.size() > 1 ? " (and " + std::to_string(scene.warnings.size() - 1) + " more)" : ""));
  return scene;
}

}  // namespace raybudget
