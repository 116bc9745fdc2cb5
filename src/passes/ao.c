#include "passes/ao.h"

#include <math.h>
#include <stdlib.h>

#include "roma_shared.h"
#include "passes/pixel_pass.h"
#include "trace/loop_costs.h"
#include "vulkan/loop_budget.h"

struct roma_ao_pass {
    roma_context *ctx;
    roma_pixel_pass pass;
    roma_ao_method method;
};

roma_result roma_ao_pass_create(roma_context *ctx, roma_ao_pass **out)
{
    return roma_ao_pass_create_mode(ctx, ROMA_AO_METHOD_ROMA, out);
}

roma_result roma_ao_pass_create_mode(roma_context *ctx, roma_ao_method method, roma_ao_pass **out)
{
    if (!out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    if (!ctx || (unsigned)method > ROMA_AO_METHOD_NAADF)
        return ROMA_ERROR_INVALID_ARGUMENT;
    roma_ao_pass *pass = calloc(1, sizeof *pass);
    if (!pass)
        return roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_ao_pass_create: out of memory");
    pass->ctx = ctx;
    pass->method = method;
    const uint32_t constant = (uint32_t)method; /* ao.comp's constant 0 */
    roma_result r = roma_pixel_pass_create_spec(ctx, "ao.comp", sizeof(roma_ao_push), 1, &constant, 1, &pass->pass);
    if (r != ROMA_SUCCESS) {
        roma_ao_pass_destroy(pass);
        return r;
    }
    *out = pass;
    return ROMA_SUCCESS;
}

void roma_ao_pass_destroy(roma_ao_pass *pass)
{
    if (!pass)
        return;
    roma_pixel_pass_destroy(&pass->pass);
    free(pass);
}

/* Loop iterations of one AO sample of ao.comp by method (loop_costs.h). */
static uint32_t sample_cost(roma_ao_method method, roma_loop_grid g, const roma_ao_push *push)
{
    switch (method) {
    case ROMA_AO_METHOD_VOXEL_DDA:
        return 1u + roma_loop_cost_walk(g, push->ray[1], UINT32_MAX);
    case ROMA_AO_METHOD_DISTANCE_FIELD:
        return 1u + push->config2[1];
    case ROMA_AO_METHOD_SCREEN_SPACE:
        return 1u + (uint32_t)push->forward[3] * (1u + push->config2[2]);
    case ROMA_AO_METHOD_NAADF: /* the clip (3 axes), then at most 3 RES + 2 boxes of 3 axes each */
        return 1u + 3u + (3u * g.res + 2u) * 4u;
    default:
        return roma_loop_cost_ao_ray(g, push->ray[2], push->ray[1]);
    }
}

roma_result roma_ao_pass_record(roma_ao_pass *pass, VkCommandBuffer cmd, const roma_ao_pass_inputs *in)
{
    if (!pass || !cmd || !in)
        return ROMA_ERROR_INVALID_ARGUMENT;
    if (!in->gbuffer_pixels || !in->map || !in->map->maps_view || !in->accum || !in->list)
        return roma_fail(&pass->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ao_pass_record: G-buffer, map, list and accumulation buffers are required");
    if (!(in->offset >= 0.0f) || !isfinite(in->offset) || !(in->tmin >= 0.0f) || !isfinite(in->tmin))
        return roma_fail(&pass->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_ao_pass_record: invalid offset or tmin");
    if (in->spp == 0)
        return ROMA_SUCCESS;
    roma_camera_frame cam = {0};
    if (pass->method == ROMA_AO_METHOD_SCREEN_SPACE &&
        (!(in->radius > 0.0f) || !isfinite(in->radius) || !in->camera || (in->ssao_layers && !in->bom) ||
         !roma_camera_make_frame(in->camera, in->width, in->height, &cam)))
        return roma_fail(&pass->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ao_pass_record: screen-space AO needs a bounded radius and the G-buffer's camera");
    roma_ao_push push = {
        /* the baselines trace the whole ray through the bound BOM or field: no blind start */
        .bom = (in->blind_start && pass->method == ROMA_AO_METHOD_ROMA) ? 0u : 1u,
        .config = {in->width, in->height, in->spp, in->frame},
        .ray = {in->offset, in->radius > 0.0f ? in->radius : INFINITY, in->tmin, ROMA_AO_DF_MIN_STEP},
        .config2 = {in->seed, ROMA_AO_DF_MAX_STEPS, 0, 0},
    };
    if (pass->method == ROMA_AO_METHOD_SCREEN_SPACE) {
        const float sx = 0.5f * (float)in->width / (cam.tan_half_fovy * cam.aspect);
        const float sy = 0.5f * (float)in->height / cam.tan_half_fovy;
        for (int k = 0; k < 3; ++k) {
            push.eye[k] = cam.origin[k];
            push.forward[k] = cam.forward[k];
            push.right[k] = cam.right[k] * sx;
            push.up[k] = cam.up[k] * sy;
        }
        push.eye[3] = ROMA_AO_SSAO_THICKNESS * in->radius;
        push.forward[3] = (float)(in->ssao_steps ? in->ssao_steps : ROMA_AO_SSAO_STEPS);
        push.config2[2] = in->ssao_layers;
    }
    /* The samples in parts within the device's loop budget (loop_budget.h). */
    const roma_loop_grid grid = {in->map->resolution, in->map->grid_cell, in->map->levels};
    const roma_loop_parts parts =
        roma_loop_parts_plan(pass->ctx, 0, in->spp, sample_cost(pass->method, grid, &push), 0, 0);
    uint32_t range[4];
    roma_result r = ROMA_SUCCESS;
    for (uint32_t part = 0; r == ROMA_SUCCESS && roma_loop_parts_get(&parts, part, range); ++part) {
        push.sample_first = range[0];
        push.sample_end = range[1];
        r = roma_pixel_pass_record_list(&pass->pass, cmd, in->list, in->map, in->bom, in->gbuffer_pixels, in->accum,
                                        &push);
    }
    return r;
}
