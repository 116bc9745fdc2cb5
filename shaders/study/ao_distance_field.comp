#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// The accuracy study's distance field through the public AO pass (src/study/study_ao.h):
// each ray sphere-traced through the field built from the map's BOM every frame
// (src/study/distance_field.h), bound in the BOM's place; the ROMA paper's comparator.
#include "roma_ao_images.glsl"
#define ROMA_DF_WORD(i) roma_fetch_bom_word(i)
#include "roma_distance_field.glsl"

bool roma_ao_ray_open(vec3 origin, vec3 dir, float skip, float tmax)
{
    // config2.y: most steps; ray.w: least step (cells).
    return !roma_df_occluded(roma_fetch_grid(0u), origin, dir, tmax, pc.config2.y, pc.ray.w);
}
