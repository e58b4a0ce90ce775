#include "bvh/embree_build.h"

#include <bit>
#include <cmath>
#include <limits>
#include <string>

#include <embree3/rtcore.h>

#include "raybudget/error.h"

namespace raybudget::bvh {
namespace {

struct TmpNode {
  bool leaf;
};
struct TmpInner : TmpNode {
  TmpNode* child[2];
  Box bounds[2];
};
struct TmpLeaf : TmpNode {
  uint32_t count;
  uint32_t ids[1];  // `count` entries, allocated past the struct
};

void* createNode(RTCThreadLocalAllocator alloc, unsigned int childCount, void*) {
  if (childCount != 2) return nullptr;  // maxBranchingFactor is 2
  auto* n = static_cast<TmpInner*>(rtcThreadLocalAlloc(alloc, sizeof(TmpInner), 16));
  n->leaf = false;
  n->child[0] = n->child[1] = nullptr;
  return n;
}

void setChildren(void* node, void** children, unsigned int count, void*) {
  auto* n = static_cast<TmpInner*>(node);
  for (unsigned i = 0; i < count && i < 2; ++i) n->child[i] = static_cast<TmpNode*>(children[i]);
}

void setBounds(void* node, const RTCBounds** bounds, unsigned int count, void*) {
  auto* n = static_cast<TmpInner*>(node);
  for (unsigned i = 0; i < count && i < 2; ++i)
    n->bounds[i] = {{bounds[i]->lower_x, bounds[i]->lower_y, bounds[i]->lower_z}, {bounds[i]->upper_x, bounds[i]->upper_y, bounds[i]->upper_z}};
}

void* createLeaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void*) {
  auto* l = static_cast<TmpLeaf*>(rtcThreadLocalAlloc(alloc, sizeof(TmpLeaf) + count * sizeof(uint32_t), 16));
  l->leaf = true;
  l->count = uint32_t(count);
  for (size_t i = 0; i < count; ++i) l->ids[i] = prims[i].primID;
  return l;
}

void splitPrimitive(const RTCBuildPrimitive* prim, unsigned int axis, float position, RTCBounds* left, RTCBounds* right, void* user) {
  const auto& split = *static_cast<const SplitFunction*>(user);
  const Box clip{{prim->lower_x, prim->lower_y, prim->lower_z}, {prim->upper_x, prim->upper_y, prim->upper_z}};
  Box l, r;
  split(prim->primID, clip, int(axis), position, l, r);
  *left = RTCBounds{l.min.x, l.min.y, l.min.z, 0.0f, l.max.x, l.max.y, l.max.z, 0.0f};
  *right = RTCBounds{r.min.x, r.min.y, r.min.z, 0.0f, r.max.x, r.max.y, r.max.z, 0.0f};
}

float area(const Box& b) {
  const glm::vec3 d = glm::max(b.max - b.min, glm::vec3(0.0f));
  return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
}

Box merge(const Box& a, const Box& b) { return {glm::min(a.min, b.min), glm::max(a.max, b.max)}; }

// Writes one child slot of a node: box (rounded outwards) plus index and count bits.
void setChild(gpu::GpuBvhNode& n, int side, const Box& box, uint32_t index, uint32_t count) {
  const Box b = roundOutwards(box);
  const float fi = std::bit_cast<float>(index), fc = std::bit_cast<float>(count);
  if (side == 0) {
    n.leftMinIndex = glm::vec4(b.min, fi);
    n.leftMaxCount = glm::vec4(b.max, fc);
  } else {
    n.rightMinIndex = glm::vec4(b.min, fi);
    n.rightMaxCount = glm::vec4(b.max, fc);
  }
}

struct EmbreeDevice {
  RTCDevice device = rtcNewDevice(nullptr);
  ~EmbreeDevice() {
    if (device) rtcReleaseDevice(device);
  }
};

struct EmbreeBvh {
  RTCBVH bvh;
  explicit EmbreeBvh(RTCDevice d) : bvh(rtcNewBVH(d)) {}
  ~EmbreeBvh() {
    if (bvh) rtcReleaseBVH(bvh);
  }
};

}  // namespace

Box roundOutwards(const Box& b) {
  const float inf = std::numeric_limits<float>::infinity();
  Box r;
  for (int k = 0; k < 3; ++k) {
    r.min[k] = std::nextafter(b.min[k], -inf);
    r.max[k] = std::nextafter(b.max[k], inf);
  }
  return r;
}

FlatTree buildTree(const std::vector<BuildRef>& refs, const TreeShape& shape, std::vector<gpu::GpuBvhNode>& nodes,
                   const std::function<uint32_t(const uint32_t* ids, uint32_t count)>& emitLeaf, const SplitFunction& split) {
  if (refs.empty()) throw Error("BVH build over zero primitives");
  static EmbreeDevice device;  // Embree keeps its thread pool per device: create it once
  if (!device.device) throw Error("Embree: rtcNewDevice failed");
  // Spatial splits need room for the split references: Embree's manual asks for about twice.
  std::vector<RTCBuildPrimitive> prims(split ? 2 * refs.size() : refs.size());
  for (size_t i = 0; i < refs.size(); ++i) {
    const Box& b = refs[i].box;
    prims[i] = RTCBuildPrimitive{b.min.x, b.min.y, b.min.z, 0u, b.max.x, b.max.y, b.max.z, refs[i].id};
  }
  EmbreeBvh bvh(device.device);
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.byteSize = sizeof(args);
  args.buildQuality = RTC_BUILD_QUALITY_HIGH;
  args.maxBranchingFactor = 2;
  args.maxDepth = shape.maxDepth;
  args.minLeafSize = 1;
  args.maxLeafSize = shape.maxLeafSize;
  args.traversalCost = 1.0f;
  args.intersectionCost = shape.intersectionCost;
  args.bvh = bvh.bvh;
  args.primitives = prims.data();
  args.primitiveCount = refs.size();
  args.primitiveArrayCapacity = prims.size();
  args.createNode = createNode;
  args.setNodeChildren = setChildren;
  args.setNodeBounds = setBounds;
  args.createLeaf = createLeaf;
  if (split) {
    args.splitPrimitive = splitPrimitive;
    args.userPtr = const_cast<SplitFunction*>(&split);
  }
  auto* root = static_cast<TmpNode*>(rtcBuildBVH(&args));
  if (!root) throw Error("Embree: rtcBuildBVH failed (error " + std::to_string(int(rtcGetDeviceError(device.device))) + ")");

  Box all = refs[0].box;
  for (const BuildRef& r : refs) all = merge(all, r.box);
  const float rootArea = std::max(area(all), std::numeric_limits<float>::min());
  FlatTree tree;
  tree.root = uint32_t(nodes.size());
  nodes.push_back({});
  // A leaf root becomes an inner node whose right child is empty (min > max: never entered).
  const Box empty{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(-std::numeric_limits<float>::max())};
  if (root->leaf) {
    const auto* leaf = static_cast<const TmpLeaf*>(root);
    setChild(nodes[tree.root], 0, all, emitLeaf(leaf->ids, leaf->count), leaf->count);
    setChild(nodes[tree.root], 1, empty, 0, 1);
    tree.nodeCount = 1;
    tree.sahCost = 1.0f + float(leaf->count);
    return tree;
  }
  // Depth-first flattening: each inner node's slot is reserved before its children's.
  float cost = 1.0f;  // the root's traversal
  std::vector<std::pair<const TmpInner*, uint32_t>> stack = {{static_cast<const TmpInner*>(root), tree.root}};
  while (!stack.empty()) {
    const auto [inner, slot] = stack.back();
    stack.pop_back();
    for (int c = 0; c < 2; ++c) {
      const TmpNode* child = inner->child[c];
      const float share = area(inner->bounds[c]) / rootArea;
      if (child->leaf) {
        const auto* leaf = static_cast<const TmpLeaf*>(child);
        setChild(nodes[slot], c, inner->bounds[c], emitLeaf(leaf->ids, leaf->count), leaf->count);
        cost += share * float(leaf->count);
      } else {
        const uint32_t index = uint32_t(nodes.size());
        nodes.push_back({});
        setChild(nodes[slot], c, inner->bounds[c], index, 0);
        cost += share;
        stack.push_back({static_cast<const TmpInner*>(child), index});
      }
    }
  }
  tree.nodeCount = uint32_t(nodes.size()) - tree.root;
  tree.sahCost = cost;
  return tree;
}

}  // namespace raybudget::bvh
