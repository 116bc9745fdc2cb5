/* --up: a scene authored with another up axis turned so that +y is up, as the tools'
 * cameras assume. A rotation (no mirror), applied to positions, normals, lights and the
 * scene's camera. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"

/* The rotation that takes `up` to +y: rows of a 3x3 matrix. */
static int rotation_for(const char *up, float m[3][3])
{
    static const float identity[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    static const float y_down[3][3] = {{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}; /* 180 degrees about x */
    static const float z_up[3][3] = {{1, 0, 0}, {0, 0, 1}, {0, -1, 0}};   /* (x, y, z) -> (x, z, -y) */
    const float(*r)[3] = !strcmp(up, "+y") ? identity : !strcmp(up, "-y") ? y_down : !strcmp(up, "+z") ? z_up : NULL;
    if (!r)
        return 0;
    memcpy(m, r, sizeof(float) * 9);
    return 1;
}

int roma_app_valid_up(const char *up)
{
    float m[3][3];
    return up && rotation_for(up, m);
}

static void turn(const float m[3][3], const float in[3], float out[3])
{
    float v[3];
    for (int r = 0; r < 3; ++r)
        v[r] = m[r][0] * in[0] + m[r][1] * in[1] + m[r][2] * in[2];
    memcpy(out, v, sizeof v);
}

/* The file's own warnings were said when it was loaded; the copy repeats none. */
static void errors_only(roma_log_level level, roma_result code, const char *message, void *user)
{
    (void)code, (void)user;
    if (level >= ROMA_LOG_ERROR)
        fprintf(stderr, "libroma: %s\n", message);
}

static roma_camera turn_camera(float m[3][3], const roma_camera *c)
{
    roma_camera out = *c;
    turn(m, c->eye, out.eye);
    turn(m, c->target, out.target);
    float up_in[3] = {c->up[0], c->up[1], c->up[2]};
    if (up_in[0] == 0.0f && up_in[1] == 0.0f && up_in[2] == 0.0f)
        up_in[1] = 1.0f;
    turn(m, up_in, out.up);
    return out;
}

roma_result roma_app_reorient(const roma_scene *scene, const char *up, roma_scene **out)
{
    float m[3][3];
    if (!scene || !up || !out || !rotation_for(up, m))
        return ROMA_ERROR_INVALID_ARGUMENT;
    roma_scene_view v;
    roma_result r = roma_scene_get_view(scene, &v);
    if (r != ROMA_SUCCESS)
        return r;
    size_t nv = (size_t)v.vertex_count * 3;
    float *positions = malloc(sizeof(float) * nv), *normals = malloc(sizeof(float) * nv);
    roma_light *lights = malloc(sizeof(roma_light) * (v.light_count ? v.light_count : 1));
    roma_camera *cameras = malloc(sizeof(roma_camera) * (v.camera_count ? v.camera_count : 1));
    if (!positions || !normals || !lights || !cameras) {
        free(positions);
        free(normals);
        free(lights);
        free(cameras);
        return ROMA_ERROR_OUT_OF_HOST_MEMORY;
    }
    for (uint32_t i = 0; i < v.vertex_count; ++i) {
        turn(m, v.positions + 3 * i, positions + 3 * i);
        turn(m, v.normals + 3 * i, normals + 3 * i);
    }
    for (uint32_t i = 0; i < v.light_count; ++i) {
        lights[i] = v.lights[i];
        turn(m, v.lights[i].position, lights[i].position);
        turn(m, v.lights[i].direction, lights[i].direction);
    }
    roma_camera camera = v.has_camera ? turn_camera(m, &v.camera) : v.camera;
    for (uint32_t i = 0; i < v.camera_count; ++i)
        cameras[i] = turn_camera(m, &v.cameras[i]);
    /* Normals that were zero (unused vertices) stay zero; the builder recomputes none. */
    roma_scene_desc d = {.positions = positions, .normals = normals, .vertex_count = v.vertex_count,
                         .indices = v.indices, .triangle_count = v.triangle_count,
                         .triangle_materials = v.triangle_materials, .materials = v.materials,
                         .material_count = v.material_count, .lights = lights, .light_count = v.light_count,
                         .camera = v.has_camera ? &camera : NULL, .cameras = cameras,
                         .camera_count = v.camera_count, .name = v.name,
                         .logger = {errors_only, NULL}};
    r = roma_scene_create(&d, out);
    free(positions);
    free(normals);
    free(lights);
    free(cameras);
    return r;
}
