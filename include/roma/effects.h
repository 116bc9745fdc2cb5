/** @file
 * libroma: effects and the plan of passes a frame runs.
 *
 * The effect plan is derived from the scene and the caller's options before any
 * GPU work, so that a frame runs only the passes its scene calls for:
 *  - ambient occlusion: the AO pass, when asked for;
 *  - direct light: one pass for point/spot/directional lights (shadow rays to
 *    each light) when the scene has any, one soft-shadow pass for area lights
 *    (emissive triangles) when it has any; a scene with neither runs no direct pass;
 *  - one-bounce diffuse GI: the GI gather when the scene has any light (the light
 *    leaving a bounce hit is the direct light there: area-light samples and
 *    directional lights by shadow rays), plus reflective shadow maps when it has point
 *    or spot lights (the route the GI gather takes for them);
 *  - many lights: visibility of many synthetic point lights, when asked for.
 * The G-buffer runs when any pass runs. ROMA arrays are built once per frame per
 * distinct (RES, A) that some pass traces, and not at all when nothing traces.
 * The plan is pure host computation: any thread (the scene is only read). */
#ifndef ROMA_EFFECTS_H
#define ROMA_EFFECTS_H

#include "roma/api.h"

#include <stdint.h>

#include "roma/presets.h"
#include "roma/result.h"
#include "roma/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Effects an image can be asked for (bit flags). */
enum {
    ROMA_EFFECT_AO = 1u << 0,           /**< ambient occlusion */
    ROMA_EFFECT_DIRECT = 1u << 1,       /**< direct light: punctual lights and area lights */
    ROMA_EFFECT_GI = 1u << 2,           /**< one-bounce diffuse GI from every light */
    ROMA_EFFECT_LIGHTS = 1u << 3,       /**< visibility of many synthetic point lights */
    ROMA_EFFECT_ALL_ = (1u << 4) - 1u   /**< every known bit (for validation) */
};

/** The passes a frame of effects can run (roma_effect_plan.passes). */
typedef enum roma_pass_kind {
    ROMA_PASS_GBUFFER = 0,     /**< rasterized G-buffer: position, normals, albedo */
    ROMA_PASS_AO,              /**< snapped any-hit, hemisphere rays */
    ROMA_PASS_PUNCTUAL_LIGHTS, /**< point/spot/directional light with un-snapped shadow rays */
    ROMA_PASS_SOFT_SHADOWS,    /**< area-light samples, un-snapped shadow rays */
    ROMA_PASS_MANY_LIGHTS,     /**< visibility of many point lights, un-snapped */
    ROMA_PASS_RSM,             /**< reflective shadow maps of point/spot lights */
    ROMA_PASS_GI,              /**< snapped closest-hit bounce rays, direct light at the hits */
    ROMA_PASS_COUNT            /**< number of passes (not a pass) */
} roma_pass_kind;

/** The name of a pass, for logs and statistics.
 *
 * @param pass  any value; values outside the enum are allowed.
 * @return a static string: "gbuffer", "ao", "punctual_lights", "soft_shadows",
 *         "many_lights", "rsm", "gi"; "unknown" outside the enum.
 * @par Threads
 * Any thread. */
ROMA_API const char *roma_pass_name(roma_pass_kind pass);

/** What a frame of effects is asked for (roma_effect_plan_derive).
 * Zero value: the paper's settings (RES 128; A = 4 for hemisphere rays, A = 8 for
 * rays towards lights) and 256 many lights; no effect. */
typedef struct roma_effect_options {
    uint32_t effects;          /**< ROMA_EFFECT_* bits asked for */
    uint32_t resolution;       /**< RES of every array: 32, 64, 128 or 256; 0 = the preset's (128) */
    uint32_t ao_angular;       /**< A of the AO array, 1..16; 0 = the preset's (4) */
    uint32_t gi_angular;       /**< A of the GI array; 0 = the preset's (4) */
    uint32_t shadow_angular;   /**< A of the array for shadow rays (punctual and area lights); 0 = 8 */
    uint32_t lights_angular;   /**< A of the many-lights array; 0 = 8 */
    uint32_t many_light_count; /**< 1..65536; 0 = 256 */
    roma_preset preset;        /**< resolution, ao_angular and gi_angular where 0 (roma/presets.h); 0 = medium */
} roma_effect_options;

/** One ROMA array of a plan. */
typedef struct roma_map_config {
    uint32_t resolution; /**< RES */
    uint32_t angular; /**< A (A x A maps) */
} roma_map_config;

/** Which passes run and which ROMA arrays they share (roma_effect_plan_derive). */
typedef struct roma_effect_plan {
    uint32_t effects;                   /**< as asked (an effect the scene cannot show renders black) */
    uint32_t passes;                    /**< bit (1u << roma_pass_kind) per pass that runs */
    uint32_t map_count;                 /**< distinct ROMA arrays built per frame */
    roma_map_config maps[ROMA_PASS_COUNT]; /**< the distinct arrays, map_count of them */
    int32_t pass_map[ROMA_PASS_COUNT];  /**< index into maps of the array a pass traces; -1: none */
    uint32_t many_light_count;          /**< resolved count (0 when the pass does not run) */
} roma_effect_plan;

/** Resolves defaults and derives the plan from the scene. Rejects unknown effect
 * bits, resolutions other than 32/64/128/256, A outside 1..16 and many-light
 * counts above 65536 (ROMA_ERROR_INVALID_ARGUMENT, message through logger, which
 * may be NULL); on failure *out_plan runs nothing: zeroed, with every pass_map -1.
 * Lights with zero intensity or colour call for no pass.
 *
 * @param scene          the scene whose lights and emitters decide the light passes.
 * @param options        what is asked for; NULL = the zero value (no effect).
 * @param logger         where the rejection message goes; NULL: stderr.
 * @param[out] out_plan  the plan.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL scene or out_plan, or the
 *         rejected options above.
 * @par Threads
 * Any thread. */
ROMA_API roma_result roma_effect_plan_derive(const roma_scene *scene, const roma_effect_options *options,
                                             const roma_logger *logger, roma_effect_plan *out_plan);

/** Whether a plan runs a pass. 0 for a NULL plan or a pass outside the enum (a shift by 32
 * or more is undefined).
 *
 * @param plan  from roma_effect_plan_derive; may be NULL.
 * @param pass  the pass.
 * @return 1 when the plan runs pass, else 0.
 * @par Threads
 * Any thread (pure). */
static inline int roma_effect_plan_runs(const roma_effect_plan *plan, roma_pass_kind pass)
{
    return plan && (uint32_t)pass < (uint32_t)ROMA_PASS_COUNT && ((plan->passes >> (uint32_t)pass) & 1u);
}

#ifdef __cplusplus
}
#endif

#endif /* ROMA_EFFECTS_H */
