/* roma_map: owns the GPU buffers of one ROMA and records its build (BOM
 * rasterization + rotation) and batch traces. */
#include "roma/map.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "voxelize/bom_raster.h"
#include "voxelize/bom_voxelize.h"
#include "rotate/directions.h"
#include "map/level_runs.h"
#include "map/map_internal.h"
#include "rotate/map_params.h"
#include "roma/sampling.h"

static int valid_resolution(uint32_t r)
{
    return r == 32 || r == 64 || r == 128 || r == 256;
}

static void scene_bounds(const float *positions, const uint32_t *indices, uint32_t triangle_count,
                         float bmin[3], float bmax[3])
{
    for (int i = 0; i < 3; ++i) {
        bmin[i] = INFINITY;
        bmax[i] = -INFINITY;
    }
    for (uint64_t i = 0; i < 3ull * triangle_count; ++i) {
        const float *p = positions + 3ull * indices[i];
        for (int a = 0; a < 3; ++a) {
            bmin[a] = fminf(bmin[a], p[a]);
            bmax[a] = fmaxf(bmax[a], p[a]);
        }
    }
}

/* Refuses scene bounds the grid's float arithmetic cannot handle (map_params.h). */
static roma_result check_bounds(const roma_logger *log, const float bmin[3], const float bmax[3],
                                uint32_t res, float margin_cells, const char *fn)
{
    switch (roma_grid_check(bmin, bmax, res, margin_cells)) {
    case ROMA_GRID_OK:
        return ROMA_SUCCESS;
    case ROMA_GRID_EMPTY:
        return roma_fail(log, ROMA_ERROR_INVALID_SCENE, "%s: the scene bounds are empty or not finite", fn);
    case ROMA_GRID_TOO_LARGE:
        return roma_fail(log, ROMA_ERROR_INVALID_SCENE,
                         "%s: the scene reaches (%g, %g, %g)-(%g, %g, %g); the grid must stay within "
                         "+-%g world units", fn, (double)bmin[0], (double)bmin[1], (double)bmin[2],
                         (double)bmax[0], (double)bmax[1], (double)bmax[2], ROMA_GRID_MAX_COORDINATE);
    case ROMA_GRID_TOO_SMALL:
        break;
    }
    return roma_fail(log, ROMA_ERROR_INVALID_SCENE,
                     "%s: the scene is too small: cells of a RES %u grid around it would be under %g world "
                     "units", fn, res, ROMA_GRID_MIN_CELL);
}

/* Host positions into the staging buffer of `slot` (made on first use), as float4, in
 * one pass that also refuses non-finite values and takes the bounds of the vertices
 * (the host's whole per-frame cost for new positions). Nothing reads the staging
 * before a build records its copy, so a refused call leaves nothing behind. */
static roma_result stage_positions(roma_map *map, uint32_t slot, const float *positions, float bmin[3],
                                   float bmax[3])
{
    roma_buffer *staging = &map->position_staging[slot];
    if (!staging->buffer) {
        roma_result r = roma_buffer_create(map->ctx, 16ull * map->vertex_count, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                           ROMA_MEMORY_UPLOAD, staging);
        if (r != ROMA_SUCCESS)
            return r;
    }
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    float *dst = staging->mapped;
    int finite = 1;
    for (uint32_t v = 0; v < map->vertex_count; ++v) {
        for (int a = 0; a < 3; ++a) {
            float x = positions[3 * v + a];
            finite &= x - x == 0.0f; /* false for NaN and infinities, without a branch */
            lo[a] = x < lo[a] ? x : lo[a];
            hi[a] = x > hi[a] ? x : hi[a];
            dst[4 * v + a] = x;
        }
        dst[4 * v + 3] = 1.0f;
    }
    if (!finite) {
        uint64_t i = 0;
        while (isfinite(positions[i]))
            ++i;
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_SCENE, "roma_map_record_build: vertex %llu is not finite",
                         (unsigned long long)(i / 3));
    }
    memcpy(bmin, lo, sizeof lo);
    memcpy(bmax, hi, sizeof hi);
    return ROMA_SUCCESS;
}

static void record_copy_staged(roma_map *map, VkCommandBuffer cmd, uint32_t slot)
{
    VkBufferCopy copy = {0, 0, 16ull * map->vertex_count};
    vkCmdCopyBuffer(cmd, map->position_staging[slot].buffer, map->positions.buffer, 1, &copy);
}

/* The scene's first positions, before any build: staged in slot 0 and copied with a
 * submission this call waits for, so slot 0 is free again when it returns. */
static roma_result upload_initial_positions(roma_map *map, const float *positions)
{
    float bmin[3], bmax[3];
    roma_result r = stage_positions(map, 0, positions, bmin, bmax);
    VkCommandBuffer cmd;
    if (r == ROMA_SUCCESS)
        r = roma_begin_one_shot(map->ctx, &cmd);
    if (r != ROMA_SUCCESS)
        return r;
    record_copy_staged(map, cmd, 0);
    r = roma_submit_one_shot(map->ctx, cmd);
    scene_bounds(positions, map->indices_host, map->triangle_count, map->scene_min, map->scene_max);
    return r;
}

static const VkDescriptorType staged_types[ROMA_TRACE_STAGED_BINDINGS] = {
    VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER,
    VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER};

/* The batch-trace pipeline of `mode` (staged: roma_map_trace's own buffers), made on
 * first use. */
static roma_result make_trace_pipeline(roma_map *map, int staged, roma_trace_mode mode)
{
    roma_compute_pipeline *p = staged ? &map->trace_staged[mode] : &map->trace[mode];
    if (p->pipeline)
        return ROMA_SUCCESS;
    const uint32_t constant = (uint32_t)mode;
    /* trace.comp reaches everything by address: no set. The cascade code only for a map of
     * several levels. */
    return roma_compute_pipeline_create_flags(map->ctx, staged ? "trace_staged.comp" : "trace.comp", staged_types,
                                              staged ? ROMA_TRACE_STAGED_BINDINGS : 0, sizeof(roma_trace_push),
                                              &constant, 1, map->levels > 1 ? ROMA_PIPELINE_CASCADES : 0, p);
}

/* Rotation bindings: the parameters as a uniform buffer (every invocation of a workgroup
 * reads the same frame; uniform loads are the cheapest on every device). */
static const VkDescriptorType rotate_types[ROMA_ROTATE_BINDINGS] = {
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
    VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER};

roma_result roma_map_create(roma_context *ctx, const roma_map_desc *desc_in, const roma_scene *scene,
                            roma_map **out)
{
    roma_map_desc desc = desc_in ? *desc_in : (roma_map_desc){0};
    const roma_logger *log = desc.logger.fn ? &desc.logger : (ctx ? &ctx->logger : NULL);
    if (!out)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_create: out_map is NULL");
    *out = NULL;
    if (!ctx || !scene)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_create: context and scene are required");
    uint32_t preset_res = 0, preset_angular = 0;
    if (roma_preset_map_settings(desc.preset, &preset_res, &preset_angular) != ROMA_SUCCESS)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_create: unknown preset %d", (int)desc.preset);
    if (desc.resolution == 0)
        desc.resolution = preset_res;
    if (desc.angular == 0)
        desc.angular = preset_angular;
    if (desc.margin_cells == 0.0f)
        desc.margin_cells = 1.0f;
    if (!valid_resolution(desc.resolution))
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_map_create: resolution %u is not one of 32, 64, 128, 256", desc.resolution);
    if (desc.angular > ROMA_MAX_ANGULAR)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_map_create: angular resolution %u is outside [1, %u]", desc.angular,
                         ROMA_MAX_ANGULAR);
    if ((unsigned)desc.bom_mode > ROMA_BOM_CONSERVATIVE)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_create: unknown bom_mode %d", (int)desc.bom_mode);
    if (desc.frames_in_flight == 0)
        desc.frames_in_flight = 2;
    if (desc.frames_in_flight > ROMA_MAX_FRAMES_IN_FLIGHT)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_create: frames_in_flight %u is outside [1, %u]",
                         desc.frames_in_flight, ROMA_MAX_FRAMES_IN_FLIGHT);
    if (!(desc.margin_cells >= 0.5f) || desc.margin_cells > desc.resolution / 8.0f)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_map_create: margin_cells %g must be in [0.5, RES/8] (jitter needs half a cell)",
                         (double)desc.margin_cells);
    if (desc.cascades == 0)
        desc.cascades = 1;
    if (desc.cascades > ROMA_MAX_LEVELS || desc.cascades * desc.angular * desc.angular > 256u)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_map_create: %u cascade levels of %u x %u maps: at most %u levels and 256 maps in all",
                         desc.cascades, desc.angular, desc.angular, ROMA_MAX_LEVELS);
    if (desc.cascades > 1 && desc.bom_mode != ROMA_BOM_EXACT)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_map_create: cascade levels need the exact BOM mode (bom_mode 0)");
    roma_scene_view sv;
    roma_scene_get_view(scene, &sv);
    roma_result bounds = check_bounds(log, sv.bounds_min, sv.bounds_max, desc.resolution, desc.margin_cells,
                                      "roma_map_create");
    if (bounds != ROMA_SUCCESS)
        return bounds;

    /* Passes read the maps as a texel buffer (roma/trace_descriptors.glsl). */
    const uint64_t map_words = (uint64_t)desc.resolution * desc.resolution * (desc.resolution / 32) *
                               desc.angular * desc.angular * desc.cascades;
    if (map_words > ctx->properties.limits.maxTexelBufferElements)
        return roma_fail(log, ROMA_ERROR_UNSUPPORTED,
                         "roma_map_create: RES %u with %u x %u maps in %u levels needs %llu words, more than this "
                         "device's maxTexelBufferElements (%u)", desc.resolution, desc.angular, desc.angular,
                         desc.cascades, (unsigned long long)map_words, ctx->properties.limits.maxTexelBufferElements);
    /* ...and the rotation writes them as one storage buffer (128 MiB at most on lavapipe). */
    if (map_words * 4 > ctx->properties.limits.maxStorageBufferRange)
        return roma_fail(log, ROMA_ERROR_UNSUPPORTED,
                         "roma_map_create: RES %u with %u x %u maps in %u levels needs %llu bytes, more than this "
                         "device's maxStorageBufferRange (%u)", desc.resolution, desc.angular, desc.angular,
                         desc.cascades, (unsigned long long)(map_words * 4),
                         ctx->properties.limits.maxStorageBufferRange);
    roma_map *map = calloc(1, sizeof *map);
    uint32_t *indices = malloc(sizeof(uint32_t) * 3 * (size_t)sv.triangle_count);
    /* This frame's frames, then those the maps were last built from. */
    const size_t frame_count = (size_t)desc.angular * desc.angular * desc.cascades;
    roma_map_frame *frames = calloc(2 * frame_count, sizeof *frames);
    if (!map || !indices || !frames) {
        free(map);
        free(indices);
        free(frames);
        return roma_fail(log, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_map_create: out of memory");
    }
    memcpy(indices, sv.indices, sizeof(uint32_t) * 3 * (size_t)sv.triangle_count);
    map->ctx = ctx;
    map->logger = *log;
    map->res = desc.resolution;
    map->words = desc.resolution / 32;
    map->angular = desc.angular;
    map->map_count = desc.angular * desc.angular;
    map->levels = desc.cascades;
    map->bom_mode = desc.bom_mode;
    map->margin_cells = desc.margin_cells;
    map->frames_in_flight = desc.frames_in_flight;
    map->vertex_count = sv.vertex_count;
    map->triangle_count = sv.triangle_count;
    map->total_vertices = sv.vertex_count;
    map->total_triangles = sv.triangle_count;
    map->static_triangles = sv.triangle_count;
    map->live_vertices = sv.vertex_count;
    map->live_triangles = sv.triangle_count;
    map->indices_host = indices;
    map->frames = frames;
    map->built_frames = frames + frame_count;

    const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                       VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    const uint64_t texel_words = (uint64_t)map->res * map->res * map->words;
    /* TRANSFER_SRC: a new layout (instances added or removed) copies the scene's part out. */
    roma_result r = roma_buffer_create(ctx, 16ull * sv.vertex_count,
                                       storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                       ROMA_MEMORY_DEVICE, &map->positions);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, 12ull * sv.triangle_count, storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               ROMA_MEMORY_DEVICE_MAPPED, &map->indices);
    if (r == ROMA_SUCCESS && !map->indices.mapped) { /* copied by the first build */
        r = roma_buffer_create(ctx, 12ull * sv.triangle_count, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, ROMA_MEMORY_UPLOAD,
                               &map->indices_staging);
        map->indices_pending = 1;
    }
    /* UNIFORM_TEXEL: the tracing passes read the BOM through bom_view (faster than storage
     * loads on CPU devices); it is no larger than the maps, so within the same limit. The
     * exact BOM has a slot after the last level: the dynamic instances voxelized alone. */
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, 4 * texel_words * (map->levels + (desc.bom_mode == ROMA_BOM_EXACT)),
                               storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                               VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                               ROMA_MEMORY_DEVICE, &map->bom);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, 4 * texel_words * map->map_count * map->levels,
                               storage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                   VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                               ROMA_MEMORY_DEVICE, &map->maps);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, ROMA_PARAMS_BLOCK_BYTES,
                               storage | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               ROMA_MEMORY_DEVICE, &map->params);
    /* The scatter rotation's cell list: 1/16 of the grid's cells (scenes occupy a few
     * percent); a fuller grid is rotated by the gather instead. */
    map->cell_capacity = (uint32_t)(texel_words * 32 / 16);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, sizeof(roma_rotate_cells) + 4ull * map->cell_capacity,
                               storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               ROMA_MEMORY_DEVICE, &map->cells);
    if (r == ROMA_SUCCESS)
        r = desc.bom_mode == ROMA_BOM_EXACT
                ? roma_bom_voxelizer_create(ctx, map->res, map->positions.buffer, map->indices.buffer,
                                            map->bom.buffer, map->bom.size, &map->voxelizer)
                : roma_bom_raster_create(ctx, &map->raster);
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create(ctx, "gather_positions.comp", 0, sizeof(roma_gather_positions_push),
                                         &map->gather_positions);
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create(ctx, "transform_instances.comp", 0, sizeof(roma_instance_push),
                                         &map->transform_instances);
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create_typed(ctx, "occupied_cells.comp", rotate_types, ROMA_ROTATE_BINDINGS,
                                               sizeof(roma_rotate_push), &map->occupied_cells);
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create_typed(ctx, "rotate_scatter.comp", rotate_types, ROMA_ROTATE_BINDINGS,
                                               sizeof(roma_rotate_push), &map->rotate_scatter);
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create_typed(ctx, "rotate_gather.comp", rotate_types, ROMA_ROTATE_BINDINGS,
                                               sizeof(roma_rotate_push), &map->rotate_gather);
    if (r == ROMA_SUCCESS) {
        /* The three rotation pipelines have the same bindings: one set serves them all. */
        const VkDescriptorType *types = rotate_types;
        r = roma_descriptor_set_create(ctx, &map->occupied_cells, types, ROMA_ROTATE_BINDINGS, &map->rotate_set);
        const VkBuffer buffers[ROMA_ROTATE_BINDINGS] = {map->bom.buffer, map->maps.buffer, map->cells.buffer,
                                                        map->params.buffer};
        for (uint32_t b = 0; r == ROMA_SUCCESS && b < ROMA_ROTATE_BINDINGS; ++b)
            roma_descriptor_write_buffer(ctx, &map->rotate_set, b, types[b], buffers[b]);
    }
    if (r == ROMA_SUCCESS)
        r = make_trace_pipeline(map, 1, ROMA_TRACE_SNAPPED_ANY);
    if (r == ROMA_SUCCESS)
        r = roma_descriptor_set_create(ctx, &map->trace_staged[0], staged_types, ROMA_TRACE_STAGED_BINDINGS,
                                       &map->staged_set);
    /* The set every tracing pass binds (roma/trace_descriptors.glsl), written once. */
    if (r == ROMA_SUCCESS)
        r = roma_buffer_view_create(ctx, map->maps.buffer, VK_FORMAT_R32_UINT, &map->maps_view);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_view_create(ctx, map->bom.buffer, VK_FORMAT_R32_UINT, &map->bom_view);
    if (r == ROMA_SUCCESS)
        r = roma_descriptor_set_create_with_layout(ctx, roma_trace_binding_types, ROMA_TRACE_BINDINGS,
                                                   &map->trace_set);
    for (int i = 0; i < 2 && r == ROMA_SUCCESS; ++i) {
        roma_descriptor_set *set = i == 0 ? &map->trace_set : &map->staged_set;
        roma_descriptor_write_view(ctx, set, ROMA_TRACE_BINDING_MAPS,
                                   roma_trace_binding_types[ROMA_TRACE_BINDING_MAPS], map->maps_view);
        roma_descriptor_write_buffer(ctx, set, ROMA_TRACE_BINDING_PARAMS,
                                     roma_trace_binding_types[ROMA_TRACE_BINDING_PARAMS], map->params.buffer);
    }
    if (r == ROMA_SUCCESS) {
        memcpy(map->indices.mapped ? map->indices.mapped : map->indices_staging.mapped, indices,
               12ull * sv.triangle_count);
        r = upload_initial_positions(map, sv.positions);
    }
    if (r == ROMA_SUCCESS)
        r = roma_map_chunks_create(map, sv.positions);
    if (r != ROMA_SUCCESS) {
        roma_map_destroy(map);
        return r;
    }
    *out = map;
    return ROMA_SUCCESS;
}

void roma_map_destroy(roma_map *map)
{
    if (!map)
        return;
    roma_context *ctx = map->ctx;
    for (int m = 0; m < 4; ++m) {
        roma_compute_pipeline_destroy(ctx, &map->trace[m]);
        roma_compute_pipeline_destroy(ctx, &map->trace_staged[m]);
    }
    roma_descriptor_set_destroy(ctx, &map->rotate_set);
    roma_descriptor_set_destroy(ctx, &map->trace_set);
    roma_descriptor_set_destroy(ctx, &map->staged_set);
    for (int i = 0; i < 2; ++i)
        if (map->staging_views[i])
            vkDestroyBufferView(ctx->device, map->staging_views[i], ctx->allocator);
    if (map->maps_view)
        vkDestroyBufferView(ctx->device, map->maps_view, ctx->allocator);
    if (map->bom_view)
        vkDestroyBufferView(ctx->device, map->bom_view, ctx->allocator);
    roma_compute_pipeline_destroy(ctx, &map->rotate_gather);
    roma_compute_pipeline_destroy(ctx, &map->rotate_scatter);
    roma_compute_pipeline_destroy(ctx, &map->occupied_cells);
    roma_compute_pipeline_destroy(ctx, &map->gather_positions);
    roma_compute_pipeline_destroy(ctx, &map->transform_instances);
    roma_map_instances_release(map, 1);
    for (uint32_t i = 0; i < ROMA_MAX_FRAMES_IN_FLIGHT; ++i)
        roma_buffer_destroy(ctx, &map->position_staging[i]);
    roma_bom_raster_destroy(map->raster);
    roma_bom_voxelizer_destroy(map->voxelizer);
    roma_buffer_destroy(ctx, &map->cells);
    roma_buffer_destroy(ctx, &map->params);
    roma_buffer_destroy(ctx, &map->maps);
    roma_buffer_destroy(ctx, &map->bom);
    roma_buffer_destroy(ctx, &map->static_maps);
    roma_buffer_destroy(ctx, &map->static_bom);
    free(map->restore_regions);
    roma_buffer_destroy(ctx, &map->indices);
    roma_buffer_destroy(ctx, &map->indices_staging);
    roma_buffer_destroy(ctx, &map->positions);
    roma_buffer_destroy(ctx, &map->ray_staging);
    roma_buffer_destroy(ctx, &map->hit_staging);
    roma_buffer_destroy(ctx, &map->ray_device);
    roma_buffer_destroy(ctx, &map->hit_device);
    free(map->indices_host);
    free(map->chunk_boxes);
    free(map->frames);
    free(map);
}

/* Grid placement and candidate frames of this frame (host copies; the build records
 * them into the params buffer). The bounds were checked by the caller. */
/* The cube of cascade level l (edge `edge` before the margin) around `centre`, snapped to
 * the level's own cells: its grid origin is a whole number of cells, so that static
 * geometry falls into the same cells as the centre moves. */
static void place_level(const roma_map *map, uint32_t l, const double centre[3], double edge, const float jitter[3],
                        roma_grid_params *out)
{
    /* The cell size from the edge alone (a cube around the world origin), so that it is the
     * same whatever the centre; then the cube's centre on a cell corner (RES is even). */
    const float lo[3] = {(float)(-0.5 * edge), (float)(-0.5 * edge), (float)(-0.5 * edge)};
    const float hi[3] = {-lo[0], -lo[1], -lo[2]};
    roma_compute_grid(lo, hi, map->res, map->angular, map->margin_cells, NULL, out);
    const double cell = out->origin[3];
    for (int a = 0; a < 3; ++a)
        out->origin[a] = (float)((floor(centre[a] / cell + 0.5) - 0.5 * map->res + jitter[a]) * cell);
    out->level[0] = l;
    out->level[1] = map->levels;
    out->level[2] = l * map->map_count;
    out->level[3] = l * map->map_count * map->res * map->res * map->words;
}

static void compute_frame_params(roma_map *map, const roma_map_frame_desc *frame, const float bmin[3],
                                 const float bmax[3])
{
    float jitter[3] = {0.0f, 0.0f, 0.0f};
    if (frame->jitter_grid)
        for (int i = 0; i < 3; ++i)
            jitter[i] = roma_random(frame->seed, 0x67726964u /* 'grid' */, frame->frame, (uint32_t)i) - 0.5f;
    if (map->levels == 1) {
        roma_compute_grid(bmin, bmax, map->res, map->angular, map->margin_cells, jitter, &map->grids[0]);
    } else {
        /* Nested cubes around the focus, each twice the last's edge. Without a finest edge,
         * the coarsest cube holds the whole volume around the focus: the volume's longest
         * edge for a focus at its centre, more for a focus off it (a camera outside an object
         * or at a level's end), so that nothing is left untraced. That edge moves in steps of
         * a quarter octave, not with the focus, so that a moving camera keeps the cell size
         * (static geometry stays in its cells, unchanged levels are kept) between steps. */
        double centre[3], reach = 0.0, longest = 0.0;
        for (int a = 0; a < 3; ++a) {
            centre[a] = frame->focus ? (double)frame->focus[a] : 0.5 * ((double)bmin[a] + (double)bmax[a]);
            reach = fmax(reach, fmax(centre[a] - (double)bmin[a], (double)bmax[a] - centre[a]));
            longest = fmax(longest, (double)bmax[a] - (double)bmin[a]);
        }
        double coarsest = longest;
        if (2.0 * reach > longest && longest > 0.0)
            coarsest = longest * pow(2.0, ceil(4.0 * log2(2.0 * reach / longest) - 1e-9) / 4.0);
        double edge = frame->finest_extent > 0.0f ? (double)frame->finest_extent
                                                  : coarsest / (double)(1u << (map->levels - 1));
        for (uint32_t l = 0; l < map->levels; ++l, edge *= 2.0)
            place_level(map, l, centre, edge, jitter, &map->grids[l]);
    }
    float dirs[3 * ROMA_MAX_ANGULAR * ROMA_MAX_ANGULAR];
    roma_candidate_directions(map->angular, frame->seed, frame->frame, frame->jitter_directions, dirs);
    for (uint32_t l = 0; l < map->levels; ++l)
        for (uint32_t k = 0; k < map->map_count; ++k)
            roma_compute_map_frame(&map->grids[l], dirs + 3 * k, &map->frames[l * map->map_count + k]);
}

/* The parameters travel in the command buffer (at most 36,912 bytes, under
 * vkCmdUpdateBuffer's 65,536): no host-visible copy can be overwritten while an
 * earlier frame still reads it. */
static void record_frame_params(roma_map *map, VkCommandBuffer cmd)
{
    unsigned char block[ROMA_PARAMS_BLOCK_BYTES];
    const size_t frames_at = sizeof(roma_grid_params) * ROMA_MAX_LEVELS; /* roma/trace_types.h */
    const size_t frames = (size_t)map->map_count * map->levels;
    size_t bytes = frames_at + sizeof(roma_map_frame) * frames;
    memset(block, 0, frames_at);
    memcpy(block, map->grids, sizeof(roma_grid_params) * map->levels);
    memcpy(block + frames_at, map->frames, sizeof(roma_map_frame) * frames);
    vkCmdUpdateBuffer(cmd, map->params.buffer, 0, bytes, block);
}

/* The frame's arguments, checked before anything is recorded or changed. */
static roma_result check_frame(roma_map *map, const roma_map_frame_desc *f)
{
    const char *fn = "roma_map_record_build";
    if (f->slot >= map->frames_in_flight)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT, "%s: slot %u, the map has %u frames in flight",
                         fn, f->slot, map->frames_in_flight);
    if (f->positions && f->gpu_positions)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "%s: positions and gpu_positions are both set; give one", fn);
    if ((f->positions || f->gpu_positions) && f->vertex_count != map->vertex_count)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "%s: %u vertices given, the map was made with %u", fn, f->vertex_count, map->vertex_count);
    if (f->gpu_positions) {
        uint32_t stride = f->gpu_position_stride ? f->gpu_position_stride : 12u;
        if (stride < 12u || stride % 4u)
            return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                             "%s: gpu_position_stride %u must be a multiple of 4 and at least 12", fn, stride);
        if (f->gpu_positions % 4u)
            return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT, "%s: gpu_positions is not 4-byte aligned", fn);
        /* The gather addresses 32-bit words with a 32-bit index (gather_positions.comp). */
        if ((uint64_t)f->vertex_count * stride > ((uint64_t)1 << 34))
            return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                             "%s: %u vertices of %u bytes span more than 16 GiB", fn, f->vertex_count, stride);
        if (!f->volume)
            return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                             "%s: gpu_positions needs a volume (the host cannot see their bounds)", fn);
    }
    if (f->volume)
        for (int a = 0; a < 3; ++a)
            if (!(f->volume->min[a] <= f->volume->max[a]))
                return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                                 "%s: volume min (%g, %g, %g) is not below max (%g, %g, %g)", fn,
                                 (double)f->volume->min[0], (double)f->volume->min[1], (double)f->volume->min[2],
                                 (double)f->volume->max[0], (double)f->volume->max[1], (double)f->volume->max[2]);
    return ROMA_SUCCESS;
}

/* New positions of this frame into the map's positions buffer (after the opening
 * barrier of the build). */
static void record_positions(roma_map *map, VkCommandBuffer cmd, const roma_map_frame_desc *f)
{
    if (f->positions) {
        record_copy_staged(map, cmd, f->slot);
    } else if (f->gpu_positions) {
        uint32_t stride = f->gpu_position_stride ? f->gpu_position_stride : 12u;
        roma_gather_positions_push push = {
            .src = f->gpu_positions, .dst = map->positions.address, .config = {map->vertex_count, stride / 4u, 0, 0}};
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, map->gather_positions.pipeline);
        vkCmdPushConstants(cmd, map->gather_positions.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
        roma_cmd_dispatch_linear(cmd, map->vertex_count, ROMA_GATHER_WORKGROUP_SIZE);
    }
}

/* Compute-shader writes of libroma's passes made visible to the next consumer. */
static void compute_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access)
{
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            dst_stage, dst_access);
}

/* A timer's queries are recorded into the map's command buffers: its pool must live on
 * the map's VkDevice (contexts sharing one device through desc.external may mix). */
static roma_result check_timer(const roma_map *map, const roma_gpu_timer *timer, const char *fn)
{
    const roma_context *owner = roma_gpu_timer_context(timer);
    if (owner && owner->device != map->ctx->device)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "%s: timer was created on another Vulkan device than the map", fn);
    return ROMA_SUCCESS;
}

/* Rotation (roma_shared.h) of cascade level `level`: clear its maps when `clear` (the other
 * levels' are kept), list the occupied cells of BOM slot `source` (the level's own, or the
 * dynamic instances' alone), scatter them into its maps; the gather runs instead, from the
 * level's whole BOM, when the list overflowed. */
static void record_rotation(roma_map *map, VkCommandBuffer cmd, uint32_t level, uint32_t source, int clear,
                            uint32_t first_word, uint32_t word_count)
{
    const uint64_t words = (uint64_t)map->res * map->res * map->words;
    const uint64_t gather_groups = (words * map->map_count + ROMA_ROTATE_WORKGROUP_SIZE - 1) /
                                   ROMA_ROTATE_WORKGROUP_SIZE;
    const uint32_t gather_x = gather_groups < 65535u ? (uint32_t)gather_groups : 65535u;
    const uint32_t gather_y = (uint32_t)((gather_groups + gather_x - 1) / gather_x);
    roma_rotate_push push = {.config = {map->cell_capacity, gather_x, gather_y, level},
                             .source = {source, first_word, word_count, 0}};
    /* WAR against earlier readers of the maps and the list (traces, downloads, the
     * previous build's or level's indirect dispatches). */
    roma_cmd_memory_barrier(cmd,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT |
                                VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    const VkDeviceSize level_bytes = 4 * words * map->map_count;
    if (clear)
        vkCmdFillBuffer(cmd, map->maps.buffer, level * level_bytes, level_bytes, 0);
    const roma_rotate_cells header = {.scatter = {0, map->map_count, 1, 0}, .gather = {0, 0, 1, 0}};
    vkCmdUpdateBuffer(cmd, map->cells.buffer, 0, sizeof header, &header);
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    /* One set layout and push range for the three pipelines: bound once. */
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, map->occupied_cells.layout, 0, 1,
                            &map->rotate_set.set, 0, NULL);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, map->occupied_cells.pipeline);
    vkCmdPushConstants(cmd, map->occupied_cells.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    roma_cmd_dispatch_linear(cmd, word_count, ROMA_ROTATE_WORKGROUP_SIZE);
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                                VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, map->rotate_scatter.pipeline);
    vkCmdDispatchIndirect(cmd, map->cells.buffer, offsetof(roma_rotate_cells, scatter));
    /* Zero workgroups unless the list overflowed (then the scatter did nothing). The
     * barrier is for the cases the GPU cannot know apart in advance: both write the maps. */
    compute_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, map->rotate_gather.pipeline);
    vkCmdDispatchIndirect(cmd, map->cells.buffer, offsetof(roma_rotate_cells, gather));
}

/* Level l's BOM cleared and voxelized from those of triangles 0 .. end - 1 that touch its cube. */
static roma_result voxelize_level(roma_map *map, VkCommandBuffer cmd, uint32_t l, uint32_t end)
{
    roma_triangle_run runs[ROMA_VOXELIZE_RUNS];
    const uint32_t n = roma_map_level_runs(map, l, end, runs);
    for (uint32_t i = 0; i < n; ++i)
        map->triangles_voxelized += runs[i].count;
    return roma_bom_voxelize_record_runs(map->voxelizer, cmd, &map->grids[l], runs, n, 1);
}

/* The BOM of the levels in the mask: exact compute voxelization (each level's part of the
 * buffer) or one of the raster modes (one level). */
static roma_result record_bom(roma_map *map, VkCommandBuffer cmd, uint32_t levels)
{
    roma_result r = ROMA_SUCCESS;
    if (map->voxelizer) {
        for (uint32_t l = 0; l < map->levels && r == ROMA_SUCCESS; ++l)
            if (levels & (1u << l))
                r = voxelize_level(map, cmd, l, map->total_triangles);
        return r;
    }
    if (!(levels & 1u))
        return ROMA_SUCCESS;
    roma_bom_push bom_push = {
        .positions = map->positions.address,
        .indices = map->indices.address,
        .bom = map->bom.address,
        .params = map->params.address,
        .config = {0, map->bom_mode == ROMA_BOM_UNION3 ? ROMA_BOM_MODE_UNION3 : ROMA_BOM_MODE_DOMINANT,
                   map->total_triangles, map->bom_mode == ROMA_BOM_CONSERVATIVE ? ROMA_BOM_FLAG_CONSERVATIVE : 0u},
    };
    map->triangles_voxelized = map->total_triangles;
    return roma_bom_raster_record(map->raster, cmd, &bom_push, map->bom.buffer, map->bom.size, map->res);
}

/* One cascade level's part of the BOM. */
static VkDeviceSize bom_level_bytes(const roma_map *map)
{
    return 4ull * map->res * map->res * map->words;
}

/* The copies of the static geometry's BOM and maps, made once a build has dynamic instances. */
static roma_result make_static_copies(roma_map *map)
{
    if (map->static_maps.buffer)
        return ROMA_SUCCESS;
    const uint64_t texel_words = (uint64_t)map->res * map->res * map->words;
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    roma_result r = roma_buffer_create(map->ctx, 4 * texel_words * map->levels, usage, ROMA_MEMORY_DEVICE,
                                       &map->static_bom);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(map->ctx, 4 * texel_words * map->map_count * map->levels, usage, ROMA_MEMORY_DEVICE,
                               &map->static_maps);
    /* A row of texels per region, at most RES in each map (restore_static), made once here
     * rather than in every build. */
    if (r == ROMA_SUCCESS && !(map->restore_regions = malloc(sizeof *map->restore_regions * map->res * map->map_count)))
        r = roma_fail(&map->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_map_record_build: out of host memory");
    if (r != ROMA_SUCCESS) {
        roma_buffer_destroy(map->ctx, &map->static_bom);
        roma_buffer_destroy(map->ctx, &map->static_maps);
    }
    return r;
}

/* Level l's BOM and maps into the static copies, after its voxelization and rotation. */
static void save_static(roma_map *map, VkCommandBuffer cmd, uint32_t l)
{
    const VkDeviceSize bom_bytes = bom_level_bytes(map), maps_bytes = bom_bytes * map->map_count;
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
    const VkBufferCopy bom = {l * bom_bytes, l * bom_bytes, bom_bytes}, maps = {l * maps_bytes, l * maps_bytes, maps_bytes};
    vkCmdCopyBuffer(cmd, map->bom.buffer, map->static_bom.buffer, 1, &bom);
    vkCmdCopyBuffer(cmd, map->maps.buffer, map->static_maps.buffer, 1, &maps);
}

/* Level l's static part copied back over the box [bmin, bmax] (world) alone: its BOM cells
 * (a cell of margin) and, in each map, the texels whose columns cross the box (two of margin:
 * every map bit a cell in the box can set). */
static void restore_static(roma_map *map, VkCommandBuffer cmd, uint32_t l, const float bmin[3], const float bmax[3])
{
    const roma_grid_params *g = &map->grids[l];
    const int res = (int)map->res;
    const VkDeviceSize word = 4, bom_base = l * bom_level_bytes(map), maps_base = bom_base * map->map_count;
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        lo[a] = (int)fmaxf(floorf((bmin[a] - g->origin[a]) * g->inv_cell[0]) - 1.0f, 0.0f);
        hi[a] = (int)fminf(floorf((bmax[a] - g->origin[a]) * g->inv_cell[0]) + 1.0f, (float)(res - 1));
        if (lo[a] > hi[a])
            return; /* outside the cube: nothing of it was added */
    }
    VkBufferCopy *regions = map->restore_regions;
    uint32_t n = 0;
    for (int y = lo[1]; y <= hi[1]; ++y) {
        const VkDeviceSize at = bom_base + word * ((VkDeviceSize)(y * res + lo[0]) * map->words);
        regions[n++] = (VkBufferCopy){at, at, word * (VkDeviceSize)(hi[0] - lo[0] + 1) * map->words};
    }
    vkCmdCopyBuffer(cmd, map->static_bom.buffer, map->bom.buffer, n, regions);
    n = 0;
    for (uint32_t k = 0; k < map->map_count; ++k) {
        const roma_map_frame *f = &map->frames[l * map->map_count + k];
        const float *to_map[2] = {f->to_map_0, f->to_map_1};
        float mlo[2] = {INFINITY, INFINITY}, mhi[2] = {-INFINITY, -INFINITY};
        for (int c = 0; c < 8; ++c) {
            float p[3];
            for (int a = 0; a < 3; ++a) /* the box's corner, in the grid units the frame takes */
                p[a] = ((c >> a & 1 ? (float)(hi[a] + 1) : (float)lo[a]) * g->origin[3]) * g->inv_cell[1];
            for (int a = 0; a < 2; ++a) {
                const float m = to_map[a][0] * p[0] + to_map[a][1] * p[1] + to_map[a][2] * p[2] + to_map[a][3];
                mlo[a] = fminf(mlo[a], m);
                mhi[a] = fmaxf(mhi[a], m);
            }
        }
        const int x0 = (int)fmaxf(floorf(mlo[0]) - 2.0f, 0.0f), x1 = (int)fminf(floorf(mhi[0]) + 2.0f, (float)(res - 1));
        const int y0 = (int)fmaxf(floorf(mlo[1]) - 2.0f, 0.0f), y1 = (int)fminf(floorf(mhi[1]) + 2.0f, (float)(res - 1));
        for (int y = y0; y <= y1 && x0 <= x1; ++y) {
            const VkDeviceSize at = maps_base + word * ((VkDeviceSize)(((int)k * res + y) * res + x0) * map->words);
            regions[n++] = (VkBufferCopy){at, at, word * (VkDeviceSize)(x1 - x0 + 1) * map->words};
        }
    }
    if (n)
        vkCmdCopyBuffer(cmd, map->static_maps.buffer, map->maps.buffer, n, regions);
}

/* The dynamic instances' triangles added to level l's BOM and maps: voxelized alone into the
 * slot after the last level, whose cells the scatter adds to the maps, and into the level's
 * own BOM (the ray-start walk reads it; the gather, if the list overflows, rotates it whole). */
static roma_result add_dynamic(roma_map *map, VkCommandBuffer cmd, uint32_t l, const float bmin[3],
                               const float bmax[3])
{
    const uint32_t first = map->static_triangles, count = map->total_triangles - map->static_triangles;
    roma_grid_params alone = map->grids[l];
    alone.level[0] = map->levels;
    roma_result r = roma_bom_voxelize_record_level(map->voxelizer, cmd, &alone, first, count, 1);
    if (r == ROMA_SUCCESS)
        r = roma_bom_voxelize_record_level(map->voxelizer, cmd, &map->grids[l], first, count, 0);
    /* Only the BOM rows (y) the box covers, a cell of margin, hold its cells. */
    const roma_grid_params *g = &map->grids[l];
    const float y0 = floorf((bmin[1] - g->origin[1]) * g->inv_cell[0]) - 1.0f;
    const float y1 = floorf((bmax[1] - g->origin[1]) * g->inv_cell[0]) + 1.0f;
    const uint32_t row0 = (uint32_t)fminf(fmaxf(y0, 0.0f), (float)(map->res - 1));
    const uint32_t row1 = (uint32_t)fminf(fmaxf(y1, 0.0f), (float)(map->res - 1));
    const uint32_t row_words = map->res * map->words;
    if (r == ROMA_SUCCESS)
        record_rotation(map, cmd, l, map->levels, 0, row0 * row_words, (row1 - row0 + 1) * row_words);
    return r;
}

/* A whole build over dynamic instances (the exact BOM, no new positions). A level that moved or
 * has new directions is built from every triangle, as without dynamic instances (a static copy
 * would not outlive the frame: a jittered map pays nothing for them). A level placed as last
 * time whose static part is stale is voxelized and rotated from the static triangles and saved;
 * one whose static part is current is copied back where dynamic cells were; then every level
 * the dynamic instances touch gets theirs. A level they neither touch nor touched is kept. */
static roma_result record_layered(roma_map *map, VkCommandBuffer cmd, uint32_t *rebuilt)
{
    float dmin[3] = {INFINITY, INFINITY, INFINITY}, dmax[3] = {-INFINITY, -INFINITY, -INFINITY};
    roma_map_instances_bounds(map, 1, dmin, dmax);
    const size_t level_frames = sizeof(roma_map_frame) * map->map_count;
    *rebuilt = 0;
    for (uint32_t l = 0; l < map->levels; ++l) {
        const int placed = map->bom_current[l] && map->maps_current[l] &&
                           memcmp(&map->built_grids[l], &map->grids[l], sizeof map->grids[l]) == 0 &&
                           memcmp(map->built_frames + l * map->map_count, map->frames + l * map->map_count,
                                  level_frames) == 0;
        const int static_same = placed && map->static_current[l] &&
                                map->built_static_versions[l] == map->static_version;
        const int touches = roma_map_touches_level(map, l, dmin, dmax);
        if (static_same && (map->built_versions[l] == map->geometry_version || (!touches && !map->dynamic_in[l]))) {
            map->built_versions[l] = map->geometry_version;
            continue;
        }
        roma_result r = ROMA_SUCCESS;
        if (!placed) {
            r = voxelize_level(map, cmd, l, map->total_triangles);
            if (r == ROMA_SUCCESS)
                record_rotation(map, cmd, l, l, 1, 0, map->res * map->res * map->words);
        } else if (!static_same) {
            r = voxelize_level(map, cmd, l, map->static_triangles);
            if (r == ROMA_SUCCESS) {
                record_rotation(map, cmd, l, l, 1, 0, map->res * map->res * map->words);
                save_static(map, cmd, l);
            }
        } else if (map->dynamic_in[l]) {
            restore_static(map, cmd, l, map->dynamic_min[l], map->dynamic_max[l]);
        }
        if (r == ROMA_SUCCESS && touches && placed)
            r = add_dynamic(map, cmd, l, dmin, dmax);
        if (r != ROMA_SUCCESS) { /* what was recorded may have cleared any level */
            memset(map->bom_current, 0, sizeof map->bom_current);
            memset(map->maps_current, 0, sizeof map->maps_current);
            memset(map->static_current, 0, sizeof map->static_current);
            return r;
        }
        map->bom_current[l] = map->maps_current[l] = 1;
        map->static_current[l] = (uint8_t)placed; /* else it holds every triangle */
        map->dynamic_in[l] = (uint8_t)touches;
        memcpy(map->dynamic_min[l], dmin, sizeof dmin);
        memcpy(map->dynamic_max[l], dmax, sizeof dmax);
        map->built_grids[l] = map->grids[l];
        map->built_versions[l] = map->geometry_version;
        map->built_static_versions[l] = map->static_version;
        memcpy(map->built_frames + l * map->map_count, map->frames + l * map->map_count, level_frames);
        ++*rebuilt;
    }
    return ROMA_SUCCESS;
}

roma_result roma_map_record_steps(roma_map *map, VkCommandBuffer cmd, const roma_map_frame_desc *frame_in,
                                  roma_gpu_timer *timer, uint32_t steps)
{
    if (!map || !cmd)
        return roma_fail(map ? &map->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_map_record_build: %s is NULL", map ? "cmd" : "map");
    roma_result r = check_timer(map, timer, "roma_map_record_build");
    if (r != ROMA_SUCCESS)
        return r;
    roma_map_frame_desc frame = frame_in ? *frame_in : (roma_map_frame_desc){0};
    /* The box the grid is fitted to: the volume, else the bounds of new host positions,
     * else those of the last ones. */
    float pmin[3], pmax[3];
    r = check_frame(map, &frame);
    if (r == ROMA_SUCCESS)
        r = roma_map_mesh_positions_check(map, &frame, "roma_map_record_build");
    if (r == ROMA_SUCCESS && frame.positions)
        r = stage_positions(map, frame.slot, frame.positions, pmin, pmax);
    if (r != ROMA_SUCCESS)
        return r;
    float bmin[3], bmax[3];
    memcpy(bmin, frame.volume ? frame.volume->min : frame.positions ? pmin : map->scene_min, sizeof bmin);
    memcpy(bmax, frame.volume ? frame.volume->max : frame.positions ? pmax : map->scene_max, sizeof bmax);
    roma_map_mesh_positions_take_bounds(map, &frame, 0); /* given back below if the build fails */
    if (!frame.volume) /* and the instances, where they are this frame */
        roma_map_instances_bounds(map, 0, bmin, bmax);
    r = check_bounds(&map->logger, bmin, bmax, map->res, map->margin_cells, "roma_map_record_build");
    /* Dynamic instances over static geometry: a whole build keeps the static part apart. */
    const int whole = steps == (ROMA_MAP_STEP_VOXELIZE | ROMA_MAP_STEP_ROTATE);
    const int layered = whole && map->voxelizer && !frame.positions && !frame.gpu_positions &&
                        roma_map_instances_dynamic(map);
    if (r == ROMA_SUCCESS && layered)
        r = make_static_copies(map);
    roma_map_layout layout = {0};
    if (r == ROMA_SUCCESS)
        r = roma_map_instances_prepare(map, &layout);
    if (r != ROMA_SUCCESS) {
        roma_map_mesh_positions_take_bounds(map, &frame, 1);
        return r;
    }
    roma_map_instances_release(map, 0); /* what the build slots' earlier builds used */
    compute_frame_params(map, &frame, bmin, bmax);
    const int static_moved = frame.positions || frame.gpu_positions || layout.changed || map->builds == 0 ||
                             memcmp(bmin, map->volume_min, sizeof bmin) != 0 ||
                             memcmp(bmax, map->volume_max, sizeof bmax) != 0;
    /* New mesh positions move dynamic instances alone (roma_map_mesh_positions_check). */
    if (static_moved || map->transforms_dirty || roma_map_mesh_positions_used(map, &frame))
        map->geometry_version = ++map->ctx->geometry_versions;
    if (static_moved)
        map->static_version = map->geometry_version;
    memcpy(map->volume_min, bmin, sizeof bmin);
    memcpy(map->volume_max, bmax, sizeof bmax);
    map->positions_moved |= frame.positions || frame.gpu_positions;
    map->transforms_dirty = 0;
    if (frame.positions) /* later frames without a volume fit these bounds */
        for (int a = 0; a < 3; ++a)
            map->scene_min[a] = pmin[a], map->scene_max[a] = pmax[a];
    if (frame.positions) /* the levels' runs follow them; positions the host cannot see: every chunk */
        roma_map_chunks_update(map, frame.positions);
    else if (frame.gpu_positions)
        map->chunks_known = 0;

    /* Everything earlier on the queue (traces of the previous frame from any stage,
     * downloads, the caller's writes of gpu_positions) before this build writes. */
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                                VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    record_frame_params(map, cmd);
    if (map->indices_pending) { /* the scene's indices, until a build that copies them is recorded */
        const VkBufferCopy copy = {0, 0, map->indices_staging.size};
        vkCmdCopyBuffer(cmd, map->indices_staging.buffer, map->indices.buffer, 1, &copy);
    }
    roma_map_instances_record_copies(map, cmd, &layout);
    if (layout.changed) /* the scene's positions copied into the new buffer before this frame's */
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    record_positions(map, cmd, &frame);
    roma_map_mesh_positions_record(map, cmd, &frame);
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                                VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_UNIFORM_READ_BIT);
    roma_map_instances_record_transforms(map, cmd, layout.changed);
    ++map->builds;
    map->triangles_voxelized = 0;

    if (layered) {
        uint32_t scope = roma_gpu_timer_begin(timer, cmd, "bom_and_rotate");
        r = record_layered(map, cmd, &map->levels_rebuilt);
        roma_gpu_timer_end(timer, cmd, scope);
        if (r != ROMA_SUCCESS)
            return r;
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                                VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT);
        map->built = 1;
        map->indices_pending = 0;
        return ROMA_SUCCESS;
    }
    /* The levels to voxelize and rotate: those whose placement, geometry or directions
     * changed since they were built (a still camera over static geometry without jitter
     * rebuilds nothing); every level where a step is asked alone (the benchmark times each). */
    const size_t level_frames = sizeof(roma_map_frame) * map->map_count;
    uint32_t stale_bom = 0, stale_maps = 0;
    for (uint32_t l = 0; l < map->levels; ++l) {
        const int bom_same = whole && map->bom_current[l] && map->built_versions[l] == map->geometry_version &&
                             memcmp(&map->built_grids[l], &map->grids[l], sizeof map->grids[l]) == 0;
        const int maps_same = bom_same && map->maps_current[l] &&
                              memcmp(map->built_frames + l * map->map_count, map->frames + l * map->map_count,
                                     level_frames) == 0;
        stale_bom |= bom_same ? 0u : 1u << l;
        stale_maps |= maps_same ? 0u : 1u << l;
    }
    if (steps & ROMA_MAP_STEP_VOXELIZE) {
        uint32_t scope = roma_gpu_timer_begin(timer, cmd, "bom");
        r = record_bom(map, cmd, stale_bom);
        roma_gpu_timer_end(timer, cmd, scope);
        if (r != ROMA_SUCCESS) { /* what was recorded may have cleared any level */
            memset(map->bom_current, 0, sizeof map->bom_current);
            memset(map->maps_current, 0, sizeof map->maps_current);
            return r;
        }
    }
    if (steps & ROMA_MAP_STEP_ROTATE) {
        uint32_t scope = roma_gpu_timer_begin(timer, cmd, "rotate");
        for (uint32_t l = 0; l < map->levels; ++l)
            if (stale_maps & (1u << l))
                record_rotation(map, cmd, l, l, 1, 0, map->res * map->res * map->words);
        roma_gpu_timer_end(timer, cmd, scope);
    }
    map->levels_rebuilt = 0;
    for (uint32_t l = 0; l < map->levels; ++l) {
        if ((stale_bom | stale_maps) & (1u << l))
            map->static_current[l] = 0; /* the level holds every triangle now */
        if ((steps & ROMA_MAP_STEP_VOXELIZE) && (stale_bom & (1u << l))) {
            map->bom_current[l] = 1;
            map->built_grids[l] = map->grids[l];
            map->built_versions[l] = map->geometry_version;
        }
        /* Maps count as built from this BOM only in a whole build (a rotation alone may
         * follow another placement's BOM). */
        if (stale_maps & (1u << l)) {
            map->maps_current[l] = whole;
            memcpy(map->built_frames + l * map->map_count, map->frames + l * map->map_count, level_frames);
        }
        map->levels_rebuilt += ((stale_bom | stale_maps) >> l) & 1u;
    }
    /* Maps and parameters readable by any later command: traces from any stage,
     * downloads. */
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT);
    if (steps & ROMA_MAP_STEP_ROTATE)
        map->built = 1;
    map->indices_pending = 0;
    return ROMA_SUCCESS;
}

roma_result roma_map_record_build(roma_map *map, VkCommandBuffer cmd, const roma_map_frame_desc *frame,
                                  roma_gpu_timer *timer)
{
    return roma_map_record_steps(map, cmd, frame, timer, ROMA_MAP_STEP_VOXELIZE | ROMA_MAP_STEP_ROTATE);
}

roma_result roma_map_build(roma_map *map, const roma_map_frame_desc *frame, roma_gpu_timer *timer)
{
    if (!map)
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_build: map is NULL");
    roma_result r = check_timer(map, timer, "roma_map_build"); /* before the reset is recorded */
    if (r != ROMA_SUCCESS)
        return r;
    VkCommandBuffer cmd;
    r = roma_begin_one_shot(map->ctx, &cmd);
    if (r != ROMA_SUCCESS)
        return r;
    roma_gpu_timer_reset(timer, cmd);
    r = roma_map_record_build(map, cmd, frame, timer);
    roma_result s = roma_submit_one_shot(map->ctx, cmd);
    return r != ROMA_SUCCESS ? r : s;
}

roma_result roma_map_get_info(const roma_map *map, roma_map_info *out)
{
    if (out)
        memset(out, 0, sizeof *out);
    if (!map || !out)
        return roma_fail(map ? &map->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_map_get_info: %s is NULL", map ? "out_info" : "map");
    out->resolution = map->res;
    out->angular = map->angular;
    out->map_count = map->map_count;
    out->words_per_texel = map->words;
    memcpy(out->grid_origin, map->grids[0].origin, sizeof out->grid_origin);
    out->grid_cell = map->grids[0].origin[3];
    out->trace_cell = map->grids[0].origin[3] * 1.7320508f;
    out->bom_bytes = bom_level_bytes(map) * map->levels; /* the levels' (not the dynamic slot) */
    out->bom_address = map->bom.address;
    out->bom_buffer = map->bom.buffer;
    out->bom_view = map->bom_view;
    out->maps_bytes = map->maps.size;
    out->params_bytes = map->params.size;
    out->geometry_bytes = map->positions.size + map->indices.size;
    out->maps_address = map->maps.address;
    out->params_address = map->params.address;
    out->maps_buffer = map->maps.buffer;
    out->params_buffer = map->params.buffer;
    out->maps_view = map->maps_view;
    out->trace_set = map->trace_set.set;
    out->trace_set_layout = map->trace_set.layout;
    out->levels = map->levels;
    out->levels_rebuilt = map->levels_rebuilt;
    out->static_copy_bytes = map->static_bom.size + map->static_maps.size;
    out->triangles_voxelized = map->triangles_voxelized;
    return ROMA_SUCCESS;
}

roma_result roma_map_candidate(const roma_map *map, uint32_t k, float out_dir[3])
{
    if (out_dir)
        out_dir[0] = out_dir[1] = out_dir[2] = 0.0f;
    if (!map || !out_dir)
        return roma_fail(map ? &map->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_map_candidate: %s is NULL", map ? "out_dir" : "map");
    if (k >= map->map_count)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_map_candidate: k = %u but the map has %u candidates", k, map->map_count);
    if (!map->built)
        return roma_fail(&map->logger, ROMA_ERROR_NOT_READY, "roma_map_candidate: the map has not been built yet");
    memcpy(out_dir, map->frames[k].dir, 3 * sizeof(float));
    return ROMA_SUCCESS;
}

/* Checks shared by both trace calls: arguments first, then whether there is a map to trace. */
static roma_result check_trace(const roma_map *map, roma_trace_mode mode, uint32_t ray_count,
                               const roma_gpu_timer *timer, const char *fn)
{
    if ((unsigned)mode > ROMA_TRACE_UNSNAPPED_CLOSEST)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT, "%s: unknown mode %d", fn, (int)mode);
    roma_result r = check_timer(map, timer, fn);
    if (r == ROMA_SUCCESS && ray_count && !map->built)
        r = roma_fail(&map->logger, ROMA_ERROR_NOT_READY, "%s: build the map first", fn);
    return r;
}

roma_result roma_map_record_trace(roma_map *map, VkCommandBuffer cmd, const roma_trace_desc *desc,
                                  roma_gpu_timer *timer)
{
    if (!map || !cmd || !desc)
        return roma_fail(map ? &map->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_map_record_trace: %s is NULL", !map ? "map" : !cmd ? "cmd" : "desc");
    if (desc->ray_count && (!desc->rays || !desc->hits))
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_record_trace: rays and hits addresses are required");
    roma_result r = check_trace(map, desc->mode, desc->ray_count, timer, "roma_map_record_trace");
    if (r != ROMA_SUCCESS || desc->ray_count == 0)
        return r;
    roma_trace_push push = {
        .rays = desc->rays,
        .hits = desc->hits,
        .params = map->params.address,
        .maps = map->maps.address,
        .config = {(uint32_t)desc->mode, desc->max_steps ? desc->max_steps : 8u, desc->ray_count, 0},
    };
    r = make_trace_pipeline(map, 0, desc->mode);
    if (r != ROMA_SUCCESS)
        return r;
    const roma_compute_pipeline *pipe = &map->trace[desc->mode];
    uint32_t scope = roma_gpu_timer_begin(timer, cmd, "trace");
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe->pipeline);
    vkCmdPushConstants(cmd, pipe->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    roma_cmd_dispatch_linear(cmd, desc->ray_count, ROMA_TRACE_WORKGROUP_SIZE);
    roma_gpu_timer_end(timer, cmd, scope);
    return ROMA_SUCCESS;
}

/* A buffer of roma_map_trace's (staging, or the device buffers it is copied into) that grows
 * to the largest batch seen. */
static roma_result ensure_staging(roma_map *map, roma_buffer *b, VkDeviceSize size, roma_memory_kind kind)
{
    if (b->buffer && b->size >= size)
        return ROMA_SUCCESS;
    roma_buffer_destroy(map->ctx, b);
    return roma_buffer_create(map->ctx, size,
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                  VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT |
                                  VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                              kind, b);
}

/* Texel views of the buffers the staged trace reads and writes in the staged set (rays: two
 * RGBA32F texels each, hits: one RG32UI texel each). No recorded use is pending:
 * roma_map_trace waits for its submissions. */
static roma_result bind_staging(roma_map *map, VkBuffer rays, VkBuffer hits)
{
    roma_context *ctx = map->ctx;
    if (map->staged_rays == rays && map->staged_hits == hits)
        return ROMA_SUCCESS;
    map->staged_rays = map->staged_hits = VK_NULL_HANDLE;
    for (int i = 0; i < 2; ++i)
        if (map->staging_views[i]) {
            vkDestroyBufferView(ctx->device, map->staging_views[i], ctx->allocator);
            map->staging_views[i] = VK_NULL_HANDLE;
        }
    roma_result r = roma_buffer_view_create(ctx, rays, VK_FORMAT_R32G32B32A32_SFLOAT, &map->staging_views[0]);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_view_create(ctx, hits, VK_FORMAT_R32G32_UINT, &map->staging_views[1]);
    if (r == ROMA_SUCCESS) {
        roma_descriptor_write_view(ctx, &map->staged_set, ROMA_TRACE_BINDING_RAYS,
                                   VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, map->staging_views[0]);
        roma_descriptor_write_view(ctx, &map->staged_set, ROMA_TRACE_BINDING_HITS,
                                   VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, map->staging_views[1]);
        map->staged_rays = rays;
        map->staged_hits = hits;
    }
    return r;
}

roma_result roma_map_record_trace_staged(roma_map *map, VkCommandBuffer cmd, roma_trace_mode mode,
                                         uint32_t max_steps, uint32_t ray_count, roma_gpu_timer *timer)
{
    if (!map || !cmd)
        return ROMA_ERROR_INVALID_ARGUMENT;
    roma_result r = check_trace(map, mode, ray_count, timer, "roma_map_trace");
    if (r != ROMA_SUCCESS || ray_count == 0)
        return r;
    if ((VkDeviceSize)ray_count * sizeof(roma_ray) > map->ray_staging.size ||
        (VkDeviceSize)ray_count * sizeof(roma_hit) > map->hit_staging.size)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_trace: %u rays exceed the staging buffers",
                         ray_count);
    r = make_trace_pipeline(map, 1, mode);
    if (r != ROMA_SUCCESS)
        return r;
    const roma_compute_pipeline *pipe = &map->trace_staged[mode];
    roma_trace_push push = {.config = {(uint32_t)mode, max_steps ? max_steps : 8u, ray_count, 0}};
    uint32_t scope = roma_gpu_timer_begin(timer, cmd, "trace");
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe->pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe->layout, 0, 1, &map->staged_set.set, 0, NULL);
    vkCmdPushConstants(cmd, pipe->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    roma_cmd_dispatch_linear(cmd, ray_count, ROMA_TRACE_WORKGROUP_SIZE);
    roma_gpu_timer_end(timer, cmd, scope);
    return ROMA_SUCCESS;
}

roma_result roma_map_trace(roma_map *map, roma_trace_mode mode, uint32_t max_steps, const roma_ray *rays,
                           uint32_t ray_count, roma_hit *out_hits, roma_gpu_timer *timer)
{
    if (!map || (ray_count && (!rays || !out_hits)))
        return roma_fail(map ? &map->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_trace: %s is NULL",
                         !map ? "map" : !rays ? "rays" : "out_hits");
    /* Refused before the staging buffers are resized for the batch. */
    roma_result r = check_trace(map, mode, ray_count, timer, "roma_map_trace");
    if (r != ROMA_SUCCESS || ray_count == 0)
        return r;
    /* The rays are read through a texel buffer of 2 RGBA32F texels each. */
    uint32_t max_texels = map->ctx->properties.limits.maxTexelBufferElements;
    if ((uint64_t)ray_count * 2 > max_texels)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_map_trace: %u rays, at most %u in one call on this device (maxTexelBufferElements / 2)",
                         ray_count, max_texels / 2);
    const VkDeviceSize ray_bytes = sizeof(roma_ray) * (VkDeviceSize)ray_count;
    const VkDeviceSize hit_bytes = sizeof(roma_hit) * (VkDeviceSize)ray_count;
    r = ensure_staging(map, &map->ray_staging, ray_bytes, ROMA_MEMORY_UPLOAD);
    if (r == ROMA_SUCCESS)
        r = ensure_staging(map, &map->hit_staging, hit_bytes, ROMA_MEMORY_READBACK);
    /* The trace reads device-local memory: the staging itself where it is (CPU and
     * integrated devices), else device buffers it is copied into and out of. */
    const VkMemoryPropertyFlags local = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    const int copied = r == ROMA_SUCCESS && (map->ctx->force_staging || !((map->ray_staging.memory_flags & local) &&
                                                                          (map->hit_staging.memory_flags & local)));
    if (copied)
        r = ensure_staging(map, &map->ray_device, ray_bytes, ROMA_MEMORY_DEVICE);
    if (copied && r == ROMA_SUCCESS)
        r = ensure_staging(map, &map->hit_device, hit_bytes, ROMA_MEMORY_DEVICE);
    /* The staged set names the buffers of this call (no recorded use is pending: this call and
     * the last one both waited for their submissions). */
    if (r == ROMA_SUCCESS)
        r = copied ? bind_staging(map, map->ray_device.buffer, map->hit_device.buffer)
                   : bind_staging(map, map->ray_staging.buffer, map->hit_staging.buffer);
    if (r != ROMA_SUCCESS) {
        /* Keep nothing this call grew: these buffers are only a cache. */
        roma_buffer_destroy(map->ctx, &map->ray_staging);
        roma_buffer_destroy(map->ctx, &map->hit_staging);
        roma_buffer_destroy(map->ctx, &map->ray_device);
        roma_buffer_destroy(map->ctx, &map->hit_device);
        map->staged_rays = map->staged_hits = VK_NULL_HANDLE;
        return r;
    }
    memcpy(map->ray_staging.mapped, rays, sizeof(roma_ray) * (size_t)ray_count);
    VkCommandBuffer cmd;
    r = roma_begin_one_shot(map->ctx, &cmd);
    if (r != ROMA_SUCCESS)
        return r;
    roma_gpu_timer_reset(timer, cmd);
    if (copied) {
        const VkBufferCopy in = {0, 0, ray_bytes};
        vkCmdCopyBuffer(cmd, map->ray_staging.buffer, map->ray_device.buffer, 1, &in);
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    }
    r = roma_map_record_trace_staged(map, cmd, mode, max_steps, ray_count, timer);
    if (copied) {
        compute_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        const VkBufferCopy out = {0, 0, hit_bytes};
        vkCmdCopyBuffer(cmd, map->hit_device.buffer, map->hit_staging.buffer, 1, &out);
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    } else {
        compute_barrier(cmd, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    }
    roma_result s = roma_submit_one_shot(map->ctx, cmd);
    if (r == ROMA_SUCCESS)
        r = s;
    if (r == ROMA_SUCCESS)
        r = roma_buffer_invalidate(map->ctx, &map->hit_staging);
    if (r == ROMA_SUCCESS)
        memcpy(out_hits, map->hit_staging.mapped, sizeof(roma_hit) * (size_t)ray_count);
    return r;
}

/* The first `bytes` of src (the BOM's levels, without the dynamic instances' slot). */
static roma_result download(roma_map *map, const roma_buffer *src, VkDeviceSize bytes, uint32_t *out,
                            uint64_t word_count)
{
    if (!out)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_map download: out_words is NULL");
    /* Compared in words: word_count * 4 wraps for huge counts and could match the size. */
    if (word_count != bytes / 4)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_map download: word_count %llu, the buffer holds %llu words",
                         (unsigned long long)word_count, (unsigned long long)(bytes / 4));
    if (!map->built) /* device memory not written yet: no garbage handed out */
        return roma_fail(&map->logger, ROMA_ERROR_NOT_READY, "roma_map download: the map has not been built yet");
    roma_buffer staging;
    roma_result r = roma_buffer_create(map->ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, ROMA_MEMORY_READBACK, &staging);
    if (r != ROMA_SUCCESS)
        return r;
    VkCommandBuffer cmd;
    r = roma_begin_one_shot(map->ctx, &cmd);
    if (r == ROMA_SUCCESS) {
        VkBufferCopy copy = {0, 0, bytes};
        vkCmdCopyBuffer(cmd, src->buffer, staging.buffer, 1, &copy);
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        r = roma_submit_one_shot(map->ctx, cmd);
    }
    if (r == ROMA_SUCCESS)
        r = roma_buffer_invalidate(map->ctx, &staging);
    if (r == ROMA_SUCCESS)
        memcpy(out, staging.mapped, bytes);
    roma_buffer_destroy(map->ctx, &staging);
    return r;
}

roma_result roma_map_download_bom(roma_map *map, uint32_t *out, uint64_t word_count)
{
    return map ? download(map, &map->bom, bom_level_bytes(map) * map->levels, out, word_count)
               : roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_download_bom: map is NULL");
}

roma_result roma_map_download_maps(roma_map *map, uint32_t *out, uint64_t word_count)
{
    return map ? download(map, &map->maps, map->maps.size, out, word_count)
               : roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_download_maps: map is NULL");
}

roma_result roma_map_get_frame_params(const roma_map *map, roma_grid_params *grid, const roma_map_frame **frames)
{
    if (!map || !grid || !frames)
        return ROMA_ERROR_INVALID_ARGUMENT;
    *grid = map->grids[0];
    *frames = map->frames;
    return ROMA_SUCCESS;
}

roma_result roma_map_get_level_params(const roma_map *map, uint32_t *levels, const roma_grid_params **grids,
                                      const roma_map_frame **frames)
{
    if (!map || !levels || !grids || !frames)
        return ROMA_ERROR_INVALID_ARGUMENT;
    *levels = map->levels;
    *grids = map->grids;
    *frames = map->frames;
    return ROMA_SUCCESS;
}
_Static_assert(ROMA_PARAMS_BLOCK_BYTES == sizeof(roma_grid_params) * ROMA_MAX_LEVELS + ROMA_MAX_ANGULAR * ROMA_MAX_ANGULAR * sizeof(roma_map_frame), "the uniform block of roma_rotate.glsl");
