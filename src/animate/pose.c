/* Keyframes -> node transforms -> joint matrices, on the host (glTF 2.0 animation
 * semantics: LINEAR with slerp for rotations, STEP, CUBICSPLINE with tangents scaled by
 * the key interval). Matrices are column-major 4x4, m[4 * column + row]. */
#include "animate/pose.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/log.h"

static void mat_identity(float *m)
{
    memset(m, 0, 16 * sizeof(float));
    m[0] = m[5] = m[10] = m[15] = 1.0f;
}

static void mat_mul(const float *a, const float *b, float *out)
{
    float r[16];
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) {
            float s = 0.0f;
            for (int k = 0; k < 4; ++k)
                s += a[4 * k + row] * b[4 * c + k];
            r[4 * c + row] = s;
        }
    memcpy(out, r, sizeof r);
}

/* General 4x4 inverse (cofactors, double); identity when singular. */
static void mat_inverse(const float *m, float *out)
{
    double a[16], inv[16];
    for (int i = 0; i < 16; ++i)
        a[i] = m[i];
    inv[0] = a[5] * a[10] * a[15] - a[5] * a[11] * a[14] - a[9] * a[6] * a[15] + a[9] * a[7] * a[14] +
             a[13] * a[6] * a[11] - a[13] * a[7] * a[10];
    inv[4] = -a[4] * a[10] * a[15] + a[4] * a[11] * a[14] + a[8] * a[6] * a[15] - a[8] * a[7] * a[14] -
             a[12] * a[6] * a[11] + a[12] * a[7] * a[10];
    inv[8] = a[4] * a[9] * a[15] - a[4] * a[11] * a[13] - a[8] * a[5] * a[15] + a[8] * a[7] * a[13] +
             a[12] * a[5] * a[11] - a[12] * a[7] * a[9];
    inv[12] = -a[4] * a[9] * a[14] + a[4] * a[10] * a[13] + a[8] * a[5] * a[14] - a[8] * a[6] * a[13] -
              a[12] * a[5] * a[10] + a[12] * a[6] * a[9];
    inv[1] = -a[1] * a[10] * a[15] + a[1] * a[11] * a[14] + a[9] * a[2] * a[15] - a[9] * a[3] * a[14] -
             a[13] * a[2] * a[11] + a[13] * a[3] * a[10];
    inv[5] = a[0] * a[10] * a[15] - a[0] * a[11] * a[14] - a[8] * a[2] * a[15] + a[8] * a[3] * a[14] +
             a[12] * a[2] * a[11] - a[12] * a[3] * a[10];
    inv[9] = -a[0] * a[9] * a[15] + a[0] * a[11] * a[13] + a[8] * a[1] * a[15] - a[8] * a[3] * a[13] -
             a[12] * a[1] * a[11] + a[12] * a[3] * a[9];
    inv[13] = a[0] * a[9] * a[14] - a[0] * a[10] * a[13] - a[8] * a[1] * a[14] + a[8] * a[2] * a[13] +
              a[12] * a[1] * a[10] - a[12] * a[2] * a[9];
    inv[2] = a[1] * a[6] * a[15] - a[1] * a[7] * a[14] - a[5] * a[2] * a[15] + a[5] * a[3] * a[14] +
             a[13] * a[2] * a[7] - a[13] * a[3] * a[6];
    inv[6] = -a[0] * a[6] * a[15] + a[0] * a[7] * a[14] + a[4] * a[2] * a[15] - a[4] * a[3] * a[14] -
             a[12] * a[2] * a[7] + a[12] * a[3] * a[6];
    inv[10] = a[0] * a[5] * a[15] - a[0] * a[7] * a[13] - a[4] * a[1] * a[15] + a[4] * a[3] * a[13] +
              a[12] * a[1] * a[7] - a[12] * a[3] * a[5];
    inv[14] = -a[0] * a[5] * a[14] + a[0] * a[6] * a[13] + a[4] * a[1] * a[14] - a[4] * a[2] * a[13] -
              a[12] * a[1] * a[6] + a[12] * a[2] * a[5];
    inv[3] = -a[1] * a[6] * a[11] + a[1] * a[7] * a[10] + a[5] * a[2] * a[11] - a[5] * a[3] * a[10] -
             a[9] * a[2] * a[7] + a[9] * a[3] * a[6];
    inv[7] = a[0] * a[6] * a[11] - a[0] * a[7] * a[10] - a[4] * a[2] * a[11] + a[4] * a[3] * a[10] +
             a[8] * a[2] * a[7] - a[8] * a[3] * a[6];
    inv[11] = -a[0] * a[5] * a[11] + a[0] * a[7] * a[9] + a[4] * a[1] * a[11] - a[4] * a[3] * a[9] -
              a[8] * a[1] * a[7] + a[8] * a[3] * a[5];
    inv[15] = a[0] * a[5] * a[10] - a[0] * a[6] * a[9] - a[4] * a[1] * a[10] + a[4] * a[2] * a[9] +
              a[8] * a[1] * a[6] - a[8] * a[2] * a[5];
    double det = a[0] * inv[0] + a[1] * inv[4] + a[2] * inv[8] + a[3] * inv[12];
    if (det == 0.0 || !isfinite(det)) {
        mat_identity(out);
        return;
    }
    for (int i = 0; i < 16; ++i)
        out[i] = (float)(inv[i] / det);
}

static void mat_trs(const float t[3], const float q_in[4], const float s[3], float *m)
{
    float n = sqrtf(q_in[0] * q_in[0] + q_in[1] * q_in[1] + q_in[2] * q_in[2] + q_in[3] * q_in[3]);
    float x = 0, y = 0, z = 0, w = 1;
    if (n > 0.0f)
        x = q_in[0] / n, y = q_in[1] / n, z = q_in[2] / n, w = q_in[3] / n;
    float r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w),
                  2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                  2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)};
    for (int c = 0; c < 3; ++c) {
        for (int row = 0; row < 3; ++row)
            m[4 * c + row] = r[3 * c + row] * s[c];
        m[4 * c + 3] = 0.0f;
    }
    m[12] = t[0], m[13] = t[1], m[14] = t[2], m[15] = 1.0f;
}

static void transform_point(const float *m, const float p[3], float out[3])
{
    for (int row = 0; row < 3; ++row)
        out[row] = m[row] * p[0] + m[4 + row] * p[1] + m[8 + row] * p[2] + m[12 + row];
}

/* Parents before children: a node's depth, then a counting sort by depth. */
static int make_order(const roma_scene_node *nodes, uint32_t n, uint32_t *order)
{
    uint32_t *depth = calloc(n ? n : 1, sizeof *depth), max_depth = 0;
    if (!depth)
        return 0;
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t d = 0;
        for (int32_t p = nodes[i].parent; p >= 0 && d <= n; p = nodes[p].parent)
            ++d; /* the scene checked that parents form a forest */
        depth[i] = d;
        max_depth = d > max_depth ? d : max_depth;
    }
    uint32_t at = 0;
    for (uint32_t d = 0; d <= max_depth; ++d)
        for (uint32_t i = 0; i < n; ++i)
            if (depth[i] == d)
                order[at++] = i;
    free(depth);
    return 1;
}

static void box_empty(float *b)
{
    b[0] = b[1] = b[2] = INFINITY;
    b[3] = b[4] = b[5] = -INFINITY;
}

static void box_add(float *b, const float p[3])
{
    for (int a = 0; a < 3; ++a) {
        b[a] = fminf(b[a], p[a]);
        b[3 + a] = fmaxf(b[3 + a], p[a]);
    }
}

roma_result roma_pose_eval_init(roma_pose_eval *e, const roma_scene_view *view, const roma_logger *log)
{
    memset(e, 0, sizeof *e);
    e->anim = view->animation;
    e->vertex_count = view->vertex_count;
    const roma_scene_animation_data *a = &e->anim;
    uint32_t n = a->node_count, clips = a->animation_count;
    e->order = malloc(sizeof(uint32_t) * (n ? n : 1));
    e->local_rest = malloc(sizeof(float) * 16 * (n ? n : 1));
    e->local = malloc(sizeof(float) * 16 * (n ? n : 1));
    e->world = malloc(sizeof(float) * 16 * (n ? n : 1));
    e->joints = malloc(sizeof(float) * 16 * (a->joint_total ? a->joint_total : 1));
    e->clip_duration = calloc(clips ? clips : 1, sizeof(float));
    e->joint_box = malloc(sizeof(float) * 6 * (a->joint_total ? a->joint_total : 1));
    e->node_box = malloc(sizeof(float) * 6 * (n ? n : 1));
    if (!e->order || !e->local_rest || !e->local || !e->world || !e->joints || !e->clip_duration ||
        !e->joint_box || !e->node_box || !make_order(a->nodes, n, e->order)) {
        roma_pose_eval_free(e);
        return roma_fail(log, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_animator_create: out of host memory");
    }
    /* Rest locals from the rest worlds: nodes given by a matrix keep it exactly. */
    for (uint32_t i = 0; i < n; ++i) {
        const roma_scene_node *node = &a->nodes[i];
        if (node->parent < 0) {
            memcpy(e->local_rest + 16 * i, node->world, sizeof node->world);
        } else {
            float inv[16];
            mat_inverse(a->nodes[node->parent].world, inv);
            mat_mul(inv, node->world, e->local_rest + 16 * i);
        }
    }
    for (uint32_t c = 0; c < a->channel_count; ++c) {
        const roma_scene_anim_channel *ch = &a->channels[c];
        float last = a->times[ch->first_time + ch->key_count - 1];
        if (ch->animation < clips && last > e->clip_duration[ch->animation])
            e->clip_duration[ch->animation] = last;
    }
    /* Which rest-local vertices each joint and each node moves. */
    for (uint32_t j = 0; j < a->joint_total; ++j)
        box_empty(e->joint_box + 6 * j);
    for (uint32_t i = 0; i < n; ++i)
        box_empty(e->node_box + 6 * i);
    for (uint32_t v = 0; v < e->vertex_count; ++v) {
        const float *p = a->vertex_rest_local + 3 * (size_t)v;
        int32_t skin = a->vertex_skin ? a->vertex_skin[v] : -1;
        if (skin < 0) {
            box_add(e->node_box + 6 * (size_t)a->vertex_node[v], p);
            continue;
        }
        int weighted = 0;
        for (int k = 0; k < 4; ++k)
            if (a->vertex_weights[4 * (size_t)v + k] > 0.0f) {
                box_add(e->joint_box + 6 * ((size_t)a->skins[skin].first_joint + a->vertex_joints[4 * (size_t)v + k]),
                        p);
                weighted = 1;
            }
        e->origin_vertices |= !weighted;
    }
    roma_pose_eval_pose(e, 0, 0.0f);
    return ROMA_SUCCESS;
}

void roma_pose_eval_free(roma_pose_eval *e)
{
    free(e->order);
    free(e->local_rest);
    free(e->local);
    free(e->world);
    free(e->joints);
    free(e->clip_duration);
    free(e->joint_box);
    free(e->node_box);
    memset(e, 0, sizeof *e);
}

/* The channel's value at time t into out (components floats). */
static void sample(const roma_scene_animation_data *a, const roma_scene_anim_channel *ch, float t, float *out)
{
    const float *times = a->times + ch->first_time, *values = a->values + ch->first_value;
    uint32_t n = ch->key_count, c = ch->components;
    int cubic = ch->interpolation == ROMA_ANIM_CUBICSPLINE;
    /* Element k's value: CUBICSPLINE stores (in-tangent, value, out-tangent) per key. */
#define VALUE(k) (values + (cubic ? (3 * (size_t)(k) + 1) * c : (size_t)(k) * c))
    if (n == 1 || t <= times[0]) {
        memcpy(out, VALUE(0), sizeof(float) * c);
        return;
    }
    if (t >= times[n - 1]) {
        memcpy(out, VALUE(n - 1), sizeof(float) * c);
        return;
    }
    uint32_t lo = 0, hi = n - 1; /* times[lo] <= t < times[hi] */
    while (hi - lo > 1) {
        uint32_t mid = (lo + hi) / 2;
        if (times[mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    float dt = times[hi] - times[lo], u = dt > 0.0f ? (t - times[lo]) / dt : 0.0f;
    const float *v0 = VALUE(lo), *v1 = VALUE(hi);
    if (ch->interpolation == ROMA_ANIM_STEP) {
        memcpy(out, v0, sizeof(float) * c);
    } else if (cubic) {
        const float *out_tangent = values + (3 * (size_t)lo + 2) * c, *in_tangent = values + (3 * (size_t)hi) * c;
        float u2 = u * u, u3 = u2 * u;
        float h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
        for (uint32_t i = 0; i < c; ++i)
            out[i] = h00 * v0[i] + h10 * dt * out_tangent[i] + h01 * v1[i] + h11 * dt * in_tangent[i];
    } else if (ch->path == ROMA_ANIM_ROTATION && c == 4) {
        /* slerp along the shorter arc */
        float d = v0[0] * v1[0] + v0[1] * v1[1] + v0[2] * v1[2] + v0[3] * v1[3], sign = d < 0.0f ? -1.0f : 1.0f;
        d = fabsf(d);
        float w0 = 1.0f - u, w1 = u;
        if (d < 0.9995f) {
            float theta = acosf(d), s = sinf(theta);
            w0 = sinf((1.0f - u) * theta) / s;
            w1 = sinf(u * theta) / s;
        }
        for (int i = 0; i < 4; ++i)
            out[i] = w0 * v0[i] + sign * w1 * v1[i];
    } else {
        for (uint32_t i = 0; i < c; ++i)
            out[i] = v0[i] + u * (v1[i] - v0[i]);
    }
#undef VALUE
}

void roma_pose_eval_pose(roma_pose_eval *e, uint32_t clip, float time)
{
    const roma_scene_animation_data *a = &e->anim;
    uint32_t n = a->node_count;
    memcpy(e->local, e->local_rest, sizeof(float) * 16 * n);
    float duration = clip < a->animation_count ? e->clip_duration[clip] : 0.0f;
    float t = time > 0.0f && duration > 0.0f ? fmodf(time, duration) : 0.0f;
    /* Animated nodes: rest TRS with the clip's channels over it. Channels of one node are
     * gathered by walking all channels per animated node (clips have few channels). */
    for (uint32_t c = 0; c < a->channel_count; ++c) {
        const roma_scene_anim_channel *ch = &a->channels[c];
        if (ch->animation != clip || ch->path == ROMA_ANIM_WEIGHTS)
            continue;
        uint32_t node = ch->node;
        int first = 1; /* the first channel of this node in the list builds its TRS */
        for (uint32_t k = 0; k < c && first; ++k)
            first = !(a->channels[k].animation == clip && a->channels[k].node == node &&
                      a->channels[k].path != ROMA_ANIM_WEIGHTS);
        if (!first)
            continue;
        const roma_scene_node *nd = &a->nodes[node];
        float tr[3], rot[4], sc[3];
        memcpy(tr, nd->translation, sizeof tr);
        memcpy(rot, nd->rotation, sizeof rot);
        memcpy(sc, nd->scale, sizeof sc);
        for (uint32_t k = c; k < a->channel_count; ++k) {
            const roma_scene_anim_channel *o = &a->channels[k];
            if (o->animation != clip || o->node != node)
                continue;
            if (o->path == ROMA_ANIM_TRANSLATION)
                sample(a, o, t, tr);
            else if (o->path == ROMA_ANIM_ROTATION)
                sample(a, o, t, rot);
            else if (o->path == ROMA_ANIM_SCALE)
                sample(a, o, t, sc);
        }
        mat_trs(tr, rot, sc, e->local + 16 * (size_t)node);
    }
    for (uint32_t k = 0; k < n; ++k) {
        uint32_t i = e->order[k];
        int32_t p = a->nodes[i].parent;
        if (p < 0)
            memcpy(e->world + 16 * (size_t)i, e->local + 16 * (size_t)i, sizeof(float) * 16);
        else
            mat_mul(e->world + 16 * (size_t)p, e->local + 16 * (size_t)i, e->world + 16 * (size_t)i);
    }
    for (uint32_t j = 0; j < a->joint_total; ++j)
        mat_mul(e->world + 16 * (size_t)a->joint_nodes[j], a->inverse_binds + 16 * (size_t)j, e->joints + 16 * (size_t)j);
}

/* The box b (rest-local) under m, grown into out. */
static void box_transform_add(const float *m, const float *b, float *out)
{
    if (b[0] > b[3])
        return;
    for (int corner = 0; corner < 8; ++corner) {
        float p[3] = {corner & 1 ? b[3] : b[0], corner & 2 ? b[4] : b[1], corner & 4 ? b[5] : b[2]}, q[3];
        transform_point(m, p, q);
        box_add(out, q);
    }
}

void roma_pose_eval_bounds(const roma_pose_eval *e, roma_box *out)
{
    float b[6];
    box_empty(b);
    for (uint32_t j = 0; j < e->anim.joint_total; ++j)
        box_transform_add(e->joints + 16 * (size_t)j, e->joint_box + 6 * (size_t)j, b);
    for (uint32_t i = 0; i < e->anim.node_count; ++i)
        box_transform_add(e->world + 16 * (size_t)i, e->node_box + 6 * (size_t)i, b);
    if (e->origin_vertices) { /* skinned with all-zero weights: at the origin, CPU and GPU alike */
        const float origin[3] = {0.0f, 0.0f, 0.0f};
        box_add(b, origin);
    }
    for (int a = 0; a < 3; ++a)
        out->min[a] = b[a], out->max[a] = b[3 + a];
}

void roma_pose_eval_rows(const roma_pose_eval *e, float *out)
{
    uint32_t n = e->anim.node_count;
    for (uint32_t i = 0; i < n + e->anim.joint_total; ++i) {
        const float *m = i < n ? e->world + 16 * (size_t)i : e->joints + 16 * (size_t)(i - n);
        for (int row = 0; row < 3; ++row)
            for (int c = 0; c < 4; ++c)
                out[12 * (size_t)i + 4 * row + c] = m[4 * c + row];
    }
}

void roma_pose_eval_skin(const roma_pose_eval *e, float *out)
{
    const roma_scene_animation_data *a = &e->anim;
    for (uint32_t v = 0; v < e->vertex_count; ++v) {
        const float *p = a->vertex_rest_local + 3 * (size_t)v;
        int32_t skin = a->vertex_skin ? a->vertex_skin[v] : -1;
        float *o = out + 3 * (size_t)v;
        if (skin < 0) {
            transform_point(e->world + 16 * (size_t)a->vertex_node[v], p, o);
            continue;
        }
        const float *w = a->vertex_weights + 4 * (size_t)v;
        float sum = w[0] + w[1] + w[2] + w[3], acc[3] = {0, 0, 0};
        for (int k = 0; k < 4; ++k) {
            float q[3];
            transform_point(e->joints + 16 * ((size_t)a->skins[skin].first_joint + a->vertex_joints[4 * (size_t)v + k]),
                            p, q);
            for (int c = 0; c < 3; ++c)
                acc[c] += w[k] * q[c];
        }
        for (int c = 0; c < 3; ++c)
            o[c] = sum > 0.0f ? acc[c] / sum : acc[c];
    }
}
