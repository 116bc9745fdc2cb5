/* roma_light_effect: shadowed irradiance from punctual lights and area lights on the
 * engine's G-buffer images (shaders/effects/lights_images.comp); punctual lights in an
 * upload buffer per slot, area lights (a scene's emissive triangles and their sampling CDF,
 * effects/light_data.h) set between frames. The surface grid (effects/surface_cells.h),
 * rebuilt from the map's triangles when they move, tells the shadow segments' ends on which
 * side of a wall in its voxels a light lies. */
#include "roma/light_effect.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "effects/image_effect.h"
#include "effects/lit_effect_variants.h"
#include "effects/lit_record.h"
#include "effects/light_data.h"
#include "effects/surface_cells.h"
#include "roma_shared.h"
#include "trace/loop_costs.h"
#include "util/log.h"
#include "vulkan/loop_budget.h"


struct roma_light_effect {
    roma_image_effect base;
    roma_upload lights[ROMA_MAX_FRAMES_IN_FLIGHT];
    roma_light_data area; /* absent when its emitter_count is 0 */
    uint32_t surface_resolution;
    roma_surface_cells grid; /* made on the first record with a light that has an end */
    roma_upload surfaces[ROMA_MAX_FRAMES_IN_FLIGHT]; /* roma_surface_grid per slot */
    int exact; /* the module walks every segment through the BOM (the study's; its loop costs) */
};

roma_result roma_light_settings_resolve(const roma_light_settings *in, roma_light_settings *out)
{
    roma_light_settings s = in ? *in : (roma_light_settings){0};
    if (out)
        memset(out, 0, sizeof *out);
    if (!out)
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_light_settings_resolve: out is NULL");
    if (!isfinite(s.offset_cells) || s.offset_cells < 0.0f || !isfinite(s.skip_cells))
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_light_settings: offset_cells must be finite and not negative, skip_cells finite");
    if (s.max_steps == 0)
        s.max_steps = ROMA_DEFAULT_SHADOW_STEPS;
    if (s.area_samples == 0)
        s.area_samples = ROMA_DEFAULT_AREA_LIGHT_SAMPLES;
    if ((unsigned)s.output > ROMA_LIGHT_OUTPUT_VISIBLE_COUNT)
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_light_settings: output %d is not a roma_light_output",
                         (int)s.output);
    if (s.offset_cells == 0.0f)
        s.offset_cells = ROMA_DEFAULT_OFFSET_CELLS;
    s.skip_cells = s.skip_cells < 0.0f ? 0.0f : s.skip_cells > 0.0f ? s.skip_cells : ROMA_DEFAULT_SHADOW_SKIP_CELLS;
    if (!roma_image_effect_divisor_valid(s.resolution_divisor))
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT, "%s: resolution_divisor %u is not 1, 2 or 4", "roma_light_settings",
                         s.resolution_divisor);
    if (s.resolution_divisor == 0)
        s.resolution_divisor = 1;
    *out = s;
    return ROMA_SUCCESS;
}

roma_result roma_light_effect_create(roma_context *ctx, const roma_light_effect_desc *desc_in,
                                     roma_light_effect **out)
{
    return roma_light_effect_create_variant(ctx, desc_in, "lights_images.comp", 0, out);
}

roma_result roma_light_effect_create_variant(roma_context *ctx, const roma_light_effect_desc *desc_in,
                                             const char *module, int exact, roma_light_effect **out)
{
    roma_light_effect_desc desc = desc_in ? *desc_in : (roma_light_effect_desc){0};
    const roma_logger *log = desc.logger.fn ? &desc.logger : (ctx ? &ctx->logger : NULL);
    if (!out)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_light_effect_create: out is NULL");
    *out = NULL;
    if (!ctx)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_light_effect_create: context is NULL");
    if (desc.frames_in_flight == 0)
        desc.frames_in_flight = 2;
    if (desc.frames_in_flight > ROMA_MAX_FRAMES_IN_FLIGHT)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_light_effect_create: frames_in_flight %u outside [1, %u]", desc.frames_in_flight,
                         ROMA_MAX_FRAMES_IN_FLIGHT);
    if (desc.surface_resolution == 0)
        desc.surface_resolution = ROMA_DEFAULT_LIGHT_SURFACE_RESOLUTION;
    if (desc.surface_resolution < 32 || desc.surface_resolution > 256)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_light_effect_create: surface_resolution %u outside [32, 256]", desc.surface_resolution);
    roma_light_effect *e = calloc(1, sizeof *e);
    if (!e)
        return roma_fail(log, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_light_effect_create: out of host memory");
    roma_result r = roma_image_effect_init(&e->base, ctx, log, "roma_light_effect_record", module,
                                           "image_list_rgba32f.comp", 0.0f, 3,
                                           sizeof(roma_light_images_push), desc.frames_in_flight,
                                           desc.pixel_dispatch);
    if (r != ROMA_SUCCESS) {
        free(e);
        return r;
    }
    e->exact = exact;
    e->surface_resolution = desc.surface_resolution;
    *out = e;
    return ROMA_SUCCESS;
}

void roma_light_effect_destroy(roma_light_effect *e)
{
    if (!e)
        return;
    roma_context *ctx = e->base.ctx;
    for (uint32_t s = 0; s < ROMA_MAX_FRAMES_IN_FLIGHT; ++s) {
        roma_upload_destroy(ctx, &e->lights[s]);
        roma_upload_destroy(ctx, &e->surfaces[s]);
    }
    roma_surface_cells_destroy(&e->grid);
    roma_light_data_destroy(ctx, &e->area);
    roma_image_effect_free(&e->base);
    free(e);
}

roma_result roma_light_effect_set_area_lights(roma_light_effect *e, const roma_scene *scene)
{
    const roma_logger *log = e ? &e->base.logger : NULL;
    if (!e)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_light_effect_set_area_lights: effect is NULL");
    roma_context *ctx = e->base.ctx;
    /* Built aside, swapped in only when complete: a failure keeps the previous set. */
    roma_light_data area = {0};
    if (scene) {
        roma_result r = roma_light_data_create(ctx, scene, log, &area);
        if (r != ROMA_SUCCESS)
            return roma_fail(log, r, "roma_light_effect_set_area_lights: cannot set the scene's area lights");
    }
    roma_light_data_destroy(ctx, &e->area);
    e->area = area;
    e->grid.version = 0; /* the grid ranks the area lights after the walls: built again */
    return ROMA_SUCCESS;
}

roma_result roma_light_effect_record(roma_light_effect *e, VkCommandBuffer cmd, uint32_t slot, const roma_map *map,
                                     const roma_light_images *im, const roma_light *lights, uint32_t light_count,
                                     const roma_light_settings *settings_in)
{
    return roma_light_effect_record_variant(e, cmd, slot, map, im, lights, light_count, settings_in, NULL);
}

roma_result roma_light_effect_record_variant(roma_light_effect *e, VkCommandBuffer cmd, uint32_t slot,
                                             const roma_map *map, const roma_light_images *im,
                                             const roma_light *lights, uint32_t light_count,
                                             const roma_light_settings *settings_in,
                                             const roma_shadow_variant *variant)
{
    const roma_logger *log = e ? &e->base.logger : NULL;
    static const char name[] = "roma_light_effect_record";
    roma_result r = roma_lit_record_check(e ? &e->base : NULL, name, cmd, map, im, lights, light_count);
    if (r != ROMA_SUCCESS)
        return r;
    roma_light_settings s;
    r = roma_light_settings_resolve(settings_in, &s);
    if (r != ROMA_SUCCESS)
        return roma_fail(log, r, "roma_light_effect_record: invalid settings");
    roma_map_info info;
    r = roma_lit_record_begin(&e->base, name, slot, s.frame, map, im, s.resolution_divisor, &info);
    if (r != ROMA_SUCCESS)
        return r;
    roma_upload *buf = &e->lights[slot];
    uint32_t packed = 0, exact_packed = 0;
    r = roma_lit_record_pack(e->base.ctx, buf, lights, light_count, s.exact_light_count, &packed, &exact_packed);
    if (r != ROMA_SUCCESS)
        return r;
    /* Counting visible lights takes the punctual lights only. */
    const uint32_t area_samples = s.output == ROMA_LIGHT_OUTPUT_VISIBLE_COUNT ? 0 : s.area_samples;
    /* The surface grid, for the lights that have an end (not suns), unless the blind-start
     * baseline walks nothing. */
    int ends = e->area.emitter_count && area_samples;
    for (uint32_t i = 0; i < light_count && !ends; ++i)
        ends = lights[i].type != ROMA_LIGHT_DIRECTIONAL;
    const int surfaces = ends && !(variant && variant->blind_start);
    /* Area lights set since the last record into device memory, ahead of the grid's build
     * that ranks them. */
    roma_light_data_record(&e->area, cmd);
    if (surfaces) {
        r = roma_surface_cells_follow_record(&e->grid, &e->surfaces[slot], e->base.ctx, e->surface_resolution,
                                             ROMA_SURFACE_LAYERS_TWO, cmd, slot, map, &e->area, log, name);
        if (r != ROMA_SUCCESS)
            return r;
    }
    /* The slot's lights and surface grid into device memory. */
    const VkPipelineStageFlags2 readers = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    roma_upload_record(buf, cmd, readers, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    if (surfaces)
        roma_upload_record(&e->surfaces[slot], cmd, readers, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    roma_light_images_push push = {.lights = buf->device.address, .bom = info.bom_address,
                                   .emitters = e->area.emitters.device.address,
                                   .cdf = e->area.cdf.device.address,
                                   .config = {im->width, im->height, packed, s.max_steps},
                                   .config2 = {s.seed, e->area.emitter_count, area_samples, s.frame},
                                   .config3 = {s.lights_per_frame, exact_packed, (uint32_t)s.output, 0},
                                   .ray = {s.offset_cells * info.trace_cell, s.skip_cells * info.trace_cell, 0, 0},
                                   .surfaces = surfaces ? e->surfaces[slot].device.address : 0};
    if (variant && variant->blind_start)
        push.bom = 0; /* every BOM walk off */
    const VkImageView views[4] = {im->position, im->normal, im->geometric_normal ? im->geometric_normal : im->normal,
                                  im->output};
    /* The items (lights traced every frame, sampled lights, area-light samples; as
     * lights_images.comp counts them) in parts within the device's loop budget. */
    const uint32_t exact = s.lights_per_frame == 0 ? packed : (exact_packed < packed ? exact_packed : packed);
    const uint32_t rest = packed - exact;
    const uint32_t sampled = s.lights_per_frame == 0 || s.lights_per_frame > rest ? rest : s.lights_per_frame;
    const uint32_t items = exact + sampled + (e->area.emitter_count ? area_samples : 0);
    /* Counting lights walks one skip length of each start (lights_images.comp). */
    const float walk = s.output == ROMA_LIGHT_OUTPUT_VISIBLE_COUNT ? 1.0f : ROMA_START_WALK;
    const roma_shadow_cost shadow = {{info.resolution, info.grid_cell, info.levels}, push.ray[1], walk, s.max_steps,
                                     ROMA_BACK_SKIP_POINT, e->exact};
    uint32_t per_item = roma_loop_cost_punctual_light(&shadow);
    if (e->area.emitter_count) {
        const uint32_t area = roma_loop_cost_area_sample(&shadow, e->area.emitter_count);
        per_item = area > per_item ? area : per_item;
    }
    const roma_loop_parts parts = roma_loop_parts_plan(e->base.ctx, 0, items, per_item, 0, 0);
    roma_loop_parts_get(&parts, 0, push.part);
    r = roma_image_effect_dispatch(&e->base, cmd, slot, &info, views, im->input_layout, &push, im->width,
                                   im->height);
    for (uint32_t part = 1; r == ROMA_SUCCESS && roma_loop_parts_get(&parts, part, push.part); ++part)
        roma_image_effect_dispatch_more(&e->base, cmd, &push);
    if (r == ROMA_SUCCESS)
        roma_image_effect_finish(&e->base, cmd, im->width, im->height);
    if (r == ROMA_SUCCESS) {
        roma_upload_done(buf);
        if (surfaces)
            roma_upload_done(&e->surfaces[slot]);
        roma_light_data_done(&e->area);
    } else if (surfaces) {
        e->grid.version = 0; /* a grid build recorded above goes with the dropped cmd: build it again */
    }
    return r;
}
