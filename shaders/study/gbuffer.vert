#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer, vertex stage (both the depth pre-pass and the shading pass: the
// same module, so that depths match bit for bit for the EQUAL test; the clip
// position is `precise` so neither compilation may contract or reorder it.
// `invariant gl_Position` would state the same, but glslang puts it on the
// gl_PerVertex member and the layers' SPIR-V validator warns about that). Pulls
// triangle gl_VertexIndex / 3 through buffer addresses. Vertices past the
// triangles (3 more) form a full-screen triangle at depth 0 (the far plane
// under reversed Z) that fills the pixels no geometry covered.
#include "roma_gbuffer.glsl"

layout(location = 0) out vec3 v_position;
layout(location = 1) out vec3 v_normal;
layout(location = 2) flat out uint v_triangle;

void main()
{
    uint tri = uint(gl_VertexIndex) / 3u;
    uint corner = uint(gl_VertexIndex) % 3u;
    if (tri >= pc.config.x) {
        // Background: covers the whole viewport, z = 0 exactly.
        vec2 xy = vec2(corner == 1u ? 3.0 : -1.0, corner == 2u ? 3.0 : -1.0);
        gl_Position = vec4(xy, 0.0, 1.0);
        v_position = vec3(0.0);
        v_normal = vec3(0.0);
        v_triangle = ROMA_GBUFFER_NO_TRIANGLE;
        return;
    }
    uint index = RomaGbufferIndices(pc.indices).i[3u * tri + corner];
    vec3 p = RomaGbufferVec4s(pc.positions).v[index].xyz;
    v_position = p;
    v_normal = RomaGbufferVec4s(pc.normals).v[index].xyz;
    v_triangle = tri;
    precise vec4 clip = roma_gbuffer_clip(RomaGbufferParams(pc.params).params.camera, p);
    gl_Position = clip;
}
