/* roma_study_ao: the study's AO methods through the public AO pass (study/study_ao.h). */
#include "study/study_ao.h"

#include <math.h>
#include <stdlib.h>

#include "effects/ao_effect_variant.h"
#include "study/distance_field.h"
#include "study/naadf.h"
#include "study/study_shaders.h"
#include "trace/loop_costs.h"
#include "util/log.h"
#include "vulkan/vk_internal.h"

struct roma_study_ao {
    roma_context *ctx;
    roma_ao_method method;
    roma_ao_effect *effect;
    /* Built every frame from the BOM they were made for (remade for another BOM). */
    roma_distance_field field;
    roma_naadf naadf;
    VkBuffer built_from;
    uint32_t built_resolution;
};

/* Each method's shader (shaders/study/ao_*.comp; ROMA's is the public one). */
static const char *method_module(roma_ao_method method)
{
    switch (method) {
    case ROMA_AO_METHOD_ROMA: return "ao_images.comp";
    case ROMA_AO_METHOD_VOXEL_DDA: return "ao_voxel_dda.comp";
    case ROMA_AO_METHOD_DISTANCE_FIELD: return "ao_distance_field.comp";
    case ROMA_AO_METHOD_SCREEN_SPACE: return "ao_screen_space.comp";
    case ROMA_AO_METHOD_NAADF: return "ao_naadf.comp";
    }
    return NULL;
}

roma_result roma_study_ao_create(roma_context *ctx, roma_ao_method method, const roma_ao_effect_desc *desc,
                                 roma_study_ao **out)
{
    if (!out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    const char *module = method_module(method);
    if (!ctx || !module)
        return roma_fail(ctx ? &ctx->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_study_ao_create: %s", !ctx ? "context is NULL" : "unknown AO method");
    roma_study_ao *ao = calloc(1, sizeof *ao);
    if (!ao)
        return roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_study_ao_create: out of host memory");
    ao->ctx = ctx;
    ao->method = method;
    roma_study_shaders_use(ctx);
    roma_result r = roma_ao_effect_create_variant(ctx, desc, module, &ao->effect);
    if (r != ROMA_SUCCESS) {
        free(ao);
        return r;
    }
    *out = ao;
    return ROMA_SUCCESS;
}

static void release_structure(roma_study_ao *ao)
{
    roma_distance_field_destroy(&ao->field);
    roma_naadf_destroy(&ao->naadf);
    ao->built_from = VK_NULL_HANDLE;
    ao->built_resolution = 0;
}

void roma_study_ao_destroy(roma_study_ao *ao)
{
    if (!ao)
        return;
    release_structure(ao);
    roma_ao_effect_destroy(ao->effect);
    free(ao);
}

/* The map's info, with one level where the method reads the BOM's grid alone. */
static roma_result baseline_map_info(roma_study_ao *ao, const roma_map *map, const char *name, roma_map_info *info)
{
    roma_result r = roma_map_get_info(map, info);
    if (r != ROMA_SUCCESS)
        return r;
    if (ao->method != ROMA_AO_METHOD_ROMA && info->levels > 1)
        return roma_fail(&ao->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "%s: the study's baselines trace one grid, and the map has %u cascade levels", name,
                         info->levels);
    return ROMA_SUCCESS;
}

roma_result roma_study_ao_record_build(roma_study_ao *ao, VkCommandBuffer cmd, const roma_map *map)
{
    if (!ao || !cmd || !map)
        return ROMA_ERROR_INVALID_ARGUMENT;
    if (ao->method != ROMA_AO_METHOD_DISTANCE_FIELD && ao->method != ROMA_AO_METHOD_NAADF)
        return ROMA_SUCCESS;
    roma_map_info info;
    roma_result r = baseline_map_info(ao, map, "roma_study_ao_record_build", &info);
    if (r != ROMA_SUCCESS)
        return r;
    if (ao->built_from != info.bom_buffer || ao->built_resolution != info.resolution) {
        release_structure(ao);
        r = ao->method == ROMA_AO_METHOD_DISTANCE_FIELD
                ? roma_distance_field_create(ao->ctx, info.bom_buffer, info.resolution, &ao->field)
                : roma_naadf_create(ao->ctx, info.bom_buffer, info.resolution, &ao->naadf);
        if (r != ROMA_SUCCESS)
            return r;
        ao->built_from = info.bom_buffer;
        ao->built_resolution = info.resolution;
    }
    if (ao->method == ROMA_AO_METHOD_DISTANCE_FIELD)
        roma_distance_field_record(&ao->field, cmd);
    else
        roma_naadf_record(&ao->naadf, cmd);
    return ROMA_SUCCESS;
}

roma_result roma_study_ao_record(roma_study_ao *ao, VkCommandBuffer cmd, uint32_t slot, const roma_map *map,
                                 const roma_ao_images *images, const roma_ao_settings *settings,
                                 const roma_study_ao_inputs *inputs)
{
    if (!ao || !map || !images)
        return ROMA_ERROR_INVALID_ARGUMENT;
    const roma_study_ao_inputs in = inputs ? *inputs : (roma_study_ao_inputs){0};
    roma_map_info info;
    roma_result r = baseline_map_info(ao, map, "roma_study_ao_record", &info);
    if (r != ROMA_SUCCESS)
        return r;
    roma_ao_settings s;
    r = roma_ao_settings_resolve(settings, &s);
    if (r != ROMA_SUCCESS)
        return r;
    const roma_loop_grid grid = {info.resolution, info.grid_cell, info.levels};
    const float radius = s.radius > 0.0f ? s.radius : INFINITY;
    roma_ao_variant v = {.blind_start = ao->method == ROMA_AO_METHOD_ROMA && in.blind_start};
    switch (ao->method) {
    case ROMA_AO_METHOD_ROMA:
        break;
    case ROMA_AO_METHOD_VOXEL_DDA:
        v.sample_cost = 1u + roma_loop_cost_walk(grid, radius, UINT32_MAX);
        break;
    case ROMA_AO_METHOD_DISTANCE_FIELD:
        if (ao->built_from != info.bom_buffer)
            return roma_fail(&ao->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                             "roma_study_ao_record: the distance field was not built from this map "
                             "(roma_study_ao_record_build)");
        v.bound = ao->field.distances_view;
        v.push.config2[1] = ROMA_AO_DF_MAX_STEPS;
        v.push.ray[3] = ROMA_AO_DF_MIN_STEP;
        v.sample_cost = 1u + ROMA_AO_DF_MAX_STEPS;
        break;
    case ROMA_AO_METHOD_NAADF:
        if (ao->built_from != info.bom_buffer)
            return roma_fail(&ao->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                             "roma_study_ao_record: the NAADF hierarchy was not built from this map "
                             "(roma_study_ao_record_build)");
        v.bound = ao->naadf.cells_view;
        v.sample_cost = 1u + 3u + (3u * info.resolution + 2u) * 4u; /* the clip, then at most 3 RES + 2 boxes */
        break;
    case ROMA_AO_METHOD_SCREEN_SPACE: {
        roma_camera_frame cam;
        if (!(s.radius > 0.0f) || !isfinite(s.radius) || !in.camera || (in.ssao_layers && !in.layers) ||
            in.ssao_layers > ROMA_AO_SSAO_MAX_LAYERS ||
            !roma_camera_make_frame(in.camera, images->width, images->height, &cam))
            return roma_fail(&ao->ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                             "roma_study_ao_record: screen-space AO needs a bounded radius, the images' camera "
                             "and, with layers, their view (at most %u)", ROMA_AO_SSAO_MAX_LAYERS);
        const float sx = 0.5f * (float)images->width / (cam.tan_half_fovy * cam.aspect);
        const float sy = 0.5f * (float)images->height / cam.tan_half_fovy;
        for (int k = 0; k < 3; ++k) {
            v.push.eye[k] = cam.origin[k];
            v.push.forward[k] = cam.forward[k];
            v.push.right[k] = cam.right[k] * sx;
            v.push.up[k] = cam.up[k] * sy;
        }
        v.push.eye[3] = ROMA_AO_SSAO_THICKNESS * s.radius;
        v.push.forward[3] = (float)(in.ssao_steps ? in.ssao_steps : ROMA_AO_SSAO_STEPS);
        v.push.config2[2] = in.ssao_layers;
        v.bound = in.ssao_layers ? in.layers : VK_NULL_HANDLE;
        v.sample_cost = 1u + (uint32_t)v.push.forward[3] * (1u + in.ssao_layers);
        break;
    }
    }
    return roma_ao_effect_record_variant(ao->effect, cmd, slot, map, images, settings, &v);
}

uint64_t roma_study_ao_bytes(const roma_study_ao *ao, uint64_t *build_bytes)
{
    if (build_bytes)
        *build_bytes = 0;
    if (ao && ao->field.ctx)
        return roma_distance_field_bytes(&ao->field, build_bytes);
    if (ao && ao->naadf.ctx)
        return roma_naadf_bytes(&ao->naadf, build_bytes);
    return 0;
}
