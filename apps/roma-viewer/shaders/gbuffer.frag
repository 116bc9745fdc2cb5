#version 460
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
// Position (w = 1 on geometry), the face normal turned towards the eye (flat shading:
// skinned vertices carry no normals), and the triangle's base colour.
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer Albedo { vec4 a[]; };

layout(push_constant) uniform Push {
    vec4 clip_rows[4];
    vec4 eye;
    uvec2 positions;
    uvec2 albedo;
    uvec2 indices;
} pc;

layout(location = 0) in vec3 world;
layout(location = 1) flat in uint triangle;
layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_albedo;

void main()
{
    vec3 n = cross(dFdx(world), dFdy(world));
    float len = length(n);
    n = len > 0.0 ? n / len : vec3(0.0, 1.0, 0.0);
    if (dot(n, pc.eye.xyz - world) < 0.0)
        n = -n;
    out_position = vec4(world, 1.0);
    out_normal = vec4(n, 0.0);
    out_albedo = Albedo(pc.albedo).a[triangle];
}
