/* roma_animator: the host evaluates the pose (animate/pose.c), the GPU skins every vertex
 * (shaders/animate/skin.comp) into one of two position buffers, in turn, so the previous
 * frame's positions stay readable. */
#include "roma/animation.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "animate/pose.h"
#include "roma_shared.h"
#include "util/log.h"
#include "vulkan/vk_internal.h"

struct roma_animator {
    roma_context *ctx;
    roma_logger logger;
    uint32_t frames_in_flight;
    roma_pose_eval eval;
    uint32_t row_count;                        /* node worlds + joint matrices */
    roma_buffer vertices;                      /* roma_skin_vertex per vertex (device) */
    roma_buffer rows[ROMA_MAX_FRAMES_IN_FLIGHT]; /* per slot, host-visible, made on first use */
    roma_buffer positions[2];                  /* 3 floats per vertex, written in turn */
    uint32_t current;                          /* the buffer the last record wrote */
    roma_compute_pipeline skin;
};

static const VkBufferUsageFlags position_usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                                 VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                                 VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;

/* The skinning inputs of every vertex and the rest positions into both position buffers,
 * through one staging buffer and one submission. */
static roma_result upload(roma_animator *an, const roma_scene_view *v)
{
    const roma_scene_animation_data *a = &v->animation;
    VkDeviceSize vbytes = sizeof(roma_skin_vertex) * (VkDeviceSize)v->vertex_count;
    VkDeviceSize pbytes = 12ull * v->vertex_count;
    roma_buffer staging = {0};
    roma_result r = roma_buffer_create(an->ctx, vbytes + pbytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, ROMA_MEMORY_UPLOAD,
                                       &staging);
    if (r != ROMA_SUCCESS)
        return r;
    roma_skin_vertex *sv = staging.mapped;
    for (uint32_t i = 0; i < v->vertex_count; ++i) {
        roma_skin_vertex *o = &sv[i];
        memset(o, 0, sizeof *o);
        memcpy(o->rest, a->vertex_rest_local + 3 * (size_t)i, 3 * sizeof(float));
        uint32_t node = a->vertex_node[i];
        memcpy(&o->rest[3], &node, sizeof node);
        int32_t skin = a->vertex_skin ? a->vertex_skin[i] : -1;
        if (skin < 0) {
            o->joints[0] = 0xffffffffu;
            continue;
        }
        const float *w = a->vertex_weights + 4 * (size_t)i;
        float sum = w[0] + w[1] + w[2] + w[3];
        for (int k = 0; k < 4; ++k) {
            o->joints[k] = a->skins[skin].first_joint + a->vertex_joints[4 * (size_t)i + k];
            o->weights[k] = sum > 0.0f ? w[k] / sum : w[k];
        }
    }
    memcpy((char *)staging.mapped + vbytes, v->positions, pbytes);
    VkCommandBuffer cmd;
    r = roma_begin_one_shot(an->ctx, &cmd);
    if (r == ROMA_SUCCESS) {
        VkBufferCopy vc = {0, 0, vbytes}, pc = {vbytes, 0, pbytes};
        vkCmdCopyBuffer(cmd, staging.buffer, an->vertices.buffer, 1, &vc);
        vkCmdCopyBuffer(cmd, staging.buffer, an->positions[0].buffer, 1, &pc);
        vkCmdCopyBuffer(cmd, staging.buffer, an->positions[1].buffer, 1, &pc);
        r = roma_submit_one_shot(an->ctx, cmd);
    }
    roma_buffer_destroy(an->ctx, &staging);
    return r;
}

roma_result roma_animator_create(roma_context *ctx, const roma_scene *scene, const roma_animator_desc *desc_in,
                                 roma_animator **out)
{
    roma_animator_desc desc = desc_in ? *desc_in : (roma_animator_desc){0};
    const roma_logger *log = desc.logger.fn ? &desc.logger : (ctx ? &ctx->logger : NULL);
    if (!out)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_animator_create: out_animator is NULL");
    *out = NULL;
    if (!ctx || !scene)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT, "roma_animator_create: context and scene are required");
    if (desc.frames_in_flight == 0)
        desc.frames_in_flight = 2;
    if (desc.frames_in_flight > ROMA_MAX_FRAMES_IN_FLIGHT)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_animator_create: frames_in_flight %u is outside [1, %u]", desc.frames_in_flight,
                         ROMA_MAX_FRAMES_IN_FLIGHT);
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    if (!v.animation.node_count || !v.animation.vertex_node || !v.animation.vertex_rest_local)
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_animator_create: scene '%s' has no animation data (no nodes or per-vertex data)",
                         v.name ? v.name : "");
    roma_animator *an = calloc(1, sizeof *an);
    if (!an)
        return roma_fail(log, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_animator_create: out of host memory");
    an->ctx = ctx;
    an->logger = *log;
    an->frames_in_flight = desc.frames_in_flight;
    an->row_count = v.animation.node_count + v.animation.joint_total;
    roma_result r = roma_pose_eval_init(&an->eval, &v, log);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, sizeof(roma_skin_vertex) * (VkDeviceSize)v.vertex_count,
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               ROMA_MEMORY_DEVICE, &an->vertices);
    for (int i = 0; i < 2 && r == ROMA_SUCCESS; ++i)
        r = roma_buffer_create(ctx, 12ull * v.vertex_count, position_usage, ROMA_MEMORY_DEVICE, &an->positions[i]);
    if (r == ROMA_SUCCESS)
        r = roma_compute_pipeline_create(ctx, "skin.comp", 0, sizeof(roma_skin_push), &an->skin);
    if (r == ROMA_SUCCESS)
        r = upload(an, &v);
    if (r != ROMA_SUCCESS) {
        roma_animator_destroy(an);
        return r;
    }
    *out = an;
    return ROMA_SUCCESS;
}

void roma_animator_destroy(roma_animator *an)
{
    if (!an)
        return;
    roma_compute_pipeline_destroy(an->ctx, &an->skin);
    roma_buffer_destroy(an->ctx, &an->vertices);
    for (int i = 0; i < 2; ++i)
        roma_buffer_destroy(an->ctx, &an->positions[i]);
    for (uint32_t i = 0; i < ROMA_MAX_FRAMES_IN_FLIGHT; ++i)
        roma_buffer_destroy(an->ctx, &an->rows[i]);
    roma_pose_eval_free(&an->eval);
    free(an);
}

static roma_result check_pose(const roma_animator *an, const roma_animator_pose *pose, const char *fn)
{
    if (!pose)
        return roma_fail(&an->logger, ROMA_ERROR_INVALID_ARGUMENT, "%s: pose is NULL", fn);
    uint32_t clips = an->eval.anim.animation_count;
    if (pose->clip >= (clips ? clips : 1))
        return roma_fail(&an->logger, ROMA_ERROR_INVALID_ARGUMENT, "%s: clip %u, the scene has %u", fn, pose->clip,
                         clips);
    if (!isfinite(pose->time))
        return roma_fail(&an->logger, ROMA_ERROR_INVALID_ARGUMENT, "%s: time is not finite", fn);
    return ROMA_SUCCESS;
}

roma_result roma_animator_record(roma_animator *an, VkCommandBuffer cmd, uint32_t slot,
                                 const roma_animator_pose *pose, roma_animator_output *out)
{
    if (out)
        memset(out, 0, sizeof *out);
    if (!an || !cmd || !out)
        return roma_fail(an ? &an->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_animator_record: %s is NULL",
                         !an ? "animator" : !cmd ? "cmd" : "out");
    roma_result r = check_pose(an, pose, "roma_animator_record");
    if (r != ROMA_SUCCESS)
        return r;
    if (slot >= an->frames_in_flight)
        return roma_fail(&an->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_animator_record: slot %u of %u", slot,
                         an->frames_in_flight);
    roma_buffer *rows = &an->rows[slot];
    if (!rows->buffer) {
        r = roma_buffer_create(an->ctx, 48ull * an->row_count,
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                               ROMA_MEMORY_UPLOAD, rows);
        if (r != ROMA_SUCCESS)
            return r;
    }
    roma_pose_eval_pose(&an->eval, pose->clip, pose->time);
    roma_pose_eval_rows(&an->eval, rows->mapped);
    uint32_t next = an->current ^ 1u;
    /* Earlier readers of the buffer about to be written (two frames back) are done. */
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    roma_skin_push push = {.vertices = an->vertices.address,
                           .rows = rows->address,
                           .positions = an->positions[next].address,
                           .config = {an->eval.vertex_count, an->eval.anim.node_count, 0, 0}};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, an->skin.pipeline);
    vkCmdPushConstants(cmd, an->skin.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    roma_cmd_dispatch_linear(cmd, an->eval.vertex_count, ROMA_SKIN_WORKGROUP_SIZE);
    out->positions = an->positions[next].address;
    out->positions_buffer = an->positions[next].buffer;
    out->previous_positions = an->positions[an->current].address;
    out->previous_positions_buffer = an->positions[an->current].buffer;
    roma_pose_eval_bounds(&an->eval, &out->bounds);
    an->current = next;
    return ROMA_SUCCESS;
}

roma_result roma_animator_pose_cpu(roma_animator *an, const roma_animator_pose *pose, float *out_positions,
                                   roma_box *out_bounds)
{
    if (!an || !out_positions)
        return roma_fail(an ? &an->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_animator_pose_cpu: %s is NULL",
                         an ? "out_positions" : "animator");
    roma_result r = check_pose(an, pose, "roma_animator_pose_cpu");
    if (r != ROMA_SUCCESS)
        return r;
    roma_pose_eval_pose(&an->eval, pose->clip, pose->time);
    roma_pose_eval_skin(&an->eval, out_positions);
    if (out_bounds)
        roma_pose_eval_bounds(&an->eval, out_bounds);
    return ROMA_SUCCESS;
}

roma_result roma_animator_get_info(const roma_animator *an, roma_animator_info *out)
{
    if (out)
        memset(out, 0, sizeof *out);
    if (!an || !out)
        return roma_fail(an ? &an->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_animator_get_info: %s is NULL",
                         an ? "out_info" : "animator");
    out->vertex_count = an->eval.vertex_count;
    out->clip_count = an->eval.anim.animation_count;
    out->joint_count = an->eval.anim.joint_total;
    out->node_count = an->eval.anim.node_count;
    return ROMA_SUCCESS;
}

roma_result roma_animator_clip_duration(const roma_animator *an, uint32_t clip, float *out_seconds)
{
    if (out_seconds)
        *out_seconds = 0.0f;
    if (!an || !out_seconds)
        return roma_fail(an ? &an->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_animator_clip_duration: %s is NULL", an ? "out_seconds" : "animator");
    if (clip >= an->eval.anim.animation_count)
        return roma_fail(&an->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_animator_clip_duration: clip %u of %u", clip,
                         an->eval.anim.animation_count);
    *out_seconds = an->eval.clip_duration[clip];
    return ROMA_SUCCESS;
}

roma_result roma_animator_download_positions(roma_animator *an, float *out, uint32_t vertex_count)
{
    if (!an || !out)
        return roma_fail(an ? &an->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_animator_download_positions: %s is NULL", an ? "out_positions" : "animator");
    if (vertex_count != an->eval.vertex_count)
        return roma_fail(&an->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_animator_download_positions: %u vertices asked for, the scene has %u", vertex_count,
                         an->eval.vertex_count);
    const roma_buffer *src = &an->positions[an->current];
    roma_buffer staging;
    roma_result r = roma_buffer_create(an->ctx, src->size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, ROMA_MEMORY_READBACK,
                                       &staging);
    if (r != ROMA_SUCCESS)
        return r;
    VkCommandBuffer cmd;
    r = roma_begin_one_shot(an->ctx, &cmd);
    if (r == ROMA_SUCCESS) {
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferCopy copy = {0, 0, 12ull * vertex_count};
        vkCmdCopyBuffer(cmd, src->buffer, staging.buffer, 1, &copy);
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        r = roma_submit_one_shot(an->ctx, cmd);
    }
    if (r == ROMA_SUCCESS)
        r = roma_buffer_invalidate(an->ctx, &staging);
    if (r == ROMA_SUCCESS)
        memcpy(out, staging.mapped, 12ull * vertex_count);
    roma_buffer_destroy(an->ctx, &staging);
    return r;
}
