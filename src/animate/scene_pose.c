/* roma_scene_pose: a posed copy of an animated scene, evaluated and skinned on the host. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "animate/pose.h"
#include "util/log.h"

roma_result roma_scene_pose(const roma_scene *scene, const roma_animator_pose *pose, const roma_logger *log,
                            roma_scene **out)
{
    if (out)
        *out = NULL;
    if (!scene || !pose || !out)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_scene_pose: %s is NULL",
                         !scene ? "scene" : !pose ? "pose" : "out_posed");
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    if (!v.animation.node_count || !v.animation.vertex_node || !v.animation.vertex_rest_local)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_scene_pose: scene '%s' has no animation data",
                         v.name ? v.name : "");
    uint32_t clips = v.animation.animation_count;
    if (pose->clip >= (clips ? clips : 1) || !isfinite(pose->time))
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_scene_pose: clip %u of %u, time %g: the clip must exist and the time be finite",
                         pose->clip, clips, (double)pose->time);
    roma_pose_eval e;
    roma_result r = roma_pose_eval_init(&e, &v, log);
    if (r != ROMA_SUCCESS)
        return r;
    float *positions = malloc(12ull * v.vertex_count);
    if (!positions) {
        roma_pose_eval_free(&e);
        return roma_fail(log, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_scene_pose: out of host memory");
    }
    roma_pose_eval_pose(&e, pose->clip, pose->time);
    roma_pose_eval_skin(&e, positions);
    roma_pose_eval_free(&e);
    roma_scene_desc d = {.positions = positions, .vertex_count = v.vertex_count, .indices = v.indices,
                         .triangle_count = v.triangle_count, .triangle_materials = v.triangle_materials,
                         .materials = v.materials, .material_count = v.material_count, .lights = v.lights,
                         .light_count = v.light_count, .camera = v.has_camera ? &v.camera : NULL, .cameras = v.cameras,
                         .camera_count = v.camera_count, .name = v.name};
    if (log)
        d.logger = *log;
    roma_scene *posed = NULL;
    r = roma_scene_create(&d, &posed);
    free(positions);
    if (r == ROMA_SUCCESS)
        r = roma_scene_set_animation_data(posed, &v.animation, log);
    if (r != ROMA_SUCCESS) {
        roma_scene_destroy(posed);
        return r;
    }
    *out = posed;
    return ROMA_SUCCESS;
}
