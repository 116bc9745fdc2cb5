/* The closed box room of the closed-room tests (box_room.h). */
#include "box_room.h"

#include <math.h>
#include <string.h>

#include "harness.h"

void roma_test_rotate(const float r[9], const float in[3], float out[3])
{
    for (int i = 0; i < 3; ++i)
        out[i] = r[3 * i] * in[0] + r[3 * i + 1] * in[1] + r[3 * i + 2] * in[2];
}

/* Rodrigues: angle about the unit axis. */
void roma_test_rotation(const float axis_in[3], float angle, float r[9])
{
    float len = sqrtf(axis_in[0] * axis_in[0] + axis_in[1] * axis_in[1] + axis_in[2] * axis_in[2]);
    float x = axis_in[0] / len, y = axis_in[1] / len, z = axis_in[2] / len, c = cosf(angle), s = sinf(angle);
    const float m[9] = {c + x * x * (1 - c),     x * y * (1 - c) - z * s, x * z * (1 - c) + y * s,
                        y * x * (1 - c) + z * s, c + y * y * (1 - c),     y * z * (1 - c) - x * s,
                        z * x * (1 - c) - y * s, z * y * (1 - c) + x * s, c + z * z * (1 - c)};
    memcpy(r, m, sizeof m);
}

/* Axis-aligned box [lo, hi] as 12 triangles into the arrays (8 vertices). */
static void add_box(const float lo[3], const float hi[3], float *pos, uint32_t *vcount, uint32_t *idx, uint32_t *tcount)
{
    uint32_t base = *vcount;
    for (int i = 0; i < 8; ++i) {
        pos[3 * (base + i) + 0] = (i & 1) ? hi[0] : lo[0];
        pos[3 * (base + i) + 1] = (i & 2) ? hi[1] : lo[1];
        pos[3 * (base + i) + 2] = (i & 4) ? hi[2] : lo[2];
    }
    static const uint32_t faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
    for (int f = 0; f < 6; ++f) {
        const uint32_t *q = faces[f];
        const uint32_t t[6] = {q[0], q[1], q[2], q[0], q[2], q[3]};
        for (int k = 0; k < 6; ++k)
            idx[3 * *tcount + k] = base + t[k];
        *tcount += 2;
    }
    *vcount += 8;
}

/* The box room turned by rot, with a light outside it when with_light. */
roma_scene *roma_test_box_room(const float rot[9], int with_light)
{
    float pos[16 * 3];
    uint32_t idx[24 * 3], vcount = 0, tcount = 0;
    add_box((const float[3]){-1, 0, -1}, (const float[3]){1, 2, 2}, pos, &vcount, idx, &tcount);
    add_box((const float[3]){-0.5f, 0, -0.6f}, (const float[3]){0.1f, 0.7f, 0.0f}, pos, &vcount, idx, &tcount);
    for (uint32_t v = 0; v < vcount; ++v) {
        float p[3] = {pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]};
        roma_test_rotate(rot, p, &pos[3 * v]);
    }
    roma_light light = {.type = ROMA_LIGHT_POINT, .color = {1, 1, 1}, .intensity = 20.0f};
    roma_test_rotate(rot, (const float[3]){0.0f, 1.0f, -1.3f}, light.position);
    if (with_light == 2) { /* a sun on the roof and the back wall, from outside */
        light.type = ROMA_LIGHT_DIRECTIONAL;
        light.intensity = 3.0f;
        roma_test_rotate(rot, (const float[3]){0.2f, -0.6f, 0.775f}, light.direction);
    }
    roma_camera cam = {.fovy_deg = 70.0f};
    roma_test_rotate(rot, (const float[3]){0.0f, 1.0f, 1.9f}, cam.eye);
    roma_test_rotate(rot, (const float[3]){0.0f, 0.6f, -1.0f}, cam.target);
    roma_test_rotate(rot, (const float[3]){0.0f, 1.0f, 0.0f}, cam.up);
    roma_scene_desc d = {.positions = pos, .vertex_count = vcount, .indices = idx, .triangle_count = tcount,
                         .lights = with_light ? &light : NULL, .light_count = with_light ? 1u : 0u,
                         .camera = &cam, .name = "box room"};
    roma_scene *scene = NULL;
    CHECK_RESULT(roma_scene_create(&d, &scene), ROMA_SUCCESS);
    return scene;
}


/* The box room with a light near its ceiling (box_room.h). */
roma_scene *roma_test_box_room_ceiling_light(const float rot[9], const roma_test_outside_light *o)
{
    float pos[28 * 3];
    uint32_t idx[38 * 3], mat[38], vcount = 0, tcount = 0;
    add_box((const float[3]){-1, 0, -1}, (const float[3]){1, 2, 2}, pos, &vcount, idx, &tcount);
    add_box((const float[3]){-0.5f, 0, -0.6f}, (const float[3]){0.1f, 0.7f, 0.0f}, pos, &vcount, idx, &tcount);
    if (o->thickness > 0.0f)
        add_box((const float[3]){-1, 2, -1}, (const float[3]){1, 2 + o->thickness, 2}, pos, &vcount, idx, &tcount);
    const float y = o->inside ? 2.0f - o->gap : 2.0f + o->thickness + o->gap;
    const uint32_t room_triangles = tcount;
    if (o->kind == ROMA_TEST_OUTSIDE_LAMP) {
        const float quad[4][3] = {{-0.5f, y, 0.0f}, {0.5f, y, 0.0f}, {0.5f, y, 1.0f}, {-0.5f, y, 1.0f}};
        memcpy(&pos[3 * vcount], quad, sizeof quad);
        const uint32_t t[6] = {vcount, vcount + 2, vcount + 1, vcount, vcount + 3, vcount + 2};
        memcpy(&idx[3 * tcount], t, sizeof t);
        vcount += 4;
        tcount += 2;
    }
    for (uint32_t i = 0; i < tcount; ++i)
        mat[i] = i >= room_triangles;
    if (o->lamp_first && tcount > room_triangles) { /* the lamp's two triangles to the front */
        uint32_t lamp[6];
        memcpy(lamp, &idx[3 * room_triangles], sizeof lamp);
        memmove(&idx[6], idx, 3 * sizeof(uint32_t) * room_triangles);
        memcpy(idx, lamp, sizeof lamp);
        for (uint32_t i = 0; i < tcount; ++i)
            mat[i] = i < tcount - room_triangles;
    }
    for (uint32_t v = 0; v < vcount; ++v) {
        float p[3] = {pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]};
        roma_test_rotate(rot, p, &pos[3 * v]);
    }
    const roma_material materials[2] = {{.base_color = {0.8f, 0.8f, 0.8f}},
                                        {.base_color = {0.8f, 0.8f, 0.8f}, .emission = {4.0f, 4.0f, 4.0f}}};
    roma_light light = {.type = o->kind == ROMA_TEST_OUTSIDE_SPOT ? ROMA_LIGHT_SPOT : ROMA_LIGHT_POINT,
                        .color = {1, 1, 1}, .intensity = 4.0f, .outer_cone_angle = 1.2f, .inner_cone_angle = 1.0f};
    roma_test_rotate(rot, (const float[3]){0.0f, y, 0.5f}, light.position);
    roma_test_rotate(rot, (const float[3]){0.0f, -1.0f, 0.0f}, light.direction);
    roma_camera cam = {.fovy_deg = 70.0f};
    roma_test_rotate(rot, (const float[3]){0.0f, 1.0f, 1.9f}, cam.eye);
    roma_test_rotate(rot, (const float[3]){0.0f, 0.8f, -1.0f}, cam.target);
    roma_test_rotate(rot, (const float[3]){0.0f, 1.0f, 0.0f}, cam.up);
    const int punctual = o->kind != ROMA_TEST_OUTSIDE_LAMP;
    roma_scene_desc d = {.positions = pos, .vertex_count = vcount, .indices = idx, .triangle_count = tcount,
                         .triangle_materials = mat, .materials = materials, .material_count = 2,
                         .lights = punctual ? &light : NULL, .light_count = punctual ? 1u : 0u, .camera = &cam,
                         .name = "box room, light at the ceiling"};
    roma_scene *scene = NULL;
    CHECK_RESULT(roma_scene_create(&d, &scene), ROMA_SUCCESS);
    return scene;
}
