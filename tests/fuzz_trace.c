/* Differential fuzzing of the trace: random scenes and maps, random rays, traced on the device
 * (roma_map_trace, the four query modes) and by the C mirror (src/trace/cpu_mirror.c), compared
 * hit for hit, bit for bit; on the way, each level's BOM against the CPU voxelizer (exact mode,
 * no instances) and the maps against the mirror's rotation.
 *
 * Scenes: triangles of every size (a millionth of the volume to larger than it), on a lattice
 * (coplanar, cell-face aligned), duplicated, degenerate (zero area, repeated vertices), scaled
 * by 1e-20 to 1e20 and moved away from the origin; sometimes meshes with instances, a clipping
 * volume, cascade levels around a random focus. Maps: RES 32 to 256, A 1 to 16, every BOM mode,
 * jittered or not. Rays: origins anywhere in and around the levels, on cell faces and corners, on
 * triangles and vertices, far outside; directions uniform, along axes, on octant edges (with
 * signed zeros), on stratum edges, exactly along candidates, with subnormal components,
 * unnormalised (1e-30 to 1e30), NaN and infinite; tmin and tmax of every order, equal, infinite.
 *
 * Where the device's map selection differs from the mirror's, it must be a neighbouring stratum
 * within ROMA_CPU_SELECTION_TOLERANCE of an edge (what Vulkan lets atan round); the mirror then
 * traces in the device's map and must agree. A closest hit's distance must lie in [tmin, tmax].
 *
 *   fuzz_trace [--seconds S] [--rays N] [--seed S] [--case C] [--rays-per-case N]
 * runs cases until S seconds have passed (default 60: ctest's slice) and at least N rays were
 * compared (default 0; `make fuzz-trace`: 1e8); --case C runs that one case of the seed (to
 * reproduce a finding); N rays per case (default 262,144: the scene, build and rotation cost
 * more than the rays). Exit status 0 when every comparison held, 1 otherwise (each finding
 * printed with its case and ray in hex). */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_random.h"
#include "harness.h"
#include "map/map_internal.h"
#include "roma/map.h"
#include "rotate/directions.h"
#include "trace/cpu_mirror.h"
#include "voxelize_cpu.h"

static float between(rng *r, float lo, float hi)
{
    return lo + (hi - lo) * unit(r);
}

static float pow10f_between(rng *r, float lo, float hi)
{
    return powf(10.0f, between(r, lo, hi));
}


/* --- scenes --- */

typedef struct mesh_data {
    float *positions;
    uint32_t *indices;
    uint32_t vertex_count, triangle_count;
} mesh_data;

static void mesh_free(mesh_data *m)
{
    free(m->positions);
    free(m->indices);
    memset(m, 0, sizeof *m);
}

/* Triangles in the unit cube (some beyond it), then scaled by scale and moved by offset. */
static int mesh_random(rng *r, uint32_t triangles, float scale, const float offset[3], mesh_data *m)
{
    m->positions = malloc(sizeof(float) * 9 * triangles);
    m->indices = malloc(sizeof(uint32_t) * 3 * triangles);
    if (!m->positions || !m->indices)
        return 0;
    m->vertex_count = 3 * triangles;
    m->triangle_count = triangles;
    const float lattice = (float)(8u << below(r, 4)); /* cell-face-like coordinates: k / 8 .. k / 64 */
    for (uint32_t t = 0; t < triangles; ++t) {
        float *v = m->positions + 9 * t;
        const uint32_t kind = below(r, 16);
        if (kind < 6) { /* small to medium, anywhere */
            const float size = pow10f_between(r, -6.0f, 0.0f), c[3] = {unit(r), unit(r), unit(r)};
            for (int i = 0; i < 9; ++i)
                v[i] = c[i % 3] + size * between(r, -1.0f, 1.0f);
        } else if (kind < 9) { /* axis-aligned, on the lattice: coplanar faces and shared edges */
            const int axis = (int)below(r, 3);
            const float plane = (float)below(r, (uint32_t)lattice + 1) / lattice;
            for (int i = 0; i < 3; ++i)
                for (int a = 0; a < 3; ++a)
                    v[3 * i + a] = a == axis ? plane : (float)below(r, (uint32_t)lattice + 1) / lattice;
        } else if (kind < 11 && t > 0) { /* a copy of an earlier triangle, maybe nudged by an ULP */
            const float *w = m->positions + 9 * below(r, t);
            for (int i = 0; i < 9; ++i)
                v[i] = below(r, 2) ? w[i] : nextafterf(w[i], below(r, 2) ? 2.0f : -2.0f);
        } else if (kind < 13) { /* degenerate: a repeated vertex or three on a line */
            const float a[3] = {unit(r), unit(r), unit(r)}, b[3] = {unit(r), unit(r), unit(r)};
            const float s = between(r, -1.0f, 2.0f);
            for (int i = 0; i < 3; ++i) {
                v[i] = a[i];
                v[3 + i] = below(r, 2) ? a[i] : b[i];
                v[6 + i] = a[i] + s * (b[i] - a[i]);
            }
        } else if (kind < 14) { /* larger than the volume */
            for (int i = 0; i < 9; ++i)
                v[i] = between(r, -2.0f, 3.0f);
        } else { /* a thin sliver */
            const float a[3] = {unit(r), unit(r), unit(r)}, d = pow10f_between(r, -7.0f, -2.0f);
            for (int i = 0; i < 3; ++i) {
                v[i] = a[i];
                v[3 + i] = a[i] + between(r, -0.5f, 0.5f);
                v[6 + i] = a[i] + (i == (int)(t % 3) ? d : 0.0f);
            }
        }
        for (int i = 0; i < 3; ++i)
            m->indices[3 * t + (uint32_t)i] = 3 * t + (uint32_t)i;
    }
    /* Every scene needs a triangle of non-zero area (roma_scene_create): the first one spans the
     * unit cube's diagonal plane. */
    const float first[9] = {0, 0, 0, 1, 0, 1, 0, 1, 1};
    memcpy(m->positions, first, sizeof first);
    for (uint32_t i = 0; i < 9 * triangles; ++i)
        m->positions[i] = m->positions[i] * scale + offset[i % 3];
    return 1;
}

/* A scene collapsed by its scale and offset is refused; its message is expected, and the
 * scenes' debug lines are not wanted. */
static void quiet(roma_log_level level, roma_result code, const char *message, void *user)
{
    (void)level, (void)code, (void)message, (void)user;
}

static roma_scene *scene_of(const mesh_data *m)
{
    roma_scene *scene = NULL;
    roma_scene_desc d = {.positions = m->positions, .vertex_count = m->vertex_count, .indices = m->indices,
                         .triangle_count = m->triangle_count, .name = "fuzz", .logger = {quiet, NULL}};
    return roma_scene_create(&d, &scene) == ROMA_SUCCESS ? scene : NULL;
}

/* --- one case --- */

typedef struct totals {
    uint64_t cases, refused, rays, traces, hits, selections, crossed, bom_words, map_words;
    uint64_t mismatches, bom_diffs, bom_ties, map_diffs, range_errors, call_errors;
} totals;

typedef struct case_desc {
    uint32_t res, angular, levels, triangles, instances, rays, max_steps;
    roma_bom_mode mode;
    float scale, offset[3], margin;
    int jitter_grid, jitter_directions, volume;
} case_desc;

static const char *mode_name(roma_bom_mode m)
{
    return m == ROMA_BOM_EXACT ? "exact" : m == ROMA_BOM_UNION3 ? "union3" : m == ROMA_BOM_DOMINANT ? "dominant"
                                                                                                   : "conservative";
}

static void print_case(const case_desc *c, uint64_t seed, uint64_t index)
{
    fprintf(stderr, "  case %" PRIu64 " of seed %" PRIu64 ": RES %u A %u levels %u %s, %u triangles, %u instances, "
            "scale %a offset (%a, %a, %a), margin %g, jitter %d/%d, volume %d, max_steps %u\n", index, seed, c->res,
            c->angular, c->levels, mode_name(c->mode), c->triangles, c->instances, (double)c->scale,
            (double)c->offset[0], (double)c->offset[1], (double)c->offset[2], (double)c->margin, c->jitter_grid,
            c->jitter_directions, c->volume, c->max_steps);
}

static void print_ray(const roma_ray *ray, int m, roma_hit gpu, roma_hit cpu, const char *what)
{
    fprintf(stderr, "    %s, mode %d: origin (%a, %a, %a) dir (%a, %a, %a) tmin %a tmax %a: device (t %a, info %#x), "
            "mirror (t %a, info %#x)\n", what, m, (double)ray->origin[0], (double)ray->origin[1],
            (double)ray->origin[2], (double)ray->dir[0], (double)ray->dir[1], (double)ray->dir[2], (double)ray->tmin,
            (double)ray->tmax, (double)gpu.t, gpu.info, (double)cpu.t, cpu.info);
}

static void case_random(rng *r, uint32_t rays_per_case, case_desc *c)
{
    memset(c, 0, sizeof *c);
    const uint32_t res_pick = below(r, 32);
    c->res = res_pick == 0 ? 256u : res_pick < 12 ? 32u : res_pick < 24 ? 64u : 128u;
    c->angular = 1u + below(r, 8);
    if (c->res <= 64 && below(r, 8) == 0)
        c->angular = 9u + below(r, 8); /* up to 16 */
    c->levels = 1;
    c->mode = (roma_bom_mode)below(r, 4);
    if (below(r, 3) == 0) { /* cascades: the exact mode, K x A x A <= 256 */
        c->mode = ROMA_BOM_EXACT;
        c->levels = 2u + below(r, 3);
        while (c->levels * c->angular * c->angular > 256u)
            --c->angular;
    }
    c->triangles = 1u + below(r, below(r, 4) == 0 ? 4000u : 300u);
    c->instances = below(r, 4) == 0 ? 1u + below(r, 4) : 0u;
    /* Scales across the supported range; extreme ones a quarter of the time. */
    c->scale = below(r, 4) == 0 ? pow10f_between(r, -20.0f, 20.0f) : pow10f_between(r, -2.0f, 3.0f);
    const float away = below(r, 2) ? pow10f_between(r, -1.0f, 4.0f) : 0.0f;
    for (int a = 0; a < 3; ++a)
        c->offset[a] = c->scale * away * between(r, -1.0f, 1.0f);
    c->margin = below(r, 3) == 0 ? between(r, 0.5f, (float)c->res / 8.0f) : 0.0f;
    c->jitter_grid = (int)below(r, 2);
    c->jitter_directions = (int)below(r, 2);
    c->volume = below(r, 6) == 0;
    c->max_steps = below(r, 4) == 0 ? below(r, 17) : 8u;
    c->rays = rays_per_case;
}

/* A random rotation (unit quaternion), scale and translation, row-major 3x4. */
static void transform_random(rng *r, float scale, float t[12])
{
    float q[4], n = 0.0f;
    for (int i = 0; i < 4; ++i) {
        q[i] = between(r, -1.0f, 1.0f);
        n += q[i] * q[i];
    }
    n = n > 1e-6f ? 1.0f / sqrtf(n) : 0.0f;
    for (int i = 0; i < 4; ++i)
        q[i] = n > 0.0f ? q[i] * n : (i == 0 ? 1.0f : 0.0f);
    const float w = q[0], x = q[1], y = q[2], z = q[3], s = pow10f_between(r, -1.0f, 0.5f);
    const float m[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
                        2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                        2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)};
    for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 3; ++col)
            t[4 * row + col] = m[3 * row + col] * s;
        t[4 * row + 3] = scale * between(r, -0.5f, 1.5f);
    }
}

/* Rays of every class over the levels' cubes (grids) and the scene (m). */
static void rays_random(rng *r, const case_desc *c, roma_map *map, uint32_t levels, const roma_grid_params *grids,
                        const mesh_data *m, roma_ray *rays)
{
    for (uint32_t i = 0; i < c->rays; ++i) {
        roma_ray *ray = &rays[i];
        const roma_grid_params *g = &grids[below(r, levels)];
        const float cell = g->origin[3], side = cell * (float)g->dims[0];
        const uint32_t origin_kind = below(r, 8);
        for (int a = 0; a < 3; ++a)
            ray->origin[a] = g->origin[a] + side * between(r, -0.2f, 1.2f);
        if (origin_kind == 1 || origin_kind == 2) { /* on cell faces, edges or corners */
            for (int a = 0; a < 3; ++a)
                if (origin_kind == 2 || below(r, 2))
                    ray->origin[a] = g->origin[a] + cell * (float)((int)below(r, g->dims[0] + 3u) - 1);
        } else if (origin_kind == 3 || origin_kind == 4) { /* on a triangle or at a vertex */
            const float *v = m->positions + 9 * below(r, m->triangle_count);
            float b0 = unit(r), b1 = unit(r);
            if (b0 + b1 > 1.0f)
                b0 = 1.0f - b0, b1 = 1.0f - b1;
            if (origin_kind == 4)
                b0 = (float)below(r, 2), b1 = b0 > 0.0f ? 0.0f : (float)below(r, 2);
            for (int a = 0; a < 3; ++a)
                ray->origin[a] = v[a] + b0 * (v[3 + a] - v[a]) + b1 * (v[6 + a] - v[a]);
        } else if (origin_kind == 5) { /* far away */
            const float far = side * pow10f_between(r, 0.0f, 6.0f);
            for (int a = 0; a < 3; ++a)
                ray->origin[a] = g->origin[a] + 0.5f * side + far * between(r, -1.0f, 1.0f);
        }
        if (below(r, 4096) == 0)
            ray->origin[below(r, 3)] = below(r, 2) ? NAN : INFINITY;

        const uint32_t dir_kind = below(r, 10);
        const float z = between(r, -1.0f, 1.0f), phi = 6.2831853f * unit(r), sr = sqrtf(fmaxf(0.0f, 1.0f - z * z));
        float d[3] = {sr * cosf(phi), sr * sinf(phi), z};
        if (dir_kind == 1) { /* along an axis, signed zeros elsewhere */
            const int axis = (int)below(r, 3);
            for (int a = 0; a < 3; ++a)
                d[a] = a == axis ? (below(r, 2) ? 1.0f : -1.0f) : (below(r, 2) ? 0.0f : -0.0f);
        } else if (dir_kind == 2) { /* on an octant edge: one component a signed zero */
            d[below(r, 3)] = below(r, 2) ? 0.0f : -0.0f;
        } else if (dir_kind == 3 || dir_kind == 4) { /* on a stratum edge (or corner) */
            const float a = (float)c->angular;
            float u = unit(r), v = unit(r);
            u = (float)below(r, c->angular + 1u) / a;
            if (dir_kind == 4)
                v = (float)below(r, c->angular + 1u) / a;
            roma_square_to_hemisphere(below(r, 2) ? u : v, below(r, 2) ? v : u, d);
            if (below(r, 2))
                d[0] = -d[0], d[1] = -d[1], d[2] = -d[2];
        } else if (dir_kind == 5) { /* exactly along a candidate, either way */
            roma_map_candidate(map, below(r, c->angular * c->angular), d);
            if (below(r, 2))
                d[0] = -d[0], d[1] = -d[1], d[2] = -d[2];
        } else if (dir_kind == 6) { /* subnormal or barely normal components */
            for (int a = 0; a < 3; ++a)
                if (below(r, 2))
                    d[a] = (below(r, 2) ? 1.0f : -1.0f) * pow10f_between(r, -45.0f, -36.0f);
        } else if (dir_kind == 7) { /* unnormalised */
            const float s = pow10f_between(r, -30.0f, 30.0f);
            for (int a = 0; a < 3; ++a)
                d[a] *= s;
        } else if (dir_kind == 8 && below(r, 64) == 0) { /* invalid */
            const float bad[4] = {0.0f, NAN, INFINITY, -0.0f};
            d[below(r, 3)] = bad[below(r, 4)];
            if (below(r, 2))
                d[0] = d[1] = d[2] = 0.0f;
        }
        memcpy(ray->dir, d, sizeof d);

        const float span = side * (below(r, 2) ? 1.0f : pow10f_between(r, -4.0f, 0.0f));
        switch (below(r, 10)) {
        case 0: case 1: case 2: ray->tmin = 0.0f, ray->tmax = INFINITY; break;
        case 3: ray->tmin = 0.0f, ray->tmax = span * unit(r); break;
        case 4: ray->tmin = span * between(r, -0.5f, 0.5f), ray->tmax = ray->tmin + span * unit(r); break;
        case 5: ray->tmin = ray->tmax = below(r, 2) ? 0.0f : span * between(r, -0.5f, 0.5f); break;
        case 6: ray->tmax = span * between(r, -0.5f, 0.5f), ray->tmin = ray->tmax + span * unit(r); break;
        case 7: ray->tmin = -INFINITY, ray->tmax = below(r, 2) ? INFINITY : span * unit(r); break;
        case 8: ray->tmin = below(r, 2) ? -0.0f : 0.0f, ray->tmax = below(r, 2) ? 1e30f : 3.4e38f; break;
        default:
            ray->tmin = span * between(r, -0.1f, 0.1f), ray->tmax = ray->tmin + span * 2.0f * unit(r);
            if (below(r, 256) == 0) {
                if (below(r, 2))
                    ray->tmin = NAN;
                else
                    ray->tmax = NAN;
            }
        }
    }
}

/* Whether a BOM cell where the device and the CPU voxelizer differ is a float tie, which the
 * exact voxelizer allows (docs/accuracy.md), in the grid's float coordinates as both compute
 * them: for a cell the device has and the CPU not, some triangle touches the cell grown by
 * TIE_CELLS; for a cell the device missed, no triangle reaches into the cell shrunk by
 * TIE_CELLS but a thin one (thinner than TIE_CELLS: the device's float edge tests cannot
 * resolve it, and moving a corner by that much would make it zero-area). */
#define TIE_CELLS 1e-4
static int bom_tie(const roma_voxel_grid *vg, const roma_scene_view *view, const uint32_t cell[3], int extra)
{
    const double grow = extra ? TIE_CELLS : -TIE_CELLS;
    const double box[3] = {cell[0] - grow, cell[1] - grow, cell[2] - grow};
    for (uint32_t t = 0; t < view->triangle_count; ++t) {
        double g[3][3];
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a)
                g[k][a] = (view->positions[3 * view->indices[3 * t + (uint32_t)k] + (uint32_t)a] - vg->origin[a]) *
                          vg->inv_cell;
        double e[3][3], longest = 0.0;
        for (int k = 0; k < 3; ++k) {
            double l = 0.0;
            for (int a = 0; a < 3; ++a) {
                e[k][a] = g[(k + 1) % 3][a] - g[k][a];
                l += e[k][a] * e[k][a];
            }
            longest = fmax(longest, sqrt(l));
        }
        const double n[3] = {e[0][1] * e[1][2] - e[0][2] * e[1][1], e[0][2] * e[1][0] - e[0][0] * e[1][2],
                             e[0][0] * e[1][1] - e[0][1] * e[1][0]};
        const double height = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) / fmax(longest, 1e-300);
        if (!extra && !(height >= TIE_CELLS))
            continue; /* too thin to count: the device may miss it */
        if (roma_tri_box_overlap(box, 1.0 + 2.0 * grow, g[0], g[1], g[2]))
            return extra; /* extra: touched, a tie; missed: a triangle reaches inside, not a tie */
    }
    return !extra;
}

/* The level a ray starts in (roma_level_of in roma/trace.glsl): the finest whose cube holds
 * its origin, else the coarsest. */
static uint32_t start_level(uint32_t levels, const roma_grid_params *grids, const float o[3])
{
    for (uint32_t l = 0; l + 1 < levels; ++l) {
        const float side = (float)grids[l].dims[0] * grids[l].origin[3];
        int inside = 1;
        for (int a = 0; a < 3; ++a)
            inside &= o[a] >= grids[l].origin[a] && o[a] < grids[l].origin[a] + side;
        if (inside)
            return l;
    }
    return levels - 1;
}

static int same_hit(roma_hit a, roma_hit b)
{
    return a.info == b.info && memcmp(&a.t, &b.t, sizeof a.t) == 0;
}

static void run_case(roma_context *ctx, uint64_t seed, uint64_t index, uint32_t rays_per_case, totals *tot)
{
    rng r = rng_of(seed, index);
    case_desc c;
    case_random(&r, rays_per_case, &c);
    mesh_data scene_mesh = {0}, instance_mesh = {0};
    roma_scene *scene = NULL, *mesh_scene = NULL;
    roma_map *map = NULL;
    uint32_t *bom = NULL, *maps = NULL, *cpu = NULL;
    roma_ray *rays = NULL;
    roma_hit *gpu = NULL;
    const uint64_t failures_before = tot->mismatches + tot->bom_diffs + tot->map_diffs + tot->range_errors +
                                     tot->call_errors;
    ++tot->cases;
    if (!mesh_random(&r, c.triangles, c.scale, c.offset, &scene_mesh))
        goto done;
    scene = scene_of(&scene_mesh);
    if (!scene) { /* collapsed at this scale and offset: nothing of non-zero area left */
        ++tot->refused;
        goto done;
    }
    const roma_map_desc desc = {.resolution = c.res, .angular = c.angular, .bom_mode = c.mode,
                                .margin_cells = c.margin, .cascades = c.levels, .logger = {quiet, NULL}};
    const roma_result created = roma_map_create(ctx, &desc, scene, &map);
    /* Outside the supported range, or maps larger than the device's buffers: refused, as documented. */
    if (created == ROMA_ERROR_INVALID_SCENE || created == ROMA_ERROR_UNSUPPORTED) {
        ++tot->refused;
        goto done;
    }
    if (created != ROMA_SUCCESS) {
        fprintf(stderr, "roma_map_create: %s\n", roma_result_string(created));
        ++tot->call_errors;
        goto done;
    }
    if (c.instances) {
        const float zero[3] = {0.0f, 0.0f, 0.0f};
        uint32_t mesh_id = 0;
        if (!mesh_random(&r, 1u + below(&r, 64), 1.0f, zero, &instance_mesh) ||
            !(mesh_scene = scene_of(&instance_mesh)) || roma_map_add_mesh(map, mesh_scene, &mesh_id) != ROMA_SUCCESS) {
            ++tot->call_errors;
            goto done;
        }
        for (uint32_t i = 0; i < c.instances; ++i) {
            roma_instance_desc in = {.mesh = mesh_id};
            transform_random(&r, c.scale, in.transform);
            for (int row = 0; row < 3; ++row) {
                for (int col = 0; col < 3; ++col)
                    in.transform[4 * row + col] *= c.scale;
                in.transform[4 * row + 3] += c.offset[row];
            }
            uint32_t id;
            if (roma_map_add_instance(map, &in, &id) != ROMA_SUCCESS) {
                ++tot->call_errors;
                goto done;
            }
        }
    }
    roma_scene_view view;
    roma_scene_get_view(scene, &view);
    roma_box volume;
    float focus[3];
    for (int a = 0; a < 3; ++a) {
        const float lo = view.bounds_min[a], ext = view.bounds_max[a] - lo;
        volume.min[a] = lo + ext * between(&r, -0.1f, 0.4f);
        volume.max[a] = lo + ext * between(&r, 0.6f, 1.1f);
        focus[a] = lo + ext * between(&r, -0.1f, 1.1f);
    }
    const float longest = fmaxf(view.bounds_max[0] - view.bounds_min[0],
                                fmaxf(view.bounds_max[1] - view.bounds_min[1], view.bounds_max[2] - view.bounds_min[2]));
    const roma_map_frame_desc frame = {
        .frame = below(&r, 1000), .seed = (uint32_t)next_u64(&r), .jitter_grid = c.jitter_grid,
        .jitter_directions = c.jitter_directions, .volume = c.volume ? &volume : NULL,
        .focus = c.levels > 1 ? focus : NULL,
        .finest_extent = c.levels > 1 && below(&r, 2) ? longest * pow10f_between(&r, -2.0f, 0.0f) : 0.0f};
    const roma_result built = roma_map_build(map, &frame, NULL);
    if (built == ROMA_ERROR_INVALID_SCENE) { /* the clipping volume or the instances out of range */
        ++tot->refused;
        goto done;
    }
    if (built != ROMA_SUCCESS) {
        fprintf(stderr, "roma_map_build: %s\n", roma_result_string(built));
        ++tot->call_errors;
        goto done;
    }
    uint32_t levels = 0;
    const roma_grid_params *grids;
    const roma_map_frame *frames;
    roma_map_get_level_params(map, &levels, &grids, &frames);
    const uint64_t texel_words = (uint64_t)c.res * c.res * (c.res / 32u);
    const uint64_t map_words = texel_words * c.angular * c.angular;
    bom = malloc(4 * texel_words * levels);
    maps = malloc(4 * map_words * levels);
    cpu = malloc(4 * (map_words > texel_words ? map_words : texel_words));
    rays = malloc(sizeof(roma_ray) * c.rays);
    gpu = malloc(sizeof(roma_hit) * c.rays);
    if (!bom || !maps || !cpu || !rays || !gpu) {
        ++tot->call_errors;
        goto done;
    }
    if (roma_map_download_bom(map, bom, texel_words * levels) != ROMA_SUCCESS ||
        roma_map_download_maps(map, maps, map_words * levels) != ROMA_SUCCESS) {
        ++tot->call_errors;
        goto done;
    }
    /* Each level: its BOM against the CPU voxelizer (exact, scene triangles only), its maps
     * against the mirror's rotation of that BOM. */
    for (uint32_t l = 0; l < levels; ++l) {
        const roma_grid_params *g = &grids[l];
        if (c.mode == ROMA_BOM_EXACT && !c.instances) {
            const roma_voxel_grid vg = {{g->origin[0], g->origin[1], g->origin[2]}, g->inv_cell[0], c.res};
            roma_voxelize_cpu(&vg, view.positions, 3, view.indices, view.triangle_count, cpu);
            uint64_t diff = 0;
            for (uint64_t i = 0; i < texel_words; ++i) {
                const uint32_t differ = bom[l * texel_words + i] ^ cpu[i];
                for (uint32_t b = 0; b < 32; ++b) {
                    if (!(differ >> b & 1u))
                        continue;
                    const uint32_t words = c.res / 32u, texel = (uint32_t)(i / words);
                    const uint32_t cell[3] = {texel % c.res, texel / c.res, (uint32_t)(i % words) * 32u + b};
                    const int extra = (bom[l * texel_words + i] >> b & 1u) != 0;
                    if (bom_tie(&vg, &view, cell, extra)) {
                        ++tot->bom_ties;
                    } else if (++diff <= 4) {
                        fprintf(stderr, "    level %u cell (%u, %u, %u): %s the CPU voxelizer, not a tie\n", l,
                                cell[0], cell[1], cell[2], extra ? "occupied on the device, not by" : "missed by the "
                                "device, occupied by");
                    }
                }
            }
            tot->bom_words += texel_words;
            if (diff) {
                print_case(&c, seed, index);
                fprintf(stderr, "    level %u: %" PRIu64 " BOM cells differ from the CPU voxelizer beyond a tie\n", l, diff);
            }
            tot->bom_diffs += diff;
        }
        roma_cpu_rotate(g, frames + g->level[2], bom + l * texel_words, cpu);
        uint64_t diff = 0;
        for (uint64_t i = 0; i < map_words; ++i)
            diff += maps[g->level[3] + i] != cpu[i];
        tot->map_words += map_words;
        if (diff) {
            print_case(&c, seed, index);
            fprintf(stderr, "    level %u: %" PRIu64 " map words differ from the mirror's rotation\n", l, diff);
        }
        tot->map_diffs += diff;
    }

    rays_random(&r, &c, map, levels, grids, &scene_mesh, rays);
    tot->rays += c.rays;
    for (int m = 0; m < 4; ++m) {
        const roma_result traced = roma_map_trace(map, (roma_trace_mode)m, c.max_steps, rays, c.rays, gpu, NULL);
        if (traced != ROMA_SUCCESS) {
            fprintf(stderr, "roma_map_trace: %s\n", roma_result_string(traced));
            ++tot->call_errors;
            goto done;
        }
        const uint32_t steps = c.max_steps ? c.max_steps : 8u;
        for (uint32_t i = 0; i < c.rays; ++i) {
            const roma_ray *ray = &rays[i];
            roma_hit h = roma_cpu_trace_levels(levels, grids, frames, maps, ray, (roma_trace_mode)m, steps, -1, 0);
            const uint32_t gpu_map = ROMA_HIT_MAP(gpu[i].info);
            if (!same_hit(h, gpu[i]) && ROMA_HIT_MAP(h.info) != gpu_map) {
                /* Only a neighbouring stratum on an edge (the same fold): then trace in the device's map. */
                if ((h.info & ROMA_HIT_FOLDED) != (gpu[i].info & ROMA_HIT_FOLDED) ||
                    !roma_cpu_selection_may_differ(ray->dir, c.angular, gpu_map, NULL)) {
                    if (tot->mismatches < 20) {
                        print_case(&c, seed, index);
                        print_ray(ray, m, gpu[i], h, "map selection beyond the tolerance");
                    }
                    ++tot->mismatches;
                    continue;
                }
                h = roma_cpu_trace_levels(levels, grids, frames, maps, ray, (roma_trace_mode)m, steps, (int)gpu_map,
                                          (gpu[i].info & ROMA_HIT_FOLDED) != 0);
                ++tot->selections;
            }
            ++tot->traces;
            tot->hits += gpu[i].info & ROMA_HIT_FLAG;
            tot->crossed += ROMA_HIT_LEVEL(gpu[i].info) > start_level(levels, grids, ray->origin);
            if (!same_hit(h, gpu[i])) {
                if (tot->mismatches < 20) {
                    print_case(&c, seed, index);
                    print_ray(ray, m, gpu[i], h, "device and mirror differ");
                }
                ++tot->mismatches;
            }
            /* A closest hit lies in [tmin, tmax] (docs/robustness.md). */
            if ((m & 1) && (gpu[i].info & ROMA_HIT_FLAG) && !(gpu[i].t >= ray->tmin && gpu[i].t <= ray->tmax)) {
                if (tot->range_errors < 20) {
                    print_case(&c, seed, index);
                    print_ray(ray, m, gpu[i], h, "closest hit outside [tmin, tmax]");
                }
                ++tot->range_errors;
            }
        }
    }
done:
    if (tot->mismatches + tot->bom_diffs + tot->map_diffs + tot->range_errors + tot->call_errors !=
        failures_before) {
        print_case(&c, seed, index);
        fprintf(stderr, "    %" PRIu64 " findings; reproduce: fuzz_trace --seed %" PRIu64 " --case %" PRIu64
                " --rays-per-case %u\n", tot->mismatches + tot->bom_diffs + tot->map_diffs + tot->range_errors +
                tot->call_errors - failures_before, seed, index, rays_per_case);
    }
    free(bom);
    free(maps);
    free(cpu);
    free(rays);
    free(gpu);
    roma_map_destroy(map);
    roma_scene_destroy(scene);
    roma_scene_destroy(mesh_scene);
    mesh_free(&scene_mesh);
    mesh_free(&instance_mesh);
}

int main(int argc, char **argv)
{
    double seconds = 60.0;
    uint64_t min_rays = 0, seed = 1, only_case = UINT64_MAX;
    uint32_t rays_per_case = 1u << 18;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--seconds"))
            seconds = atof(argv[i + 1]);
        else if (!strcmp(argv[i], "--rays"))
            min_rays = strtoull(argv[i + 1], NULL, 10);
        else if (!strcmp(argv[i], "--seed"))
            seed = strtoull(argv[i + 1], NULL, 10);
        else if (!strcmp(argv[i], "--case"))
            only_case = strtoull(argv[i + 1], NULL, 10);
        else if (!strcmp(argv[i], "--rays-per-case"))
            rays_per_case = (uint32_t)strtoul(argv[i + 1], NULL, 10);
        else {
            fprintf(stderr, "fuzz_trace: unknown option %s\n", argv[i]);
            return 2;
        }
    }
    if (rays_per_case == 0 || rays_per_case > (1u << 22)) {
        fprintf(stderr, "fuzz_trace: --rays-per-case must lie in [1, 4194304]\n");
        return 2;
    }
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("fuzz_trace");
    totals tot = {0};
    const double start = now_seconds();
    double last_report = start;
    if (only_case != UINT64_MAX) {
        run_case(ctx, seed, only_case, rays_per_case, &tot);
    } else {
        for (uint64_t index = 0; now_seconds() - start < seconds || tot.rays < min_rays; ++index) {
            run_case(ctx, seed, index, rays_per_case, &tot);
            if (now_seconds() - last_report > 60.0) {
                last_report = now_seconds();
                printf("%.0f s: %" PRIu64 " cases, %" PRIu64 " rays, %" PRIu64 " mismatches\n", last_report - start,
                       tot.cases, tot.rays, tot.mismatches);
                fflush(stdout);
            }
        }
    }
    const double elapsed = now_seconds() - start;
    printf("fuzz_trace seed %" PRIu64 ": %.1f s, %" PRIu64 " cases (%" PRIu64 " refused as documented), %" PRIu64
           " rays, %" PRIu64 " traces compared with the mirror in 4 modes (%" PRIu64 " hits, %" PRIu64
           " ended in a coarser level than they began in, %" PRIu64 " traced in the device's map across a stratum edge)\n",
           seed, elapsed, tot.cases, tot.refused, tot.rays, tot.traces, tot.hits, tot.crossed, tot.selections);
    printf("  %" PRIu64 " BOM words compared with the CPU voxelizer (%" PRIu64 " cells differ on a float tie), %" PRIu64
           " map words with the mirror's rotation\n", tot.bom_words, tot.bom_ties, tot.map_words);
    printf("  findings: %" PRIu64 " trace mismatches, %" PRIu64 " closest hits outside [tmin, tmax], %" PRIu64
           " BOM cells beyond a tie, %" PRIu64 " map words, %" PRIu64 " failed calls\n", tot.mismatches, tot.range_errors,
           tot.bom_diffs, tot.map_diffs, tot.call_errors);
    CHECK(tot.mismatches == 0 && tot.range_errors == 0 && tot.bom_diffs == 0 && tot.map_diffs == 0 &&
          tot.call_errors == 0);
    CHECK(tot.traces > 0);
    roma_test_context_finish(ctx);
    return roma_test_finish("fuzz_trace");
}
