/* Built-in scenes: each builds, deterministically, with finite data and the
 * features it exists for (closed Cornell room with an area light and one
 * spot; blinds with slats thinner than 1/128 of the scene). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "roma/builtin_scenes.h"
#include "roma/scene.h"

/* Moller-Trumbore with a small tolerance so rays through shared edges count. */
static double ray_hit(const float o[3], const double d[3], const roma_scene_view *v, uint32_t t)
{
    const float *p0 = v->positions + 3 * v->indices[3 * t], *p1 = v->positions + 3 * v->indices[3 * t + 1],
                *p2 = v->positions + 3 * v->indices[3 * t + 2];
    double e1[3], e2[3], s[3], p[3], q[3];
    for (int k = 0; k < 3; ++k) {
        e1[k] = p1[k] - p0[k];
        e2[k] = p2[k] - p0[k];
        s[k] = o[k] - p0[k];
    }
    p[0] = d[1] * e2[2] - d[2] * e2[1], p[1] = d[2] * e2[0] - d[0] * e2[2], p[2] = d[0] * e2[1] - d[1] * e2[0];
    double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (fabs(det) < 1e-12)
        return -1.0;
    double u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) / det;
    q[0] = s[1] * e1[2] - s[2] * e1[1], q[1] = s[2] * e1[0] - s[0] * e1[2], q[2] = s[0] * e1[1] - s[1] * e1[0];
    double w = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
    double t_hit = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
    const double eps = 1e-6;
    if (u < -eps || w < -eps || u + w > 1.0 + eps || t_hit <= 1e-6)
        return -1.0;
    return t_hit;
}

static double closest_hit(const float o[3], const double d[3], const roma_scene_view *v)
{
    double best = -1.0;
    for (uint32_t t = 0; t < v->triangle_count; ++t) {
        double h = ray_hit(o, d, v, t);
        if (h > 0.0 && (best < 0.0 || h < best))
            best = h;
    }
    return best;
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static void check_common(const char *name, const roma_scene_view *v)
{
    CHECK(strcmp(v->name, name) == 0);
    CHECK(v->triangle_count > 0 && v->degenerate_triangle_count == 0);
    for (uint32_t i = 0; i < 3 * v->vertex_count; ++i)
        CHECK(isfinite(v->positions[i]) && isfinite(v->normals[i]));
    for (int k = 0; k < 3; ++k)
        CHECK(v->bounds_max[k] > v->bounds_min[k]);
    CHECK(v->has_camera);
}

/* area_light: 1 for cornell, 0 for cornell_spot (same room, ceiling quad dark). */
static void test_cornell(const roma_scene_view *v, int area_light)
{
    CHECK(area_light ? v->emissive_triangle_count >= 2 : v->emissive_triangle_count == 0);
    CHECK(v->light_count == 1 && v->lights[0].type == ROMA_LIGHT_SPOT);
    int red = 0, green = 0;
    for (uint32_t m = 0; m < v->material_count; ++m) {
        const float *c = v->materials[m].base_color;
        red += c[0] > 2 * c[1] && c[0] > 2 * c[2];
        green += c[1] > 2 * c[0] && c[1] > 2 * c[2];
    }
    CHECK(red == 1 && green == 1);
    for (int k = 0; k < 3; ++k) /* the camera is inside the room */
        CHECK(v->camera.eye[k] > v->bounds_min[k] && v->camera.eye[k] < v->bounds_max[k]);

    /* Closed room: 200 directions from inside all hit a wall within the box. */
    const float o[3] = {0.0f, 1.5f, 0.0f};
    double diag = 0.0;
    for (int k = 0; k < 3; ++k)
        diag += (v->bounds_max[k] - v->bounds_min[k]) * (v->bounds_max[k] - v->bounds_min[k]);
    int misses = 0;
    for (int i = 0; i < 200; ++i) {
        double z = 1.0 - (2.0 * i + 1.0) / 200.0, r = sqrt(1.0 - z * z), phi = i * 2.39996322972865332;
        double d[3] = {r * cos(phi), z, r * sin(phi)};
        double h = closest_hit(o, d, v);
        misses += !(h > 0.0 && h * h <= diag);
    }
    if (misses)
        fprintf(stderr, "cornell: %d of 200 rays escaped the room\n", misses);
    CHECK(misses == 0);
}

/* Horizontal faces (all three vertices at one height) at levels closer than
 * extent/128: each slat contributes its top and bottom. */
static void test_blinds(const roma_scene_view *v)
{
    CHECK(v->emissive_triangle_count > 0);
    CHECK(v->light_count == 1 && v->lights[0].type == ROMA_LIGHT_DIRECTIONAL);
    float extent = 0.0f;
    for (int k = 0; k < 3; ++k)
        extent = fmaxf(extent, v->bounds_max[k] - v->bounds_min[k]);
    float *levels = malloc(v->triangle_count * sizeof *levels);
    uint32_t n = 0;
    for (uint32_t t = 0; levels && t < v->triangle_count; ++t) {
        const uint32_t *tri = v->indices + 3 * t;
        float y = v->positions[3 * tri[0] + 1];
        if (v->positions[3 * tri[1] + 1] == y && v->positions[3 * tri[2] + 1] == y)
            levels[n++] = y;
    }
    qsort(levels, n, sizeof *levels, cmp_float);
    int thin = 0;
    for (uint32_t i = 1; i < n; ++i)
        thin += levels[i] > levels[i - 1] && levels[i] - levels[i - 1] < extent / 128.0f;
    free(levels);
    printf("blinds: %d horizontal gaps below extent/128 = %g\n", thin, extent / 128.0f);
    CHECK(thin >= 30);
}

int main(void)
{
    roma_test_log log;
    roma_logger logger = roma_test_logger(&log);
    const char *const *names = roma_builtin_scene_names();
    CHECK(names && names[0] && strcmp(names[0], "cornell") == 0);
    int count = 0, seen_blinds = 0;
    for (; names && names[count]; ++count) {
        const char *name = names[count];
        roma_scene *a = NULL, *b = NULL;
        CHECK_RESULT(roma_scene_create_builtin(name, &logger, &a), ROMA_SUCCESS);
        CHECK_RESULT(roma_scene_create_builtin(name, &logger, &b), ROMA_SUCCESS);
        if (!a || !b) {
            roma_scene_destroy(a);
            roma_scene_destroy(b);
            continue;
        }
        roma_scene_view v, w;
        roma_scene_get_view(a, &v);
        roma_scene_get_view(b, &w);
        printf("%s: %u triangles, %u emissive, %u lights\n", name, v.triangle_count,
               v.emissive_triangle_count, v.light_count);
        check_common(name, &v);
        CHECK(v.vertex_count == w.vertex_count && v.triangle_count == w.triangle_count);
        CHECK(memcmp(v.positions, w.positions, 3 * sizeof(float) * v.vertex_count) == 0);
        CHECK(memcmp(v.indices, w.indices, 3 * sizeof(uint32_t) * v.triangle_count) == 0);
        if (!strcmp(name, "cornell") || !strcmp(name, "cornell_spot"))
            test_cornell(&v, !strcmp(name, "cornell"));
        if (!strcmp(name, "blinds")) {
            seen_blinds = 1;
            test_blinds(&v);
        }
        roma_scene_destroy(a);
        roma_scene_destroy(b);
    }
    CHECK(count >= 2 && seen_blinds);
    CHECK(log.errors == 0 && log.warnings == 0);

    roma_scene *s = NULL;
    CHECK_RESULT(roma_scene_create_builtin(NULL, NULL, &s), ROMA_SUCCESS); /* default: cornell */
    if (s) {
        roma_scene_view v;
        roma_scene_get_view(s, &v);
        CHECK(strcmp(v.name, "cornell") == 0);
        roma_scene_destroy(s);
    }
    s = (roma_scene *)&count;
    CHECK_RESULT(roma_scene_create_builtin("no-such-scene", &logger, &s), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(s == NULL && log.errors == 1);
    CHECK_RESULT(roma_scene_create_builtin("cornell", &logger, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    return roma_test_finish("test_builtin_scenes");
}
