/* The views of the reflective shadow maps that one-bounce GI looks hits up in:
 * a spot light looks along its axis with a field of view of twice its outer
 * cone (at most 170 degrees), a point light along the six axes (cube faces of
 * 90 degrees). Directional lights get none. Each view is rendered with the
 * G-buffer pass (study/gbuffer.h). */
#ifndef ROMA_STUDY_RSM_VIEWS_H
#define ROMA_STUDY_RSM_VIEWS_H

#include "roma/camera.h"
#include "roma_shared.h"
#include "util/log.h"

#define ROMA_MAX_RSM_VIEWS 48u

typedef struct roma_rsm_views {
    roma_rsm_view views[ROMA_MAX_RSM_VIEWS];  /* info.zw (pixel address) left for the caller */
    roma_camera cameras[ROMA_MAX_RSM_VIEWS];
    uint32_t count;
} roma_rsm_views;

/* lights: as uploaded (effects/light_data.h); views refer to them by index.
 * ROMA_ERROR_UNSUPPORTED past ROMA_MAX_RSM_VIEWS views. */
roma_result roma_rsm_views_plan(const roma_gpu_light *lights, uint32_t light_count, uint32_t size, float near_plane,
                                const roma_logger *logger, roma_rsm_views *out);

#endif /* ROMA_STUDY_RSM_VIEWS_H */
