/* A fuzzer of API call sequences, written against the installed headers only: an engine's
 * frame loop over 2 or 3 frames in flight (its own command buffers and fences) around one map,
 * with random calls between frames: meshes and instances added and removed while frames are in
 * flight, dynamic instances moved, meshes given new positions on the GPU (a skinned character's:
 * roma_mesh_positions), the scene's own positions moved from the host, builds with
 * and without jitter, a clipping volume, cascade levels, traces recorded after builds, an AO
 * effect recorded on the engine's images, created and dropped mid-run, the images resized
 * between frames, the map destroyed (after waiting for its frames, as the contract asks) and
 * created again with other settings, and calls that must fail (unknown ids, static instances moved, non-finite
 * transforms, slots out of range, unknown modes), each with its documented code and one error
 * message, leaving the map as it was.
 *
 * Checks: every call returns what its header documents; no validation message (synchronization
 * validation on, outside the sanitizer suite); no leak or sanitizer report (make
 * test-sanitize); and at the end of each sequence, the map traces a batch of rays bit for bit
 * as a map created afresh from what the sequence left (the same scene positions, meshes,
 * instances and transforms) and built once: whatever the calls did in between, nothing stale
 * remains in the map.
 *
 *   fuzz_calls [--seconds S] [--seed S] [--sequence N]
 * runs sequences of seed S until S seconds have passed (default 30: ctest's slice), or
 * sequence N alone. */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "roma/ao_effect.h"
#include "roma/context.h"
#include "roma/map.h"
#include "roma/scene.h"
#include "gpu_images.h"
#include "fuzz_random.h"
#include "harness.h"

#define MAX_SLOTS 3
#define MAX_MESHES 8
#define MAX_INSTANCES 24
#define STEPS 40
#define RAYS 512



/* The base scene: a floor (y = 0, [0, 4]^2) and a box whose x the host moves. */
#define BASE_VERTICES 12
#define BASE_TRIANGLES 14
static const uint32_t base_indices[3 * BASE_TRIANGLES] = {
    0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7, 8, 10, 9, 8, 11, 10, 4, 8, 9, 4, 9, 5, 7, 6, 10, 7, 10, 11,
    4, 7, 11, 4, 11, 8, 5, 9, 10, 5, 10, 6};

static void base_pose(float box_x, float out[3 * BASE_VERTICES])
{
    const float floor[12] = {0, 0, 0, 4, 0, 0, 4, 0, 4, 0, 0, 4};
    memcpy(out, floor, sizeof floor);
    for (int v = 0; v < 8; ++v) {
        float *p = out + 12 + 3 * v;
        const int corner = v % 4;
        p[0] = box_x + (corner == 1 || corner == 2 ? 0.5f : 0.0f);
        p[1] = corner >= 2 ? 1.0f : 0.3f;
        p[2] = v < 4 ? 1.5f : 2.0f;
    }
}

static roma_scene *scene_from(const float *positions, uint32_t vertices, const uint32_t *indices, uint32_t triangles,
                              roma_logger logger)
{
    roma_scene *scene = NULL;
    roma_scene_desc d = {.positions = positions, .vertex_count = vertices, .indices = indices,
                         .triangle_count = triangles, .logger = logger};
    CHECK_RESULT(roma_scene_create(&d, &scene), ROMA_SUCCESS);
    return scene;
}

/* A small random mesh in [0, 1]^3: a tetrahedron's faces, or a quad; p: its 4 positions. */
static const uint32_t tetra[12] = {0, 1, 2, 0, 3, 1, 1, 3, 2, 2, 3, 0};
static roma_scene *mesh_random(rng *r, roma_logger logger, float p[12], uint32_t *triangles)
{
    for (int i = 0; i < 12; ++i)
        p[i] = unit(r);
    *triangles = below(r, 2) ? 4u : 2u;
    return scene_from(p, 4, tetra, *triangles, logger);
}

static void transform_random(rng *r, float t[12])
{
    const float angle = 6.2831853f * unit(r), s = 0.3f + unit(r), c = cosf(angle), n = sinf(angle);
    const float m[12] = {c * s, 0, n * s, 3.5f * unit(r), 0, s, 0, 1.5f * unit(r), -n * s, 0, c * s, 3.5f * unit(r)};
    memcpy(t, m, sizeof m);
}

typedef struct mesh_slot {
    int live;
    uint32_t id, triangles;
    float p[12];       /* its 4 positions now (the last given on the GPU) */
    roma_scene *scene; /* of those positions, kept for the fresh map at the end */
} mesh_slot;

typedef struct instance_slot {
    int live;
    uint32_t id, mesh; /* mesh: index into the meshes */
    roma_instance_desc desc;
} instance_slot;

typedef struct engine {
    roma_context *ctx;
    VkDevice dev;
    VkCommandPool pool;
    VkCommandBuffer cmds[MAX_SLOTS];
    VkFence fences[MAX_SLOTS];
    roma_test_host_buffer rays[MAX_SLOTS], hits[MAX_SLOTS];
    roma_test_host_buffer poses[MAX_SLOTS]; /* meshes' positions written "on the GPU": 64 bytes a mesh */
    roma_test_log log;
    uint64_t frames, ao_records, resizes, maps_replaced, bad_calls, mesh_poses; /* what the sequences did */
} engine;

typedef struct sequence {
    rng r;
    uint32_t slots, frame, resolution, angular, cascades;
    roma_map *map;
    roma_scene *base;
    float positions[3 * BASE_VERTICES];
    int use_volume, jitter;
    roma_box volume;
    mesh_slot meshes[MAX_MESHES];
    instance_slot instances[MAX_INSTANCES];
    /* The AO effect and the engine's G-buffer images it reads (position, normal) and writes. */
    roma_ao_effect *ao;
    roma_test_image gbuffer[2], ao_out;
    uint32_t width, height; /* 0: no images */
    int images_fresh;       /* created since the last frame: cleared and laid out by the next */
    uint32_t calls, expected_errors, frames;
} sequence;

/* Whether a live static instance uses mesh slot m (its positions must not change then). */
static int has_static_instance(const sequence *q, uint32_t m)
{
    for (uint32_t i = 0; i < MAX_INSTANCES; ++i)
        if (q->instances[i].live && q->instances[i].mesh == m && !(q->instances[i].desc.flags & ROMA_INSTANCE_DYNAMIC))
            return 1;
    return 0;
}

static void wait_all(engine *e, uint32_t slots)
{
    CHECK(vkWaitForFences(e->dev, slots, e->fences, VK_TRUE, UINT64_MAX) == VK_SUCCESS);
}

static roma_map_frame_desc frame_desc(const sequence *q, uint32_t slot, const float *positions)
{
    roma_map_frame_desc fd = {.frame = q->frame, .seed = 5, .jitter_grid = q->jitter, .jitter_directions = q->jitter,
                              .slot = slot, .volume = q->use_volume ? &q->volume : NULL};
    if (positions) {
        fd.positions = positions;
        fd.vertex_count = BASE_VERTICES;
    }
    return fd;
}

/* A new map with the sequence's settings, holding its live meshes and instances (their ids
 * rewritten); the base scene at its current positions. */
static roma_map *map_rebuild(engine *e, sequence *q, roma_logger logger)
{
    roma_map *map = NULL;
    roma_map_desc md = {.resolution = q->resolution, .angular = q->angular, .frames_in_flight = q->slots,
                        .cascades = q->cascades, .logger = logger};
    CHECK_RESULT(roma_map_create(e->ctx, &md, q->base, &map), ROMA_SUCCESS);
    if (!map)
        return NULL;
    for (uint32_t m = 0; m < MAX_MESHES; ++m)
        if (q->meshes[m].live)
            CHECK_RESULT(roma_map_add_mesh(map, q->meshes[m].scene, &q->meshes[m].id), ROMA_SUCCESS);
    for (uint32_t i = 0; i < MAX_INSTANCES; ++i)
        if (q->instances[i].live) {
            q->instances[i].desc.mesh = q->meshes[q->instances[i].mesh].id;
            CHECK_RESULT(roma_map_add_instance(map, &q->instances[i].desc, &q->instances[i].id), ROMA_SUCCESS);
        }
    return map;
}

/* The engine's images at a new random size (after waiting for every frame that used them). */
static void images_resize(engine *e, sequence *q)
{
    wait_all(e, q->slots);
    for (int i = 0; i < 2; ++i)
        roma_test_image_destroy(e->dev, &q->gbuffer[i]);
    roma_test_image_destroy(e->dev, &q->ao_out);
    q->width = 8u + below(&q->r, 57);
    q->height = 8u + below(&q->r, 41);
    for (int i = 0; i < 2; ++i)
        roma_test_image_create(e->ctx, q->width, q->height, VK_FORMAT_R32G32B32A32_SFLOAT,
                               VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, &q->gbuffer[i]);
    roma_test_image_create(e->ctx, q->width, q->height, VK_FORMAT_R32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT,
                           &q->ao_out);
    q->images_fresh = 1;
    ++e->resizes;
}

/* New images: the G-buffer cleared to one surface point (on the floor, facing up) and laid out
 * for sampling, the output for storage writes. */
static void images_prepare(VkCommandBuffer cmd, sequence *q)
{
    const VkClearColorValue values[2] = {{.float32 = {2.0f, 0.01f, 2.0f, 1.0f}}, {.float32 = {0.0f, 1.0f, 0.0f, 0.0f}}};
    const VkImageSubresourceRange all = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    for (int i = 0; i < 2; ++i) {
        roma_test_layout_barrier(cmd, q->gbuffer[i].image, VK_IMAGE_LAYOUT_UNDEFINED,
                                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                                 VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        vkCmdClearColorImage(cmd, q->gbuffer[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &values[i], 1, &all);
        roma_test_layout_barrier(cmd, q->gbuffer[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                                 VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    }
    roma_test_layout_barrier(cmd, q->ao_out.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                             VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                             VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    q->images_fresh = 0;
}

/* One frame in slot s: wait for it, record a build (new host positions sometimes), a trace and
 * the AO effect where there is one, submit with the slot's fence. */
static void frame(engine *e, sequence *q)
{
    const uint32_t s = q->frame % q->slots;
    CHECK(vkWaitForFences(e->dev, 1, &e->fences[s], VK_TRUE, UINT64_MAX) == VK_SUCCESS);
    const int move = below(&q->r, 2);
    if (move)
        base_pose(3.0f * unit(&q->r), q->positions);
    roma_map_frame_desc fd = frame_desc(q, s, move ? q->positions : NULL);
    const float focus[3] = {4.0f * unit(&q->r), 0.5f, 4.0f * unit(&q->r)};
    if (q->cascades > 1)
        fd.focus = focus;
    roma_ray *rays = e->rays[s].mapped;
    for (uint32_t i = 0; i < RAYS; ++i)
        rays[i] = (roma_ray){{4.0f * unit(&q->r), 0.05f + 1.5f * unit(&q->r), 4.0f * unit(&q->r)}, 0.0f,
                             {unit(&q->r) - 0.5f, unit(&q->r) - 0.5f, unit(&q->r) - 0.5f}, INFINITY};
    /* Meshes without static instances bent to new positions, written where the GPU reads them
     * (this slot's buffer: its last frame is done), 3 floats at a stride of 12 or 16 bytes. */
    roma_mesh_positions posed[MAX_MESHES];
    uint32_t posed_count = 0;
    for (uint32_t m = 0; m < MAX_MESHES && below(&q->r, 2); ++m) {
        mesh_slot *ms = &q->meshes[m];
        if (!ms->live || has_static_instance(q, m) || below(&q->r, 2))
            continue;
        const uint32_t stride = below(&q->r, 2) ? 12u : 16u;
        float next[12];
        roma_box box = {{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
        for (int v = 0; v < 4; ++v)
            for (int a = 0; a < 3; ++a) {
                next[3 * v + a] = ms->p[3 * v + a] + 0.2f * (unit(&q->r) - 0.5f);
                box.min[a] = fminf(box.min[a], next[3 * v + a]);
                box.max[a] = fmaxf(box.max[a], next[3 * v + a]);
            }
        roma_scene *scene = scene_from(next, 4, tetra, ms->triangles, (roma_logger){0});
        if (!scene)
            continue;
        for (int v = 0; v < 4; ++v)
            memcpy((char *)e->poses[s].mapped + 64u * m + stride * (uint32_t)v, next + 3 * v, 12);
        posed[posed_count++] = (roma_mesh_positions){.mesh = ms->id, .gpu_positions = e->poses[s].address + 64u * m,
                                                     .gpu_position_stride = stride, .bounds = box};
        memcpy(ms->p, next, sizeof next);
        roma_scene_destroy(ms->scene); /* the map keeps no pointer to it */
        ms->scene = scene;
        ++e->mesh_poses;
    }
    fd.mesh_positions = posed_count ? posed : NULL;
    fd.mesh_position_count = posed_count;
    CHECK(vkResetFences(e->dev, 1, &e->fences[s]) == VK_SUCCESS);
    CHECK(vkResetCommandBuffer(e->cmds[s], 0) == VK_SUCCESS);
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                   .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    CHECK(vkBeginCommandBuffer(e->cmds[s], &bi) == VK_SUCCESS);
    if (q->images_fresh)
        images_prepare(e->cmds[s], q);
    CHECK_RESULT(roma_map_record_build(q->map, e->cmds[s], &fd, NULL), ROMA_SUCCESS);
    roma_trace_desc td = {.mode = (roma_trace_mode)below(&q->r, 4), .max_steps = 8, .rays = e->rays[s].address,
                          .hits = e->hits[s].address, .ray_count = RAYS};
    CHECK_RESULT(roma_map_record_trace(q->map, e->cmds[s], &td, NULL), ROMA_SUCCESS);
    if (q->ao && q->width) {
        /* The engine's order: the last frame's writes of the output (an earlier submission)
         * before this frame's. */
        VkMemoryBarrier2 mb = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
                               .srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                               .srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                               .dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                               .dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_SHADER_READ_BIT};
        VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1,
                                .pMemoryBarriers = &mb};
        vkCmdPipelineBarrier2(e->cmds[s], &dep);
        roma_ao_images images = {.width = q->width, .height = q->height, .position = q->gbuffer[0].view,
                                 .normal = q->gbuffer[1].view, .output = q->ao_out.view};
        roma_ao_settings settings = {.samples = 1u + below(&q->r, 8), .radius = below(&q->r, 2) ? 0.5f : 0.0f,
                                     .seed = q->frame};
        CHECK_RESULT(roma_ao_effect_record(q->ao, e->cmds[s], s, q->map, &images, &settings), ROMA_SUCCESS);
        ++e->ao_records;
    }
    CHECK(vkEndCommandBuffer(e->cmds[s]) == VK_SUCCESS);
    VkSubmitInfo submit = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1,
                           .pCommandBuffers = &e->cmds[s]};
    CHECK(vkQueueSubmit(roma_context_queue(e->ctx), 1, &submit, e->fences[s]) == VK_SUCCESS);
    ++q->frame;
    ++q->frames;
    ++e->frames;
}

/* A call that must fail with `want` and one error message, leaving the map as it was. */
static void expect_error(engine *e, sequence *q, roma_result got, roma_result want, const char *what)
{
    if (got != want) {
        fprintf(stderr, "%s: %s, expected %s\n", what, roma_result_string(got), roma_result_string(want));
        ++roma_test_failures;
    }
    ++q->expected_errors;
    (void)e;
}

static void bad_call(engine *e, sequence *q)
{
    ++e->bad_calls;
    const float finite[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    float bad[12];
    memcpy(bad, finite, sizeof bad);
    bad[below(&q->r, 12)] = below(&q->r, 2) ? NAN : INFINITY;
    uint32_t out = 0;
    switch (below(&q->r, 7)) {
    case 6: { /* new positions for a mesh with a static instance, or for an unknown mesh */
        roma_map_frame_desc fd = frame_desc(q, 0, NULL);
        roma_mesh_positions given = {.mesh = 100000u, .gpu_positions = e->poses[0].address,
                                     .bounds = {{0, 0, 0}, {1, 1, 1}}};
        for (uint32_t m = 0; m < MAX_MESHES; ++m)
            if (q->meshes[m].live && has_static_instance(q, m))
                given.mesh = q->meshes[m].id;
        fd.mesh_positions = &given;
        fd.mesh_position_count = 1;
        expect_error(e, q, roma_map_record_build(q->map, e->cmds[0], &fd, NULL), ROMA_ERROR_INVALID_ARGUMENT,
                     given.mesh == 100000u ? "positions of an unknown mesh" : "positions of a mesh with a static instance");
        break;
    }
    case 0:
        expect_error(e, q, roma_map_remove_instance(q->map, 100000u + below(&q->r, 1000)),
                     ROMA_ERROR_INVALID_ARGUMENT, "remove an unknown instance");
        break;
    case 1:
        expect_error(e, q, roma_map_remove_mesh(q->map, 100000u), ROMA_ERROR_INVALID_ARGUMENT,
                     "remove an unknown mesh");
        break;
    case 2: {
        roma_instance_desc d = {.mesh = 100000u};
        expect_error(e, q, roma_map_add_instance(q->map, &d, &out), ROMA_ERROR_INVALID_ARGUMENT,
                     "an instance of an unknown mesh");
        CHECK(out == UINT32_MAX);
        break;
    }
    case 3: { /* a non-finite transform on a live dynamic instance, or a static one moved */
        for (uint32_t i = 0; i < MAX_INSTANCES; ++i)
            if (q->instances[i].live) {
                const int dynamic = (q->instances[i].desc.flags & ROMA_INSTANCE_DYNAMIC) != 0;
                expect_error(e, q, roma_map_set_instance_transform(q->map, q->instances[i].id, dynamic ? bad : finite),
                             ROMA_ERROR_INVALID_ARGUMENT, dynamic ? "a non-finite transform" : "a static instance moved");
                return;
            }
        expect_error(e, q, roma_map_set_instance_transform(q->map, 100000u, finite), ROMA_ERROR_INVALID_ARGUMENT,
                     "move an unknown instance");
        break;
    }
    case 4: { /* a slot out of range, recorded into no command buffer of ours */
        roma_map_frame_desc fd = frame_desc(q, q->slots + below(&q->r, 3), NULL);
        expect_error(e, q, roma_map_record_build(q->map, e->cmds[0], &fd, NULL), ROMA_ERROR_INVALID_ARGUMENT,
                     "a frame slot out of range");
        break;
    }
    default: { /* a mesh with instances left cannot go */
        for (uint32_t i = 0; i < MAX_INSTANCES; ++i)
            if (q->instances[i].live) {
                expect_error(e, q, roma_map_remove_mesh(q->map, q->meshes[q->instances[i].mesh].id),
                             ROMA_ERROR_INVALID_ARGUMENT, "remove a mesh with instances");
                return;
            }
        roma_ray ray = {{1, 1, 1}, 0, {0, 1, 0}, 1};
        roma_hit hit;
        expect_error(e, q, roma_map_trace(q->map, (roma_trace_mode)7, 8, &ray, 1, &hit, NULL),
                     ROMA_ERROR_INVALID_ARGUMENT, "an unknown trace mode");
    }
    }
}

static void step(engine *e, sequence *q, roma_logger logger)
{
    ++q->calls;
    switch (below(&q->r, 14)) {
    case 12: /* create the AO effect, or drop it (after waiting for the frames that used it) */
        if (!q->ao) {
            CHECK_RESULT(roma_ao_effect_create(e->ctx, &(roma_ao_effect_desc){.frames_in_flight = q->slots}, &q->ao),
                         ROMA_SUCCESS);
        } else {
            wait_all(e, q->slots);
            roma_ao_effect_destroy(q->ao);
            q->ao = NULL;
        }
        break;
    case 13: /* the engine's images resized between frames */
        images_resize(e, q);
        break;
    case 0: case 1: case 2: case 3:
        frame(e, q);
        break;
    case 4: { /* add a mesh */
        for (uint32_t m = 0; m < MAX_MESHES; ++m)
            if (!q->meshes[m].live) {
                roma_scene *mesh = mesh_random(&q->r, logger, q->meshes[m].p, &q->meshes[m].triangles);
                if (mesh && roma_map_add_mesh(q->map, mesh, &q->meshes[m].id) == ROMA_SUCCESS) {
                    q->meshes[m].live = 1;
                    q->meshes[m].scene = mesh;
                } else {
                    CHECK(!"roma_map_add_mesh failed");
                    roma_scene_destroy(mesh);
                }
                break;
            }
        break;
    }
    case 5: { /* remove a mesh without instances */
        const uint32_t m = below(&q->r, MAX_MESHES);
        int used = 0;
        for (uint32_t i = 0; i < MAX_INSTANCES; ++i)
            used |= q->instances[i].live && q->instances[i].mesh == m;
        if (q->meshes[m].live && !used) {
            CHECK_RESULT(roma_map_remove_mesh(q->map, q->meshes[m].id), ROMA_SUCCESS);
            roma_scene_destroy(q->meshes[m].scene);
            memset(&q->meshes[m], 0, sizeof q->meshes[m]);
        }
        break;
    }
    case 6: case 7: { /* add an instance of a live mesh */
        const uint32_t m = below(&q->r, MAX_MESHES);
        for (uint32_t i = 0; q->meshes[m].live && i < MAX_INSTANCES; ++i)
            if (!q->instances[i].live) {
                instance_slot *in = &q->instances[i];
                in->desc = (roma_instance_desc){.mesh = q->meshes[m].id,
                                                .flags = below(&q->r, 2) ? ROMA_INSTANCE_DYNAMIC : 0u};
                transform_random(&q->r, in->desc.transform);
                in->mesh = m;
                CHECK_RESULT(roma_map_add_instance(q->map, &in->desc, &in->id), ROMA_SUCCESS);
                in->live = 1;
                break;
            }
        break;
    }
    case 8: { /* remove an instance */
        instance_slot *in = &q->instances[below(&q->r, MAX_INSTANCES)];
        if (in->live) {
            CHECK_RESULT(roma_map_remove_instance(q->map, in->id), ROMA_SUCCESS);
            in->live = 0;
        }
        break;
    }
    case 9: { /* move a dynamic instance */
        instance_slot *in = &q->instances[below(&q->r, MAX_INSTANCES)];
        if (in->live && (in->desc.flags & ROMA_INSTANCE_DYNAMIC)) {
            transform_random(&q->r, in->desc.transform);
            CHECK_RESULT(roma_map_set_instance_transform(q->map, in->id, in->desc.transform), ROMA_SUCCESS);
        }
        break;
    }
    case 10:
        bad_call(e, q);
        break;
    default: /* destroy the map with frames pending (after waiting for them) and make another */
        if (below(&q->r, 3) == 0) {
            wait_all(e, q->slots);
            ++e->maps_replaced;
            roma_map_destroy(q->map);
            q->resolution = below(&q->r, 2) ? 32u : 64u;
            q->angular = 1u + below(&q->r, 3);
            q->cascades = below(&q->r, 3) == 0 ? 2u : 1u;
            q->map = map_rebuild(e, q, logger);
            if (q->map)
                frame(e, q);
        } else {
            q->jitter = (int)below(&q->r, 2);
            q->use_volume = below(&q->r, 4) == 0;
        }
    }
}

/* The final state: the fuzzed map and a fresh one, both built with the same frame and traced
 * by roma_map_trace: hits equal bit for bit. Returns the mismatches. */
static uint32_t compare_with_fresh(engine *e, sequence *q, roma_logger logger)
{
    wait_all(e, q->slots);
    static roma_ray rays[RAYS];
    static roma_hit a[RAYS], b[RAYS];
    for (uint32_t i = 0; i < RAYS; ++i)
        rays[i] = (roma_ray){{4.0f * unit(&q->r), 0.05f + 1.5f * unit(&q->r), 4.0f * unit(&q->r)}, 0.0f,
                             {unit(&q->r) - 0.5f, unit(&q->r) - 0.5f, unit(&q->r) - 0.5f}, INFINITY};
    const float focus[3] = {2.0f, 0.5f, 2.0f};
    roma_map_frame_desc fd = frame_desc(q, 0, q->positions);
    fd.focus = q->cascades > 1 ? focus : NULL;
    /* The base scene of the fresh map starts from the current positions. */
    roma_scene *was = q->base;
    q->base = scene_from(q->positions, BASE_VERTICES, base_indices, BASE_TRIANGLES, logger);
    roma_map *fresh = map_rebuild(e, q, logger);
    uint32_t mismatches = RAYS;
    if (fresh && roma_map_build(q->map, &fd, NULL) == ROMA_SUCCESS && roma_map_build(fresh, &fd, NULL) == ROMA_SUCCESS) {
        mismatches = 0;
        for (int m = 0; m < 4; ++m) {
            CHECK_RESULT(roma_map_trace(q->map, (roma_trace_mode)m, 8, rays, RAYS, a, NULL), ROMA_SUCCESS);
            CHECK_RESULT(roma_map_trace(fresh, (roma_trace_mode)m, 8, rays, RAYS, b, NULL), ROMA_SUCCESS);
            for (uint32_t i = 0; i < RAYS; ++i)
                mismatches += a[i].info != b[i].info || memcmp(&a[i].t, &b[i].t, sizeof a[i].t) != 0;
        }
    }
    roma_map_destroy(fresh);
    roma_scene_destroy(was);
    return mismatches;
}

/* One sequence; returns 1 when its end state matched a fresh map. */
static int run_sequence(engine *e, uint64_t seed, uint64_t index)
{
    sequence q;
    memset(&q, 0, sizeof q);
    q.r = rng_of(seed, index);
    q.slots = 2u + below(&q.r, 2);
    q.resolution = below(&q.r, 2) ? 32u : 64u;
    q.angular = 1u + below(&q.r, 3);
    q.cascades = below(&q.r, 3) == 0 ? 2u : 1u;
    q.volume = (roma_box){{0.5f, -0.1f, 0.5f}, {3.5f, 1.2f, 3.5f}};
    base_pose(1.0f, q.positions);
    const int errors_before = e->log.errors;
    roma_logger logger = {0};
    q.base = scene_from(q.positions, BASE_VERTICES, base_indices, BASE_TRIANGLES, logger);
    q.map = map_rebuild(e, &q, logger);
    if (!q.map)
        return 0;
    frame(e, &q); /* a map is built before anything else traces it */
    for (uint32_t s = 0; s < STEPS; ++s)
        step(e, &q, logger);
    const uint32_t mismatches = compare_with_fresh(e, &q, logger);
    /* Every deliberate error logged one message on the context's logger; nothing else did. */
    const int errors = e->log.errors - errors_before;
    if (mismatches || errors != (int)q.expected_errors) {
        fprintf(stderr, "sequence %" PRIu64 " of seed %" PRIu64 " (%u slots, RES %u, A %u, %u levels): %u of %u hits "
                "differ from a fresh map; %d error messages for %u deliberate errors; reproduce: fuzz_calls --seed %"
                PRIu64 " --sequence %" PRIu64 "\n", index, seed, q.slots, q.resolution, q.angular, q.cascades,
                mismatches, 4 * RAYS, errors, q.expected_errors, seed, index);
        ++roma_test_failures;
    }
    wait_all(e, q.slots);
    roma_ao_effect_destroy(q.ao);
    for (int i = 0; i < 2; ++i)
        roma_test_image_destroy(e->dev, &q.gbuffer[i]);
    roma_test_image_destroy(e->dev, &q.ao_out);
    roma_map_destroy(q.map);
    roma_scene_destroy(q.base);
    for (uint32_t m = 0; m < MAX_MESHES; ++m)
        roma_scene_destroy(q.meshes[m].scene);
    return mismatches == 0;
}

int main(int argc, char **argv)
{
    double seconds = 30.0;
    uint64_t seed = 1, only = UINT64_MAX;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--seconds"))
            seconds = atof(argv[i + 1]);
        else if (!strcmp(argv[i], "--seed"))
            seed = strtoull(argv[i + 1], NULL, 10);
        else if (!strcmp(argv[i], "--sequence"))
            only = strtoull(argv[i + 1], NULL, 10);
        else {
            fprintf(stderr, "fuzz_calls: unknown option %s\n", argv[i]);
            return 2;
        }
    }
    engine e;
    memset(&e, 0, sizeof e);
    roma_context_desc cd = {.flags = roma_test_sync_validation_flags(), .logger = roma_test_logger_quiet(&e.log)};
    if (roma_context_create(&cd, &e.ctx) != ROMA_SUCCESS) { /* a failure, not a skip */
        fprintf(stderr, "no Vulkan context with validation layers\n");
        return 1;
    }
    e.dev = roma_context_device(e.ctx);
    VkCommandPoolCreateInfo pool_info = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                         .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                         .queueFamilyIndex = roma_context_queue_family(e.ctx)};
    CHECK(vkCreateCommandPool(e.dev, &pool_info, NULL, &e.pool) == VK_SUCCESS);
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = e.pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = MAX_SLOTS};
    CHECK(vkAllocateCommandBuffers(e.dev, &ai, e.cmds) == VK_SUCCESS);
    for (int s = 0; s < MAX_SLOTS; ++s) {
        VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, .flags = VK_FENCE_CREATE_SIGNALED_BIT};
        CHECK(vkCreateFence(e.dev, &fi, NULL, &e.fences[s]) == VK_SUCCESS);
        roma_test_host_buffer_create(e.ctx, sizeof(roma_ray) * RAYS, &e.rays[s]);
        roma_test_host_buffer_create(e.ctx, sizeof(roma_hit) * RAYS, &e.hits[s]);
        roma_test_host_buffer_create(e.ctx, 64u * MAX_MESHES, &e.poses[s]);
    }
    uint64_t sequences = 0, matched = 0;
    const double start = now_seconds();
    if (!roma_test_failures) {
        if (only != UINT64_MAX) {
            matched += (uint64_t)run_sequence(&e, seed, only);
            sequences = 1;
        } else {
            for (uint64_t i = 0; now_seconds() - start < seconds; ++i, ++sequences)
                matched += (uint64_t)run_sequence(&e, seed, i);
        }
    }
    vkDeviceWaitIdle(e.dev);
    for (int s = 0; s < MAX_SLOTS; ++s) {
        vkDestroyFence(e.dev, e.fences[s], NULL);
        roma_test_host_buffer_destroy(e.dev, &e.rays[s]);
        roma_test_host_buffer_destroy(e.dev, &e.hits[s]);
        roma_test_host_buffer_destroy(e.dev, &e.poses[s]);
    }
    vkDestroyCommandPool(e.dev, e.pool, NULL);
    const uint32_t validation = roma_context_validation_error_count(e.ctx);
    printf("fuzz_calls seed %" PRIu64 ": %.1f s, %" PRIu64 " sequences of %u calls (%" PRIu64 " frames, %" PRIu64
           " AO records, %" PRIu64 " image resizes, %" PRIu64 " maps replaced, %" PRIu64 " meshes posed, %" PRIu64
           " calls that must fail), %" PRIu64 " ended equal to a fresh map; %u validation messages\n", seed,
           now_seconds() - start, sequences, STEPS, e.frames, e.ao_records, e.resizes, e.maps_replaced, e.mesh_poses,
           e.bad_calls, matched, validation);
    CHECK(sequences > 0 && matched == sequences && validation == 0);
    CHECK(e.frames > 0 && e.ao_records > 0 && e.resizes > 0 && e.maps_replaced > 0 && e.mesh_poses > 0 &&
          e.bad_calls > 0);
    roma_context_destroy(e.ctx);
    return roma_test_finish("fuzz_calls");
}
