#version 460
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
// The viewer's G-buffer: vertices pulled from the positions the map reads too (the
// static upload or the animator's skinned output), so both see the same triangles. A
// non-indexed draw of 3 vertices per triangle: the triangle's index travels to the
// fragment shader (gl_PrimitiveID would need the geometry-shader capability).
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Positions { float v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer Indices { uint i[]; };

layout(push_constant) uniform Push {
    vec4 clip_rows[4];   // world -> clip, one row per component
    vec4 eye;
    uvec2 positions;     // 3 floats per vertex
    uvec2 albedo;        // vec4 per triangle
    uvec2 indices;       // 3 per triangle
} pc;

layout(location = 0) out vec3 world;
layout(location = 1) flat out uint triangle;

void main()
{
    triangle = uint(gl_VertexIndex) / 3u;
    uint i = 3u * Indices(pc.indices).i[gl_VertexIndex];
    Positions p = Positions(pc.positions);
    vec4 x = vec4(p.v[i], p.v[i + 1u], p.v[i + 2u], 1.0);
    world = x.xyz;
    gl_Position = vec4(dot(pc.clip_rows[0], x), dot(pc.clip_rows[1], x), dot(pc.clip_rows[2], x),
                       dot(pc.clip_rows[3], x));
}
