/* Skinning against poses written out by hand: a glTF made here (one animated joint, one
 * static joint, eight vertices, half of them blended between the two) whose four clips
 * each exercise one kind of key: translation LINEAR, rotation LINEAR (slerp), scale STEP
 * and translation CUBICSPLINE. At times between and on keys, the animator's GPU skinning
 * and its host skinning (roma_animator_pose_cpu) must give the positions the glTF 2.0
 * formulas give, evaluated here without libroma's pose code. test_animation checks the
 * GPU against the host on real files; this one checks both against the specification.
 * Each clip's expected positions are also computed with the wrong interpolation (STEP for
 * LINEAR, linear for STEP and CUBICSPLINE, normalised linear blending of quaternions for
 * slerp): the animator must be far from those, so the comparison can tell one kind of key
 * from another. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "roma/animation.h"
#include "roma/gltf.h"

#define VERTICES 8
#define TRIANGLES 4
/* Largest |difference| between the animator and the closed form, in scene units (the
 * vertices lie within 4 units of the origin): float rounding of a few products per
 * coordinate; 2.6e-7 measured on lavapipe (the slerp clip). */
#define BOUND 4e-7f
/* The wrong interpolation must be at least this far at some vertex of the clip. */
#define WRONG_APART 1e-3f

static const float rest[VERTICES][3] = {
    {0.5f, 0.2f, 0.3f}, {1.5f, 0.1f, 0.4f}, {1.7f, 1.2f, 0.1f}, {0.4f, 1.3f, 0.2f},  /* joint A alone */
    {2.0f, 0.0f, 1.0f}, {3.0f, 0.2f, 1.1f}, {3.1f, 1.0f, 0.9f}, {2.2f, 1.1f, 1.2f}}; /* A 0.25, B 0.75 */
static const float weight_a[VERTICES] = {1, 1, 1, 1, 0.25f, 0.25f, 0.25f, 0.25f};
/* Joint A rests at (1, 0, 0) with the inverse bind matrix translate(-1, 0, 0): the rest
 * pose is the mesh as written. Joint B is static at the origin (identity). */
static const float rest_t[3] = {1, 0, 0};

/* Clip 0: translation LINEAR; clip 1: rotation LINEAR (slerp); clip 2: scale STEP; clip 3:
 * translation CUBICSPLINE (in-tangent, value, out-tangent per key). */
static const float times3[3] = {0, 1, 2}, times2[2] = {0, 1}, times_cubic[2] = {0, 2};
static const float linear_t[3][3] = {{1, 0, 0}, {3, 0, 0}, {3, 2, 0}};
static const float slerp_q[2][4] = {{0, 0, 0, 1}, {0, 0.70710678f, 0, 0.70710678f}}; /* 0 and 90 deg about y */
static const float step_s[3][3] = {{1, 1, 1}, {2, 2, 2}, {0.5f, 1, 3}};
static const float cubic_t[2][3][3] = {{{0, 0, 0}, {1, 0, 0}, {2, 1, 0}}, {{0, -1, 1}, {3, 1, 0}, {0, 0, 0}}};

/* The binary chunk: each array at its offset (all multiples of 4). */
typedef struct bin_layout {
    size_t positions, joints, weights, indices, inverse_binds, t3, t2, tc, lin, slerp, step, cubic, size;
} bin_layout;

static bin_layout layout(void)
{
    bin_layout l;
    size_t at = 0;
    l.positions = at, at += sizeof rest;
    l.joints = at, at += 4 * VERTICES;
    l.weights = at, at += 16 * VERTICES;
    l.indices = at, at += 2 * 3 * TRIANGLES;
    l.inverse_binds = at, at += 2 * 64;
    l.t3 = at, at += sizeof times3;
    l.t2 = at, at += sizeof times2;
    l.tc = at, at += sizeof times_cubic;
    l.lin = at, at += sizeof linear_t;
    l.slerp = at, at += sizeof slerp_q;
    l.step = at, at += sizeof step_s;
    l.cubic = at, at += sizeof cubic_t;
    l.size = at;
    return l;
}

static void fill_bin(const bin_layout *l, uint8_t *b)
{
    memcpy(b + l->positions, rest, sizeof rest);
    for (int v = 0; v < VERTICES; ++v) {
        uint8_t j[4] = {0, 1, 0, 0};
        float w[4] = {weight_a[v], 1.0f - weight_a[v], 0, 0};
        memcpy(b + l->joints + 4 * v, j, 4);
        memcpy(b + l->weights + 16 * v, w, 16);
    }
    const uint16_t idx[3 * TRIANGLES] = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
    memcpy(b + l->indices, idx, sizeof idx);
    float ibm[2][16] = {{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1, 0, 0, 1}, /* column-major */
                        {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}};
    memcpy(b + l->inverse_binds, ibm, sizeof ibm);
    memcpy(b + l->t3, times3, sizeof times3);
    memcpy(b + l->t2, times2, sizeof times2);
    memcpy(b + l->tc, times_cubic, sizeof times_cubic);
    memcpy(b + l->lin, linear_t, sizeof linear_t);
    memcpy(b + l->slerp, slerp_q, sizeof slerp_q);
    memcpy(b + l->step, step_s, sizeof step_s);
    memcpy(b + l->cubic, cubic_t, sizeof cubic_t);
}

/* The glTF file (GLB: JSON chunk, then the binary chunk) into a new buffer. */
static uint8_t *make_glb(size_t *out_size)
{
    bin_layout l = layout();
    char json[4096];
    int n = snprintf(json, sizeof json,
        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0,1,2]}],"
        "\"nodes\":[{\"mesh\":0,\"skin\":0},{\"name\":\"A\",\"translation\":[1,0,0]},{\"name\":\"B\"}],"
        "\"skins\":[{\"joints\":[1,2],\"inverseBindMatrices\":4}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"JOINTS_0\":1,\"WEIGHTS_0\":2},"
        "\"indices\":3}]}],"
        "\"buffers\":[{\"byteLength\":%zu}],"
        "\"bufferViews\":["
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},"
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},"
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},"
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},"
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},"
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu},{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}],"
        "\"accessors\":["
        "{\"bufferView\":0,\"componentType\":5126,\"count\":8,\"type\":\"VEC3\",\"min\":[0.4,0,0.1],\"max\":[3.1,1.3,1.2]},"
        "{\"bufferView\":1,\"componentType\":5121,\"count\":8,\"type\":\"VEC4\"},"
        "{\"bufferView\":2,\"componentType\":5126,\"count\":8,\"type\":\"VEC4\"},"
        "{\"bufferView\":3,\"componentType\":5123,\"count\":12,\"type\":\"SCALAR\"},"
        "{\"bufferView\":4,\"componentType\":5126,\"count\":2,\"type\":\"MAT4\"},"
        "{\"bufferView\":5,\"componentType\":5126,\"count\":3,\"type\":\"SCALAR\",\"min\":[0],\"max\":[2]},"
        "{\"bufferView\":6,\"componentType\":5126,\"count\":2,\"type\":\"SCALAR\",\"min\":[0],\"max\":[1]},"
        "{\"bufferView\":7,\"componentType\":5126,\"count\":2,\"type\":\"SCALAR\",\"min\":[0],\"max\":[2]},"
        "{\"bufferView\":8,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
        "{\"bufferView\":9,\"componentType\":5126,\"count\":2,\"type\":\"VEC4\"},"
        "{\"bufferView\":10,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
        "{\"bufferView\":11,\"componentType\":5126,\"count\":6,\"type\":\"VEC3\"}],"
        "\"animations\":["
        "{\"name\":\"linear\",\"samplers\":[{\"input\":5,\"output\":8,\"interpolation\":\"LINEAR\"}],"
        "\"channels\":[{\"sampler\":0,\"target\":{\"node\":1,\"path\":\"translation\"}}]},"
        "{\"name\":\"slerp\",\"samplers\":[{\"input\":6,\"output\":9,\"interpolation\":\"LINEAR\"}],"
        "\"channels\":[{\"sampler\":0,\"target\":{\"node\":1,\"path\":\"rotation\"}}]},"
        "{\"name\":\"step\",\"samplers\":[{\"input\":5,\"output\":10,\"interpolation\":\"STEP\"}],"
        "\"channels\":[{\"sampler\":0,\"target\":{\"node\":1,\"path\":\"scale\"}}]},"
        "{\"name\":\"cubic\",\"samplers\":[{\"input\":7,\"output\":11,\"interpolation\":\"CUBICSPLINE\"}],"
        "\"channels\":[{\"sampler\":0,\"target\":{\"node\":1,\"path\":\"translation\"}}]}]}",
        l.size, l.positions, sizeof rest, l.joints, (size_t)4 * VERTICES, l.weights, (size_t)16 * VERTICES,
        l.indices, (size_t)6 * TRIANGLES, l.inverse_binds, (size_t)128, l.t3, sizeof times3, l.t2, sizeof times2,
        l.tc, sizeof times_cubic, l.lin, sizeof linear_t, l.slerp, sizeof slerp_q, l.step, sizeof step_s, l.cubic,
        sizeof cubic_t);
    if (n <= 0 || (size_t)n >= sizeof json)
        return NULL;
    size_t json_len = ((size_t)n + 3) & ~(size_t)3, bin_len = (l.size + 3) & ~(size_t)3;
    size_t total = 12 + 8 + json_len + 8 + bin_len;
    uint8_t *glb = calloc(1, total);
    if (!glb)
        return NULL;
    uint32_t header[3] = {0x46546C67u, 2u, (uint32_t)total}; /* "glTF", version 2 */
    uint32_t json_head[2] = {(uint32_t)json_len, 0x4E4F534Au}, bin_head[2] = {(uint32_t)bin_len, 0x004E4942u};
    memcpy(glb, header, 12);
    memcpy(glb + 12, json_head, 8);
    memset(glb + 20, ' ', json_len); /* JSON padding is spaces */
    memcpy(glb + 20, json, (size_t)n);
    memcpy(glb + 20 + json_len, bin_head, 8);
    fill_bin(&l, glb + 28 + json_len);
    *out_size = total;
    return glb;
}

/* Joint A's local transform at time t of clip `clip`, as translation, rotation (angle
 * about y, or a quaternion for the wrong blend) and scale; `wrong` takes the wrong
 * interpolation. Only the animated property departs from the rest pose. */
typedef struct joint_pose {
    float t[3], q[4], s[3];
} joint_pose;

static void hermite(float u, float dt, const float p0[3], const float m0[3], const float p1[3], const float m1[3],
                    float *out)
{
    double u2 = (double)u * u, u3 = u2 * u;
    double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
    for (int i = 0; i < 3; ++i)
        out[i] = (float)(h00 * p0[i] + h10 * dt * m0[i] + h01 * p1[i] + h11 * dt * m1[i]);
}

static joint_pose pose_at(int clip, float time, int wrong)
{
    joint_pose p = {{rest_t[0], rest_t[1], rest_t[2]}, {0, 0, 0, 1}, {1, 1, 1}};
    if (clip == 0 || (clip == 2 && wrong)) { /* linear between the keys of times3 */
        const float (*v)[3] = clip == 0 ? linear_t : step_s;
        int k = time < 1.0f ? 0 : 1;
        float u = time - times3[k];
        float *dst = clip == 0 ? p.t : p.s;
        for (int i = 0; i < 3; ++i)
            dst[i] = clip == 0 && wrong ? v[k][i] : (float)((1.0 - u) * v[k][i] + (double)u * v[k + 1][i]);
    } else if (clip == 1) {
        double angle = 0.5 * 3.14159265358979323846 * time; /* slerp from 0 to 90 degrees is the angle's lerp */
        if (wrong) { /* normalised linear blend of the two quaternions */
            double q[4], len = 0.0;
            for (int i = 0; i < 4; ++i) {
                q[i] = (1.0 - time) * slerp_q[0][i] + (double)time * slerp_q[1][i];
                len += q[i] * q[i];
            }
            angle = 2.0 * atan2(q[1] / sqrt(len), q[3] / sqrt(len));
        }
        p.q[1] = (float)sin(angle / 2), p.q[3] = (float)cos(angle / 2);
    } else if (clip == 2) { /* STEP: the last key at or before the time */
        int k = time >= 2.0f ? 2 : time >= 1.0f ? 1 : 0;
        memcpy(p.s, step_s[k], sizeof p.s);
    } else if (wrong) { /* clip 3 with linear keys */
        float u = time / 2.0f;
        for (int i = 0; i < 3; ++i)
            p.t[i] = (1.0f - u) * cubic_t[0][1][i] + u * cubic_t[1][1][i];
    } else {
        hermite(time / 2.0f, 2.0f, cubic_t[0][1], cubic_t[0][2], cubic_t[1][1], cubic_t[1][0], p.t);
    }
    return p;
}

/* sum_k w_k * world(joint_k) * inverse_bind_k * v: joint A is T * R * S after translate(-1, 0, 0),
 * joint B the identity. */
static void skin_vertex(const joint_pose *p, int v, double out[3])
{
    double x[3] = {rest[v][0] - 1.0, rest[v][1], rest[v][2]};
    for (int i = 0; i < 3; ++i)
        x[i] *= p->s[i];
    /* rotation by the unit quaternion q (about y only here, written in general) */
    double qx = p->q[0], qy = p->q[1], qz = p->q[2], qw = p->q[3];
    double r[3] = {(1 - 2 * (qy * qy + qz * qz)) * x[0] + 2 * (qx * qy - qz * qw) * x[1] + 2 * (qx * qz + qy * qw) * x[2],
                   2 * (qx * qy + qz * qw) * x[0] + (1 - 2 * (qx * qx + qz * qz)) * x[1] + 2 * (qy * qz - qx * qw) * x[2],
                   2 * (qx * qz - qy * qw) * x[0] + 2 * (qy * qz + qx * qw) * x[1] + (1 - 2 * (qx * qx + qy * qy)) * x[2]};
    for (int i = 0; i < 3; ++i)
        out[i] = weight_a[v] * (r[i] + p->t[i]) + (1.0 - weight_a[v]) * rest[v][i];
}

/* Largest |animator - closed form| over the vertices. */
static float apart(const float *positions, const joint_pose *p)
{
    double worst = 0.0;
    for (int v = 0; v < VERTICES; ++v) {
        double want[3];
        skin_vertex(p, v, want);
        for (int i = 0; i < 3; ++i)
            worst = fmax(worst, fabs(positions[3 * v + i] - want[i]));
    }
    return (float)worst;
}

/* Records the skinning of `pose`, submits and waits, then reads the positions back. */
static int skin_on_gpu(roma_context *ctx, VkCommandPool pool, roma_animator *an, const roma_animator_pose *pose,
                       uint32_t frame, float *positions)
{
    VkDevice dev = roma_context_device(ctx);
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    VkCommandBuffer cmd;
    if (vkAllocateCommandBuffers(dev, &ai, &cmd) != VK_SUCCESS)
        return 0;
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                   .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    vkBeginCommandBuffer(cmd, &bi);
    roma_animator_output out;
    int ok = roma_animator_record(an, cmd, frame % 2, pose, &out) == ROMA_SUCCESS;
    vkEndCommandBuffer(cmd);
    VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &cmd};
    ok = ok && vkQueueSubmit(roma_context_queue(ctx), 1, &si, VK_NULL_HANDLE) == VK_SUCCESS;
    vkQueueWaitIdle(roma_context_queue(ctx));
    vkFreeCommandBuffers(dev, pool, 1, &cmd);
    return ok && roma_animator_download_positions(an, positions, VERTICES) == ROMA_SUCCESS;
}

int main(void)
{
    roma_context *ctx = roma_test_context();
    if (!ctx)
        return roma_test_finish("test_animation_closed_form");
    size_t size = 0;
    uint8_t *glb = make_glb(&size);
    CHECK(glb != NULL);
    roma_scene *scene = NULL;
    if (glb)
        CHECK_RESULT(roma_scene_load_gltf_memory(glb, size, NULL, NULL, &scene), ROMA_SUCCESS);
    free(glb);
    roma_animator *an = NULL;
    if (scene)
        CHECK_RESULT(roma_animator_create(ctx, scene, NULL, &an), ROMA_SUCCESS);
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .queueFamilyIndex = roma_context_queue_family(ctx)};
    CHECK(vkCreateCommandPool(roma_context_device(ctx), &pi, NULL, &pool) == VK_SUCCESS);
    if (an) {
        roma_animator_info info;
        CHECK_RESULT(roma_animator_get_info(an, &info), ROMA_SUCCESS);
        CHECK(info.vertex_count == VERTICES && info.clip_count == 4 && info.joint_count == 2);
        static const char *names[4] = {"translation LINEAR", "rotation LINEAR (slerp)", "scale STEP",
                                       "translation CUBICSPLINE"};
        static const float durations[4] = {2, 1, 2, 2};
        /* Times between keys and on inner keys; clips loop at their duration. */
        static const float times[4][4] = {
            {0.25f, 1.0f, 1.5f, 1.75f}, {0.3f, 0.5f, 0.75f, 0.9f}, {0.5f, 1.0f, 1.5f, 1.99f}, {0.5f, 1.0f, 1.3f, 1.7f}};
        uint32_t frame = 0;
        float worst_gpu = 0.0f, worst_cpu = 0.0f;
        for (uint32_t c = 0; c < 4 && info.clip_count == 4; ++c) {
            float duration = 0.0f;
            CHECK_RESULT(roma_animator_clip_duration(an, c, &duration), ROMA_SUCCESS);
            CHECK(duration == durations[c]);
            float clip_gpu = 0.0f, clip_cpu = 0.0f, wrong = 0.0f;
            for (int k = 0; k < 4; ++k) {
                roma_animator_pose pose = {c, times[c][k]};
                float gpu[3 * VERTICES], cpu[3 * VERTICES];
                CHECK(skin_on_gpu(ctx, pool, an, &pose, frame++, gpu));
                CHECK_RESULT(roma_animator_pose_cpu(an, &pose, cpu, NULL), ROMA_SUCCESS);
                joint_pose right = pose_at((int)c, pose.time, 0), off = pose_at((int)c, pose.time, 1);
                clip_gpu = fmaxf(clip_gpu, apart(gpu, &right));
                clip_cpu = fmaxf(clip_cpu, apart(cpu, &right));
                wrong = fmaxf(wrong, apart(gpu, &off));
            }
            printf("clip %u (%s): GPU %.3g, host %.3g from the closed form; %.3g from the wrong interpolation\n", c,
                   names[c], (double)clip_gpu, (double)clip_cpu, (double)wrong);
            CHECK(wrong >= WRONG_APART);
            worst_gpu = fmaxf(worst_gpu, clip_gpu);
            worst_cpu = fmaxf(worst_cpu, clip_cpu);
        }
        printf("largest difference from the closed form: GPU %.3g, host %.3g (bound %.3g)\n", (double)worst_gpu,
               (double)worst_cpu, (double)BOUND);
        CHECK(worst_gpu <= BOUND && worst_cpu <= BOUND);
    }
    if (pool)
        vkDestroyCommandPool(roma_context_device(ctx), pool, NULL);
    roma_animator_destroy(an);
    roma_scene_destroy(scene);
    roma_test_context_finish(ctx);
    return roma_test_finish("test_animation_closed_form");
}
