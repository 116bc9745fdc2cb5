/* Meshes and instances in a roma_map, on the installed headers only: a floor (the map's
 * scene) and instances of one box mesh, static and dynamic.
 *  - vertical rays see each instance where its transform puts it, and the floor elsewhere;
 *  - moving a dynamic instance moves it; a static one refuses a new transform;
 *  - adding and removing instances and meshes; the API calls never submit or wait;
 *  - the BOM of instances equals, bit for bit, the BOM of the same boxes baked into a scene;
 *  - a loop of frames in flight (two slots, synchronization validation) that moves, adds
 *    and removes instances between frames: answers follow, no hazard, nothing freed in use. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "roma/map.h"
#include "roma/scene.h"

static roma_test_log log_;

/* An axis-aligned box [c - h, c + h] appended to pos/idx (8 vertices, 12 triangles). */
static void add_box(float *pos, uint32_t *idx, uint32_t *nv, uint32_t *nt, const float c[3], float h)
{
    static const uint32_t faces[36] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                       2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    for (int k = 0; k < 8; ++k)
        for (int a = 0; a < 3; ++a)
            pos[3 * (*nv + (uint32_t)k) + (uint32_t)a] = c[a] + ((k >> a) & 1 ? h : -h);
    for (int i = 0; i < 36; ++i)
        idx[3 * *nt + (uint32_t)i] = *nv + faces[i];
    *nv += 8, *nt += 12;
}

/* The floor, plus boxes of half-size 0.25 at the given centres. */
static roma_scene *make_scene(const float (*boxes)[3], int box_count, int with_floor)
{
    float pos[3 * (4 + 8 * 4)];
    uint32_t idx[3 * (2 + 12 * 4)], mats[2 + 12 * 4] = {0}, nv = 0, nt = 0;
    if (with_floor) {
        const float floor[12] = {-2, 0, -2, 2, 0, -2, 2, 0, 2, -2, 0, 2};
        const uint32_t fi[6] = {0, 2, 1, 0, 3, 2};
        memcpy(pos, floor, sizeof floor);
        memcpy(idx, fi, sizeof fi);
        nv = 4, nt = 2;
    }
    for (int b = 0; b < box_count; ++b)
        add_box(pos, idx, &nv, &nt, boxes[b], 0.25f);
    roma_material grey = {{0.5f, 0.5f, 0.5f}, {0, 0, 0}};
    roma_scene_desc d = {.positions = pos, .vertex_count = nv, .indices = idx, .triangle_count = nt,
                         .triangle_materials = mats, .materials = &grey, .material_count = 1,
                         .logger = roma_test_logger(&log_)};
    roma_scene *s = NULL;
    CHECK_RESULT(roma_scene_create(&d, &s), ROMA_SUCCESS);
    return s;
}

static void translation(float x, float y, float z, float t[12])
{
    const float m[12] = {1, 0, 0, x, 0, 1, 0, y, 0, 0, 1, z};
    memcpy(t, m, sizeof m);
}

/* Straight down from y = 2 at (x, z): the box top (y = 0.75, t = 1.25) or the floor (t = 2). */
static float down_t(roma_map *map, float x, float z)
{
    roma_ray ray = {{x, 2.0f, z}, 0.0f, {0.0f, -1.0f, 0.0f}, 3.0f};
    roma_hit hit = {0};
    CHECK_RESULT(roma_map_trace(map, ROMA_TRACE_UNSNAPPED_CLOSEST, 256, &ray, 1, &hit, NULL), ROMA_SUCCESS);
    return (hit.info & ROMA_HIT_FLAG) ? hit.t : INFINITY;
}

#define EXPECT_T(map, x, z, want)                                                                       \
    do {                                                                                                \
        roma_map_info i_;                                                                               \
        roma_map_get_info(map, &i_);                                                                    \
        CHECK_NEAR(down_t(map, x, z), want, 3.0 * i_.trace_cell);                                       \
    } while (0)

static uint64_t submits(roma_context *ctx)
{
    roma_context_info ci;
    roma_context_get_info(ctx, &ci);
    return ci.queue_submits + ci.queue_waits;
}

static void test_api(roma_context *ctx, roma_scene *floor, roma_scene *box)
{
    roma_map *map = NULL;
    CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.resolution = 64, .angular = 2}, floor, &map), ROMA_SUCCESS);
    if (!map)
        return;
    uint64_t before = submits(ctx);
    uint32_t mesh, fixed, moving;
    CHECK_RESULT(roma_map_add_mesh(map, box, &mesh), ROMA_SUCCESS);
    roma_instance_desc d = {.mesh = mesh};
    translation(-1.0f, 0.5f, 0.0f, d.transform);
    CHECK_RESULT(roma_map_add_instance(map, &d, &fixed), ROMA_SUCCESS);
    translation(1.0f, 0.5f, 0.0f, d.transform);
    d.flags = ROMA_INSTANCE_DYNAMIC;
    CHECK_RESULT(roma_map_add_instance(map, &d, &moving), ROMA_SUCCESS);
    CHECK(submits(ctx) == before); /* no API call waits */

    roma_map_frame_desc frame = {.frame = 1, .seed = 2, .jitter_directions = 1};
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    EXPECT_T(map, -1.0f, 0.0f, 1.25f);
    EXPECT_T(map, 1.0f, 0.0f, 1.25f);
    EXPECT_T(map, 0.0f, 0.0f, 2.0f);

    /* The dynamic instance moves; the static one refuses. */
    float t[12];
    translation(0.0f, 0.5f, 0.0f, t);
    CHECK_RESULT(roma_map_set_instance_transform(map, moving, t), ROMA_SUCCESS);
    log_ = (roma_test_log){0};
    CHECK_RESULT(roma_map_set_instance_transform(map, fixed, t), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(log_.last_code == ROMA_ERROR_INVALID_ARGUMENT);
    frame.frame = 2;
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    EXPECT_T(map, 1.0f, 0.0f, 2.0f);
    EXPECT_T(map, 0.0f, 0.0f, 1.25f);
    EXPECT_T(map, -1.0f, 0.0f, 1.25f);

    /* All zero is the identity when moving too, as when adding: the box at the origin. */
    static const float zero[12];
    CHECK_RESULT(roma_map_set_instance_transform(map, moving, zero), ROMA_SUCCESS);
    frame.frame = 20;
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    const float at_zero = down_t(map, 0.0f, 0.0f);
    translation(0.0f, 0.0f, 0.0f, t);
    CHECK_RESULT(roma_map_set_instance_transform(map, moving, t), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    const float at_identity = down_t(map, 0.0f, 0.0f);
    printf("a dynamic instance moved by an all-zero transform: hit at %.4f, by the identity %.4f (the floor: 2)\n",
           at_zero, at_identity);
    CHECK(at_zero == at_identity && at_zero < 1.9f);
    translation(0.0f, 0.5f, 0.0f, t);
    CHECK_RESULT(roma_map_set_instance_transform(map, moving, t), ROMA_SUCCESS);

    /* A second instance of the same mesh; then the static one removed. */
    uint32_t third;
    translation(0.0f, 0.5f, 1.0f, d.transform);
    CHECK_RESULT(roma_map_add_instance(map, &d, &third), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_remove_instance(map, fixed), ROMA_SUCCESS);
    frame.frame = 3;
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    EXPECT_T(map, -1.0f, 0.0f, 2.0f);
    EXPECT_T(map, 0.0f, 1.0f, 1.25f);
    EXPECT_T(map, 0.0f, 0.0f, 1.25f);

    /* Bad calls: refused with their code, nothing changed. */
    CHECK_RESULT(roma_map_remove_instance(map, fixed), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_map_remove_mesh(map, mesh), ROMA_ERROR_INVALID_ARGUMENT); /* instances remain */
    d.mesh = 7;
    uint32_t none;
    CHECK_RESULT(roma_map_add_instance(map, &d, &none), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(none == UINT32_MAX);
    d.mesh = mesh;
    d.transform[3] = NAN;
    CHECK_RESULT(roma_map_add_instance(map, &d, &none), ROMA_ERROR_INVALID_ARGUMENT);
    d.transform[3] = 0.0f;
    d.flags = 8;
    CHECK_RESULT(roma_map_add_instance(map, &d, &none), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_map_remove_instance(map, moving), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_remove_instance(map, third), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_remove_mesh(map, mesh), ROMA_SUCCESS);
    frame.frame = 4;
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    EXPECT_T(map, 0.0f, 0.0f, 2.0f);
    roma_map_destroy(map);
}

/* Two boxes as instances, and the same boxes baked into the scene: the same BOM. */
static void test_same_bom(roma_context *ctx, roma_scene *floor, roma_scene *box)
{
    const float centres[2][3] = {{-1.0f, 0.5f, 0.25f}, {0.75f, 0.25f, -0.5f}};
    roma_scene *baked = make_scene(centres, 2, 1);
    roma_map *a = NULL, *b = NULL;
    roma_map_desc md = {.resolution = 64, .angular = 2};
    CHECK_RESULT(roma_map_create(ctx, &md, floor, &a), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_create(ctx, &md, baked, &b), ROMA_SUCCESS);
    if (a && b) {
        uint32_t mesh, id;
        CHECK_RESULT(roma_map_add_mesh(a, box, &mesh), ROMA_SUCCESS);
        for (int i = 0; i < 2; ++i) {
            roma_instance_desc d = {.mesh = mesh, .flags = i ? ROMA_INSTANCE_DYNAMIC : 0u};
            translation(centres[i][0], centres[i][1], centres[i][2], d.transform);
            CHECK_RESULT(roma_map_add_instance(a, &d, &id), ROMA_SUCCESS);
        }
        roma_map_frame_desc frame = {.frame = 5, .seed = 9, .jitter_grid = 1, .jitter_directions = 1};
        CHECK_RESULT(roma_map_build(a, &frame, NULL), ROMA_SUCCESS);
        CHECK_RESULT(roma_map_build(b, &frame, NULL), ROMA_SUCCESS);
        roma_map_info ia, ib;
        roma_map_get_info(a, &ia);
        roma_map_get_info(b, &ib);
        uint64_t words = ia.bom_bytes / 4;
        uint32_t *wa = malloc(ia.bom_bytes), *wb = malloc(ib.bom_bytes);
        CHECK_RESULT(roma_map_download_bom(a, wa, words), ROMA_SUCCESS);
        CHECK_RESULT(roma_map_download_bom(b, wb, words), ROMA_SUCCESS);
        uint64_t differ = 0, set = 0;
        for (uint64_t w = 0; w < words; ++w) {
            differ += (uint64_t)__builtin_popcount(wa[w] ^ wb[w]);
            set += (uint64_t)__builtin_popcount(wa[w]);
        }
        printf("BOM of two instances vs the same boxes baked in: %llu cells set, %llu differ\n",
               (unsigned long long)set, (unsigned long long)differ);
        CHECK(set > 0 && differ == 0);
        CHECK(memcmp(ia.grid_origin, ib.grid_origin, sizeof ia.grid_origin) == 0);
        free(wa), free(wb);
    }
    roma_map_destroy(a);
    roma_map_destroy(b);
    roma_scene_destroy(baked);
}

/* Frames in flight: the engine's loop with two slots; between frames the dynamic box
 * moves along x, frame 3 adds an instance at z = 1 and frame 5 removes it. */
static void test_frames(roma_context *ctx, roma_scene *floor, roma_scene *box)
{
    enum { SLOTS = 2, FRAMES = 8 };
    roma_map *map = NULL;
    CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.resolution = 64, .angular = 2, .frames_in_flight = SLOTS},
                                 floor, &map),
                 ROMA_SUCCESS);
    if (!map)
        return;
    VkDevice dev = roma_context_device(ctx);
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                  .queueFamilyIndex = roma_context_queue_family(ctx)};
    VkCommandPool pool;
    CHECK(vkCreateCommandPool(dev, &pi, NULL, &pool) == VK_SUCCESS);
    VkCommandBuffer cmds[SLOTS];
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = SLOTS};
    CHECK(vkAllocateCommandBuffers(dev, &ai, cmds) == VK_SUCCESS);
    VkFence fences[SLOTS];
    for (int s = 0; s < SLOTS; ++s) {
        VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, .flags = VK_FENCE_CREATE_SIGNALED_BIT};
        CHECK(vkCreateFence(dev, &fi, NULL, &fences[s]) == VK_SUCCESS);
    }
    uint32_t mesh, moving, extra = UINT32_MAX;
    CHECK_RESULT(roma_map_add_mesh(map, box, &mesh), ROMA_SUCCESS);
    roma_instance_desc d = {.mesh = mesh, .flags = ROMA_INSTANCE_DYNAMIC};
    translation(-1.0f, 0.5f, 0.0f, d.transform);
    CHECK_RESULT(roma_map_add_instance(map, &d, &moving), ROMA_SUCCESS);
    uint64_t before = submits(ctx);
    for (uint32_t f = 0; f < FRAMES; ++f) {
        uint32_t s = f % SLOTS;
        CHECK(vkWaitForFences(dev, 1, &fences[s], VK_TRUE, UINT64_MAX) == VK_SUCCESS);
        float t[12];
        translation(-1.0f + 0.25f * (float)f, 0.5f, 0.0f, t);
        CHECK_RESULT(roma_map_set_instance_transform(map, moving, t), ROMA_SUCCESS);
        if (f == 3) {
            translation(0.0f, 0.5f, 1.0f, d.transform);
            CHECK_RESULT(roma_map_add_instance(map, &d, &extra), ROMA_SUCCESS);
        }
        if (f == 5)
            CHECK_RESULT(roma_map_remove_instance(map, extra), ROMA_SUCCESS);
        vkResetFences(dev, 1, &fences[s]);
        vkResetCommandBuffer(cmds[s], 0);
        VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        vkBeginCommandBuffer(cmds[s], &bi);
        roma_map_frame_desc fd = {.frame = f, .seed = 4, .jitter_grid = 1, .jitter_directions = 1, .slot = s};
        CHECK_RESULT(roma_map_record_build(map, cmds[s], &fd, NULL), ROMA_SUCCESS);
        vkEndCommandBuffer(cmds[s]);
        VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &cmds[s]};
        CHECK(vkQueueSubmit(roma_context_queue(ctx), 1, &si, fences[s]) == VK_SUCCESS);
    }
    CHECK(submits(ctx) == before); /* neither the record calls nor add/remove/move submitted */
    vkWaitForFences(dev, SLOTS, fences, VK_TRUE, UINT64_MAX);
    /* The last frame: the moving box at x = 0.75, the extra one gone. */
    EXPECT_T(map, 0.75f, 0.0f, 1.25f);
    EXPECT_T(map, -1.0f, 0.0f, 2.0f);
    EXPECT_T(map, 0.0f, 1.0f, 2.0f);
    for (int s = 0; s < SLOTS; ++s)
        vkDestroyFence(dev, fences[s], NULL);
    vkDestroyCommandPool(dev, pool, NULL);
    roma_map_destroy(map);
}

/* The geometry cap counts instances added since the last build: adding many instances of
 * a 1,002,528-triangle mesh before any build is refused once the live triangles would pass
 * UINT32_MAX / 12 (357,913,941): the 358th instance, and removing one makes room again. */
static void test_geometry_cap(roma_context *ctx, roma_scene *floor)
{
    const uint32_t n = 708; /* n x n quads */
    float *pos = malloc(sizeof(float) * 3 * (n + 1) * (n + 1));
    uint32_t *idx = malloc(sizeof(uint32_t) * 6 * n * n);
    roma_map *map = NULL;
    roma_scene *grid = NULL;
    if (pos && idx) {
        for (uint32_t y = 0; y <= n; ++y)
            for (uint32_t x = 0; x <= n; ++x) {
                float *p = pos + 3 * (y * (n + 1) + x);
                p[0] = (float)x / n, p[1] = 0.0f, p[2] = (float)y / n;
            }
        for (uint32_t y = 0; y < n; ++y)
            for (uint32_t x = 0; x < n; ++x) {
                uint32_t a = y * (n + 1) + x, *t = idx + 6 * (y * n + x);
                t[0] = a, t[1] = a + n + 1, t[2] = a + 1, t[3] = a + 1, t[4] = a + n + 1, t[5] = a + n + 2;
            }
        roma_scene_desc d = {.positions = pos, .vertex_count = (n + 1) * (n + 1), .indices = idx,
                             .triangle_count = 2 * n * n, .name = "grid"};
        CHECK_RESULT(roma_scene_create(&d, &grid), ROMA_SUCCESS);
    }
    CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.resolution = 32, .angular = 1}, floor, &map), ROMA_SUCCESS);
    uint32_t mesh = 0, first = 0, added = 0;
    if (map && grid && roma_map_add_mesh(map, grid, &mesh) == ROMA_SUCCESS) {
        roma_instance_desc id = {.mesh = mesh};
        uint32_t instance;
        while (added < 1000 && roma_map_add_instance(map, &id, &instance) == ROMA_SUCCESS) {
            if (added == 0)
                first = instance;
            ++added;
        }
        CHECK(added == 357);
        CHECK_RESULT(roma_map_remove_instance(map, first), ROMA_SUCCESS);
        CHECK_RESULT(roma_map_add_instance(map, &id, &instance), ROMA_SUCCESS);
        CHECK_RESULT(roma_map_add_instance(map, &id, &instance), ROMA_ERROR_INVALID_ARGUMENT);
    } else {
        CHECK(0);
    }
    roma_map_destroy(map);
    roma_scene_destroy(grid);
    free(pos);
    free(idx);
}

int main(void)
{
    roma_context_desc cd = {.flags = roma_test_sync_validation_flags(), .logger = roma_test_logger(&log_)};
    roma_context *ctx = NULL;
    if (roma_context_create(&cd, &ctx) != ROMA_SUCCESS) { /* a failure, not a skip: CI has the device */
        fprintf(stderr, "no Vulkan context with validation layers\n");
        return 1;
    }
    const float origin[1][3] = {{0.0f, 0.0f, 0.0f}};
    roma_scene *floor = make_scene(NULL, 0, 1), *box = make_scene(origin, 1, 0);
    if (floor && box) {
        test_api(ctx, floor, box);
        test_same_bom(ctx, floor, box);
        test_frames(ctx, floor, box);
        test_geometry_cap(ctx, floor);
    }
    roma_scene_destroy(floor);
    roma_scene_destroy(box);
    CHECK(roma_context_validation_error_count(ctx) == 0);
    roma_context_destroy(ctx);
    return roma_test_finish("test_instances");
}
