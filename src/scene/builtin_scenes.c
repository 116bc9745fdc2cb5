/* libroma: built-in scenes, generated in C and validated by roma_scene_create.
 *
 * Every quad gets its own four vertices so the computed normals stay flat
 * (no smoothing across box edges). Scenes are deterministic: no randomness,
 * no dependence on the machine. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "roma/builtin_scenes.h"
#include "util/log.h"

#define DEG(x) ((float)((x) * 3.14159265358979323846 / 180.0))

typedef struct builder {
    float *pos;
    uint32_t *idx, *mat;
    uint32_t nv, nt, cap_v, cap_t;
    int oom;
} builder;

/* Room for 4 more vertices and 2 more triangles; sets oom on failure. */
static int reserve(builder *b)
{
    if (b->nv + 4 > b->cap_v) {
        uint32_t n = b->cap_v ? 2 * b->cap_v : 256;
        float *p = realloc(b->pos, (size_t)n * 3 * sizeof(float));
        if (!p)
            return 0;
        b->pos = p;
        b->cap_v = n;
    }
    if (b->nt + 2 > b->cap_t) {
        uint32_t n = b->cap_t ? 2 * b->cap_t : 128;
        uint32_t *i = realloc(b->idx, (size_t)n * 3 * sizeof(uint32_t));
        if (i)
            b->idx = i;
        uint32_t *m = realloc(b->mat, (size_t)n * sizeof(uint32_t));
        if (m)
            b->mat = m;
        if (!i || !m)
            return 0;
        b->cap_t = n;
    }
    return 1;
}

/* Quad p0 p1 p2 p3, counter-clockwise seen from the side its normal faces. */
static void quad(builder *b, float p[4][3], uint32_t material)
{
    if (b->oom || !reserve(b)) {
        b->oom = 1;
        return;
    }
    uint32_t v = b->nv;
    memcpy(b->pos + 3 * (size_t)v, p, 12 * sizeof(float));
    const uint32_t tri[6] = {v, v + 1, v + 2, v, v + 2, v + 3};
    memcpy(b->idx + 3 * (size_t)b->nt, tri, sizeof tri);
    b->mat[b->nt] = b->mat[b->nt + 1] = material;
    b->nv += 4;
    b->nt += 2;
}

/* Axis-aligned rectangle in the plane axis = c; (u0,v0)-(u1,v1) span the two
 * other axes in cyclic order (x: y,z; y: z,x; z: x,y). flip turns the normal
 * from +axis to -axis. */
static void rect(builder *b, int axis, float c, float u0, float v0, float u1, float v1, int flip,
                 uint32_t material)
{
    const float uv[4][2] = {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}};
    float p[4][3];
    for (int i = 0; i < 4; ++i) {
        int k = flip ? 3 - i : i;
        p[i][axis] = c;
        p[i][(axis + 1) % 3] = uv[k][0];
        p[i][(axis + 2) % 3] = uv[k][1];
    }
    quad(b, p, material);
}

/* Closed box with outward normals, rotated by `angle` around its vertical axis. */
static void box(builder *b, const float centre[3], const float half[3], float angle, uint32_t material)
{
    static const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                    {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    float corner[8][3], cs = cosf(angle), sn = sinf(angle);
    for (int i = 0; i < 8; ++i) {
        float x = (i & 1 ? 1.0f : -1.0f) * half[0], y = (i & 2 ? 1.0f : -1.0f) * half[1],
              z = (i & 4 ? 1.0f : -1.0f) * half[2];
        corner[i][0] = centre[0] + x * cs + z * sn;
        corner[i][1] = centre[1] + y;
        corner[i][2] = centre[2] - x * sn + z * cs;
    }
    for (int f = 0; f < 6; ++f) {
        float p[4][3];
        for (int k = 0; k < 4; ++k)
            memcpy(p[k], corner[faces[f][k]], sizeof p[k]);
        quad(b, p, material);
    }
}

/* Open-top container standing on y = 0: outer shell, inner shell and rim,
 * with walls (and floor) `t` thick. */
static void open_box(builder *b, float cx, float cz, float h, float height, float t, uint32_t material)
{
    float o = h, i = h - t;
    rect(b, 1, 0.0f, cz - o, cx - o, cz + o, cx + o, 1, material);   /* outer bottom, facing -y */
    rect(b, 1, t, cz - i, cx - i, cz + i, cx + i, 0, material);      /* inner bottom, facing +y */
    for (int s = 0; s < 2; ++s) {
        float sign = s ? 1.0f : -1.0f;
        /* x walls: outer faces away from the centre, inner faces towards it */
        rect(b, 0, cx + sign * o, 0.0f, cz - o, height, cz + o, !s, material);
        rect(b, 0, cx + sign * i, t, cz - i, height, cz + i, s, material);
        rect(b, 2, cz + sign * o, cx - o, 0.0f, cx + o, height, !s, material);
        rect(b, 2, cz + sign * i, cx - i, t, cx + i, height, s, material);
    }
    /* rim: four trapezoids between the outer and inner squares */
    const float sq[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int k = 0; k < 4; ++k) {
        const float *a = sq[k], *c = sq[(k + 1) % 4];
        float p[4][3] = {{cx + a[0] * o, height, cz + a[1] * o},
                         {cx + a[0] * i, height, cz + a[1] * i},
                         {cx + c[0] * i, height, cz + c[1] * i},
                         {cx + c[0] * o, height, cz + c[1] * o}};
        quad(b, p, material);
    }
}

static roma_result finish(builder *b, const char *name, const roma_material *materials,
                          uint32_t material_count, const roma_light *lights, uint32_t light_count,
                          const roma_camera *camera, const roma_logger *logger, roma_scene **out)
{
    roma_result r;
    if (b->oom) {
        r = roma_fail(logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "built-in scene '%s': out of host memory",
                      name);
    } else {
        roma_scene_desc desc = {0};
        desc.positions = b->pos;
        desc.vertex_count = b->nv;
        desc.indices = b->idx;
        desc.triangle_count = b->nt;
        desc.triangle_materials = b->mat;
        desc.materials = materials;
        desc.material_count = material_count;
        desc.lights = lights;
        desc.light_count = light_count;
        desc.camera = camera;
        desc.name = name;
        if (logger)
            desc.logger = *logger;
        r = roma_scene_create(&desc, out);
    }
    free(b->pos);
    free(b->idx);
    free(b->mat);
    return r;
}

/* Closed room, 2 wide and high (x in [-1, 1], y in [0, 2]) and 3 deep
 * (z in [-1, 2]) so that a camera inside, by the front wall, sees the back
 * wall and both blocks; ambient occlusion finds walls in every direction.
 * "cornell_spot" is the same room with the ceiling quad dark, lit by the spot
 * alone: the scene where ROMA's one-bounce GI (RSMs of point and spot lights)
 * and the reference's carry the same light. */
static roma_result cornell(const char *name, int area_light_on, const roma_logger *logger, roma_scene **out)
{
    enum { WHITE, RED, GREEN, LIGHT };
    roma_material materials[] = {
        {{0.73f, 0.73f, 0.73f}, {0, 0, 0}},
        {{0.63f, 0.065f, 0.05f}, {0, 0, 0}},
        {{0.14f, 0.45f, 0.091f}, {0, 0, 0}},
        {{0.78f, 0.78f, 0.78f}, {12.0f, 10.0f, 8.0f}},
    };
    if (!area_light_on)
        materials[LIGHT].emission[0] = materials[LIGHT].emission[1] = materials[LIGHT].emission[2] = 0.0f;
    builder b = {0};
    rect(&b, 1, 0.0f, -1, -1, 2, 1, 0, WHITE);  /* floor */
    rect(&b, 1, 2.0f, -1, -1, 2, 1, 1, WHITE);  /* ceiling */
    rect(&b, 2, -1.0f, -1, 0, 1, 2, 0, WHITE);  /* back wall */
    rect(&b, 2, 2.0f, -1, 0, 1, 2, 1, WHITE);   /* front wall, behind the camera */
    rect(&b, 0, -1.0f, 0, -1, 2, 2, 0, RED);    /* left */
    rect(&b, 0, 1.0f, 0, -1, 2, 2, 1, GREEN);   /* right */
    rect(&b, 1, 1.98f, -0.55f, -0.3f, 0.05f, 0.3f, 1, LIGHT); /* area light, facing down */
    const float tall_c[3] = {-0.42f, 0.6f, -0.5f}, tall_h[3] = {0.28f, 0.6f, 0.28f};
    const float short_c[3] = {0.4f, 0.3f, -0.05f}, short_h[3] = {0.28f, 0.3f, 0.28f};
    box(&b, tall_c, tall_h, DEG(-15.0), WHITE);
    box(&b, short_c, short_h, DEG(18.0), WHITE);

    /* Spot high in the front-left corner, aimed at the top of the short block. */
    roma_light spot = {0};
    spot.type = ROMA_LIGHT_SPOT;
    const float from[3] = {-0.85f, 1.9f, 1.3f}, to[3] = {0.4f, 0.6f, -0.05f};
    for (int j = 0; j < 3; ++j) {
        spot.position[j] = from[j];
        spot.direction[j] = to[j] - from[j];
        spot.color[j] = 1.0f;
    }
    spot.intensity = 3.0f; /* candela */
    spot.inner_cone_angle = 0.2f;
    spot.outer_cone_angle = 0.35f;

    const roma_camera camera = {{0.0f, 1.0f, 1.9f}, {0.0f, 0.8f, -1.0f}, {0.0f, 1.0f, 0.0f}, 50.0f};
    return finish(&b, name, materials, 4, &spot, 1, &camera, logger, out);
}

/* Hard case for voxel methods: horizontal blind slats 1 cm thick (the
 * scene is ~3 units across, so below 1/128 of it) hanging 5 mm in front of
 * a window wall, and an open box with 1 cm walls on the floor. Light comes
 * through the window from a sun (directional) and from an emissive "sky"
 * quad outside, placed above the sun's path so it does not shadow the sun. */
static roma_result blinds(const roma_logger *logger, roma_scene **out)
{
    enum { WHITE, SLAT, BOX, SKY };
    static const roma_material materials[] = {
        {{0.75f, 0.75f, 0.75f}, {0, 0, 0}},
        {{0.85f, 0.8f, 0.7f}, {0, 0, 0}},
        {{0.6f, 0.3f, 0.2f}, {0, 0, 0}},
        {{0.0f, 0.0f, 0.0f}, {2.0f, 2.4f, 3.0f}},
    };
    builder b = {0};
    rect(&b, 1, 0.0f, -1, -1, 1, 1, 0, WHITE);                /* floor */
    rect(&b, 2, 1.0f, -1, 0, 1, 2, 1, WHITE);                 /* back wall, behind the camera */
    /* window wall z = -1 with an opening x in [-0.6, 0.6], y in [0.5, 1.7] */
    rect(&b, 2, -1.0f, -1.0f, 0.0f, 1.0f, 0.5f, 0, WHITE);
    rect(&b, 2, -1.0f, -1.0f, 1.7f, 1.0f, 2.0f, 0, WHITE);
    rect(&b, 2, -1.0f, -1.0f, 0.5f, -0.6f, 1.7f, 0, WHITE);
    rect(&b, 2, -1.0f, 0.6f, 0.5f, 1.0f, 1.7f, 0, WHITE);
    /* 30 slats: 1 cm thick, 3 cm deep, 4 cm pitch, wider than the opening */
    for (int i = 0; i < 30; ++i) {
        const float c[3] = {0.0f, 0.52f + 0.04f * (float)i, -0.98f}, h[3] = {0.65f, 0.005f, 0.015f};
        box(&b, c, h, 0.0f, SLAT);
    }
    open_box(&b, -0.35f, -0.2f, 0.2f, 0.3f, 0.01f, BOX);
    rect(&b, 1, 2.4f, -2.0f, -1.0f, -1.05f, 1.0f, 1, SKY); /* outside, facing down */

    roma_light sun = {0};
    sun.type = ROMA_LIGHT_DIRECTIONAL;
    const float dir[3] = {0.1f, -0.6f, 1.0f}, color[3] = {1.0f, 0.95f, 0.85f};
    memcpy(sun.direction, dir, sizeof dir);
    memcpy(sun.color, color, sizeof color);
    sun.intensity = 5.0f; /* lux */

    const roma_camera camera = {{0.6f, 1.4f, 0.95f}, {-0.15f, 0.55f, -0.9f}, {0.0f, 1.0f, 0.0f}, 65.0f};
    return finish(&b, "blinds", materials, 4, &sun, 1, &camera, logger, out);
}

/* Two 2 x 2 parallel plates half a unit apart: the upper one emits radiance
 * 1, so the irradiance on the lower one has a closed form (view factor). */
static roma_result plates(const roma_logger *logger, roma_scene **out)
{
    static const roma_material materials[] = {
        {{0.5f, 0.5f, 0.5f}, {0, 0, 0}},
        {{0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}},
    };
    builder b = {0};
    rect(&b, 1, 0.0f, -1, -1, 1, 1, 0, 0);
    rect(&b, 1, 0.5f, -1, -1, 1, 1, 1, 1);
    const roma_camera camera = {{0.0f, 0.25f, 2.5f}, {0.0f, 0.25f, 0.0f}, {0.0f, 1.0f, 0.0f}, 45.0f};
    return finish(&b, "plates", materials, 2, NULL, 0, &camera, logger, out);
}

static const char *const builtin_names[] = {"cornell", "blinds", "plates", "cornell_spot", NULL};

const char *const *roma_builtin_scene_names(void)
{
    return builtin_names;
}

roma_result roma_scene_create_builtin(const char *name, const roma_logger *logger, roma_scene **out_scene)
{
    if (out_scene)
        *out_scene = NULL;
    if (!out_scene)
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_scene_create_builtin: out_scene must not be NULL");
    if (!name || !strcmp(name, "cornell"))
        return cornell("cornell", 1, logger, out_scene);
    if (!strcmp(name, "cornell_spot"))
        return cornell("cornell_spot", 0, logger, out_scene);
    if (!strcmp(name, "blinds"))
        return blinds(logger, out_scene);
    if (!strcmp(name, "plates"))
        return plates(logger, out_scene);
    return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT,
                     "unknown built-in scene '%s' (have: cornell, blinds, plates, cornell_spot)", name);
}
