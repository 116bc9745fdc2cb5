/* The example engine's scene (scene.h). */
#include "scene.h"

#include <stdlib.h>
#include <string.h>

#include "roma/builtin_scenes.h"

const float box_centre[3] = {0.0f, 1.5f, 0.5f};
const float character_placement[4] = {-0.4f, 0.0f, 1.1f, 0.9f};
const roma_box scene_volume = {{-1.05f, -0.05f, -1.05f}, {1.05f, 2.05f, 2.05f}};

float box_offset(uint32_t frame)
{
    return -0.6f + 0.3f * (float)(frame % 5);
}

roma_scene *make_scene(roma_logger logger, const roma_scene *character, uint32_t *out_character_first,
                       uint32_t *out_character_count, uint32_t *out_box_first)
{
    roma_scene *room = NULL;
    if (roma_scene_create_builtin("cornell", &logger, &room) != ROMA_SUCCESS)
        return NULL;
    roma_scene_view v, cv = {0};
    roma_scene_get_view(room, &v);
    if (character)
        roma_scene_get_view(character, &cv);
    uint32_t room_vertices = v.vertex_count, room_triangles = v.triangle_count;
    v.vertex_count += cv.vertex_count; /* from here on: room + character */
    v.triangle_count += cv.triangle_count;
    uint32_t nv = v.vertex_count + 8, nt = v.triangle_count + 12;
    float *pos = malloc(sizeof(float) * 3 * nv);
    uint32_t *idx = malloc(sizeof(uint32_t) * 3 * nt), *mat = malloc(sizeof(uint32_t) * nt);
    roma_scene *scene = NULL;
    if (pos && idx && mat) {
        memcpy(pos, v.positions, sizeof(float) * 3 * room_vertices);
        memcpy(idx, v.indices, sizeof(uint32_t) * 3 * room_triangles);
        memcpy(mat, v.triangle_materials, sizeof(uint32_t) * room_triangles);
        for (uint32_t i = 0; i < 3 * cv.vertex_count; ++i)
            pos[3 * room_vertices + i] = cv.positions[i] * character_placement[3] + character_placement[i % 3];
        for (uint32_t i = 0; i < 3 * cv.triangle_count; ++i)
            idx[3 * room_triangles + i] = cv.indices[i] + room_vertices;
        for (uint32_t t = 0; t < cv.triangle_count; ++t)
            mat[room_triangles + t] = 0;
        for (int c = 0; c < 8; ++c)
            for (int a = 0; a < 3; ++a)
                pos[3 * (v.vertex_count + c) + a] = box_centre[a] + ((c >> a) & 1 ? BOX_HALF : -BOX_HALF);
        static const uint32_t faces[36] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                           2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
        for (int i = 0; i < 36; ++i)
            idx[3 * v.triangle_count + i] = v.vertex_count + faces[i];
        for (int t = 0; t < 12; ++t)
            mat[v.triangle_count + t] = 0;
        roma_scene_desc d = {.positions = pos, .vertex_count = nv, .indices = idx, .triangle_count = nt,
                             .triangle_materials = mat, .materials = v.materials, .material_count = v.material_count,
                             .lights = v.lights, .light_count = v.light_count, .name = "room with a moving box",
                             .logger = logger};
        if (roma_scene_create(&d, &scene) != ROMA_SUCCESS)
            scene = NULL;
        *out_box_first = v.vertex_count;
        *out_character_first = room_vertices;
        *out_character_count = cv.vertex_count;
    }
    free(pos), free(idx), free(mat);
    roma_scene_destroy(room);
    return scene;
}
