#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// roma_temporal_effect, step 1: this frame's value averaged with the history of the same
// surface point, fetched where the point was on the previous frame's picture (the previous
// world -> clip matrix) and kept only when the previous frame saw the same surface there
// (within three pixel footprints). A running mean over at most max_history frames.
#include "roma_shared.h"
#include "roma_footprint.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D t_current;
layout(set = 0, binding = 1) uniform sampler2D t_position;
layout(set = 0, binding = 2) uniform sampler2D t_previous_position;
layout(set = 0, binding = 3) uniform sampler2D t_history;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D t_accumulated;

layout(push_constant) uniform Push { roma_temporal_images_push pc; };

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(pc.config.xy);
    if (any(greaterThanEqual(p, size)))
        return;
    vec3 value = texelFetch(t_current, p, 0).rgb;
    vec4 pos = texelFetch(t_position, p, 0);
    if (!(pos.w > 0.0)) {
        imageStore(t_accumulated, p, vec4(value, 0.0));
        return;
    }
    vec3 mean = value;
    float count = 1.0;
    uint flags = pc.config.w;
    if ((flags & ROMA_TEMPORAL_RESET) == 0u) {
        ivec2 q = p;
        if ((flags & ROMA_TEMPORAL_STILL) == 0u) {
            vec4 x = vec4(pos.xyz, 1.0);
            vec4 c = vec4(dot(pc.prev_row0, x), dot(pc.prev_row1, x), dot(pc.prev_row2, x), dot(pc.prev_row3, x));
            q = c.w > 0.0 ? ivec2(floor((c.xy / c.w * 0.5 + 0.5) * vec2(size))) : ivec2(-1);
        }
        if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size))) {
            vec4 history = texelFetch(t_history, q, 0);
            vec4 was = texelFetch(t_previous_position, q, 0);
            // A pixel alone on its surface keeps no history: nothing tells its surface from another.
            float footprint = roma_pixel_footprint(t_position, p, size, pos.xyz);
            if (history.a > 0.0 && was.w > 0.0 && footprint < ROMA_FOOTPRINT_ALONE &&
                distance(was.xyz, pos.xyz) <= 3.0 * footprint) {
                count = min(history.a + 1.0, float(pc.config.z));
                mean = history.rgb + (value - history.rgb) / count;
            }
        }
    }
    imageStore(t_accumulated, p, vec4(mean, count));
}
