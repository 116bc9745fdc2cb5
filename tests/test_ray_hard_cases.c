/* Numerical hard cases of the ray queries (roma_map_trace), on the CI device:
 *  1. crafted rays at every RES: axis directions, the pole and the horizon, stratum
 *     edges and the concentric map's diagonals, directions scaled by 2^+-100 and
 *     2^-140 (subnormal), zero/NaN/Inf directions; origins on cell corners, edges
 *     and faces, on the grid boundary, outside it, inside occupied cells; empty,
 *     reversed, negative, infinite and NaN [tmin, tmax]. The GPU equals the C
 *     mirror bit for bit, every result is well defined, and a direction scaled by a
 *     power of two traces exactly like the unscaled one;
 *  2. bit ranges that start and end on word boundaries (cells 0, 31, 32, 63, ...):
 *     axis rays through plates on chosen cells agree exactly with Embree;
 *  3. a scene scaled by powers of two gives bit-identical results; scaled by 1e-3 and
 *     1e4, or moved 1e4 to 1e6 away from the origin, its error against Embree stays
 *     that of the unit scene (plus what rounding its vertices to float lost);
 *  4. degenerate scenes: flat, one triangle, sub-cell and sliver triangles, a
 *     triangle across the whole grid. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "reference.h"
#include "trace/cpu_mirror.h"
#include "rotate/directions.h"
#include "roma/builtin_scenes.h"
#include "roma/map.h"
#include "map/map_internal.h"
#include "roma/sampling.h"

/* --- scenes --- */

typedef struct mesh {
    float pos[3 * 512];
    uint32_t idx[3 * 512];
    uint32_t vertices, triangles;
} mesh;

static void add_triangle(mesh *m, const float a[3], const float b[3], const float c[3])
{
    const float *v[3] = {a, b, c};
    for (int i = 0; i < 3; ++i) {
        memcpy(m->pos + 3 * m->vertices, v[i], 3 * sizeof(float));
        m->idx[3 * m->triangles + (uint32_t)i] = m->vertices++;
    }
    ++m->triangles;
}

/* Axis-aligned rectangle [x0,x1] x [y0,y1] at height z. */
static void add_plate(mesh *m, float x0, float y0, float x1, float y1, float z)
{
    float a[3] = {x0, y0, z}, b[3] = {x1, y0, z}, c[3] = {x1, y1, z}, d[3] = {x0, y1, z};
    add_triangle(m, a, b, c);
    add_triangle(m, a, c, d);
}

/* The six faces of box [lo, hi]. */
static void add_box(mesh *m, const float lo[3], const float hi[3])
{
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            float q[4][3];
            for (int k = 0; k < 4; ++k) {
                q[k][axis] = side ? hi[axis] : lo[axis];
                q[k][u] = (k == 1 || k == 2) ? hi[u] : lo[u];
                q[k][v] = (k >= 2) ? hi[v] : lo[v];
            }
            add_triangle(m, q[0], q[1], q[2]);
            add_triangle(m, q[0], q[2], q[3]);
        }
}

/* x -> x * scale + offset, in double, rounded once. */
static roma_scene *make_scene(const mesh *m, double scale, const double offset[3])
{
    float *p = malloc(sizeof(float) * 3 * m->vertices);
    for (uint32_t i = 0; i < 3 * m->vertices; ++i)
        p[i] = (float)((double)m->pos[i] * scale + (offset ? offset[i % 3] : 0.0));
    roma_scene_desc desc = {.positions = p, .vertex_count = m->vertices, .indices = m->idx,
                            .triangle_count = m->triangles};
    roma_scene *scene = NULL;
    CHECK_RESULT(roma_scene_create(&desc, &scene), ROMA_SUCCESS);
    free(p);
    return scene;
}

/* --- a built map and its mirror data --- */

typedef struct fixture {
    roma_map *map;
    roma_map_info info;
    roma_grid_params grid;
    const roma_map_frame *frames;
    uint32_t *maps;
} fixture;

static int fixture_open(roma_context *ctx, const roma_scene *scene, roma_map_desc desc,
                        roma_map_frame_desc frame, fixture *f)
{
    memset(f, 0, sizeof *f);
    if (!scene)
        return 0;
    roma_result r = roma_map_create(ctx, &desc, scene, &f->map);
    CHECK_RESULT(r, ROMA_SUCCESS);
    if (r != ROMA_SUCCESS)
        return 0;
    CHECK_RESULT(roma_map_build(f->map, &frame, NULL), ROMA_SUCCESS);
    roma_map_get_info(f->map, &f->info);
    uint64_t words = (uint64_t)f->info.map_count * f->info.resolution * f->info.resolution *
                     f->info.words_per_texel;
    f->maps = malloc(words * sizeof(uint32_t));
    CHECK_RESULT(roma_map_download_maps(f->map, f->maps, words), ROMA_SUCCESS);
    roma_map_get_frame_params(f->map, &f->grid, &f->frames);
    return 1;
}

static void fixture_close(fixture *f)
{
    roma_map_destroy(f->map);
    free(f->maps);
    memset(f, 0, sizeof *f);
}

/* World point at continuous BOM cell coordinates g. */
static void grid_point(const fixture *f, float gx, float gy, float gz, float out[3])
{
    const float g[3] = {gx, gy, gz};
    for (int a = 0; a < 3; ++a)
        out[a] = f->info.grid_origin[a] + g[a] * f->info.grid_cell;
}

static int same_hit(roma_hit a, roma_hit b)
{
    return a.info == b.info && memcmp(&a.t, &b.t, sizeof a.t) == 0;
}

static int direction_valid(const float d[3]);

/* Rays that are traced at all: valid direction, finite origin, tmin <= tmax. */
static int ray_valid(const roma_ray *r)
{
    return direction_valid(r->dir) && isfinite(r->origin[0]) && isfinite(r->origin[1]) &&
           isfinite(r->origin[2]) && r->tmin <= r->tmax;
}

/* The documented rule: subnormal components count as zero; a direction with a NaN or
 * infinite component, or no normal component, is invalid (a miss). */
static int direction_valid(const float d[3])
{
    float unit[3];
    return roma_unit_direction(d, unit);
}

/* A result is well defined: known info bits, a map that exists, t = INFINITY unless a
 * closest hit, and a closest hit inside [tmin, tmax]. */
static int well_defined(const fixture *f, const roma_ray *r, roma_trace_mode mode, roma_hit h)
{
    if (h.info & ~(ROMA_HIT_FLAG | 0xff00u | 0x10000u))
        return 0;
    if (ROMA_HIT_MAP(h.info) >= f->info.map_count)
        return 0;
    int closest = mode == ROMA_TRACE_SNAPPED_CLOSEST || mode == ROMA_TRACE_UNSNAPPED_CLOSEST;
    if (!(h.info & ROMA_HIT_FLAG) || !closest)
        return h.t == INFINITY;
    if (!isfinite(h.t))
        return 0;
    return h.t >= r->tmin && h.t <= r->tmax; /* exactly: roma_hit_distance clamps */
}

typedef struct trace_counts {
    uint32_t rays, mismatches, undefined, selection, invalid_hits;
    float widest; /* the largest distance from a stratum edge of a selection difference */
} trace_counts;

/* Traces rays in all four modes on the GPU (max_steps as given), checks them against
 * the mirror and for well-definedness; hits[mode] receives the GPU results if given. */
static trace_counts trace_checked(const fixture *f, const roma_ray *rays, uint32_t n,
                                  uint32_t max_steps, roma_hit *hits[4], const char *label)
{
    trace_counts c = {0};
    roma_hit *gpu = malloc(sizeof(roma_hit) * n);
    for (int m = 0; m < 4; ++m) {
        CHECK_RESULT(roma_map_trace(f->map, (roma_trace_mode)m, max_steps, rays, n, gpu, NULL), ROMA_SUCCESS);
        for (uint32_t i = 0; i < n; ++i) {
            const roma_ray *r = &rays[i];
            int folded;
            uint32_t k = ray_valid(r) ? roma_cpu_select_map(r->dir, f->info.angular, &folded) : 0;
            uint32_t gk = ROMA_HIT_MAP(gpu[i].info);
            if (k != gk) {
                /* Only on a stratum edge, within what Vulkan lets atan and sqrt round. */
                float distance = INFINITY;
                const int may = ray_valid(r) && roma_cpu_selection_may_differ(r->dir, f->info.angular, gk, &distance);
                if (ray_valid(r))
                    c.widest = fmaxf(c.widest, distance);
                if (!may) {
                    if (c.undefined < 4)
                        fprintf(stderr, "  %s ray %u d (%.9g %.9g %.9g): gpu map %u, mirror map %u\n", label, i,
                                r->dir[0], r->dir[1], r->dir[2], gk, k);
                    ++c.undefined;
                }
                ++c.selection;
            }
            /* The mirror selects its own map and fold; only on a stratum edge, where the
             * two may round apart, does it trace the GPU's choice instead. */
            int edge = k != gk;
            roma_hit cpu = roma_cpu_trace(&f->grid, f->frames, f->maps, r, (roma_trace_mode)m, max_steps,
                                          edge ? (int)gk : -1, edge ? (int)((gpu[i].info >> 16) & 1u) : 0);
            if (!same_hit(cpu, gpu[i])) {
                if (c.mismatches < 4)
                    fprintf(stderr, "  %s mode %d ray %u o (%.9g %.9g %.9g) d (%.9g %.9g %.9g) [%.9g, %.9g]: "
                            "gpu (%.9g, %#x) mirror (%.9g, %#x)\n", label, m, i, r->origin[0], r->origin[1],
                            r->origin[2], r->dir[0], r->dir[1], r->dir[2], r->tmin, r->tmax, gpu[i].t,
                            gpu[i].info, cpu.t, cpu.info);
                ++c.mismatches;
            }
            if (!well_defined(f, r, (roma_trace_mode)m, gpu[i])) {
                if (c.undefined < 4)
                    fprintf(stderr, "  %s mode %d ray %u: ill-defined result (%.9g, %#x) for [%.9g, %.9g]\n",
                            label, m, i, gpu[i].t, gpu[i].info, r->tmin, r->tmax);
                ++c.undefined;
            }
            if (!ray_valid(r) && (gpu[i].info != 0 || gpu[i].t != INFINITY))
                ++c.invalid_hits; /* must be a plain miss: map 0, not folded */
        }
        if (hits)
            memcpy(hits[m], gpu, sizeof(roma_hit) * n);
    }
    c.rays = n;
    free(gpu);
    return c;
}

/* --- 1. crafted rays --- */

/* The exponent k for which d * 2^k has its largest component in [2^127, FLT_MAX]
 * (2^k itself may not be a float: scale with ldexpf). */
static int top_exponent(const float d[3])
{
    float m = fmaxf(fmaxf(fabsf(d[0]), fabsf(d[1])), fabsf(d[2]));
    int e;
    frexpf(m, &e); /* m = f * 2^e, f in [0.5, 1) */
    return 128 - e;
}

static int has_subnormal(const float d[3])
{
    for (int a = 0; a < 3; ++a)
        if (d[a] != 0.0f && fabsf(d[a]) < FLT_MIN)
            return 1;
    return 0;
}

enum { MAX_DIRS = 128 };

static uint32_t hard_directions(uint32_t angular, float dirs[MAX_DIRS][3])
{
    uint32_t n = 0;
#define DIR(x, y, z) (dirs[n][0] = (x), dirs[n][1] = (y), dirs[n][2] = (z), ++n)
    for (int a = 0; a < 3; ++a)
        for (int s = -1; s <= 1; s += 2) {
            dirs[n][0] = dirs[n][1] = dirs[n][2] = 0.0f;
            dirs[n++][a] = (float)s;
        }
    DIR(1.0f, 0.0f, -0.0f);              /* horizon with a negative zero */
    DIR(0.70710678f, 0.70710678f, 0.0f); /* horizon, on the concentric map's diagonal */
    DIR(-0.6f, 0.8f, 0.0f);
    DIR(1.0f, 1.0f, 1.0f);               /* diagonals of the map */
    DIR(-1.0f, 1.0f, 1.0f);
    DIR(1.0f, -1.0f, -1.0f);
    DIR(1e-7f, 0.0f, 1.0f);              /* next to the pole */
    DIR(0.0f, 1e-7f, -1.0f);
    DIR(3.0f, 4.0f, 12.0f);              /* unnormalised */
    DIR(0.001f, -0.002f, 0.003f);
    DIR(1.0f, 1e-40f, 0.0f);             /* subnormal beside normal: as (1, 0, 0) */
    DIR(1e6f, 1e-33f, 0.0f);             /* a ratio below FLT_MIN: as (1, 0, 0) */
    /* Stratum edges and corners of the candidate grid, upper and lower hemisphere. */
    for (uint32_t i = 0; i <= angular && n + 4 < MAX_DIRS - 24; ++i)
        for (uint32_t j = 0; j <= angular && n + 4 < MAX_DIRS - 24; ++j) {
            float d[3];
            roma_square_to_hemisphere((float)i / (float)angular, (float)j / (float)angular, d);
            DIR(d[0], d[1], d[2]);
            DIR(-d[0], -d[1], -d[2]);
        }
    for (int i = 0; i < 4; ++i) { /* random ones */
        float d[3];
        roma_square_to_hemisphere(roma_random(5, (uint32_t)i, 0, 0), roma_random(5, (uint32_t)i, 0, 1), d);
        DIR(d[0], d[1], (i & 1) ? -d[2] : d[2]);
    }
    return n;
#undef DIR
}

/* The GPU's rotation of this frame equals the mirror's, word for word. */
static void check_rotation(const fixture *f, const char *label)
{
    const uint32_t res = f->info.resolution, words = f->info.words_per_texel;
    const uint64_t bom_words = (uint64_t)res * res * words, map_words = bom_words * f->info.map_count;
    uint32_t *bom = malloc(bom_words * sizeof(uint32_t)), *maps = malloc(map_words * sizeof(uint32_t));
    CHECK(bom && maps);
    if (bom && maps) {
        CHECK_RESULT(roma_map_download_bom(f->map, bom, bom_words), ROMA_SUCCESS);
        roma_cpu_rotate(&f->grid, f->frames, bom, maps);
        uint64_t diff = 0;
        for (uint64_t i = 0; i < map_words; ++i)
            diff += maps[i] != f->maps[i];
        printf("%-24s rotation: %llu of %llu words differ from the mirror\n", label, (unsigned long long)diff,
               (unsigned long long)map_words);
        CHECK(diff == 0);
    }
    free(bom);
    free(maps);
}

/* World point of map k's cell coordinates m (roma_shared.h: map -> BOM -> world). */
static void map_point(const fixture *f, uint32_t k, const float m[3], float out[3])
{
    const roma_map_frame *fr = &f->frames[k];
    for (int a = 0; a < 3; ++a) {
        float b = ((fr->map_to_bom_0[a] * m[0] + fr->map_to_bom_1[a] * m[1]) + fr->map_to_bom_2[a] * m[2]) +
                  fr->map_to_bom_3[a];
        out[a] = f->grid.origin[a] + b * f->grid.origin[3];
    }
}

/* Origins at the centre of an occupied cell of each map, traced along that map's
 * candidate and its opposite (so that map is the one selected), snapped and
 * un-snapped: always a hit, and a closest hit at t = tmin exactly, because the
 * origin's own cell holds the tmin point (tmin = 0, -cell/4, and tmin = tmax = 0). */
static void check_inside_occupied(const fixture *f, const char *label)
{
    const uint32_t res = f->info.resolution, words = f->info.words_per_texel;
    uint32_t rays = 0, wrong = 0, cells = 0;
    for (uint32_t k = 0; k < f->info.map_count; ++k) {
        /* The first occupied cell from the middle texel row on. */
        int x = -1, y = -1, c = -1;
        for (uint32_t t = res * res / 2; t < res * res && c < 0; ++t)
            for (uint32_t w = 0; w < words && c < 0; ++w) {
                uint32_t bits = f->maps[((uint64_t)k * res * res + t) * words + w];
                if (bits)
                    x = (int)(t % res), y = (int)(t / res), c = (int)(w * 32 + (uint32_t)__builtin_ctz(bits));
            }
        CHECK(c >= 0);
        if (c < 0)
            continue;
        ++cells;
        const float m[3] = {(float)x + 0.5f, (float)y + 0.5f, (float)c + 0.5f};
        const float cz = f->frames[k].dir[3];
        roma_ray ray;
        map_point(f, k, m, ray.origin);
        const float ranges[3][2] = {{0.0f, INFINITY}, {-0.25f * cz, INFINITY}, {0.0f, 0.0f}};
        for (int side = 0; side < 2; ++side)
            for (int r = 0; r < 3; ++r) {
                for (int a = 0; a < 3; ++a)
                    ray.dir[a] = side ? -f->frames[k].dir[a] : f->frames[k].dir[a];
                ray.tmin = ranges[r][0];
                ray.tmax = ranges[r][1];
                for (int mode = 0; mode < 4; ++mode) {
                    roma_hit h;
                    CHECK_RESULT(roma_map_trace(f->map, (roma_trace_mode)mode, 8, &ray, 1, &h, NULL), ROMA_SUCCESS);
                    int closest = mode == ROMA_TRACE_SNAPPED_CLOSEST || mode == ROMA_TRACE_UNSNAPPED_CLOSEST;
                    int ok = (h.info & ROMA_HIT_FLAG) && ROMA_HIT_MAP(h.info) == k &&
                             ((h.info >> 16) & 1u) == (uint32_t)side && (closest ? h.t == ray.tmin : h.t == INFINITY);
                    if (!ok && wrong < 4)
                        fprintf(stderr, "  %s map %u cell (%d %d %d) side %d mode %d [%g, %g]: t %.9g info %#x\n",
                                label, k, x, y, c, side, mode, ray.tmin, ray.tmax, h.t, h.info);
                    wrong += !ok;
                    ++rays;
                }
            }
    }
    printf("%-24s origins in occupied cells of %u maps: %u of %u traces not a hit at tmin\n", label, cells, wrong,
           rays);
    CHECK(wrong == 0);
}

static void check_crafted(roma_context *ctx, const roma_scene *scene, uint32_t res, uint32_t angular,
                          roma_map_frame_desc frame)
{
    fixture f;
    if (!fixture_open(ctx, scene, (roma_map_desc){.resolution = res, .angular = angular}, frame, &f))
        return;
    const float cell = f.info.grid_cell;
    float dirs[MAX_DIRS][3];
    uint32_t n_dirs = hard_directions(angular, dirs);
    const uint32_t n_regular = n_dirs;

    /* An occupied BOM cell, for origins inside geometry. */
    uint64_t bom_words = (uint64_t)res * res * (res / 32);
    uint32_t *bom = malloc(bom_words * sizeof(uint32_t));
    CHECK_RESULT(roma_map_download_bom(f.map, bom, bom_words), ROMA_SUCCESS);
    float occupied[3] = {0.5f, 0.5f, 0.5f};
    int found = 0;
    for (uint64_t i = bom_words / 2; i < bom_words && !found; ++i)
        if (bom[i]) {
            uint32_t texel = (uint32_t)(i / (res / 32)), z = (uint32_t)(i % (res / 32)) * 32 + (uint32_t)__builtin_ctz(bom[i]);
            occupied[0] = (float)(texel % res) + 0.5f, occupied[1] = (float)(texel / res) + 0.5f;
            occupied[2] = (float)z + 0.5f;
            found = 1;
        }
    CHECK(found);
    free(bom);

    /* Origins in BOM cell coordinates. */
    const float h = (float)(res / 2);
    const float origins[][3] = {
        {h + 0.3f, h + 0.6f, h + 0.45f}, /* generic */
        {h, h, h},                       /* cell corner */
        {h, h, h + 0.5f},                /* cell edge */
        {h + 0.5f, h + 0.5f, h},         /* cell face */
        {h + 0.5f, h + 0.5f, 32.0f},     /* face between words 0 and 1 (the grid's top face at RES 32) */
        {h + 0.5f, h + 0.5f, 32.0f - 1e-3f},
        {h + 0.5f, h + 0.5f, (float)res - 32.0f}, /* face between the last two words */
        {0.0f, 0.0f, 0.0f},              /* grid corner */
        {(float)res, (float)res, (float)res},
        {0.5f, h, (float)res},           /* on the boundary */
        {-0.5f, h + 0.5f, h + 0.5f},     /* outside, entering along +x */
        {h + 0.5f, h + 0.5f, -2.0f * (float)res}, /* far outside */
        {3.0f * (float)res, -2.0f * (float)res, h}, /* outside, missing */
        {occupied[0], occupied[1], occupied[2]},
        {occupied[0] + 0.49f, occupied[1] - 0.49f, occupied[2] + 0.49f},
    };
    const uint32_t n_cell_origins = sizeof origins / sizeof origins[0];
    /* World-space origins so far out that map coordinates overflow. */
    const float far[][3] = {{1e38f, 1e38f, 1e38f}, {-3e38f, 1e20f, 0.0f}, {1e10f, -1e10f, 1e10f}};
    const uint32_t n_origins = n_cell_origins + sizeof far / sizeof far[0];
    const float ranges[][2] = {
        {0.0f, INFINITY}, {0.0f, 0.0f}, {3.0f, 3.0f}, {-5.0f, INFINITY}, {-INFINITY, INFINITY},
        {0.0f, 0.5f}, {5.0f, 2.0f}, {INFINITY, INFINITY}, {NAN, INFINITY}, {0.0f, NAN},
        {0.25f, 40.0f}, {-INFINITY, -1.0f},
    };
    const uint32_t n_ranges = sizeof ranges / sizeof ranges[0];

    /* Invalid directions come after the regular and scaled ones. */
    uint32_t n_scaled = 4 * n_regular;
    const float invalid[][3] = {
        {0.0f, 0.0f, 0.0f}, {-0.0f, 0.0f, -0.0f}, {NAN, 0.0f, 1.0f}, {0.0f, 0.0f, NAN},
        {INFINITY, 0.0f, 0.0f}, {1.0f, -INFINITY, 1.0f}, {1e-40f, -1e-41f, 0.0f},
    };
    const uint32_t n_invalid = sizeof invalid / sizeof invalid[0];
    const uint32_t n_all_dirs = n_regular + n_scaled + n_invalid;
    const uint32_t n = n_all_dirs * n_origins * n_ranges;
    roma_ray *rays = malloc(sizeof(roma_ray) * n);
    uint32_t i = 0;
    for (uint32_t d = 0; d < n_all_dirs; ++d) {
        float dir[3];
        if (d < n_regular) {
            memcpy(dir, dirs[d], sizeof dir);
        } else if (d < n_regular + n_scaled) {
            /* 2^100, 2^-100 (squares overflow / underflow), the power of two that puts
             * the largest component in [2^127, FLT_MAX] and 2^-140 (subnormal
             * components; below FLT_MIN they count as zero, see direction_valid). */
            uint32_t base = (d - n_regular) % n_regular, which = (d - n_regular) / n_regular;
            int k = which == 0 ? 100 : which == 1 ? -100 : which == 2 ? top_exponent(dirs[base]) : -140;
            for (int a = 0; a < 3; ++a)
                dir[a] = ldexpf(dirs[base][a], k);
        } else {
            memcpy(dir, invalid[d - n_regular - n_scaled], sizeof dir);
        }
        for (uint32_t o = 0; o < n_origins; ++o)
            for (uint32_t r = 0; r < n_ranges; ++r, ++i) {
                if (o < n_cell_origins)
                    grid_point(&f, origins[o][0], origins[o][1], origins[o][2], rays[i].origin);
                else
                    memcpy(rays[i].origin, far[o - n_cell_origins], sizeof rays[i].origin);
                memcpy(rays[i].dir, dir, sizeof dir);
                rays[i].tmin = ranges[r][0] * cell;
                rays[i].tmax = ranges[r][1] * cell;
            }
    }
    roma_hit *hits[4];
    for (int m = 0; m < 4; ++m)
        hits[m] = malloc(sizeof(roma_hit) * n);
    char label[64];
    snprintf(label, sizeof label, "RES %u A %u frame %u", res, angular, frame.frame);
    trace_counts c = trace_checked(&f, rays, n, 2 * res, hits, label);
    check_rotation(&f, label);
    check_inside_occupied(&f, label);

    /* A direction scaled by 2^100, 2^-100 or up to the largest floats traces exactly as
     * the unscaled one (unless it had subnormal components: scaled up, they are not). */
    uint32_t scaled_diff = 0, hit_count = 0;
    const uint32_t per_dir = n_origins * n_ranges;
    for (uint32_t d = n_regular; d < n_regular + 3 * n_regular; ++d) {
        uint32_t base = (d - n_regular) % n_regular;
        if (has_subnormal(dirs[base]))
            continue;
        for (uint32_t j = 0; j < per_dir; ++j)
            for (int m = 0; m < 4; ++m)
                scaled_diff += !same_hit(hits[m][d * per_dir + j], hits[m][base * per_dir + j]);
    }
    for (uint32_t j = 0; j < n_regular * per_dir; ++j)
        hit_count += hits[ROMA_TRACE_SNAPPED_ANY][j].info & ROMA_HIT_FLAG;
    /* Directions that differ only below FLT_MIN trace as (1, 0, 0) (index 1). */
    for (uint32_t d = 0; d < n_regular; ++d) {
        const float *v = dirs[d];
        if (!(v[0] >= 1.0f && v[1] > 0.0f && v[1] < 1e-30f && v[2] == 0.0f))
            continue;
        for (uint32_t j = 0; j < per_dir; ++j)
            for (int m = 0; m < 4; ++m)
                scaled_diff += !same_hit(hits[m][d * per_dir + j], hits[m][1 * per_dir + j]);
    }
    printf("%-24s %6u rays x 4 modes: %u mirror mismatches, %u ill-defined, %u selection "
           "differences (at most %.3g of the square from a stratum edge), %u invalid rays not a plain miss, "
           "%u scaled-direction differences, %u snapped hits\n", label, n, c.mismatches, c.undefined, c.selection,
           (double)c.widest, c.invalid_hits, scaled_diff, hit_count);
    CHECK(c.mismatches == 0);
    CHECK(c.undefined == 0);
    CHECK(c.invalid_hits == 0);
    CHECK(scaled_diff == 0);
    CHECK(hit_count > 0 && hit_count < n_regular * per_dir);
    for (int m = 0; m < 4; ++m)
        free(hits[m]);
    free(rays);
    fixture_close(&f);
}

/* --- 2. bit ranges on word boundaries, exact against Embree --- */

static int in_list(uint32_t v, const uint32_t *list, uint32_t n)
{
    for (uint32_t i = 0; i < n; ++i)
        if (list[i] == v)
            return 1;
    return 0;
}

static void check_word_boundaries(roma_context *ctx, uint32_t res)
{
    /* Plates at the centres of chosen cells: with margin 0.5 and no jitter, the unit
     * cube's z = j / (RES - 1) is the centre of cell j. */
    const uint32_t plate_cells[] = {0, 31, 32, 64, 95, 159, 160, res - 1};
    mesh *m = calloc(1, sizeof *m);
    for (uint32_t p = 0; p < sizeof plate_cells / sizeof plate_cells[0]; ++p)
        if (plate_cells[p] < res)
            add_plate(m, 0.0f, 0.0f, 1.0f, 1.0f, (float)((double)plate_cells[p] / (double)(res - 1)));
    roma_scene *scene = make_scene(m, 1.0, NULL);
    free(m);
    roma_ref *ref = NULL;
    if (scene)
        CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    fixture f;
    if (!ref || !fixture_open(ctx, scene, (roma_map_desc){.resolution = res, .angular = 1, .margin_cells = 0.5f},
                              (roma_map_frame_desc){0}, &f)) {
        roma_ref_destroy(ref);
        roma_scene_destroy(scene);
        return;
    }
    const uint32_t ends_all[] = {0, 1, 30, 31, 32, 33, 62, 63, 64, 65, 95, 96, 127, 128, 159, 160, 191, 192,
                                 res - 2, res - 1};
    uint32_t ends[32], n_ends = 0;
    for (uint32_t e = 0; e < sizeof ends_all / sizeof ends_all[0]; ++e)
        if (ends_all[e] < res && !in_list(ends_all[e], ends, n_ends))
            ends[n_ends++] = ends_all[e];

    const float cell = f.info.grid_cell;
    const float columns[2][2] = {{(float)(res / 2) + 0.5f, (float)(res / 2) + 0.5f}, {1.5f, (float)res - 1.5f}};
    uint32_t cap = n_ends * n_ends * 2 * 2 * 2, n = 0;
    roma_ray *rays = malloc(sizeof(roma_ray) * cap);
    for (uint32_t a = 0; a < n_ends; ++a)
        for (uint32_t b = 0; b < n_ends; ++b) {
            if (ends[b] < ends[a])
                continue;
            float lo = (float)ends[a], hi = (float)ends[b];
            for (int col = 0; col < 2; ++col)
                for (int variant = 0; variant < 4; ++variant) {
                    roma_ray *r = &rays[n++];
                    /* Cells [a, b]: up from a + 1/4 or down from b + 3/4, either starting
                     * there (tmin 0) or starting at the grid's edge and cut by tmin. */
                    int up = variant & 1, from_edge = variant & 2;
                    float start = from_edge ? (up ? 0.25f : (float)res - 0.25f) : (up ? lo + 0.25f : hi + 0.75f);
                    float first = up ? lo + 0.25f : hi + 0.75f, last = up ? hi + 0.75f : lo + 0.25f;
                    grid_point(&f, columns[col][0], columns[col][1], start, r->origin);
                    r->dir[0] = r->dir[1] = 0.0f;
                    r->dir[2] = up ? 1.0f : -1.0f;
                    r->tmin = fabsf(first - start) * cell;
                    r->tmax = fabsf(last - start) * cell;
                }
        }
    roma_hit *hits[4];
    for (int k = 0; k < 4; ++k)
        hits[k] = malloc(sizeof(roma_hit) * n);
    char label[64];
    snprintf(label, sizeof label, "word ranges RES %u", res);
    trace_counts c = trace_checked(&f, rays, n, 4, hits, label);
    CHECK(c.mismatches == 0 && c.undefined == 0);

    float *orgs = malloc(sizeof(float) * 3 * n), *dirs = malloc(sizeof(float) * 3 * n);
    float *tmins = malloc(sizeof(float) * n), *tmaxs = malloc(sizeof(float) * n), *ref_t = malloc(sizeof(float) * n);
    for (uint32_t i = 0; i < n; ++i) {
        memcpy(orgs + 3 * i, rays[i].origin, 3 * sizeof(float));
        memcpy(dirs + 3 * i, rays[i].dir, 3 * sizeof(float));
        tmins[i] = rays[i].tmin;
        tmaxs[i] = rays[i].tmax;
    }
    roma_ref_intersect_batch(ref, n, orgs, dirs, tmins, tmaxs, ref_t);
    uint32_t wrong_hit = 0, wrong_t = 0, ref_hits = 0;
    for (uint32_t i = 0; i < n; ++i) {
        int expect = isfinite(ref_t[i]);
        ref_hits += (uint32_t)expect;
        /* The closest hit is the entry face of the plate's cell: half a cell early. */
        float expect_t = fmaxf(ref_t[i] - 0.5f * cell, rays[i].tmin);
        for (int k = 0; k < 4; ++k) {
            if (((hits[k][i].info & ROMA_HIT_FLAG) != 0) != expect) {
                if (wrong_hit++ < 4)
                    fprintf(stderr, "  %s mode %d ray %u: roma %s, Embree t %.9g in [%.9g, %.9g]\n", label, k, i,
                            (hits[k][i].info & 1) ? "hit" : "miss", ref_t[i], rays[i].tmin, rays[i].tmax);
            } else if (expect && (k & 1) && !(fabsf(hits[k][i].t - expect_t) <= 1e-3f * cell)) {
                if (wrong_t++ < 4)
                    fprintf(stderr, "  %s mode %d ray %u: roma t %.9g, expected %.9g\n", label, k, i, hits[k][i].t,
                            expect_t);
            }
        }
    }
    printf("%-24s %6u rays: %u hit by Embree; %u hit/miss and %u distance disagreements\n", label, n, ref_hits,
           wrong_hit, wrong_t);
    CHECK(ref_hits > 0 && ref_hits < n);
    CHECK(wrong_hit == 0);
    CHECK(wrong_t == 0);
    free(orgs), free(dirs), free(tmins), free(tmaxs), free(ref_t);
    for (int k = 0; k < 4; ++k)
        free(hits[k]);
    free(rays);
    fixture_close(&f);
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
}

/* --- 3. scale and placement --- */

/* A closed room (unit cube) with a box inside it. */
static void room_mesh(mesh *m)
{
    const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, blo[3] = {0.3f, 0.3f, 0.2f}, bhi[3] = {0.5f, 0.6f, 0.4f};
    add_box(m, lo, hi);
    add_box(m, blo, bhi);
}

enum { ROOM_RAYS = 4096 };

/* Rays from points of the 1/128 lattice inside the room (exact at 1e5 too), random
 * directions; lengths in units of the unit room. */
static void room_rays(roma_ray *rays, float tmax)
{
    for (uint32_t i = 0; i < ROOM_RAYS; ++i) {
        roma_ray *r = &rays[i];
        for (int a = 0; a < 3; ++a)
            r->origin[a] = (float)(16 + (int)(roma_random(3, i, 0, (uint32_t)a) * 96.0f)) / 128.0f;
        float d[3];
        roma_square_to_hemisphere(roma_random(3, i, 1, 0), roma_random(3, i, 1, 1), d);
        r->dir[0] = d[0], r->dir[1] = d[1], r->dir[2] = (i & 1) ? -d[2] : d[2];
        r->tmin = 0.0f;
        r->tmax = tmax;
    }
}

typedef struct room_error {
    double agreement;    /* snapped any-hit within tmax vs Embree on the snapped ray */
    double median, p99;  /* |closest-hit error| in trace cells vs Embree on the snapped ray */
    double trace_cell;   /* world units */
    uint32_t mirror_diff; /* un-snapped closest hits that differ from the C mirror's on the same maps */
    uint64_t map_bits;    /* occupied cells over all maps */
} room_error;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Traces the room (scaled by s, moved by off) and, with_reference, measures it against
 * Embree. out_any and out_closest (optional) receive the snapped results. */
static room_error measure_room(roma_context *ctx, double s, const double off[3], uint32_t res,
                               int with_reference, roma_hit *out_any, roma_hit *out_closest,
                               roma_hit *out_unsnapped)
{
    room_error e = {0};
    mesh *m = calloc(1, sizeof *m);
    room_mesh(m);
    roma_scene *scene = make_scene(m, s, off);
    free(m);
    roma_ref *ref = NULL;
    if (scene && with_reference)
        CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    fixture f;
    roma_map_frame_desc frame = {.frame = 3, .seed = 11, .jitter_grid = 1, .jitter_directions = 1};
    if ((with_reference && !ref) || !fixture_open(ctx, scene, (roma_map_desc){.resolution = res, .angular = 4}, frame, &f)) {
        roma_ref_destroy(ref);
        roma_scene_destroy(scene);
        return e;
    }
    static roma_ray rays[2][ROOM_RAYS];
    room_rays(rays[0], 0.3f);
    room_rays(rays[1], INFINITY);
    for (int k = 0; k < 2; ++k)
        for (uint32_t i = 0; i < ROOM_RAYS; ++i)
            for (int a = 0; a < 3; ++a) {
                rays[k][i].origin[a] = (float)((double)rays[k][i].origin[a] * s + (off ? off[a] : 0.0));
                if (a == 0)
                    rays[k][i].tmax = (float)((double)rays[k][i].tmax * s);
            }
    static roma_hit any[ROOM_RAYS], closest[ROOM_RAYS];
    CHECK_RESULT(roma_map_trace(f.map, ROMA_TRACE_SNAPPED_ANY, 0, rays[0], ROOM_RAYS, any, NULL), ROMA_SUCCESS);
    CHECK_RESULT(roma_map_trace(f.map, ROMA_TRACE_SNAPPED_CLOSEST, 0, rays[1], ROOM_RAYS, closest, NULL),
                 ROMA_SUCCESS);
    if (out_unsnapped) {
        CHECK_RESULT(roma_map_trace(f.map, ROMA_TRACE_UNSNAPPED_CLOSEST, 64, rays[1], ROOM_RAYS, out_unsnapped, NULL),
                     ROMA_SUCCESS);
        for (uint32_t i = 0; i < ROOM_RAYS; ++i) {
            /* On a stratum edge, where the GPU and the mirror may select apart, the GPU's map. */
            int folded;
            uint32_t k = roma_cpu_select_map(rays[1][i].dir, f.info.angular, &folded);
            uint32_t gk = ROMA_HIT_MAP(out_unsnapped[i].info);
            int gfolded = (out_unsnapped[i].info & ROMA_HIT_FOLDED) != 0;
            int edge = k != gk || folded != gfolded;
            roma_hit cpu = roma_cpu_trace(&f.grid, f.frames, f.maps, &rays[1][i], ROMA_TRACE_UNSNAPPED_CLOSEST, 64,
                                          edge ? (int)gk : -1, edge ? gfolded : 0);
            e.mirror_diff += !same_hit(out_unsnapped[i], cpu);
        }
    }
    for (uint64_t w = 0; w < (uint64_t)f.info.map_count * f.info.resolution * f.info.resolution * f.grid.dims[1]; ++w)
        e.map_bits += (uint64_t)__builtin_popcount(f.maps[w]);
    static double err[ROOM_RAYS];
    uint32_t agree = 0, n_err = 0;
    for (uint32_t i = 0; i < ROOM_RAYS && with_reference; ++i) {
        float cand[3];
        roma_map_candidate(f.map, ROMA_HIT_MAP(any[i].info), cand);
        float sign = (any[i].info & 0x10000u) ? -1.0f : 1.0f;
        float d[3] = {sign * cand[0], sign * cand[1], sign * cand[2]};
        int ref_any = roma_ref_occluded(ref, rays[0][i].origin, d, 0.0f, rays[0][i].tmax);
        agree += ref_any == (int)(any[i].info & ROMA_HIT_FLAG);
        roma_map_candidate(f.map, ROMA_HIT_MAP(closest[i].info), cand);
        sign = (closest[i].info & 0x10000u) ? -1.0f : 1.0f;
        float d2[3] = {sign * cand[0], sign * cand[1], sign * cand[2]};
        roma_ref_hit rh;
        if (roma_ref_intersect(ref, rays[1][i].origin, d2, 0.0f, INFINITY, &rh) && (closest[i].info & ROMA_HIT_FLAG))
            err[n_err++] = fabs((double)closest[i].t - (double)rh.t) / (double)f.info.trace_cell;
    }
    qsort(err, n_err, sizeof err[0], cmp_double);
    e.agreement = (double)agree / ROOM_RAYS;
    e.trace_cell = f.info.trace_cell;
    e.median = n_err ? err[n_err / 2] : INFINITY;
    e.p99 = n_err ? err[(n_err * 99) / 100] : INFINITY;
    if (with_reference)
        CHECK(n_err > ROOM_RAYS * 95 / 100); /* a closed room: nearly every ray hits */
    if (out_any)
        memcpy(out_any, any, sizeof any);
    if (out_closest)
        memcpy(out_closest, closest, sizeof closest);
    fixture_close(&f);
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
    return e;
}

static void check_scale_and_placement(roma_context *ctx)
{
    const uint32_t res = 128;
    static roma_hit any0[ROOM_RAYS], closest0[ROOM_RAYS], any1[ROOM_RAYS], closest1[ROOM_RAYS],
        unsnapped0[ROOM_RAYS], unsnapped1[ROOM_RAYS];
    room_error base = measure_room(ctx, 1.0, NULL, res, 1, any0, closest0, unsnapped0);
    printf("room, unit scale:             agreement %.4f, closest error median %.3f p99 %.3f trace cells; "
           "%u un-snapped hits differ from the mirror's\n", base.agreement, base.median, base.p99, base.mirror_diff);
    CHECK(base.mirror_diff == 0);
    /* The unit room itself: measured 0.9807, 0.600 and 2.723, with the margins below. */
    CHECK(base.agreement >= 0.9807 - 0.005);
    CHECK(base.median <= 0.600 + 0.05);
    CHECK(base.p99 <= 2.723 + 0.25);

    /* Powers of two: every quantity scales exactly, so must every result, down to the
     * smallest and up to the largest scenes a grid accepts (map_params.h; no Embree
     * there: its own epsilons are not meant for 1e-33 or 1e37). */
    const int exponents[] = {-105, -10, 13, 123};
    for (int i = 0; i < 4; ++i) {
        double s = ldexp(1.0, exponents[i]);
        room_error scaled = measure_room(ctx, s, NULL, res, 0, any1, closest1, unsnapped1);
        uint32_t diff = 0;
        for (uint32_t r = 0; r < ROOM_RAYS; ++r) {
            uint32_t d = any0[r].info != any1[r].info || closest0[r].info != closest1[r].info;
            d += (closest0[r].info & 1) && (float)((double)closest0[r].t * s) != closest1[r].t;
            d += unsnapped0[r].info != unsnapped1[r].info;
            d += (unsnapped0[r].info & 1) && (float)((double)unsnapped0[r].t * s) != unsnapped1[r].t;
            if (d && diff < 3)
                fprintf(stderr, "  2^%d ray %u: any %#x / %#x, closest %#x %.9g / %#x %.9g, un-snapped %#x %.9g / "
                        "%#x %.9g (unit room / scaled, t unscaled)\n", exponents[i], r, any0[r].info, any1[r].info,
                        closest0[r].info, closest0[r].t, closest1[r].info, (double)closest1[r].t / s,
                        unsnapped0[r].info, unsnapped0[r].t, unsnapped1[r].info, (double)unsnapped1[r].t / s);
            diff += d;
        }
        printf("room scaled by 2^%-3d:         %u results differ from the unit room's (scaled); occupied cells "
               "%llu (unit room %llu); %u un-snapped hits differ from the mirror's\n", exponents[i], diff,
               (unsigned long long)scaled.map_bits, (unsigned long long)base.map_bits, scaled.mirror_diff);
        CHECK(diff == 0);
        CHECK(scaled.map_bits == base.map_bits);
        CHECK(scaled.mirror_diff == 0);
    }

    /* Other scales and far placements: the error against Embree stays that of the unit room. */
    const struct { double s, off[3]; const char *name; } cases[] = {
        {1e-3, {0, 0, 0}, "scaled by 1e-3"},
        {1e4, {0, 0, 0}, "scaled by 1e4"},
        {1.0, {1e4, -1e4, 1e4}, "moved to (1e4,-1e4,1e4)"},
        {100.0, {-1e5, 1e5, 0}, "x100 at (-1e5,1e5,0)"},
        {1.0, {1e5, -1e5, 1e5}, "moved to (1e5,-1e5,1e5)"},
        {10.0, {1e6, -1e6, 1e6}, "x10 at (1e6,-1e6,1e6)"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        room_error e = measure_room(ctx, cases[i].s, cases[i].off, res, 1, NULL, NULL, NULL);
        /* Far out, the scene's own vertices are rounded to float: half an ulp of the
         * coordinates (2^-8 at 1e5), in trace cells, is what the input itself lost. */
        double far = fmax(fmax(fabs(cases[i].off[0]), fabs(cases[i].off[1])), fabs(cases[i].off[2])) + cases[i].s;
        double input = 0.5 * ((double)nextafterf((float)far, INFINITY) - (double)(float)far) / e.trace_cell;
        printf("room %-24s agreement %.4f, closest error median %.3f p99 %.3f trace cells "
               "(input rounding %.3f)\n", cases[i].name, e.agreement, e.median, e.p99, input);
        CHECK(e.agreement >= base.agreement - 0.005);
        CHECK(e.median <= base.median + 0.05 + input);
        CHECK(e.p99 <= base.p99 + 0.25 + input);
    }
}

/* Scenes beyond the supported range (map_params.h) are refused with a message, at
 * creation and in an update, and a refused update leaves the map as it was. */
static void check_supported_range(roma_context *ctx)
{
    mesh *m = calloc(1, sizeof *m);
    room_mesh(m);
    const struct { int exponent; const char *word; } refused[] = {{127, "within"}, {-120, "too small"}};
    for (int i = 0; i < 2; ++i) {
        roma_scene *scene = make_scene(m, ldexp(1.0, refused[i].exponent), NULL);
        roma_test_log log;
        roma_map *map = (roma_map *)1;
        roma_map_desc desc = {.resolution = 64, .angular = 2, .logger = roma_test_logger(&log)};
        CHECK_RESULT(roma_map_create(ctx, &desc, scene, &map), ROMA_ERROR_INVALID_SCENE);
        CHECK(map == NULL && log.errors == 1 && strstr(log.last, refused[i].word));
        if (map != NULL && map != (roma_map *)1)
            roma_map_destroy(map); /* wrongly accepted: counted above, not leaked */
        roma_scene_destroy(scene);
    }
    roma_scene *scene = make_scene(m, 1.0, NULL);
    fixture f;
    if (fixture_open(ctx, scene, (roma_map_desc){.resolution = 64, .angular = 2}, (roma_map_frame_desc){0}, &f)) {
        static roma_ray rays[ROOM_RAYS];
        static roma_hit before[ROOM_RAYS], after[ROOM_RAYS];
        room_rays(rays, INFINITY);
        CHECK_RESULT(roma_map_trace(f.map, ROMA_TRACE_SNAPPED_CLOSEST, 0, rays, ROOM_RAYS, before, NULL), ROMA_SUCCESS);
        float *huge = malloc(sizeof(float) * 3 * m->vertices);
        for (uint32_t v = 0; v < 3 * m->vertices; ++v)
            huge[v] = m->pos[v] * 0x1p127f;
        CHECK_RESULT(roma_map_build(f.map, &(roma_map_frame_desc){.positions = huge, .vertex_count = m->vertices}, NULL),
                     ROMA_ERROR_INVALID_SCENE);
        free(huge);
        CHECK_RESULT(roma_map_build(f.map, &(roma_map_frame_desc){0}, NULL), ROMA_SUCCESS);
        CHECK_RESULT(roma_map_trace(f.map, ROMA_TRACE_SNAPPED_CLOSEST, 0, rays, ROOM_RAYS, after, NULL), ROMA_SUCCESS);
        uint32_t diff = 0;
        for (uint32_t i = 0; i < ROOM_RAYS; ++i)
            diff += !same_hit(before[i], after[i]);
        printf("supported range: 2^127 and 2^-120 rooms refused; a refused update changed %u of %u results\n", diff,
               ROOM_RAYS);
        CHECK(diff == 0);
        fixture_close(&f);
    }
    roma_scene_destroy(scene);
    free(m);
}

/* --- 4. degenerate scenes --- */

/* Rays straight down onto points (x, y) from height z0 + 0.25, against Embree;
 * RES 64, A = 1 (the candidate is the pole): hit/miss must agree exactly. */
static void check_down_rays(roma_context *ctx, const mesh *m, roma_bom_mode mode, const float (*pts)[2],
                            uint32_t n_pts, float z0, const char *name)
{
    roma_scene *scene = make_scene(m, 1.0, NULL);
    roma_ref *ref = NULL;
    if (scene)
        CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    fixture f;
    if (!ref || !fixture_open(ctx, scene, (roma_map_desc){.resolution = 64, .angular = 1, .bom_mode = mode},
                              (roma_map_frame_desc){0}, &f)) {
        roma_ref_destroy(ref);
        roma_scene_destroy(scene);
        return;
    }
    roma_ray rays[64];
    for (uint32_t i = 0; i < n_pts; ++i) {
        rays[i] = (roma_ray){{pts[i][0], pts[i][1], z0 + 0.25f}, 0.0f, {0.0f, 0.0f, -1.0f}, INFINITY};
    }
    roma_hit *hits[4], storage[4][64];
    for (int k = 0; k < 4; ++k)
        hits[k] = storage[k];
    trace_counts c = trace_checked(&f, rays, n_pts, 128, hits, name);
    CHECK(c.mismatches == 0 && c.undefined == 0);
    uint32_t wrong = 0;
    for (uint32_t i = 0; i < n_pts; ++i) {
        roma_ref_hit rh;
        int expect = roma_ref_intersect(ref, rays[i].origin, rays[i].dir, 0.0f, INFINITY, &rh);
        for (int k = 0; k < 4; ++k) {
            int got = (hits[k][i].info & ROMA_HIT_FLAG) != 0;
            /* A closest hit is the top face of the highest cell of the surface in the
             * ray's column: one cell above it, plus the rise of the surface across the
             * column's footprint, |dz/dx| + |dz/dy| cells (a cell touching the surface at
             * the footprint's edge counts). */
            const float *n = rh.geometric_normal;
            float rise = expect ? (fabsf(n[0]) + fabsf(n[1])) / fmaxf(fabsf(n[2]), 1e-6f) : 0.0f;
            int bad = got != expect ||
                      (got && (k & 1) && !(fabsf(hits[k][i].t - rh.t) <= (1.0f + rise) * f.info.grid_cell + 1e-4f));
            if (bad && wrong++ < 4)
                fprintf(stderr, "  %s mode %d point (%g, %g): roma %s t %g, Embree %s t %g\n", name, k, pts[i][0],
                        pts[i][1], got ? "hit" : "miss", hits[k][i].t, expect ? "hit" : "miss",
                        expect ? rh.t : INFINITY);
        }
    }
    printf("%-24s %u points: %u disagreements with Embree\n", name, n_pts, wrong);
    CHECK(wrong == 0);
    fixture_close(&f);
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
}

static void check_degenerate_scenes(roma_context *ctx)
{
    /* Points well inside (>= 3 cells) and well outside the shapes below. */
    const float pts[][2] = {{0.2f, 0.2f}, {0.5f, 0.3f}, {0.3f, 0.5f}, {0.1f, 0.7f}, {0.7f, 0.1f},
                            {0.8f, 0.8f}, {0.95f, 0.9f}, {0.6f, 0.7f}};
    const uint32_t n_pts = sizeof pts / sizeof pts[0];
    mesh *m = calloc(1, sizeof *m);

    /* Flat: one triangle in z = 0.5 (zero extent along z). Hits where x + y < 1. */
    const float a[3] = {0, 0, 0.5f}, b[3] = {1, 0, 0.5f}, c[3] = {0, 1, 0.5f};
    add_triangle(m, a, b, c);
    check_down_rays(ctx, m, ROMA_BOM_UNION3, pts, n_pts, 0.5f, "flat triangle");
    check_down_rays(ctx, m, ROMA_BOM_CONSERVATIVE, pts, n_pts, 0.5f, "flat (conservative)");

    /* One tilted triangle. */
    memset(m, 0, sizeof *m);
    const float ta[3] = {0, 0, 0}, tb[3] = {1, 0, 0.3f}, tc[3] = {0, 1, 0.6f};
    add_triangle(m, ta, tb, tc);
    check_down_rays(ctx, m, ROMA_BOM_UNION3, pts, n_pts, 0.6f, "tilted triangle");

    /* A floor, a sub-cell triangle (a fifth of a cell) and a sliver (1e-4 wide)
     * above it: a conservative BOM keeps both. */
    memset(m, 0, sizeof *m);
    add_plate(m, 0.0f, 0.0f, 1.0f, 1.0f, 0.0f);
    const float cell = 1.0f / 62.0f, s = 0.2f * cell;
    const float sa[3] = {0.5f, 0.5f, 0.6f}, sb[3] = {0.5f + s, 0.5f, 0.6f}, sc[3] = {0.5f, 0.5f + s, 0.6f};
    add_triangle(m, sa, sb, sc);
    const float la[3] = {0.1f, 0.9f, 0.8f}, lb[3] = {0.9f, 0.9f, 0.8f}, lc[3] = {0.9f, 0.9001f, 0.8f};
    add_triangle(m, la, lb, lc);
    const float up[3] = {0, 0, 1}, top[3] = {0.05f, 0.05f, 1.0f};
    add_triangle(m, up, up, top); /* zero area: kept, hits nothing, sets the height */
    /* Points on the sliver's midline: its width at x is 1e-4 (x - 0.1) / 0.8. */
    float sub_pts[4][2] = {{0.5f + 0.05f * cell, 0.5f + 0.05f * cell}, {0.3f, 0}, {0.5f, 0}, {0.85f, 0}};
    for (int i = 1; i < 4; ++i)
        sub_pts[i][1] = 0.9f + 0.5e-4f * (sub_pts[i][0] - 0.1f) / 0.8f;
    check_down_rays(ctx, m, ROMA_BOM_CONSERVATIVE, (const float (*)[2])sub_pts, 4, 0.8f, "sub-cell + sliver");
    /* The same without the floor, so that any-hit queries must find the small shapes
     * themselves, plus two points well away from them (misses). The two plate
     * triangles (the floor) are dropped by rebuilding from the other triangles. */
    mesh *nf = calloc(1, sizeof *nf);
    for (uint32_t t = 2; t < m->triangles; ++t)
        add_triangle(nf, m->pos + 3 * m->idx[3 * t], m->pos + 3 * m->idx[3 * t + 1], m->pos + 3 * m->idx[3 * t + 2]);
    const float grid_corner[3] = {0.0f, 0.0f, 0.0f}; /* zero area: keeps the grid's extent as before */
    add_triangle(nf, grid_corner, grid_corner, grid_corner);
    float nf_pts[6][2];
    memcpy(nf_pts, sub_pts, sizeof sub_pts);
    nf_pts[4][0] = 0.2f, nf_pts[4][1] = 0.2f;
    nf_pts[5][0] = 0.7f, nf_pts[5][1] = 0.3f;
    check_down_rays(ctx, nf, ROMA_BOM_CONSERVATIVE, (const float (*)[2])nf_pts, 6, 0.8f, "sub-cell + sliver, no floor");
    free(nf);

    /* A triangle across the whole grid, through a room. */
    memset(m, 0, sizeof *m);
    room_mesh(m);
    const float ha[3] = {-0.0f, 1.0f, 1.0f}, hb[3] = {1.0f, 0.0f, 1.0f}, hc[3] = {1.0f, 1.0f, 0.0f};
    add_triangle(m, ha, hb, hc);
    const float room_pts[][2] = {{0.9f, 0.9f}, {0.7f, 0.9f}, {0.95f, 0.6f}, {0.2f, 0.2f}};
    check_down_rays(ctx, m, ROMA_BOM_UNION3, room_pts, 4, 0.7f, "grid-wide triangle");
    free(m);
}

/* --- jitter and frame counters --- */

static void check_frames(roma_context *ctx, const roma_scene *scene)
{
    /* Frame counters and seeds at the ends of their range: candidates stay unit and in
     * their strata, the grid jitter stays within half a cell. */
    const uint32_t values[] = {0u, 1u, 0x7fffffffu, 0x80000000u, 0xfffffffeu, 0xffffffffu};
    roma_map *map = NULL;
    CHECK_RESULT(roma_map_create(ctx, &(roma_map_desc){.resolution = 32, .angular = 5}, scene, &map), ROMA_SUCCESS);
    if (!map)
        return;
    CHECK_RESULT(roma_map_build(map, &(roma_map_frame_desc){0}, NULL), ROMA_SUCCESS);
    roma_map_info still;
    roma_map_get_info(map, &still);
    uint32_t bad = 0;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) {
            roma_map_frame_desc frame = {.frame = values[i], .seed = values[j], .jitter_grid = 1, .jitter_directions = 1};
            CHECK_RESULT(roma_map_build(map, &frame, NULL), ROMA_SUCCESS);
            roma_map_info info;
            roma_map_get_info(map, &info);
            for (int a = 0; a < 3; ++a)
                bad += !(fabsf(info.grid_origin[a] - still.grid_origin[a]) <= 0.5f * info.grid_cell * 1.0001f);
            for (uint32_t k = 0; k < info.map_count; ++k) {
                float d[3];
                roma_map_candidate(map, k, d);
                int folded;
                bad += roma_direction_to_map(d, info.angular, &folded) != k || folded;
                bad += !(fabsf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - 1.0f) < 1e-5f);
            }
        }
    printf("frame/seed wrap: %u bad candidates or grid offsets over 36 builds\n", bad);
    CHECK(bad == 0);
    roma_map_destroy(map);
}

/* --- rays that start on a cell face: the distance's zero and its range --- */

/* Closest hits of rays whose origins lie exactly on BOM cell faces next to plates (the map
 * axis-aligned: A 1, no jitter, so the faces are the maps' texel faces too), along the axes
 * and nearly so, with [tmin, tmax] of [0, inf), [-10, -10], [0, 0] and [-0, inf): the GPU and
 * the mirror agree bit for bit (a zero distance is +0 on both: C's fmaxf and GLSL's max pick
 * different zeros of -0 and +0, and a tmin of -0 came back as -0 from the device) and every distance lies in [tmin, tmax] exactly (an origin on a plate's
 * face with tmin = tmax = -10 gave 0). */
static void check_face_origins(roma_context *ctx)
{
    mesh m = {0};
    add_plate(&m, 0.0f, 0.0f, 32.0f, 32.0f, 15.5f);
    const float lo[3] = {15.5f, 4.0f, 4.0f}, hi[3] = {15.5f + 1e-3f, 28.0f, 28.0f};
    add_box(&m, lo, hi);
    add_plate(&m, 0.0f, 0.0f, 32.0f, 32.0f, 0.0f);
    add_plate(&m, 0.0f, 0.0f, 32.0f, 32.0f, 32.0f);
    roma_scene *scene = make_scene(&m, 1.0, NULL);
    const uint32_t angulars[2] = {1, 2};
    uint32_t rays_total = 0, negative_zero = 0, outside = 0, mismatches = 0;
    for (int ai = 0; ai < 2; ++ai) {
        fixture f;
        if (!fixture_open(ctx, scene, (roma_map_desc){.resolution = 32, .angular = angulars[ai]},
                          (roma_map_frame_desc){0}, &f))
            continue;
        enum { N = 4096 };
        roma_ray *rays = calloc(N, sizeof *rays);
        roma_hit *hits[4];
        for (int k = 0; k < 4; ++k)
            hits[k] = calloc(N, sizeof(roma_hit));
        static const float dirs[8][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1},
                                         {1, 0, 3e-38f}, {-1, 1e-7f, 0}};
        static const float ranges[4][2] = {{0.0f, INFINITY}, {-10.0f, -10.0f}, {0.0f, 0.0f}, {-0.0f, INFINITY}};
        uint32_t n = 0;
        for (uint32_t i = 0; n < N; ++i) {
            const uint32_t c = i % 64, d = (i / 64) % 8, r = (i / 512) % 4;
            /* integer BOM coordinates near the plates: on cell faces in every axis */
            const float g[3] = {(float)(12 + c % 8), (float)(10 + (c / 8) % 8), (float)(13 + (i / 1536) % 6)};
            grid_point(&f, g[0], g[1], g[2], rays[n].origin);
            memcpy(rays[n].dir, dirs[d], sizeof rays[n].dir);
            rays[n].tmin = ranges[r][0];
            rays[n].tmax = ranges[r][1];
            ++n;
        }
        trace_counts tc = trace_checked(&f, rays, n, 8, hits, "face origins");
        mismatches += tc.mismatches + tc.undefined;
        for (int mode = 1; mode < 4; mode += 2) /* the closest-hit modes */
            for (uint32_t i = 0; i < n; ++i) {
                const roma_hit h = hits[mode][i];
                if (!(h.info & ROMA_HIT_FLAG))
                    continue;
                negative_zero += h.t == 0.0f && signbit(h.t);
                outside += !(h.t >= rays[i].tmin && h.t <= rays[i].tmax);
            }
        rays_total += 4 * n;
        for (int k = 0; k < 4; ++k)
            free(hits[k]);
        free(rays);
        fixture_close(&f);
    }
    printf("face origins: %u rays, %u GPU/mirror mismatches or ill-defined results, %u closest hits at -0, "
           "%u outside [tmin, tmax]\n", rays_total, mismatches, negative_zero, outside);
    CHECK(mismatches == 0 && negative_zero == 0 && outside == 0);
    roma_scene_destroy(scene);
}

int main(void)
{
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_ray_hard_cases");
    roma_scene *cornell = NULL;
    CHECK_RESULT(roma_scene_create_builtin("cornell", NULL, &cornell), ROMA_SUCCESS);
    const uint32_t resolutions[] = {32, 64, 128, 256};
    for (int i = 0; i < 4; ++i)
        check_crafted(ctx, cornell, resolutions[i], i == 3 ? 2 : 3 + (uint32_t)i,
                      (roma_map_frame_desc){.frame = 0xffffffffu - (uint32_t)i, .seed = 7, .jitter_grid = 1,
                                            .jitter_directions = 1});
    check_crafted(ctx, cornell, 64, 1, (roma_map_frame_desc){0}); /* the pole map, no jitter */
    for (int i = 0; i < 4; ++i)
        check_word_boundaries(ctx, resolutions[i]);
    check_scale_and_placement(ctx);
    check_supported_range(ctx);
    check_degenerate_scenes(ctx);
    check_frames(ctx, cornell);
    check_face_origins(ctx);
    /* The crafted directions (scaled to 2^100 and past 2^127, subnormal components, axes)
     * through the corrected division and square root that GPUs trace with, on this device
     * too: IEEE's results from products and sums rounded to nearest, the mirror's bits. */
    roma_context *corrected = roma_test_context_flags(ROMA_CONTEXT_CORRECTED_DIVISION);
    if (corrected) {
        printf("with the corrected division:\n");
        check_crafted(corrected, cornell, 64, 4, (roma_map_frame_desc){.frame = 3, .seed = 7, .jitter_grid = 1,
                                                                         .jitter_directions = 1});
        roma_test_context_finish(corrected);
    }
    roma_scene_destroy(cornell);
    roma_test_context_finish(ctx);
    return roma_test_finish("test_ray_hard_cases");
}
