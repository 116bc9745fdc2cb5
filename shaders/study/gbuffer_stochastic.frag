#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// G-buffer of a stochastic depth layer, depth pass: drops fragments at random
// (roma_gbuffer_dropped), so the depth left is that of the nearest kept surface.
#include "roma_gbuffer.glsl"

layout(location = 0) in vec3 v_position; // unused: declared as the vertex stage writes them
layout(location = 1) in vec3 v_normal;
layout(location = 2) flat in uint v_triangle;

void main()
{
    if (roma_gbuffer_dropped(uvec2(gl_FragCoord.xy), v_triangle))
        discard;
}
