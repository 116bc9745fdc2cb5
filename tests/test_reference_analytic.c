/* Reference tracer against closed-form answers: AO of planes, boxes, disks and
 * slabs; punctual, area and one-bounce lighting; many-lights visibility;
 * determinism across thread counts; argument validation.
 *
 * Monte Carlo checks use tolerance = 5 standard errors (Bernoulli variance for
 * AO, the sample variance of spp = 1 estimates otherwise). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "reference/reference.h"
#include "roma/sampling.h"
#include "roma/scene.h"

#define PI_D 3.14159265358979323846
#define DEG(x) ((float)((x) * PI_D / 180.0))

/* --- Scene building --- */

typedef struct mesh {
    float *pos;
    uint32_t *idx, *mat;
    uint32_t nv, nt, cap_v, cap_t;
} mesh;

static void mesh_reserve(mesh *m, uint32_t nv, uint32_t nt)
{
    if (m->nv + nv > m->cap_v) {
        m->cap_v = 2 * (m->nv + nv);
        m->pos = realloc(m->pos, 3 * sizeof(float) * m->cap_v);
    }
    if (m->nt + nt > m->cap_t) {
        m->cap_t = 2 * (m->nt + nt);
        m->idx = realloc(m->idx, 3 * sizeof(uint32_t) * m->cap_t);
        m->mat = realloc(m->mat, sizeof(uint32_t) * m->cap_t);
    }
    if (!m->pos || !m->idx || !m->mat) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
}

static uint32_t add_vertex(mesh *m, double x, double y, double z)
{
    m->pos[3 * m->nv + 0] = (float)x;
    m->pos[3 * m->nv + 1] = (float)y;
    m->pos[3 * m->nv + 2] = (float)z;
    return m->nv++;
}

static void add_tri(mesh *m, uint32_t a, uint32_t b, uint32_t c, uint32_t material)
{
    m->idx[3 * m->nt + 0] = a;
    m->idx[3 * m->nt + 1] = b;
    m->idx[3 * m->nt + 2] = c;
    m->mat[m->nt++] = material;
}

/* Parallelogram centre c, half-edge vectors u and v; own vertices (flat normals). */
static void add_quad(mesh *m, const double c[3], const double u[3], const double v[3],
                     uint32_t material)
{
    mesh_reserve(m, 4, 2);
    uint32_t i0 = add_vertex(m, c[0] - u[0] - v[0], c[1] - u[1] - v[1], c[2] - u[2] - v[2]);
    uint32_t i1 = add_vertex(m, c[0] + u[0] - v[0], c[1] + u[1] - v[1], c[2] + u[2] - v[2]);
    uint32_t i2 = add_vertex(m, c[0] + u[0] + v[0], c[1] + u[1] + v[1], c[2] + u[2] + v[2]);
    uint32_t i3 = add_vertex(m, c[0] - u[0] + v[0], c[1] - u[1] + v[1], c[2] - u[2] + v[2]);
    add_tri(m, i0, i1, i2, material);
    add_tri(m, i0, i2, i3, material);
}

/* Horizontal square (normal +-y) centred at (x, y, z) with half side h. */
static void add_hsquare(mesh *m, double x, double y, double z, double h, uint32_t material)
{
    double c[3] = {x, y, z}, u[3] = {h, 0, 0}, v[3] = {0, 0, h};
    add_quad(m, c, u, v, material);
}

static void add_box(mesh *m, const double lo[3], const double hi[3], uint32_t material)
{
    double c[3], e[3];
    for (int k = 0; k < 3; ++k) {
        c[k] = 0.5 * (lo[k] + hi[k]);
        e[k] = 0.5 * (hi[k] - lo[k]);
    }
    for (int axis = 0; axis < 3; ++axis)
        for (int side = -1; side <= 1; side += 2) {
            double fc[3] = {c[0], c[1], c[2]}, u[3] = {0, 0, 0}, v[3] = {0, 0, 0};
            fc[axis] += side * e[axis];
            int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
            u[a1] = e[a1];
            v[a2] = e[a2];
            add_quad(m, fc, u, v, material);
        }
}

/* Horizontal regular polygon (fan of n triangles), vertex radius r, centre c. */
static void add_disk(mesh *m, const double c[3], double r, uint32_t n, uint32_t material)
{
    mesh_reserve(m, n + 1, n);
    uint32_t centre = add_vertex(m, c[0], c[1], c[2]);
    uint32_t first = m->nv;
    for (uint32_t i = 0; i < n; ++i) {
        double a = 2.0 * PI_D * i / n;
        add_vertex(m, c[0] + r * cos(a), c[1], c[2] + r * sin(a));
    }
    for (uint32_t i = 0; i < n; ++i)
        add_tri(m, centre, first + i, first + (i + 1) % n, material);
}

static void mesh_free(mesh *m)
{
    free(m->pos);
    free(m->idx);
    free(m->mat);
    memset(m, 0, sizeof *m);
}

static roma_scene *make_scene(const mesh *m, const float *normals, const roma_material *mats,
                              uint32_t mat_count, const roma_light *lights, uint32_t light_count)
{
    roma_scene_desc d;
    memset(&d, 0, sizeof d);
    d.positions = m->pos;
    d.normals = normals;
    d.vertex_count = m->nv;
    d.indices = m->idx;
    d.triangle_count = m->nt;
    d.triangle_materials = m->mat;
    d.materials = mats;
    d.material_count = mat_count;
    d.lights = lights;
    d.light_count = light_count;
    d.name = "analytic";
    roma_scene *scene = NULL;
    CHECK_RESULT(roma_scene_create(&d, &scene), ROMA_SUCCESS);
    return scene;
}

static roma_ref *make_ref(const roma_scene *scene, uint32_t threads, roma_test_log *log)
{
    roma_ref_desc d;
    memset(&d, 0, sizeof d);
    d.thread_count = threads;
    d.logger = roma_test_logger(log);
    roma_ref *ref = NULL;
    if (scene)
        CHECK_RESULT(roma_ref_create(scene, &d, &ref), ROMA_SUCCESS);
    return ref;
}

/* --- Closed forms --- */

/* View factor from a differential area at x (normal n) to a polygon above its
 * tangent plane: contour integral (1/2pi) sum_i theta_i n . unit(r_i x r_i+1). */
static double view_factor_polygon(const double x[3], const double n[3], const double *v, int count)
{
    double sum = 0.0;
    for (int i = 0; i < count; ++i) {
        const double *a = &v[3 * i], *b = &v[3 * ((i + 1) % count)];
        double r0[3] = {a[0] - x[0], a[1] - x[1], a[2] - x[2]};
        double r1[3] = {b[0] - x[0], b[1] - x[1], b[2] - x[2]};
        double c[3] = {r0[1] * r1[2] - r0[2] * r1[1], r0[2] * r1[0] - r0[0] * r1[2],
                       r0[0] * r1[1] - r0[1] * r1[0]};
        double lc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        if (lc == 0.0)
            continue;
        double theta = atan2(lc, r0[0] * r1[0] + r0[1] * r1[1] + r0[2] * r1[2]);
        sum += theta * (n[0] * c[0] + n[1] * c[1] + n[2] * c[2]) / lc;
    }
    return fabs(sum) / (2.0 * PI_D);
}

/* Differential area to a parallel a x b rectangle with one corner above it, A = a/h, B = b/h. */
static double f_corner(double A, double B)
{
    double a1 = sqrt(1.0 + A * A), b1 = sqrt(1.0 + B * B);
    return (A / a1 * atan(B / a1) + B / b1 * atan(A / b1)) / (2.0 * PI_D);
}

/* Parallel square of half side s centred above at height h: four corner rectangles. */
static double f_square(double s, double h)
{
    return 4.0 * f_corner(s / h, s / h);
}

static double offset_height(const roma_ref *ref, const float p[3], const float gn[3])
{
    float o[3];
    roma_ref_offset_origin(ref, p, gn, o);
    return (double)o[1] - (double)p[1];
}

typedef void (*estimator_fn)(const roma_ref *, const float *, const float *, const float *,
                             const float *, uint32_t, uint32_t, uint32_t, float *);

/* Mean and standard error of k independent spp = 1 estimates (pixels 0..k-1). */
static void mc_stats(estimator_fn f, const roma_ref *ref, const float p[3], const float gn[3],
                     const float n[3], const float albedo[3], uint32_t k, uint32_t seed,
                     double mean[3], double se[3])
{
    double s1[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
    for (uint32_t i = 0; i < k; ++i) {
        float v[3];
        f(ref, p, gn, n, albedo, 1, seed, i, v);
        for (int c = 0; c < 3; ++c) {
            s1[c] += v[c];
            s2[c] += (double)v[c] * v[c];
        }
    }
    for (int c = 0; c < 3; ++c) {
        mean[c] = s1[c] / k;
        double var = (s2[c] - k * mean[c] * mean[c]) / (k - 1);
        se[c] = sqrt(var > 0.0 ? var : 0.0) / sqrt((double)k);
    }
}

static const float UP[3] = {0.0f, 1.0f, 0.0f};
static const float DOWN[3] = {0.0f, -1.0f, 0.0f};

/* --- AO --- */

static void test_ao_open_plane(void)
{
    mesh m = {0};
    add_hsquare(&m, 0, 0, 0, 1.5, 0);
    roma_material mat = {{0.8f, 0.8f, 0.8f}, {0, 0, 0}};
    roma_scene *scene = make_scene(&m, NULL, &mat, 1, NULL, 0);
    roma_test_log log;
    roma_ref *ref = make_ref(scene, 2, &log);
    if (ref) {
        roma_ref_render_desc d;
        memset(&d, 0, sizeof d);
        d.camera = (roma_camera){{0, 5, 0}, {0, 0, 0}, {0, 0, -1}, 45.0f};
        d.width = d.height = 48;
        d.effects = ROMA_EFFECT_AO;
        d.spp = 16;
        d.seed = 1;
        roma_ref_images im;
        CHECK_RESULT(roma_ref_render(ref, &d, &im), ROMA_SUCCESS);
        if (im.ao.pixels && im.coverage.pixels) {
            uint32_t covered = 0, not_one = 0, total = d.width * d.height;
            for (uint32_t i = 0; i < total; ++i) {
                covered += im.coverage.pixels[i] == 1.0f;
                not_one += im.ao.pixels[i] != 1.0f;
            }
            printf("AO open plane: %u of %u pixels covered, %u pixels with AO != 1\n", covered,
                   total, not_one);
            CHECK(covered > total / 4 && covered < total);
            CHECK(not_one == 0);
        }
        roma_ref_images_free(&im);
        CHECK(log.errors == 0);
    }
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
    mesh_free(&m);
}

static void test_ao_closed_box(void)
{
    mesh m = {0};
    double lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
    add_box(&m, lo, hi, 0);
    roma_material mat = {{0.8f, 0.8f, 0.8f}, {0, 0, 0}};
    roma_scene *scene = make_scene(&m, NULL, &mat, 1, NULL, 0);
    roma_test_log log;
    roma_ref *ref = make_ref(scene, 2, &log);
    if (ref) {
        roma_ref_render_desc d;
        memset(&d, 0, sizeof d);
        d.camera = (roma_camera){{0.2f, 0.1f, 0.3f}, {1.0f, 0.3f, -0.5f}, {0, 0, 0}, 90.0f};
        d.width = d.height = 32;
        d.effects = ROMA_EFFECT_AO;
        d.spp = 16;
        d.seed = 2;
        roma_ref_images im;
        CHECK_RESULT(roma_ref_render(ref, &d, &im), ROMA_SUCCESS);
        if (im.ao.pixels && im.coverage.pixels) {
            uint32_t uncovered = 0, not_zero = 0, total = d.width * d.height;
            for (uint32_t i = 0; i < total; ++i) {
                uncovered += im.coverage.pixels[i] != 1.0f;
                not_zero += im.ao.pixels[i] != 0.0f;
            }
            printf("AO closed box: %u uncovered pixels, %u pixels with AO != 0\n", uncovered,
                   not_zero);
            CHECK(uncovered == 0);
            CHECK(not_zero == 0);
        }
        roma_ref_images_free(&im);
    }
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
    mesh_free(&m);
}

static void test_ao_disk(void)
{
    const double h = 1.0, r = 1.0;
    const uint32_t sides = 256, n_samples = 100000;
    mesh m = {0};
    double c[3] = {0, h, 0};
    add_disk(&m, c, r, sides, 0);
    roma_material mat = {{0.8f, 0.8f, 0.8f}, {0, 0, 0}};
    roma_scene *scene = make_scene(&m, NULL, &mat, 1, NULL, 0);
    roma_test_log log;
    roma_ref *ref = make_ref(scene, 2, &log);
    if (ref) {
        const float p[3] = {0, 0, 0};
        double dh = offset_height(ref, p, UP);
        /* Exact polygon view factor from the ray origin, plus the disk formula for reference. */
        double *poly = malloc(3 * sizeof(double) * sides);
        for (uint32_t i = 0; i < sides; ++i) {
            double a = 2.0 * PI_D * i / sides;
            poly[3 * i + 0] = r * cos(a);
            poly[3 * i + 1] = h;
            poly[3 * i + 2] = r * sin(a);
        }
        double x[3] = {0, dh, 0}, nn[3] = {0, 1, 0};
        double expected = 1.0 - view_factor_polygon(x, nn, poly, (int)sides);
        free(poly);
        double r_eq = r * sqrt(sides * sin(2.0 * PI_D / sides) / (2.0 * PI_D));
        double disk = (h - dh) * (h - dh) / ((h - dh) * (h - dh) + r_eq * r_eq);
        float ao = roma_ref_ao_point(ref, p, UP, UP, 0.0f, n_samples, 3, 0);
        double tol = 5.0 * sqrt(expected * (1.0 - expected) / n_samples);
        printf("AO parallel disk: measured %.5f, polygon exact %.5f, disk(R_eq) %.5f, tol %.4f\n",
               ao, expected, disk, tol);
        CHECK_NEAR(ao, expected, tol);
        CHECK_NEAR(expected, disk, 1e-5);
    }
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
    mesh_free(&m);
}

static void test_ao_slab(void)
{
    const double h = 1.0, half = 100.0 * h; /* larger slabs inflate the scene-relative offset */
    const uint32_t n_samples = 100000;
    mesh m = {0};
    add_hsquare(&m, 0, h, 0, half, 0);
    roma_material mat = {{0.8f, 0.8f, 0.8f}, {0, 0, 0}};
    roma_scene *scene = make_scene(&m, NULL, &mat, 1, NULL, 0);
    roma_test_log log;
    roma_ref *ref = make_ref(scene, 2, &log);
    if (ref) {
        const float p[3] = {0, 0, 0};
        double he = h - offset_height(ref, p, UP); /* distance from the ray origin */

        float ao = roma_ref_ao_point(ref, p, UP, UP, 2.0f, n_samples, 4, 0);
        double expected = (he / 2.0) * (he / 2.0);
        double tol = 5.0 * sqrt(expected * (1.0 - expected) / n_samples);
        printf("AO slab, radius 2h: measured %.5f, expected %.5f, tol %.4f\n", ao, expected, tol);
        CHECK_NEAR(ao, expected, tol);

        ao = roma_ref_ao_point(ref, p, UP, UP, 0.5f, n_samples, 4, 0);
        printf("AO slab, radius h/2: measured %.5f, expected 1\n", ao);
        CHECK(ao == 1.0f);

        ao = roma_ref_ao_point(ref, p, UP, UP, 0.0f, n_samples, 4, 0);
        expected = 1.0 - f_square(half, he);
        tol = 5.0 * sqrt(expected * (1.0 - expected) / n_samples);
        printf("AO slab, unbounded: measured %.6f, expected %.6f, tol %.5f\n", ao, expected, tol);
        CHECK_NEAR(ao, expected, tol);
        CHECK(roma_ref_ao_point(ref, p, UP, UP, INFINITY, n_samples, 4, 0) == ao);
    }
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
    mesh_free(&m);
}

/* --- Ray queries --- */

static void test_intersect(void)
{
    mesh m = {0};
    mesh_reserve(&m, 3, 1);
    add_vertex(&m, 0, 0, 0);
    add_vertex(&m, 1, 0, 0);
    add_vertex(&m, 0, 0, 1);
    add_tri(&m, 0, 1, 2, 0);
    const float s = 0.70710678f;
    const float normals[9] = {0, 1, 0, s, s, 0, 0, s, s};
    roma_material mat = {{0.8f, 0.8f, 0.8f}, {0, 0, 0}};
    roma_scene *scene = make_scene(&m, normals, &mat, 1, NULL, 0);
    roma_test_log log;
    roma_ref *ref = make_ref(scene, 1, &log);
    if (ref) {
        /* Hit at barycentrics (0.5, 0.25, 0.25): n = 0.5 n0 + 0.25 n1 + 0.25 n2, normalised. */
        float en[3] = {0.25f * s, 0.5f + 0.5f * s, 0.25f * s};
        float len = sqrtf(en[0] * en[0] + en[1] * en[1] + en[2] * en[2]);
        for (int k = 0; k < 3; ++k)
            en[k] /= len;
        const float above[3] = {0.25f, 1.0f, 0.25f}, below[3] = {0.25f, -2.0f, 0.25f};
        roma_ref_hit hit;
        CHECK(roma_ref_intersect(ref, above, DOWN, 0.0f, INFINITY, &hit) == 1);
        CHECK_NEAR(hit.t, 1.0, 1e-6);
        CHECK(hit.triangle == 0);
        CHECK_NEAR(hit.position[0], 0.25, 1e-6);
        CHECK_NEAR(hit.position[1], 0.0, 1e-6);
        CHECK_NEAR(hit.position[2], 0.25, 1e-6);
        CHECK_NEAR(hit.geometric_normal[1], 1.0, 1e-6);
        for (int k = 0; k < 3; ++k)
            CHECK_NEAR(hit.shading_normal[k], en[k], 1e-6);
        /* From below both normals flip to face the ray. */
        CHECK(roma_ref_intersect(ref, below, UP, 0.0f, INFINITY, &hit) == 1);
        CHECK_NEAR(hit.t, 2.0, 1e-6);
        CHECK_NEAR(hit.geometric_normal[1], -1.0, 1e-6);
        for (int k = 0; k < 3; ++k)
            CHECK_NEAR(hit.shading_normal[k], -en[k], 1e-6);
        /* (tmin, tmax) limits; a scaled direction scales t. */
        const float down2[3] = {0, -2, 0};
        CHECK(roma_ref_intersect(ref, above, DOWN, 0.0f, 0.5f, &hit) == 0);
        CHECK(roma_ref_intersect(ref, above, DOWN, 1.5f, INFINITY, &hit) == 0);
        CHECK(roma_ref_intersect(ref, above, down2, 0.0f, INFINITY, &hit) == 1);
        CHECK_NEAR(hit.t, 0.5, 1e-6);
        CHECK(roma_ref_occluded(ref, above, DOWN, 0.0f, INFINITY) == 1);
        CHECK(roma_ref_occluded(ref, above, DOWN, 0.0f, 0.99f) == 0);
        CHECK(roma_ref_occluded(ref, above, UP, 0.0f, INFINITY) == 0);
        const float outside[3] = {0.8f, 1.0f, 0.8f};
        CHECK(roma_ref_occluded(ref, outside, DOWN, 0.0f, INFINITY) == 0);
        CHECK(log.errors == 0);
    }
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
    mesh_free(&m);
}

/* Room used by the batch and determinism tests: closed box, an inner block, an
 * emissive panel under the ceiling, a point and a spot light. */
static roma_scene *make_room(mesh *m)
{
    double lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
    add_box(m, lo, hi, 0);
    double blo[3] = {-0.4, -1, -0.3}, bhi[3] = {0.1, -0.2, 0.2};
    add_box(m, blo, bhi, 1);
    add_hsquare(m, 0.2, 0.98, 0.1, 0.3, 2);
    static const roma_material mats[3] = {
        {{0.7f, 0.6f, 0.5f}, {0, 0, 0}},
        {{0.2f, 0.5f, 0.8f}, {0, 0, 0}},
        {{0.9f, 0.9f, 0.9f}, {4.0f, 3.5f, 3.0f}},
    };
    roma_light lights[2];
    memset(lights, 0, sizeof lights);
    lights[0] = (roma_light){ROMA_LIGHT_POINT, {0.5f, 0.3f, 0.5f}, {0, 0, 0}, {1, 0.8f, 0.6f},
                             1.5f, 0.0f, 0.0f, 0.0f};
    lights[1] = (roma_light){ROMA_LIGHT_SPOT, {-0.7f, 0.8f, 0.6f}, {0.3f, -0.9f, -0.3f},
                             {0.5f, 0.7f, 1.0f}, 3.0f, 5.0f, DEG(15), DEG(35)};
    float d = sqrtf(0.09f + 0.81f + 0.09f);
    for (int k = 0; k < 3; ++k)
        lights[1].direction[k] /= d;
    return make_scene(m, NULL, mats, 3, lights, 2);
}

static void test_batch(void)
{
    mesh m = {0};
    roma_scene *scene = make_room(&m);
    roma_test_log log;
    roma_ref *ref = make_ref(scene, 2, &log);
    if (ref) {
        const uint32_t n = 5000;
        float *orgs = malloc(3 * sizeof(float) * n), *dirs = malloc(3 * sizeof(float) * n);
        float *tmaxs = malloc(sizeof(float) * n), *ts = malloc(sizeof(float) * n);
        float *ts_default = malloc(sizeof(float) * n);
        uint8_t *occ = malloc(n);
        uint32_t mismatches = 0, hits = 0;
        for (uint32_t i = 0; i < n; ++i) {
            float u = roma_random(5, i, 0, 0), v = roma_random(5, i, 0, 1);
            float z = 1.0f - 2.0f * u, r = sqrtf(fmaxf(0.0f, 1.0f - z * z));
            float phi = 2.0f * ROMA_PI * v;
            dirs[3 * i + 0] = r * cosf(phi);
            dirs[3 * i + 1] = r * sinf(phi);
            dirs[3 * i + 2] = z;
            orgs[3 * i + 0] = 0.5f;
            orgs[3 * i + 1] = 0.2f * roma_random(5, i, 0, 2);
            orgs[3 * i + 2] = -0.5f;
            tmaxs[i] = (i & 1) ? INFINITY : 0.7f;
        }
        roma_ref_occluded_batch(ref, n, orgs, dirs, NULL, tmaxs, occ);
        roma_ref_intersect_batch(ref, n, orgs, dirs, NULL, tmaxs, ts);
        roma_ref_intersect_batch(ref, n, orgs, dirs, NULL, NULL, ts_default);
        for (uint32_t i = 0; i < n; ++i) {
            const float *o = &orgs[3 * i], *dd = &dirs[3 * i];
            roma_ref_hit hit;
            int h = roma_ref_intersect(ref, o, dd, 0.0f, tmaxs[i], &hit);
            float t = h ? hit.t : INFINITY;
            int hinf = roma_ref_intersect(ref, o, dd, 0.0f, INFINITY, &hit);
            hits += h;
            mismatches += occ[i] != (uint8_t)roma_ref_occluded(ref, o, dd, 0.0f, tmaxs[i]);
            mismatches += occ[i] != (uint8_t)h;
            mismatches += memcmp(&ts[i], &t, sizeof t) != 0;
            mismatches += !hinf || memcmp(&ts_default[i], &hit.t, sizeof t) != 0;
        }
        printf("batch: %u rays, %u hits within tmax, %u mismatches with single-ray queries\n", n,
               hits, mismatches);
        CHECK(mismatches == 0);
        CHECK(hits > n / 2 && hits < n);
        free(orgs);
        free(dirs);
        free(tmaxs);
        free(ts);
        free(ts_default);
        free(occ);
    }
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
    mesh_free(&m);
}

/* --- Direct light --- */

/* Floor (albedo (0.5, 0.6, 0.7)) plus a small occluder at (1.5, 1, 1.5). */
static roma_scene *make_floor_scene(mesh *m, const roma_light *light)
{
    static const roma_material mats[2] = {{{0.5f, 0.6f, 0.7f}, {0, 0, 0}},
                                          {{0.3f, 0.3f, 0.3f}, {0, 0, 0}}};
    add_hsquare(m, 0, 0, 0, 10, 0);
    add_hsquare(m, 1.5, 1, 1.5, 0.2, 1);
    return make_scene(m, NULL, mats, 2, light, 1);
}

/* Direct radiance at the floor point below (x, z), found with a ray from above. */
static void floor_direct(const roma_ref *ref, double x, double z, float out[3])
{
    const float org[3] = {(float)x, 5.0f, (float)z};
    roma_ref_hit hit;
    out[0] = out[1] = out[2] = -1.0f;
    CHECK(roma_ref_intersect(ref, org, DOWN, 0.0f, INFINITY, &hit) == 1);
    CHECK_NEAR(hit.position[1], 0.0, 1e-6);
    CHECK_NEAR(hit.shading_normal[1], 1.0, 1e-6);
    CHECK_NEAR(hit.geometric_normal[1], 1.0, 1e-6);
    const float albedo[3] = {0.5f, 0.6f, 0.7f};
    roma_ref_direct_point(ref, hit.position, hit.geometric_normal, hit.shading_normal, albedo, 4,
                          7, 0, out);
}

static void check_rgb(const char *what, const float got[3], const double want[3])
{
    printf("%s: measured (%.6g, %.6g, %.6g), expected (%.6g, %.6g, %.6g)\n", what, got[0], got[1],
           got[2], want[0], want[1], want[2]);
    for (int c = 0; c < 3; ++c)
        CHECK_NEAR(got[c], want[c], 1e-5 * fabs(want[c]) + 1e-7);
}

/* Point/spot light at (0, lh, 0): expected radiance at floor point (x, 0, z) times a factor. */
static void expect_point(double x, double z, double lh, double intensity, const float color[3],
                         double factor, double out[3])
{
    const double albedo[3] = {0.5, 0.6, 0.7};
    double d2 = x * x + z * z + lh * lh, cosv = lh / sqrt(d2);
    for (int c = 0; c < 3; ++c)
        out[c] = albedo[c] / PI_D * intensity * color[c] * cosv / d2 * factor;
}

static void test_punctual(void)
{
    const float color[3] = {1.0f, 0.5f, 0.25f};
    const double zero[3] = {0, 0, 0};
    float got[3];
    double want[3];
    roma_test_log log;

    /* Point light, unlimited range; (3, 3) lies in the occluder's shadow. */
    {
        roma_light l = {ROMA_LIGHT_POINT, {0, 2, 0}, {0, 0, 0}, {1, 0.5f, 0.25f}, 10.0f, 0, 0, 0};
        mesh m = {0};
        roma_scene *scene = make_floor_scene(&m, &l);
        roma_ref *ref = make_ref(scene, 1, &log);
        if (ref) {
            const double pts[3][2] = {{0, 0}, {1, 0.5}, {-3, 2}};
            for (int i = 0; i < 3; ++i) {
                floor_direct(ref, pts[i][0], pts[i][1], got);
                expect_point(pts[i][0], pts[i][1], 2.0, 10.0, color, 1.0, want);
                check_rgb("point light", got, want);
            }
            floor_direct(ref, 3, 3, got);
            check_rgb("point light, shadowed", got, zero);
        }
        roma_ref_destroy(ref);
        roma_scene_destroy(scene);
        mesh_free(&m);
    }
    /* Range window max(min(1 - (d/range)^4, 1), 0). */
    {
        roma_light l = {ROMA_LIGHT_POINT, {0, 2, 0}, {0, 0, 0}, {1, 0.5f, 0.25f}, 10.0f, 3.0f, 0, 0};
        mesh m = {0};
        roma_scene *scene = make_floor_scene(&m, &l);
        roma_ref *ref = make_ref(scene, 1, &log);
        if (ref) {
            double d = sqrt(1 + 0.25 + 4);
            floor_direct(ref, 1, 0.5, got);
            expect_point(1, 0.5, 2.0, 10.0, color, 1.0 - pow(d / 3.0, 4.0), want);
            check_rgb("point light, range window", got, want);
            floor_direct(ref, -3, 2, got);
            check_rgb("point light, beyond range", got, zero);
        }
        roma_ref_destroy(ref);
        roma_scene_destroy(scene);
        mesh_free(&m);
    }
    /* Spot light pointing down: inner 20 deg, outer 30 deg. */
    {
        roma_light l = {ROMA_LIGHT_SPOT, {0, 2, 0}, {0, -1, 0}, {1, 0.5f, 0.25f}, 10.0f, 0,
                        DEG(20), DEG(30)};
        mesh m = {0};
        roma_scene *scene = make_floor_scene(&m, &l);
        roma_ref *ref = make_ref(scene, 1, &log);
        if (ref) {
            double x10 = 2.0 * tan(10 * PI_D / 180), x25 = 2.0 * tan(25 * PI_D / 180);
            double x40 = 2.0 * tan(40 * PI_D / 180);
            floor_direct(ref, x10, 0, got);
            expect_point(x10, 0, 2.0, 10.0, color, 1.0, want);
            check_rgb("spot, inside inner cone", got, want);
            double ci = cos(20 * PI_D / 180), co = cos(30 * PI_D / 180);
            double a = (cos(25 * PI_D / 180) - co) / (ci - co);
            floor_direct(ref, 0, -x25, got);
            expect_point(0, -x25, 2.0, 10.0, color, a * a, want);
            check_rgb("spot, between the cones", got, want);
            floor_direct(ref, -x40, 0, got);
            check_rgb("spot, outside outer cone", got, zero);
        }
        roma_ref_destroy(ref);
        roma_scene_destroy(scene);
        mesh_free(&m);
    }
    /* Directional light travelling along (0.3, -1, 0.2); (1.8, 1.7) is shadowed. */
    {
        double dl = sqrt(0.09 + 1.0 + 0.04);
        roma_light l = {ROMA_LIGHT_DIRECTIONAL, {0, 0, 0},
                        {(float)(0.3 / dl), (float)(-1.0 / dl), (float)(0.2 / dl)},
                        {1, 0.5f, 0.25f}, 3.0f, 0, 0, 0};
        mesh m = {0};
        roma_scene *scene = make_floor_scene(&m, &l);
        roma_ref *ref = make_ref(scene, 1, &log);
        if (ref) {
            const double albedo[3] = {0.5, 0.6, 0.7};
            for (int c = 0; c < 3; ++c)
                want[c] = albedo[c] / PI_D * 3.0 * color[c] * (1.0 / dl);
            floor_direct(ref, 0, 0, got);
            check_rgb("directional", got, want);
            floor_direct(ref, -2, 1, got);
            check_rgb("directional", got, want);
            floor_direct(ref, 1.8, 1.7, got);
            check_rgb("directional, shadowed", got, zero);
        }
        roma_ref_destroy(ref);
        roma_scene_destroy(scene);
        mesh_free(&m);
    }
}

/* Two square emitters over a floor: E = sum Le_i * pi * F_i (sampling picks them by
 * area * luminance, so both emitters and the CDF are exercised). */
static void test_area_light(void)
{
    const double h = 1.0, b = 0.25;
    static const roma_material mats[3] = {{{0.5f, 0.5f, 0.5f}, {0, 0, 0}},
                                          {{0.9f, 0.9f, 0.9f}, {2.0f, 3.0f, 4.0f}},
                                          {{0.9f, 0.9f, 0.9f}, {6.0f, 1.0f, 0.5f}}};
    mesh m = {0};
    add_hsquare(&m, 0, 0, 0, 2.0, 0);
    add_hsquare(&m, 0, h, 0, b, 1);
    add_hsquare(&m, 0.8, 1.5, -0.3, 0.2, 2);
    roma_scene *scene = make_scene(&m, NULL, mats, 3, NULL, 0);
    roma_test_log log;
    roma_ref *ref = make_ref(scene, 2, &log);
    if (ref) {
        const float p[3] = {0, 0, 0}, albedo[3] = {0.5f, 0.5f, 0.5f};
        double x[3] = {0, 0, 0}, nn[3] = {0, 1, 0};
        double sq_a[12] = {-b, h, -b, b, h, -b, b, h, b, -b, h, b};
        double sq_b[12] = {0.6, 1.5, -0.5, 1.0, 1.5, -0.5, 1.0, 1.5, -0.1, 0.6, 1.5, -0.1};
        double fa = f_square(b, h), fa_contour = view_factor_polygon(x, nn, sq_a, 4);
        double fb = view_factor_polygon(x, nn, sq_b, 4);
        CHECK_NEAR(fa, fa_contour, 1e-12); /* the two closed forms agree */
        double want[3];
        for (int c = 0; c < 3; ++c)
            want[c] = albedo[c] * (mats[1].emission[c] * fa + mats[2].emission[c] * fb);

        const uint32_t k = 20000;
        double mean[3], se[3];
        mc_stats(roma_ref_direct_point, ref, p, UP, UP, albedo, k, 11, mean, se);
        float got[3];
        roma_ref_direct_point(ref, p, UP, UP, albedo, k, 12, 0, got);
        printf("area lights (F = %.6f, %.6f): expected (%.5f, %.5f, %.5f)\n", fa, fb, want[0],
               want[1], want[2]);
        printf("  %u x spp 1: (%.5f, %.5f, %.5f) +- (%.5f, %.5f, %.5f); spp %u: (%.5f, %.5f, %.5f)\n",
               k, mean[0], mean[1], mean[2], se[0], se[1], se[2], k, got[0], got[1], got[2]);
        for (int c = 0; c < 3; ++c) {
            CHECK(se[c] > 0.0 && se[c] < 0.01 * want[c]);
            CHECK_NEAR(mean[c], want[c], 5.0 * se[c]);
            CHECK_NEAR(got[c], want[c], 5.0 * se[c]);
        }
        CHECK(log.errors == 0);
    }
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
    mesh_free(&m);
}

/* --- One bounce between plates --- */

static void test_one_bounce(void)
{
    const double h = 1.0, a = 1.0, s = 0.02 * h, e0 = 2.0;
    static const roma_material mats[2] = {{{0.8f, 0.8f, 0.8f}, {0, 0, 0}},
                                          {{0.6f, 0.5f, 0.4f}, {0, 0, 0}}};
    roma_light l = {ROMA_LIGHT_DIRECTIONAL, {0, 0, 0}, {0, 1, 0}, {1, 1, 1}, (float)e0, 0, 0, 0};
    mesh m = {0};
    add_hsquare(&m, 0, 0, 0, s / 2, 0);
    add_hsquare(&m, 0, h, 0, a, 1);
    roma_scene *scene = make_scene(&m, NULL, mats, 2, &l, 1);
    roma_test_log log;
    roma_ref *ref = make_ref(scene, 2, &log);
    if (ref) {
        const float org[3] = {0, 0.5f, 0}, albedo[3] = {0.8f, 0.8f, 0.8f};
        roma_ref_hit hit;
        CHECK(roma_ref_intersect(ref, org, DOWN, 0.0f, INFINITY, &hit) == 1);
        CHECK(hit.triangle < 2); /* the receiver */
        const float *p = hit.position, *gn = hit.geometric_normal, *n = hit.shading_normal;

        float direct[3];
        roma_ref_direct_point(ref, p, gn, n, albedo, 4, 1, 0, direct);
        const double zero[3] = {0, 0, 0};
        check_rgb("receiver top, direct (light from below)", direct, zero);
        /* The plate's underside outside the shadow: rho/pi * E0. */
        const float org2[3] = {0.5f, 0.5f, 0.5f};
        roma_ref_hit plate;
        CHECK(roma_ref_intersect(ref, org2, UP, 0.0f, INFINITY, &plate) == 1);
        roma_ref_direct_point(ref, plate.position, plate.geometric_normal, plate.shading_normal,
                              mats[1].base_color, 4, 1, 0, direct);
        double plate_want[3];
        for (int c = 0; c < 3; ++c)
            plate_want[c] = mats[1].base_color[c] / PI_D * e0;
        check_rgb("plate underside, direct", direct, plate_want);

        double he = h - offset_height(ref, p, gn);
        double f = f_square(a, he) - f_square(s / 2, he);
        double want[3];
        for (int c = 0; c < 3; ++c)
            want[c] = albedo[c] / PI_D * mats[1].base_color[c] * e0 * f;
        const uint32_t k = 40000;
        double mean[3], se[3];
        mc_stats(roma_ref_indirect_point, ref, p, gn, n, albedo, k, 21, mean, se);
        float got[3];
        roma_ref_indirect_point(ref, p, gn, n, albedo, k, 22, 0, got);
        printf("one bounce (F = %.6f): expected (%.5f, %.5f, %.5f)\n", f, want[0], want[1],
               want[2]);
        printf("  %u x spp 1: (%.5f, %.5f, %.5f) +- (%.5f, %.5f, %.5f); spp %u: (%.5f, %.5f, %.5f)\n",
               k, mean[0], mean[1], mean[2], se[0], se[1], se[2], k, got[0], got[1], got[2]);
        for (int c = 0; c < 3; ++c) {
            CHECK(se[c] > 0.0 && se[c] < 0.01 * want[c]);
            CHECK_NEAR(mean[c], want[c], 5.0 * se[c]);
            CHECK_NEAR(got[c], want[c], 5.0 * se[c]);
        }
    }
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
    mesh_free(&m);
}

/* --- Many lights --- */

static void test_many_lights(void)
{
    mesh m = {0};
    add_hsquare(&m, 0, 0, 0, 10, 0);
    double c[3] = {0, 0, 0}, u[3] = {0, 10, 0}, v[3] = {0, 0, 10};
    add_quad(&m, c, u, v, 0); /* wall x = 0 */
    roma_material mat = {{0.8f, 0.8f, 0.8f}, {0, 0, 0}};
    roma_scene *scene = make_scene(&m, NULL, &mat, 1, NULL, 0);
    roma_test_log log;
    roma_ref *ref = make_ref(scene, 1, &log);
    if (ref) {
        const float lights[] = {
            -2, 1, 0,   -0.5f, 3, 1,  -4, 0.5f, -2, /* visible: same side, above */
            1, 1, 0,    3, 2, -1,     0.5f, 0.2f, 4, /* behind the wall */
            -2, -1, 0,  -1, -0.5f, 1,                /* below the floor */
        };
        const float p[3] = {-1, 0, 0}, q[3] = {2, 0, 0.5f};
        uint32_t n = roma_ref_count_visible_lights(ref, p, UP, UP, lights, 8);
        uint32_t nq = roma_ref_count_visible_lights(ref, q, UP, UP, lights, 8);
        printf("many lights: %u visible from x < 0 (expected 3), %u from x > 0 (expected 3)\n", n,
               nq);
        CHECK(n == 3);
        CHECK(nq == 3);
        /* A tilted shading normal hides lights behind its hemisphere. */
        const float tilted[3] = {0.6f, 0.8f, 0.0f};
        CHECK(roma_ref_count_visible_lights(ref, p, UP, tilted, lights, 8) == 2);
        CHECK(roma_ref_count_visible_lights(ref, p, UP, UP, lights, 0) == 0);
    }
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
    mesh_free(&m);
}

/* --- Images: determinism, consistency with the point estimators, validation --- */

static _Thread_local int on_main_thread;

typedef struct progress_log {
    int calls, off_thread, decreasing;
    float last;
} progress_log;

static void on_progress(float fraction, void *user)
{
    progress_log *pl = user;
    if (!on_main_thread)
        ++pl->off_thread;
    if (fraction < pl->last)
        ++pl->decreasing;
    pl->last = fraction;
    ++pl->calls;
}

static int images_equal(const roma_image *a, const roma_image *b)
{
    if (a->width != b->width || a->height != b->height || a->channels != b->channels)
        return 0;
    if (!a->pixels || !b->pixels)
        return a->pixels == b->pixels;
    return memcmp(a->pixels, b->pixels,
                  sizeof(float) * a->width * a->height * a->channels) == 0;
}

static void test_determinism(void)
{
    mesh m = {0};
    roma_scene *scene = make_room(&m);
    roma_test_log log1, log2;
    roma_ref *r1 = make_ref(scene, 1, &log1);
    roma_ref *r2 = make_ref(scene, 2, &log2);
    if (r1 && r2) {
        roma_scene_view view;
        CHECK_RESULT(roma_scene_get_view(scene, &view), ROMA_SUCCESS);
        float lights[3 * 16];
        roma_many_lights_positions(view.bounds_min, view.bounds_max, 16, 5, lights);

        roma_ref_render_desc d;
        memset(&d, 0, sizeof d);
        d.camera = (roma_camera){{0.6f, 0.5f, 0.9f}, {-0.3f, -0.4f, -0.5f}, {0, 0, 0}, 70.0f};
        d.width = 40;
        d.height = 30;
        d.effects = ROMA_EFFECT_AO | ROMA_EFFECT_DIRECT | ROMA_EFFECT_GI | ROMA_EFFECT_LIGHTS;
        d.spp = 4;
        d.ao_radius = 0.5f;
        d.seed = 9;
        d.many_light_positions = lights;
        d.many_light_count = 16;
        progress_log pl = {0, 0, 0, 0.0f};
        d.progress = on_progress;
        d.progress_user_data = &pl;

        roma_ref_images a, b, c;
        CHECK_RESULT(roma_ref_render(r1, &d, &a), ROMA_SUCCESS);
        CHECK(pl.calls >= 1 && pl.last == 1.0f);
        pl = (progress_log){0, 0, 0, 0.0f};
        CHECK_RESULT(roma_ref_render(r2, &d, &b), ROMA_SUCCESS);
        printf("determinism: %d progress calls (2 threads), %d off the calling thread, last %.3f\n",
               pl.calls, pl.off_thread, pl.last);
        CHECK(pl.calls >= 1 && pl.last == 1.0f && pl.off_thread == 0 && pl.decreasing == 0);
        d.progress = NULL;
        CHECK_RESULT(roma_ref_render(r2, &d, &c), ROMA_SUCCESS);
        int same_ab = images_equal(&a.ao, &b.ao) && images_equal(&a.direct, &b.direct) &&
                      images_equal(&a.gi, &b.gi) && images_equal(&a.lights, &b.lights) &&
                      images_equal(&a.coverage, &b.coverage);
        int same_bc = images_equal(&b.ao, &c.ao) && images_equal(&b.direct, &c.direct) &&
                      images_equal(&b.gi, &c.gi) && images_equal(&b.lights, &c.lights) &&
                      images_equal(&b.coverage, &c.coverage);
        printf("determinism: 1 vs 2 threads bit-identical: %s; repeat: %s\n",
               same_ab ? "yes" : "NO", same_bc ? "yes" : "NO");
        CHECK(same_ab);
        CHECK(same_bc);

        /* Pixel (x, y) uses pixel index y * width + x and the centre ray. */
        if (a.ao.pixels && a.direct.pixels && a.gi.pixels && a.lights.pixels) {
            double sum_ao = 0, sum_direct = 0, sum_gi = 0, sum_lights = 0;
            uint32_t bad = 0, total = d.width * d.height;
            for (uint32_t i = 0; i < total; ++i) {
                sum_ao += a.ao.pixels[i];
                sum_lights += a.lights.pixels[i];
                bad += !(a.ao.pixels[i] >= 0.0f && a.ao.pixels[i] <= 1.0f) ||
                       a.coverage.pixels[i] != 1.0f;
                for (int k = 0; k < 3; ++k) {
                    float dv = a.direct.pixels[3 * i + k], gv = a.gi.pixels[3 * i + k];
                    bad += !(dv >= 0.0f && isfinite(dv)) || !(gv >= 0.0f && isfinite(gv));
                    sum_direct += dv;
                    sum_gi += gv;
                }
            }
            printf("room image means: AO %.4f, direct %.4f, GI %.4f, visible lights %.3f; %u bad\n",
                   sum_ao / total, sum_direct / (3 * total), sum_gi / (3 * total),
                   sum_lights / total, bad);
            CHECK(bad == 0);
            CHECK(sum_direct > 0.0 && sum_gi > 0.0 && sum_lights > 0.0 && sum_ao > 0.0);

            roma_camera_frame frame;
            CHECK(roma_camera_make_frame(&d.camera, d.width, d.height, &frame));
            const uint32_t px = 27, py = 11, pixel = py * d.width + px;
            float org[3], dir[3];
            roma_camera_ray(&frame, px + 0.5f, py + 0.5f, org, dir);
            roma_ref_hit hit;
            if (roma_ref_intersect(r1, org, dir, 0.0f, INFINITY, &hit)) {
                const float *alb = view.materials[view.triangle_materials[hit.triangle]].base_color;
                float ao = roma_ref_ao_point(r1, hit.position, hit.geometric_normal,
                                             hit.shading_normal, d.ao_radius, d.spp, d.seed, pixel);
                float dr[3], gi[3];
                roma_ref_direct_point(r1, hit.position, hit.geometric_normal, hit.shading_normal,
                                      alb, d.spp, d.seed, pixel, dr);
                roma_ref_indirect_point(r1, hit.position, hit.geometric_normal,
                                        hit.shading_normal, alb, d.spp, d.seed, pixel, gi);
                uint32_t nl = roma_ref_count_visible_lights(
                    r1, hit.position, hit.geometric_normal, hit.shading_normal, lights, 16);
                CHECK(a.ao.pixels[pixel] == ao);
                CHECK(a.lights.pixels[pixel] == (float)nl);
                CHECK(memcmp(&a.direct.pixels[3 * pixel], dr, sizeof dr) == 0);
                CHECK(memcmp(&a.gi.pixels[3 * pixel], gi, sizeof gi) == 0);
            } else {
                CHECK(!"pixel (27, 11) should see the room");
            }
        }
        roma_ref_images_free(&a);
        roma_ref_images_free(&b);
        roma_ref_images_free(&c);
        CHECK(a.ao.pixels == NULL && a.coverage.pixels == NULL);
        CHECK(log1.errors == 0 && log2.errors == 0);
    }
    roma_ref_destroy(r1);
    roma_ref_destroy(r2);
    roma_scene_destroy(scene);
    mesh_free(&m);
}

static void test_bad_desc(void)
{
    mesh m = {0};
    add_hsquare(&m, 0, 0, 0, 1, 0);
    roma_material mat = {{0.8f, 0.8f, 0.8f}, {0, 0, 0}};
    roma_scene *scene = make_scene(&m, NULL, &mat, 1, NULL, 0);
    roma_test_log log;
    roma_ref *ref = make_ref(scene, 1, &log);
    if (ref) {
        roma_ref_render_desc good;
        memset(&good, 0, sizeof good);
        good.camera = (roma_camera){{0, 3, 3}, {0, 0, 0}, {0, 0, 0}, 0.0f};
        good.width = 8;
        good.height = 6;
        good.effects = ROMA_EFFECT_AO;
        good.spp = 2;
        roma_ref_images im;
        CHECK_RESULT(roma_ref_render(ref, &good, &im), ROMA_SUCCESS);
        CHECK(im.ao.pixels && im.coverage.pixels && !im.direct.pixels && !im.gi.pixels &&
              !im.lights.pixels);
        roma_ref_images_free(&im);

        roma_ref_render_desc bad[8];
        for (int i = 0; i < 8; ++i)
            bad[i] = good;
        bad[0].width = 0;
        bad[1].height = 0;
        bad[2].width = 16385;
        bad[3].camera.target[1] = 3;
        bad[3].camera.target[2] = 3; /* eye == target */
        bad[4].effects |= ROMA_EFFECT_LIGHTS; /* no positions */
        bad[5].effects |= 1u << 9;
        bad[6].ao_radius = NAN;
        bad[7].camera.eye[0] = INFINITY;
        for (int i = 0; i < 8; ++i) {
            int errors = log.errors;
            memset(&im, 0x5a, sizeof im);
            CHECK_RESULT(roma_ref_render(ref, &bad[i], &im), ROMA_ERROR_INVALID_ARGUMENT);
            CHECK(im.coverage.pixels == NULL && im.ao.pixels == NULL);
            CHECK(log.errors == errors + 1);
        }
        printf("bad desc: last message \"%s\"\n", log.last);
        CHECK_RESULT(roma_ref_render(NULL, &good, &im), ROMA_ERROR_INVALID_ARGUMENT);
        CHECK_RESULT(roma_ref_render(ref, NULL, &im), ROMA_ERROR_INVALID_ARGUMENT);
        CHECK_RESULT(roma_ref_render(ref, &good, NULL), ROMA_ERROR_INVALID_ARGUMENT);
    }
    roma_ref *none = (roma_ref *)&m;
    CHECK_RESULT(roma_ref_create(NULL, NULL, &none), ROMA_ERROR_INVALID_ARGUMENT);
    CHECK(none == NULL);
    roma_ref_destroy(NULL);
    roma_ref_images_free(NULL);
    roma_ref_destroy(ref);
    roma_scene_destroy(scene);
    mesh_free(&m);
}

int main(void)
{
    on_main_thread = 1;
    test_ao_open_plane();
    test_ao_closed_box();
    test_ao_disk();
    test_ao_slab();
    test_intersect();
    test_batch();
    test_punctual();
    test_area_light();
    test_one_bounce();
    test_many_lights();
    test_determinism();
    test_bad_desc();
    return roma_test_finish("test_reference_analytic");
}
