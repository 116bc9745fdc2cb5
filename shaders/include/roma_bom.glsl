// BOM rasterization, shared by voxelize/bom.vert and voxelize/bom.frag.
//
// Projection of draw `axis` (cyclic, so the 2D cross product of projected edges
// is exactly the 3D normal's component along the axis):
//   axis 0: pixel (u, v) = grid (y, z), depth = x
//   axis 1: pixel (u, v) = grid (z, x), depth = y
//   axis 2: pixel (u, v) = grid (x, y), depth = z   (the BOM's own texel layout)
// Grid coordinates: g = (p - origin) * inv_cell, in cells; cell k owns [k, k+1).
#ifndef ROMA_BOM_GLSL
#define ROMA_BOM_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "roma_shared.h"


layout(push_constant, std430) uniform RomaBomPushBlock { roma_bom_push pc; };

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer RomaBomParams {
    roma_grid_params grid;
};

// World-axis grid coordinates -> (u, v, depth) of the projection along `axis`.
vec3 roma_bom_project(vec3 g, uint axis)
{
    return axis == 0u ? g.yzx : (axis == 1u ? g.zxy : g);
}

#endif // ROMA_BOM_GLSL
