// The body of shaders/effects/image_upsample_*.comp, which differ in the output's format only:
// an effect traced at a resolution divisor s > 1 (one pixel of each s x s block, at the
// block's place config.w gives, as the list pass of roma_image_list_build.glsl took it) fills
// every other covered pixel from the traced pixels of the 2 x 2 blocks around it, weighted
// bilinearly and by how well their surface matches the pixel's: normals that agree, and a
// step between the points that stays in the pixel's plane (a depth edge steps off it). With
// no traced neighbour on a matching surface the best-matching one is taken, with none
// covered the background. config.z = 1: uncovered pixels are left as they are (the effect
// was given the frame's shared list), else they get the background.
#include "roma_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 1, binding = 0) uniform sampler2D roma_up_position;
layout(set = 1, binding = 1) uniform sampler2D roma_up_normal;
layout(set = 1, binding = 3, ROMA_IMAGE_UPSAMPLE_FORMAT) uniform image2D roma_up_output;

layout(push_constant) uniform Push { roma_image_list_push pc; };

void main()
{
    // Over every pixel (the list bound in the set is the traced pixels').
    uvec2 xy = gl_GlobalInvocationID.xy;
    uint width = pc.config.x, height = pc.config.y;
    if (xy.x >= width || xy.y >= height)
        return;
    ivec2 at = ivec2(xy);
    int scale = int(max(pc.config.w & 0xffu, 1u));
    ivec2 place = ivec2((pc.config.w >> 8) & 0xffu, (pc.config.w >> 16) & 0xffu);
    vec4 position = texelFetch(roma_up_position, at, 0);
    if (!(position.w > 0.0)) {
        if (pc.config.z == 0u)
            imageStore(roma_up_output, at, pc.background);
        return;
    }
    ivec2 in_block = at % scale;
    if (in_block == place)
        return; // traced
    vec3 n = normalize(texelFetch(roma_up_normal, at, 0).xyz);
    // The traced pixels around: those of blocks b0 .. b0 + 1, at b * scale + place.
    vec2 u = vec2(at - place) / float(scale);
    ivec2 b0 = ivec2(floor(u));
    vec2 f = u - vec2(b0);
    vec4 sum = vec4(0.0), best_value = pc.background;
    float weights = 0.0, best = -1.0;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            ivec2 q = (b0 + ivec2(i, j)) * scale + place;
            if (q.x < 0 || q.y < 0 || q.x >= int(width) || q.y >= int(height))
                continue;
            vec4 qp = texelFetch(roma_up_position, q, 0);
            if (!(qp.w > 0.0))
                continue;
            float agree = max(dot(n, normalize(texelFetch(roma_up_normal, q, 0).xyz)), 0.0);
            agree *= agree;
            agree *= agree;
            agree *= agree; // the 8th power, without pow
            vec3 step = qp.xyz - position.xyz;
            float len = length(step), off_plane = len > 0.0 ? abs(dot(n, step)) / len * 5.0 : 0.0;
            float surface = agree * exp(-off_plane * off_plane);
            float w = surface * (i == 1 ? f.x : 1.0 - f.x) * (j == 1 ? f.y : 1.0 - f.y);
            vec4 value = imageLoad(roma_up_output, q);
            sum += w * value;
            weights += w;
            if (surface > best) {
                best = surface;
                best_value = value;
            }
        }
    imageStore(roma_up_output, at, weights > 1e-4 ? sum / weights : best_value);
}
