// libroma's loop guard: every loop of libroma's shaders starts its body with
// ROMA_LOOP_TICK(). Compiled with ROMA_LOOP_GUARD (the CMake option of the same name, on in
// the sanitizer build), each tick counts the iterations of the invocation (all loops
// together, as llvmpipe's budget counts them), and when the invocation's main returns the
// count raises the peak of this pipeline's slot in the context's guard buffer; the context
// reports a slot above half of llvmpipe's budget (src/vulkan/loop_guard.h). The shader's own
// main is renamed and called by the guard's: one atomic an invocation, none in its loops (an
// atomic under a branch inside the loops cost llvmpipe, which runs both sides of a branch,
// 2.4 times the time of the sanitizer suite's slowest test). Without it the tick is nothing.
// Included by every compute and fragment shader right after its extensions, before its main.
#ifndef ROMA_LOOP_GUARD_GLSL
#define ROMA_LOOP_GUARD_GLSL

#include "roma_shared.h"

#ifdef ROMA_LOOP_GUARD
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
layout(constant_id = ROMA_LOOP_GUARD_ADDRESS_LO_ID) const uint roma_loop_guard_lo_ = 0u;
layout(constant_id = ROMA_LOOP_GUARD_ADDRESS_HI_ID) const uint roma_loop_guard_hi_ = 0u;
layout(constant_id = ROMA_LOOP_GUARD_SLOT_ID) const uint roma_loop_guard_slot_ = 0u;
layout(buffer_reference, std430, buffer_reference_align = 4) buffer RomaLoopGuardPeaks { uint peak[]; };
uint roma_loop_iterations_ = 0u;
#define ROMA_LOOP_TICK() (roma_loop_iterations_ += 1u)
void roma_guarded_main();
void main()
{
    roma_guarded_main();
    if (roma_loop_iterations_ != 0u && (roma_loop_guard_lo_ | roma_loop_guard_hi_) != 0u)
        atomicMax(RomaLoopGuardPeaks(uvec2(roma_loop_guard_lo_, roma_loop_guard_hi_)).peak[roma_loop_guard_slot_],
                  roma_loop_iterations_);
}
#define main roma_guarded_main
#else
#define ROMA_LOOP_TICK()
#endif

#endif // ROMA_LOOP_GUARD_GLSL
