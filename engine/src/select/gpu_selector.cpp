#include "select/gpu_selector.h"

#include <algorithm>
#include <bit>
#include <cstring>

#include "select_apply_comp.h"
#include "select_bitonic_comp.h"
#include "select_block_sort_comp.h"
#include "select_candidates_comp.h"
#include "select_gather_comp.h"
#include "select_keys_comp.h"
#include "select_merge_comp.h"
#include "select_walk_comp.h"
#include "shared/selection.h"
#include "shared/config.h"
#include "vk/check.h"
#include "vk/compute_set.h"
#include "vk/pipelines.h"
#include "vk/resources.h"
#include "vk/timestamps.h"

namespace raybudget::select {
namespace {

using gpu::SelectPush;

// The frame's fill quality at one rate per effect (x, y, z: RB_ITEM_*) and its still share
// (w), as SelectPush holds them.
glm::vec4 qualities(const ItemFrame& frame, float FillQuality::*rate, float FillStill::*still) {
  static_assert(RB_ITEMS_PER_OBJECT == 3);
  return {frame.qualities[0].*rate, frame.qualities[1].*rate, frame.qualities[2].*rate, frame.still.*still};
}
static_assert(uint32_t(Policy::Paper) == RB_SELECT_PAPER && uint32_t(Policy::Density) == RB_SELECT_DENSITY &&
              uint32_t(Policy::Nearest) == RB_SELECT_NEAREST && uint32_t(Policy::Random) == RB_SELECT_RANDOM && uint32_t(Policy::Benefit) == RB_SELECT_BENEFIT);

constexpr uint32_t kBlock = 1024;  // the bitonic shader's shared-memory block
// mergeArgs holds a dispatch for every merge pass any 32-bit candidate count can need.
static_assert(RB_MERGE_MAX_PASSES >= 32 - std::countr_zero(RB_MERGE_BLOCK));

uint32_t paddedSize(uint32_t n) { return std::max(kBlock, std::bit_ceil(std::max(n, 1u))); }

// The walk runs as one subgroup (shaders/select/select_walk.comp): its workgroup size is
// the device's subgroup size, and it needs the subgroup vote, arithmetic, shuffle and ballot
// ops (and shaderFloat64 for the density keys, select_common.glsl).
vk::Owned<VkPipeline> createWalkPipeline(const vk::Context& ctx, VkPipelineLayout layout) {
  VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &subgroup};
  vkGetPhysicalDeviceProperties2(ctx.physicalDevice(), &properties);
  const VkSubgroupFeatureFlags needed = VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_VOTE_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT |
                                        VK_SUBGROUP_FEATURE_SHUFFLE_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT;
  if ((subgroup.supportedOperations & needed) != needed || !(subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT))
    throw Error(std::string("the GPU selection needs subgroup vote, arithmetic, shuffle and ballot operations in compute shaders; ") +
                ctx.properties().deviceName + " lacks them");
  if (!ctx.shaderFloat64())
    throw Error(std::string("the GPU selection needs shaderFloat64 (correctly rounded density keys, select_common.glsl); ") +
                ctx.properties().deviceName + " lacks it");
  const uint32_t size = subgroup.subgroupSize;
  const VkSpecializationMapEntry entry{0, 0, sizeof(size)};
  const VkSpecializationInfo info{1, &entry, sizeof(size), &size};
  return vk::createComputePipeline(ctx, layout, kSpirv_select_walk_comp, &info);
}

}  // namespace

struct GpuSelector::Impl {
  const vk::Context& ctx;
  uint32_t capacity, padded;
  vk::Buffer candidates, order, relevance, spare, scratch, flags, result, readback, sums, slots, mergeArgs, walkOrder, placeholder;
  vk::ComputeSet set;
  vk::Owned<VkPipeline> keys, bitonic, blockSort, merge, gather, walk, candidatesFromObjects, apply;
  bool mergeSort = false;  // a CPU device: the barrier-free merge sort beats the bitonic sort
  vk::TimestampPool timestamps;
  double gpuMs = 0.0;

  Impl(const vk::Context& c, uint32_t cap, SortMethod sort)
      : ctx(c), capacity(cap), padded(paddedSize(cap)), timestamps(c, 1, 1) {
    if (cap > RB_ORDER_FREE_MAX_TERMS)
      throw Error("GPU selection: a capacity of " + std::to_string(cap) + " candidates exceeds the most its sums hold exactly, " +
                  std::to_string(RB_ORDER_FREE_MAX_TERMS));
    mergeSort = sort == SortMethod::Merge || (sort == SortMethod::Auto && c.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU);
    const uint32_t keySlots = mergeSort ? std::max(cap, 1u) : padded;  // the bitonic sort pads to a power of two
    const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    candidates = vk::createBuffer(c, std::max(cap, 1u) * sizeof(gpu::GpuCandidate),
                                  storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, false);
    order = vk::createBuffer(c, keySlots * 8ull, storage, false);  // 8-byte keys (select_common.glsl)
    relevance = vk::createBuffer(c, keySlots * 8ull, storage, false);
    spare = vk::createBuffer(c, std::max(cap, 1u) * 8ull, storage, false);
    slots = vk::createBuffer(c, std::max(cap, 1u) * 4ull, storage, false);
    // Per order (the policy's, `paper`'s relevance order) and merge pass: its indirect
    // dispatch (16 bytes each), written by the block sort.
    mergeArgs = vk::createBuffer(c, 2ull * RB_MERGE_MAX_PASSES * 16, storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, false);
    walkOrder = vk::createBuffer(c, 2ull * padded * 16, storage, false);  // the walk's records; `paper`'s second order from `padded`
    scratch = vk::createBuffer(c, std::max(cap, 1u) * 4ull, storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false);  // `paper`'s taken flags
    flags = vk::createBuffer(c, std::max(cap, 1u) * 4ull, storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, false);
    result = vk::createBuffer(c, kResultBytes, storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, false);
    readback = vk::createBuffer(c, std::max(cap, 1u) * 4ull, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    sums = vk::createBuffer(c, kResultBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);  // select()'s copy of the result words
    placeholder = vk::createBuffer(c, 32, storage, false);  // bindings 6-9, 14, 15 until bindFrame
    const std::vector<VkDescriptorType> types(16, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    set = vk::createComputeSet(c, types, sizeof(SelectPush));
    const VkBuffer p = placeholder.buffer;
    bindFrame({p, p, p, p, p, p});
    candidatesFromObjects = vk::createComputePipeline(c, set.pipelineLayout, kSpirv_select_candidates_comp);
    apply = vk::createComputePipeline(c, set.pipelineLayout, kSpirv_select_apply_comp);
    keys = vk::createComputePipeline(c, set.pipelineLayout, kSpirv_select_keys_comp);
    bitonic = vk::createComputePipeline(c, set.pipelineLayout, kSpirv_select_bitonic_comp);
    gather = vk::createComputePipeline(c, set.pipelineLayout, kSpirv_select_gather_comp);
    walk = createWalkPipeline(c, set.pipelineLayout);
    merge = vk::createComputePipeline(c, set.pipelineLayout, kSpirv_select_merge_comp);
    blockSort = vk::createComputePipeline(c, set.pipelineLayout, kSpirv_select_block_sort_comp);
  }

  void bindFrame(const FrameBuffers& f) {
    const VkBuffer buffers[16] = {candidates.buffer, order.buffer,   relevance.buffer, scratch.buffer, flags.buffer,     result.buffer,
                                  f.records,         f.selection,    f.params,         f.costs,        spare.buffer,     slots.buffer,
                                  mergeArgs.buffer,  walkOrder.buffer, f.coverage,     f.items};
    vk::writeStorageBuffers(ctx, set.set, buffers);
  }

  void recordFrame(VkCommandBuffer cmd, uint32_t objects, Policy policy, float budget, FrameScale scale, const PolicyOptions& options,
                   const ItemFrame& items) {
    // `benefit` selects among items: up to RB_ITEMS_PER_OBJECT candidates per object.
    // With rates chosen per item, up to three segments per item.
    const uint64_t most = uint64_t(objects) * (policy == Policy::Benefit ? RB_ITEMS_PER_OBJECT * (items.rate == RB_RATE_AUTO ? 3u : 1u) : 1u);
    if (most > capacity) throw Error("GPU selection of " + std::to_string(most) + " candidates exceeds its capacity " + std::to_string(capacity));
    if (policy == Policy::Optimal || policy == Policy::All || policy == Policy::None)
      throw Error(std::string("frame selection runs the budgeted policies, not ") + policyName(policy));
    SelectPush push{glm::uvec4(0, padded, uint32_t(policy), options.seed), glm::uvec4(0, 0, 0, options.graphPointers),
                    glm::vec4(budget, scale.kappa, items.probeBudget, scale.workPerRay), glm::uvec4(options.paperHops, 1, objects, items.rate),
                    glm::uvec4(items.effects, items.lights, items.pixels, items.ablation), qualities(items, &FillQuality::quarter, &FillStill::quarter),
                    qualities(items, &FillQuality::sixteenth, &FillStill::sixteenth)};
    vkCmdFillBuffer(cmd, result.buffer, 0, VK_WHOLE_SIZE, 0);  // the candidate count
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, set.pipelineLayout, 0, 1, &set.set, 0, nullptr);
    dispatch(cmd, candidatesFromObjects, push, vk::groupsFor(objects, RB_GROUP_SIZE));
    orderForWalk(cmd, push, policy, uint32_t(most));
    // Few objects: the walk applies the selection itself (select_walk.comp), a dispatch saved.
    const bool applyInWalk = objects <= RB_APPLY_IN_WALK_OBJECTS;
    SelectPush walking = push;
    if (applyInWalk) walking.stage.x = RB_APPLY_IN_WALK;
    dispatch(cmd, walk, walking, 1);
    if (!applyInWalk) dispatch(cmd, apply, push, vk::groupsFor(objects, RB_GROUP_SIZE));
  }

  // Binds `pipeline` with `push`, records the dispatch, then a barrier for the next step.
  template <class RecordDispatch>
  void step(VkCommandBuffer cmd, VkPipeline pipeline, const SelectPush& push, RecordDispatch recordDispatch) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdPushConstants(cmd, set.pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    recordDispatch();
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  }
  void dispatch(VkCommandBuffer cmd, VkPipeline pipeline, const SelectPush& push, uint32_t groups) {
    step(cmd, pipeline, push, [&] { vkCmdDispatch(cmd, groups, 1, 1); });
  }

  // What the walk reads for up to `most` candidates: the policy's order (and `paper`'s
  // relevance order), laid out as the walk's records (select_gather.comp).
  void orderForWalk(VkCommandBuffer cmd, const SelectPush& push, Policy policy, uint32_t most) {
    // One block of a greedy policy's candidates: the block sort gathers them too.
    const bool gatherInSort = mergeSort && policy != Policy::Paper && most <= RB_MERGE_BLOCK;
    sortOrder(cmd, push, 0, most, gatherInSort);
    if (policy == Policy::Paper) sortOrder(cmd, push, 1, most);
    if (!gatherInSort) dispatch(cmd, gather, push, vk::groupsFor(most, RB_GROUP_SIZE));
  }

  // A sort of one order (0: the policy's, 1: `paper`'s relevance order) of up to `most`
  // candidates: the merge sort (computing its own keys), or keys then the bitonic sort.
  void sortOrder(VkCommandBuffer cmd, SelectPush push, uint32_t which, uint32_t most, bool gatherInSort = false) {
    push.stage = glm::uvec4(0, gatherInSort ? RB_GATHER_IN_SORT : 0, which, push.stage.w);
    if (mergeSort) {
      // Blocks sorted by one workgroup each, then merge passes while runs are shorter than
      // `most`. The shaders count the levels the candidates need and pick the buffers (in
      // frame mode only the GPU knows how many there are); the block sort writes each merge
      // pass's indirect dispatch, empty where the candidates need no such pass (on lavapipe
      // a dispatch costs ~0.07 ms even when all its invocations exit at once).
      dispatch(cmd, blockSort, push, vk::groupsFor(most, RB_MERGE_BLOCK));
      vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                        VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
      uint32_t pass = 0;
      for (uint32_t run = RB_MERGE_BLOCK; run < most; run *= 2, ++pass) {
        push.stage.x = run;
        push.stage.y = pass;
        step(cmd, merge, push, [&] { vkCmdDispatchIndirect(cmd, mergeArgs.buffer, (which * RB_MERGE_MAX_PASSES + pass) * 16ull); });
      }
      return;
    }
    dispatch(cmd, keys, push, vk::groupsFor(push.sizes.y, RB_KEYS_GROUP_SIZE));
    push.stage.x = 0;  // every stage up to the block size in one dispatch
    push.stage.y = 0;
    dispatch(cmd, bitonic, push, push.sizes.y / kBlock);
    for (uint32_t k = 2 * kBlock; k <= push.sizes.y; k <<= 1) {
      for (uint32_t j = k / 2; j >= kBlock; j >>= 1) {
        push.stage.x = k;
        push.stage.y = j;
        dispatch(cmd, bitonic, push, push.sizes.y / 2 / 512);
      }
      push.stage.x = k;
      push.stage.y = 0;  // every j below the block size, in shared memory
      dispatch(cmd, bitonic, push, push.sizes.y / kBlock);
    }
  }

  Selection run(std::span<const Candidate> c, Policy policy, float budget, const PolicyOptions& options) {
    if (policy == Policy::Optimal) throw Error("the optimal policy runs on the CPU only (benchmarks)");
    if (c.size() > capacity) throw Error("GPU selection of " + std::to_string(c.size()) + " candidates exceeds its capacity " + std::to_string(capacity));
    validateCandidates(c, budget);  // the CPU reference's errors for the same input
    const uint32_t n = uint32_t(c.size()), pad = paddedSize(n);
    // Uploaded in ID order: the sort keys break ties by the candidate's slot
    // (select_common.glsl), which is then its place in ID order, as the CPU reference's ties.
    std::vector<uint32_t> byId(n);
    for (uint32_t i = 0; i < n; ++i) byId[i] = i;
    std::stable_sort(byId.begin(), byId.end(), [&](uint32_t a, uint32_t b) { return c[a].id < c[b].id; });
    std::vector<gpu::GpuCandidate> data;
    for (uint32_t i : byId) data.push_back({c[i].id, c[i].cost, c[i].value, c[i].distance});
    vk::Buffer staging = vk::createBuffer(ctx, std::max<size_t>(1, data.size()) * sizeof(gpu::GpuCandidate), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    if (!data.empty()) std::memcpy(staging.mapped, data.data(), data.size() * sizeof(gpu::GpuCandidate));
    // Rate segments: the items' levels live in scratch, one word per item group.
    const bool segments = policy == Policy::Benefit && options.rateSegments;
    uint32_t groups = 0;
    for (const Candidate& x : c) groups = std::max(groups, x.id / RB_SEGMENT_SLOTS + 1);
    if (segments && groups > capacity)
      throw Error("GPU selection: rate segment IDs up to " + std::to_string(groups * RB_SEGMENT_SLOTS) + " exceed the capacity's " +
                  std::to_string(capacity) + " item groups");
    const ItemFrame atPriors;  // (unread: only frame mode prices segments and marks item levels)
    SelectPush push{glm::uvec4(n, pad, uint32_t(policy), options.seed), glm::uvec4(0, 0, 0, segments ? groups : options.graphPointers),
                    glm::vec4(budget, 0, 0, 0), glm::uvec4(options.paperHops, 0, 0, segments ? RB_RATE_AUTO : RB_RATE_FULL), glm::uvec4(0),
                    qualities(atPriors, &FillQuality::quarter, &FillStill::quarter),
                    qualities(atPriors, &FillQuality::sixteenth, &FillStill::sixteenth)};
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      timestamps.reset(cmd, 0);
      if (n > 0) {
        const VkBufferCopy copy{0, 0, n * sizeof(gpu::GpuCandidate)};
        vkCmdCopyBuffer(cmd, staging.buffer, candidates.buffer, 1, &copy);
      }
      vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, set.pipelineLayout, 0, 1, &set.set, 0, nullptr);
      timestamps.begin(cmd, 0, 0);
      const bool sorted = policy != Policy::None && policy != Policy::All;
      if (sorted && n > 0) orderForWalk(cmd, push, policy, n);
      dispatch(cmd, walk, push, 1);
      timestamps.end(cmd, 0, 0);
      const VkBufferCopy back{0, 0, std::max(n, 1u) * 4ull};
      vkCmdCopyBuffer(cmd, flags.buffer, readback.buffer, 1, &back);
      const VkBufferCopy words{0, 0, kResultBytes};
      vkCmdCopyBuffer(cmd, result.buffer, sums.buffer, 1, &words);
      vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    });
    gpuMs = timestamps.read(0)[0].value_or(0.0);
    const auto* f = static_cast<const uint32_t*>(readback.mapped);
    Selection s;
    for (uint32_t i = 0; i < n; ++i)
      if (f[i]) {
        const Candidate& x = c[byId[i]];
        s.ids.push_back(x.id);
        s.cost += x.cost;
        s.value += x.value;
      }
    std::sort(s.ids.begin(), s.ids.end());
    return s;
  }
};

GpuSelector::GpuSelector(const vk::Context& ctx, uint32_t capacity, SortMethod sort) : impl_(std::make_unique<Impl>(ctx, capacity, sort)) {}
GpuSelector::~GpuSelector() = default;
Selection GpuSelector::select(std::span<const Candidate> candidates, Policy policy, float budget,
                                      const PolicyOptions& options) {
  return impl_->run(candidates, policy, budget, options);
}
double GpuSelector::lastGpuMs() const { return impl_->gpuMs; }
GpuSelector::WalkSums GpuSelector::lastWalkSums() const {
  const auto* r = static_cast<const uint32_t*>(impl_->sums.mapped);
  return {std::bit_cast<float>(r[1]), std::bit_cast<float>(r[2])};
}
void GpuSelector::bindFrame(const FrameBuffers& buffers) { impl_->bindFrame(buffers); }
void GpuSelector::recordFrame(VkCommandBuffer cmd, uint32_t objects, Policy policy, float budget, FrameScale scale, const PolicyOptions& options,
                              const ItemFrame& items) const {
  impl_->recordFrame(cmd, objects, policy, budget, scale, options, items);
}
VkBuffer GpuSelector::resultBuffer() const { return impl_->result.buffer; }
VkBuffer GpuSelector::candidateBuffer() const { return impl_->candidates.buffer; }

}  // namespace raybudget::select
