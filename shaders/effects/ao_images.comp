#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// Ambient occlusion from an engine's G-buffer images (roma_ao_effect): each ray a snapped
// any-hit query through the map bound at set 0 (the trace set), after the exact walk of its
// skipped start. The pass itself is roma_ao_images.glsl.
#include "roma_ao_images.glsl"

bool roma_ao_ray_open(vec3 origin, vec3 dir, float skip, float tmax)
{
    // The skipped start, walked exactly (roma/ray_start.glsl).
    if (roma_ray_start_blocked(origin, dir, min(skip, tmax)))
        return false;
    roma_hit h = roma_trace_snapped(origin, dir, skip, tmax, false);
    return (h.info & ROMA_HIT_FLAG) == 0u;
}
