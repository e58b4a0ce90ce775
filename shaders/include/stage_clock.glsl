// The ray-tracing stage's deadlines (RenderSettings::stageDeadline): the trace passes stop
// tracing once the stage has run for frame.stageDeadline's ticks of the device clock
// (VK_KHR_shader_clock's shaderDeviceClock, GL_EXT_shader_realtime_clock), and the pixels left
// keep their fallbacks. The selection predicts the stage's time; the deadline bounds it where
// the prediction was wrong (a camera jump that left many shadow pixels uncertain: a trace pass
// at 2-10x its prediction). The effects pass stops at T less the fill's recent time (x), the
// shadow pass at T less the effects' and the fill's (y: select/stage_deadline.h), so that
// shadows that ran past their prediction are cut rather than the reflections and refractions
// after them. The fill is cut only at about T itself (z), where the stage would else end past
// it: without the fill 15 of 16 pixels of an item at 1/16 keep the fallback, a far worse image
// per millisecond saved than any traced pixel left out.
// The stage is not contiguous on the queue: the fallback and lighting passes run between the
// shadow pass and the effects pass. Its time is counted in TileListBlock::stageClock, reset to
// 0 before coverage (coverage_pass.cpp):
//   x the device clock when coverage began (workgroup 0; 0 until then),
//   y the stage's span from x to the end of the select pass, then of the shadow pass (every
//     RB_SPAN_STRIDE-th workgroup and the last: lavapipe may run a contiguous range of a
//     dispatch's workgroups on each thread, so the last one may end long before the others),
//   z 1 + when the effects pass began, after x (workgroup 0; 0 until then),
//   w 0;
// and in TileListBlock::deadlineCut, reset with it, what the deadline left to the fallbacks:
//   x the pixels the trace passes would have traced or probed (FrameTiming::deadlineCutPixels),
//   y the work the selection predicted for them, in 1/RB_CUT_WORK_UNITS of its units (items
//     only), which the time scale takes off the frame's prediction before it learns from it,
//   z of x, the shadow pass's (the effects pass's time is learned where it cut none),
//   w the pixels the fill would have filled past its deadline (FrameTiming::fillCutPixels).
// The effects pass counts y + its time since z.
// The clock's unit is the device's: the CPU learns ticks per millisecond from y and the
// timestamps of the same passes (selection_stage.cpp). What a trace pass does past its deadline
// is include/deadline_cut.glsl's.
// The includer enables GL_EXT_shader_realtime_clock and includes bindings.glsl.
#ifndef RB_STAGE_CLOCK_GLSL
#define RB_STAGE_CLOCK_GLSL

uint deviceClock() { return max(clockRealtime2x32EXT().x, 1u); }  // (0 marks "not yet")

// Coverage: the stage begins.
void stampStageStart() {
  if (gl_WorkGroupID.x == 0u && gl_LocalInvocationIndex == 0u) atomicCompSwap(stageClock.x, 0u, deviceClock());
}

#define RB_SPAN_STRIDE 4u

// The end of a workgroup of the select pass or the shadow pass: the stage's span so far.
void stampStageSpan() {
  bool stamps = gl_WorkGroupID.x % RB_SPAN_STRIDE == RB_SPAN_STRIDE - 1u || gl_WorkGroupID.x + 1u == gl_NumWorkGroups.x;
  // (The workgroup's last invocation: lavapipe runs its subgroups one after the other.)
  if (stamps && gl_LocalInvocationIndex + 1u == gl_WorkGroupSize.x && stageClock.x != 0u) atomicMax(stageClock.y, deviceClock() - stageClock.x);
}

// The effects pass begins.
void stampEffectsStart() {
  if (gl_WorkGroupID.x == 0u && gl_LocalInvocationIndex == 0u && stageClock.x != 0u)
    atomicCompSwap(stageClock.z, 0u, deviceClock() - stageClock.x + 1u);
}

#endif
