#include "trace/cpu_mirror.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "rotate/directions.h"

void roma_cpu_rotate(const roma_grid_params *grid, const roma_map_frame *frames,
                     const uint32_t *bom, uint32_t *maps)
{
    const uint32_t res = grid->dims[0], words = grid->dims[1], map_count = grid->dims[3];
    const float fres = (float)res;
    for (uint32_t k = 0; k < map_count; ++k) {
        const roma_map_frame *f = &frames[k];
        for (uint32_t y = 0; y < res; ++y)
            for (uint32_t x = 0; x < res; ++x)
                for (uint32_t w = 0; w < words; ++w) {
                    float mx = (float)x + 0.5f, my = (float)y + 0.5f;
                    uint32_t out = 0;
                    for (uint32_t i = 0; i < 32; ++i)
                        for (uint32_t h = 0; h < ROMA_ROTATE_SAMPLES; ++h) {
                            float mz = (float)(w * 32 + i) + ((float)h + 0.5f) / (float)ROMA_ROTATE_SAMPLES;
                            float b[3];
                            for (int a = 0; a < 3; ++a)
                                b[a] = ((f->map_to_bom_0[a] * mx + f->map_to_bom_1[a] * my) +
                                        f->map_to_bom_2[a] * mz) + f->map_to_bom_3[a];
                            if (b[0] >= 0.0f && b[1] >= 0.0f && b[2] >= 0.0f && b[0] < fres &&
                                b[1] < fres && b[2] < fres) {
                                uint32_t cx = (uint32_t)floorf(b[0]), cy = (uint32_t)floorf(b[1]),
                                         cz = (uint32_t)floorf(b[2]);
                                uint32_t word = bom[(cy * res + cx) * words + (cz >> 5)];
                                out |= ((word >> (cz & 31u)) & 1u) << i;
                            }
                        }
                    maps[((k * res + y) * res + x) * words + w] = out;
                }
    }
}

uint32_t roma_cpu_select_map(const float dir[3], uint32_t angular, int *folded)
{
    return roma_direction_to_map(dir, angular, folded);
}

int roma_cpu_selection_may_differ(const float dir[3], uint32_t angular, uint32_t gpu_map, float *distance)
{
    float unit[3], u = 0.0f, v = 0.0f, far = 0.0f;
    if (distance)
        *distance = INFINITY;
    if (angular == 0 || gpu_map >= angular * angular || !roma_unit_direction(dir, unit))
        return 0;
    const float s = unit[2] < 0.0f ? -1.0f : 1.0f, up[3] = {unit[0] * s, unit[1] * s, unit[2] * s};
    roma_hemisphere_to_square(up, &u, &v);
    const float uv[2] = {u, v};
    const uint32_t gpu[2] = {gpu_map % angular, gpu_map / angular};
    for (int a = 0; a < 2; ++a) {
        const uint32_t mine = (uint32_t)fminf(uv[a] * (float)angular, (float)(angular - 1));
        if (mine == gpu[a])
            continue;
        if (mine + 1 != gpu[a] && gpu[a] + 1 != mine)
            return 0;
        const uint32_t edge = mine > gpu[a] ? mine : gpu[a]; /* the edge between them */
        far = fmaxf(far, fabsf(uv[a] - (float)edge / (float)angular));
    }
    if (distance)
        *distance = far;
    return far <= ROMA_CPU_SELECTION_TOLERANCE;
}

static void to_map(const roma_grid_params *grid, const roma_map_frame *f, const float p[3], float m[3])
{
    const float *rows[3] = {f->to_map_0, f->to_map_1, f->to_map_2};
    const float u = grid->inv_cell[1]; /* grid units: trace_types.h */
    float r[3] = {(p[0] - grid->origin[0]) * u, (p[1] - grid->origin[1]) * u, (p[2] - grid->origin[2]) * u};
    for (int a = 0; a < 3; ++a)
        m[a] = ((rows[a][0] * r[0] + rows[a][1] * r[1]) + rows[a][2] * r[2]) + rows[a][3];
}

static int cell_range(float lo, float hi, uint32_t res, int *c_lo, int *c_hi)
{
    *c_lo = 0;
    *c_hi = -1;
    if (!(lo <= hi) || hi < 0.0f || lo >= (float)res)
        return 0;
    *c_lo = (int)floorf(fmaxf(lo, 0.0f));
    *c_hi = (int)floorf(fminf(hi, (float)res - 0.5f));
    return 1;
}

static uint32_t range_mask(int c_lo, int c_hi, uint32_t w)
{
    int base = (int)w * 32;
    int lo = c_lo - base > 0 ? c_lo - base : 0;
    int hi = c_hi - base < 31 ? c_hi - base : 31;
    if (lo > hi)
        return 0u;
    return (0xffffffffu >> (uint32_t)(31 - hi)) & (0xffffffffu << (uint32_t)lo);
}

static int first_cell(const uint32_t *maps, uint32_t base, int c_lo, int c_hi, int upward)
{
    uint32_t w_lo = (uint32_t)c_lo >> 5, w_hi = (uint32_t)c_hi >> 5;
    if (upward) {
        for (uint32_t w = w_lo; w <= w_hi; ++w) {
            uint32_t bits = maps[base + w] & range_mask(c_lo, c_hi, w);
            if (bits)
                return (int)w * 32 + __builtin_ctz(bits);
        }
    } else {
        for (uint32_t w = w_hi + 1; w-- > w_lo;) {
            uint32_t bits = maps[base + w] & range_mask(c_lo, c_hi, w);
            if (bits)
                return (int)w * 32 + 31 - __builtin_clz(bits);
        }
    }
    return -1;
}

/* The last occupied cell of the run that starts at cell c, going up or down the column,
 * looked for in c's word and the next, as roma_run_end in trace.glsl. */
static int run_end(const uint32_t *maps, uint32_t base, int c, int upward, uint32_t res)
{
    int w = c >> 5, b = c & 31;
    uint32_t empty = ~maps[base + (uint32_t)w] &
                     (upward ? (b == 31 ? 0u : 0xffffffffu << (b + 1)) : (b == 0 ? 0u : 0xffffffffu >> (32 - b)));
    if (!empty) {
        w += upward ? 1 : -1;
        if (w < 0 || w >= (int)(res >> 5))
            return upward ? (int)res - 1 : 0;
        empty = ~maps[base + (uint32_t)w];
        if (!empty)
            return upward ? w * 32 + 31 : w * 32;
    }
    return upward ? w * 32 + __builtin_ctz(empty) - 1 : w * 32 + 31 - __builtin_clz(empty) + 1;
}

/* roma_hit_distance in GLSL: within [tmin, tmax], and +0 rather than -0. */
static float hit_distance(float t, float tmin, float tmax)
{
    return fminf(fmaxf(t, tmin), tmax) + 0.0f;
}

static roma_hit trace_snapped(const roma_grid_params *grid, const roma_map_frame *f, uint32_t k,
                              int folded, const uint32_t *maps, const roma_ray *ray, int closest,
                              roma_hit hit)
{
    const uint32_t res = grid->dims[0], words = grid->dims[1];
    float m[3];
    to_map(grid, f, ray->origin, m);
    if (!isfinite(m[0]) || !isfinite(m[1]) || !isfinite(m[2]))
        return hit;
    if (!(m[0] >= 0.0f && m[0] < (float)res && m[1] >= 0.0f && m[1] < (float)res))
        return hit;
    float inv_cz = f->cell[3], cz = f->dir[3];
    float lo = folded ? m[2] - ray->tmax * inv_cz : m[2] + ray->tmin * inv_cz;
    float hi = folded ? m[2] - ray->tmin * inv_cz : m[2] + ray->tmax * inv_cz;
    int c_lo, c_hi;
    if (!cell_range(lo, hi, res, &c_lo, &c_hi))
        return hit;
    uint32_t base = ((k * res + (uint32_t)m[1]) * res + (uint32_t)m[0]) * words;
    int c = first_cell(maps, base, c_lo, c_hi, !folded);
    if (c < 0)
        return hit;
    hit.info |= ROMA_HIT_FLAG;
    if (closest) {
        float t = folded ? (m[2] - (float)(c + 1)) * cz : ((float)c - m[2]) * cz;
        hit.t = hit_distance(t, ray->tmin, ray->tmax);
    }
    return hit;
}

static roma_hit trace_unsnapped(const roma_grid_params *grid, const roma_map_frame *f, uint32_t k,
                                const uint32_t *maps, const roma_ray *ray, const float dn[3], int closest,
                                uint32_t max_steps, roma_cpu_walk_counts *counts, roma_hit hit, int *gave_up)
{
    const uint32_t res = grid->dims[0], words = grid->dims[1];
    const float *rows[3] = {f->to_map_0, f->to_map_1, f->to_map_2};
    float dm[3], inv[3], m0[3];
    for (int a = 0; a < 3; ++a) {
        dm[a] = (rows[a][0] * dn[0] + rows[a][1] * dn[1]) + rows[a][2] * dn[2];
        dm[a] = fabsf(dm[a]) < FLT_MIN ? 0.0f : dm[a]; /* as the GLSL: every reciprocal finite */
        inv[a] = dm[a] != 0.0f ? 1.0f / dm[a] : 0.0f;
    }
    to_map(grid, f, ray->origin, m0);
    if (!isfinite(m0[0]) || !isfinite(m0[1]) || !isfinite(m0[2]))
        return hit; /* an origin so far out that its map coordinates overflow */
    const float fres = (float)res;
    float t_in = ray->tmin * grid->inv_cell[1], t_out = ray->tmax * grid->inv_cell[1]; /* grid units */
    for (int a = 0; a < 2; ++a) {
        if (dm[a] == 0.0f) {
            if (!(m0[a] >= 0.0f && m0[a] < fres))
                return hit;
        } else {
            float ta = (0.0f - m0[a]) * inv[a];
            float tb = (fres - m0[a]) * inv[a];
            t_in = fmaxf(t_in, fminf(ta, tb));
            t_out = fminf(t_out, fmaxf(ta, tb));
        }
    }
    if (!(t_in <= t_out))
        return hit;
    float px = dm[0] == 0.0f ? m0[0] : m0[0] + dm[0] * t_in;
    float py = dm[1] == 0.0f ? m0[1] : m0[1] + dm[1] * t_in;
    int ix = (int)fminf(fmaxf(floorf(px), 0.0f), fres - 1.0f);
    int iy = (int)fminf(fmaxf(floorf(py), 0.0f), fres - 1.0f);
    /* Each column also searched past the ray's exit for a step of a thin wall ahead, and the
     * next column back from its entry for the wall's next step (trace.glsl says why). */
    const float run_window = (float)ROMA_RUN_WINDOW * fabsf(inv[2]);
    float back = 0.0f;
    float t_cur = t_in;
    for (uint32_t step = 0; step < max_steps; ++step) {
        float tx = dm[0] > 0.0f ? ((float)(ix + 1) - m0[0]) * inv[0]
                 : dm[0] < 0.0f ? ((float)ix - m0[0]) * inv[0] : INFINITY;
        float ty = dm[1] > 0.0f ? ((float)(iy + 1) - m0[1]) * inv[1]
                 : dm[1] < 0.0f ? ((float)iy - m0[1]) * inv[1] : INFINITY;
        float t_next = fminf(fminf(tx, ty), t_out);
        float ta = t_cur - back, tb = fminf(t_next + run_window, t_out);
        float za = dm[2] == 0.0f ? m0[2] : m0[2] + dm[2] * ta;
        float zb = dm[2] == 0.0f ? m0[2] : m0[2] + dm[2] * tb;
        float z_exit = dm[2] == 0.0f ? m0[2] : m0[2] + dm[2] * t_next;
        int upward = dm[2] >= 0.0f;
        int exit_cell = z_exit < 0.0f ? -1 : z_exit >= fres ? (int)res : (int)floorf(fminf(z_exit, fres - 0.5f));
        int unseen = back > 0.0f && (upward ? za < 0.0f : za >= fres);
        uint32_t base = ((k * res + (uint32_t)iy) * res + (uint32_t)ix) * words;
        int c = -1, c_lo, c_hi;
        if (cell_range(fminf(za, zb), fmaxf(za, zb), res, &c_lo, &c_hi))
            c = first_cell(maps, base, c_lo, c_hi, upward);
        int ahead = c >= 0 && (upward ? c > exit_cell : c < exit_cell);
        if ((c >= 0 && !ahead) || (c < 0 && unseen)) {
            hit.info |= ROMA_HIT_FLAG;
            if (closest) {
                float tc = c < 0 ? t_cur
                         : dm[2] > 0.0f ? ((float)c - m0[2]) * inv[2]
                         : dm[2] < 0.0f ? ((float)(c + 1) - m0[2]) * inv[2] : t_cur;
                hit.t = hit_distance(fmaxf(tc, t_cur) * grid->inv_cell[2], ray->tmin, ray->tmax);
            }
            if (counts) {
                /* A cell wholly before the column's entry was found only by the search back. */
                float z_entry = dm[2] == 0.0f ? m0[2] : m0[2] + dm[2] * t_cur;
                counts->unseen_hits += c < 0;
                int before_entry = upward ? (float)(c + 1) <= z_entry : (float)c > z_entry;
                counts->back_hits += c >= 0 && back > 0.0f && before_entry;
            }
            return hit;
        }
        back = 0.0f;
        if (ahead) {
            if (counts)
                ++counts->steps_ahead;
            float gap = upward ? (float)c - z_exit : z_exit - (float)(c + 1);
            float span = (float)(abs(run_end(maps, base, c, upward, res) - c) + 2) - gap;
            back = fmaxf(span, 0.0f) * fabsf(inv[2]);
        }
        if (t_next >= t_out)
            return hit;
        if (tx <= ty)
            ix += dm[0] > 0.0f ? 1 : -1;
        else
            iy += dm[1] > 0.0f ? 1 : -1;
        if (ix < 0 || iy < 0 || ix >= (int)res || iy >= (int)res)
            return hit;
        t_cur = t_next;
    }
    *gave_up = 1; /* walked max_steps texels: the rest counts as open */
    return hit;
}

roma_hit roma_cpu_trace(const roma_grid_params *grid, const roma_map_frame *frames,
                        const uint32_t *maps, const roma_ray *ray, roma_trace_mode mode,
                        uint32_t max_steps, int map_override, int folded_override)
{
    return roma_cpu_trace_counted(grid, frames, maps, ray, mode, max_steps, map_override, folded_override, NULL);
}

/* One level's trace (frames and maps: that level's), as roma_trace_snapped_level and
 * roma_trace_unsnapped_level in GLSL; *gave_up set when an un-snapped walk ran out of steps. */
static roma_hit trace_level(const roma_grid_params *grid, const roma_map_frame *frames, const uint32_t *maps,
                            const roma_ray *ray, roma_trace_mode mode, uint32_t max_steps, int map_override,
                            int folded_override, roma_cpu_walk_counts *counts, int *gave_up)
{
    float unit[3];
    const float *o = ray->origin;
    int valid = roma_unit_direction(ray->dir, unit) && isfinite(o[0]) && isfinite(o[1]) &&
                isfinite(o[2]) && ray->tmin <= ray->tmax;
    int folded = 0;
    uint32_t k = valid ? roma_unit_direction_to_map(unit, grid->dims[2], &folded) : 0;
    if (map_override >= 0) {
        k = (uint32_t)map_override;
        folded = folded_override;
    }
    roma_hit hit = {INFINITY, (k << 8) | (folded ? 0x10000u : 0u)};
    if (!valid)
        return hit;
    int closest = (mode & 1) != 0;
    if (mode == ROMA_TRACE_SNAPPED_ANY || mode == ROMA_TRACE_SNAPPED_CLOSEST)
        return trace_snapped(grid, &frames[k], k, folded, maps, ray, closest, hit);
    return trace_unsnapped(grid, &frames[k], k, maps, ray, unit, closest, max_steps ? max_steps : 8, counts, hit,
                           gave_up);
}

roma_hit roma_cpu_trace_counted(const roma_grid_params *grid, const roma_map_frame *frames,
                                const uint32_t *maps, const roma_ray *ray, roma_trace_mode mode,
                                uint32_t max_steps, int map_override, int folded_override,
                                roma_cpu_walk_counts *counts)
{
    int gave_up = 0;
    return trace_level(grid, frames, maps, ray, mode, max_steps, map_override, folded_override, counts, &gave_up);
}

/* roma_level_of in GLSL: the finest level whose cube holds p, else the coarsest. */
static uint32_t level_of(uint32_t levels, const roma_grid_params *grids, const float p[3])
{
    for (uint32_t l = 0; l + 1 < levels; ++l) {
        const roma_grid_params *g = &grids[l];
        const float side = (float)g->dims[0] * g->origin[3];
        int inside = 1;
        for (int a = 0; a < 3; ++a)
            inside &= p[a] >= g->origin[a] && p[a] < g->origin[a] + side;
        if (inside)
            return l;
    }
    return levels ? levels - 1 : 0;
}

/* ROMA_LEVEL_OVERLAP_CELLS in GLSL: a coarser level's part begins this many of its cells
 * before the finer level's part ends. */
#define LEVEL_OVERLAP_CELLS 1.7320508f
/* roma_level_exit in GLSL (inv: dn's reciprocals, 0 where dn is 0). */
static float level_exit(const roma_grid_params *g, const float origin[3], const float dn[3], const float inv[3])
{
    const float side = (float)g->dims[0] * g->origin[3];
    float ta[3];
    for (int a = 0; a < 3; ++a) {
        const float lo = g->origin[a] - origin[a], hi = lo + side;
        ta[a] = dn[a] > 0.0f ? hi * inv[a] : dn[a] < 0.0f ? lo * inv[a] : INFINITY;
    }
    return fminf(ta[0], fminf(ta[1], ta[2]));
}

roma_hit roma_cpu_trace_levels(uint32_t levels, const roma_grid_params *grids, const roma_map_frame *frames,
                               const uint32_t *maps, const roma_ray *ray, roma_trace_mode mode, uint32_t max_steps,
                               int map_override, int folded_override)
{
    /* roma_level_walk in GLSL: each level over its part of [tmin, tmax]. */
    float dn[3] = {0.0f, 0.0f, 0.0f}, along[3], inv[3];
    const int unit = roma_unit_direction(ray->dir, dn);
    const float *o = ray->origin;
    /* A ray that is not traced is the plain miss (info 0); walked in level 0 here and in its
     * origin's level in GLSL, alike: the trace returns before it reads a grid. */
    const int traced = unit && isfinite(o[0]) && isfinite(o[1]) && isfinite(o[2]) && ray->tmin <= ray->tmax;
    uint32_t l = traced ? level_of(levels, grids, ray->origin) : 0u;
    const roma_grid_params *g = &grids[l];
    int last = !traced || l + 1 >= levels;
    const int unsnapped = mode == ROMA_TRACE_UNSNAPPED_ANY || mode == ROMA_TRACE_UNSNAPPED_CLOSEST;
    /* The traced line: the ray, or a snapped query's candidate (roma_level_walk in GLSL). */
    int folded = 0;
    uint32_t k = unit ? roma_unit_direction_to_map(dn, g->dims[2], &folded) : 0;
    if (map_override >= 0) {
        k = (uint32_t)map_override;
        folded = folded_override;
    }
    for (int a = 0; a < 3; ++a) {
        along[a] = !unsnapped && unit ? (folded ? -frames[k].dir[a] : frames[k].dir[a]) : dn[a];
        inv[a] = along[a] != 0.0f ? 1.0f / along[a] : 0.0f;
    }
    float t0 = ray->tmin, t1 = !last ? fminf(level_exit(g, ray->origin, along, inv), ray->tmax) : ray->tmax;
    for (;;) {
        roma_ray part = *ray;
        part.tmin = t0;
        part.tmax = t1;
        int gave_up = 0;
        roma_hit h = trace_level(g, frames + g->level[2], maps + g->level[3], &part, mode, max_steps, map_override,
                                 folded_override, NULL, &gave_up);
        h.info |= l << ROMA_HIT_LEVEL_SHIFT;
        if ((unsnapped && gave_up) || last || (h.info & ROMA_HIT_FLAG) || !(t1 < ray->tmax))
            return h;
        g = &grids[++l];
        t0 = fmaxf(t0, t1 - LEVEL_OVERLAP_CELLS * g->origin[3]);
        last = l + 1 >= levels;
        t1 = last ? ray->tmax : fminf(level_exit(g, ray->origin, along, inv), ray->tmax);
    }
}
