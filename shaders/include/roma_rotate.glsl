// Rotation shaders (rotate/*.comp): push constants, bindings and the sample expression
// they share. Buffers are bound, not reached by address: on CPU devices address-based
// loads run one lane at a time.
#ifndef ROMA_ROTATE_GLSL
#define ROMA_ROTATE_GLSL

#include "roma_shared.h"

layout(push_constant) uniform Push { roma_rotate_push pc; };

layout(std430, set = 0, binding = ROMA_ROTATE_BINDING_BOM) readonly buffer RomaRotateBom { uint bom[]; };
layout(std430, set = 0, binding = ROMA_ROTATE_BINDING_MAPS) buffer RomaRotateMaps { uint maps[]; };
layout(std430, set = 0, binding = ROMA_ROTATE_BINDING_CELLS) buffer RomaRotateCells {
    roma_rotate_cells list_header;
    uint cells[];        // x | y << 8 | z << 16
};
layout(std140, set = 0, binding = ROMA_ROTATE_BINDING_PARAMS) uniform RomaRotateParams {
    roma_grid_params grids[ROMA_MAX_LEVELS];
    roma_map_frame frames[ROMA_MAX_ANGULAR * ROMA_MAX_ANGULAR];
};

// The cascade level this dispatch rotates: its grid; its BOM's first word (its maps' is
// grid.level.w, its first frame grid.level.z).
roma_grid_params roma_rotate_grid() { return grids[pc.config.w]; }
uint roma_rotate_bom_base(roma_grid_params g) { return g.level.x * g.dims.x * g.dims.x * g.dims.y; }

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
