/* Out of device memory is an error, not a crash, and leaves nothing behind:
 *  - device memory is accounted: every object returns what it took when destroyed;
 *  - a context with a device-memory budget refuses, with ROMA_ERROR_OUT_OF_DEVICE_MEMORY,
 *    any create call that would pass it. Budgets from a few bytes up to what a map
 *    needs make each allocation of roma_map_create fail in turn: every failure
 *    releases everything the call had taken and the context stays usable;
 *  - a trace whose staging buffers do not fit fails the same way; the map still traces;
 *  - no device: test_no_driver. */
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "roma/builtin_scenes.h"
#include "roma/map.h"

static uint64_t in_use(const roma_context *ctx)
{
    roma_context_info info;
    roma_context_get_info(ctx, &info);
    return info.device_memory_in_use;
}

static roma_context *budget_context(uint64_t budget, roma_test_log *log)
{
    roma_context_desc desc = {.flags = ROMA_CONTEXT_VALIDATION, .logger = roma_test_logger(log),
                              .device_memory_budget = budget};
    roma_context *ctx = NULL;
    CHECK_RESULT(roma_context_create(&desc, &ctx), ROMA_SUCCESS);
    return ctx;
}

/* A built map traces a ray from the middle of the room into a wall. */
static int map_works(roma_map *map)
{
    if (roma_map_build(map, &(roma_map_frame_desc){.jitter_grid = 1}, NULL) != ROMA_SUCCESS)
        return 0;
    roma_map_info info;
    roma_map_get_info(map, &info);
    float mid = 0.5f * info.grid_cell * (float)info.resolution;
    roma_ray ray = {{info.grid_origin[0] + mid, info.grid_origin[1] + mid, info.grid_origin[2] + mid},
                    0.0f, {0.0f, 1.0f, 0.0f}, INFINITY};
    roma_hit hit;
    return roma_map_trace(map, ROMA_TRACE_SNAPPED_ANY, 0, &ray, 1, &hit, NULL) == ROMA_SUCCESS &&
           (hit.info & ROMA_HIT_FLAG);
}

/* Builds, then traces as map_works does: the code of the first call that fails. */
static roma_result first_failure(roma_map *map)
{
    roma_result r = roma_map_build(map, &(roma_map_frame_desc){.jitter_grid = 1}, NULL);
    if (r != ROMA_SUCCESS)
        return r;
    roma_ray ray = {{0.0f, 0.0f, 0.0f}, 0.0f, {0.0f, 1.0f, 0.0f}, INFINITY};
    roma_hit hit;
    return roma_map_trace(map, ROMA_TRACE_SNAPPED_ANY, 0, &ray, 1, &hit, NULL);
}

int main(void)
{
    roma_scene *scene = NULL;
    CHECK_RESULT(roma_scene_create_builtin("cornell", NULL, &scene), ROMA_SUCCESS);
    roma_test_log log;
    roma_context *ctx = budget_context(0, &log);
    if (!ctx || !scene) {
        roma_scene_destroy(scene);
        roma_context_destroy(ctx);
        return roma_test_finish("test_device_memory");
    }
    roma_context_info info;
    roma_context_get_info(ctx, &info);
    printf("largest allocation the device allows: %llu bytes\n", (unsigned long long)info.max_allocation_size);
    CHECK(info.max_allocation_size > 0 && info.device_memory_budget == 0);

    /* Accounting: a map holds at least its BOM and maps, and gives them back. */
    uint64_t base = in_use(ctx);
    roma_map *map = NULL;
    const roma_map_desc small = {.resolution = 32, .angular = 2};
    CHECK_RESULT(roma_map_create(ctx, &small, scene, &map), ROMA_SUCCESS);
    CHECK(map && map_works(map));
    roma_map_info mi;
    roma_map_get_info(map, &mi);
    uint64_t map_bytes = in_use(ctx) - base;
    printf("RES 32, A 2 map, built and traced once: %llu bytes of device memory\n", (unsigned long long)map_bytes);
    CHECK(map_bytes >= mi.bom_bytes + mi.maps_bytes + mi.params_bytes);
    roma_map_destroy(map);
    CHECK(in_use(ctx) == base);
    roma_test_context_finish(ctx);

    /* Budgets up to just short of what a second map takes, on top of a first map that
     * stays alive (so that memory in use never starts at zero, where a double release
     * would hide): creation, the first build and the first trace fail in turn at every
     * allocation, and each failure gives back exactly what its call took. Each budget
     * is the last one plus what its refused allocation asked for (the message names
     * the bytes asked for and those in use), so the next run fails one allocation
     * later. */
    int refused = 0, created = 0, steps = 0;
    uint64_t extra = 0;
    while (extra < map_bytes) {
        ++steps;
        uint64_t next = map_bytes;
        roma_context *c = budget_context(base + map_bytes + extra, &log);
        roma_map *ballast = NULL;
        if (!c || roma_map_create(c, &small, scene, &ballast) != ROMA_SUCCESS || !map_works(ballast)) {
            CHECK(!"a context with room for one map could not hold it");
            roma_map_destroy(ballast);
            roma_test_context_finish(c);
            break;
        }
        uint64_t before = in_use(c);
        CHECK(before == base + map_bytes);
        roma_map *m = (roma_map *)1;
        log.errors = 0;
        roma_result r = roma_map_create(c, &small, scene, &m);
        if (r == ROMA_SUCCESS) {
            ++created;
            /* Created within the budget: building and tracing need the rest. */
            uint64_t after_create = in_use(c);
            CHECK_RESULT(first_failure(m), ROMA_ERROR_OUT_OF_DEVICE_MEMORY);
            CHECK(log.errors == 1 && strstr(log.last, "budget") != NULL);
            CHECK(in_use(c) == after_create); /* a failed build keeps nothing; a failed trace drops its cache */
            roma_map_destroy(m);
        } else {
            ++refused;
            CHECK(r == ROMA_ERROR_OUT_OF_DEVICE_MEMORY);
            CHECK(m == NULL);
            CHECK(log.errors == 1 && strstr(log.last, "budget") != NULL);
        }
        unsigned long long asked = 0, limit = 0, used = 0;
        const char *colon = strchr(log.last, ':');
        if (colon && sscanf(colon + 1, " %llu more bytes of device memory would exceed the context's budget of %llu "
                            "(%llu in use)", &asked, &limit, &used) == 3) {
            CHECK(limit == base + map_bytes + extra);
            next = used + asked - (base + map_bytes);
            CHECK(next > extra);
        } else {
            CHECK(!"the refusal names the bytes asked for and those in use");
        }
        CHECK(in_use(c) == before);
        CHECK(map_works(ballast)); /* the context and its other objects carry on */
        roma_map_destroy(ballast);
        CHECK(in_use(c) == base);
        roma_test_context_finish(c);
        if (next <= extra)
            break;
        extra = next;
    }
    printf("%d budgets below a second map's %llu bytes: %d refused at creation, %d at the first build or trace\n",
           steps, (unsigned long long)map_bytes, refused, created);
    CHECK(refused > 0 && created > 0);

    /* Enough for the map, not for a large trace's staging buffers. */
    ctx = budget_context(base + map_bytes + 4096, &log);
    map = NULL;
    uint64_t ctx_base = ctx ? in_use(ctx) : 0;
    if (ctx)
        CHECK_RESULT(roma_map_create(ctx, &small, scene, &map), ROMA_SUCCESS);
    if (map) {
        CHECK(map_works(map));
        enum { N = 1 << 16 };
        roma_ray *rays = calloc(N, sizeof *rays);
        roma_hit *hits = calloc(N, sizeof *hits);
        uint64_t before = in_use(ctx);
        log.errors = 0;
        CHECK_RESULT(roma_map_trace(map, ROMA_TRACE_SNAPPED_ANY, 0, rays, N, hits, NULL),
                     ROMA_ERROR_OUT_OF_DEVICE_MEMORY);
        CHECK(log.errors == 1 && strstr(log.last, "budget") != NULL);
        CHECK(in_use(ctx) <= before);
        CHECK(map_works(map)); /* small traces still run */
        free(rays);
        free(hits);
        roma_map_destroy(map);
        CHECK(in_use(ctx) == ctx_base);
    }
    roma_test_context_finish(ctx);
    roma_scene_destroy(scene);
    return roma_test_finish("test_device_memory");
}
