/* Lights in awkward places never put NaN or Inf into an image: every effect on
 * ROMA (still and moving camera) over scenes with a point light on a surface,
 * a point light shut inside a closed box, a grazing sun, a spot light with a
 * zero-width cone, a light of zero and one of enormous intensity, normals that
 * point away from their faces and a degenerate emissive triangle. Every pixel of
 * every image is checked: finite, AO in [0, 1], light counts in [0, lights],
 * radiance >= 0. Validation stays clean. RES 64 and small RSMs keep it fast:
 * what is tested is robustness, not accuracy. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "passes/effect_render.h"
#include "roma/sampling.h"

#define W 32u
#define H 24u
#define LIGHTS 16u

/* A floor (y = 0, 4 x 4), a closed unit box standing on it, an emissive quad
 * overhead and one degenerate emissive triangle, with the given lights. */
static roma_scene *make_scene(const roma_light *lights, uint32_t light_count, int flip_normals)
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
    roma_material m[2] = {{{0.7f, 0.7f, 0.7f}, {0, 0, 0}}, {{0.5f, 0.5f, 0.5f}, {3, 3, 3}}};
    /* Vertex normals opposite to what the faces say (the floor's faces point up). */
    float normals[sizeof pos / sizeof pos[0]];
    for (size_t i = 0; i < sizeof pos / sizeof pos[0]; i += 3) {
        normals[i] = 0.0f;
        normals[i + 1] = flip_normals ? -1.0f : 1.0f;
        normals[i + 2] = 0.0f;
    }
    roma_scene_desc d = {.positions = pos, .normals = normals, .vertex_count = 19, .indices = idx,
                         .triangle_count = tri_count, .triangle_materials = mats, .materials = m,
                         .material_count = 2, .lights = lights, .light_count = light_count};
    roma_scene *s = NULL;
    CHECK_RESULT(roma_scene_create(&d, &s), ROMA_SUCCESS);
    return s;
}

static void check_images(const char *name, const roma_effect_images *img)
{
    uint32_t bad = 0;
    for (uint32_t i = 0; i < W * H; ++i) {
        float ao = img->ao.pixels[i], n = img->lights.pixels[i];
        bad += !(ao >= 0.0f && ao <= 1.0f) + !(n >= 0.0f && n <= (float)LIGHTS);
        for (int c = 0; c < 3; ++c) {
            float a = img->direct.pixels[3 * i + c], b = img->gi.pixels[3 * i + c];
            bad += !(a >= 0.0f && isfinite(a)) + !(b >= 0.0f && isfinite(b));
        }
    }
    if (bad)
        fprintf(stderr, "%s: %u bad pixel values\n", name, bad);
    CHECK(bad == 0);
}

static void run_case(roma_context *ctx, const char *name, const roma_light *lights, uint32_t count, int flip)
{
    roma_scene *scene = make_scene(lights, count, flip);
    if (!scene)
        return;
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    float positions[3 * LIGHTS];
    roma_many_lights_positions(v.bounds_min, v.bounds_max, LIGHTS, 1, positions);
    /* One many-light sits on the floor and one inside the box. */
    positions[0] = 1.0f, positions[1] = 0.0f, positions[2] = 1.0f;
    positions[3] = 0.0f, positions[4] = 0.5f, positions[5] = 0.0f;
    roma_camera cam = {{0.0f, 1.5f, 3.5f}, {0.0f, 0.3f, 0.0f}, {0, 1, 0}, 60.0f};
    roma_camera path[3] = {cam, cam, cam};
    path[1].eye[0] = 0.4f;
    path[2].eye[0] = 0.8f;
    for (int moving = 0; moving < 2; ++moving) {
        roma_effect_render_desc d = {
            .camera = cam, .width = W, .height = H, .spp = 2, .frames = moving ? 3 : 1, .seed = 1, .rsm_size = 64,
            .options = {.effects = ROMA_EFFECT_AO | ROMA_EFFECT_DIRECT | ROMA_EFFECT_GI | ROMA_EFFECT_LIGHTS,
                        .many_light_count = LIGHTS, .resolution = 64},
            .many_light_positions = positions, .camera_path = moving ? path : NULL,
        };
        roma_effect_images img;
        roma_effect_stats st;
        CHECK_RESULT(roma_effect_render(ctx, scene, &d, &img, &st), ROMA_SUCCESS);
        if (img.ao.pixels) {
            char label[128];
            snprintf(label, sizeof label, "%s (%s camera)", name, moving ? "moving" : "still");
            check_images(label, &img);
            printf("%-40s passes 0x%02x, all pixels finite and in range\n", label, st.plan.passes);
        }
        roma_effect_images_free(&img);
    }
    roma_scene_destroy(scene);
}

int main(void)
{
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_skip("no Vulkan device");
    const roma_light on_floor = {.type = ROMA_LIGHT_POINT, .position = {1.0f, 0.0f, 0.0f},
                                 .color = {1, 1, 1}, .intensity = 5.0f};
    const roma_light in_box = {.type = ROMA_LIGHT_POINT, .position = {0.0f, 0.5f, 0.0f},
                               .color = {1, 1, 1}, .intensity = 5.0f};
    const roma_light grazing = {.type = ROMA_LIGHT_DIRECTIONAL, .direction = {1.0f, 0.0f, 0.0f},
                                .color = {1, 1, 1}, .intensity = 3.0f};
    const roma_light thin_spot = {.type = ROMA_LIGHT_SPOT, .position = {0.0f, 1.9f, 1.5f},
                                  .direction = {0.0f, -1.0f, -0.5f}, .color = {1, 1, 1}, .intensity = 5.0f,
                                  .inner_cone_angle = 0.3f, .outer_cone_angle = 0.3f};
    const roma_light dark = {.type = ROMA_LIGHT_POINT, .position = {0.0f, 1.5f, 0.0f}, .color = {1, 1, 1}};
    const roma_light huge = {.type = ROMA_LIGHT_POINT, .position = {0.0f, 1.5f, 1.0f}, .color = {1, 1, 1},
                             .intensity = 1e30f};
    /* Finite, but intensity / d^2 and the sums over frames overflow float unless
     * each light's irradiance is bounded (ROMA_MAX_IRRADIANCE). */
    const roma_light near_max = {.type = ROMA_LIGHT_POINT, .position = {1.0f, 0.001f, 0.0f},
                                 .color = {1, 1, 1}, .intensity = 3e38f};
    run_case(ctx, "point light on the floor", &on_floor, 1, 0);
    run_case(ctx, "point light inside the box", &in_box, 1, 0);
    run_case(ctx, "grazing sun", &grazing, 1, 0);
    run_case(ctx, "spot with a zero-width cone", &thin_spot, 1, 0);
    run_case(ctx, "zero-intensity light", &dark, 1, 0);
    run_case(ctx, "light of intensity 1e30", &huge, 1, 0);
    run_case(ctx, "3e38 cd, 1 mm above the floor", &near_max, 1, 0);
    run_case(ctx, "normals flipped, no punctual light", NULL, 0, 1);
    roma_test_context_finish(ctx);
    return roma_test_finish("test_effects_hard_cases");
}
