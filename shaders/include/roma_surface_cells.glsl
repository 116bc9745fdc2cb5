// The surface grid's build (src/effects/surface_cells.h), shared by
// effects/surface_cells.comp (one invocation per triangle) and
// effects/surface_cells_tiles.comp (one per queued tile of a large triangle): a
// triangle's key is written with atomicMin into every cell it overlaps (the exact
// voxelizer's test), so that a cell shared by several triangles holds the lowest key
// whatever the order the invocations ran in. The key is the index, with
// ROMA_SURFACE_EMITTER set for an area light's triangle: a wall and a lamp in the same cells
// leave the wall there, whichever comes first in the scene (a light's end looks for the
// walls; its own plane it skips). The voxelizer's BOM binding holds the cells, one uint
// each, (z * RES + y) * RES + x, and from two layers on (runs[0].w: ROMA_SURFACE_LAYERS_*) the
// highest index + 1 of a triangle that is not an area light in each after them (both halves of
// a ceiling's quad where a lamp shares its cells); a third layer, in a buffer of its own at
// runs[1].xy, holds the lowest area light's key in each (EMITTERS: a lamp whose cells a ceiling
// shares, which the first layer ranks after the ceiling) or counts the triangles that overlap
// each (COUNTS: where the two layers hold all of them; then a flag per block of cells,
// ROMA_SURFACE_BLOCK, and per super-block, ROMA_SURFACE_SUPER); the push's runs[0].xy the
// address of the emitters' bits.
#ifndef ROMA_SURFACE_CELLS_GLSL
#define ROMA_SURFACE_CELLS_GLSL

#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "roma_voxelize.glsl"

layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer RomaEmitterBits { uint w[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer RomaThirdCells { uint u[]; };

// Triangle tri's key (the emitters' bits: runs[0].xy, covering runs[0].z triangles).
uint roma_surface_key(uint tri)
{
    bool emitter = tri < pc.runs[0].z && (RomaEmitterBits(pc.runs[0].xy).w[tri >> 5u] & (1u << (tri & 31u))) != 0u;
    return emitter ? tri | ROMA_SURFACE_EMITTER : tri;
}

// The cells of columns [lo.x, hi.x] x [lo.y, hi.y] of the triangle's footprint.
void roma_surface_columns(roma_vox_triangle t, uint tri, ivec2 lo, ivec2 hi, int res)
{
    uint key = roma_surface_key(tri);
    for (int iv = lo.y; iv <= hi.y; ++iv) {
        ROMA_LOOP_TICK();
        for (int iu = lo.x; iu <= hi.x; ++iu) {
            ROMA_LOOP_TICK();
            ivec2 span = roma_vox_column_span(t, iu, iv);
            for (int k = span.x; k <= span.y; ++k) {
                ROMA_LOOP_TICK();
                ivec3 c = ivec3(iu, iv, k);
                if (!roma_vox_overlaps(t, c))
                    continue;
                ivec3 w = roma_vox_from_columns(c, t.a);
                uint cell = (uint(w.z) * uint(res) + uint(w.y)) * uint(res) + uint(w.x);
                atomicMin(bom[cell], key);
                if (pc.runs[0].w >= ROMA_SURFACE_LAYERS_TWO && key < ROMA_SURFACE_EMITTER) // the highest wall's + 1
                    atomicMax(bom[uint(res * res * res) + cell], key + 1u);
                if (pc.runs[0].w == ROMA_SURFACE_LAYERS_EMITTERS && key >= ROMA_SURFACE_EMITTER) // the lowest lamp's
                    atomicMin(RomaThirdCells(pc.runs[1].xy).u[cell], key);
                else if (pc.runs[0].w == ROMA_SURFACE_LAYERS_COUNTS &&
                         atomicAdd(RomaThirdCells(pc.runs[1].xy).u[cell], 1u) == 0u) { // the cell's block holds one
                    uint side = (uint(res) + ROMA_SURFACE_BLOCK - 1u) / ROMA_SURFACE_BLOCK;
                    uvec3 b = uvec3(w) / ROMA_SURFACE_BLOCK;
                    uint blocks = uint(res * res * res);
                    if (atomicOr(RomaThirdCells(pc.runs[1].xy).u[blocks + (b.z * side + b.y) * side + b.x], 1u) == 0u) {
                        // and the first of the block's to flag it flags its super-block
                        uint supers = blocks + side * side * side;
                        uint super_side = (uint(res) + ROMA_SURFACE_SUPER - 1u) / ROMA_SURFACE_SUPER;
                        uvec3 s = uvec3(w) / ROMA_SURFACE_SUPER;
                        atomicOr(RomaThirdCells(pc.runs[1].xy).u[supers + (s.z * super_side + s.y) * super_side + s.x], 1u);
                    }
                }
            }
        }
    }
}

#endif // ROMA_SURFACE_CELLS_GLSL
