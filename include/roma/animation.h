/** @file
 * libroma: playing a scene's glTF animations (node animations and skins) on the GPU.
 *
 * A roma_animator evaluates a clip at a time on the host (keyframes -> node transforms
 * -> joint matrices: a few hundred matrices, not vertices) and records a compute pass
 * that skins every vertex of the scene into a positions buffer it owns (3 floats per
 * vertex, 12-byte stride). Feed that buffer to roma_map_record_build
 * (roma_map_frame_desc.gpu_positions) with the bounds the animator returns as the
 * volume, and the ROMA maps follow the animation every frame; the previous frame's
 * positions stay readable for motion vectors.
 *
 * Skinning follows glTF: a skinned vertex is sum_k w_k * J[joint_k] * p_rest with
 * J = world(joint node) * inverse bind matrix (weights normalised to sum 1); any other
 * vertex is world(its node) * p_rest. Clips loop over their duration (the last key).
 * Morph targets are not played (the loader keeps the base mesh).
 *
 * Threads and queues (roma/context.h): an animator is externally synchronised, used by one
 * thread at a time; record calls never submit or wait. The slot rules are those of roma_map_frame_desc.slot.
 *
 * Lifetimes: an animator reads the scene's animation arrays while it lives: the scene must
 * outlive it (and keep its animation data: no roma_scene_set_animation_data meanwhile). */
#ifndef ROMA_ANIMATION_H
#define ROMA_ANIMATION_H

#include "roma/api.h"

#include <stdint.h>
#include <vulkan/vulkan.h>

#include "roma/context.h"
#include "roma/map.h"
#include "roma/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Plays a scene's glTF skins and node animations on the GPU (opaque). Used by one thread at a
 * time (roma/context.h). */
typedef struct roma_animator roma_animator;

/** Settings of roma_animator_create; the zero value is the default. */
typedef struct roma_animator_desc {
    uint32_t frames_in_flight; /**< slots for the per-frame matrices, [1, 8]; 0 = 2 */
    roma_logger logger;        /**< 0 = the context's */
} roma_animator_desc;

/** Creates an animator for a scene. The scene must carry animation data
 * (roma_scene_view.animation with per-vertex arrays, as the glTF loader keeps for skinned or
 * animated files): ROMA_ERROR_INVALID_ARGUMENT otherwise. Uploads the per-vertex skinning
 * data and the rest pose (submits and waits once; not a per-frame call).
 *
 * @param context   the context; must outlive the animator.
 * @param scene     the animated scene; must outlive the animator (its arrays are read, not
 *                  copied).
 * @param desc      settings; NULL = the zero value (2 slots, the context's logger). Copied.
 * @param[out] out_animator  the new animator; NULL on failure.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL out_animator, context or
 *         scene, frames_in_flight above 8, a scene without animation data;
 *         ROMA_ERROR_OUT_OF_HOST_MEMORY, or a Vulkan failure code (roma_result).
 * @par Threads
 * Any thread; submits to the context's queue (roma_context_desc.queue_lock). */
ROMA_API roma_result roma_animator_create(roma_context *context, const roma_scene *scene, const roma_animator_desc *desc,
                                          roma_animator **out_animator);
/** Destroys the animator and its buffers (roma_animator_output handles become invalid).
 *
 * @param animator  the animator, or NULL (nothing is done). The caller makes sure no
 *                  submitted work still uses it or its position buffers.
 * @par Threads
 * Any thread, the animator externally synchronised. */
ROMA_API void roma_animator_destroy(roma_animator *animator);

/** A clip and a time in it. */
typedef struct roma_animator_pose {
    uint32_t clip;   /**< index of the animation, < roma_animator_info.clip_count (0 if none) */
    float time;      /**< seconds, finite; wraps at the clip's duration; negative = 0 */
} roma_animator_pose;

/** Where one record put this frame's positions (roma_animator_record). */
typedef struct roma_animator_output {
    VkDeviceAddress positions;          /**< this frame's skinned positions (3 floats per vertex) */
    VkDeviceAddress previous_positions; /**< the previous record's (the rest pose before the first) */
    /** The buffer positions lies in (for the caller's use as a storage or vertex buffer). */
    VkBuffer positions_buffer;
    VkBuffer previous_positions_buffer; /**< the buffer previous_positions lies in */
    /** Bounds every skinned vertex lies in: the union of each joint's rest-pose vertex box
     * under its joint matrix (and each node's under its world matrix), so it holds however
     * the weights mix. A volume for roma_map_frame_desc. */
    roma_box bounds;
} roma_animator_output;

/** Records the skinning of `pose` into cmd (compute; a barrier after every earlier
 * command first, so the previous frame's readers of the buffer it overwrites are done).
 * The matrices go to the slot's storage. The written positions are visible to
 * roma_map_record_build (which opens with its own barrier); for other readers the
 * caller adds a barrier from compute-shader writes. Two position buffers are written in
 * turn: a record overwrites the one the record before last wrote.
 *
 * @param animator  the animator.
 * @param cmd       a command buffer of the context's queue family, recording.
 * @param slot      the engine's frame slot, below frames_in_flight (the matrices are written
 *                  to the slot's host-visible storage now).
 * @param pose      the clip and time; copied.
 * @param[out] out  where this frame's positions are; zeroed first. The buffers belong to the
 *                  animator and live until roma_animator_destroy.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL animator, cmd, pose or out, a
 *         clip out of range, a non-finite time, a slot not below frames_in_flight; a Vulkan
 *         failure code (roma_result) for the slot's storage, made on its first use.
 * @par Threads
 * Any thread, the animator externally synchronised; cmd externally synchronised. Never submits or
 * waits. */
ROMA_API roma_result roma_animator_record(roma_animator *animator, VkCommandBuffer cmd, uint32_t slot,
                                          const roma_animator_pose *pose, roma_animator_output *out);

/** The same pose evaluated and skinned on the host (the GPU pass's reference, and a path
 * for CPU callers): out_positions receives 3 floats per vertex. No GPU work.
 *
 * @param animator            the animator.
 * @param pose                the clip and time.
 * @param[out] out_positions  3 * vertex_count floats (roma_animator_info.vertex_count).
 * @param[out] out_bounds     the bounds, as roma_animator_output.bounds; may be NULL.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL animator, pose or out_positions,
 *         a clip out of range or a non-finite time.
 * @par Threads
 * Any thread, the animator externally synchronised. */
ROMA_API roma_result roma_animator_pose_cpu(roma_animator *animator, const roma_animator_pose *pose, float *out_positions,
                                            roma_box *out_bounds);

/** What an animator plays (roma_animator_get_info). */
typedef struct roma_animator_info {
    uint32_t vertex_count; /**< vertices the animator skins: the scene's */
    uint32_t clip_count; /**< animations (glTF animations) of the scene */
    uint32_t joint_count; /**< skin joints over all skins */
    uint32_t node_count; /**< nodes of the glTF node hierarchy */
} roma_animator_info;

/** What the animator plays.
 *
 * @param animator       the animator.
 * @param[out] out_info  the counts; zeroed on failure.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for NULL arguments (out_info zeroed).
 * @par Threads
 * Any thread, the animator externally synchronised. */
ROMA_API roma_result roma_animator_get_info(const roma_animator *animator, roma_animator_info *out_info);
/** Seconds of clip `clip` (its last key time).
 *
 * @param animator          the animator.
 * @param clip              the clip, below roma_animator_info.clip_count.
 * @param[out] out_seconds  the duration; 0 on failure.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for NULL arguments or a clip out of range.
 * @par Threads
 * Any thread, the animator externally synchronised. */
ROMA_API roma_result roma_animator_clip_duration(const roma_animator *animator, uint32_t clip, float *out_seconds);

/** A copy of `scene` posed at `pose` on the host, no GPU involved: positions skinned as the
 * animator skins them, normals recomputed from the posed faces, materials and animation
 * data kept; lights and the camera stay where the file puts them at rest. For offline
 * renderers and tools (roma-render --time). The same errors as roma_animator_create for a
 * scene without animation data.
 *
 * @param scene   the animated scene; only read.
 * @param pose    the clip and time.
 * @param logger  where messages go; NULL: stderr (warnings and errors).
 * @param[out] out_posed  the new scene, owned by the caller and independent of scene; NULL on
 *                failure.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for NULL arguments, a scene without
 *         animation data, a clip out of range or a non-finite time;
 *         ROMA_ERROR_OUT_OF_HOST_MEMORY; the codes of roma_scene_create for the posed geometry
 *         (ROMA_ERROR_EMPTY_SCENE, ROMA_ERROR_INVALID_SCENE).
 * @par Threads
 * Any thread; the scene may be read by others meanwhile. */
ROMA_API roma_result roma_scene_pose(const roma_scene *scene, const roma_animator_pose *pose, const roma_logger *logger,
                                     roma_scene **out_posed);

/** Downloads the positions of the last recorded (and completed) skinning, 3 floats per
 * vertex (the rest pose before the first record). Blocking (submits a copy after the work
 * already submitted to the context's queue, and waits); for tests and tools.
 *
 * @param animator            the animator.
 * @param[out] out_positions  3 * vertex_count floats.
 * @param vertex_count        must equal roma_animator_info.vertex_count.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for NULL arguments or another
 *         vertex_count; a Vulkan failure code (roma_result).
 * @par Threads
 * Any thread, the animator externally synchronised; submits to the context's queue
 * (roma_context_desc.queue_lock). */
ROMA_API roma_result roma_animator_download_positions(roma_animator *animator, float *out_positions, uint32_t vertex_count);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_ANIMATION_H */
