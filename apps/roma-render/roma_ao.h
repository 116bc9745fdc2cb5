/* roma-render's ROMA tracer for ambient occlusion, all on the GPU: the G-buffer
 * pass (passes/gbuffer.h) gives each pixel's surface point and normals, and the
 * AO pass (passes/ao.h) traces its rays through the ROMA maps, rebuilt with new
 * jitter every frame. */
#ifndef ROMA_RENDER_ROMA_AO_H
#define ROMA_RENDER_ROMA_AO_H

#include "reference.h"
#include "roma/map.h"

typedef struct roma_ao_settings {
    roma_camera camera;
    uint32_t width, height, spp, frames, seed;
    float radius;                  /* <= 0: unbounded */
    roma_map_desc map;
    float offset_cells;            /* origin offset along the normal, in BOM cells */
} roma_ao_settings;

typedef struct roma_ao_timings {
    /* GPU timestamps summed over frames; trace_ms is the AO pass, gbuffer_ms the
     * G-buffer pass (frame 0 only). */
    double bom_ms, rotate_ms, trace_ms, gbuffer_ms;
    uint64_t rays;        /* covered pixels * spp * frames (below-surface ones included, not traced) */
    roma_map_info info;
} roma_ao_timings;

/* out_ao: 1-channel visibility (background 1), allocated by the call. */
roma_result roma_render_ao_roma(roma_context *ctx, const roma_scene *scene, const roma_ao_settings *s,
                                roma_image *out_ao, roma_ao_timings *timings);

#endif /* ROMA_RENDER_ROMA_AO_H */
