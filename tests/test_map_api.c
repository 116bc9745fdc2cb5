/* roma_map API contract: argument checks with exact codes and messages, defaults,
 * info and memory figures, candidates, animation updates, and that failed calls
 * leave the map usable. */
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "roma/builtin_scenes.h"
#include "roma/map.h"
#include "vulkan/vk_internal.h"

static uint64_t popcount_words(const uint32_t *w, uint64_t n)
{
    uint64_t c = 0;
    for (uint64_t i = 0; i < n; ++i)
        c += (uint64_t)__builtin_popcount(w[i]);
    return c;
}

int main(void)
{
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_map_api");
    roma_scene *scene = NULL;
    CHECK_RESULT(roma_scene_create_builtin("cornell", NULL, &scene), ROMA_SUCCESS);
    roma_test_log log;
    roma_map *map = (roma_map *)1;

    /* Rejections, each with its code, a message, and no object. */
    struct { roma_map_desc desc; const char *why; } bad[] = {
        {{.resolution = 96}, "resolution"},
        {{.resolution = 512}, "resolution"},
        {{.angular = 17}, "angular"},
        {{.bom_mode = (roma_bom_mode)7}, "bom_mode"},
        {{.margin_cells = 0.25f}, "margin_cells"},
        {{.resolution = 32, .margin_cells = 5.0f}, "margin_cells"},
        {{.preset = (roma_preset)5}, "preset"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        bad[i].desc.logger = roma_test_logger(&log);
        map = (roma_map *)1;
        CHECK_RESULT(roma_map_create(ctx, &bad[i].desc, scene, &map), ROMA_ERROR_INVALID_ARGUMENT);
        CHECK(map == NULL);
        CHECK(log.errors == 1 && strstr(log.last, bad[i].why) != NULL);
    }
    CHECK_RESULT(roma_map_create(NULL, NULL, scene, &map), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_map_create(ctx, NULL, NULL, &map), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_map_create(ctx, NULL, scene, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    roma_map_destroy(NULL);

    /* Maps that the rotation cannot write as one storage buffer are refused by name, where the
     * device's maxStorageBufferRange is below them (lavapipe: 128 MiB, RES 256 with more than 64
     * maps; before, a validation error at the first build). */
    const uint64_t a16_bytes = 256ull * 256 * 8 * 4 * 256;
    if (a16_bytes > ctx->properties.limits.maxStorageBufferRange) {
        map = (roma_map *)1;
        CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.resolution = 256, .angular = 16,
                                                           .logger = roma_test_logger(&log)}, scene, &map),
                     ROMA_ERROR_UNSUPPORTED);
        CHECK(map == NULL && log.errors == 1 && strstr(log.last, "maxStorageBufferRange") != NULL);
    }

    /* A preset sets RES and A where the desc leaves them 0. */
    roma_map *preset_map = NULL;
    roma_map_info preset_info;
    CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.preset = ROMA_PRESET_LOW}, scene, &preset_map), ROMA_SUCCESS);
    CHECK(preset_map && roma_map_get_info(preset_map, &preset_info) == ROMA_SUCCESS &&
          preset_info.resolution == 128 && preset_info.angular == 2);
    roma_map_destroy(preset_map);
    preset_map = NULL;
    CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.preset = ROMA_PRESET_HIGH, .angular = 3}, scene, &preset_map),
                 ROMA_SUCCESS);
    CHECK(preset_map && roma_map_get_info(preset_map, &preset_info) == ROMA_SUCCESS &&
          preset_info.resolution == 256 && preset_info.angular == 3);
    roma_map_destroy(preset_map);

    /* Zero desc = RES 128, A 4; queries before the first build are refused. */
    CHECK_RESULT(roma_map_create(ctx, NULL, scene, &map), ROMA_SUCCESS);
    if (!map) {
        roma_scene_destroy(scene);
        roma_test_context_finish(ctx);
        return roma_test_finish("test_map_api");
    }
    roma_map_info info;
    CHECK_RESULT(roma_map_get_info(map, &info), ROMA_SUCCESS);
    CHECK(info.resolution == 128 && info.angular == 4 && info.map_count == 16 && info.words_per_texel == 4);
    CHECK(info.bom_bytes == 128ull * 128 * 128 / 8);
    CHECK(info.maps_bytes == 16 * info.bom_bytes);
    float dir[3];
    CHECK_RESULT(roma_map_candidate(map, 0, dir), ROMA_ERROR_NOT_READY);
    roma_ray ray = {{0.0f, 1.0f, 0.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, INFINITY};
    roma_hit hit;
    CHECK_RESULT(roma_map_trace(map, ROMA_TRACE_SNAPPED_ANY, 0, &ray, 1, &hit, NULL), ROMA_ERROR_NOT_READY);

    roma_map_frame_desc frame = {.frame = 3, .seed = 4, .jitter_grid = 0, .jitter_directions = 1};
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_get_info(map, &info), ROMA_SUCCESS);
    CHECK(info.maps_address != 0 && info.params_address != 0);
    CHECK(info.bom_address != 0 && info.bom_buffer != VK_NULL_HANDLE); /* roma/ray_start.glsl's BOM */
    CHECK_NEAR(info.trace_cell, info.grid_cell * sqrtf(3.0f), 1e-6);
    for (uint32_t k = 0; k < info.map_count; ++k) {
        CHECK_RESULT(roma_map_candidate(map, k, dir), ROMA_SUCCESS);
        CHECK_NEAR(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2], 1.0, 1e-5);
        CHECK(dir[2] >= 0.0f);
    }
    CHECK_RESULT(roma_map_candidate(map, info.map_count, dir), ROMA_ERROR_INVALID_ARGUMENT);
    /* From the middle of the closed room every direction hits a wall. */
    CHECK_RESULT(roma_map_trace(map, ROMA_TRACE_SNAPPED_ANY, 0, &ray, 1, &hit, NULL), ROMA_SUCCESS);
    CHECK(hit.info & ROMA_HIT_FLAG);
    CHECK_RESULT(roma_map_trace(map, (roma_trace_mode)9, 0, &ray, 1, &hit, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_map_download_bom(map, NULL, 1), ROMA_ERROR_INVALID_ARGUMENT);
    uint32_t small[4];
    CHECK_RESULT(roma_map_download_bom(map, small, 4), ROMA_ERROR_INVALID_ARGUMENT);

    /* Animation: moving every vertex moves the grid with it; the BOM keeps its occupancy. */
    roma_scene_view sv;
    roma_scene_get_view(scene, &sv);
    uint64_t words = info.bom_bytes / 4;
    uint32_t *before = malloc(info.bom_bytes), *after = malloc(info.bom_bytes);
    CHECK_RESULT(roma_map_download_bom(map, before, words), ROMA_SUCCESS);
    float origin_before[3];
    memcpy(origin_before, info.grid_origin, sizeof origin_before);
    float *moved = malloc(sizeof(float) * 3 * sv.vertex_count);
    for (uint32_t i = 0; i < 3 * sv.vertex_count; ++i)
        moved[i] = sv.positions[i] + (i % 3 == 0 ? 10.0f : 0.0f);
    roma_map_frame_desc move = frame;
    move.positions = moved, move.vertex_count = sv.vertex_count;
    CHECK_RESULT(roma_map_build(map, &move, NULL), ROMA_SUCCESS);
    roma_map_get_info(map, &info);
    CHECK_NEAR(info.grid_origin[0], origin_before[0] + 10.0f, 1e-4);
    CHECK_NEAR(info.grid_origin[1], origin_before[1], 1e-6);
    CHECK_RESULT(roma_map_download_bom(map, after, words), ROMA_SUCCESS);
    uint64_t nb = popcount_words(before, words), na = popcount_words(after, words);
    printf("BOM cells before %llu, after a 10-unit move %llu\n", (unsigned long long)nb, (unsigned long long)na);
    /* The grid moves with the geometry, but the float origin rounds differently, so walls that lie
     * on cell faces may flip to the neighbouring cell: the counts agree to within 1%. */
    CHECK(nb > 0 && fabs((double)na - (double)nb) < 0.01 * (double)nb);
    /* The room moved: a ray from its old centre now starts outside it. */
    CHECK_RESULT(roma_map_trace(map, ROMA_TRACE_SNAPPED_ANY, 0, &ray, 1, &hit, NULL), ROMA_SUCCESS);
    roma_ray inside = ray;
    inside.origin[0] += 10.0f;
    roma_hit hit_inside;
    CHECK_RESULT(roma_map_trace(map, ROMA_TRACE_SNAPPED_ANY, 0, &inside, 1, &hit_inside, NULL), ROMA_SUCCESS);
    CHECK(hit_inside.info & ROMA_HIT_FLAG);

    /* Bad updates are refused and leave the map as it was. */
    move.vertex_count = sv.vertex_count - 1;
    CHECK_RESULT(roma_map_build(map, &move, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    move.vertex_count = sv.vertex_count;
    moved[4] = NAN;
    CHECK_RESULT(roma_map_build(map, &move, NULL), ROMA_ERROR_INVALID_SCENE);
    CHECK_RESULT(roma_map_build(NULL, &move, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_trace(map, ROMA_TRACE_SNAPPED_ANY, 0, &inside, 1, &hit_inside, NULL), ROMA_SUCCESS);
    CHECK(hit_inside.info & ROMA_HIT_FLAG);

    free(before);
    free(after);
    free(moved);
    roma_map_destroy(map);

    /* Pipelines belong to the context: a map of another RES and A, built and traced the
     * same way, compiles none. */
    roma_context_info ci;
    CHECK_RESULT(roma_context_get_info(ctx, &ci), ROMA_SUCCESS);
    uint32_t compiled = ci.pipelines_compiled;
    roma_map *other = NULL;
    CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.resolution = 64, .angular = 2}, scene, &other), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_build(other, &frame, NULL), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_trace(other, ROMA_TRACE_SNAPPED_ANY, 0, &ray, 1, &hit, NULL), ROMA_SUCCESS);
    CHECK_RESULT(roma_context_get_info(ctx, &ci), ROMA_SUCCESS);
    printf("compute pipelines compiled: %u after the first map, %u after a second of RES 64, A 2\n", compiled,
           ci.pipelines_compiled);
    CHECK(compiled > 0 && ci.pipelines_compiled == compiled);
    roma_map_destroy(other);
    roma_scene_destroy(scene);
    roma_test_context_finish(ctx);
    return roma_test_finish("test_map_api");
}
