#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// The accuracy study's exact traversal through the public AO pass (src/study/study_ao.h):
// each ray walked through the map's BOM from its origin to its end (3D DDA, no snapping,
// rotation or step bound): the voxelization's own error apart from ROMA's.
#include "roma_ao_images.glsl"

bool roma_ao_ray_open(vec3 origin, vec3 dir, float skip, float tmax)
{
    return roma_bom_walk(origin, dir, tmax, 1 << 20) < 0.0;
}
