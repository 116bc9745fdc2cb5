/* The effect plan: which passes run and which ROMA arrays they trace, from the
 * scene's lights and the caller's options (roma/effects.h). Pure CPU. */
#include <string.h>

#include "roma/effects.h"
#include "roma/presets.h"
#include "roma_shared.h"
#include "util/log.h"

static const char *const pass_names[ROMA_PASS_COUNT] = {
    "gbuffer", "ao", "punctual_lights", "soft_shadows", "many_lights", "rsm", "gi",
};

const char *roma_pass_name(roma_pass_kind pass)
{
    return (unsigned)pass < ROMA_PASS_COUNT ? pass_names[pass] : "unknown";
}

static int valid_resolution(uint32_t r)
{
    return r == 32 || r == 64 || r == 128 || r == 256;
}

/* Index of (res, angular) in the plan's arrays, added when new. */
static int32_t use_map(roma_effect_plan *plan, uint32_t res, uint32_t angular)
{
    for (uint32_t i = 0; i < plan->map_count; ++i)
        if (plan->maps[i].resolution == res && plan->maps[i].angular == angular)
            return (int32_t)i;
    plan->maps[plan->map_count] = (roma_map_config){res, angular};
    return (int32_t)plan->map_count++;
}

static void add_pass(roma_effect_plan *plan, roma_pass_kind pass, uint32_t res, uint32_t angular)
{
    plan->passes |= 1u << pass;
    plan->pass_map[pass] = angular ? use_map(plan, res, angular) : -1;
}

roma_result roma_effect_plan_derive(const roma_scene *scene, const roma_effect_options *options,
                                    const roma_logger *logger, roma_effect_plan *out_plan)
{
    if (!out_plan)
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_effect_plan_derive: out_plan is NULL");
    memset(out_plan, 0, sizeof *out_plan);
    for (int i = 0; i < ROMA_PASS_COUNT; ++i)
        out_plan->pass_map[i] = -1;
    roma_scene_view v;
    if (!scene || roma_scene_get_view(scene, &v) != ROMA_SUCCESS)
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_effect_plan_derive: scene is NULL");
    roma_effect_options o = options ? *options : (roma_effect_options){0};
    uint32_t preset_res = 0, preset_angular = 0;
    if (roma_preset_map_settings(o.preset, &preset_res, &preset_angular) != ROMA_SUCCESS)
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_effect_plan_derive: unknown preset %d",
                         (int)o.preset);
    if (o.resolution == 0) o.resolution = preset_res;
    if (o.ao_angular == 0) o.ao_angular = preset_angular;
    if (o.gi_angular == 0) o.gi_angular = preset_angular;
    if (o.shadow_angular == 0) o.shadow_angular = 8;
    if (o.lights_angular == 0) o.lights_angular = 8;
    if (o.many_light_count == 0) o.many_light_count = 256;

    if (o.effects & ~(uint32_t)ROMA_EFFECT_ALL_)
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_effect_plan_derive: unknown effect bits 0x%x", o.effects & ~(uint32_t)ROMA_EFFECT_ALL_);
    if (!valid_resolution(o.resolution))
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_effect_plan_derive: resolution %u is not one of 32, 64, 128, 256", o.resolution);
    const uint32_t angulars[4] = {o.ao_angular, o.gi_angular, o.shadow_angular, o.lights_angular};
    for (int i = 0; i < 4; ++i)
        if (angulars[i] > ROMA_MAX_ANGULAR)
            return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT,
                             "roma_effect_plan_derive: angular resolution %u is outside [1, %u]", angulars[i],
                             ROMA_MAX_ANGULAR);
    if (o.many_light_count > 65536u)
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_effect_plan_derive: %u many lights (at most 65536)", o.many_light_count);

    uint32_t punctual = 0, rsm_lights = 0;
    for (uint32_t i = 0; i < v.light_count; ++i) {
        const roma_light *l = &v.lights[i];
        if (!(l->intensity > 0.0f) || !(l->color[0] > 0.0f || l->color[1] > 0.0f || l->color[2] > 0.0f))
            continue; /* a dark light casts nothing: no pass for it */
        ++punctual;
        rsm_lights += l->type == ROMA_LIGHT_POINT || l->type == ROMA_LIGHT_SPOT;
    }

    roma_effect_plan *p = out_plan;
    p->effects = o.effects;
    if (o.effects & ROMA_EFFECT_AO)
        add_pass(p, ROMA_PASS_AO, o.resolution, o.ao_angular);
    if ((o.effects & ROMA_EFFECT_DIRECT) && punctual)
        add_pass(p, ROMA_PASS_PUNCTUAL_LIGHTS, o.resolution, o.shadow_angular);
    if ((o.effects & ROMA_EFFECT_DIRECT) && v.emissive_triangle_count)
        add_pass(p, ROMA_PASS_SOFT_SHADOWS, o.resolution, o.shadow_angular);
    if ((o.effects & ROMA_EFFECT_GI) && (punctual || v.emissive_triangle_count)) {
        if (rsm_lights)
            add_pass(p, ROMA_PASS_RSM, 0, 0);
        add_pass(p, ROMA_PASS_GI, o.resolution, o.gi_angular);
    }
    if (o.effects & ROMA_EFFECT_LIGHTS) {
        add_pass(p, ROMA_PASS_MANY_LIGHTS, o.resolution, o.lights_angular);
        p->many_light_count = o.many_light_count;
    }
    if (p->passes)
        add_pass(p, ROMA_PASS_GBUFFER, 0, 0);
    return ROMA_SUCCESS;
}
