/* Lights, normals and views in awkward places never put NaN or Inf into an
 * image, and where the answer is known the effects give it:
 *
 * 1. Every effect on ROMA through the public passes (support/public_render.h; GI from
 *    point and spot lights through their RSMs, the study's route, as well), from a still
 *    camera and a moved one, over a point light on a
 *    surface, one shut inside a closed box, a grazing sun, spot lights with a
 *    hard edge (inner = outer) and a needle cone (1e-6 rad), lights of zero and
 *    of enormous intensity, an area light of enormous emission, vertex normals
 *    flipped against their faces or missing, and cameras that see only back
 *    faces (inside the box, under the floor). Every pixel of every image is
 *    checked: finite, AO in [0, 1], light counts in [0, lights], radiance >= 0.
 * 2. A light of zero intensity renders exactly as no light at all.
 * 3. Direct light of the punctual cases (no area light, so no sampling noise)
 *    against Embree at the G-buffer's points: a light shut in the box leaks onto
 *    at most the measured fraction of pixels, a light on the floor and a sun in
 *    its plane give the floor exactly nothing, and elsewhere ROMA's voxel shadows
 *    stay within the measured error.
 * RES 64 and small RSMs keep it fast. Validation stays clean. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "public_render.h"
#include "reference.h"
#include "roma/sampling.h"

#define W 32u
#define H 24u
#define LIGHTS 16u
#define ALL_EFFECTS (ROMA_EFFECT_AO | ROMA_EFFECT_DIRECT | ROMA_EFFECT_GI | ROMA_EFFECT_LIGHTS)

typedef enum normals_kind { NORMALS_UP, NORMALS_FLIPPED, NORMALS_MISSING } normals_kind;

typedef struct scene_variant {
    const roma_light *lights;
    uint32_t light_count;
    normals_kind normals;
    float emission; /* of the quad overhead; 0: no area light */
} scene_variant;

/* A floor (y = 0, 4 x 4), a closed unit box standing on it, a quad overhead
 * (emissive unless v.emission is 0) and one degenerate emissive triangle. */
static roma_scene *make_scene(scene_variant v)
{
    static const float pos[] = {
        -2, 0, -2, 2, 0, -2, 2, 0, 2, -2, 0, 2,                                 /* floor 0-3 */
        -0.5f, 0, -0.5f, 0.5f, 0, -0.5f, 0.5f, 1, -0.5f, -0.5f, 1, -0.5f,       /* box 4-11 */
        -0.5f, 0, 0.5f, 0.5f, 0, 0.5f, 0.5f, 1, 0.5f, -0.5f, 1, 0.5f,
        -1, 2, -1, 1, 2, -1, 1, 2, 1, -1, 2, 1,                                 /* light quad 12-15 */
        0, 2.5f, 0, 0, 2.5f, 0, 0, 2.5f, 0,                                     /* degenerate 16-18 */
    };
    static const uint32_t idx[] = {
        0, 2, 1, 0, 3, 2,                                                       /* floor */
        4, 5, 6, 4, 6, 7, 8, 10, 9, 8, 11, 10, 4, 7, 11, 4, 11, 8,              /* box */
        5, 9, 10, 5, 10, 6, 7, 6, 10, 7, 10, 11, 4, 8, 9, 4, 9, 5,
        12, 13, 14, 12, 14, 15,                                                 /* light */
        16, 17, 18,
    };
    const uint32_t tri_count = (uint32_t)(sizeof idx / sizeof idx[0] / 3);
    uint32_t mats[sizeof idx / sizeof idx[0] / 3];
    for (uint32_t t = 0; t < tri_count; ++t)
        mats[t] = t >= 14 ? 1 : 0;
    const float e = v.emission;
    roma_material m[2] = {{{0.7f, 0.7f, 0.7f}, {0, 0, 0}}, {{0.5f, 0.5f, 0.5f}, {e, e, e}}};
    /* Every vertex normal points up, or down (against the floor's faces). */
    float normals[sizeof pos / sizeof pos[0]];
    for (size_t i = 0; i < sizeof pos / sizeof pos[0]; i += 3) {
        normals[i] = 0.0f;
        normals[i + 1] = v.normals == NORMALS_FLIPPED ? -1.0f : 1.0f;
        normals[i + 2] = 0.0f;
    }
    roma_scene_desc d = {.positions = pos, .normals = v.normals == NORMALS_MISSING ? NULL : normals,
                         .vertex_count = 19, .indices = idx, .triangle_count = tri_count,
                         .triangle_materials = mats, .materials = m, .material_count = 2,
                         .lights = v.lights, .light_count = v.light_count};
    roma_scene *s = NULL;
    CHECK_RESULT(roma_scene_create(&d, &s), ROMA_SUCCESS);
    return s;
}

static const roma_camera outside = {{0.0f, 1.5f, 3.5f}, {0.0f, 0.3f, 0.0f}, {0, 1, 0}, 60.0f};
static const roma_camera inside_box = {{0.1f, 0.4f, 0.2f}, {-0.3f, 0.6f, -0.4f}, {0, 1, 0}, 90.0f};
static const roma_camera under_floor = {{0.3f, -1.5f, 0.2f}, {0.0f, 0.0f, 0.0f}, {0, 0, 1}, 70.0f};

/* Every pixel finite and in range. (Coverage is not checked against Embree's primary
 * hits: the tools' G-buffer is made of those very hits, so the two agree by construction.) */
static void check_images(const char *name, const effect_api_result *img)
{
    uint32_t bad = 0;
    for (uint32_t i = 0; i < W * H; ++i) {
        float ao = img->ao.pixels[i], n = img->lights.pixels[i];
        uint32_t bad_here = !(ao >= 0.0f && ao <= 1.0f) + !(n >= 0.0f && n <= (float)LIGHTS);
        const float *a = &img->direct.pixels[3 * i], *b = &img->gi.pixels[3 * i];
        for (int k = 0; k < 3; ++k)
            bad_here += !(a[k] >= 0.0f && isfinite(a[k])) + !(b[k] >= 0.0f && isfinite(b[k]));
        if (bad_here && bad < 3)
            fprintf(stderr, "%s: pixel (%u, %u): ao %.9g, lights %g, direct (%g %g %g), gi (%g %g %g)\n", name,
                    i % W, i / W, ao, n, a[0], a[1], a[2], b[0], b[1], b[2]);
        bad += bad_here;
    }
    if (bad)
        fprintf(stderr, "%s: %u bad pixel values\n", name, bad);
    CHECK(bad == 0);
}

typedef struct render_out {
    effect_api_result img;
    roma_gbuffer_pixel px[W * H];
} render_out;

/* Renders every effect (a still camera over one frame, then, with also_moved, a moved one over three
 * frames with the last seed: its hashes wrap) and checks the images; the still camera's images
 * and G-buffer stay in *keep if given. The moved camera on the cases of extreme values and
 * back faces only: each render builds every effect's pipelines, which under the sanitizers
 * takes most of the test's time. */
static void run_case(roma_context *ctx, const char *name, scene_variant v, const roma_camera *cam,
                     render_out *keep, int also_moved)
{
    roma_scene *scene = make_scene(v);
    if (!scene)
        return;
    roma_ref *ref = NULL;
    CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    roma_scene_view sv;
    roma_scene_get_view(scene, &sv);
    float positions[3 * LIGHTS];
    roma_many_lights_positions(sv.bounds_min, sv.bounds_max, LIGHTS, 1, positions);
    /* One many-light sits on the floor and one inside the box. */
    positions[0] = 1.0f, positions[1] = 0.0f, positions[2] = 1.0f;
    positions[3] = 0.0f, positions[4] = 0.5f, positions[5] = 0.0f;
    roma_camera moved = *cam;
    moved.eye[0] += 0.2f;
    render_out *out = malloc(sizeof *out);
    for (int moving = 0; moving < 1 + also_moved && out && ref; ++moving) {
        memset(out, 0, sizeof *out);
        const effect_api_desc d = {
            .camera = moving ? moved : *cam, .width = W, .height = H, .spp = 2, .frames = moving ? 3 : 1,
            .gi_rsm = 1, .rsm_size = 64, .seed = moving ? 0xffffffffu : 1u,
            .options = {.effects = ALL_EFFECTS, .many_light_count = LIGHTS, .resolution = 64},
            .many_light_positions = positions,
        };
        CHECK_RESULT(roma_test_public_render(ctx, scene, ref, &d, &out->img, out->px), ROMA_SUCCESS);
        if (out->img.ao.pixels) {
            char label[128];
            snprintf(label, sizeof label, "%s (%s camera)", name, moving ? "moved" : "still");
            check_images(label, &out->img);
            printf("%-52s passes 0x%02x, all pixels finite and in range\n", label, out->img.plan.passes);
        }
        if (!moving && keep) {
            *keep = *out;
            memset(&out->img, 0, sizeof out->img);
        }
        effect_api_result_free(&out->img);
    }
    free(out);
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
}

/* 2. Two renders of the same view are identical, pixel for pixel. */
static void check_same_images(const char *what, const render_out *a, const render_out *b)
{
    const roma_image *ia[4] = {&a->img.ao, &a->img.direct, &a->img.gi, &a->img.lights};
    const roma_image *ib[4] = {&b->img.ao, &b->img.direct, &b->img.gi, &b->img.lights};
    uint32_t diff = 0;
    for (int e = 0; e < 4; ++e) {
        if (!ia[e]->pixels || !ib[e]->pixels) {
            ++diff;
            continue;
        }
        for (size_t i = 0; i < (size_t)W * H * ia[e]->channels; ++i)
            diff += !(ia[e]->pixels[i] == ib[e]->pixels[i]);
    }
    printf("%-52s %u values differ\n", what, diff);
    CHECK(diff == 0);
}

/* 3. Direct light of one punctual light, no area light: ROMA against Embree at the
 * G-buffer's points (the same points, so the difference is visibility only). */
typedef struct direct_bounds {
    double max_rel_mae;      /* sum |roma - ref| / sum ref (infinite if ROMA lights a scene Embree leaves dark) */
    double max_dark_lit;     /* fraction of pixels Embree leaves dark that ROMA lights */
    int floor_dark;          /* the light lies in the floor's plane: the floor is exactly dark in both */
} direct_bounds;

static void check_direct_against_embree(roma_context *ctx, const char *name, const roma_light *light,
                                        direct_bounds bounds)
{
    scene_variant v = {light, 1, NORMALS_UP, 0.0f};
    roma_scene *scene = make_scene(v);
    if (!scene)
        return;
    roma_ref *ref = NULL;
    CHECK_RESULT(roma_ref_create(scene, NULL, &ref), ROMA_SUCCESS);
    render_out *out = calloc(1, sizeof *out);
    const effect_api_desc d = {
        .camera = outside, .width = W, .height = H, .spp = 1, .frames = 1, .seed = 1,
        .options = {.effects = ROMA_EFFECT_DIRECT, .resolution = 64},
    };
    if (out && ref)
        CHECK_RESULT(roma_test_public_render(ctx, scene, ref, &d, &out->img, out->px), ROMA_SUCCESS);
    if (out && ref && out->img.direct.pixels) {
        double sum_ref = 0.0, sum_abs = 0.0, floor_roma = 0.0, floor_ref = 0.0;
        uint32_t covered = 0, dark = 0, dark_lit = 0;
        for (uint32_t i = 0; i < W * H; ++i) {
            const roma_gbuffer_pixel *p = &out->px[i];
            if (!isfinite(p->position_t[3]))
                continue;
            ++covered;
            float rgb[3];
            roma_ref_direct_point(ref, p->position_t, p->geometric_normal, p->shading_normal, p->albedo, 1, 1, i,
                                  rgb);
            const float *roma = &out->img.direct.pixels[3 * i];
            uint32_t triangle;
            memcpy(&triangle, &p->albedo[3], sizeof triangle);
            int on_floor = triangle < 2;
            for (int c = 0; c < 3; ++c) {
                sum_ref += rgb[c];
                sum_abs += fabs((double)roma[c] - rgb[c]);
                if (on_floor) {
                    floor_roma += roma[c];
                    floor_ref += rgb[c];
                }
            }
            if (rgb[0] == 0.0f && rgb[1] == 0.0f && rgb[2] == 0.0f) {
                ++dark;
                dark_lit += roma[0] > 0.0f || roma[1] > 0.0f || roma[2] > 0.0f;
            }
        }
        /* Where Embree is dark everywhere, any light from ROMA is an infinite relative error. */
        double rel_mae = sum_ref > 0.0 ? sum_abs / sum_ref : sum_abs > 0.0 ? INFINITY : 0.0;
        double dark_frac = dark ? (double)dark_lit / dark : 0.0;
        printf("%-52s vs Embree: %u px, relative MAE %.4f, %u of %u dark px lit (%.4f), floor %g / %g\n", name,
               covered, rel_mae, dark_lit, dark, dark_frac, floor_roma, floor_ref);
        CHECK(covered > W * H / 3);
        CHECK(rel_mae <= bounds.max_rel_mae);
        CHECK(dark_frac <= bounds.max_dark_lit);
        if (bounds.floor_dark)
            CHECK(floor_roma == 0.0 && floor_ref == 0.0);
    }
    if (out)
        effect_api_result_free(&out->img);
    free(out);
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
}

/* The part to run (ctest runs each as a test of its own, in parallel: every render builds
 * every effect's pipelines, which takes most of the time, several times longer under the
 * sanitizers): "1" the first cases of 1., "2" the others and 2., "3" the checks of 3.; no
 * argument: all. */
int main(int argc, char **argv)
{
    const int part = argc > 1 ? atoi(argv[1]) : 0;
    if (argc > 1 && (part < 1 || part > 3)) {
        fprintf(stderr, "usage: test_effects_hard_cases [1|2|3]\n");
        return 2;
    }
    const int two = part == 0 || part == 2, three = part == 0 || part == 3;
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_effects_hard_cases");
    const roma_light on_floor = {.type = ROMA_LIGHT_POINT, .position = {1.0f, 0.0f, 0.0f},
                                 .color = {1, 1, 1}, .intensity = 5.0f};
    const roma_light in_box = {.type = ROMA_LIGHT_POINT, .position = {0.0f, 0.5f, 0.0f},
                               .color = {1, 1, 1}, .intensity = 5.0f};
    const roma_light grazing = {.type = ROMA_LIGHT_DIRECTIONAL, .direction = {1.0f, 0.0f, 0.0f},
                                .color = {1, 1, 1}, .intensity = 3.0f};
    const roma_light hard_spot = {.type = ROMA_LIGHT_SPOT, .position = {0.0f, 1.9f, 1.5f},
                                  .direction = {0.0f, -1.0f, -0.5f}, .color = {1, 1, 1}, .intensity = 5.0f,
                                  .inner_cone_angle = 0.3f, .outer_cone_angle = 0.3f};
    /* cos(1e-6) rounds to 1 in float: the cone's edge and axis meet. */
    const roma_light needle_spot = {.type = ROMA_LIGHT_SPOT, .position = {1.0f, 1.9f, 1.0f},
                                    .direction = {0.0f, -1.0f, 0.0f}, .color = {1, 1, 1}, .intensity = 5.0f,
                                    .inner_cone_angle = 1e-6f, .outer_cone_angle = 1e-6f};
    const roma_light dark = {.type = ROMA_LIGHT_POINT, .position = {0.0f, 1.5f, 0.0f}, .color = {1, 1, 1}};
    const roma_light huge = {.type = ROMA_LIGHT_POINT, .position = {0.0f, 1.5f, 1.0f}, .color = {1, 1, 1},
                             .intensity = 1e30f};
    /* Finite, but intensity / d^2 and the sums over frames overflow float unless
     * each light's irradiance is bounded (ROMA_MAX_IRRADIANCE). */
    const roma_light near_max = {.type = ROMA_LIGHT_POINT, .position = {1.0f, 0.001f, 0.0f},
                                 .color = {1, 1, 1}, .intensity = 3e38f};
    const roma_light sun_and_spot[2] = {grazing, hard_spot};

    /* 1. Finite and in range: each case in its part, the moved camera where also_moved. */
    const struct {
        const char *name;
        scene_variant v;
        const roma_camera *cam;
        int also_moved, part;
    } cases[] = {
        {"point light on the floor", {&on_floor, 1, NORMALS_UP, 3.0f}, &outside, 1, 1},
        {"point light inside the box", {&in_box, 1, NORMALS_UP, 3.0f}, &outside, 0, 1},
        {"grazing sun", {&grazing, 1, NORMALS_UP, 3.0f}, &outside, 0, 1},
        {"spot with inner = outer", {&hard_spot, 1, NORMALS_UP, 3.0f}, &outside, 0, 1},
        {"spot with a 1e-6 rad cone", {&needle_spot, 1, NORMALS_UP, 3.0f}, &outside, 0, 1},
        {"light of intensity 1e30", {&huge, 1, NORMALS_UP, 3.0f}, &outside, 1, 1},
        {"3e38 cd, 1 mm above the floor", {&near_max, 1, NORMALS_UP, 3.0f}, &outside, 1, 1},
        {"area light of emission 1e30", {&on_floor, 1, NORMALS_UP, 1e30f}, &outside, 1, 2},
        {"normals flipped, no punctual light", {NULL, 0, NORMALS_FLIPPED, 3.0f}, &outside, 0, 2},
        {"normals flipped, sun and spot", {sun_and_spot, 2, NORMALS_FLIPPED, 3.0f}, &outside, 1, 2},
        {"normals missing, point light", {&on_floor, 1, NORMALS_MISSING, 3.0f}, &outside, 0, 2},
        {"back faces: camera inside the lit box", {&in_box, 1, NORMALS_MISSING, 3.0f}, &inside_box, 0, 2},
        {"back faces: camera under the floor", {sun_and_spot, 2, NORMALS_UP, 3.0f}, &under_floor, 1, 2},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i)
        if (part == 0 || part == cases[i].part)
            run_case(ctx, cases[i].name, cases[i].v, cases[i].cam, NULL, cases[i].also_moved);

    /* 2. Zero intensity is no light. */
    render_out *with_dark = two ? calloc(1, sizeof *with_dark) : NULL;
    render_out *without = two ? calloc(1, sizeof *without) : NULL;
    if (with_dark && without) {
        run_case(ctx, "zero-intensity light", (scene_variant){&dark, 1, NORMALS_UP, 3.0f}, &outside, with_dark, 0);
        run_case(ctx, "no punctual light", (scene_variant){NULL, 0, NORMALS_UP, 3.0f}, &outside, without, 0);
        check_same_images("zero-intensity light = no light:", with_dark, without);
        effect_api_result_free(&with_dark->img);
        effect_api_result_free(&without->img);
    }
    free(with_dark);
    free(without);

    /* 3. Against Embree. Bounds: the values measured on lavapipe (printed), plus 0.005.
     * A light in the floor's plane gives the floor nothing in both (the cosine is 0,
     * not a shadow). A point light 1 mm above the floor shows ROMA's known limit:
     * shadow rays that run along a surface meet its voxels, so the floor gets 38% of
     * the reference's light (docs/robustness.md). */
    const float a1 = 0.017452406f, c1 = 0.9998477f; /* sin and cos of 1 degree */
    const roma_light sun_1deg = {.type = ROMA_LIGHT_DIRECTIONAL, .direction = {c1, -a1, 0.0f},
                                 .color = {1, 1, 1}, .intensity = 3.0f};
    const roma_light sun_30deg = {.type = ROMA_LIGHT_DIRECTIONAL, .direction = {0.8660254f, -0.5f, 0.0f},
                                  .color = {1, 1, 1}, .intensity = 3.0f};
    if (three) {
        /* All dark in Embree: the leak is bounded by the fraction of pixels ROMA lights. */
        check_direct_against_embree(ctx, "light shut in the box", &in_box, (direct_bounds){INFINITY, 0.008, 0});
        check_direct_against_embree(ctx, "light on the floor", &on_floor, (direct_bounds){0.198, 0.005, 1});
        check_direct_against_embree(ctx, "sun in the floor's plane", &grazing, (direct_bounds){0.0, 0.005, 1});
        check_direct_against_embree(ctx, "sun 1 degree above the floor", &sun_1deg, (direct_bounds){0.005, 0.005, 0});
        check_direct_against_embree(ctx, "sun 30 degrees above the floor", &sun_30deg,
                                    (direct_bounds){0.028, 0.005, 0});
        check_direct_against_embree(ctx, "spot with inner = outer", &hard_spot, (direct_bounds){0.037, 0.005, 0});
        check_direct_against_embree(ctx, "spot with a 1e-6 rad cone", &needle_spot, (direct_bounds){0.0, 0.005, 0});
        check_direct_against_embree(ctx, "3e38 cd, 1 mm above the floor", &near_max, (direct_bounds){0.676, 0.048, 0});
    }

    roma_test_context_finish(ctx);
    return roma_test_finish("test_effects_hard_cases");
}
