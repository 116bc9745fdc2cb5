#version 460
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
// The example engine's own animation pass, writing where libroma reads the scene's
// positions (roma_map_frame_desc.gpu_positions): the room at rest, the character's
// vertices from libroma's skinning (roma_animator) placed in the room, and one rigid
// box moved by a translation.
layout(local_size_x = 64) in;

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer RestPositions { float p[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer Positions { float p[]; };

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer SkinnedPositions { float p[]; };

layout(push_constant) uniform Push {
    uvec2 rest;          // 3 floats per vertex
    uvec2 positions;     // 3 floats per vertex
    uvec2 skinned;       // the character's skinned positions (roma_animator_output.positions)
    uint vertex_count;
    uint object_first;   // the moving box's vertices: [object_first, vertex_count)
    uint character_first, character_count;
    vec2 pad;
    vec4 offset;         // the box's translation this frame
    vec4 placement;      // the character's: xyz offset, w scale
} pc;

void main()
{
    uint v = gl_GlobalInvocationID.x;
    if (v >= pc.vertex_count)
        return;
    vec3 p = vec3(RestPositions(pc.rest).p[3u * v], RestPositions(pc.rest).p[3u * v + 1u],
                  RestPositions(pc.rest).p[3u * v + 2u]);
    if (v >= pc.object_first) {
        p += pc.offset.xyz;
    } else if (v >= pc.character_first && v < pc.character_first + pc.character_count) {
        uint c = v - pc.character_first;
        SkinnedPositions s = SkinnedPositions(pc.skinned);
        p = vec3(s.p[3u * c], s.p[3u * c + 1u], s.p[3u * c + 2u]) * pc.placement.w + pc.placement.xyz;
    }
    Positions(pc.positions).p[3u * v] = p.x;
    Positions(pc.positions).p[3u * v + 1u] = p.y;
    Positions(pc.positions).p[3u * v + 2u] = p.z;
}
