/* Host side of roma_animator: a clip evaluated at a time into node world matrices and
 * joint matrices, the bounds of the skinned scene, and the CPU skinning the GPU pass is
 * checked against. */
#ifndef ROMA_ANIMATE_POSE_H
#define ROMA_ANIMATE_POSE_H

#include "roma/animation.h"
#include "roma/scene.h"

typedef struct roma_pose_eval {
    roma_scene_animation_data anim; /* the scene's arrays (the scene outlives the animator) */
    uint32_t vertex_count;
    uint32_t *order;                /* nodes, parents before children */
    float *local_rest;              /* 16 per node: inverse(parent world) * world, at rest */
    float *local, *world;           /* 16 per node, this pose */
    float *joints;                  /* 16 per joint, this pose */
    float *clip_duration;           /* per clip */
    float *joint_box, *node_box;    /* 6 per joint / node (min xyz, max xyz) of the rest-local
                                       vertices it moves; min > max when it moves none */
    int origin_vertices;            /* skinned vertices whose weights are all 0: they sit at the
                                       origin in every pose (no joint moves them) */
} roma_pose_eval;

/* NULL on failure (out of memory). */
roma_result roma_pose_eval_init(roma_pose_eval *e, const roma_scene_view *view, const roma_logger *log);
void roma_pose_eval_free(roma_pose_eval *e);

/* Evaluates the clip at `time` (looped): world and joints. */
void roma_pose_eval_pose(roma_pose_eval *e, uint32_t clip, float time);
/* The bounds of every vertex under the current pose. */
void roma_pose_eval_bounds(const roma_pose_eval *e, roma_box *out);
/* Node worlds then joints, 12 floats each (the three rows of the affine part), for the
 * GPU pass. */
void roma_pose_eval_rows(const roma_pose_eval *e, float *out);
/* The skinned positions of the current pose, 3 floats per vertex. */
void roma_pose_eval_skin(const roma_pose_eval *e, float *out_positions);

#endif /* ROMA_ANIMATE_POSE_H */
