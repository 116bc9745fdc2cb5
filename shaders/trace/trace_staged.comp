#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// Batch trace of the map's own staging buffers (roma_map_trace), bound as texel
// buffers: on CPU devices texel fetches and image stores cost a fraction of
// storage-buffer or address-based loads and stores.
#include "roma/trace_descriptors.glsl"
#include "roma_batch_trace.glsl"

// Ray i: texels 2i (origin, tmin) and 2i + 1 (dir, tmax).
layout(set = ROMA_TRACE_SET, binding = ROMA_TRACE_BINDING_RAYS) uniform samplerBuffer rays;
// Hit i: (t bits, info).
layout(set = ROMA_TRACE_SET, binding = ROMA_TRACE_BINDING_HITS, rg32ui) uniform writeonly uimageBuffer hits;

void main()
{
    uint i;
    if (!roma_batch_index(i))
        return;
    vec4 a = texelFetch(rays, int(2u * i)), b = texelFetch(rays, int(2u * i + 1u));
    roma_hit h = roma_batch_trace(roma_ray(a.xyz, a.w, b.xyz, b.w));
    imageStore(hits, int(i), uvec4(floatBitsToUint(h.t), h.info, 0u, 0u));
}
