// What each public effect's pass (roma_{ao,lights,gi}_images.glsl) reads first: its pixel
// (from the covered-pixel list or over the images, roma_image_list.glsl) and the surface
// there from the engine's G-buffer images at set 1, bindings 0-2; binding 3 is the
// effect's output, declared by the pass with its own format. Include after a trace file
// (roma/trace_descriptors.glsl or roma_lights.glsl): the scale is the cascade level's.
#ifndef ROMA_EFFECT_SURFACE_GLSL
#define ROMA_EFFECT_SURFACE_GLSL

#include "roma_image_list.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform sampler2D roma_effect_position; // w > 0: covered
layout(set = 1, binding = 1) uniform sampler2D roma_effect_normal;
layout(set = 1, binding = 2) uniform sampler2D roma_effect_geometric_normal;

struct roma_effect_surface {
    uint pixel;   // y * width + x
    ivec2 at;     // (x, y)
    bool covered; // false: the background, and nothing below is read
    vec3 p;       // the surface point
    vec3 n;       // unit shading normal
    vec3 ng;      // unit geometric normal
    float scale;  // the trace cell of the cascade level that holds p, in level 0's
};

// This invocation's pixel and its surface; false past the end of the list or the images.
bool roma_effect_surface_read(uint width, uint height, out roma_effect_surface s)
{
    s.covered = false;
    s.p = s.n = s.ng = vec3(0.0);
    s.scale = 1.0;
    if (!roma_image_pixel(width, height, s.pixel, s.at))
        return false;
    vec4 position = texelFetch(roma_effect_position, s.at, 0);
    s.covered = position.w > 0.0;
    if (!s.covered)
        return true;
    s.p = position.xyz;
    s.n = normalize(texelFetch(roma_effect_normal, s.at, 0).xyz);
    s.ng = normalize(texelFetch(roma_effect_geometric_normal, s.at, 0).xyz);
    s.scale = roma_level_scale(s.p);
    return true;
}

#endif // ROMA_EFFECT_SURFACE_GLSL
