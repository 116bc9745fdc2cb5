/* Every model of scenes/ (see its README.md) loads with the
 * triangle count of the README table (instanced counts where nodes reuse a
 * mesh), finite data and non-empty bounds; skinned models keep their skins
 * and animations. Skips (77) when the folder is absent. */
#include <math.h>
#include <string.h>

#include "harness.h"
#include "roma/gltf.h"

typedef struct expected {
    const char *file;
    uint32_t triangles;
    uint32_t animations; /* > 0: skinned and animated */
    int camera;          /* the file places a perspective camera in its scene */
} expected;

static const expected models[] = {
    {"cornell.glb", 34, 0, 0},
    {"spot.glb", 5856, 0, 0},
    {"bunny.glb", 69451, 0, 0},
    {"dragon_res3.glb", 47794, 0, 0},
    {"dragon_res2.glb", 202520, 0, 0},
    {"2CylinderEngine.glb", 121496, 0, 1},
    {"tabletop.gltf", 23388, 0, 0},
    {"CesiumMan.glb", 4672, 1, 0},
    {"Fox.glb", 576, 3, 0},
};

static void check_model(const expected *e, const char *path)
{
    roma_test_log log;
    roma_gltf_desc desc = {.logger = roma_test_logger(&log)};
    roma_scene *s = NULL;
    roma_result r = roma_scene_load_gltf(path, &desc, &s);
    if (r != ROMA_SUCCESS || !s) {
        fprintf(stderr, "%s: load failed: %s\n", e->file, roma_result_string(r));
        ++roma_test_failures;
        return;
    }
    roma_scene_view v;
    roma_scene_get_view(s, &v);
    printf("%-20s %7u triangles (%u degenerate), %7u vertices, bounds [%g %g %g]..[%g %g %g], %u warnings\n",
           e->file, v.triangle_count, v.degenerate_triangle_count, v.vertex_count, v.bounds_min[0],
           v.bounds_min[1], v.bounds_min[2], v.bounds_max[0], v.bounds_max[1], v.bounds_max[2], log.warnings);
    if (v.triangle_count != e->triangles) {
        fprintf(stderr, "%s: %u triangles, README says %u\n", e->file, v.triangle_count, e->triangles);
        ++roma_test_failures;
    }
    CHECK(log.errors == 0);
    int finite = 1;
    for (uint32_t i = 0; i < 3 * v.vertex_count; ++i)
        finite = finite && isfinite(v.positions[i]) && isfinite(v.normals[i]);
    CHECK(finite);
    for (int k = 0; k < 3; ++k)
        CHECK(v.bounds_max[k] > v.bounds_min[k]);
    CHECK(v.has_camera == e->camera);

    const roma_scene_animation_data *a = &v.animation;
    if (e->animations) {
        CHECK(a->skin_count >= 1 && a->joint_total > 0 && a->node_count > 0);
        CHECK(a->animation_count == e->animations && a->channel_count > 0);
        uint32_t skinned = 0;
        for (uint32_t i = 0; a->vertex_skin && i < v.vertex_count; ++i)
            skinned += a->vertex_skin[i] >= 0;
        CHECK(skinned == v.vertex_count);
        CHECK(a->vertex_rest_local && a->vertex_weights && a->vertex_joints && a->times && a->values);
        /* Skinned at rest, the figure stands upright: taller (y) than deep or wide. */
        float size[3];
        for (int k = 0; k < 3; ++k)
            size[k] = v.bounds_max[k] - v.bounds_min[k];
        printf("  %u skin(s), %u joints, %u animations, %u channels\n", a->skin_count, a->joint_total,
               a->animation_count, a->channel_count);
        if (!strcmp(e->file, "CesiumMan.glb"))
            CHECK(size[1] > size[0] && size[1] > size[2]);
    } else {
        CHECK(a->skin_count == 0 && a->animation_count == 0);
    }
    roma_scene_destroy(s);
}

int main(void)
{
    char path[4096];
    size_t n = sizeof models / sizeof models[0];
    for (size_t i = 0; i < n; ++i) {
        if (!roma_test_scene_file(models[i].file, path, sizeof path))
            continue;
        check_model(models + i, path);
    }
    return roma_test_finish("test_shared_scenes");
}
