#version 460
#extension GL_GOOGLE_include_directive : require
#include "roma_loop_guard.glsl"
// G-buffer, shading pass: the depth pre-pass left the nearest depth per pixel;
// with the EQUAL test done before the shader (early_fragment_tests) only the
// nearest surface's fragment (or the background triangle) runs, and writes
// the whole pixel record into the storage buffer.
#include "roma_gbuffer.glsl"

layout(early_fragment_tests) in;

layout(buffer_reference, std430, buffer_reference_align = 16) writeonly buffer RomaGbufferWords {
    uvec4 w[];
};

layout(location = 0) in vec3 v_position;
layout(location = 1) in vec3 v_normal;
layout(location = 2) flat in uint v_triangle;

void main()
{
    roma_gbuffer_params prm = RomaGbufferParams(pc.params).params;
    uvec2 pix = uvec2(gl_FragCoord.xy);
    if (pix.x >= prm.dims.x || pix.y >= prm.dims.y || roma_gbuffer_dropped(pix, v_triangle))
        return; // a fragment a stochastic layer dropped: one at the depth of the kept one
    RomaGbufferWords out_px = RomaGbufferWords(pc.pixels);
    uint base = 4u * (pix.y * prm.dims.x + pix.x);
    const float inf = uintBitsToFloat(0x7f800000u);
    if (v_triangle == ROMA_GBUFFER_NO_TRIANGLE) {
        out_px.w[base + 0u] = uvec4(0u, 0u, 0u, floatBitsToUint(inf));
        out_px.w[base + 1u] = uvec4(0u);
        out_px.w[base + 2u] = uvec4(0u);
        out_px.w[base + 3u] = uvec4(0u, 0u, 0u, ROMA_GBUFFER_NO_TRIANGLE);
        return;
    }
    uint tri = v_triangle;
    RomaGbufferIndices indices = RomaGbufferIndices(pc.indices);
    RomaGbufferVec4s positions = RomaGbufferVec4s(pc.positions);
    vec3 p0 = positions.v[indices.i[3u * tri + 0u]].xyz;
    vec3 p1 = positions.v[indices.i[3u * tri + 1u]].xyz;
    vec3 p2 = positions.v[indices.i[3u * tri + 2u]].xyz;

    // The point where the pixel centre's ray meets the triangle's plane: an interpolated
    // position is only as exact as the rasterizer's barycentrics (median relative error
    // of t 1.6e-5 measured on an NVIDIA GPU, 8e-8 on lavapipe). The interpolated one is
    // kept where the ray grazes the plane or the two are not within rounding (a sliver).
    vec3 p = v_position;
    vec3 eye = prm.camera.eye.xyz;
    vec2 ndc = gl_FragCoord.xy / vec2(prm.dims.xy) * 2.0 - 1.0;
    vec3 ray = prm.camera.forward.xyz + prm.camera.right.xyz * (ndc.x / prm.camera.right.w)
             - prm.camera.up.xyz * (ndc.y / prm.camera.up.w);
    vec3 plane_n = cross(p1 - p0, p2 - p0);
    float facing = dot(ray, plane_n);
    vec3 on_plane = eye + ray * (dot(p0 - eye, plane_n) / facing);
    // A coordinate all three corners share (a floor at y = 0) stays exact, as interpolated.
    on_plane = mix(on_plane, p0, bvec3(p0.x == p1.x && p1.x == p2.x, p0.y == p1.y && p1.y == p2.y,
                                       p0.z == p1.z && p1.z == p2.z));
    if (abs(facing) > 1e-3 * length(ray) * length(plane_n) && distance(on_plane, p) <= 1e-3 * distance(p, eye))
        p = on_plane;
    vec3 to_eye = eye - p;
    float t = length(to_eye);
    // Same rules as the reference tracer: geometric normal facing the eye (the
    // view direction for a sliver), shading normal on its side.
    vec3 gn = cross(p1 - p0, p2 - p0);
    float gl2 = dot(gn, gn);
    gn = gl2 > 0.0 ? gn * inversesqrt(gl2) : to_eye / max(t, 1e-30);
    if (dot(gn, to_eye) < 0.0)
        gn = -gn;
    vec3 sn = gn;
    float sl2 = dot(v_normal, v_normal);
    if (sl2 > 1e-24)
        sn = v_normal * inversesqrt(sl2);
    if (dot(sn, gn) < 0.0)
        sn = -sn;

    // Motion: where the same world point lands in the previous frame, minus
    // where it lands now (both projected, so equal cameras give exactly 0).
    // +INF when the point is not in front of the previous camera.
    vec2 size = vec2(prm.dims.xy);
    vec3 cur = roma_gbuffer_pixel_of(prm.camera, p, size);
    vec3 prev = roma_gbuffer_pixel_of(prm.previous, p, size);
    vec2 motion = prev.z > 0.0 ? prev.xy - cur.xy : vec2(inf);

    vec3 albedo = RomaGbufferVec4s(pc.albedo).v[tri].rgb;
    out_px.w[base + 0u] = floatBitsToUint(vec4(p, t));
    out_px.w[base + 1u] = floatBitsToUint(vec4(sn, motion.x));
    out_px.w[base + 2u] = floatBitsToUint(vec4(gn, motion.y));
    out_px.w[base + 3u] = uvec4(floatBitsToUint(albedo), tri);
}
