// Rotation shaders (rotate/*.comp): push constants and the buffers they share.
#ifndef ROMA_ROTATE_GLSL
#define ROMA_ROTATE_GLSL

#include "roma_trace.glsl"

layout(push_constant) uniform Push { roma_rotate_push pc; };

layout(buffer_reference, std430, buffer_reference_align = 4) buffer RomaWordsOut { uint w[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer RomaRotateCells {
    roma_rotate_cells header;
    uint cells[];        // x | y << 8 | z << 16
};

// The BOM coordinates of sample h of map cell (x, y, j): the one float expression
// both rotation paths evaluate (so that they agree bit for bit).
vec3 roma_rotate_sample(roma_map_frame f, uint x, uint y, uint j, uint h)
{
    float mx = float(x) + 0.5, my = float(y) + 0.5;
    float mz = float(j) + (float(h) + 0.5) / float(ROMA_ROTATE_SAMPLES);
    precise vec3 b = ((f.map_to_bom_0.xyz * mx + f.map_to_bom_1.xyz * my) + f.map_to_bom_2.xyz * mz)
                     + f.map_to_bom_3.xyz;
    return b;
}

#endif // ROMA_ROTATE_GLSL
