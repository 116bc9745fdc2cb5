/* roma_gi_effect: one-bounce GI on the engine's G-buffer images (shaders/effects/
 * gi_images.comp). The scene given between frames brings the surfaces' materials, normals
 * and area lights; the triangles themselves are the map's, where its last build put them:
 * the surface grid the bounce hits look up (effects/surface_cells.h) is rebuilt from the
 * map's positions whenever they or its box have changed, so animation and instances are
 * followed. The punctual lights and the roma_gi_scene record that points at all of it
 * live in upload buffers per frame slot (vulkan/upload.h: device-local, staged where the
 * host cannot map it). */
#include "roma/gi_effect.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "effects/image_effect.h"
#include "effects/lit_effect_variants.h"
#include "effects/lit_record.h"
#include "map/map_internal.h"
#include "effects/light_data.h"
#include "effects/scene_buffers.h"
#include "effects/surface_cells.h"
#include "roma/ao_effect.h"
#include "roma_shared.h"
#include "trace/loop_costs.h"
#include "util/log.h"
#include "vulkan/loop_budget.h"

/* What set_scene uploads: replaced as a whole. */
typedef struct gi_surfaces {
    roma_scene_buffers materials; /* albedo per triangle, normals per vertex (its positions go unused) */
    roma_light_data emitters;     /* the scene's area lights (its punctual lights come per record) */
} gi_surfaces;

struct roma_gi_effect {
    roma_image_effect base;
    uint32_t surface_resolution;
    gi_surfaces surfaces; /* materials.triangle_count == 0: no scene */
    roma_surface_cells grid;        /* made on the first record with a scene */
    roma_upload lights[ROMA_MAX_FRAMES_IN_FLIGHT];
    roma_upload scene[ROMA_MAX_FRAMES_IN_FLIGHT]; /* roma_gi_scene per slot */
    int exact; /* the module walks bounce and shadow rays through the BOM (the study's) */
};

roma_result roma_gi_settings_resolve(const roma_gi_settings *in, roma_gi_settings *out)
{
    roma_gi_settings s = in ? *in : (roma_gi_settings){0};
    if (out)
        memset(out, 0, sizeof *out);
    if (!out)
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_gi_settings_resolve: out is NULL");
    if (!isfinite(s.offset_cells) || s.offset_cells < 0.0f || !isfinite(s.skip_cells) ||
        !isfinite(s.shadow_skip_cells))
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_gi_settings: offset_cells must be finite and not negative, the skips finite");
    if (s.samples == 0)
        s.samples = ROMA_DEFAULT_GI_SAMPLES;
    if (s.max_steps == 0)
        s.max_steps = ROMA_DEFAULT_SHADOW_STEPS;
    if (s.offset_cells == 0.0f)
        s.offset_cells = ROMA_DEFAULT_OFFSET_CELLS;
    s.skip_cells = s.skip_cells < 0.0f ? 0.0f : s.skip_cells > 0.0f ? s.skip_cells : ROMA_DEFAULT_AO_SKIP_CELLS;
    s.shadow_skip_cells = s.shadow_skip_cells < 0.0f   ? 0.0f
                          : s.shadow_skip_cells > 0.0f ? s.shadow_skip_cells
                                                       : ROMA_DEFAULT_SHADOW_SKIP_CELLS;
    if (!roma_image_effect_divisor_valid(s.resolution_divisor))
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT, "%s: resolution_divisor %u is not 1, 2 or 4", "roma_gi_settings",
                         s.resolution_divisor);
    if (s.resolution_divisor == 0)
        s.resolution_divisor = 1;
    *out = s;
    return ROMA_SUCCESS;
}

static void surfaces_free(roma_context *ctx, gi_surfaces *s)
{
    roma_light_data_destroy(ctx, &s->emitters);
    roma_scene_buffers_destroy(ctx, &s->materials);
    memset(s, 0, sizeof *s);
}

roma_result roma_gi_effect_create(roma_context *ctx, const roma_gi_effect_desc *desc_in, roma_gi_effect **out)
{
    return roma_gi_effect_create_variant(ctx, desc_in, "gi_images.comp", 0, out);
}

roma_result roma_gi_effect_create_variant(roma_context *ctx, const roma_gi_effect_desc *desc_in, const char *module,
                                          int exact, roma_gi_effect **out)
{
    roma_gi_effect_desc desc = desc_in ? *desc_in : (roma_gi_effect_desc){0};
    const roma_logger *log = desc.logger.fn ? &desc.logger : (ctx ? &ctx->logger : NULL);
    if (!out)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_gi_effect_create: out is NULL");
    *out = NULL;
    if (!ctx)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_gi_effect_create: context is NULL");
    if (desc.frames_in_flight == 0)
        desc.frames_in_flight = 2;
    if (desc.surface_resolution == 0)
        desc.surface_resolution = ROMA_DEFAULT_GI_SURFACE_RESOLUTION;
    if (desc.frames_in_flight > ROMA_MAX_FRAMES_IN_FLIGHT)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_gi_effect_create: frames_in_flight %u outside [1, %u]",
                         desc.frames_in_flight, ROMA_MAX_FRAMES_IN_FLIGHT);
    if (desc.surface_resolution < 32 || desc.surface_resolution > 256)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_gi_effect_create: surface_resolution %u outside [32, 256]", desc.surface_resolution);
    roma_gi_effect *e = calloc(1, sizeof *e);
    if (!e)
        return roma_fail(log, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_gi_effect_create: out of host memory");
    e->surface_resolution = desc.surface_resolution;
    roma_result r = roma_image_effect_init(&e->base, ctx, log, "roma_gi_effect_record", module,
                                           "image_list_rgba32f.comp", 0.0f, 3,
                                           sizeof(roma_gi_images_push), desc.frames_in_flight,
                                           desc.pixel_dispatch);
    if (r != ROMA_SUCCESS) {
        free(e);
        return r;
    }
    e->exact = exact;
    *out = e;
    return ROMA_SUCCESS;
}

void roma_gi_effect_destroy(roma_gi_effect *e)
{
    if (!e)
        return;
    roma_context *ctx = e->base.ctx;
    for (uint32_t s = 0; s < ROMA_MAX_FRAMES_IN_FLIGHT; ++s) {
        roma_upload_destroy(ctx, &e->lights[s]);
        roma_upload_destroy(ctx, &e->scene[s]);
    }
    surfaces_free(ctx, &e->surfaces);
    roma_surface_cells_destroy(&e->grid);
    roma_image_effect_free(&e->base);
    free(e);
}

roma_result roma_gi_effect_set_scene(roma_gi_effect *e, const roma_scene *scene)
{
    const roma_logger *log = e ? &e->base.logger : NULL;
    if (!e)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_gi_effect_set_scene: effect is NULL");
    roma_context *ctx = e->base.ctx;
    if (!scene) {
        surfaces_free(ctx, &e->surfaces);
        return ROMA_SUCCESS;
    }
    /* Built aside, swapped in only when complete: a failure keeps the previous scene. */
    gi_surfaces s;
    memset(&s, 0, sizeof s);
    roma_scene_view v;
    roma_result r = roma_scene_get_view(scene, &v);
    if (r == ROMA_SUCCESS && !(v.triangle_count > 0))
        r = roma_fail(log, ROMA_ERROR_INVALID_SCENE, "roma_gi_effect_set_scene: the scene has no triangles");
    if (r == ROMA_SUCCESS)
        r = roma_scene_buffers_create(ctx, scene, &s.materials);
    if (r == ROMA_SUCCESS)
        r = roma_light_data_create(ctx, scene, log, &s.emitters);
    if (r != ROMA_SUCCESS) {
        surfaces_free(ctx, &s);
        return roma_fail(log, r, "roma_gi_effect_set_scene: cannot upload the scene's surfaces");
    }
    surfaces_free(ctx, &e->surfaces);
    e->surfaces = s;
    e->grid.version = 0; /* the grid ranks the area lights after the walls: built again */
    return ROMA_SUCCESS;
}

roma_result roma_gi_effect_record(roma_gi_effect *e, VkCommandBuffer cmd, uint32_t slot, const roma_map *map,
                                  const roma_light_images *im, const roma_light *lights, uint32_t light_count,
                                  const roma_gi_settings *settings_in)
{
    return roma_gi_effect_record_variant(e, cmd, slot, map, im, lights, light_count, settings_in, NULL);
}

roma_result roma_gi_effect_record_variant(roma_gi_effect *e, VkCommandBuffer cmd, uint32_t slot, const roma_map *map,
                                          const roma_light_images *im, const roma_light *lights, uint32_t light_count,
                                          const roma_gi_settings *settings_in, const roma_shadow_variant *variant)
{
    const roma_logger *log = e ? &e->base.logger : NULL;
    static const char name[] = "roma_gi_effect_record";
    roma_result r = roma_lit_record_check(e ? &e->base : NULL, name, cmd, map, im, lights, light_count);
    if (r != ROMA_SUCCESS)
        return r;
    roma_gi_settings s;
    r = roma_gi_settings_resolve(settings_in, &s);
    if (r != ROMA_SUCCESS)
        return roma_fail(log, r, "roma_gi_effect_record: invalid settings");
    roma_map_info info;
    /* The lights and the scene record live in buffers per slot (one record per slot and frame). */
    r = roma_lit_record_begin(&e->base, name, slot, s.frame, map, im, s.resolution_divisor, &info);
    if (r != ROMA_SUCCESS)
        return r;
    roma_context *ctx = e->base.ctx;
    uint32_t packed = 0, exact = 0;
    r = roma_lit_record_pack(ctx, &e->lights[slot], lights, light_count, 0, &packed, &exact);
    if (r == ROMA_SUCCESS)
        r = roma_lit_slot_buffer(ctx, &e->scene[slot], sizeof(roma_gi_scene));
    if (r != ROMA_SUCCESS)
        return r;
    const gi_surfaces *sf = &e->surfaces;
    const int have_scene = sf->materials.triangle_count > 0;
    /* Area lights set since the last record into device memory, ahead of the grid's build
     * that ranks them. */
    roma_light_data_record(&sf->emitters, cmd);
    if (have_scene) {
        /* Three layers: the bounce hits find a lamp that shares its cells with a ceiling. */
        r = roma_surface_cells_follow(&e->grid, ctx, e->surface_resolution, ROMA_SURFACE_LAYERS_EMITTERS, cmd, slot,
                                      map, &sf->emitters, log, name);
        if (r != ROMA_SUCCESS)
            return r;
        /* The scene's vertex normals fit the map's vertices only where no build moved them;
         * elsewhere (animation, instances) the face normals serve. */
        const uint32_t normals = !map->positions_moved && map->vertex_count == sf->materials.vertex_count
                                     ? sf->materials.vertex_count
                                     : 0;
        roma_gi_scene gs = {
            .surfaces = roma_surface_cells_view(&e->grid, map),
            .normals = sf->materials.normals.address, .albedo = sf->materials.albedo.address,
            .emitters = sf->emitters.emitters.device.address, .cdf = sf->emitters.cdf.device.address,
            .config = {sf->emitters.emitter_count, packed,
                       variant && variant->rsm_views ? ROMA_GI_PUNCTUAL_RSM : ROMA_GI_PUNCTUAL_RAYS, 0},
            .config2 = {sf->materials.triangle_count, normals, 0, 0},
        };
        memcpy(roma_upload_write(&e->scene[slot], sizeof gs), &gs, sizeof gs);
    }
    /* The slot's lights and scene record into device memory (vulkan/upload.h). */
    roma_upload_record(&e->lights[slot], cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    roma_upload_record(&e->scene[slot], cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    roma_gi_images_push push = {
        .scene = have_scene ? e->scene[slot].device.address : 0, .lights = e->lights[slot].device.address,
        .bom = info.bom_address,
        .config = {im->width, im->height, s.samples, s.frame},
        .config2 = {s.seed, s.max_steps, 0, 0},
        .ray = {s.offset_cells * info.trace_cell, s.skip_cells * info.trace_cell, s.shadow_skip_cells * info.trace_cell,
                0},
    };
    const int exact_rays = e->exact;
    if (variant && variant->blind_start)
        push.bom = 0; /* every BOM walk off */
    push.config2[3] = exact_rays; /* read by the study's exact module only */
    if (variant && variant->rsm_views) {
        push.views = variant->rsm_views;
        push.config2[2] = variant->rsm_view_count;
        push.ray[3] = variant->rsm_tolerance;
    }
    const VkImageView views[4] = {im->position, im->normal, im->geometric_normal ? im->geometric_normal : im->normal,
                                  im->output};
    /* Samples and the lights at their hits in parts within the device's loop budget. */
    const roma_loop_grid grid = {info.resolution, info.grid_cell, info.levels};
    const roma_shadow_cost shadow = {grid, push.ray[2], ROMA_START_WALK, s.max_steps, ROMA_BACK_SKIP_POINT, exact_rays};
    uint32_t bounce = roma_loop_cost_gi_bounce(grid, push.ray[1], exact_rays) + push.config2[2]; /* RSM views */
    if (have_scene && sf->emitters.emitter_count)
        bounce += roma_loop_cost_area_sample(&shadow, sf->emitters.emitter_count);
    const roma_loop_parts parts =
        roma_loop_parts_plan(ctx, 0, s.samples, bounce, packed, roma_loop_cost_punctual_light(&shadow));
    roma_loop_parts_get(&parts, 0, push.part);
    r = roma_image_effect_dispatch(&e->base, cmd, slot, &info, views, im->input_layout, &push, im->width,
                                   im->height);
    for (uint32_t part = 1; r == ROMA_SUCCESS && roma_loop_parts_get(&parts, part, push.part); ++part)
        roma_image_effect_dispatch_more(&e->base, cmd, &push);
    if (r == ROMA_SUCCESS)
        roma_image_effect_finish(&e->base, cmd, im->width, im->height);
    if (r == ROMA_SUCCESS) {
        roma_upload_done(&e->lights[slot]);
        roma_upload_done(&e->scene[slot]);
        roma_light_data_done(&e->surfaces.emitters);
    }
    if (r != ROMA_SUCCESS)
        e->grid.version = 0; /* a grid build recorded above goes with the dropped cmd: build it again */
    return r;
}
