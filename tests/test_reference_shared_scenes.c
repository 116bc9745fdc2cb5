/* Smoke test of the reference tracer on real data: every model of
 * scenes/ and every built-in scene loads, gets a roma_ref and renders
 * all four effects at a small size with its default camera. Checks: the scene
 * covers > 10% of the pixels (5% for two thin figures, see shared_models);
 * every pixel is finite; AO lies in [0,1] and is 1 on the background; direct
 * and GI are >= 0 (and > 0 somewhere in the lit built-in cornell); many-lights
 * counts are integers in [0, LIGHTS]. The shared models have no punctual
 * lights, so their direct/GI may be zero. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "reference/reference.h"
#include "roma/builtin_scenes.h"
#include "roma/gltf.h"
#include "roma/sampling.h"
#include "roma/scene.h"

#define WIDTH 48u
#define HEIGHT 36u
#define SPP 4u
#define LIGHTS 16u

/* min_coverage: percent of pixels the model must cover. roma_scene_default_camera
 * frames the bounding sphere, so tall, thin figures (CesiumMan, Fox) fill less of a
 * 4:3 image (about 7%); everything else must cover more than 10%. */
typedef struct shared_model {
    const char *file;
    uint32_t min_coverage;
} shared_model;

static const shared_model shared_models[] = {
    {"cornell.glb", 10},     {"spot.glb", 10},          {"bunny.glb", 10},
    {"dragon_res3.glb", 10}, {"dragon_res2.glb", 10},   {"2CylinderEngine.glb", 10},
    {"tabletop.gltf", 10},   {"CesiumMan.glb", 5},      {"Fox.glb", 5},
};

typedef struct image_stats {
    uint32_t non_finite, negative, out_of_range;
    double max_value;
} image_stats;

/* Scans every channel of img; out_of_range counts values outside [lo, hi]. */
static image_stats scan(const roma_image *img, float lo, float hi)
{
    image_stats s = {0, 0, 0, 0.0};
    size_t n = (size_t)img->width * img->height * img->channels;
    for (size_t i = 0; i < n; ++i) {
        float v = img->pixels[i];
        if (!isfinite(v)) {
            ++s.non_finite;
            continue;
        }
        if (v < 0.0f)
            ++s.negative;
        if (v < lo || v > hi)
            ++s.out_of_range;
        if (v > s.max_value)
            s.max_value = v;
    }
    return s;
}

static int image_ok(const roma_image *img, uint32_t channels)
{
    return img->pixels && img->width == WIDTH && img->height == HEIGHT && img->channels == channels;
}

/* require_light: direct and GI must be > 0 somewhere (scenes with lights). */
static void check_scene(const char *label, const roma_scene *scene, uint32_t min_coverage,
                        int require_light)
{
    int failures_before = roma_test_failures;
    roma_scene_view v;
    CHECK_RESULT(roma_scene_get_view(scene, &v), ROMA_SUCCESS);

    roma_test_log log;
    roma_ref_desc ref_desc = {.thread_count = 0, .logger = roma_test_logger(&log)};
    roma_ref *ref = NULL;
    roma_result r = roma_ref_create(scene, &ref_desc, &ref);
    if (r != ROMA_SUCCESS || !ref) {
        fprintf(stderr, "%s: roma_ref_create failed: %s\n", label, roma_result_string(r));
        ++roma_test_failures;
        return;
    }

    float lights[3 * LIGHTS];
    roma_many_lights_positions(v.bounds_min, v.bounds_max, LIGHTS, 1, lights);
    roma_camera cam;
    roma_scene_default_camera(scene, (float)WIDTH / (float)HEIGHT, &cam);
    roma_ref_render_desc desc = {
        .camera = cam, .width = WIDTH, .height = HEIGHT,
        .effects = ROMA_EFFECT_AO | ROMA_EFFECT_DIRECT | ROMA_EFFECT_GI | ROMA_EFFECT_LIGHTS,
        .spp = SPP, .ao_radius = 0.0f, .seed = 1,
        .many_light_positions = lights, .many_light_count = LIGHTS,
    };
    roma_ref_images im;
    memset(&im, 0, sizeof im);
    r = roma_ref_render(ref, &desc, &im);
    if (r != ROMA_SUCCESS) {
        fprintf(stderr, "%s: roma_ref_render failed: %s\n", label, roma_result_string(r));
        ++roma_test_failures;
        roma_ref_destroy(ref);
        return;
    }
    CHECK(log.errors == 0);
    int shapes = image_ok(&im.ao, 1) && image_ok(&im.direct, 3) && image_ok(&im.gi, 3) &&
                 image_ok(&im.lights, 1) && image_ok(&im.coverage, 1);
    CHECK(shapes);
    if (!shapes) {
        fprintf(stderr, "%s: output images missing or of the wrong size/channels\n", label);
        roma_ref_images_free(&im);
        roma_ref_destroy(ref);
        return;
    }

    const uint32_t pixels = WIDTH * HEIGHT;
    uint32_t covered = 0, bad_coverage = 0, bad_background_ao = 0, bad_light_count = 0;
    for (uint32_t i = 0; i < pixels; ++i) {
        float c = im.coverage.pixels[i];
        if (c == 1.0f)
            ++covered;
        else if (c != 0.0f)
            ++bad_coverage;
        if (c == 0.0f && im.ao.pixels[i] != 1.0f)
            ++bad_background_ao;
        float l = im.lights.pixels[i];
        if (!(l >= 0.0f && l <= (float)LIGHTS && l == floorf(l)))
            ++bad_light_count;
    }
    image_stats ao = scan(&im.ao, 0.0f, 1.0f);
    image_stats direct = scan(&im.direct, 0.0f, INFINITY);
    image_stats gi = scan(&im.gi, 0.0f, INFINITY);
    image_stats cnt = scan(&im.lights, 0.0f, (float)LIGHTS);

    printf("%-28s %7u tris  coverage %5.1f%%  ao max %.3f  direct max %.4g  gi max %.4g  lights max %g\n",
           label, v.triangle_count, 100.0 * covered / pixels, ao.max_value, direct.max_value,
           gi.max_value, cnt.max_value);

    CHECK(covered * 100u > pixels * min_coverage);
    CHECK(bad_coverage == 0);
    CHECK(ao.non_finite == 0 && direct.non_finite == 0 && gi.non_finite == 0 && cnt.non_finite == 0);
    CHECK(ao.out_of_range == 0);
    CHECK(bad_background_ao == 0);
    CHECK(direct.negative == 0);
    CHECK(gi.negative == 0);
    CHECK(bad_light_count == 0);
    if (require_light) {
        CHECK(direct.max_value > 0.0);
        CHECK(gi.max_value > 0.0);
    }
    if (roma_test_failures != failures_before)
        fprintf(stderr, "%s: %d check(s) failed above\n", label, roma_test_failures - failures_before);

    roma_ref_images_free(&im);
    roma_ref_destroy(ref);
}

int main(void)
{
    char path[4096];
    size_t n = sizeof shared_models / sizeof shared_models[0];
    for (size_t i = 0; i < n; ++i) {
        if (!roma_test_scene_file(shared_models[i].file, path, sizeof path))
            continue;
        roma_test_log log;
        roma_gltf_desc desc = {.logger = roma_test_logger(&log)};
        roma_scene *scene = NULL;
        roma_result r = roma_scene_load_gltf(path, &desc, &scene);
        if (r != ROMA_SUCCESS || !scene) {
            fprintf(stderr, "%s: load failed: %s\n", shared_models[i].file, roma_result_string(r));
            ++roma_test_failures;
            continue;
        }
        check_scene(shared_models[i].file, scene, shared_models[i].min_coverage, 0);
        roma_scene_destroy(scene);
    }

    for (const char *const *name = roma_builtin_scene_names(); *name; ++name) {
        roma_test_log log;
        roma_logger logger = roma_test_logger(&log);
        roma_scene *scene = NULL;
        roma_result r = roma_scene_create_builtin(*name, &logger, &scene);
        char label[64];
        snprintf(label, sizeof label, "builtin:%s", *name);
        if (r != ROMA_SUCCESS || !scene) {
            fprintf(stderr, "%s: create failed: %s\n", label, roma_result_string(r));
            ++roma_test_failures;
            continue;
        }
        check_scene(label, scene, 10, strcmp(*name, "cornell") == 0);
        roma_scene_destroy(scene);
    }
    return roma_test_finish("test_reference_shared_scenes");
}
