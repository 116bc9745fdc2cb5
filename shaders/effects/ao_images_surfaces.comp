#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// Ambient occlusion from an engine's G-buffer images with ROMA_AO_START_SURFACES
// (roma_ao_effect): as ao_images.comp, and where the walk of a ray's skipped start meets an
// occupied BOM cell, the surface grid's triangles decide (roma_ao_surface_start.glsl). A module
// of its own: compiled into ao_images.comp, the grid's code slowed the default pass on lavapipe
// about twofold even where no ray reached it.
#include "roma_ao_surface_start.glsl"

bool roma_ao_ray_open(vec3 origin, vec3 dir, float skip, float tmax)
{
    if (!roma_ao_start_open(origin, dir, skip, tmax))
        return false;
    roma_hit h = roma_trace_snapped(origin, dir, skip, tmax, false);
    return (h.info & ROMA_HIT_FLAG) == 0u;
}
