#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// One invocation loops p.count times and writes how many iterations it ran (words[0]) and
// a value that depends on each of them (words[1]): the device's loop budget per invocation,
// measured (roma_loop_probe, src/vulkan/loop_budget.h), and the loop guard's seeded overrun.
#include "roma_shared.h"

layout(local_size_x = 1) in;

layout(std430, binding = ROMA_FILL_BINDING_OUTPUT) writeonly buffer Output { uint words[]; } out_buf;

layout(push_constant) uniform Push { roma_fill_push p; };

void main()
{
    uint ran = 0u, h = p.value;
    for (uint i = 0u; i < p.count; ++i) {
        ROMA_LOOP_TICK();
        ran += 1u;
        h = h * 1664525u + i; // keeps each iteration's work in the result
    }
    out_buf.words[0] = ran;
    out_buf.words[1] = h;
}
