/* The study's reflective shadow maps (study/study_rsm.h). */
#include "study/study_rsm.h"

#include <stdlib.h>

#include "effects/light_data.h"
#include "effects/scene_buffers.h"
#include "study/gbuffer.h"
#include "study/rsm_views.h"
#include "study/study_shaders.h"
#include "util/log.h"
#include "vulkan/vk_internal.h"

struct roma_study_rsm {
    roma_context *ctx;
    roma_scene_buffers geometry;
    roma_rsm_views views;
    roma_gbuffer *maps[ROMA_MAX_RSM_VIEWS];
    roma_buffer table; /* the views as the GI pass reads them, device-local */
    uint32_t size;
    float near_plane;
    int written; /* the table holds the views */
};

void roma_study_rsm_destroy(roma_study_rsm *rsm)
{
    if (!rsm)
        return;
    for (uint32_t v = ROMA_MAX_RSM_VIEWS; v-- > 0;) /* the first one's pipelines last */
        roma_gbuffer_destroy(rsm->maps[v]);
    roma_buffer_destroy(rsm->ctx, &rsm->table);
    roma_scene_buffers_destroy(rsm->ctx, &rsm->geometry);
    free(rsm);
}

roma_result roma_study_rsm_create(roma_context *ctx, const roma_scene *scene, uint32_t size, roma_study_rsm **out)
{
    if (!out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    if (!ctx || !scene || size > 4096)
        return roma_fail(ctx ? &ctx->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_study_rsm_create: %s", !ctx || !scene ? "context or scene is NULL" : "size above 4096");
    roma_study_rsm *rsm = calloc(1, sizeof *rsm);
    if (!rsm)
        return roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_study_rsm_create: out of host memory");
    rsm->ctx = ctx;
    rsm->size = size ? size : 256;
    roma_study_shaders_use(ctx);
    roma_scene_view view;
    roma_scene_get_view(scene, &view);
    rsm->near_plane = roma_gbuffer_near_plane(scene);
    /* The lights packed as the GI effect packs the same list: the views name them by index. */
    roma_gpu_light *packed = calloc(view.light_count ? view.light_count : 1, sizeof *packed);
    uint32_t count = 0;
    for (uint32_t i = 0; packed && i < view.light_count; ++i)
        count += (uint32_t)roma_light_pack(&view.lights[i], packed + count);
    roma_result r = packed ? roma_rsm_views_plan(packed, count, rsm->size, rsm->near_plane, &ctx->logger, &rsm->views)
                           : ROMA_ERROR_OUT_OF_HOST_MEMORY;
    free(packed);
    if (r == ROMA_SUCCESS && rsm->views.count)
        r = roma_scene_buffers_create(ctx, scene, &rsm->geometry);
    for (uint32_t v = 0; v < rsm->views.count && r == ROMA_SUCCESS; ++v) {
        r = v == 0 ? roma_gbuffer_create(ctx, rsm->size, rsm->size, &rsm->maps[v])
                   : roma_gbuffer_create_sharing(rsm->maps[0], rsm->size, rsm->size, &rsm->maps[v]);
        if (r == ROMA_SUCCESS) {
            const VkDeviceAddress a = roma_gbuffer_pixels_address(rsm->maps[v]);
            rsm->views.views[v].info[2] = (uint32_t)a;
            rsm->views.views[v].info[3] = (uint32_t)(a >> 32);
        }
    }
    if (r == ROMA_SUCCESS && rsm->views.count)
        r = roma_buffer_create(ctx, sizeof(roma_rsm_view) * rsm->views.count,
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               ROMA_MEMORY_DEVICE, &rsm->table);
    if (r != ROMA_SUCCESS) {
        roma_study_rsm_destroy(rsm);
        return r;
    }
    *out = rsm;
    return ROMA_SUCCESS;
}

roma_result roma_study_rsm_record(roma_study_rsm *rsm, VkCommandBuffer cmd)
{
    if (!rsm || !cmd)
        return ROMA_ERROR_INVALID_ARGUMENT;
    if (!rsm->views.count)
        return ROMA_SUCCESS;
    roma_gbuffer_inputs in = {
        .positions = rsm->geometry.positions.address, .normals = rsm->geometry.normals.address,
        .indices = rsm->geometry.indices.address, .albedo = rsm->geometry.albedo.address,
        .triangle_count = rsm->geometry.triangle_count, .near_plane = rsm->near_plane,
    };
    roma_result r = ROMA_SUCCESS;
    for (uint32_t v = 0; v < rsm->views.count && r == ROMA_SUCCESS; ++v) {
        in.camera = in.previous_camera = rsm->views.cameras[v];
        r = roma_gbuffer_record(rsm->maps[v], cmd, &in);
    }
    if (r == ROMA_SUCCESS && !rsm->written) {
        /* At most ROMA_MAX_RSM_VIEWS small entries: within vkCmdUpdateBuffer's 65,536 bytes. */
        vkCmdUpdateBuffer(cmd, rsm->table.buffer, 0, sizeof(roma_rsm_view) * rsm->views.count, rsm->views.views);
        /* vkCmdUpdateBuffer is a clear-class transfer command: the transfer stage covers it. */
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
        rsm->written = 1;
    }
    return r;
}

void roma_study_rsm_variant(const roma_study_rsm *rsm, float tolerance, roma_shadow_variant *variant)
{
    if (!variant)
        return;
    variant->rsm_views = rsm && rsm->views.count ? rsm->table.address : 0;
    variant->rsm_view_count = rsm ? rsm->views.count : 0;
    variant->rsm_tolerance = tolerance;
}

uint64_t roma_study_rsm_bytes(const roma_study_rsm *rsm)
{
    if (!rsm)
        return 0;
    return (uint64_t)rsm->views.count * rsm->size * rsm->size * sizeof(roma_gbuffer_pixel) + rsm->table.size;
}
