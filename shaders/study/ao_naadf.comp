#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// The accuracy study's NAADF through the public AO pass (src/study/study_ao.h): each ray
// traversed through the hierarchy built from the map's BOM every frame (src/study/naadf.h),
// bound in the BOM's place: the exact traversal's voxels, empty space left a box at a time.
#include "roma_ao_images.glsl"
#define ROMA_NAADF_WORD(i) roma_fetch_bom_word(i)
#include "roma_naadf.glsl"

bool roma_ao_ray_open(vec3 origin, vec3 dir, float skip, float tmax)
{
    return !roma_naadf_occluded(roma_fetch_grid(0u), origin, dir, tmax);
}
