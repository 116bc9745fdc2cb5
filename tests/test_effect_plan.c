/* The effect plan (roma/effects.h): scenes with and without each trigger run
 * exactly the passes they call for, and arrays are shared per distinct (RES, A). */
#include <string.h>

#include "harness.h"
#include "roma/builtin_scenes.h"
#include "roma/effects.h"
#include "roma/scene.h"

static const uint32_t ALL = ROMA_EFFECT_AO | ROMA_EFFECT_DIRECT | ROMA_EFFECT_GI | ROMA_EFFECT_LIGHTS;

static uint32_t bits(int count, const roma_pass_kind *passes)
{
    uint32_t b = 0;
    for (int i = 0; i < count; ++i)
        b |= 1u << passes[i];
    return b;
}
#define PASSES(...) bits((int)(sizeof((roma_pass_kind[]){__VA_ARGS__}) / sizeof(roma_pass_kind)), \
                         (roma_pass_kind[]){__VA_ARGS__})

/* A floor quad with the given lights and, if emissive, a glowing material. */
static roma_scene *quad_scene(const roma_light *lights, uint32_t light_count, int emissive)
{
    static const float pos[] = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
    static const uint32_t idx[] = {0, 1, 2, 0, 2, 3};
    roma_material m = {{0.5f, 0.5f, 0.5f}, {emissive ? 1.0f : 0.0f, 0, 0}};
    roma_scene_desc d = {.positions = pos, .vertex_count = 4, .indices = idx, .triangle_count = 2,
                         .materials = &m, .material_count = 1, .lights = lights, .light_count = light_count};
    roma_scene *s = NULL;
    CHECK_RESULT(roma_scene_create(&d, &s), ROMA_SUCCESS);
    return s;
}

static roma_effect_plan plan_of(const roma_scene *scene, uint32_t effects)
{
    roma_effect_plan p;
    roma_effect_options o = {.effects = effects};
    CHECK_RESULT(roma_effect_plan_derive(scene, &o, NULL, &p), ROMA_SUCCESS);
    return p;
}

static void test_builtins(void)
{
    roma_scene *cornell = NULL, *plates = NULL, *blinds = NULL;
    CHECK_RESULT(roma_scene_create_builtin("cornell", NULL, &cornell), ROMA_SUCCESS);
    CHECK_RESULT(roma_scene_create_builtin("plates", NULL, &plates), ROMA_SUCCESS);
    CHECK_RESULT(roma_scene_create_builtin("blinds", NULL, &blinds), ROMA_SUCCESS);
    if (!cornell || !plates || !blinds)
        goto done;

    /* Cornell: area light + spot light: every pass; two arrays (A = 4 and A = 8). */
    roma_effect_plan p = plan_of(cornell, ALL);
    CHECK(p.passes == PASSES(ROMA_PASS_GBUFFER, ROMA_PASS_AO, ROMA_PASS_PUNCTUAL_LIGHTS, ROMA_PASS_SOFT_SHADOWS,
                             ROMA_PASS_MANY_LIGHTS, ROMA_PASS_RSM, ROMA_PASS_GI));
    CHECK(p.map_count == 2);
    CHECK(p.pass_map[ROMA_PASS_AO] == p.pass_map[ROMA_PASS_GI]);
    CHECK(p.pass_map[ROMA_PASS_SOFT_SHADOWS] == p.pass_map[ROMA_PASS_PUNCTUAL_LIGHTS]);
    CHECK(p.pass_map[ROMA_PASS_SOFT_SHADOWS] == p.pass_map[ROMA_PASS_MANY_LIGHTS]);
    CHECK(p.pass_map[ROMA_PASS_AO] != p.pass_map[ROMA_PASS_SOFT_SHADOWS]);
    CHECK(p.maps[p.pass_map[ROMA_PASS_AO]].angular == 4 && p.maps[p.pass_map[ROMA_PASS_AO]].resolution == 128);
    CHECK(p.maps[p.pass_map[ROMA_PASS_SOFT_SHADOWS]].angular == 8);
    CHECK(p.pass_map[ROMA_PASS_GBUFFER] == -1 && p.pass_map[ROMA_PASS_RSM] == -1);
    CHECK(p.many_light_count == 256);

    /* AO only: one array, no light pass. */
    p = plan_of(cornell, ROMA_EFFECT_AO);
    CHECK(p.passes == PASSES(ROMA_PASS_GBUFFER, ROMA_PASS_AO));
    CHECK(p.map_count == 1 && p.maps[0].angular == 4);
    CHECK(p.many_light_count == 0);

    /* Direct light only: no A = 4 array is built. */
    p = plan_of(cornell, ROMA_EFFECT_DIRECT);
    CHECK(p.passes == PASSES(ROMA_PASS_GBUFFER, ROMA_PASS_PUNCTUAL_LIGHTS, ROMA_PASS_SOFT_SHADOWS));
    CHECK(p.map_count == 1 && p.maps[0].angular == 8);

    /* Plates: one area light, no punctual light: soft shadows and GI (its bounce hits
     * lit by area-light samples), no RSM. */
    p = plan_of(plates, ALL & ~(uint32_t)ROMA_EFFECT_LIGHTS);
    CHECK(p.passes == PASSES(ROMA_PASS_GBUFFER, ROMA_PASS_AO, ROMA_PASS_SOFT_SHADOWS, ROMA_PASS_GI));
    p = plan_of(plates, ROMA_EFFECT_GI);
    CHECK(p.passes == PASSES(ROMA_PASS_GBUFFER, ROMA_PASS_GI) && p.map_count == 1 && p.maps[0].angular == 4);

    /* Blinds: a directional light (no RSM for it) and an area light. */
    p = plan_of(blinds, ROMA_EFFECT_DIRECT | ROMA_EFFECT_GI);
    CHECK(p.passes == PASSES(ROMA_PASS_GBUFFER, ROMA_PASS_PUNCTUAL_LIGHTS, ROMA_PASS_SOFT_SHADOWS, ROMA_PASS_GI));
    CHECK(p.map_count == 2);
done:
    roma_scene_destroy(cornell);
    roma_scene_destroy(plates);
    roma_scene_destroy(blinds);
}

static void test_custom_scenes(void)
{
    /* No light at all: direct and GI need nothing; AO alone traces. */
    roma_scene *dark = quad_scene(NULL, 0, 0);
    roma_light point = {.type = ROMA_LIGHT_POINT, .position = {0, 1, 0}, .color = {1, 1, 1}, .intensity = 2};
    roma_scene *lit = quad_scene(&point, 1, 0);
    roma_light off = point;
    off.intensity = 0.0f;
    roma_scene *unlit = quad_scene(&off, 1, 0);
    roma_scene *glow = quad_scene(NULL, 0, 1);
    if (!dark || !lit || !unlit || !glow)
        goto done;
    roma_effect_plan p = plan_of(dark, ROMA_EFFECT_DIRECT | ROMA_EFFECT_GI);
    CHECK(p.passes == 0 && p.map_count == 0);
    CHECK(p.effects == (ROMA_EFFECT_DIRECT | ROMA_EFFECT_GI));
    p = plan_of(dark, ROMA_EFFECT_AO | ROMA_EFFECT_DIRECT | ROMA_EFFECT_GI);
    CHECK(p.passes == PASSES(ROMA_PASS_GBUFFER, ROMA_PASS_AO));
    p = plan_of(dark, 0);
    CHECK(p.passes == 0 && p.map_count == 0);

    /* A point light: direct with shadows and GI through an RSM, no soft shadows. */
    p = plan_of(lit, ROMA_EFFECT_DIRECT | ROMA_EFFECT_GI);
    CHECK(p.passes == PASSES(ROMA_PASS_GBUFFER, ROMA_PASS_PUNCTUAL_LIGHTS, ROMA_PASS_RSM, ROMA_PASS_GI));
    CHECK(p.map_count == 2);

    /* A light of zero intensity casts nothing: no pass for it. */
    p = plan_of(unlit, ROMA_EFFECT_DIRECT | ROMA_EFFECT_GI);
    CHECK(p.passes == 0);

    /* Emissive triangles alone: soft shadows, no punctual pass; GI without an RSM. */
    p = plan_of(glow, ROMA_EFFECT_DIRECT);
    CHECK(p.passes == PASSES(ROMA_PASS_GBUFFER, ROMA_PASS_SOFT_SHADOWS));
    p = plan_of(glow, ROMA_EFFECT_GI);
    CHECK(p.passes == PASSES(ROMA_PASS_GBUFFER, ROMA_PASS_GI));

    /* Equal A for every pass: one array shared by all of them. */
    roma_effect_options o = {.effects = ROMA_EFFECT_AO | ROMA_EFFECT_DIRECT | ROMA_EFFECT_GI | ROMA_EFFECT_LIGHTS,
                             .resolution = 64, .ao_angular = 6, .gi_angular = 6, .shadow_angular = 6,
                             .lights_angular = 6, .many_light_count = 1000};
    CHECK_RESULT(roma_effect_plan_derive(lit, &o, NULL, &p), ROMA_SUCCESS);
    CHECK(p.map_count == 1 && p.maps[0].resolution == 64 && p.maps[0].angular == 6);
    CHECK(p.many_light_count == 1000);
done:
    roma_scene_destroy(dark);
    roma_scene_destroy(lit);
    roma_scene_destroy(unlit);
    roma_scene_destroy(glow);
}

static void test_bad_options(void)
{
    roma_scene *s = quad_scene(NULL, 0, 0);
    if (!s)
        return;
    roma_test_log log = {0};
    roma_logger logger = roma_test_logger(&log);
    roma_effect_plan p;
    roma_effect_options bad[] = {
        {.effects = 1u << 7},
        {.effects = ROMA_EFFECT_AO, .resolution = 100},
        {.effects = ROMA_EFFECT_AO, .resolution = 512},
        {.effects = ROMA_EFFECT_AO, .ao_angular = 17},
        {.effects = ROMA_EFFECT_LIGHTS, .many_light_count = 70000},
        {.effects = ROMA_EFFECT_AO, .preset = (roma_preset)5},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        memset(&p, 0xab, sizeof p);
        int before = log.errors;
        CHECK_RESULT(roma_effect_plan_derive(s, &bad[i], &logger, &p), ROMA_ERROR_INVALID_ARGUMENT);
        CHECK(log.errors == before + 1);
        CHECK(p.passes == 0 && p.map_count == 0);
    }
    CHECK_RESULT(roma_effect_plan_derive(NULL, NULL, &logger, &p), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_effect_plan_derive(s, NULL, &logger, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    /* NULL options: nothing asked, nothing runs. */
    CHECK_RESULT(roma_effect_plan_derive(s, NULL, NULL, &p), ROMA_SUCCESS);
    CHECK(p.passes == 0);
    CHECK(strcmp(roma_pass_name(ROMA_PASS_SOFT_SHADOWS), "soft_shadows") == 0);
    CHECK(strcmp(roma_pass_name((roma_pass_kind)99), "unknown") == 0);
    roma_scene_destroy(s);
}

/* Presets (roma/presets.h): RES and A of the snapped rays where the options leave them 0;
 * an explicit value wins; shadow rays keep A 8. */
static void test_presets(void)
{
    roma_scene *s = quad_scene(NULL, 0, 1); /* emissive: GI runs */
    if (!s)
        return;
    static const uint32_t want[][2] = {{128, 4}, {128, 2}, {128, 4}, {256, 4}, {256, 8}};
    for (unsigned preset = 0; preset <= ROMA_PRESET_COUNT; ++preset) {
        uint32_t res = 0, angular = 0;
        CHECK_RESULT(roma_preset_map_settings((roma_preset)preset, &res, &angular), ROMA_SUCCESS);
        CHECK(res == want[preset][0] && angular == want[preset][1]);
        roma_effect_options o = {.effects = ROMA_EFFECT_AO | ROMA_EFFECT_GI, .preset = (roma_preset)preset};
        roma_effect_plan p;
        CHECK_RESULT(roma_effect_plan_derive(s, &o, NULL, &p), ROMA_SUCCESS);
        const roma_pass_kind snapped[2] = {ROMA_PASS_AO, ROMA_PASS_GI};
        for (int i = 0; i < 2; ++i) {
            const roma_map_config *m = &p.maps[p.pass_map[snapped[i]]];
            CHECK(p.pass_map[snapped[i]] >= 0 && m->resolution == want[preset][0] && m->angular == want[preset][1]);
        }
        o.resolution = 64, o.ao_angular = 3;
        CHECK_RESULT(roma_effect_plan_derive(s, &o, NULL, &p), ROMA_SUCCESS);
        CHECK(p.maps[p.pass_map[ROMA_PASS_AO]].resolution == 64 && p.maps[p.pass_map[ROMA_PASS_AO]].angular == 3);
        CHECK(p.maps[p.pass_map[ROMA_PASS_GI]].angular == want[preset][1]);
        /* Names: each parses back to itself (any case); the default reads as medium. */
        roma_preset back = (roma_preset)99;
        CHECK_RESULT(roma_preset_parse(roma_preset_name((roma_preset)preset), &back), ROMA_SUCCESS);
        CHECK(back == (preset == ROMA_PRESET_DEFAULT ? ROMA_PRESET_MEDIUM : (roma_preset)preset));
    }
    roma_preset p = ROMA_PRESET_LOW;
    CHECK_RESULT(roma_preset_parse("ULTRA", &p), ROMA_SUCCESS);
    CHECK(p == ROMA_PRESET_ULTRA);
    CHECK_RESULT(roma_preset_parse("extreme", &p), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_preset_parse("ultr", &p), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK_RESULT(roma_preset_parse(NULL, &p), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(p == ROMA_PRESET_ULTRA); /* left unchanged */
    CHECK(roma_preset_name((roma_preset)5) == NULL);
    uint32_t res = 7;
    CHECK_RESULT(roma_preset_map_settings((roma_preset)5, &res, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(res == 7);
    roma_scene_destroy(s);
}

int main(void)
{
    test_presets();
    test_builtins();
    test_custom_scenes();
    test_bad_options();
    return roma_test_finish("test_effect_plan");
}
