#include "effects/surface_cells.h"

#include <math.h>
#include <string.h>

#include "effects/lit_record.h"
#include "map/map_internal.h"
#include "roma_shared.h"
#include "util/log.h"

/* The voxelizer's bindings: positions, indices, the cells (its BOM binding), the tile queue. */
static const VkDescriptorType cell_types[ROMA_VOXELIZE_BINDINGS] = {
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};

roma_result roma_surface_cells_create(roma_context *ctx, uint32_t resolution, uint32_t layers,
                                      roma_surface_cells *out)
{
    memset(out, 0, sizeof *out);
    if (!ctx || resolution == 0 || resolution > 256 || layers < ROMA_SURFACE_LAYERS_LOWEST ||
        layers > ROMA_SURFACE_LAYERS_COUNTS)
        return ROMA_ERROR_INVALID_ARGUMENT;
    out->ctx = ctx;
    out->resolution = resolution;
    out->layers = layers;
    const VkDeviceSize layer = (VkDeviceSize)resolution * resolution * resolution * sizeof(uint32_t);
    const VkDeviceSize bytes = (layers >= ROMA_SURFACE_LAYERS_TWO ? 2 : 1) * layer;
    roma_result r = roma_buffer_create(ctx, bytes,
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                           VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                       ROMA_MEMORY_DEVICE, &out->cells); /* (a source for the tests' read-back) */
    const VkDeviceSize blocks_side = (resolution + ROMA_SURFACE_BLOCK - 1) / ROMA_SURFACE_BLOCK;
    const VkDeviceSize supers_side = (resolution + ROMA_SURFACE_SUPER - 1) / ROMA_SURFACE_SUPER;
    const VkDeviceSize third = layer + (layers == ROMA_SURFACE_LAYERS_COUNTS
                                            ? (blocks_side * blocks_side * blocks_side +
                                               supers_side * supers_side * supers_side) * sizeof(uint32_t)
                                            : 0);
    if (r == ROMA_SUCCESS && layers > ROMA_SURFACE_LAYERS_TWO)
        r = roma_buffer_create(ctx, third,
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                               ROMA_MEMORY_DEVICE, &out->third_cells);
    if (r == ROMA_SUCCESS)
        r = roma_tile_queue_create(ctx, resolution, &out->queue);
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create_typed(ctx, "surface_cells.comp", cell_types, ROMA_VOXELIZE_BINDINGS,
                                               sizeof(roma_voxelize_push), &out->triangles);
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create_typed(ctx, "surface_cells_tiles.comp", cell_types, ROMA_VOXELIZE_BINDINGS,
                                               sizeof(roma_voxelize_push), &out->tiles);
    if (r != ROMA_SUCCESS)
        roma_surface_cells_destroy(out);
    return r;
}

void roma_surface_cells_destroy(roma_surface_cells *cells)
{
    if (cells->ctx) {
        for (uint32_t s = 0; s < ROMA_MAX_FRAMES_IN_FLIGHT; ++s)
            roma_descriptor_set_destroy(cells->ctx, &cells->sets[s]);
        roma_compute_pipeline_destroy(cells->ctx, &cells->tiles);
        roma_compute_pipeline_destroy(cells->ctx, &cells->triangles);
        roma_tile_queue_destroy(cells->ctx, &cells->queue);
        roma_buffer_destroy(cells->ctx, &cells->cells);
        roma_buffer_destroy(cells->ctx, &cells->third_cells);
    }
    memset(cells, 0, sizeof *cells);
}

roma_result roma_surface_cells_place(roma_surface_cells *cells, const float bounds_min[3], const float bounds_max[3])
{
    float extent = 0.0f, centre[3];
    for (int k = 0; k < 3; ++k) {
        extent = fmaxf(extent, bounds_max[k] - bounds_min[k]);
        centre[k] = 0.5f * (bounds_min[k] + bounds_max[k]);
    }
    if (!(extent > 0.0f) || !isfinite(extent) || !isfinite(centre[0] + centre[1] + centre[2]))
        return roma_fail(&cells->ctx->logger, ROMA_ERROR_INVALID_SCENE, "surface grid: the bounds are empty");
    cells->cell = extent * 1.04f / (float)cells->resolution;
    for (int k = 0; k < 3; ++k)
        cells->origin[k] = centre[k] - 0.5f * (float)cells->resolution * cells->cell;
    return ROMA_SUCCESS;
}

roma_result roma_surface_cells_record(roma_surface_cells *cells, VkCommandBuffer cmd, uint32_t slot,
                                      const roma_surface_geometry *geometry)
{
    roma_context *ctx = cells->ctx;
    if (slot >= ROMA_MAX_FRAMES_IN_FLIGHT)
        return ROMA_ERROR_INVALID_ARGUMENT;
    roma_descriptor_set *set = &cells->sets[slot];
    if (!set->set) {
        roma_result r = roma_descriptor_set_create(ctx, &cells->triangles, cell_types, ROMA_VOXELIZE_BINDINGS, set);
        if (r != ROMA_SUCCESS)
            return r;
    }
    roma_descriptor_write_buffer(ctx, set, ROMA_VOXELIZE_BINDING_POSITIONS, cell_types[0], geometry->positions);
    roma_descriptor_write_buffer(ctx, set, ROMA_VOXELIZE_BINDING_INDICES, cell_types[1], geometry->indices);
    roma_descriptor_write_buffer(ctx, set, ROMA_VOXELIZE_BINDING_BOM, cell_types[2], cells->cells.buffer);
    roma_descriptor_write_buffer(ctx, set, ROMA_VOXELIZE_BINDING_QUEUE, cell_types[3], cells->queue.buffer.buffer);

    /* Earlier reads of the grid (the passes of frames before) and of the queue (the last
     * build's indirect dispatch) finish, and the last build's writes are made available,
     * before they are cleared. */
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                            VK_ACCESS_2_TRANSFER_WRITE_BIT);
    const VkDeviceSize layer = (VkDeviceSize)cells->resolution * cells->resolution * cells->resolution * 4;
    vkCmdFillBuffer(cmd, cells->cells.buffer, 0, layer, ROMA_GBUFFER_NO_TRIANGLE);
    if (cells->layers >= ROMA_SURFACE_LAYERS_TWO)
        vkCmdFillBuffer(cmd, cells->cells.buffer, layer, layer, 0);
    if (cells->layers > ROMA_SURFACE_LAYERS_TWO)
        vkCmdFillBuffer(cmd, cells->third_cells.buffer, 0, VK_WHOLE_SIZE, /* and COUNTS' (super-)blocks */
                        cells->layers == ROMA_SURFACE_LAYERS_COUNTS ? 0u : ROMA_GBUFFER_NO_TRIANGLE);
    roma_tile_queue_record_reset(&cells->queue, cmd);
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    roma_voxelize_push push;
    memset(&push, 0, sizeof push);
    for (int k = 0; k < 3; ++k)
        push.grid.origin[k] = cells->origin[k];
    push.grid.origin[3] = cells->cell;
    push.grid.inv_cell[0] = 1.0f / cells->cell;
    push.grid.dims[0] = cells->resolution;
    push.config[0] = geometry->triangle_count;
    push.config[1] = cells->queue.capacity;
    push.runs[0][0] = (uint32_t)geometry->emitter_bits;
    push.runs[0][1] = (uint32_t)(geometry->emitter_bits >> 32);
    push.runs[0][2] = geometry->emitter_bits ? geometry->emitter_triangles : 0;
    push.runs[0][3] = cells->layers;
    push.runs[1][0] = (uint32_t)cells->third_cells.address; /* 0: no third layer */
    push.runs[1][1] = (uint32_t)(cells->third_cells.address >> 32);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cells->triangles.layout, 0, 1, &set->set, 0, NULL);
    vkCmdPushConstants(cmd, cells->triangles.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    roma_tile_queue_record_passes(&cells->queue, cmd, cells->triangles.pipeline, cells->tiles.pipeline,
                                  geometry->triangle_count);
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    return ROMA_SUCCESS;
}

roma_result roma_surface_cells_follow(roma_surface_cells *cells, roma_context *ctx, uint32_t resolution,
                                      uint32_t layers, VkCommandBuffer cmd, uint32_t slot, const roma_map *map,
                                      const roma_light_data *emitters, const roma_logger *log, const char *name)
{
    /* A count of two or less says the two layers hold a cell's every triangle only where no
     * area light is ranked after the walls (the second layer's). */
    if (layers == ROMA_SURFACE_LAYERS_COUNTS && emitters && emitters->emitter_count)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "%s: a surface grid of counts ranks no area lights", name);
    if (cells->ctx && cells->version == map->geometry_version)
        return ROMA_SUCCESS;
    roma_result r = ROMA_SUCCESS;
    if (!cells->ctx)
        r = roma_surface_cells_create(ctx, resolution, layers, cells);
    if (r == ROMA_SUCCESS)
        r = roma_surface_cells_place(cells, map->volume_min, map->volume_max);
    const int ranked = emitters && emitters->emitter_count;
    const roma_surface_geometry g = {map->positions.buffer, map->indices.buffer, map->total_triangles,
                                     ranked ? emitters->bits.device.address : 0, ranked ? emitters->bit_triangles : 0};
    if (r == ROMA_SUCCESS)
        r = roma_surface_cells_record(cells, cmd, slot, &g);
    if (r != ROMA_SUCCESS) {
        cells->version = 0; /* whatever was placed or recorded, build it again next time */
        return roma_fail(log, r, "%s: cannot build the surface grid", name);
    }
    cells->version = map->geometry_version;
    return ROMA_SUCCESS;
}

roma_surface_grid roma_surface_cells_view(const roma_surface_cells *cells, const roma_map *map)
{
    return (roma_surface_grid){
        .cells = cells->cells.address, .indices = map->indices.address, .positions = map->positions.address,
        .third_cells = cells->third_cells.address,
        .grid = {cells->origin[0], cells->origin[1], cells->origin[2], cells->cell},
        .config = {cells->resolution, cells->layers, 0, 0},
    };
}

roma_result roma_surface_cells_follow_record(roma_surface_cells *cells, roma_upload *record, roma_context *ctx,
                                             uint32_t resolution, uint32_t layers, VkCommandBuffer cmd, uint32_t slot,
                                             const roma_map *map, const roma_light_data *emitters,
                                             const roma_logger *log, const char *name)
{
    roma_result r = roma_lit_slot_buffer(ctx, record, sizeof(roma_surface_grid));
    if (r == ROMA_SUCCESS)
        r = roma_surface_cells_follow(cells, ctx, resolution, layers, cmd, slot, map, emitters, log, name);
    if (r != ROMA_SUCCESS)
        return r;
    const roma_surface_grid view = roma_surface_cells_view(cells, map);
    memcpy(roma_upload_write(record, sizeof view), &view, sizeof view);
    return ROMA_SUCCESS;
}
