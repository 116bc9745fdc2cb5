#include "voxelize_cpu.h"

#include <math.h>
#include <string.h>

/* Upper faces of a cell are pulled in by this much (cells): half-open boxes. */
#define UPPER_FACE_EPS 1e-9

static void sub3(const double a[3], const double b[3], double out[3])
{
    for (int i = 0; i < 3; ++i)
        out[i] = a[i] - b[i];
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Separated along axis when the triangle's projection [lo, hi] and the box's
 * [0, s]^3 projection do not touch. Coordinates are relative to the box's min
 * corner (exact for float input), and the box interval is built from corners
 * rather than centre +- radius, so axis-aligned contacts compare equal values. */
static int separated(const double axis[3], const double *a, const double *b, const double *c, double s)
{
    double p0 = dot3(axis, a), p1 = dot3(axis, b), p2 = dot3(axis, c);
    double lo = fmin(p0, fmin(p1, p2)), hi = fmax(p0, fmax(p1, p2));
    double box_lo = 0.0, box_hi = 0.0;
    for (int i = 0; i < 3; ++i) {
        box_lo += fmin(axis[i] * s, 0.0);
        box_hi += fmax(axis[i] * s, 0.0);
    }
    return lo > box_hi || hi < box_lo;
}

int roma_tri_box_overlap(const double box_min[3], double box_size, const double v0[3], const double v1[3],
                         const double v2[3])
{
    double a[3], b[3], d[3];
    sub3(v0, box_min, a);
    sub3(v1, box_min, b);
    sub3(v2, box_min, d);
    /* Box face normals. */
    for (int i = 0; i < 3; ++i) {
        double lo = fmin(a[i], fmin(b[i], d[i])), hi = fmax(a[i], fmax(b[i], d[i]));
        if (lo > box_size || hi < 0.0)
            return 0;
    }
    double e[3][3], n[3];
    sub3(b, a, e[0]);
    sub3(d, b, e[1]);
    sub3(a, d, e[2]);
    /* Triangle normal. */
    cross3(e[0], e[1], n);
    if (separated(n, a, b, d, box_size))
        return 0;
    /* Box axes x triangle edges. */
    for (int i = 0; i < 3; ++i) {
        double unit[3] = {0, 0, 0}, axis[3];
        unit[i] = 1.0;
        for (int j = 0; j < 3; ++j) {
            cross3(unit, e[j], axis);
            if (separated(axis, a, b, d, box_size))
                return 0;
        }
    }
    return 1;
}

static int clampi(double v, int lo, int hi)
{
    if (!(v >= lo))
        return lo;
    if (v > hi)
        return hi;
    return (int)v;
}

uint64_t roma_voxelize_cpu(const roma_voxel_grid *grid, const float *positions, uint32_t stride,
                           const uint32_t *indices, uint32_t triangle_count, uint32_t *words)
{
    const uint32_t res = grid->resolution;
    const int ires = (int)res;
    memset(words, 0, (size_t)res * res * res / 8);
    uint64_t occupied = 0;
    for (uint32_t t = 0; t < triangle_count; ++t) {
        double g[3][3];
        for (int k = 0; k < 3; ++k) {
            const float *p = positions + (size_t)indices[3 * t + k] * stride;
            for (int j = 0; j < 3; ++j) {
                /* Float, in the GPU's order: corners on cell faces stay on them. */
                float gf = (p[j] - grid->origin[j]) * grid->inv_cell;
                g[k][j] = gf;
            }
        }
        double e1[3], e2[3], n[3];
        sub3(g[1], g[0], e1);
        sub3(g[2], g[0], e2);
        cross3(e1, e2, n);
        if (!(dot3(n, n) > 1e-12 * dot3(e1, e1) * dot3(e2, e2)))
            continue; /* zero area: marks nothing, as on the GPU */
        double lo[3], hi[3];
        int clo[3], chi[3], outside = 0;
        for (int j = 0; j < 3; ++j) {
            lo[j] = fmin(g[0][j], fmin(g[1][j], g[2][j]));
            hi[j] = fmax(g[0][j], fmax(g[1][j], g[2][j]));
            if (hi[j] < 0.0 || lo[j] >= res)
                outside = 1;
            clo[j] = clampi(floor(lo[j]), 0, ires - 1);
            chi[j] = clampi(floor(hi[j]), 0, ires - 1);
        }
        if (outside)
            continue;
        /* Walk columns along the dominant normal axis: the plane spans at most a
         * few cells per column there; the SAT decides each candidate. */
        double an[3] = {fabs(n[0]), fabs(n[1]), fabs(n[2])};
        int a = (an[0] >= an[1] && an[0] >= an[2]) ? 0 : (an[1] >= an[2] ? 1 : 2);
        int u = (a + 1) % 3, v = (a + 2) % 3;
        double plane = dot3(n, g[0]);
        for (int iu = clo[u]; iu <= chi[u]; ++iu)
            for (int iv = clo[v]; iv <= chi[v]; ++iv) {
                double dmin = INFINITY, dmax = -INFINITY;
                for (int corner = 0; corner < 4; ++corner) {
                    double cu = iu + (corner & 1), cv = iv + (corner >> 1);
                    double d = (plane - n[u] * cu - n[v] * cv) / n[a];
                    dmin = fmin(dmin, d);
                    dmax = fmax(dmax, d);
                }
                int k0 = clampi(floor(fmax(dmin, lo[a])) - 1.0, clo[a], chi[a]);
                int k1 = clampi(floor(fmin(dmax, hi[a])) + 1.0, clo[a], chi[a]);
                for (int k = k0; k <= k1; ++k) {
                    int cell[3];
                    cell[a] = k;
                    cell[u] = iu;
                    cell[v] = iv;
                    double bmin[3] = {cell[0], cell[1], cell[2]};
                    if (!roma_tri_box_overlap(bmin, 1.0 - UPPER_FACE_EPS, g[0], g[1], g[2]))
                        continue;
                    uint64_t w = roma_voxel_word(res, (uint32_t)cell[0], (uint32_t)cell[1], (uint32_t)cell[2]);
                    uint32_t bit = 1u << ((uint32_t)cell[2] & 31u);
                    if (!(words[w] & bit)) {
                        words[w] |= bit;
                        ++occupied;
                    }
                }
            }
    }
    return occupied;
}
