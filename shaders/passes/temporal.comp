#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// Temporal accumulation (ROMA paper 4.3: new jitter and directions every frame,
// accumulated over frames): the history is fetched where this pixel's surface
// was in the previous frame (motion vectors of the G-buffer) and kept only when
// the previous G-buffer saw the same surface there (position within a tolerance
// that grows with view distance, normals alike); otherwise it restarts. The new
// value averages up to max_history frames (a running mean, then an exponential
// one), so a still camera converges and a moving one does not smear.
#include "roma_lights.glsl"

layout(local_size_x = ROMA_PIXEL_WORKGROUP_X, local_size_y = ROMA_PIXEL_WORKGROUP_Y) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaVec4s { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) writeonly buffer RomaVec4Out { vec4 v[]; };

layout(push_constant) uniform Push { roma_temporal_push pc; };

void main()
{
    uvec2 xy = gl_GlobalInvocationID.xy;
    uint width = pc.config.x, height = pc.config.y;
    if (xy.x >= width || xy.y >= height)
        return;
    uint pixel = xy.y * width + xy.x;
    vec3 current = RomaVec4s(pc.current).v[pixel].rgb;
    roma_gbuffer_pixel g = RomaGbufferPixels(pc.pixels).p[pixel];
    float count = 0.0;
    vec3 history = vec3(0.0);
    vec2 motion = vec2(g.shading_normal.w, g.geometric_normal.w);
    if (pc.config.w != 0u && !roma_is_inf(g.position_t.w) && !roma_is_inf(motion.x)) {
        vec2 prev = vec2(xy) + 0.5 + motion;
        if (prev.x >= 0.0 && prev.y >= 0.0 && prev.x < float(width) && prev.y < float(height)) {
            uint q = uint(prev.y) * width + uint(prev.x);
            roma_gbuffer_pixel h = RomaGbufferPixels(pc.previous).p[q];
            float tolerance = pc.test.x * g.position_t.w;
            if (!roma_is_inf(h.position_t.w) && distance(h.position_t.xyz, g.position_t.xyz) <= tolerance &&
                dot(h.geometric_normal.xyz, g.geometric_normal.xyz) >= pc.test.y) {
                vec4 hv = RomaVec4s(pc.history).v[q];
                history = hv.rgb;
                count = hv.w;
            }
        }
    }
    count = min(count + 1.0, float(pc.config.z));
    RomaVec4Out(pc.dst).v[pixel] = vec4(mix(history, current, 1.0 / count), count);
}
