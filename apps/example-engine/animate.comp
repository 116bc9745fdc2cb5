#version 460
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
// The example engine's own animation pass: the rest positions of the scene, with the
// vertices of one rigid object moved by a translation, written where libroma reads
// them (roma_map_frame_desc.gpu_positions). An engine's skinning pass would sit here.
layout(local_size_x = 64) in;

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer RestPositions { float p[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer Positions { float p[]; };

layout(push_constant) uniform Push {
    uvec2 rest;          // 3 floats per vertex
    uvec2 positions;     // 3 floats per vertex
    uint vertex_count;
    uint object_first;   // the moving object's vertices: [object_first, vertex_count)
    vec2 pad;
    vec4 offset;         // its translation this frame
} pc;

void main()
{
    uint v = gl_GlobalInvocationID.x;
    if (v >= pc.vertex_count)
        return;
    vec3 p = vec3(RestPositions(pc.rest).p[3u * v], RestPositions(pc.rest).p[3u * v + 1u],
                  RestPositions(pc.rest).p[3u * v + 2u]);
    if (v >= pc.object_first)
        p += pc.offset.xyz;
    Positions(pc.positions).p[3u * v] = p.x;
    Positions(pc.positions).p[3u * v + 1u] = p.y;
    Positions(pc.positions).p[3u * v + 2u] = p.z;
}
