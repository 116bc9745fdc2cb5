/* What rays trace in the accuracy study: ROMA, or one of its baselines (src/study/study_ao.h
 * and study_shadows.h run each through the public passes). */
#ifndef ROMA_STUDY_STUDY_METHODS_H
#define ROMA_STUDY_STUDY_METHODS_H

/* What the AO rays trace: ROMA, or one of the accuracy study's baselines. */
typedef enum roma_ao_method {
    ROMA_AO_METHOD_ROMA = 0,
    /* every ray walked exactly through the map's BOM from its origin to its end (3D DDA,
     * Amanatides-Woo): the same voxels without snapping, rotation or bounded steps */
    ROMA_AO_METHOD_VOXEL_DDA = 1,
    /* every ray sphere-traced from its origin through the distance field built from the
     * map's BOM (study/distance_field.h), bound in the BOM's place, at most
     * ROMA_AO_DF_MAX_STEPS steps of at least ROMA_AO_DF_MIN_STEP cells */
    ROMA_AO_METHOD_DISTANCE_FIELD = 2,
    /* every ray marched in screen space against the G-buffer's depth layer, and the layers
     * of a stochastic depth map if given (shaders/include/roma_ssao.glsl): no map is read,
     * and a bounded radius is needed */
    ROMA_AO_METHOD_SCREEN_SPACE = 3,
    /* every ray traversed from its origin through the NAADF hierarchy built from the map's BOM
     * (study/naadf.h), bound in the BOM's place: the voxels of ROMA_AO_METHOD_VOXEL_DDA,
     * empty space left a box at a time */
    ROMA_AO_METHOD_NAADF = 4,
} roma_ao_method;

/* The screen-space baseline's march: steps per ray, and how far behind its depth a surface
 * is taken to extend, as a fraction of the AO radius. */
#define ROMA_AO_SSAO_STEPS 16u
#define ROMA_AO_SSAO_THICKNESS 0.5f
/* The stochastic depth map beside the G-buffer's depth: at most this many layers, each
 * keeping a fragment with this probability (a pixel's k-th surface from the eye is in a
 * layer with probability 0.5^k). */
#define ROMA_AO_SSAO_MAX_LAYERS 8u
#define ROMA_AO_SSAO_KEEP 0.5f

/* The ROMA paper's baseline takes up to 64 steps. With half a cell as the least step a ray
 * can clip only the corner of an occupied cell: closed rooms leak on under 0.5% of their
 * pixels (tests/test_closed_rooms.c). */
#define ROMA_AO_DF_MAX_STEPS 64u
#define ROMA_AO_DF_MIN_STEP 0.5f

/* What shadow, bounce and visibility rays trace. */
typedef enum roma_shadow_method {
    ROMA_SHADOW_METHOD_ROMA = 0,
    ROMA_SHADOW_METHOD_VOXEL_DDA = 1, /* every segment walked exactly through the BOM, no maps, no step bound */
} roma_shadow_method;

#endif /* ROMA_STUDY_STUDY_METHODS_H */
