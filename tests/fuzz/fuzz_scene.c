/* libFuzzer target for the glTF loader and the scene builder. Every input goes
 * through both:
 *  - as a .gltf/.glb file, loaded from memory (external URIs refused);
 *  - as the arrays of a roma_scene_desc (counts, positions, indices, materials,
 *    lights taken from the bytes), built with roma_scene_create.
 * Crashes, leaks, undefined behaviour and hangs are findings; so is a scene that
 * loads but cannot be rebuilt from its own view (the builder and the loader must
 * agree on what a valid scene is). Run: tests/CMakeLists.txt (make test-fuzz). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "roma/gltf.h"
#include "roma/scene.h"

/* Silent, unless ROMA_FUZZ_VERBOSE is set (to see why a crashing input was refused). */
static void quiet(roma_log_level level, roma_result code, const char *message, void *user_data)
{
    (void)code;
    (void)user_data;
    if (getenv("ROMA_FUZZ_VERBOSE"))
        fprintf(stderr, "[%s] %s\n", roma_log_level_string(level), message);
}

static const roma_logger quiet_logger = {quiet, NULL};

/* Reads everything a renderer would and rebuilds the scene from its view. */
static void exercise(const roma_scene *scene)
{
    roma_scene_view v;
    if (roma_scene_get_view(scene, &v) != ROMA_SUCCESS)
        abort();
    roma_scene_desc desc = {
        .positions = v.positions, .normals = v.normals, .vertex_count = v.vertex_count,
        .indices = v.indices, .triangle_count = v.triangle_count,
        .triangle_materials = v.triangle_materials, .materials = v.materials,
        .material_count = v.material_count, .lights = v.lights, .light_count = v.light_count,
        .camera = v.has_camera ? &v.camera : NULL, .name = v.name, .logger = quiet_logger};
    roma_scene *copy = NULL;
    if (roma_scene_create(&desc, &copy) != ROMA_SUCCESS)
        abort(); /* the loader produced a scene the builder refuses */
    roma_scene_destroy(copy);
    roma_camera cam;
    roma_scene_default_camera(scene, 1.5f, &cam);
}

/* Takes n bytes from the input, or fails when it runs out. */
static const uint8_t *take(const uint8_t **data, size_t *size, size_t n)
{
    if (*size < n)
        return NULL;
    const uint8_t *p = *data;
    *data += n, *size -= n;
    return p;
}

static void build_from_bytes(const uint8_t *data, size_t size)
{
    const uint8_t *head = take(&data, &size, 4);
    if (!head)
        return;
    uint32_t vertices = head[0], triangles = head[1], materials = head[2] % 4, lights = head[3] % 4;
    const uint8_t *pos = take(&data, &size, sizeof(float) * 3 * vertices);
    const uint8_t *idx = take(&data, &size, sizeof(uint32_t) * 3 * triangles);
    const uint8_t *mats = take(&data, &size, sizeof(roma_material) * materials);
    const uint8_t *tmat = materials ? take(&data, &size, triangles) : NULL;
    const uint8_t *lts = take(&data, &size, sizeof(roma_light) * lights);
    if (!pos || !idx || (materials && (!mats || !tmat)) || (lights && !lts))
        return;
    /* Copies: the input need not be aligned; indices and material indices mostly in range. */
    float *p = malloc(sizeof(float) * 3 * vertices + 1);
    uint32_t *ix = malloc(sizeof(uint32_t) * 3 * triangles + 1);
    uint32_t *tm = malloc(sizeof(uint32_t) * triangles + 1);
    roma_material *m = malloc(sizeof(roma_material) * materials + 1);
    roma_light *l = malloc(sizeof(roma_light) * lights + 1);
    memcpy(p, pos, sizeof(float) * 3 * vertices);
    memcpy(ix, idx, sizeof(uint32_t) * 3 * triangles);
    for (uint32_t i = 0; i < 3 * triangles; ++i)
        if (!(ix[i] & 0x80000000u))
            ix[i] %= vertices + 1;
    for (uint32_t i = 0; i < triangles && materials; ++i)
        tm[i] = tmat[i] % (materials + 1);
    memcpy(m, mats, sizeof(roma_material) * materials);
    memcpy(l, lts, sizeof(roma_light) * lights);
    roma_scene_desc desc = {.positions = p, .vertex_count = vertices, .indices = ix,
                            .triangle_count = triangles, .triangle_materials = materials ? tm : NULL,
                            .materials = materials ? m : NULL, .material_count = materials,
                            .lights = lights ? l : NULL, .light_count = lights, .logger = quiet_logger};
    roma_scene *scene = NULL;
    if (roma_scene_create(&desc, &scene) == ROMA_SUCCESS) {
        exercise(scene);
        roma_scene_destroy(scene);
    } else if (scene) {
        abort(); /* failures leave nothing behind */
    }
    free(p), free(ix), free(tm), free(m), free(l);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* Limits well under the default keep every input inside the fuzzer's memory
     * limit (a 343-byte file once asked for 4 GB); the limit checks are fuzzed too. */
    roma_gltf_desc desc = {.logger = quiet_logger, .max_vertices = 1u << 20, .max_triangles = 1u << 20};
    roma_scene *scene = (roma_scene *)&desc; /* must come back NULL on failure */
    roma_result r = roma_scene_load_gltf_memory(data, size, NULL, &desc, &scene);
    if (r == ROMA_SUCCESS) {
        exercise(scene);
        roma_scene_destroy(scene);
    } else if (scene) {
        abort();
    }
    build_from_bytes(data, size);
    return 0;
}
