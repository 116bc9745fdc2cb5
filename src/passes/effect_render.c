#include "passes/effect_render.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "study/distance_field.h"
#include "study/naadf.h"
#include "passes/ao.h"
#include "passes/denoiser.h"
#include "study/gbuffer.h"
#include "effects/light_data.h"
#include "passes/pixel_pass.h"
#include "study/rsm_views.h"
#include "effects/scene_buffers.h"
#include "effects/surface_cells.h"
#include "roma/sampling.h"
#include "trace/loop_costs.h"
#include "vulkan/loop_budget.h"

#define PI_F 3.14159265358979323846f

typedef struct renderer {
    roma_context *ctx;
    const roma_effect_render_desc *desc;
    roma_effect_plan plan;
    roma_scene_buffers geometry;
    roma_gbuffer *gbuffer;
    /* Interactive mode (a camera path): the previous frame's G-buffer and the
     * resolve / temporal / a-trous chain. */
    roma_gbuffer *gbuffer_previous;
    roma_denoiser denoiser;
    int interactive;
    roma_map *maps[ROMA_PASS_COUNT];
    roma_gpu_timer *build_timers[ROMA_PASS_COUNT]; /* one per map: its "bom" and "rotate" scopes */
    roma_light_data lights;
    roma_ao_pass *ao;
    roma_distance_field distance_field; /* ROMA_AO_METHOD_DISTANCE_FIELD: built every frame */
    roma_naadf naadf;                   /* ROMA_AO_METHOD_NAADF: built every frame */
    /* Screen-space AO with a stochastic depth map: its layers, rasterized every frame, and
     * their pixels one after the other, bound to the AO pass in the BOM's place. */
    roma_gbuffer *sd_layers[ROMA_AO_SSAO_MAX_LAYERS];
    roma_buffer sd_pixels;
    VkBufferView sd_view;
    roma_pixel_pass punctual, soft, many, gi;
    roma_gbuffer_list list; /* covered pixels of the current G-buffer, for every tracing pass */
    roma_gbuffer *rsm[ROMA_MAX_RSM_VIEWS];
    roma_rsm_views rsm_views;
    uint32_t rsm_size;
    roma_buffer views_buffer;
    roma_surface_cells surfaces; /* GI: the triangle in each cell, built on the first frame */
    roma_buffer gi_scene;        /* roma_gi_scene */
    roma_buffer accum[ROMA_PASS_COUNT];
    roma_buffer mask;
    roma_gpu_timer *timer;
    uint32_t mask_words;
    float near_plane;
} renderer;

static const VkBufferUsageFlags ACCUM_USAGE = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                              VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                              VK_BUFFER_USAGE_TRANSFER_DST_BIT;

/* Accumulator element size of each pass (0: none). */
static size_t accum_element(roma_pass_kind pass)
{
    switch (pass) {
    case ROMA_PASS_AO: return sizeof(uint32_t);
    case ROMA_PASS_PUNCTUAL_LIGHTS:
    case ROMA_PASS_SOFT_SHADOWS:
    case ROMA_PASS_GI: return 4 * sizeof(float);
    case ROMA_PASS_MANY_LIGHTS: return 2 * sizeof(uint32_t);
    default: return 0;
    }
}

/* Interactive mode: whether the passes of effect e (0 ao, 1 direct, 2 gi, 3
 * lights: the order of roma_effect_images) run. */
static int effect_traced(const renderer *R, int e)
{
    const roma_effect_plan *p = &R->plan;
    switch (e) {
    case 0: return roma_effect_plan_runs(p, ROMA_PASS_AO);
    case 1: return roma_effect_plan_runs(p, ROMA_PASS_PUNCTUAL_LIGHTS) || roma_effect_plan_runs(p, ROMA_PASS_SOFT_SHADOWS);
    case 2: return roma_effect_plan_runs(p, ROMA_PASS_GI);
    default: return roma_effect_plan_runs(p, ROMA_PASS_MANY_LIGHTS);
    }
}

/* The GI pass, its surface grid (at the RES of the map it traces) and what its
 * shader reads at a hit. */
static roma_result create_gi(renderer *R, const roma_scene *scene)
{
    roma_context *ctx = R->ctx;
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    /* Hits need their surface (the grid) for every light but point and spot lights
     * through RSMs, which hold the surfaces they light. */
    int directional = 0;
    const roma_gpu_light *lights = R->lights.host_lights;
    for (uint32_t i = 0; i < R->lights.light_count; ++i)
        directional |= (uint32_t)lights[i].position_type[3] == ROMA_GPU_LIGHT_DIRECTIONAL;
    const int surfaces = R->lights.emitter_count || directional || R->desc->gi_punctual_rays;
    const int rsm = roma_effect_plan_runs(&R->plan, ROMA_PASS_RSM);
    const uint32_t routes[2] = {(uint32_t)surfaces, (uint32_t)rsm}; /* gi.comp's constants */
    roma_result r = roma_pixel_pass_create_spec(ctx, "gi.comp", sizeof(roma_gi_push), 1, routes, 2, &R->gi);
    if (r == ROMA_SUCCESS && surfaces)
        r = roma_surface_cells_create(ctx, R->plan.maps[R->plan.pass_map[ROMA_PASS_GI]].resolution, &R->surfaces);
    if (r == ROMA_SUCCESS && surfaces)
        r = roma_surface_cells_place(&R->surfaces, v.bounds_min, v.bounds_max);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, sizeof(roma_gi_scene),
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                               ROMA_MEMORY_UPLOAD, &R->gi_scene);
    if (r != ROMA_SUCCESS)
        return r;
    const roma_surface_cells *c = &R->surfaces;
    roma_gi_scene gs = {
        .cells = c->cells.address, .indices = R->geometry.indices.address,
        .positions = R->geometry.positions.address, .normals = R->geometry.normals.address,
        .albedo = R->geometry.albedo.address, .emitters = R->lights.emitters.address, .cdf = R->lights.cdf.address,
        .grid = {c->origin[0], c->origin[1], c->origin[2], c->cell},
        .config = {c->resolution, R->lights.emitter_count, R->lights.light_count,
                   R->desc->gi_punctual_rays ? ROMA_GI_PUNCTUAL_RAYS : ROMA_GI_PUNCTUAL_RSM},
        .config2 = {R->geometry.triangle_count, R->geometry.vertex_count, 0, 0},
    };
    memcpy(R->gi_scene.mapped, &gs, sizeof gs);
    return ROMA_SUCCESS;
}

static roma_result create_resources(renderer *R, const roma_scene *scene)
{
    roma_context *ctx = R->ctx;
    const roma_effect_render_desc *d = R->desc;
    const size_t pixels = (size_t)d->width * d->height;
    roma_result r = roma_scene_buffers_create(ctx, scene, &R->geometry);
    if (r == ROMA_SUCCESS)
        r = roma_gbuffer_create(ctx, d->width, d->height, &R->gbuffer);
    if (r == ROMA_SUCCESS)
        r = roma_gpu_timer_create(ctx, 2 * ROMA_PASS_COUNT, &R->timer);
    if (r == ROMA_SUCCESS)
        r = roma_gbuffer_list_create(ctx, d->width, d->height, &R->list);
    for (uint32_t i = 0; i < R->plan.map_count && r == ROMA_SUCCESS; ++i) {
        roma_map_desc md = {.resolution = R->plan.maps[i].resolution, .angular = R->plan.maps[i].angular};
        r = roma_map_create(ctx, &md, scene, &R->maps[i]);
        if (r == ROMA_SUCCESS)
            r = roma_gpu_timer_create(ctx, 2, &R->build_timers[i]);
    }
    const int lit = roma_effect_plan_runs(&R->plan, ROMA_PASS_PUNCTUAL_LIGHTS) ||
                    roma_effect_plan_runs(&R->plan, ROMA_PASS_RSM) ||
                    roma_effect_plan_runs(&R->plan, ROMA_PASS_SOFT_SHADOWS) ||
                    roma_effect_plan_runs(&R->plan, ROMA_PASS_MANY_LIGHTS) ||
                    roma_effect_plan_runs(&R->plan, ROMA_PASS_GI);
    if (r == ROMA_SUCCESS && lit)
        r = roma_light_data_create(ctx, scene, d->many_light_positions, R->plan.many_light_count, &R->lights);
    if (r == ROMA_SUCCESS && roma_effect_plan_runs(&R->plan, ROMA_PASS_AO))
        r = roma_ao_pass_create_mode(ctx, d->ao_method, &R->ao);
    if (r == ROMA_SUCCESS && roma_effect_plan_runs(&R->plan, ROMA_PASS_AO) &&
        (d->ao_method == ROMA_AO_METHOD_DISTANCE_FIELD || d->ao_method == ROMA_AO_METHOD_NAADF)) {
        roma_map_info info;
        r = roma_map_get_info(R->maps[R->plan.pass_map[ROMA_PASS_AO]], &info);
        if (r == ROMA_SUCCESS && d->ao_method == ROMA_AO_METHOD_DISTANCE_FIELD)
            r = roma_distance_field_create(ctx, info.bom_buffer, info.resolution, &R->distance_field);
        else if (r == ROMA_SUCCESS)
            r = roma_naadf_create(ctx, info.bom_buffer, info.resolution, &R->naadf);
    }
    /* The layers share the first one's pipelines (as the RSM views share the G-buffer's). */
    for (uint32_t l = 0; r == ROMA_SUCCESS && roma_effect_plan_runs(&R->plan, ROMA_PASS_AO) && l < d->ssao_layers; ++l)
        r = l == 0 ? roma_gbuffer_create_stochastic(ctx, d->width, d->height, &R->sd_layers[l])
                   : roma_gbuffer_create_sharing(R->sd_layers[0], d->width, d->height, &R->sd_layers[l]);
    if (r == ROMA_SUCCESS && R->sd_layers[0]) {
        const VkDeviceSize layer = (VkDeviceSize)pixels * sizeof(roma_gbuffer_pixel);
        if (4ull * pixels * d->ssao_layers > ctx->properties.limits.maxTexelBufferElements)
            r = roma_fail(&ctx->logger, ROMA_ERROR_UNSUPPORTED,
                          "roma_effect_render: %u depth layers of %ux%u exceed maxTexelBufferElements", d->ssao_layers,
                          d->width, d->height);
        if (r == ROMA_SUCCESS)
            r = roma_buffer_create(ctx, layer * d->ssao_layers,
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                                   ROMA_MEMORY_DEVICE, &R->sd_pixels);
        if (r == ROMA_SUCCESS)
            r = roma_buffer_view_create(ctx, R->sd_pixels.buffer, VK_FORMAT_R32G32B32A32_UINT, &R->sd_view);
    }
    if (r == ROMA_SUCCESS && roma_effect_plan_runs(&R->plan, ROMA_PASS_PUNCTUAL_LIGHTS))
        r = roma_pixel_pass_create(ctx, "punctual_lights.comp", sizeof(roma_punctual_push), 1, &R->punctual);
    if (r == ROMA_SUCCESS && roma_effect_plan_runs(&R->plan, ROMA_PASS_SOFT_SHADOWS))
        r = roma_pixel_pass_create(ctx, "soft_shadows.comp", sizeof(roma_soft_shadows_push), 1, &R->soft);
    if (r == ROMA_SUCCESS && roma_effect_plan_runs(&R->plan, ROMA_PASS_MANY_LIGHTS))
        r = roma_pixel_pass_create(ctx, "many_lights.comp", sizeof(roma_many_lights_push), 1, &R->many);
    if (r == ROMA_SUCCESS && roma_effect_plan_runs(&R->plan, ROMA_PASS_GI))
        r = create_gi(R, scene);
    if (r == ROMA_SUCCESS && roma_effect_plan_runs(&R->plan, ROMA_PASS_RSM)) {
        r = roma_rsm_views_plan(R->lights.host_lights, R->lights.light_count, R->rsm_size, R->near_plane,
                                &ctx->logger, &R->rsm_views);
        for (uint32_t v = 0; v < R->rsm_views.count && r == ROMA_SUCCESS; ++v) {
            r = roma_gbuffer_create_sharing(R->gbuffer, R->rsm_size, R->rsm_size, &R->rsm[v]);
            if (r == ROMA_SUCCESS) {
                VkDeviceAddress a = roma_gbuffer_pixels_address(R->rsm[v]);
                R->rsm_views.views[v].info[2] = (uint32_t)a;
                R->rsm_views.views[v].info[3] = (uint32_t)(a >> 32);
            }
        }
        if (r == ROMA_SUCCESS && R->rsm_views.count) {
            r = roma_buffer_create(ctx, sizeof(roma_rsm_view) * R->rsm_views.count,
                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                                   ROMA_MEMORY_UPLOAD, &R->views_buffer);
            if (r == ROMA_SUCCESS)
                memcpy(R->views_buffer.mapped, R->rsm_views.views, sizeof(roma_rsm_view) * R->rsm_views.count);
        }
    }
    for (int p = 0; p < ROMA_PASS_COUNT && r == ROMA_SUCCESS; ++p)
        if (roma_effect_plan_runs(&R->plan, (roma_pass_kind)p) && accum_element((roma_pass_kind)p))
            r = roma_buffer_create(ctx, pixels * accum_element((roma_pass_kind)p), ACCUM_USAGE,
                                   ROMA_MEMORY_READBACK, &R->accum[p]);
    const int exact_lights = !d->lights_per_frame || d->lights_per_frame >= R->plan.many_light_count;
    if (r == ROMA_SUCCESS && d->out_light_mask && exact_lights && roma_effect_plan_runs(&R->plan, ROMA_PASS_MANY_LIGHTS)) {
        R->mask_words = (R->plan.many_light_count + 31u) / 32u;
        r = roma_buffer_create(ctx, pixels * R->mask_words * sizeof(uint32_t), ACCUM_USAGE, ROMA_MEMORY_READBACK,
                               &R->mask);
    }
    if (r == ROMA_SUCCESS && R->interactive)
        r = roma_gbuffer_create_sharing(R->gbuffer, R->desc->width, R->desc->height, &R->gbuffer_previous);
    if (r == ROMA_SUCCESS && R->interactive) {
        uint32_t mask = 0;
        for (int e = 0; e < 4; ++e)
            mask |= effect_traced(R, e) ? 1u << e : 0u;
        r = roma_denoiser_create(ctx, R->desc->width, R->desc->height, mask, &R->denoiser);
    }
    return r;
}

static void destroy_resources(renderer *R)
{
    roma_context *ctx = R->ctx;
    roma_denoiser_destroy(&R->denoiser);
    roma_gbuffer_destroy(R->gbuffer_previous);
    for (int p = 0; p < ROMA_PASS_COUNT; ++p) {
        roma_buffer_destroy(ctx, &R->accum[p]);
        roma_map_destroy(R->maps[p]);
        roma_gpu_timer_destroy(R->build_timers[p]);
    }
    roma_buffer_destroy(ctx, &R->mask);
    roma_pixel_pass_destroy(&R->punctual);
    roma_pixel_pass_destroy(&R->soft);
    roma_pixel_pass_destroy(&R->many);
    roma_pixel_pass_destroy(&R->gi);
    roma_surface_cells_destroy(&R->surfaces);
    roma_buffer_destroy(ctx, &R->gi_scene);
    roma_gbuffer_list_destroy(&R->list);
    for (uint32_t v = 0; v < ROMA_MAX_RSM_VIEWS; ++v)
        roma_gbuffer_destroy(R->rsm[v]);
    roma_buffer_destroy(ctx, &R->views_buffer);
    roma_ao_pass_destroy(R->ao);
    roma_distance_field_destroy(&R->distance_field);
    roma_naadf_destroy(&R->naadf);
    for (uint32_t l = ROMA_AO_SSAO_MAX_LAYERS; l-- > 0;) /* the first, whose pipelines they share, last */
        roma_gbuffer_destroy(R->sd_layers[l]);
    if (R->sd_view)
        vkDestroyBufferView(ctx->device, R->sd_view, ctx->allocator);
    roma_buffer_destroy(ctx, &R->sd_pixels);
    roma_light_data_destroy(ctx, &R->lights);
    roma_gpu_timer_destroy(R->timer);
    roma_gbuffer_destroy(R->gbuffer);
    roma_scene_buffers_destroy(ctx, &R->geometry);
}

static double scope_ms(roma_gpu_timer *timer, const char *name)
{
    roma_gpu_timing t[2 * ROMA_PASS_COUNT];
    uint32_t count = 2 * ROMA_PASS_COUNT;
    double ms = 0.0;
    if (roma_gpu_timer_read(timer, t, &count) == ROMA_SUCCESS)
        for (uint32_t i = 0; i < count && i < 2 * ROMA_PASS_COUNT; ++i)
            if (strcmp(t[i].name, name) == 0)
                ms += t[i].milliseconds;
    return ms;
}

/* A tracing pass once per part of its work (loop_budget.h), each part's range written into
 * the push's `part` before it is recorded. */
static roma_result record_parts(renderer *R, roma_pixel_pass *pass, VkCommandBuffer cmd, const roma_map_info *m,
                                VkBuffer pixels_buffer, VkBuffer accum, const void *push, uint32_t part[4],
                                const roma_loop_parts *parts)
{
    roma_result r = ROMA_SUCCESS;
    for (uint32_t i = 0; r == ROMA_SUCCESS && roma_loop_parts_get(parts, i, part); ++i)
        r = roma_pixel_pass_record_list(pass, cmd, &R->list, m, m->bom_view, pixels_buffer, accum, push);
    return r;
}

/* Records the planned tracing passes of frame f. */
static roma_result record_passes(renderer *R, VkCommandBuffer cmd, uint32_t f, const roma_map_info *info,
                                 VkBuffer pixels_buffer, uint32_t scopes[ROMA_PASS_COUNT])
{
    const roma_effect_render_desc *d = R->desc;
    const roma_effect_plan *plan = &R->plan;
    const float offset_cells = d->offset_cells > 0.0f ? d->offset_cells : ROMA_DEFAULT_OFFSET_CELLS;
    const uint32_t spp = d->spp ? d->spp : ROMA_DEFAULT_AO_SAMPLES;
    const uint32_t steps = d->max_steps ? d->max_steps : ROMA_DEFAULT_SHADOW_STEPS;
    const uint32_t lights_steps = d->lights_max_steps ? d->lights_max_steps : 16;
    const float skip_cells = d->skip_cells < 0.0f ? 0.0f : d->skip_cells > 0.0f ? d->skip_cells : ROMA_DEFAULT_SHADOW_SKIP_CELLS;
    const float ao_skip = d->ao_skip_cells < 0.0f ? 0.0f : d->ao_skip_cells > 0.0f ? d->ao_skip_cells : ROMA_DEFAULT_AO_SKIP_CELLS;
    const float exact_shadows = d->shadow_method == ROMA_SHADOW_METHOD_VOXEL_DDA ? 1.0f : 0.0f;
    roma_result r = ROMA_SUCCESS;
    for (int p = ROMA_PASS_AO; p < ROMA_PASS_COUNT && r == ROMA_SUCCESS; ++p) {
        if (!roma_effect_plan_runs(plan, (roma_pass_kind)p) || plan->pass_map[p] < 0)
            continue;
        const roma_map_info *m = &info[plan->pass_map[p]];
        const float offset = offset_cells * m->trace_cell;
        const VkBufferView bom_view = m->bom_view;
        /* What one shadow ray of this pass costs in loop iterations (loop_costs.h). */
        const roma_loop_grid grid = {m->resolution, m->grid_cell, m->levels};
        const roma_shadow_cost shadow = {grid, skip_cells * m->trace_cell, ROMA_START_WALK, steps,
                                         ROMA_BACK_SKIP_POINT, exact_shadows > 0.0f};
        const uint64_t bom = d->blind_ray_start ? 0u : 1u; /* the walk reads the bound BOM */
        scopes[p] = roma_gpu_timer_begin(R->timer, cmd, roma_pass_name((roma_pass_kind)p));
        switch ((roma_pass_kind)p) {
        case ROMA_PASS_AO: {
            VkBufferView bound = bom_view;
            if (R->distance_field.ctx) {
                /* The baseline's generation: from this frame's BOM, in the AO pass's time. */
                uint32_t scope = roma_gpu_timer_begin(R->timer, cmd, "distance field");
                roma_distance_field_record(&R->distance_field, cmd);
                roma_gpu_timer_end(R->timer, cmd, scope);
                bound = R->distance_field.distances_view;
            }
            if (R->naadf.ctx) {
                uint32_t scope = roma_gpu_timer_begin(R->timer, cmd, "naadf");
                roma_naadf_record(&R->naadf, cmd);
                roma_gpu_timer_end(R->timer, cmd, scope);
                bound = R->naadf.cells_view;
            }
            if (R->sd_view)
                bound = R->sd_view; /* screen space reads no BOM: the depth layers in its place */
            roma_ao_pass_inputs in = {
                .gbuffer_pixels = pixels_buffer, .width = d->width, .height = d->height, .map = m, .list = &R->list,
                .offset = offset, .radius = d->ao_radius, .tmin = ao_skip * m->trace_cell, .spp = spp, .frame = f,
                .seed = d->seed, .accum = R->accum[p].buffer, .bom = bound, .blind_start = d->blind_ray_start,
                .camera = d->camera_path ? &d->camera_path[f] : &d->camera, .ssao_steps = d->ssao_steps,
                .ssao_layers = R->sd_view ? d->ssao_layers : 0,
            };
            r = roma_ao_pass_record(R->ao, cmd, &in);
            break;
        }
        case ROMA_PASS_PUNCTUAL_LIGHTS: {
            roma_punctual_push push = {
                .lights = R->lights.lights.address, .bom = bom,
                .config = {d->width, d->height, R->lights.light_count, steps},
                .ray = {offset, skip_cells * m->trace_cell, exact_shadows, 0},
            };
            const roma_loop_parts parts = roma_loop_parts_plan(R->ctx, 0, R->lights.light_count,
                                                               roma_loop_cost_punctual_light(&shadow), 0, 0);
            r = record_parts(R, &R->punctual, cmd, m, pixels_buffer, R->accum[p].buffer, &push, push.part, &parts);
            break;
        }
        case ROMA_PASS_SOFT_SHADOWS: {
            roma_soft_shadows_push push = {
                .emitters = R->lights.emitters.address, .cdf = R->lights.cdf.address, .bom = bom,
                .config = {d->width, d->height, spp, f},
                .config2 = {d->seed, R->lights.emitter_count, steps, 0},
                .ray = {offset, skip_cells * m->trace_cell, exact_shadows, 0},
            };
            const roma_loop_parts parts = roma_loop_parts_plan(
                R->ctx, 0, spp, roma_loop_cost_area_sample(&shadow, R->lights.emitter_count), 0, 0);
            r = record_parts(R, &R->soft, cmd, m, pixels_buffer, R->accum[p].buffer, &push, push.part, &parts);
            break;
        }
        case ROMA_PASS_MANY_LIGHTS: {
            uint32_t n = R->lights.position_count;
            uint32_t tested = d->lights_per_frame && d->lights_per_frame < n ? d->lights_per_frame : n;
            int last = f + 1 == (d->frames ? d->frames : 1);
            roma_many_lights_push push = {
                .positions = R->lights.positions.address, .mask = last ? R->mask.address : 0, .bom = bom,
                .config = {d->width, d->height, n, lights_steps},
                .config2 = {d->seed, f, tested, R->mask_words},
                .ray = {offset, skip_cells * m->trace_cell, exact_shadows, 0},
            };
            roma_shadow_cost segment = shadow; /* many_lights.comp walks one skip length of each start */
            segment.start_walk = 1.0f;
            segment.max_steps = lights_steps;
            const roma_loop_parts parts =
                roma_loop_parts_plan(R->ctx, 0, tested, roma_loop_cost_punctual_light(&segment), 0, 0);
            r = record_parts(R, &R->many, cmd, m, pixels_buffer, R->accum[p].buffer, &push, push.part, &parts);
            break;
        }
        case ROMA_PASS_GI: {
            if (f == 0 && R->surfaces.ctx) { /* the scene stands still: once */
                const roma_surface_geometry g = {R->geometry.positions.buffer, R->geometry.indices.buffer,
                                                 R->geometry.triangle_count};
                r = roma_surface_cells_record(&R->surfaces, cmd, 0, &g);
                if (r != ROMA_SUCCESS)
                    break;
            }
            roma_gi_push push = {
                .lights = R->lights.lights.address, .views = R->views_buffer.address, .scene = R->gi_scene.address,
                .bom = bom,
                .config = {d->width, d->height, spp, f},
                .config2 = {d->seed, R->rsm_views.count, steps, exact_shadows > 0.0f},
                .ray = {offset, ao_skip * m->trace_cell, d->rsm_tolerance_cells * m->trace_cell, skip_cells * m->trace_cell},
            };
            /* A sample's bounce, its area-light sample and RSMs, then each light at its hit. */
            uint32_t bounce = roma_loop_cost_gi_bounce(grid, ao_skip * m->trace_cell, exact_shadows > 0.0f) +
                              R->rsm_views.count;
            if (R->lights.emitter_count)
                bounce += roma_loop_cost_area_sample(&shadow, R->lights.emitter_count);
            const roma_loop_parts parts = roma_loop_parts_plan(R->ctx, 0, spp, bounce, R->lights.light_count,
                                                               roma_loop_cost_punctual_light(&shadow));
            r = record_parts(R, &R->gi, cmd, m, pixels_buffer, R->accum[p].buffer, &push, push.part, &parts);
            break;
        }
        default:
            break;
        }
        roma_gpu_timer_end(R->timer, cmd, scopes[p]);
    }
    return r;
}

/* Interactive mode, after the passes of frame f: resolve, temporal accumulation
 * and, on the last frame, the a-trous filter. */
static roma_result record_denoise(renderer *R, VkCommandBuffer cmd, uint32_t f, int last)
{
    const roma_effect_render_desc *d = R->desc;
    const roma_gbuffer *now = f % 2 ? R->gbuffer_previous : R->gbuffer;
    const roma_gbuffer *before = f % 2 ? R->gbuffer : R->gbuffer_previous;
    roma_camera_frame cf;
    roma_camera_make_frame(&d->camera_path[f], d->width, d->height, &cf);
    roma_denoise_inputs in = {
        .pixels = roma_gbuffer_pixels_address(now), .previous_pixels = roma_gbuffer_pixels_address(before),
        .accum = {{R->accum[ROMA_PASS_AO].address, 0},
                  {R->accum[ROMA_PASS_PUNCTUAL_LIGHTS].address, R->accum[ROMA_PASS_SOFT_SHADOWS].address},
                  {R->accum[ROMA_PASS_GI].address, 0},
                  {R->accum[ROMA_PASS_MANY_LIGHTS].address, 0}},
        .frame = f, .filter = last, .spp = d->spp ? d->spp : 1, .many_light_count = R->plan.many_light_count,
        .max_history = d->max_history ? d->max_history : 32,
        .filter_iterations = d->no_spatial_filter ? 0 : d->filter_iterations ? d->filter_iterations : 3,
        .footprint = 2.0f * cf.tan_half_fovy / (float)d->height, /* pixel size per unit of view distance */
        .value_sigma = d->filter_luminance_sigma > 0.0f ? d->filter_luminance_sigma : 1.0f,
    };
    return roma_denoiser_record(&R->denoiser, cmd, &in);
}

/* The stochastic depth map's layers for frame f (new seeds every frame, so frames average
 * over layers), copied one after the other into the buffer the AO pass reads. */
static roma_result record_depth_layers(renderer *R, VkCommandBuffer cmd, const roma_gbuffer_inputs *gin, uint32_t f)
{
    const roma_effect_render_desc *d = R->desc;
    const VkDeviceSize layer = (VkDeviceSize)d->width * d->height * sizeof(roma_gbuffer_pixel);
    uint32_t scope = roma_gpu_timer_begin(R->timer, cmd, "depth layers");
    roma_result r = ROMA_SUCCESS;
    for (uint32_t l = 0; l < d->ssao_layers && r == ROMA_SUCCESS; ++l) {
        roma_gbuffer_inputs in = *gin;
        in.keep = d->ssao_keep > 0.0f ? d->ssao_keep : ROMA_AO_SSAO_KEEP;
        in.seed = roma_hash_u32(d->seed ^ roma_hash_u32(f * ROMA_AO_SSAO_MAX_LAYERS + l));
        r = roma_gbuffer_record(R->sd_layers[l], cmd, &in);
        VkBufferCopy copy = {0, l * layer, layer};
        if (r == ROMA_SUCCESS)
            vkCmdCopyBuffer(cmd, roma_gbuffer_pixels_buffer(R->sd_layers[l]), R->sd_pixels.buffer, 1, &copy);
    }
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT);
    roma_gpu_timer_end(R->timer, cmd, scope);
    return r;
}

static roma_result run_frames(renderer *R, roma_effect_stats *stats)
{
    roma_context *ctx = R->ctx;
    const roma_effect_render_desc *d = R->desc;
    const uint32_t frames = d->frames ? d->frames : 1;
    roma_gbuffer_inputs gin = {
        .positions = R->geometry.positions.address, .normals = R->geometry.normals.address,
        .indices = R->geometry.indices.address, .albedo = R->geometry.albedo.address,
        .triangle_count = R->geometry.triangle_count, .camera = d->camera, .previous_camera = d->camera,
        .near_plane = R->near_plane,
    };
    roma_result r = ROMA_SUCCESS;
    for (uint32_t f = 0; f < frames && r == ROMA_SUCCESS; ++f) {
        /* One submission a frame: every array the plan needs (each with new jitter), the
         * G-buffer when it changes, the passes. */
        VkCommandBuffer cmd;
        r = roma_begin_one_shot(ctx, &cmd);
        if (r != ROMA_SUCCESS)
            break;
        roma_gpu_timer_reset(R->timer, cmd);
        roma_map_frame_desc frame = {.frame = f, .seed = d->seed, .jitter_grid = 1, .jitter_directions = 1};
        /* Screen-space AO alone reads no map: none is built (its pass binds an unbuilt one). */
        const int no_build = d->ao_method == ROMA_AO_METHOD_SCREEN_SPACE;
        for (uint32_t i = 0; i < R->plan.map_count && r == ROMA_SUCCESS; ++i) {
            roma_gpu_timer_reset(R->build_timers[i], cmd);
            if (!no_build)
                r = roma_map_record_build(R->maps[i], cmd, &frame, R->build_timers[i]);
            if (r == ROMA_SUCCESS)
                r = roma_map_get_info(R->maps[i], &stats->map_info[i]);
        }
        uint32_t scopes[ROMA_PASS_COUNT];
        roma_gbuffer *gbuffer = R->interactive && f % 2 ? R->gbuffer_previous : R->gbuffer;
        if (R->interactive || f == 0) {
            /* A still camera needs primary visibility once; a moving one every frame,
             * with the previous camera for the motion vectors. */
            if (R->interactive) {
                gin.camera = d->camera_path[f];
                gin.previous_camera = d->camera_path[f ? f - 1 : 0];
            }
            scopes[ROMA_PASS_GBUFFER] = roma_gpu_timer_begin(R->timer, cmd, "gbuffer");
            r = roma_gbuffer_record(gbuffer, cmd, &gin);
            if (r == ROMA_SUCCESS)
                r = roma_gbuffer_list_record(&R->list, cmd, roma_gbuffer_pixels_address(gbuffer));
            roma_gpu_timer_end(R->timer, cmd, scopes[ROMA_PASS_GBUFFER]);
            /* Accumulators start at zero; the interactive mode resolves each frame alone. */
            for (int p = 0; p < ROMA_PASS_COUNT; ++p)
                if (R->accum[p].buffer)
                    vkCmdFillBuffer(cmd, R->accum[p].buffer, 0, VK_WHOLE_SIZE, 0);
        }
        if (r == ROMA_SUCCESS && R->sd_view)
            r = record_depth_layers(R, cmd, &gin, f);
        if (f == 0 && R->rsm_views.count) {
            /* The lights stand still: their RSMs once. */
            scopes[ROMA_PASS_RSM] = roma_gpu_timer_begin(R->timer, cmd, "rsm");
            for (uint32_t v = 0; v < R->rsm_views.count && r == ROMA_SUCCESS; ++v) {
                roma_gbuffer_inputs rin = gin;
                rin.camera = rin.previous_camera = R->rsm_views.cameras[v];
                r = roma_gbuffer_record(R->rsm[v], cmd, &rin);
            }
            roma_gpu_timer_end(R->timer, cmd, scopes[ROMA_PASS_RSM]);
        }
        if (r == ROMA_SUCCESS)
            r = record_passes(R, cmd, f, stats->map_info, roma_gbuffer_pixels_buffer(gbuffer), scopes);
        if (r == ROMA_SUCCESS && R->interactive)
            r = record_denoise(R, cmd, f, f + 1 == frames);
        roma_result sr = roma_submit_one_shot(ctx, cmd);
        if (r == ROMA_SUCCESS)
            r = sr;
        for (uint32_t i = 0; i < R->plan.map_count && r == ROMA_SUCCESS; ++i)
            stats->build_ms[i] += scope_ms(R->build_timers[i], "bom") + scope_ms(R->build_timers[i], "rotate");
        for (int p = 0; p < ROMA_PASS_COUNT && r == ROMA_SUCCESS; ++p)
            if (roma_effect_plan_runs(&R->plan, (roma_pass_kind)p))
                stats->pass_ms[p] += scope_ms(R->timer, roma_pass_name((roma_pass_kind)p));
        if (r == ROMA_SUCCESS && R->distance_field.ctx)
            stats->baseline_build_ms += scope_ms(R->timer, "distance field");
        if (r == ROMA_SUCCESS && R->naadf.ctx)
            stats->baseline_build_ms += scope_ms(R->timer, "naadf");
        if (r == ROMA_SUCCESS && R->sd_view)
            stats->baseline_build_ms += scope_ms(R->timer, "depth layers");
        if (r == ROMA_SUCCESS && d->progress)
            d->progress((float)(f + 1) / (float)frames, d->progress_user_data);
    }
    return r;
}

/* Host resolve of the accumulated sums into images. */
/* Interactive mode: the last frame's filtered values (coverage from its G-buffer). */
static roma_result resolve_interactive(renderer *R, const roma_gbuffer_pixel *px, roma_effect_images *out)
{
    const size_t n = (size_t)R->desc->width * R->desc->height;
    roma_image *images[4] = {&out->ao, &out->direct, &out->gi, &out->lights};
    for (size_t i = 0; i < n; ++i)
        out->coverage.pixels[i] = px && isfinite(px[i].position_t[3]) ? 1.0f : 0.0f;
    for (int e = 0; e < 4; ++e) {
        if (!images[e]->pixels)
            continue;
        if (!effect_traced(R, e)) {
            for (size_t i = 0; e == 0 && i < n; ++i)
                images[e]->pixels[i] = 1.0f; /* nothing traced: AO open, the others black */
            continue;
        }
        roma_result r = roma_denoiser_read(&R->denoiser, e, images[e]);
        if (r != ROMA_SUCCESS)
            return r;
    }
    return ROMA_SUCCESS;
}

static roma_result resolve(renderer *R, const roma_gbuffer_pixel *px, roma_effect_images *out)
{
    const roma_effect_render_desc *d = R->desc;
    const size_t n = (size_t)d->width * d->height;
    const double frames = d->frames ? d->frames : 1, spp = d->spp ? d->spp : 1;
    const uint32_t effects = R->plan.effects;
    roma_result r = roma_image_alloc(&out->coverage, d->width, d->height, 1);
    if (r == ROMA_SUCCESS && (effects & ROMA_EFFECT_AO))
        r = roma_image_alloc(&out->ao, d->width, d->height, 1);
    if (r == ROMA_SUCCESS && (effects & ROMA_EFFECT_DIRECT))
        r = roma_image_alloc(&out->direct, d->width, d->height, 3);
    if (r == ROMA_SUCCESS && (effects & ROMA_EFFECT_GI))
        r = roma_image_alloc(&out->gi, d->width, d->height, 3);
    if (r == ROMA_SUCCESS && (effects & ROMA_EFFECT_LIGHTS))
        r = roma_image_alloc(&out->lights, d->width, d->height, 1);
    for (int p = 0; p < ROMA_PASS_COUNT && r == ROMA_SUCCESS; ++p)
        if (R->accum[p].buffer)
            r = roma_buffer_invalidate(R->ctx, &R->accum[p]);
    if (r == ROMA_SUCCESS && R->mask.buffer)
        r = roma_buffer_invalidate(R->ctx, &R->mask);
    if (r != ROMA_SUCCESS)
        return r;
    if (R->interactive)
        return resolve_interactive(R, px, out);
    const uint32_t *ao = R->accum[ROMA_PASS_AO].mapped;
    const float *punctual = R->accum[ROMA_PASS_PUNCTUAL_LIGHTS].mapped;
    const float *soft = R->accum[ROMA_PASS_SOFT_SHADOWS].mapped;
    const float *gi = R->accum[ROMA_PASS_GI].mapped;
    const uint32_t *many = R->accum[ROMA_PASS_MANY_LIGHTS].mapped;
    for (size_t i = 0; i < n; ++i) {
        const int covered = px && isfinite(px[i].position_t[3]);
        out->coverage.pixels[i] = covered ? 1.0f : 0.0f;
        if (out->ao.pixels)
            out->ao.pixels[i] = covered && ao ? (float)(ao[i] / (spp * frames)) : 1.0f;
        if (!covered)
            continue;
        if (out->direct.pixels)
            for (int c = 0; c < 3; ++c) {
                double E = (punctual ? punctual[4 * i + c] / frames : 0.0) +
                           (soft ? soft[4 * i + c] / (spp * frames) : 0.0);
                out->direct.pixels[3 * i + c] = (float)(px[i].albedo[c] / PI_F * E);
            }
        if (out->gi.pixels && gi)
            for (int c = 0; c < 3; ++c)
                out->gi.pixels[3 * i + c] = (float)(px[i].albedo[c] * (gi[4 * i + c] / (spp * frames)));
        if (out->lights.pixels && many && many[2 * i + 1])
            out->lights.pixels[i] = (float)((double)many[2 * i] / many[2 * i + 1] * R->plan.many_light_count);
    }
    if (d->out_light_mask && R->mask.mapped)
        memcpy(d->out_light_mask, R->mask.mapped, n * R->mask_words * sizeof(uint32_t));
    return ROMA_SUCCESS;
}

roma_result roma_effect_render(roma_context *ctx, const roma_scene *scene, const roma_effect_render_desc *desc,
                               roma_effect_images *out_images, roma_effect_stats *out_stats)
{
    if (out_images)
        memset(out_images, 0, sizeof *out_images);
    if (out_stats)
        memset(out_stats, 0, sizeof *out_stats);
    if (!ctx || !scene || !desc || !out_images || !out_stats)
        return ROMA_ERROR_INVALID_ARGUMENT;
    const roma_logger *log = &ctx->logger;
    roma_camera_frame cf;
    if (desc->width == 0 || desc->height == 0 || desc->width > 16384 || desc->height > 16384 ||
        !roma_camera_make_frame(desc->camera_path ? &desc->camera_path[0] : &desc->camera, desc->width,
                                desc->height, &cf))
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_effect_render: bad image size %ux%u or camera",
                         desc->width, desc->height);
    if (!(desc->offset_cells >= 0.0f) || !isfinite(desc->offset_cells) || isnan(desc->ao_radius) ||
        !isfinite(desc->skip_cells) || !isfinite(desc->ao_skip_cells) ||
        !(desc->rsm_tolerance_cells >= 0.0f) || !isfinite(desc->rsm_tolerance_cells) || desc->rsm_size > 4096)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_effect_render: bad offset, skip, AO radius or RSM size (at most 4096)");
    if ((unsigned)desc->shadow_method > ROMA_SHADOW_METHOD_VOXEL_DDA ||
        (desc->shadow_method == ROMA_SHADOW_METHOD_VOXEL_DDA && desc->blind_ray_start))
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_effect_render: unknown shadow method %u, or the voxel traversal with the blind start "
                         "(it walks the BOM the blind start leaves unbound)", (unsigned)desc->shadow_method);
    if ((unsigned)desc->ao_method > ROMA_AO_METHOD_NAADF)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_effect_render: unknown AO method %u",
                         (unsigned)desc->ao_method);
    if ((desc->ssao_layers && desc->ao_method != ROMA_AO_METHOD_SCREEN_SPACE) ||
        desc->ssao_layers > ROMA_AO_SSAO_MAX_LAYERS || !(desc->ssao_keep >= 0.0f && desc->ssao_keep <= 1.0f))
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_effect_render: depth layers (at most %u, kept with a probability in [0, 1]) are for "
                         "screen-space AO", ROMA_AO_SSAO_MAX_LAYERS);
    if (desc->ao_method == ROMA_AO_METHOD_SCREEN_SPACE &&
        (desc->options.effects != ROMA_EFFECT_AO || !(desc->ao_radius > 0.0f) || !isfinite(desc->ao_radius)))
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_effect_render: screen-space AO renders AO alone, with a bounded radius");
    for (uint32_t f = 0; desc->camera_path && f < (desc->frames ? desc->frames : 1); ++f)
        if (!roma_camera_make_frame(&desc->camera_path[f], desc->width, desc->height, &cf))
            return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_effect_render: camera %u of the path is degenerate", f);
    roma_effect_stats *stats = out_stats;
    roma_result r = roma_effect_plan_derive(scene, &desc->options, log, &stats->plan);
    if (r != ROMA_SUCCESS)
        return r;
    if (desc->gi_punctual_rays) /* point and spot lights reach GI by shadow rays: no RSM */
        stats->plan.passes &= ~(1u << ROMA_PASS_RSM);
    if (roma_effect_plan_runs(&stats->plan, ROMA_PASS_MANY_LIGHTS) && !desc->many_light_positions)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_effect_render: many-light positions missing");

    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    renderer R = {.ctx = ctx, .desc = desc, .plan = stats->plan, .interactive = desc->camera_path != NULL};
    float diag = 0.0f;
    for (int k = 0; k < 3; ++k)
        diag += (v.bounds_max[k] - v.bounds_min[k]) * (v.bounds_max[k] - v.bounds_min[k]);
    R.near_plane = 1e-4f * sqrtf(diag);
    R.rsm_size = desc->rsm_size ? desc->rsm_size : 256;
    roma_gbuffer_pixel *px = NULL;
    const size_t n = (size_t)desc->width * desc->height;
    if (stats->plan.passes) {
        px = desc->out_gbuffer ? desc->out_gbuffer : malloc(n * sizeof *px);
        if (!px)
            return roma_fail(log, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_effect_render: out of memory");
        r = create_resources(&R, scene);
        if (r == ROMA_SUCCESS)
            r = run_frames(&R, stats);
        const uint32_t frames = desc->frames ? desc->frames : 1;
        if (r == ROMA_SUCCESS)
            r = roma_gbuffer_download(R.interactive && (frames - 1) % 2 ? R.gbuffer_previous : R.gbuffer, px);
    }
    if (r == ROMA_SUCCESS)
        r = resolve(&R, px, out_images);
    for (int p = 0; p < ROMA_PASS_COUNT; ++p)
        stats->pass_bytes[p] = R.accum[p].size;
    if (R.mask.buffer)
        stats->pass_bytes[ROMA_PASS_MANY_LIGHTS] += R.mask.size;
    stats->pass_bytes[ROMA_PASS_GI] += R.surfaces.cells.size + R.gi_scene.size; /* the surface grid */
    if (R.distance_field.ctx)
        stats->baseline_bytes = roma_distance_field_bytes(&R.distance_field, &stats->baseline_build_bytes);
    if (R.naadf.ctx)
        stats->baseline_bytes = roma_naadf_bytes(&R.naadf, &stats->baseline_build_bytes);
    if (R.gbuffer)
        stats->pass_bytes[ROMA_PASS_GBUFFER] = n * sizeof(roma_gbuffer_pixel);
    stats->pass_bytes[ROMA_PASS_RSM] =
        (uint64_t)R.rsm_views.count * R.rsm_size * R.rsm_size * sizeof(roma_gbuffer_pixel) + R.views_buffer.size;
    destroy_resources(&R);
    if (px != desc->out_gbuffer)
        free(px);
    if (r != ROMA_SUCCESS)
        roma_effect_images_free(out_images);
    return r;
}

void roma_effect_images_free(roma_effect_images *images)
{
    if (!images)
        return;
    roma_image_free(&images->ao);
    roma_image_free(&images->direct);
    roma_image_free(&images->gi);
    roma_image_free(&images->lights);
    roma_image_free(&images->coverage);
}
