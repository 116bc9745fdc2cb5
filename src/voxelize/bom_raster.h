/* BOM rasterization (internal): the base occupancy map is rasterized with a
 * graphics pipeline that has no attachments. Triangles are pulled by buffer
 * address in the vertex shader (shaders/voxelize/bom.vert) and the fragment shader
 * (bom.frag) sets the BOM bits of every cell its pixel column shares with the
 * triangle, with atomicOr.
 *
 * Projections (one draw each, cyclic so that the projected area keeps the sign
 * of the normal component): axis 0 draws grid (y, z) as pixel (u, v) with depth
 * x; axis 1 draws (z, x) with depth y; axis 2 draws (x, y) with depth z.
 *
 * What gets marked: cells own half-open boxes [k, k+1)^3 in grid units
 * (g = (p - origin) * inv_cell). In a draw, a fragment marks the cells of its
 * pixel column that the triangle overlaps inside the pixel square: the depth
 * range of (triangle clipped to the square), computed exactly from edge/square
 * crossings and square corners inside the triangle. (The plane-over-the-pixel
 * range d +- 0.5 fwidth(d) was measured to mark cells up to many cells away from
 * the surface for steep triangles in UNION3.)
 *  - default: standard rasterization, so a column gets marked only where the
 *    triangle covers its pixel centre; cells the surface crosses without covering
 *    a centre in any draw are missed (edges, thin or small parts);
 *  - ROMA_BOM_FLAG_CONSERVATIVE in push->config[3]: the vertex shader grows each
 *    projected triangle by half a pixel (edges moved out by the pixel square's
 *    support) and the fragment shader drops pixels the real triangle does not
 *    touch: the result is the exact voxelization up to float ties, in either mode.
 * Zero-area triangles (sine of the edge angle below 1e-6) mark nothing. In
 * ROMA_BOM_MODE_UNION3 a triangle is drawn along each axis where its projected area is
 * at least 1e-3 of its area; in ROMA_BOM_MODE_DOMINANT only along its dominant normal
 * axis (ties: lowest axis). Geometry outside the grid writes nothing. */
#ifndef ROMA_BOM_RASTER_H
#define ROMA_BOM_RASTER_H

#include <vulkan/vulkan.h>

#include "roma/context.h"
#include "roma_shared.h"


typedef struct roma_bom_raster roma_bom_raster;

roma_result roma_bom_raster_create(roma_context *ctx, roma_bom_raster **out);
/* Accepts NULL. The caller makes sure no recorded use is still executing. */
void roma_bom_raster_destroy(roma_bom_raster *raster);

/* Records into cmd (outside any render pass):
 *  1. a barrier: earlier shader/transfer accesses of the BOM complete before the
 *     clear, and earlier transfer/compute writes (geometry uploads, skinning)
 *     are visible to the raster's vertex and fragment shader reads;
 *  2. vkCmdFillBuffer(bom_buffer, 0, bom_bytes, 0) and a barrier;
 *  3. three draws of 3 * triangle_count vertices with dynamic rendering and no
 *     attachments (render area and viewport RES x RES), one per axis;
 *  4. a barrier making the BOM writes visible to compute-shader reads/writes and
 *     to transfer reads.
 * push->positions (float4 per vertex), indices (3 uint per triangle), bom and
 * params (roma_grid_params, dims.x == resolution, dims.y == resolution / 32) are
 * buffer device addresses; config.x is set per draw here; config.y is the
 * roma_bom_mode; config.z the triangle count (0: clear only); config.w the
 * flags (ROMA_BOM_FLAG_CONSERVATIVE, others must be 0). Indices must be
 * in range for positions (not checked on the GPU). bom_buffer (TRANSFER_DST
 * usage) is the buffer behind push->bom, at least bom_bytes >= RES^3 / 8 bytes
 * from offset 0 (a multiple of 4). resolution: 32..256, a multiple of 32.
 * Host writes to params must happen before submission. */
roma_result roma_bom_raster_record(roma_bom_raster *raster, VkCommandBuffer cmd,
                                   const roma_bom_push *push, VkBuffer bom_buffer,
                                   VkDeviceSize bom_bytes, uint32_t resolution);

#endif /* ROMA_BOM_RASTER_H */
