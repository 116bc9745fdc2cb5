#include "study/rsm_views.h"

#include <math.h>
#include <string.h>

#include "study/gbuffer.h"

#define PI_F 3.14159265358979323846f

roma_result roma_rsm_views_plan(const roma_gpu_light *lights, uint32_t light_count, uint32_t size, float near_plane,
                                const roma_logger *logger, roma_rsm_views *out)
{
    static const float axes[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    memset(out, 0, sizeof *out);
    for (uint32_t i = 0; i < light_count; ++i) {
        const roma_gpu_light *l = &lights[i];
        uint32_t type = (uint32_t)l->position_type[3];
        if (type == ROMA_GPU_LIGHT_DIRECTIONAL)
            continue;
        uint32_t faces = type == ROMA_GPU_LIGHT_SPOT ? 1 : 6;
        if (out->count + faces > ROMA_MAX_RSM_VIEWS)
            return roma_fail(logger, ROMA_ERROR_UNSUPPORTED,
                             "GI supports at most %u RSM views (a spot light takes one, a point light six)",
                             ROMA_MAX_RSM_VIEWS);
        for (uint32_t f = 0; f < faces; ++f) {
            const float *d = type == ROMA_GPU_LIGHT_SPOT ? l->direction_range : axes[f];
            float fovy = 90.0f;
            if (type == ROMA_GPU_LIGHT_SPOT) {
                float cos_outer = -l->cone[1] / l->cone[0];
                fovy = fminf(fmaxf(2.0f * acosf(fminf(fmaxf(cos_outer, -1.0f), 1.0f)) * 180.0f / PI_F, 1.0f), 170.0f);
            }
            roma_camera *c = &out->cameras[out->count];
            memset(c, 0, sizeof *c);
            for (int k = 0; k < 3; ++k) {
                c->eye[k] = l->position_type[k];
                c->target[k] = l->position_type[k] + d[k];
            }
            c->up[fabsf(d[1]) > 0.99f ? 2 : 1] = 1.0f;
            c->fovy_deg = fovy;
            roma_rsm_view *v = &out->views[out->count];
            if (!roma_gbuffer_camera_make(c, size, size, near_plane, &v->camera))
                return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT, "light %u has no usable RSM view", i);
            v->info[0] = i;
            v->info[1] = size;
            ++out->count;
        }
    }
    return ROMA_SUCCESS;
}
