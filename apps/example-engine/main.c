/* An engine that links libroma, written against the installed headers only: a tutorial.
 *
 * It owns its Vulkan instance and device, created with exactly what
 * roma_get_device_requirements lists (vk_helpers.c), and hands them to a libroma context.
 * Its scene (scene.c) is a room, an animated glTF character and a box that moves every
 * frame. It keeps two frames in flight, each in a slot of its own (a command buffer, a fence,
 * libroma's slot), and every frame of the loop (run_frames, below) goes:
 *   1. wait for the slot's fence: the frame the slot held is done, and the engine's checks
 *      (checks.c) read back that frame's answers;
 *   then into the slot's command buffer:
 *   2. libroma's skinning of the animated character (roma_animator_record), when given one;
 *   3. its own animation pass (animate.comp): the room at rest, the skinned character
 *      placed in it and a rigid box moved along x, into its own GPU buffer;
 *   4. roma_map_record_build, reading those positions by address (gpu_positions);
 *   5. its own tracing pass (probe.comp, including roma/trace.glsl) over probe rays whose
 *      answers are known from the box's pose that frame;
 *   6. its own G-buffer of the floor seen from above (gbuffer.comp), and libroma's AO
 *      effect on it (roma_ao_effect_record) into its own image;
 *   7. libroma's temporal effect (roma_temporal_effect_record) averaging that AO over
 *      frames into its own pair of history images, swapped every frame;
 *   8. submit, after the checks' copies of the AO for the host, with the slot's fence.
 *
 *   example-engine [--frames N] [--validation | --sync-validation] [--character file.glb]
 *
 * --validation turns on the Khronos validation layer, --sync-validation the layer with
 * synchronization validation; any message fails the run. The checks judge the probe
 * answers, the AO (darker in a corner of the room than in the open) and its average and
 * the character inside the traced volume, and print resident memory and libroma's device
 * memory at frame 100 and at the end (the soak figures). Exit code 0 when every probe
 * answer is right and no validation message was seen. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "checks.h"
#include "roma/gltf.h"
#include "roma/roma.h"
#include "scene.h"
#include "vk_helpers.h"

#define MAX_STEPS 256u
#define AO_RADIUS 0.3f

/* What the frame loop records with: libroma's objects and the engine's own. */
typedef struct renderer {
    engine *e;
    roma_context *ctx;
    roma_scene *scene, *character; /* character: NULL without --character */
    roma_animator *animator;
    roma_map *map;
    roma_ao_effect *ao;
    roma_temporal_effect *temporal;
    uint32_t vertex_count, box_first, character_first, character_count;
    buffer rest, positions; /* the scene at rest; the animated positions libroma reads */
    VkPipelineLayout animate_layout, probe_layout, gbuffer_layout;
    VkPipeline animate, probe, gbuffer;
    VkDescriptorSetLayout gbuffer_set_layout;
    VkDescriptorPool gbuffer_pool;
    VkDescriptorSet gbuffer_set;
    image gb_position, gb_normal, ao_image, history[2];
    VkCommandPool pool;
    VkCommandBuffer cmds[SLOTS];
    VkFence fences[SLOTS];
} renderer;

static void log_to_stderr(roma_log_level level, roma_result code, const char *message, void *user)
{
    (void)user, (void)code;
    if (level >= ROMA_LOG_WARNING)
        fprintf(stderr, "libroma %s: %s\n", roma_log_level_string(level), message);
}

/* libroma on the engine's device and queue: the context, the character and its animator,
 * the scene and its map. */
static int create_libroma(renderer *r, const roma_device_requirements *req, const char *character_path)
{
    roma_logger logger = {log_to_stderr, NULL};
    const engine *e = r->e;
    roma_external_device ext = {e->instance, e->physical, e->device, e->family, e->queue, &req->features};
    roma_context_desc cd = {.external = &ext, .logger = logger};
    if (roma_context_create(&cd, &r->ctx) != ROMA_SUCCESS)
        return 0;
    roma_context_info info;
    roma_context_get_info(r->ctx, &info);
    r->e->corrected_division = info.corrected_division; /* for the engine's shaders including trace.glsl */
    roma_gltf_desc gd = {.logger = logger};
    if (character_path && (roma_scene_load_gltf(character_path, &gd, &r->character) != ROMA_SUCCESS ||
                           roma_animator_create(r->ctx, r->character, &(roma_animator_desc){.frames_in_flight = SLOTS},
                                                &r->animator) != ROMA_SUCCESS))
        return 0;
    if (!(r->scene = make_scene(logger, r->character, &r->character_first, &r->character_count, &r->box_first)))
        return 0;
    roma_map_desc md = {.resolution = 128, .angular = 4, .frames_in_flight = SLOTS};
    return roma_map_create(r->ctx, &md, r->scene, &r->map) == ROMA_SUCCESS;
}

/* The engine's passes and what they write: the positions, the animation, tracing and
 * G-buffer pipelines, the floor G-buffer, its AO and the AO's history images, and libroma's
 * AO and temporal effects, which work on those images. */
static int create_passes(renderer *r)
{
    const engine *e = r->e;
    roma_scene_view sv;
    roma_scene_get_view(r->scene, &sv);
    r->vertex_count = sv.vertex_count;
    if (!buffer_create(e, 12ull * sv.vertex_count, 1, &r->rest) ||
        !buffer_create(e, 12ull * sv.vertex_count, 0, &r->positions))
        return 0;
    memcpy(r->rest.mapped, sv.positions, 12ull * sv.vertex_count);
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    const VkImageUsageFlags read_back = usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT; /* by the checks */
    const VkFormat rgba = VK_FORMAT_R32G32B32A32_SFLOAT;
    return pipeline_create(e, "animate.spv", 80, VK_NULL_HANDLE, &r->animate_layout, &r->animate) &&
           pipeline_create(e, "probe.spv", 40, VK_NULL_HANDLE, &r->probe_layout, &r->probe) &&
           image_create(e, GB_W, GB_H, rgba, usage, &r->gb_position) &&
           image_create(e, GB_W, GB_H, rgba, usage, &r->gb_normal) &&
           image_create(e, GB_W, GB_H, VK_FORMAT_R32_SFLOAT, read_back, &r->ao_image) &&
           image_create(e, GB_W, GB_H, rgba, read_back, &r->history[0]) &&
           image_create(e, GB_W, GB_H, rgba, read_back, &r->history[1]) &&
           roma_temporal_effect_create(r->ctx, &(roma_temporal_effect_desc){.frames_in_flight = SLOTS},
                                       &r->temporal) == ROMA_SUCCESS &&
           storage_image_set_create(e, 2, (VkImageView[]){r->gb_position.view, r->gb_normal.view},
                                    &r->gbuffer_set_layout, &r->gbuffer_pool, &r->gbuffer_set) &&
           pipeline_create(e, "gbuffer.spv", 32, r->gbuffer_set_layout, &r->gbuffer_layout, &r->gbuffer) &&
           roma_ao_effect_create(r->ctx, &(roma_ao_effect_desc){.frames_in_flight = SLOTS}, &r->ao) == ROMA_SUCCESS;
}

/* A command buffer and a fence (signalled, so that the first wait passes) per slot; the
 * five images go to GENERAL once, before the first frame. */
static int create_slots(renderer *r)
{
    const engine *e = r->e;
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                  .queueFamilyIndex = e->family};
    if (vkCreateCommandPool(e->device, &pi, NULL, &r->pool) != VK_SUCCESS)
        return 0;
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = r->pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = SLOTS};
    const VkImage images[5] = {r->gb_position.image, r->gb_normal.image, r->ao_image.image, r->history[0].image,
                               r->history[1].image};
    if (vkAllocateCommandBuffers(e->device, &ai, r->cmds) != VK_SUCCESS || !images_to_general(e, r->cmds[0], 5, images))
        return 0;
    VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, .flags = VK_FENCE_CREATE_SIGNALED_BIT};
    for (int s = 0; s < SLOTS; ++s)
        if (vkCreateFence(e->device, &fi, NULL, &r->fences[s]) != VK_SUCCESS)
            return 0;
    return 1;
}

static void destroy_renderer(renderer *r)
{
    VkDevice device = r->e->device;
    if (device) {
        vkDeviceWaitIdle(device);
        for (int s = 0; s < SLOTS; ++s)
            if (r->fences[s])
                vkDestroyFence(device, r->fences[s], NULL);
        if (r->pool)
            vkDestroyCommandPool(device, r->pool, NULL);
        VkPipeline pipelines[3] = {r->animate, r->probe, r->gbuffer};
        VkPipelineLayout layouts[3] = {r->animate_layout, r->probe_layout, r->gbuffer_layout};
        for (int i = 0; i < 3; ++i) {
            if (pipelines[i])
                vkDestroyPipeline(device, pipelines[i], NULL);
            if (layouts[i])
                vkDestroyPipelineLayout(device, layouts[i], NULL);
        }
        if (r->gbuffer_pool)
            vkDestroyDescriptorPool(device, r->gbuffer_pool, NULL);
        if (r->gbuffer_set_layout)
            vkDestroyDescriptorSetLayout(device, r->gbuffer_set_layout, NULL);
    }
    image *images[5] = {&r->gb_position, &r->gb_normal, &r->ao_image, &r->history[0], &r->history[1]};
    for (int i = 0; i < 5; ++i)
        image_destroy(r->e, images[i]);
    buffer_destroy(r->e, &r->rest);
    buffer_destroy(r->e, &r->positions);
    roma_ao_effect_destroy(r->ao);
    roma_temporal_effect_destroy(r->temporal);
    roma_map_destroy(r->map);
    roma_animator_destroy(r->animator);
    roma_scene_destroy(r->character);
    roma_scene_destroy(r->scene);
    roma_context_destroy(r->ctx);
}

/* 3. The engine's animation pass: the room at rest, the character's skinned vertices
 *    placed in the room, the box moved by box_offset(frame). libroma's build opens with a
 *    barrier after every earlier command, so the positions need no other. */
static void record_animation(const renderer *r, VkCommandBuffer cmd, uint32_t frame, VkDeviceAddress skinned)
{
    const float *place = character_placement;
    struct {
        VkDeviceAddress rest, positions, skinned;
        uint32_t vertex_count, object_first, character_first, character_count;
        float pad[2], offset[4], placement[4];
    } anim = {r->rest.address, r->positions.address, skinned, r->vertex_count, r->box_first, r->character_first,
              r->character_count, {0, 0}, {box_offset(frame), 0, 0, 0}, {place[0], place[1], place[2], place[3]}};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r->animate);
    vkCmdPushConstants(cmd, r->animate_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof anim, &anim);
    vkCmdDispatch(cmd, (r->vertex_count + 63) / 64, 1, 1);
}

/* 5. The engine's tracing pass over this frame's maps, reached by address (the build ends
 *    with a barrier that makes them readable by any later command). */
static void record_probe_trace(const renderer *r, VkCommandBuffer cmd, const probe_set *p)
{
    roma_map_info info;
    roma_map_get_info(r->map, &info);
    struct {
        VkDeviceAddress params, maps, rays, hits;
        uint32_t count, max_steps;
    } pp = {info.params_address, info.maps_address, p->rays.address, p->hits.address, p->count, MAX_STEPS};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r->probe);
    vkCmdPushConstants(cmd, r->probe_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof pp, &pp);
    vkCmdDispatch(cmd, 1, 1, 1);
}

/* 6. The floor G-buffer, after the last frame's readers of it (the build's opening barrier
 *    already orders them, the first barrier says so), read by libroma's AO next. */
static void record_gbuffer(const renderer *r, VkCommandBuffer cmd)
{
    memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT,
                   VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    struct {
        uint32_t size[2];
        float pad[2], area[4];
    } gp = {{GB_W, GB_H}, {0, 0}, {-1.0f, -1.0f, 1.0f, 2.0f}};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r->gbuffer);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r->gbuffer_layout, 0, 1, &r->gbuffer_set, 0, NULL);
    vkCmdPushConstants(cmd, r->gbuffer_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof gp, &gp);
    vkCmdDispatch(cmd, GB_W / 8, GB_H / 8, 1);
    memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

/* The frame loop, steps 1-8 of the header: frames frames, SLOTS of them in flight. 0 when
 * a record or a submit failed. */
static int run_frames(renderer *r, checks *c, uint32_t frames)
{
    for (uint32_t f = 0; f < frames + SLOTS; ++f) {
        uint32_t s = f % SLOTS; /* the slot: its command buffer, its fence, libroma's slot */
        VkCommandBuffer cmd = r->cmds[s];
        /* 1. The frame the slot held is done; the checks read back its answers. */
        vkWaitForFences(r->e->device, 1, &r->fences[s], VK_TRUE, UINT64_MAX);
        checks_read_slot(c, s, f);
        if (f >= frames)
            continue; /* the last SLOTS turns only wait */
        vkResetFences(r->e->device, 1, &r->fences[s]);
        vkResetCommandBuffer(cmd, 0);
        VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                       .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
        vkBeginCommandBuffer(cmd, &bi);
        /* 2. libroma skins the character; the animation pass reads its positions. */
        roma_animator_output skinned = {0};
        if (r->animator) {
            roma_animator_pose pose = {0, (float)f / 30.0f};
            if (roma_animator_record(r->animator, cmd, s, &pose, &skinned) != ROMA_SUCCESS)
                return 0;
            memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_WRITE_BIT,
                           VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT);
        }
        /* 3. The engine's animation pass places the character and moves the box. */
        record_animation(r, cmd, f, skinned.positions);
        /* 4. libroma's build from those positions. */
        roma_map_frame_desc fd = {.frame = f, .seed = 1, .jitter_grid = 1, .jitter_directions = 1, .slot = s,
                                  .volume = &scene_volume, .gpu_positions = r->positions.address,
                                  .vertex_count = r->vertex_count};
        if (roma_map_record_build(r->map, cmd, &fd, NULL) != ROMA_SUCCESS)
            return 0;
        /* 5. The engine's probe rays, traced through roma/trace.glsl. */
        record_probe_trace(r, cmd, &c->probes[s]);
        /* 6. The floor G-buffer, then libroma's AO on it. */
        record_gbuffer(r, cmd);
        roma_ao_images ai = {.width = GB_W, .height = GB_H, .position = r->gb_position.view,
                             .normal = r->gb_normal.view, .output = r->ao_image.view,
                             .input_layout = VK_IMAGE_LAYOUT_GENERAL};
        roma_ao_settings as = {.samples = 16, .radius = AO_RADIUS, .seed = 1, .frame = f};
        if (roma_ao_effect_record(r->ao, cmd, s, r->map, &ai, &as) != ROMA_SUCCESS)
            return 0;
        /* 7. The AO averaged over frames: this frame writes history[f % 2] and reads the
         *    other, which the previous frame wrote (the camera stands still: the zero matrix). */
        memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        const image *written = &r->history[f % 2], *previous = &r->history[(f + 1) % 2];
        roma_temporal_images ti = {.width = GB_W, .height = GB_H, .current = r->ao_image.view,
                                   .position = r->gb_position.view, .normal = r->gb_normal.view,
                                   .previous_position = r->gb_position.view, .history = previous->view,
                                   .accumulated = written->view, .input_layout = VK_IMAGE_LAYOUT_GENERAL};
        roma_temporal_settings ts = {.reset = f == 0, .frame = f};
        if (roma_temporal_effect_record(r->temporal, cmd, s, &ti, &ts) != ROMA_SUCCESS)
            return 0;
        /* 8. Submit, after the checks' copies of the AO and its average for the host. */
        checks_record(c, cmd, s, f, r->animator ? &skinned.bounds : NULL, r->ao_image.image, written->image);
        vkEndCommandBuffer(cmd);
        VkSubmitInfo submit = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1,
                               .pCommandBuffers = &cmd};
        if (vkQueueSubmit(r->e->queue, 1, &submit, r->fences[s]) != VK_SUCCESS)
            return 0;
    }
    return 1;
}

int main(int argc, char **argv)
{
    uint32_t frames = 12;
    int validation = 0;
    const char *character_path = NULL;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--frames") == 0 && i + 1 < argc)
            frames = (uint32_t)strtoul(argv[++i], NULL, 10);
        else if (strcmp(argv[i], "--validation") == 0)
            validation = 1;
        else if (strcmp(argv[i], "--sync-validation") == 0)
            validation = 2;
        else if (strcmp(argv[i], "--character") == 0 && i + 1 < argc)
            character_path = argv[++i];
        else {
            fprintf(stderr, "usage: example-engine [--frames N] [--validation | --sync-validation] "
                            "[--character file.glb]\n");
            return 2;
        }
    }
    engine e = {0};
    renderer r = {.e = &e};
    checks c = {0};
    roma_device_requirements req;
    int status = 1;
    if (!engine_create(&e, validation, &req) || !create_libroma(&r, &req, character_path))
        goto done;
    if (!create_passes(&r) || !create_slots(&r) || !checks_create(&c, &e, r.ctx, r.map)) {
        fprintf(stderr, "example-engine: setting up the engine's objects failed\n");
        goto done;
    }
    if (run_frames(&r, &c, frames))
        status = checks_report(&c, frames, r.animator != NULL);
done:
    destroy_renderer(&r); /* waits for the device first */
    checks_destroy(&c);
    engine_destroy(&e);
    return status == 0 && e.validation_messages == 0 ? 0 : 1;
}
