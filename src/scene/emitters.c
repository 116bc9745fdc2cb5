#include "scene/emitters.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/log.h"

static void sub3(const float a[3], const float b[3], float out[3])
{
    for (int k = 0; k < 3; ++k)
        out[k] = a[k] - b[k];
}

roma_result roma_emitter_table_build(const roma_scene_view *v, const roma_logger *logger,
                                     roma_emitter_table *out)
{
    memset(out, 0, sizeof *out);
    if (v->emissive_triangle_count == 0 || !v->emissive_triangles)
        return ROMA_SUCCESS;
    uint32_t count = v->emissive_triangle_count;
    roma_emitter *emitters = calloc(count, sizeof *emitters);
    float *cdf = calloc(count, sizeof *cdf);
    double *lums = calloc(2 * (size_t)count, sizeof *lums); /* luminance, then weight */
    if (!emitters || !cdf || !lums) {
        free(emitters);
        free(cdf);
        free(lums);
        return roma_fail(logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "out of memory for %u area-light triangles",
                         count);
    }
    double *weights = lums + count;
    double total = 0.0;
    for (uint32_t i = 0; i < count; ++i) {
        uint32_t tri = v->emissive_triangles[i];
        const uint32_t *idx = &v->indices[3 * (size_t)tri];
        const float *p0 = &v->positions[3 * (size_t)idx[0]];
        const float *p1 = &v->positions[3 * (size_t)idx[1]];
        const float *p2 = &v->positions[3 * (size_t)idx[2]];
        roma_emitter *e = &emitters[i];
        memcpy(e->v0, p0, sizeof e->v0);
        sub3(p1, p0, e->e1);
        sub3(p2, p0, e->e2);
        e->normal[0] = e->e1[1] * e->e2[2] - e->e1[2] * e->e2[1];
        e->normal[1] = e->e1[2] * e->e2[0] - e->e1[0] * e->e2[2];
        e->normal[2] = e->e1[0] * e->e2[1] - e->e1[1] * e->e2[0];
        float len = sqrtf(e->normal[0] * e->normal[0] + e->normal[1] * e->normal[1] + e->normal[2] * e->normal[2]);
        if (len > 0.0f && isfinite(len))
            for (int k = 0; k < 3; ++k)
                e->normal[k] *= 1.0f / len;
        double area = 0.5 * (double)len;
        uint32_t m = v->triangle_materials ? v->triangle_materials[tri] : 0;
        if (v->materials && m < v->material_count)
            memcpy(e->emission, v->materials[m].emission, sizeof e->emission);
        /* Rec. 709 luminance: bright emitters get proportionally more samples. */
        lums[i] = 0.2126 * e->emission[0] + 0.7152 * e->emission[1] + 0.0722 * e->emission[2];
        weights[i] = (area > 0.0 && lums[i] > 0.0 && isfinite(area * lums[i])) ? area * lums[i] : 0.0;
        total += weights[i];
    }
    if (!(total > 0.0) || !isfinite(total)) {
        /* Nothing samplable (zero luminance everywhere): behave as no area lights. */
        free(lums);
        free(emitters);
        free(cdf);
        return ROMA_SUCCESS;
    }
    double acc = 0.0;
    for (uint32_t i = 0; i < count; ++i) {
        acc += weights[i];
        cdf[i] = (float)(acc / total);
        /* pdf_area = (w_i / total) / area_i = lum_i / total; zero-weight triangles are never chosen. */
        emitters[i].pdf_area = weights[i] > 0.0 ? (float)(lums[i] / total) : 0.0f;
    }
    cdf[count - 1] = 1.0f;
    free(lums);
    out->emitters = emitters;
    out->cdf = cdf;
    out->count = count;
    return ROMA_SUCCESS;
}

void roma_emitter_table_free(roma_emitter_table *table)
{
    if (!table)
        return;
    free(table->emitters);
    free(table->cdf);
    memset(table, 0, sizeof *table);
}

uint32_t roma_emitter_pick(const roma_emitter_table *table, float u)
{
    uint32_t lo = 0, hi = table->count - 1;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (table->cdf[mid] > u)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}
