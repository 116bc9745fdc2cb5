/* An engine's frame loop around one map, written against the installed headers only
 * (this target has no src/ on its include path): two frame slots with their own
 * command buffers and fences, a box that moves every frame, positions from the host
 * on even frames and from the engine's GPU memory (by address, with a stride) on odd
 * ones, a batch trace recorded after each build, results read a frame later.
 * Synchronization validation is on. Checks:
 *  - the per-frame path submits and waits nothing (roma_context_info counters);
 *  - every frame's hits follow that frame's pose, not the pose of the frame in flight
 *    beside it;
 *  - a traced volume that leaves the box out does not see it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "roma/context.h"
#include "roma/map.h"
#include "roma/scene.h"
#include "gpu_images.h"
#include "harness.h"

#define SLOTS 2
#define FRAMES 12
#define RAYS 17
#define GPU_STRIDE 20 /* bytes: three floats and two of padding, as an engine's vertex may have */

/* A floor (y = 0, [-1, 1]^2) and a closed box, a rigid object that moves: 0.4 wide (x),
 * 0.4 tall (y in [0.2, 0.6]), 0.2 deep (z in [-0.1, 0.1]), centred on x = box_x. */
#define VERTICES 12
#define TRIANGLES 14
static const uint32_t indices[3 * TRIANGLES] = {
    0, 1, 2, 0, 2, 3,                                          /* floor */
    4, 5, 6, 4, 6, 7, 8, 10, 9, 8, 11, 10,                     /* box: z = -0.1, z = 0.1 */
    4, 8, 9, 4, 9, 5, 7, 6, 10, 7, 10, 11,                     /* y = 0.2, y = 0.6 */
    4, 7, 11, 4, 11, 8, 5, 9, 10, 5, 10, 6};                   /* x = -0.2, x = 0.2 */

static void pose(float box_x, float out[3 * VERTICES])
{
    const float floor[12] = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
    memcpy(out, floor, sizeof floor);
    for (int v = 0; v < 8; ++v) {
        float *p = out + 12 + 3 * v;
        int corner = v % 4;
        p[0] = box_x + (corner == 1 || corner == 2 ? 0.2f : -0.2f);
        p[1] = corner >= 2 ? 0.6f : 0.2f;
        p[2] = v < 4 ? -0.1f : 0.1f;
    }
}

static float box_x_of(uint32_t frame)
{
    return -0.6f + 0.3f * (float)(frame % 5);
}

/* Rays along +z at height 0.4 from z = -0.8, at x from -0.96 to 0.96. */
static void make_rays(roma_ray *rays)
{
    for (int i = 0; i < RAYS; ++i)
        rays[i] = (roma_ray){{-0.96f + 0.12f * (float)i, 0.4f, -0.8f}, 0.0f, {0.0f, 0.0f, 1.0f}, 1.6f};
}

/* Hits on the box (its front face at t = 0.7, or its back face at 0.9 where the walk
 * stepped over the front one, ROMA's one approximation here) where the box is, misses
 * where it is not; rays within two trace cells (the longest edge of a rotated cell) of its
 * sides are not judged. Returns the
 * number of wrong answers. */
static int judge(const roma_ray *rays, const roma_hit *hits, float box_x, float cell, int box_traced)
{
    int wrong = 0;
    for (int i = 0; i < RAYS; ++i) {
        float dx = fabsf(rays[i].origin[0] - box_x);
        int hit = (hits[i].info & ROMA_HIT_FLAG) != 0;
        if (!box_traced || dx > 0.2f + 2.0f * cell)
            wrong += hit;
        else if (dx < 0.2f - 2.0f * cell)
            wrong += !hit || hits[i].t < 0.7f - 3.0f * cell || hits[i].t > 0.9f + 3.0f * cell;
        if (getenv("ROMA_TEST_VERBOSE"))
            printf("  ray x %.2f: %s t %.4f (box at %.2f, cell %.4f)\n", (double)rays[i].origin[0],
                   hit ? "hit" : "miss", (double)hits[i].t, (double)box_x, (double)cell);
    }
    return wrong;
}

int main(void)
{
    roma_test_log log = {0};
    roma_context_desc cd = {.flags = roma_test_sync_validation_flags(), .logger = roma_test_logger(&log)};
    roma_context *ctx = NULL;
    if (roma_context_create(&cd, &ctx) != ROMA_SUCCESS) { /* a failure, not a skip: CI has the device */
        fprintf(stderr, "no Vulkan context with validation layers\n");
        return 1;
    }
    VkDevice dev = roma_context_device(ctx);

    float rest[3 * VERTICES];
    pose(box_x_of(0), rest);
    roma_material grey = {.base_color = {0.5f, 0.5f, 0.5f}};
    uint32_t tri_mat[TRIANGLES] = {0};
    roma_scene_desc sd = {.positions = rest, .vertex_count = VERTICES, .indices = indices, .triangle_count = TRIANGLES,
                          .triangle_materials = tri_mat, .materials = &grey, .material_count = 1,
                          .logger = roma_test_logger(&log)};
    roma_scene *scene = NULL;
    CHECK_RESULT(roma_scene_create(&sd, &scene), ROMA_SUCCESS);
    roma_map *map = NULL;
    roma_map_desc md = {.resolution = 64, .angular = 2, .frames_in_flight = SLOTS};
    CHECK_RESULT(roma_map_create(ctx, &md, scene, &map), ROMA_SUCCESS);

    /* The engine's per-slot objects. */
    VkCommandPoolCreateInfo pool_info = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                         .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                         .queueFamilyIndex = roma_context_queue_family(ctx)};
    VkCommandPool pool = VK_NULL_HANDLE;
    CHECK(vkCreateCommandPool(dev, &pool_info, NULL, &pool) == VK_SUCCESS);
    VkCommandBuffer cmds[SLOTS];
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                      .commandPool = pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                      .commandBufferCount = SLOTS};
    CHECK(vkAllocateCommandBuffers(dev, &ai, cmds) == VK_SUCCESS);
    VkFence fences[SLOTS];
    roma_test_host_buffer rays_buf[SLOTS], hits_buf[SLOTS], verts_buf[SLOTS];
    for (int s = 0; s < SLOTS; ++s) {
        VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, .flags = VK_FENCE_CREATE_SIGNALED_BIT};
        CHECK(vkCreateFence(dev, &fi, NULL, &fences[s]) == VK_SUCCESS);
        roma_test_host_buffer_create(ctx, sizeof(roma_ray) * RAYS, &rays_buf[s]);
        roma_test_host_buffer_create(ctx, sizeof(roma_hit) * RAYS, &hits_buf[s]);
        roma_test_host_buffer_create(ctx, GPU_STRIDE * VERTICES, &verts_buf[s]);
    }
    if (roma_test_failures)
        return roma_test_finish("test_frames_in_flight");

    roma_ray rays[RAYS];
    make_rays(rays);
    roma_map_info info;
    roma_context_info before, after;
    CHECK_RESULT(roma_context_get_info(ctx, &before), ROMA_SUCCESS);
    /* Around the scene for most frames; frame 7 traces only a corner of the floor. */
    const roma_box room = {{-1.0f, -0.1f, -1.0f}, {1.0f, 0.7f, 1.0f}};
    const roma_box corner = {{0.5f, -0.1f, 0.5f}, {1.0f, 0.1f, 1.0f}};
    uint32_t in_flight[SLOTS] = {UINT32_MAX, UINT32_MAX};
    float cells[FRAMES];
    int wrong = 0, judged = 0;
    for (uint32_t f = 0; f < FRAMES + SLOTS; ++f) {
        uint32_t s = f % SLOTS;
        /* The engine's wait for the slot, then the results of the frame it last held. */
        CHECK(vkWaitForFences(dev, 1, &fences[s], VK_TRUE, UINT64_MAX) == VK_SUCCESS);
        if (in_flight[s] != UINT32_MAX) {
            uint32_t g = in_flight[s];
            int w = judge(rays, hits_buf[s].mapped, box_x_of(g), cells[g], g != 7);
            if (w)
                fprintf(stderr, "frame %u (box at x = %.2f): %d wrong answers\n", g, (double)box_x_of(g), w);
            wrong += w;
            ++judged;
            in_flight[s] = UINT32_MAX;
        }
        if (f >= FRAMES)
            continue;
        float p[3 * VERTICES];
        pose(box_x_of(f), p);
        roma_map_frame_desc fd = {.frame = f, .seed = 7, .jitter_grid = 1, .jitter_directions = 1, .slot = s,
                                  .vertex_count = VERTICES};
        if (f % 2 == 0) {
            fd.positions = p;
        } else {
            for (int v = 0; v < VERTICES; ++v)
                memcpy((char *)verts_buf[s].mapped + GPU_STRIDE * v, p + 3 * v, 12);
            fd.gpu_positions = verts_buf[s].address;
            fd.gpu_position_stride = GPU_STRIDE;
            fd.volume = f == 7 ? &corner : &room;
        }
        memcpy(rays_buf[s].mapped, rays, sizeof rays);
        CHECK(vkResetFences(dev, 1, &fences[s]) == VK_SUCCESS);
        CHECK(vkResetCommandBuffer(cmds[s], 0) == VK_SUCCESS);
        VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                       .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
        CHECK(vkBeginCommandBuffer(cmds[s], &bi) == VK_SUCCESS);
        CHECK_RESULT(roma_map_record_build(map, cmds[s], &fd, NULL), ROMA_SUCCESS);
        roma_trace_desc td = {.mode = ROMA_TRACE_UNSNAPPED_CLOSEST, .max_steps = 256, .rays = rays_buf[s].address,
                              .hits = hits_buf[s].address, .ray_count = RAYS};
        CHECK_RESULT(roma_map_record_trace(map, cmds[s], &td, NULL), ROMA_SUCCESS);
        /* The engine's own barrier: shader writes of the hits before its host reads them. */
        VkMemoryBarrier2 mb = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
                               .srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                               .srcAccessMask = VK_ACCESS_2_SHADER_WRITE_BIT,
                               .dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT,
                               .dstAccessMask = VK_ACCESS_2_HOST_READ_BIT};
        VkDependencyInfo dep = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1,
                                .pMemoryBarriers = &mb};
        vkCmdPipelineBarrier2(cmds[s], &dep);
        CHECK(vkEndCommandBuffer(cmds[s]) == VK_SUCCESS);
        CHECK_RESULT(roma_map_get_info(map, &info), ROMA_SUCCESS);
        cells[f] = info.trace_cell;
        VkSubmitInfo submit = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1,
                               .pCommandBuffers = &cmds[s]};
        CHECK(vkQueueSubmit(roma_context_queue(ctx), 1, &submit, fences[s]) == VK_SUCCESS);
        in_flight[s] = f;
    }
    CHECK_RESULT(roma_context_get_info(ctx, &after), ROMA_SUCCESS);
    printf("%d frames judged, %d wrong answers; library submits %llu -> %llu, waits %llu -> %llu\n", judged, wrong,
           (unsigned long long)before.queue_submits, (unsigned long long)after.queue_submits,
           (unsigned long long)before.queue_waits, (unsigned long long)after.queue_waits);
    CHECK(judged == FRAMES && wrong == 0);
    CHECK(after.queue_submits == before.queue_submits && after.queue_waits == before.queue_waits);
    /* The corner frame's grid is a quarter of the room's: the volume was used. */
    CHECK(cells[7] < 0.5f * cells[6]);

    vkDeviceWaitIdle(dev);
    for (int s = 0; s < SLOTS; ++s) {
        vkDestroyFence(dev, fences[s], NULL);
        roma_test_host_buffer_destroy(dev, &rays_buf[s]);
        roma_test_host_buffer_destroy(dev, &hits_buf[s]);
        roma_test_host_buffer_destroy(dev, &verts_buf[s]);
    }
    vkDestroyCommandPool(dev, pool, NULL);
    roma_map_destroy(map);
    roma_scene_destroy(scene);
    CHECK(roma_context_validation_error_count(ctx) == 0 && log.errors == 0);
    roma_context_destroy(ctx);
    return roma_test_finish("test_frames_in_flight");
}
