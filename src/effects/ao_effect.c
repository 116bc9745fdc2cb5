/* roma_ao_effect: ambient occlusion from the engine's G-buffer images
 * (shaders/effects/ao_images.comp), sets from a per-slot pool. */
#include "roma/ao_effect.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "effects/ao_effect_variant.h"
#include "effects/image_effect.h"
#include "effects/surface_cells.h"
#include "roma_shared.h"
#include "trace/loop_costs.h"
#include "util/log.h"
#include "vulkan/loop_budget.h"
#include "vulkan/vk_internal.h"

struct roma_ao_effect {
    roma_image_effect base;
    int roma_rays; /* the module is ROMA's own (ao_images.comp) */
    /* ROMA_AO_START_SURFACES and ROMA_AO_TRACE_SURFACES: a pass each (ao_images_surfaces.comp,
     * ao_images_surface_rays.comp), made by the first record that asks for it, and the surface
     * grid they share (with the count layer the second needs) and its record per slot, made by
     * the first of them. */
    roma_image_effect surface_pass, surface_rays_pass;
    uint32_t frames_in_flight, surface_resolution;
    roma_pixel_dispatch pixel_dispatch;
    roma_surface_cells grid;
    roma_upload surfaces[ROMA_MAX_FRAMES_IN_FLIGHT];
};

roma_result roma_ao_settings_resolve(const roma_ao_settings *in, roma_ao_settings *out)
{
    roma_ao_settings s = in ? *in : (roma_ao_settings){0};
    if (out)
        memset(out, 0, sizeof *out);
    if (!out)
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_ao_settings_resolve: out is NULL");
    if (!isfinite(s.radius) || s.radius < 0.0f || !isfinite(s.offset_cells) || s.offset_cells < 0.0f ||
        !isfinite(s.skip_cells) || (unsigned)s.start > ROMA_AO_START_SURFACES ||
        (unsigned)s.trace > ROMA_AO_TRACE_SURFACES)
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ao_settings: radius and offset_cells must be finite and not negative, skip_cells "
                         "finite, start a roma_ao_start, trace a roma_ao_trace");
    if (s.samples == 0)
        s.samples = ROMA_DEFAULT_AO_SAMPLES;
    if (s.offset_cells == 0.0f)
        s.offset_cells = ROMA_DEFAULT_OFFSET_CELLS;
    s.skip_cells = s.skip_cells < 0.0f ? 0.0f : s.skip_cells > 0.0f ? s.skip_cells : ROMA_DEFAULT_AO_SKIP_CELLS;
    if (!roma_image_effect_divisor_valid(s.resolution_divisor))
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT, "%s: resolution_divisor %u is not 1, 2 or 4", "roma_ao_settings",
                         s.resolution_divisor);
    if (s.resolution_divisor == 0)
        s.resolution_divisor = 1;
    *out = s;
    return ROMA_SUCCESS;
}

/* One AO pass on the images (module: its shader): inputs position, normal, geometric normal;
 * output the AO image. */
static roma_result ao_pass_init(roma_image_effect *pass, roma_context *ctx, const roma_logger *log, const char *module,
                                uint32_t frames_in_flight, roma_pixel_dispatch dispatch)
{
    return roma_image_effect_init(pass, ctx, log, "roma_ao_effect_record", module, "image_list_r32f.comp", 1.0f, 3,
                                  sizeof(roma_ao_push), frames_in_flight, dispatch);
}

roma_result roma_ao_effect_create(roma_context *ctx, const roma_ao_effect_desc *desc_in, roma_ao_effect **out)
{
    return roma_ao_effect_create_variant(ctx, desc_in, "ao_images.comp", out);
}

roma_result roma_ao_effect_create_variant(roma_context *ctx, const roma_ao_effect_desc *desc_in, const char *module,
                                          roma_ao_effect **out)
{
    roma_ao_effect_desc desc = desc_in ? *desc_in : (roma_ao_effect_desc){0};
    const roma_logger *log = desc.logger.fn ? &desc.logger : (ctx ? &ctx->logger : NULL);
    if (!out)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_ao_effect_create: out is NULL");
    *out = NULL;
    if (!ctx)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_ao_effect_create: context is NULL");
    if (desc.frames_in_flight == 0)
        desc.frames_in_flight = 2;
    if (desc.frames_in_flight > ROMA_MAX_FRAMES_IN_FLIGHT)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_ao_effect_create: frames_in_flight %u outside [1, %u]",
                         desc.frames_in_flight, ROMA_MAX_FRAMES_IN_FLIGHT);
    if (desc.surface_resolution != 0 && (desc.surface_resolution < 32 || desc.surface_resolution > 256))
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ao_effect_create: surface_resolution %u outside [32, 256]", desc.surface_resolution);
    roma_ao_effect *e = calloc(1, sizeof *e);
    if (!e)
        return roma_fail(log, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_ao_effect_create: out of host memory");
    roma_result r = ao_pass_init(&e->base, ctx, log, module, desc.frames_in_flight, desc.pixel_dispatch);
    if (r != ROMA_SUCCESS) {
        free(e);
        return r;
    }
    e->surface_resolution = desc.surface_resolution;
    e->frames_in_flight = desc.frames_in_flight;
    e->pixel_dispatch = desc.pixel_dispatch;
    e->roma_rays = strcmp(module, "ao_images.comp") == 0;
    *out = e;
    return ROMA_SUCCESS;
}

void roma_ao_effect_destroy(roma_ao_effect *e)
{
    if (!e)
        return;
    for (uint32_t s = 0; s < ROMA_MAX_FRAMES_IN_FLIGHT; ++s)
        roma_upload_destroy(e->base.ctx, &e->surfaces[s]);
    roma_surface_cells_destroy(&e->grid);
    if (e->surface_pass.ctx)
        roma_image_effect_free(&e->surface_pass);
    if (e->surface_rays_pass.ctx)
        roma_image_effect_free(&e->surface_rays_pass);
    roma_image_effect_free(&e->base);
    free(e);
}

roma_result roma_ao_effect_record(roma_ao_effect *e, VkCommandBuffer cmd, uint32_t slot, const roma_map *map,
                                  const roma_ao_images *im, const roma_ao_settings *settings_in)
{
    return roma_ao_effect_record_variant(e, cmd, slot, map, im, settings_in, NULL);
}

roma_result roma_ao_effect_record_variant(roma_ao_effect *e, VkCommandBuffer cmd, uint32_t slot, const roma_map *map,
                                          const roma_ao_images *im, const roma_ao_settings *settings_in,
                                          const roma_ao_variant *variant)
{
    if (!e || !cmd || !map || !im)
        return roma_fail(e ? &e->base.logger : NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_ao_effect_record: %s is NULL",
                         !e ? "effect" : !cmd ? "cmd" : !map ? "map" : "images");
    if (!im->width || !im->height || !im->position || !im->normal || !im->output)
        return roma_fail(&e->base.logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ao_effect_record: width, height, position, normal and output are required");
    roma_result size = roma_image_effect_check_size(&e->base, "roma_ao_effect_record", im->width, im->height);
    if (size != ROMA_SUCCESS)
        return size;
    roma_ao_settings s;
    roma_result r = roma_ao_settings_resolve(settings_in, &s);
    if (r != ROMA_SUCCESS)
        return roma_fail(&e->base.logger, r, "roma_ao_effect_record: invalid settings");
    /* The surface grid for the rays' start, or for the whole rays, where asked (the study's blind
     * start walks nothing), traced by a pass of its own. */
    const int grid_usable = e->roma_rays && !(variant && variant->blind_start);
    const int rays = grid_usable && s.trace == ROMA_AO_TRACE_SURFACES;
    const int surfaces = grid_usable && (rays || s.start == ROMA_AO_START_SURFACES);
    roma_image_effect *pass = rays ? &e->surface_rays_pass : surfaces ? &e->surface_pass : &e->base;
    if (surfaces && !pass->ctx) {
        r = ao_pass_init(pass, e->base.ctx, &e->base.logger,
                         rays ? "ao_images_surface_rays.comp" : "ao_images_surfaces.comp", e->frames_in_flight,
                         e->pixel_dispatch);
        if (r != ROMA_SUCCESS) {
            memset(pass, 0, sizeof *pass);
            return r;
        }
    }
    roma_map_info info;
    r = roma_image_effect_begin(pass, slot, s.frame, map, im->pixels, im->width, im->height, s.resolution_divisor,
                                &info);
    if (r != ROMA_SUCCESS)
        return r;
    /* The grid's record lives in one buffer per slot, and the grid follows one map: a second
     * record in the slot's frame would change what the first one's dispatch reads. */
    if (surfaces && ((e->surface_pass.ctx && roma_slot_sets_same_frame(&e->surface_pass.sets, slot, s.frame)) ||
                     (e->surface_rays_pass.ctx &&
                      roma_slot_sets_same_frame(&e->surface_rays_pass.sets, slot, s.frame))))
        return roma_fail(&e->base.logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_ao_effect_record: one record per frame slot with ROMA_AO_START_SURFACES or "
                         "ROMA_AO_TRACE_SURFACES (slot %u was recorded this frame)", slot);
    uint32_t surface_cells = 0, ray_cells = 0; /* the most grid cells a ray's start and whole walk take */
    if (surfaces) {
        /* The grid at the map's RES unless the desc gave one (made by the first such record). */
        const uint32_t res = e->surface_resolution ? e->surface_resolution
                             : info.resolution < 32 ? 32 : info.resolution > 256 ? 256 : info.resolution;
        r = roma_surface_cells_follow_record(&e->grid, &e->surfaces[slot], e->base.ctx, res,
                                             ROMA_SURFACE_LAYERS_COUNTS, cmd, slot, map, NULL, &e->base.logger,
                                             "roma_ao_effect_record");
        if (r != ROMA_SUCCESS)
            return r;
        /* From the surface point to the query's start: the offset, the skip and half a texel's
         * diagonal to the column's centre; a segment crosses at most 3 cells per cell of length, and one. */
        const float reach = (s.offset_cells + s.skip_cells + 1.0f) * info.trace_cell / e->grid.cell;
        surface_cells = reach < (float)(ROMA_AO_SURFACE_CELLS / 3) ? 3u * (uint32_t)ceilf(reach) + 1u
                                                                    : ROMA_AO_SURFACE_CELLS;
        /* The whole ray's walk: its length's cells, to the grid's edge when unbounded. */
        if (rays)
            ray_cells = roma_loop_cost_walk((roma_loop_grid){e->grid.resolution, e->grid.cell, 1},
                                            s.radius > 0.0f ? s.radius : INFINITY, UINT32_MAX);
        roma_upload_record(&e->surfaces[slot], cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                           VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    }
    roma_ao_push push = {.surfaces = surfaces ? e->surfaces[slot].device.address : 0,
                         .config = {im->width, im->height, s.samples, s.frame},
                         .config2 = {s.seed, ray_cells, 0, 1},
                         .ray = {s.offset_cells * info.trace_cell, s.radius > 0.0f ? s.radius : INFINITY,
                                 s.skip_cells * info.trace_cell, 0.0f}};
    uint32_t sample_cost = roma_loop_cost_ao_ray((roma_loop_grid){info.resolution, info.grid_cell, info.levels},
                                                 push.ray[2], push.ray[1], surface_cells, ray_cells);
    if (variant) { /* the study's: its own fields of the push, its structure in the BOM's place */
        if (variant->blind_start)
            push.config2[3] = 0;
        push.config2[1] = variant->push.config2[1];
        push.config2[2] = variant->push.config2[2];
        push.ray[3] = variant->push.ray[3];
        memcpy(push.eye, variant->push.eye, sizeof push.eye);
        memcpy(push.forward, variant->push.forward, sizeof push.forward);
        memcpy(push.right, variant->push.right, sizeof push.right);
        memcpy(push.up, variant->push.up, sizeof push.up);
        if (variant->bound)
            info.bom_view = variant->bound;
        if (variant->sample_cost)
            sample_cost = variant->sample_cost;
    }
    if (surfaces) /* the surface grid's fields, whatever a variant set */
        push.ray[3] = (float)surface_cells;
    if (rays)
        push.config2[1] = ray_cells;
    const VkImageView views[4] = {im->position, im->normal, im->geometric_normal ? im->geometric_normal : im->normal,
                                  im->output};
    /* The samples in parts within the device's loop budget (one part where it has none). */
    const roma_loop_parts parts = roma_loop_parts_plan(e->base.ctx, 0, s.samples, sample_cost, 0, 0);
    uint32_t range[4];
    for (uint32_t part = 0; r == ROMA_SUCCESS && roma_loop_parts_get(&parts, part, range); ++part) {
        push.sample_first = range[0];
        push.sample_end = range[1];
        if (part == 0)
            r = roma_image_effect_dispatch(pass, cmd, slot, &info, views, im->input_layout, &push, im->width,
                                           im->height);
        else
            roma_image_effect_dispatch_more(pass, cmd, &push);
    }
    if (r == ROMA_SUCCESS)
        roma_image_effect_finish(pass, cmd, im->width, im->height);
    if (r == ROMA_SUCCESS && surfaces)
        roma_upload_done(&e->surfaces[slot]);
    else if (surfaces)
        e->grid.version = 0; /* a grid build recorded above goes with the dropped cmd: build it again */
    return r;
}
