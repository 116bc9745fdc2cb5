/* roma-render's ROMA tracer for ambient occlusion. Primary visibility (the
 * surface point and normal of each pixel) comes from the reference tracer
 * until the G-buffer pass lands, so both tracers shade exactly the same points;
 * every AO ray is traced by ROMA on the GPU. */
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
    double bom_ms, rotate_ms, trace_ms; /* GPU time summed over frames */
    uint64_t rays;
    roma_map_info info;
} roma_ao_timings;

/* out_ao: 1-channel visibility (background 1), allocated by the call. */
roma_result roma_render_ao_roma(roma_context *ctx, const roma_scene *scene, const roma_ref *ref,
                                const roma_ao_settings *s, roma_image *out_ao, roma_ao_timings *timings);

#endif /* ROMA_RENDER_ROMA_AO_H */
