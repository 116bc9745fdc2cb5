#include "map/level_runs.h"

#include <math.h>
#include <stdlib.h>

#include "util/log.h"

roma_result roma_map_chunks_create(roma_map *map, const float *positions)
{
    map->chunk_count = (map->triangle_count + ROMA_CHUNK_TRIANGLES - 1) / ROMA_CHUNK_TRIANGLES;
    map->chunk_boxes = malloc(6 * sizeof(float) * map->chunk_count);
    if (!map->chunk_boxes)
        return roma_fail(&map->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_map_create: out of memory");
    roma_map_chunks_update(map, positions);
    return ROMA_SUCCESS;
}

void roma_map_chunks_update(roma_map *map, const float *positions)
{
    for (uint32_t c = 0; c < map->chunk_count; ++c) {
        float *box = map->chunk_boxes + 6 * c;
        box[0] = box[1] = box[2] = INFINITY;
        box[3] = box[4] = box[5] = -INFINITY;
        const uint32_t end = c + 1 == map->chunk_count ? map->triangle_count : (c + 1) * ROMA_CHUNK_TRIANGLES;
        for (uint32_t t = c * ROMA_CHUNK_TRIANGLES; t < end; ++t)
            for (int k = 0; k < 3; ++k) {
                const float *p = positions + 3 * (size_t)map->indices_host[3 * (size_t)t + k];
                for (int a = 0; a < 3; ++a) {
                    box[a] = fminf(box[a], p[a]);
                    box[3 + a] = fmaxf(box[3 + a], p[a]);
                }
            }
    }
    map->chunks_known = 1;
}

int roma_map_touches_level(const roma_map *map, uint32_t l, const float bmin[3], const float bmax[3])
{
    const roma_grid_params *g = &map->grids[l];
    for (int a = 0; a < 3; ++a) {
        const float lo = g->origin[a] - g->origin[3], hi = g->origin[a] + (float)(map->res + 1) * g->origin[3];
        if (!(bmax[a] >= lo && bmin[a] <= hi))
            return 0;
    }
    return 1;
}

/* Appends triangles first .. first + count - 1 (after every run so far): extends the last
 * run where they meet it; past the limit, merges the two runs with the smallest gap. */
static void add_run(roma_triangle_run *runs, uint32_t *n, uint32_t first, uint32_t count)
{
    if (!count)
        return;
    if (*n && runs[*n - 1].first + runs[*n - 1].count == first) {
        runs[*n - 1].count += count;
        return;
    }
    runs[(*n)++] = (roma_triangle_run){first, count};
    if (*n <= ROMA_VOXELIZE_RUNS)
        return;
    uint32_t best = 0, best_gap = UINT32_MAX;
    for (uint32_t i = 0; i + 1 < *n; ++i) {
        const uint32_t gap = runs[i + 1].first - (runs[i].first + runs[i].count);
        if (gap < best_gap)
            best = i, best_gap = gap;
    }
    runs[best].count = runs[best + 1].first + runs[best + 1].count - runs[best].first;
    for (uint32_t i = best + 1; i + 1 < *n; ++i)
        runs[i] = runs[i + 1];
    --*n;
}

uint32_t roma_map_level_runs(const roma_map *map, uint32_t l, uint32_t end, roma_triangle_run out[ROMA_VOXELIZE_RUNS])
{
    roma_triangle_run runs[ROMA_VOXELIZE_RUNS + 1];
    uint32_t n = 0;
    for (uint32_t c = 0; c < map->chunk_count; ++c) {
        const uint32_t first = c * ROMA_CHUNK_TRIANGLES;
        const uint32_t last = c + 1 == map->chunk_count ? map->triangle_count : first + ROMA_CHUNK_TRIANGLES;
        const float *box = map->chunk_boxes + 6 * c;
        if (first < end && (!map->chunks_known || roma_map_touches_level(map, l, box, box + 3)))
            add_run(runs, &n, first, (last < end ? last : end) - first);
    }
    /* The instances in the layout's order (roma_map_instances_prepare). */
    uint32_t at = map->triangle_count;
    for (int dynamic = 0; dynamic < 2; ++dynamic)
        for (uint32_t i = 0; i < map->instance_count; ++i) {
            const roma_map_instance *in = &map->instances[i];
            if (!in->live || roma_map_instance_is_dynamic(in) != dynamic)
                continue;
            const uint32_t count = map->meshes[in->mesh].triangle_count;
            float bmin[3] = {INFINITY, INFINITY, INFINITY}, bmax[3] = {-INFINITY, -INFINITY, -INFINITY};
            roma_map_instance_box(map, in, bmin, bmax);
            if (at < end && roma_map_touches_level(map, l, bmin, bmax))
                add_run(runs, &n, at, (at + count < end ? at + count : end) - at);
            at += count;
        }
    for (uint32_t i = 0; i < n; ++i)
        out[i] = runs[i];
    return n;
}
