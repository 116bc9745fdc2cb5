/* The tools' ROMA images through the public effect API (effect_api.h). Uses libroma's public
 * headers, the reference tracer (for the G-buffer), the apps' clock and, for the accuracy
 * study's AO methods, the tools' study library (study/study_ao.h) on the same pass. */
#include "effect_api.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "app_image.h"
#include "study/study_ao.h"
#include "study/study_depth_layers.h"
#include "study/study_rsm.h"
#include "study/study_shadows.h"

#define PI_F 3.14159265358979323846f

enum { IN_POSITION, IN_NORMAL, IN_GEOMETRIC, OUT_AO, OUT_DIRECT, OUT_GI, OUT_LIGHTS, IMAGE_COUNT };
/* Shadow steps of the many lights' count by default (effect_api_desc.lights_max_steps). */
#define MANY_LIGHTS_MAX_STEPS 16u
#define INPUTS 3

typedef struct host_buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped;
} host_buffer;

/* What an engine holds for these passes: its command buffer, images and libroma's objects. */
typedef struct engine {
    roma_context *ctx;
    VkDevice device;
    VkPhysicalDeviceMemoryProperties memory;
    VkDeviceSize max_allocation;
    uint32_t max_storage_range; /* maxStorageBufferRange: the largest maps one buffer holds */
    VkCommandPool pool;
    VkCommandBuffer cmd;
    VkFence fence;
    app_image images[IMAGE_COUNT];
    VkDeviceSize texel_bytes[IMAGE_COUNT];
    roma_pixel_list *pixels; /* desc.shared_list: listed by the first frame, read by every frame's effects */
    roma_light_effect *count;  /* many lights: the light effect counting visible lights */
    roma_light *many_lights;   /* its unit point lights */
    host_buffer upload, readback;
    roma_map *maps[ROMA_PASS_COUNT];
    roma_ao_effect *ao;
    roma_study_ao *study_ao; /* instead of ao: a study's AO method or the blind start */
    roma_study_depth_layers *layers; /* screen-space AO's stochastic depth map */
    roma_light_effect *light;
    roma_gi_effect *gi;
    roma_study_rsm *rsm; /* desc.gi_rsm: the lights' reflective shadow maps */
    roma_gpu_timer *timer;
    uint64_t bytes;
} engine;

roma_result effect_api_gbuffer(const roma_ref *ref, const roma_camera *camera, uint32_t width, uint32_t height,
                              roma_gbuffer_pixel *out)
{
    roma_camera_frame frame;
    if (!ref || !camera || !out || !width || !height || !roma_camera_make_frame(camera, width, height, &frame))
        return ROMA_ERROR_INVALID_ARGUMENT;
    const size_t n = (size_t)width * height;
    float *planes = malloc(n * 15 * sizeof(float));
    if (!planes)
        return ROMA_ERROR_OUT_OF_HOST_MEMORY;
    const roma_ref_gbuffer g = {planes, planes + 4 * n, planes + 8 * n, planes + 12 * n};
    roma_result r = roma_ref_render_gbuffer(ref, camera, width, height, &g);
    for (size_t i = 0; i < n && r == ROMA_SUCCESS; ++i) {
        roma_gbuffer_pixel *p = &out[i];
        memset(p, 0, sizeof *p);
        p->position_t[3] = INFINITY;
        uint32_t triangle = ROMA_GBUFFER_NO_TRIANGLE;
        if (g.position[4 * i + 3] > 0.0f) {
            float d2 = 0.0f;
            for (int k = 0; k < 3; ++k) {
                const float v = g.position[4 * i + k] - camera->eye[k];
                d2 += v * v;
                p->position_t[k] = g.position[4 * i + k];
                p->shading_normal[k] = g.normal[4 * i + k];
                p->geometric_normal[k] = g.geometric_normal[4 * i + k];
                p->albedo[k] = g.albedo[3 * i + k];
            }
            p->position_t[3] = sqrtf(d2);
            /* The triangle, from the same ray (the G-buffer's planes do not carry it). */
            float org[3], dir[3];
            roma_ref_hit hit;
            roma_camera_ray(&frame, (float)(i % width) + 0.5f, (float)(i / width) + 0.5f, org, dir);
            if (roma_ref_intersect(ref, org, dir, 0.0f, INFINITY, &hit))
                triangle = hit.triangle;
        }
        memcpy(&p->albedo[3], &triangle, sizeof triangle);
    }
    free(planes);
    return r;
}

static roma_result from_vk(VkResult vr, const char *what)
{
    if (vr == VK_SUCCESS)
        return ROMA_SUCCESS;
    fprintf(stderr, "effect_api: %s failed (VkResult %d)\n", what, (int)vr);
    return vr == VK_ERROR_OUT_OF_HOST_MEMORY     ? ROMA_ERROR_OUT_OF_HOST_MEMORY
           : vr == VK_ERROR_OUT_OF_DEVICE_MEMORY ? ROMA_ERROR_OUT_OF_DEVICE_MEMORY
           : vr == VK_ERROR_DEVICE_LOST          ? ROMA_ERROR_DEVICE_LOST
                                                 : ROMA_ERROR_VULKAN;
}

/* Memory of the first type with `prefer` and `want`, else of the first with `want`. */
static roma_result allocate(engine *e, VkMemoryRequirements req, VkMemoryPropertyFlags want,
                            VkMemoryPropertyFlags prefer, VkDeviceMemory *out)
{
    if (req.size > e->max_allocation) {
        fprintf(stderr, "effect_api: out of device memory: an image or buffer of %llu bytes is larger than the "
                "device's largest allocation (%llu bytes)\n", (unsigned long long)req.size,
                (unsigned long long)e->max_allocation);
        return ROMA_ERROR_OUT_OF_DEVICE_MEMORY;
    }
    uint32_t type = UINT32_MAX;
    for (int pass = 0; pass < 2 && type == UINT32_MAX; ++pass) {
        const VkMemoryPropertyFlags flags = pass == 0 ? prefer | want : want;
        for (uint32_t i = 0; i < e->memory.memoryTypeCount && type == UINT32_MAX; ++i)
            if ((req.memoryTypeBits & (1u << i)) && (e->memory.memoryTypes[i].propertyFlags & flags) == flags)
                type = i;
    }
    if (type == UINT32_MAX) {
        fprintf(stderr, "effect_api: no memory type with the properties 0x%x\n", (unsigned)want);
        return ROMA_ERROR_MISSING_FEATURE;
    }
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size,
                               .memoryTypeIndex = type};
    roma_result r = from_vk(vkAllocateMemory(e->device, &ai, NULL, out), "vkAllocateMemory (out of device memory?)");
    if (r == ROMA_SUCCESS)
        e->bytes += req.size;
    else
        *out = VK_NULL_HANDLE;
    return r;
}

static roma_result image_create(engine *e, uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage,
                                int index)
{
    e->texel_bytes[index] = format == VK_FORMAT_R32_SFLOAT ? 4 : 16;
    roma_result r = app_image_create(e->ctx, width, height, format, usage, &e->images[index]);
    if (r != ROMA_SUCCESS)
        fprintf(stderr, "effect_api: cannot make a %ux%u image (%s)\n", width, height, roma_result_string(r));
    else
        e->bytes += e->images[index].bytes;
    return r;
}

/* A host-visible buffer, mapped; `prefer`: HOST_CACHED for one the host reads. */
static roma_result buffer_create(engine *e, VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags prefer,
                                 host_buffer *out)
{
    VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = size, .usage = usage};
    roma_result r = from_vk(vkCreateBuffer(e->device, &bi, NULL, &out->buffer), "vkCreateBuffer");
    if (r != ROMA_SUCCESS)
        out->buffer = VK_NULL_HANDLE;
    VkMemoryRequirements req;
    if (r == ROMA_SUCCESS) {
        vkGetBufferMemoryRequirements(e->device, out->buffer, &req);
        r = allocate(e, req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, prefer,
                     &out->memory);
    }
    if (r == ROMA_SUCCESS)
        r = from_vk(vkBindBufferMemory(e->device, out->buffer, out->memory, 0), "vkBindBufferMemory");
    if (r == ROMA_SUCCESS && (r = from_vk(vkMapMemory(e->device, out->memory, 0, VK_WHOLE_SIZE, 0, &out->mapped),
                                          "vkMapMemory")))
        out->mapped = NULL;
    return r;
}

static void engine_free(engine *e)
{
    if (e->fence)
        vkDestroyFence(e->device, e->fence, NULL);
    if (e->pool)
        vkDestroyCommandPool(e->device, e->pool, NULL);
    for (int i = 0; i < IMAGE_COUNT; ++i)
        app_image_destroy(e->ctx, &e->images[i]);
    host_buffer *buffers[2] = {&e->upload, &e->readback};
    for (int i = 0; i < 2; ++i) {
        if (buffers[i]->buffer)
            vkDestroyBuffer(e->device, buffers[i]->buffer, NULL);
        if (buffers[i]->memory)
            vkFreeMemory(e->device, buffers[i]->memory, NULL);
    }
    roma_gpu_timer_destroy(e->timer);
    roma_pixel_list_destroy(e->pixels);
    roma_light_effect_destroy(e->count);
    free(e->many_lights);
    roma_gi_effect_destroy(e->gi);
    roma_light_effect_destroy(e->light);
    roma_ao_effect_destroy(e->ao);
    roma_study_ao_destroy(e->study_ao);
    roma_study_rsm_destroy(e->rsm);
    roma_study_depth_layers_destroy(e->layers);
    for (int i = 0; i < ROMA_PASS_COUNT; ++i)
        roma_map_destroy(e->maps[i]);
}

static void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                           VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access)
{
    VkMemoryBarrier2 b = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, .srcStageMask = src_stage,
                          .srcAccessMask = src_access, .dstStageMask = dst_stage, .dstAccessMask = dst_access};
    VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1,
                            .pMemoryBarriers = &b};
    vkCmdPipelineBarrier2(cmd, &dep);
}

/* Frame 0 only: the G-buffer into its images (sampled from then on), the outputs to GENERAL. */
static void record_upload(engine *e, uint32_t width, uint32_t height)
{
    VkCommandBuffer cmd = e->cmd;
    const VkDeviceSize plane = (VkDeviceSize)width * height * 16;
    for (int i = 0; i < INPUTS; ++i) {
        const app_image *im = &e->images[i];
        app_image_barrier(cmd, im->image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                          VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkBufferImageCopy copy = {.bufferOffset = plane * (VkDeviceSize)i,
                                  .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                  .imageExtent = {width, height, 1}};
        vkCmdCopyBufferToImage(cmd, e->upload.buffer, im->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        app_image_barrier(cmd, im->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                          VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                          VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                          VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    }
    for (int i = INPUTS; i < IMAGE_COUNT; ++i)
        if (e->images[i].image)
            app_image_barrier(cmd, e->images[i].image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                              VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                              VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

/* The outputs' copies to the host: their offsets in the readback buffer, each a multiple of 16
 * bytes (a copy's buffer offset is a multiple of its texel's size, 16 for RGBA32F). */
static VkDeviceSize readback_offset(const engine *e, int image, uint32_t width, uint32_t height)
{
    VkDeviceSize offset = 0;
    for (int i = INPUTS; i < image; ++i)
        if (e->images[i].image)
            offset += ((VkDeviceSize)width * height * e->texel_bytes[i] + 15u) & ~(VkDeviceSize)15u;
    return offset;
}

/* Every frame but the first: the outputs back to GENERAL once the last frame's copies read them. */
static void record_outputs_writable(engine *e)
{
    for (int i = INPUTS; i < IMAGE_COUNT; ++i)
        if (e->images[i].image)
            app_image_barrier(e->cmd, e->images[i].image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                              VK_PIPELINE_STAGE_2_COPY_BIT, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                              VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

static void record_readback(engine *e, uint32_t width, uint32_t height)
{
    for (int i = INPUTS; i < IMAGE_COUNT; ++i) {
        if (!e->images[i].image)
            continue;
        app_image_barrier(e->cmd, e->images[i].image, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferImageCopy copy = {.bufferOffset = readback_offset(e, i, width, height),
                                  .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                  .imageExtent = {width, height, 1}};
        vkCmdCopyImageToBuffer(e->cmd, e->images[i].image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, e->readback.buffer,
                               1, &copy);
    }
    memory_barrier(e->cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                   VK_ACCESS_2_HOST_READ_BIT);
}

typedef struct frame_job {
    const effect_api_desc *d;
    const roma_scene_view *view;
    const effect_api_result *out;
    roma_ao_settings ao;
    roma_light_settings light;
    roma_gi_settings gi;
} frame_job;

/* Screen-space AO reads no map: an array that serves it alone is built once, before the
 * frames (the AO pass still binds it), so that its frames do not pay for voxelizing. */
static int built_once(const effect_api_desc *d, const roma_effect_plan *plan, uint32_t map)
{
    int others = 0;
    for (int p = 0; p < ROMA_PASS_COUNT; ++p)
        others |= p != ROMA_PASS_AO && roma_effect_plan_runs(plan, (roma_pass_kind)p) && plan->pass_map[p] == (int)map;
    return d->ao_method == ROMA_AO_METHOD_SCREEN_SPACE && !others;
}

static roma_result record_build(engine *e, const effect_api_desc *d, const roma_effect_plan *plan, uint32_t map,
                                uint32_t f)
{
    roma_map_frame_desc frame = {.frame = f, .seed = d->seed, .jitter_grid = !d->jitter_off,
                                 .jitter_directions = !d->jitter_off, .focus = d->camera.eye};
    /* Cascades: the finest grid's edge from the AO radius unless given. */
    frame.finest_extent = d->finest_extent > 0.0f ? d->finest_extent
                                                  : roma_app_finest_extent(plan->maps[map].resolution, d->ao_radius);
    return roma_map_record_build(e->maps[map], e->cmd, &frame, NULL);
}

/* One frame: the arrays' builds, then each effect on its array, each in a timer scope. */
static roma_result record_frame(engine *e, const frame_job *job, uint32_t f)
{
    const effect_api_desc *d = job->d;
    const roma_effect_plan *plan = &job->out->plan;
    VkCommandBuffer cmd = e->cmd;
    roma_gpu_timer_reset(e->timer, cmd);
    roma_result r = ROMA_SUCCESS;
    for (uint32_t i = 0; i < plan->map_count && r == ROMA_SUCCESS; ++i) {
        if (built_once(d, plan, i))
            continue;
        uint32_t scope = roma_gpu_timer_begin(e->timer, cmd, "build");
        r = record_build(e, d, plan, i, f);
        roma_gpu_timer_end(e->timer, cmd, scope);
    }
    if (r == ROMA_SUCCESS && e->pixels && f == 0) {
        roma_pixel_list_images list = {d->width, d->height, e->images[IN_POSITION].view, 0, f};
        uint32_t scope = roma_gpu_timer_begin(e->timer, cmd, "list");
        r = roma_pixel_list_record(e->pixels, cmd, 0, &list);
        roma_gpu_timer_end(e->timer, cmd, scope);
    }
    const roma_light *lights = job->view->lights;
    /* The study's ray start (the effects were made with its shadow method). */
    const roma_shadow_variant shadows = {.blind_start = d->blind_start};
    const uint32_t light_count = job->view->light_count;
    if (r == ROMA_SUCCESS && e->ao) {
        roma_ao_settings s = job->ao;
        s.frame = f;
        roma_ao_images im = {d->width, d->height, e->images[IN_POSITION].view, e->images[IN_NORMAL].view,
                             e->images[IN_GEOMETRIC].view, e->images[OUT_AO].view, 0, e->pixels};
        uint32_t scope = roma_gpu_timer_begin(e->timer, cmd, "ao");
        r = roma_ao_effect_record(e->ao, cmd, 0, e->maps[plan->pass_map[ROMA_PASS_AO]], &im, &s);
        roma_gpu_timer_end(e->timer, cmd, scope);
    }
    if (r == ROMA_SUCCESS && e->study_ao) {
        roma_ao_settings s = job->ao;
        s.frame = f;
        const roma_map *map = e->maps[plan->pass_map[ROMA_PASS_AO]];
        roma_ao_images im = {d->width, d->height, e->images[IN_POSITION].view, e->images[IN_NORMAL].view,
                             e->images[IN_GEOMETRIC].view, e->images[OUT_AO].view, 0, e->pixels};
        const roma_study_ao_inputs in = {.blind_start = d->blind_start, .camera = &d->camera,
                                         .ssao_steps = d->ssao_steps,
                                         .ssao_layers = roma_study_depth_layers_count(e->layers),
                                         .layers = roma_study_depth_layers_view(e->layers)};
        uint32_t scope;
        if (e->layers) { /* beside the G-buffer, not in AO's time */
            scope = roma_gpu_timer_begin(e->timer, cmd, "depth_layers");
            r = roma_study_depth_layers_record(e->layers, cmd, &d->camera, d->seed, f);
            roma_gpu_timer_end(e->timer, cmd, scope);
        }
        scope = roma_gpu_timer_begin(e->timer, cmd, "baseline_build");
        if (r == ROMA_SUCCESS)
            r = roma_study_ao_record_build(e->study_ao, cmd, map);
        roma_gpu_timer_end(e->timer, cmd, scope);
        scope = roma_gpu_timer_begin(e->timer, cmd, "ao");
        if (r == ROMA_SUCCESS)
            r = roma_study_ao_record(e->study_ao, cmd, 0, map, &im, &s, &in);
        roma_gpu_timer_end(e->timer, cmd, scope);
    }
    if (r == ROMA_SUCCESS && e->light) {
        roma_light_settings s = job->light;
        s.frame = f;
        int m = plan->pass_map[ROMA_PASS_PUNCTUAL_LIGHTS] >= 0 ? plan->pass_map[ROMA_PASS_PUNCTUAL_LIGHTS]
                                                                : plan->pass_map[ROMA_PASS_SOFT_SHADOWS];
        roma_light_images im = {d->width, d->height, e->images[IN_POSITION].view, e->images[IN_NORMAL].view,
                                e->images[IN_GEOMETRIC].view, e->images[OUT_DIRECT].view, 0, e->pixels};
        uint32_t scope = roma_gpu_timer_begin(e->timer, cmd, "direct");
        r = roma_light_effect_record_variant(e->light, cmd, 0, e->maps[m], &im, lights, light_count, &s, &shadows);
        roma_gpu_timer_end(e->timer, cmd, scope);
    }
    if (r == ROMA_SUCCESS && e->rsm && f == 0) { /* the lights stand still: their RSMs once */
        uint32_t scope = roma_gpu_timer_begin(e->timer, cmd, "rsm");
        r = roma_study_rsm_record(e->rsm, cmd);
        roma_gpu_timer_end(e->timer, cmd, scope);
    }
    if (r == ROMA_SUCCESS && e->gi) {
        roma_gi_settings s = job->gi;
        roma_shadow_variant gi_rays = shadows;
        const roma_map_info *gi_info = &job->out->map_info[plan->pass_map[ROMA_PASS_GI]];
        if (e->rsm)
            roma_study_rsm_variant(e->rsm, d->rsm_tolerance_cells * gi_info->trace_cell, &gi_rays);
        s.frame = f;
        roma_light_images im = {d->width, d->height, e->images[IN_POSITION].view, e->images[IN_NORMAL].view,
                                e->images[IN_GEOMETRIC].view, e->images[OUT_GI].view, 0, e->pixels};
        uint32_t scope = roma_gpu_timer_begin(e->timer, cmd, "gi");
        r = roma_gi_effect_record_variant(e->gi, cmd, 0, e->maps[plan->pass_map[ROMA_PASS_GI]], &im, lights,
                                          light_count, &s, &gi_rays);
        roma_gpu_timer_end(e->timer, cmd, scope);
    }
    if (r == ROMA_SUCCESS && e->count) {
        roma_light_settings s = job->light;
        s.frame = f;
        s.max_steps = d->lights_max_steps ? d->lights_max_steps : MANY_LIGHTS_MAX_STEPS;
        s.output = ROMA_LIGHT_OUTPUT_VISIBLE_COUNT;
        s.lights_per_frame = d->lights_per_frame < plan->many_light_count ? d->lights_per_frame : 0;
        roma_light_images im = {d->width, d->height, e->images[IN_POSITION].view, e->images[IN_NORMAL].view,
                                e->images[IN_GEOMETRIC].view, e->images[OUT_LIGHTS].view, 0, e->pixels};
        uint32_t scope = roma_gpu_timer_begin(e->timer, cmd, "lights");
        r = roma_light_effect_record_variant(e->count, cmd, 0, e->maps[plan->pass_map[ROMA_PASS_MANY_LIGHTS]], &im,
                                             e->many_lights, plan->many_light_count, &s, &shadows);
        roma_gpu_timer_end(e->timer, cmd, scope);
    }
    return r;
}

/* The timer's scopes of the frame just finished, added to the result's sums. */
static roma_result add_timings(engine *e, effect_api_result *out)
{
    roma_gpu_timing t[ROMA_PASS_COUNT + 8];
    uint32_t count = ROMA_PASS_COUNT + 8;
    roma_result r = roma_gpu_timer_read(e->timer, t, &count);
    uint32_t build = 0;
    for (uint32_t i = 0; i < count && r == ROMA_SUCCESS; ++i) {
        if (strcmp(t[i].name, "build") == 0 && build < ROMA_PASS_COUNT)
            out->build_ms[build++] += t[i].milliseconds;
        else if (strcmp(t[i].name, "ao") == 0)
            out->ao_ms += t[i].milliseconds;
        else if (strcmp(t[i].name, "direct") == 0)
            out->direct_ms += t[i].milliseconds;
        else if (strcmp(t[i].name, "gi") == 0)
            out->gi_ms += t[i].milliseconds;
        else if (strcmp(t[i].name, "lights") == 0)
            out->lights_ms += t[i].milliseconds;
        else if (strcmp(t[i].name, "depth_layers") == 0)
            out->depth_layers_ms += t[i].milliseconds;
        else if (strcmp(t[i].name, "rsm") == 0)
            out->rsm_ms += t[i].milliseconds;
        else if (strcmp(t[i].name, "list") == 0)
            out->list_ms += t[i].milliseconds;
        else if (strcmp(t[i].name, "baseline_build") == 0) { /* part of AO's time, as in the study */
            out->baseline_build_ms += t[i].milliseconds;
            out->ao_ms += t[i].milliseconds;
        }
    }
    return r;
}

/* The frame's outputs added to the sums kept in the result's images (covered pixels only). */
static void accumulate(const engine *e, const effect_api_desc *d, effect_api_result *out)
{
    const size_t n = (size_t)d->width * d->height;
    const char *base = e->readback.mapped;
    const float *ao = e->images[OUT_AO].image ? (const float *)(base + readback_offset(e, OUT_AO, d->width, d->height))
                                              : NULL;
    const float *direct = e->images[OUT_DIRECT].image
                              ? (const float *)(base + readback_offset(e, OUT_DIRECT, d->width, d->height))
                              : NULL;
    const float *gi = e->images[OUT_GI].image ? (const float *)(base + readback_offset(e, OUT_GI, d->width, d->height))
                                              : NULL;
    const float *count = e->images[OUT_LIGHTS].image
                             ? (const float *)(base + readback_offset(e, OUT_LIGHTS, d->width, d->height))
                             : NULL;
    for (size_t i = 0; i < n; ++i) {
        if (!(out->coverage.pixels[i] > 0.0f))
            continue;
        if (ao)
            out->ao.pixels[i] += ao[i];
        if (count && out->lights.pixels)
            out->lights.pixels[i] += count[4 * i];
        for (int c = 0; c < 3; ++c) {
            if (direct)
                out->direct.pixels[3 * i + c] += direct[4 * i + c];
            if (gi)
                out->gi.pixels[3 * i + c] += gi[4 * i + c];
        }
    }
}

/* Sums to the reference's quantities: the mean visibility, albedo / pi times the mean irradiance. */
static void resolve(const effect_api_desc *d, const float *albedo, uint32_t frames, effect_api_result *out)
{
    const size_t n = (size_t)d->width * d->height;
    for (size_t i = 0; i < n; ++i) {
        const int covered = out->coverage.pixels[i] > 0.0f;
        if (out->ao.pixels)
            out->ao.pixels[i] = covered ? out->ao.pixels[i] / (float)frames : 1.0f;
        if (out->lights.pixels)
            out->lights.pixels[i] /= (float)frames; /* 0 where nothing is seen */
        for (int c = 0; c < 3; ++c) {
            if (out->direct.pixels)
                out->direct.pixels[3 * i + c] *= albedo[3 * i + c] / PI_F / (float)frames;
            if (out->gi.pixels)
                out->gi.pixels[3 * i + c] *= albedo[3 * i + c] / PI_F / (float)frames;
        }
    }
}

static roma_result create_objects(engine *e, const roma_scene *scene, const effect_api_desc *d,
                                  effect_api_result *out)
{
    roma_effect_options options = d->options;
    options.effects &= ROMA_EFFECT_AO | ROMA_EFFECT_DIRECT | ROMA_EFFECT_GI | ROMA_EFFECT_LIGHTS;
    roma_result r = roma_effect_plan_derive(scene, &options, NULL, &out->plan);
    if (!d->gi_rsm) /* point and spot lights reach GI by shadow rays: no RSM */
        out->plan.passes &= ~(1u << ROMA_PASS_RSM);
    const roma_effect_plan *plan = &out->plan;
    for (uint32_t i = 0; i < plan->map_count && r == ROMA_SUCCESS; ++i) {
        const uint32_t angular = plan->maps[i].angular, res = plan->maps[i].resolution;
        const uint32_t fit = roma_app_levels_that_fit(res, angular, e->max_storage_range);
        /* Fewer levels than asked where one storage buffer of the device holds no more: they
         * reach less far around the camera; said (not where the 256 maps are the limit). */
        const uint32_t most = fit ? fit : 1u;
        if (d->cascades > most && fit && fit < 256u / (angular * angular))
            fprintf(stderr, "effect_api: note: RES %u, A %u: %u of the %u cascade levels fit in one storage buffer of "
                            "this device (maxStorageBufferRange %u MiB); the coarsest reaches less far\n",
                    res, angular, fit, d->cascades, e->max_storage_range >> 20);
        roma_map_desc md = {.resolution = res, .angular = angular, .frames_in_flight = 1,
                            .cascades = d->cascades < most ? d->cascades : most};
        r = roma_map_create(e->ctx, &md, scene, &e->maps[i]);
        if (r == ROMA_SUCCESS)
            r = roma_map_get_info(e->maps[i], &out->map_info[i]);
    }
    const int lit = roma_effect_plan_runs(plan, ROMA_PASS_PUNCTUAL_LIGHTS) ||
                    roma_effect_plan_runs(plan, ROMA_PASS_SOFT_SHADOWS);
    /* The surface grids at their array's RES (at least the map's RES). */
    const int ao_map = plan->pass_map[ROMA_PASS_AO];
    const roma_ao_effect_desc ao_desc = {.frames_in_flight = 1, .pixel_dispatch = d->pixel_dispatch,
                                         .surface_resolution = ao_map >= 0 ? plan->maps[ao_map].resolution : 0};
    const int light_map = plan->pass_map[ROMA_PASS_SOFT_SHADOWS] >= 0 ? plan->pass_map[ROMA_PASS_SOFT_SHADOWS]
                                                                     : plan->pass_map[ROMA_PASS_PUNCTUAL_LIGHTS];
    const int count_map = plan->pass_map[ROMA_PASS_MANY_LIGHTS];
    const roma_light_effect_desc light_desc = {.frames_in_flight = 1, .pixel_dispatch = d->pixel_dispatch,
                                               .surface_resolution = light_map >= 0 ? plan->maps[light_map].resolution : 0};
    const roma_light_effect_desc count_desc = {.frames_in_flight = 1, .pixel_dispatch = d->pixel_dispatch,
                                               .surface_resolution = count_map >= 0 ? plan->maps[count_map].resolution : 0};
    const int gi_map = plan->pass_map[ROMA_PASS_GI];
    const roma_gi_effect_desc gi_desc = {.frames_in_flight = 1, .pixel_dispatch = d->pixel_dispatch,
                                         .surface_resolution = gi_map >= 0 ? plan->maps[gi_map].resolution : 0};
    const int study_ao = d->ao_method != ROMA_AO_METHOD_ROMA || d->blind_start;
    if (r == ROMA_SUCCESS && roma_effect_plan_runs(plan, ROMA_PASS_AO) && !study_ao)
        r = roma_ao_effect_create(e->ctx, &ao_desc, &e->ao);
    if (r == ROMA_SUCCESS && roma_effect_plan_runs(plan, ROMA_PASS_AO) && study_ao)
        r = roma_study_ao_create(e->ctx, d->ao_method, &ao_desc, &e->study_ao);
    if (r == ROMA_SUCCESS && e->study_ao && d->ssao_layers)
        r = roma_study_depth_layers_create(e->ctx, scene, d->ssao_traced, d->width, d->height, d->ssao_layers,
                                           d->ssao_keep, &e->layers);
    if (r == ROMA_SUCCESS && lit)
        r = roma_study_light_effect_create(e->ctx, &light_desc, d->shadow_method, &e->light);
    if (r == ROMA_SUCCESS && lit)
        r = roma_light_effect_set_area_lights(e->light, scene);
    if (r == ROMA_SUCCESS && roma_effect_plan_runs(plan, ROMA_PASS_GI))
        r = roma_study_gi_effect_create(e->ctx, &gi_desc, d->shadow_method, d->gi_rsm, &e->gi);
    if (r == ROMA_SUCCESS && e->gi && d->gi_rsm)
        r = roma_study_rsm_create(e->ctx, scene, d->rsm_size, &e->rsm);
    if (r == ROMA_SUCCESS && e->gi)
        r = roma_gi_effect_set_scene(e->gi, scene);
    const uint32_t many = plan->many_light_count;
    if (r == ROMA_SUCCESS && roma_effect_plan_runs(plan, ROMA_PASS_MANY_LIGHTS) && many && d->many_light_positions) {
        r = roma_study_light_effect_create(e->ctx, &count_desc, d->shadow_method, &e->count);
        e->many_lights = r == ROMA_SUCCESS ? calloc(many, sizeof *e->many_lights) : NULL;
        if (r == ROMA_SUCCESS && !e->many_lights)
            r = ROMA_ERROR_OUT_OF_HOST_MEMORY;
        for (uint32_t i = 0; r == ROMA_SUCCESS && i < many; ++i)
            e->many_lights[i] = (roma_light){.type = ROMA_LIGHT_POINT,
                                             .position = {d->many_light_positions[3 * i],
                                                          d->many_light_positions[3 * i + 1],
                                                          d->many_light_positions[3 * i + 2]},
                                             .color = {1.0f, 1.0f, 1.0f},
                                             .intensity = 1.0f};
    }
    if (r == ROMA_SUCCESS && d->shared_list)
        r = roma_pixel_list_create(e->ctx, &(roma_pixel_list_desc){.frames_in_flight = 1}, &e->pixels);
    if (r == ROMA_SUCCESS)
        r = roma_gpu_timer_create(e->ctx, ROMA_PASS_COUNT + 8, &e->timer);
    return r;
}

static roma_result create_images(engine *e, const effect_api_desc *d)
{
    const uint32_t w = d->width, h = d->height;
    const VkImageUsageFlags in_usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    const VkImageUsageFlags out_usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    /* The upload first: the largest allocation before the images (its size checked there). */
    roma_result r = buffer_create(e, (VkDeviceSize)w * h * 16 * INPUTS, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, 0,
                                  &e->upload);
    for (int i = 0; i < INPUTS && r == ROMA_SUCCESS; ++i)
        r = image_create(e, w, h, VK_FORMAT_R32G32B32A32_SFLOAT, in_usage, i);
    if (r == ROMA_SUCCESS && (e->ao || e->study_ao))
        r = image_create(e, w, h, VK_FORMAT_R32_SFLOAT, out_usage, OUT_AO);
    if (r == ROMA_SUCCESS && e->light)
        r = image_create(e, w, h, VK_FORMAT_R32G32B32A32_SFLOAT, out_usage, OUT_DIRECT);
    if (r == ROMA_SUCCESS && e->gi)
        r = image_create(e, w, h, VK_FORMAT_R32G32B32A32_SFLOAT, out_usage, OUT_GI);
    if (r == ROMA_SUCCESS && e->count)
        r = image_create(e, w, h, VK_FORMAT_R32G32B32A32_SFLOAT, out_usage, OUT_LIGHTS);
    /* (16 bytes more: a buffer of no size is invalid when no output is read back) */
    if (r == ROMA_SUCCESS)
        r = buffer_create(e, readback_offset(e, IMAGE_COUNT, w, h) + 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          VK_MEMORY_PROPERTY_HOST_CACHED_BIT, &e->readback);
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                  .queueFamilyIndex = roma_context_queue_family(e->ctx)};
    if (r == ROMA_SUCCESS)
        r = from_vk(vkCreateCommandPool(e->device, &pi, NULL, &e->pool), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = e->pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    if (r == ROMA_SUCCESS)
        r = from_vk(vkAllocateCommandBuffers(e->device, &ai, &e->cmd), "vkAllocateCommandBuffers");
    VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    if (r == ROMA_SUCCESS)
        r = from_vk(vkCreateFence(e->device, &fi, NULL, &e->fence), "vkCreateFence");
    return r;
}

static roma_result run_frames(engine *e, const effect_api_desc *d, const frame_job *job, effect_api_result *out)
{
    const uint32_t frames = d->frames ? d->frames : 1;
    VkQueue queue = roma_context_queue(e->ctx);
    roma_result r = ROMA_SUCCESS;
    const roma_effect_plan *plan = &out->plan;
    int once = 0;
    for (uint32_t i = 0; i < plan->map_count; ++i)
        once |= built_once(d, plan, i);
    if (once) { /* before the frames, untimed */
        VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                       .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
        r = from_vk(vkBeginCommandBuffer(e->cmd, &bi), "vkBeginCommandBuffer");
        const int begun = r == ROMA_SUCCESS;
        for (uint32_t i = 0; i < plan->map_count && r == ROMA_SUCCESS; ++i)
            if (built_once(d, plan, i))
                r = record_build(e, d, plan, i, 0);
        VkResult ended = begun ? vkEndCommandBuffer(e->cmd) : VK_SUCCESS;
        if (r == ROMA_SUCCESS)
            r = from_vk(ended, "vkEndCommandBuffer");
        VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &e->cmd};
        if (r == ROMA_SUCCESS)
            r = from_vk(vkQueueSubmit(queue, 1, &si, e->fence), "vkQueueSubmit");
        if (r == ROMA_SUCCESS)
            r = from_vk(vkWaitForFences(e->device, 1, &e->fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        if (r == ROMA_SUCCESS)
            r = from_vk(vkResetFences(e->device, 1, &e->fence), "vkResetFences");
        if (r == ROMA_SUCCESS)
            r = from_vk(vkResetCommandBuffer(e->cmd, 0), "vkResetCommandBuffer");
    }
    for (uint32_t f = 0; f < frames && r == ROMA_SUCCESS; ++f) {
        VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                       .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
        r = from_vk(vkBeginCommandBuffer(e->cmd, &bi), "vkBeginCommandBuffer");
        if (r != ROMA_SUCCESS)
            break;
        if (f == 0)
            record_upload(e, d->width, d->height);
        else
            record_outputs_writable(e);
        r = record_frame(e, job, f);
        if (r == ROMA_SUCCESS)
            record_readback(e, d->width, d->height);
        VkResult ended = vkEndCommandBuffer(e->cmd);
        if (r == ROMA_SUCCESS)
            r = from_vk(ended, "vkEndCommandBuffer");
        VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1,
                           .pCommandBuffers = &e->cmd};
        const double submitted = roma_app_now_ms();
        if (r == ROMA_SUCCESS)
            r = from_vk(vkQueueSubmit(queue, 1, &si, e->fence), "vkQueueSubmit");
        if (r == ROMA_SUCCESS)
            r = from_vk(vkWaitForFences(e->device, 1, &e->fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        out->frames_ms += roma_app_now_ms() - submitted;
        if (r == ROMA_SUCCESS)
            r = from_vk(vkResetFences(e->device, 1, &e->fence), "vkResetFences");
        if (r == ROMA_SUCCESS)
            r = add_timings(e, out);
        if (r == ROMA_SUCCESS)
            accumulate(e, d, out);
        if (r == ROMA_SUCCESS && d->progress)
            d->progress((float)(f + 1) / (float)frames, d->progress_user_data);
        if (r == ROMA_SUCCESS)
            r = from_vk(vkResetCommandBuffer(e->cmd, 0), "vkResetCommandBuffer");
    }
    return r;
}

roma_result effect_api_render(roma_context *ctx, const roma_scene *scene, const roma_ref *ref,
                              const effect_api_desc *d, effect_api_result *out)
{
    memset(out, 0, sizeof *out);
    roma_camera_frame check;
    if (!ctx || !scene || !ref || !d || !d->width || !d->height ||
        !roma_camera_make_frame(&d->camera, d->width, d->height, &check))
        return ROMA_ERROR_INVALID_ARGUMENT;
    if (d->shadow_method == ROMA_SHADOW_METHOD_VOXEL_DDA && d->blind_start) {
        fprintf(stderr, "effect_api: the exact shadow rays walk the BOM the blind start leaves unread\n");
        return ROMA_ERROR_INVALID_ARGUMENT;
    }
    roma_scene_view view;
    roma_scene_get_view(scene, &view);
    roma_context_info info;
    roma_context_get_info(ctx, &info);
    engine e = {.ctx = ctx, .device = roma_context_device(ctx), .max_allocation = info.max_allocation_size};
    vkGetPhysicalDeviceMemoryProperties(roma_context_physical_device(ctx), &e.memory);
    if (!e.max_allocation)
        e.max_allocation = UINT64_MAX;
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(roma_context_physical_device(ctx), &props);
    e.max_storage_range = props.limits.maxStorageBufferRange;
    if (d->width > props.limits.maxImageDimension2D || d->height > props.limits.maxImageDimension2D) {
        fprintf(stderr, "effect_api: %ux%u is larger than the device's images (maxImageDimension2D %u)\n", d->width,
                d->height, props.limits.maxImageDimension2D);
        return ROMA_ERROR_INVALID_ARGUMENT;
    }
    roma_result r = create_objects(&e, scene, d, out);
    if (r == ROMA_SUCCESS)
        r = create_images(&e, d);
    const size_t n = (size_t)d->width * d->height;
    float *albedo = r == ROMA_SUCCESS ? malloc(n * 3 * sizeof(float)) : NULL;
    if (r == ROMA_SUCCESS && !albedo)
        r = ROMA_ERROR_OUT_OF_HOST_MEMORY;
    if (r == ROMA_SUCCESS)
        r = roma_image_alloc(&out->coverage, d->width, d->height, 1);
    /* An effect asked for that the scene cannot show (direct light without lights) stays black. */
    const uint32_t effects = d->options.effects;
    if (r == ROMA_SUCCESS && (effects & ROMA_EFFECT_AO))
        r = roma_image_alloc(&out->ao, d->width, d->height, 1);
    if (r == ROMA_SUCCESS && (effects & ROMA_EFFECT_DIRECT))
        r = roma_image_alloc(&out->direct, d->width, d->height, 3);
    if (r == ROMA_SUCCESS && (effects & ROMA_EFFECT_GI))
        r = roma_image_alloc(&out->gi, d->width, d->height, 3);
    if (r == ROMA_SUCCESS && (effects & ROMA_EFFECT_LIGHTS))
        r = roma_image_alloc(&out->lights, d->width, d->height, 1);
    if (r == ROMA_SUCCESS) { /* straight into the upload buffer, one plane an image */
        float *upload = e.upload.mapped;
        const roma_ref_gbuffer g = {upload, upload + 4 * n, upload + 8 * n, albedo};
        const double t0 = roma_app_now_ms();
        r = roma_ref_render_gbuffer(ref, &d->camera, d->width, d->height, &g);
        out->gbuffer_ms = roma_app_now_ms() - t0;
        for (size_t i = 0; i < n && r == ROMA_SUCCESS; ++i)
            out->coverage.pixels[i] = upload[4 * i + 3] > 0.0f ? 1.0f : 0.0f;
    }
    const float radius = d->ao_radius > 0.0f && isfinite(d->ao_radius) ? d->ao_radius : 0.0f;
    const uint32_t spp = d->spp ? d->spp : 1;
    frame_job job = {
        .d = d, .view = &view, .out = out,
        .ao = {.samples = spp, .radius = radius, .offset_cells = d->offset_cells, .skip_cells = d->ao_skip_cells,
               .seed = d->seed, .resolution_divisor = d->resolution_divisor, .start = d->ao_start,
               .trace = d->ao_trace},
        .light = {.max_steps = d->max_steps, .offset_cells = d->offset_cells, .skip_cells = d->skip_cells,
                  .area_samples = spp, .seed = d->seed, .resolution_divisor = d->resolution_divisor},
        .gi = {.samples = spp, .offset_cells = d->offset_cells, .skip_cells = d->ao_skip_cells,
               .shadow_skip_cells = d->skip_cells, .max_steps = d->max_steps, .seed = d->seed,
               .resolution_divisor = d->resolution_divisor},
    };
    if (r == ROMA_SUCCESS)
        r = run_frames(&e, d, &job, out);
    if (r == ROMA_SUCCESS)
        resolve(d, albedo, d->frames ? d->frames : 1, out);
    out->effect_bytes = e.bytes;
    out->baseline_bytes = roma_study_ao_bytes(e.study_ao, &out->baseline_build_bytes);
    out->rsm_bytes = roma_study_rsm_bytes(e.rsm);
    out->depth_layers_bytes = roma_study_depth_layers_bytes(e.layers);
    if (r != ROMA_SUCCESS && e.device)
        vkDeviceWaitIdle(e.device); /* nothing of this call may still run when its objects go */
    engine_free(&e);
    free(albedo);
    if (r != ROMA_SUCCESS)
        effect_api_result_free(out);
    return r;
}

void effect_api_result_free(effect_api_result *result)
{
    if (!result)
        return;
    roma_image_free(&result->ao);
    roma_image_free(&result->direct);
    roma_image_free(&result->gi);
    roma_image_free(&result->lights);
    roma_image_free(&result->coverage);
}
