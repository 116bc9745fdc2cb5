/* libroma: validated, immutable triangle scenes.
 *
 * roma_scene_create checks every input before it allocates anything, so a
 * failure never leaves a partial scene behind; sizes are computed with
 * overflow checks because counts come straight from files. */
#include "roma/scene.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "rotate/directions.h"
#include "util/log.h"

struct roma_scene {
    char *name;
    float *positions, *normals;
    uint32_t vertex_count;
    uint32_t *indices;
    uint32_t triangle_count, degenerate_count;
    uint32_t *triangle_materials;
    roma_material *materials;
    uint32_t material_count;
    roma_light *lights;
    uint32_t light_count;
    uint32_t *emissive;
    uint32_t emissive_count;
    int has_camera;
    roma_camera camera;
    roma_camera *cameras; /* the viewpoints the source offers (a glTF file's cameras) */
    uint32_t camera_count;
    float bmin[3], bmax[3];
    roma_scene_animation_data anim; /* every array owned by the scene */
};

#define ROMA_PI 3.14159265358979323846

static const roma_material default_material = {{0.8f, 0.8f, 0.8f}, {0.0f, 0.0f, 0.0f}};

/* NULL on size overflow or allocation failure; never malloc(0). */
static void *alloc_array(size_t count, size_t elem)
{
    if (elem && count > SIZE_MAX / elem)
        return NULL;
    size_t bytes = count * elem;
    return malloc(bytes ? bytes : 1);
}

static void *dup_array(const void *src, size_t count, size_t elem)
{
    void *dst = alloc_array(count, elem);
    if (dst && count)
        memcpy(dst, src, count * elem);
    return dst;
}

static int all_finite(const float *v, size_t n)
{
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

static const char *scene_name(const roma_scene_desc *desc)
{
    return desc->name && *desc->name ? desc->name : "(unnamed scene)";
}

/* Twice the triangle area as a cross product. Slivers whose sine of the
 * corner angle is below ~1e-7 count as zero area: float ray tests cannot
 * hit them reliably, and they carry no light. */
static int triangle_cross(const float *p, const uint32_t *tri, double c[3])
{
    const float *a = p + 3 * (size_t)tri[0], *b = p + 3 * (size_t)tri[1], *d = p + 3 * (size_t)tri[2];
    double e1[3] = {(double)b[0] - a[0], (double)b[1] - a[1], (double)b[2] - a[2]};
    double e2[3] = {(double)d[0] - a[0], (double)d[1] - a[1], (double)d[2] - a[2]};
    c[0] = e1[1] * e2[2] - e1[2] * e2[1];
    c[1] = e1[2] * e2[0] - e1[0] * e2[2];
    c[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double c2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    double l1 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
    double l2 = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
    return c2 > 1e-14 * l1 * l2 && c2 > 0.0;
}

/* Area-weighted vertex normals into out (3 per vertex, zero when unused).
 * Where incident faces cancel out (two faces back to back) the first
 * incident face's normal is used instead, so no used vertex gets zero. */
static int compute_normals(const float *p, const uint32_t *idx, uint32_t tris, uint32_t nv,
                           float *out)
{
    double *acc = alloc_array((size_t)nv * 3, sizeof *acc);
    if (!acc)
        return 0;
    memset(acc, 0, (size_t)nv * 3 * sizeof *acc);
    double c[3];
    for (uint32_t t = 0; t < tris; ++t) {
        if (!triangle_cross(p, idx + 3 * (size_t)t, c))
            continue;
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 3; ++j)
                acc[3 * (size_t)idx[3 * (size_t)t + k] + j] += c[j];
    }
    int cancelled = 0;
    for (uint32_t v = 0; v < nv; ++v) {
        double *a = acc + 3 * (size_t)v;
        double len = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        for (int j = 0; j < 3; ++j)
            out[3 * (size_t)v + j] = len > 0.0 ? (float)(a[j] / len) : 0.0f;
        if (!(len > 0.0)) {
            a[0] = -1.0; /* marks "needs a face normal" for the second pass */
            cancelled = 1;
        } else {
            a[0] = 0.0;
        }
    }
    for (uint32_t t = 0; cancelled && t < tris; ++t) {
        if (!triangle_cross(p, idx + 3 * (size_t)t, c))
            continue;
        double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        for (int k = 0; k < 3; ++k) {
            size_t v = idx[3 * (size_t)t + k];
            if (acc[3 * v] < 0.0) {
                acc[3 * v] = 0.0;
                for (int j = 0; j < 3; ++j)
                    out[3 * v + j] = (float)(c[j] / len);
            }
        }
    }
    free(acc);
    return 1;
}

static roma_result validate_light(const roma_logger *log, const char *name, uint32_t i,
                                  const roma_light *l)
{
    if (l->type != ROMA_LIGHT_POINT && l->type != ROMA_LIGHT_SPOT && l->type != ROMA_LIGHT_DIRECTIONAL)
        return roma_fail(log, ROMA_ERROR_INVALID_SCENE, "scene '%s': light %u has unknown type %d",
                         name, i, (int)l->type);
    if (!all_finite(l->position, 3) || !all_finite(l->direction, 3) || !all_finite(l->color, 3) ||
        !isfinite(l->intensity) || !isfinite(l->range) || !isfinite(l->inner_cone_angle) ||
        !isfinite(l->outer_cone_angle))
        return roma_fail(log, ROMA_ERROR_INVALID_SCENE, "scene '%s': light %u has a NaN or infinite value",
                         name, i);
    if (l->color[0] < 0.0f || l->color[1] < 0.0f || l->color[2] < 0.0f || l->intensity < 0.0f ||
        l->range < 0.0f)
        return roma_fail(log, ROMA_ERROR_INVALID_SCENE,
                         "scene '%s': light %u has a negative colour, intensity or range", name, i);
    float unit[3];
    if (l->type != ROMA_LIGHT_POINT) {
        /* Normalised as rays are: by the largest component first, so that 1e20 or
         * 1e-25 long directions are fine (their squares overflowed or vanished). */
        if (!roma_unit_direction(l->direction, unit))
            return roma_fail(log, ROMA_ERROR_INVALID_SCENE, "scene '%s': light %u has a zero direction",
                             name, i);
    }
    if (l->type == ROMA_LIGHT_SPOT) {
        float outer = l->outer_cone_angle == 0.0f ? (float)(ROMA_PI / 4.0) : l->outer_cone_angle;
        if (l->inner_cone_angle < 0.0f || outer < 0.0f || l->inner_cone_angle > outer ||
            outer > (float)(ROMA_PI / 2.0) + 1e-6f)
            return roma_fail(log, ROMA_ERROR_INVALID_SCENE,
                             "scene '%s': spot light %u needs 0 <= inner (%g) <= outer (%g) <= pi/2",
                             name, i, (double)l->inner_cone_angle, (double)outer);
    }
    return ROMA_SUCCESS;
}

static int camera_finite(const roma_camera *c)
{
    return all_finite(c->eye, 3) && all_finite(c->target, 3) && all_finite(c->up, 3) && isfinite(c->fovy_deg);
}

/* Every check that can reject the desc, before anything is allocated. */
static roma_result validate_desc(const roma_scene_desc *desc, uint32_t *out_degenerate)
{
    const roma_logger *log = &desc->logger;
    const char *name = scene_name(desc);
    if ((!desc->positions && desc->vertex_count) || (!desc->indices && desc->triangle_count) ||
        (!desc->materials && desc->material_count) || (!desc->lights && desc->light_count) ||
        (!desc->cameras && desc->camera_count))
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "scene '%s': an array is NULL but its count is not zero", name);
    if (desc->triangle_count == 0)
        return roma_fail(log, ROMA_ERROR_EMPTY_SCENE, "scene '%s' has no triangles", name);
    if ((uint64_t)desc->triangle_count * 3 > SIZE_MAX / sizeof(float) / 3)
        return roma_fail(log, ROMA_ERROR_OUT_OF_HOST_MEMORY, "scene '%s' is too large", name);

    for (uint32_t v = 0; v < desc->vertex_count; ++v)
        if (!all_finite(desc->positions + 3 * (size_t)v, 3))
            return roma_fail(log, ROMA_ERROR_INVALID_SCENE,
                             "scene '%s': vertex %u has a NaN or infinite position", name, v);
    if (desc->normals)
        for (uint32_t v = 0; v < desc->vertex_count; ++v)
            if (!all_finite(desc->normals + 3 * (size_t)v, 3))
                return roma_fail(log, ROMA_ERROR_INVALID_SCENE,
                                 "scene '%s': vertex %u has a NaN or infinite normal", name, v);
    for (size_t i = 0; i < (size_t)desc->triangle_count * 3; ++i)
        if (desc->indices[i] >= desc->vertex_count)
            return roma_fail(log, ROMA_ERROR_INVALID_SCENE,
                             "scene '%s': triangle %zu uses vertex %u but there are only %u vertices",
                             name, i / 3, desc->indices[i], desc->vertex_count);

    uint32_t material_count = desc->material_count ? desc->material_count : 1;
    if (desc->triangle_materials)
        for (uint32_t t = 0; t < desc->triangle_count; ++t)
            if (desc->triangle_materials[t] >= material_count)
                return roma_fail(log, ROMA_ERROR_INVALID_SCENE,
                                 "scene '%s': triangle %u uses material %u but there are only %u",
                                 name, t, desc->triangle_materials[t], material_count);
    for (uint32_t m = 0; m < desc->material_count; ++m) {
        const roma_material *mat = desc->materials + m;
        if (!all_finite(mat->base_color, 3) || !all_finite(mat->emission, 3))
            return roma_fail(log, ROMA_ERROR_INVALID_SCENE,
                             "scene '%s': material %u has a NaN or infinite colour", name, m);
        for (int c = 0; c < 3; ++c)
            if (mat->base_color[c] < 0.0f || mat->base_color[c] > 1.0f || mat->emission[c] < 0.0f)
                return roma_fail(log, ROMA_ERROR_INVALID_SCENE,
                                 "scene '%s': material %u needs base colour in [0,1] and emission >= 0",
                                 name, m);
    }
    for (uint32_t i = 0; i < desc->light_count; ++i) {
        roma_result r = validate_light(log, name, i, desc->lights + i);
        if (r != ROMA_SUCCESS)
            return r;
    }
    if (desc->camera && !camera_finite(desc->camera))
        return roma_fail(log, ROMA_ERROR_INVALID_SCENE, "scene '%s': camera has a NaN or infinite value",
                         name);
    for (uint32_t i = 0; i < desc->camera_count; ++i)
        if (!camera_finite(&desc->cameras[i]))
            return roma_fail(log, ROMA_ERROR_INVALID_SCENE, "scene '%s': camera %u of cameras has a NaN or "
                             "infinite value", name, i);

    uint32_t degenerate = 0;
    double c[3];
    for (uint32_t t = 0; t < desc->triangle_count; ++t)
        degenerate += !triangle_cross(desc->positions, desc->indices + 3 * (size_t)t, c);
    if (degenerate == desc->triangle_count)
        return roma_fail(log, ROMA_ERROR_EMPTY_SCENE, "scene '%s': all %u triangles have zero area",
                         name, desc->triangle_count);
    *out_degenerate = degenerate;
    return ROMA_SUCCESS;
}

static void free_animation(roma_scene_animation_data *a)
{
    free((void *)a->nodes);
    free((void *)a->skins);
    free((void *)a->joint_nodes);
    free((void *)a->inverse_binds);
    free((void *)a->vertex_node);
    free((void *)a->vertex_skin);
    free((void *)a->vertex_joints);
    free((void *)a->vertex_weights);
    free((void *)a->vertex_rest_local);
    free((void *)a->channels);
    free((void *)a->times);
    free((void *)a->values);
    free((void *)a->animation_names); /* one block: the pointers, then the strings */
    memset(a, 0, sizeof *a);
}

void roma_scene_destroy(roma_scene *scene)
{
    if (!scene)
        return;
    free(scene->name);
    free(scene->positions);
    free(scene->normals);
    free(scene->indices);
    free(scene->triangle_materials);
    free(scene->materials);
    free(scene->lights);
    free(scene->cameras);
    free(scene->emissive);
    free_animation(&scene->anim);
    free(scene);
}

/* Copies the given normals, normalised; zero ones (and all of them when none
 * are given) come from the faces. Unused vertices get zero. */
static int build_normals(const roma_scene_desc *desc, const unsigned char *used, float *out)
{
    uint32_t nv = desc->vertex_count, bad = 0;
    if (desc->normals) {
        for (uint32_t v = 0; v < nv; ++v) {
            const float *n = desc->normals + 3 * (size_t)v;
            float *o = out + 3 * (size_t)v;
            double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
            if (!used[v]) {
                o[0] = o[1] = o[2] = 0.0f;
            } else if (len > 1e-20) {
                for (int j = 0; j < 3; ++j)
                    o[j] = (float)(n[j] / len);
            } else {
                o[0] = NAN; /* replaced below */
                ++bad;
            }
        }
        if (!bad)
            return 1;
    }
    float *computed = desc->normals ? alloc_array((size_t)nv * 3, sizeof(float)) : out;
    if (!computed || !compute_normals(desc->positions, desc->indices, desc->triangle_count, nv, computed)) {
        if (computed != out)
            free(computed);
        return 0;
    }
    if (computed != out) {
        for (uint32_t v = 0; v < nv; ++v)
            if (isnan(out[3 * (size_t)v]))
                memcpy(out + 3 * (size_t)v, computed + 3 * (size_t)v, 3 * sizeof(float));
        free(computed);
        roma_logf(&desc->logger, ROMA_LOG_WARNING,
                  "scene '%s': %u vertex normal(s) had zero length; using face normals there",
                  scene_name(desc), bad);
    }
    return 1;
}

roma_result roma_scene_create(const roma_scene_desc *desc, roma_scene **out_scene)
{
    if (out_scene)
        *out_scene = NULL;
    if (!desc || !out_scene)
        return roma_fail(desc ? &desc->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_scene_create: desc and out_scene must not be NULL");
    uint32_t degenerate = 0;
    roma_result r = validate_desc(desc, &degenerate);
    if (r != ROMA_SUCCESS)
        return r;

    const char *name = scene_name(desc);
    uint32_t nv = desc->vertex_count, nt = desc->triangle_count;
    roma_scene *s = calloc(1, sizeof *s);
    unsigned char *used = calloc(nv ? nv : 1, 1);
    if (!s || !used)
        goto oom;
    s->vertex_count = nv;
    s->triangle_count = nt;
    s->degenerate_count = degenerate;
    s->material_count = desc->material_count ? desc->material_count : 1;
    s->light_count = desc->light_count;
    s->name = dup_array(name, strlen(name) + 1, 1);
    s->positions = dup_array(desc->positions, (size_t)nv * 3, sizeof(float));
    s->normals = alloc_array((size_t)nv * 3, sizeof(float));
    s->indices = dup_array(desc->indices, (size_t)nt * 3, sizeof(uint32_t));
    s->triangle_materials = alloc_array(nt, sizeof(uint32_t));
    s->materials = dup_array(desc->material_count ? desc->materials : &default_material,
                             s->material_count, sizeof(roma_material));
    s->lights = dup_array(desc->lights, desc->light_count, sizeof(roma_light));
    s->camera_count = desc->camera_count;
    s->cameras = dup_array(desc->cameras, desc->camera_count, sizeof(roma_camera));
    if (!s->name || !s->positions || !s->normals || !s->indices || !s->triangle_materials ||
        !s->materials || !s->lights || !s->cameras)
        goto oom;

    for (size_t i = 0; i < (size_t)nt * 3; ++i)
        used[desc->indices[i]] = 1;
    if (!build_normals(desc, used, s->normals))
        goto oom;

    for (uint32_t t = 0; t < nt; ++t)
        s->triangle_materials[t] = desc->triangle_materials ? desc->triangle_materials[t] : 0;

    for (int j = 0; j < 3; ++j) {
        s->bmin[j] = INFINITY;
        s->bmax[j] = -INFINITY;
    }
    for (uint32_t v = 0; v < nv; ++v) {
        if (!used[v])
            continue;
        for (int j = 0; j < 3; ++j) {
            float x = s->positions[3 * (size_t)v + j];
            s->bmin[j] = x < s->bmin[j] ? x : s->bmin[j];
            s->bmax[j] = x > s->bmax[j] ? x : s->bmax[j];
        }
    }

    /* Emissive list: two passes so the array is exactly sized. */
    double c[3];
    for (int pass = 0; pass < 2; ++pass) {
        uint32_t n = 0;
        for (uint32_t t = 0; t < nt; ++t) {
            const float *e = s->materials[s->triangle_materials[t]].emission;
            if ((e[0] > 0.0f || e[1] > 0.0f || e[2] > 0.0f) &&
                triangle_cross(s->positions, s->indices + 3 * (size_t)t, c)) {
                if (pass)
                    s->emissive[n] = t;
                ++n;
            }
        }
        if (!pass) {
            s->emissive_count = n;
            s->emissive = alloc_array(n, sizeof(uint32_t));
            if (!s->emissive)
                goto oom;
        }
    }

    for (uint32_t i = 0; i < s->light_count; ++i) {
        roma_light *l = s->lights + i;
        if (l->type != ROMA_LIGHT_POINT) {
            float unit[3];
            roma_unit_direction(l->direction, unit);
            memcpy(l->direction, unit, sizeof unit);
        }
        if (l->type == ROMA_LIGHT_SPOT && l->outer_cone_angle == 0.0f)
            l->outer_cone_angle = (float)(ROMA_PI / 4.0);
    }
    if (desc->camera) {
        s->has_camera = 1;
        s->camera = *desc->camera;
    }

    free(used);
    roma_logf(&desc->logger, ROMA_LOG_DEBUG,
              "scene '%s': %u vertices, %u triangles (%u degenerate), %u emissive, %u lights", name,
              nv, nt, degenerate, s->emissive_count, s->light_count);
    *out_scene = s;
    return ROMA_SUCCESS;

oom:
    free(used);
    roma_scene_destroy(s);
    return roma_fail(&desc->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "scene '%s': out of host memory", name);
}

roma_result roma_scene_get_view(const roma_scene *scene, roma_scene_view *out_view)
{
    if (out_view)
        memset(out_view, 0, sizeof *out_view);
    if (!scene || !out_view)
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_scene_get_view: scene and out_view must not be NULL");
    roma_scene_view *v = out_view;
    v->name = scene->name;
    v->positions = scene->positions;
    v->normals = scene->normals;
    v->vertex_count = scene->vertex_count;
    v->indices = scene->indices;
    v->triangle_count = scene->triangle_count;
    v->degenerate_triangle_count = scene->degenerate_count;
    v->triangle_materials = scene->triangle_materials;
    v->materials = scene->materials;
    v->material_count = scene->material_count;
    v->lights = scene->lights;
    v->light_count = scene->light_count;
    v->emissive_triangles = scene->emissive;
    v->emissive_triangle_count = scene->emissive_count;
    v->has_camera = scene->has_camera;
    v->camera = scene->camera;
    v->cameras = scene->cameras;
    v->camera_count = scene->camera_count;
    memcpy(v->bounds_min, scene->bmin, sizeof v->bounds_min);
    memcpy(v->bounds_max, scene->bmax, sizeof v->bounds_max);
    v->animation = scene->anim;
    return ROMA_SUCCESS;
}

void roma_scene_default_camera(const roma_scene *scene, float aspect, roma_camera *out_camera)
{
    if (!out_camera)
        return;
    memset(out_camera, 0, sizeof *out_camera);
    if (!scene)
        return;
    if (scene->has_camera)
        *out_camera = scene->camera;
    else
        roma_camera_frame_bounds(scene->bmin, scene->bmax, aspect, out_camera);
}

/* --- animation data ------------------------------------------------------ */

/* Parent links must form a forest: walk up from each node, marking the
 * current path 1 and nodes proven to reach a root 2, so the check is linear. */
static int parents_acyclic(const roma_scene_node *nodes, uint32_t n, unsigned char *state)
{
    memset(state, 0, n);
    for (uint32_t i = 0; i < n; ++i) {
        for (uint32_t v = i; state[v] != 2;) {
            if (state[v] == 1)
                return 0;
            state[v] = 1;
            if (nodes[v].parent < 0)
                break;
            v = (uint32_t)nodes[v].parent;
        }
        for (uint32_t v = i; state[v] == 1; v = (uint32_t)nodes[v].parent) {
            state[v] = 2;
            if (nodes[v].parent < 0)
                break;
        }
    }
    return 1;
}

static roma_result validate_animation(const roma_scene *s, const roma_scene_animation_data *d,
                                      const roma_logger *log, size_t *out_times, size_t *out_values)
{
    const char *name = s->name;
    if ((!d->nodes && d->node_count) || (!d->skins && d->skin_count) ||
        (d->joint_total && (!d->joint_nodes || !d->inverse_binds)) ||
        (!d->channels && d->channel_count) || (d->channel_count && (!d->times || !d->values)))
        return roma_fail(log, ROMA_ERROR_INVALID_ARGUMENT,
                         "scene '%s': animation data has a NULL array with a non-zero count", name);
#define ANIM_FAIL(...) return roma_fail(log, ROMA_ERROR_INVALID_SCENE, __VA_ARGS__)
    for (uint32_t i = 0; i < d->node_count; ++i) {
        const roma_scene_node *n = d->nodes + i;
        if (n->parent < -1 || n->parent >= (int64_t)d->node_count || n->parent == (int32_t)i)
            ANIM_FAIL("scene '%s': animation node %u has invalid parent %d", name, i, n->parent);
        if (n->skin < -1 || n->skin >= (int64_t)d->skin_count)
            ANIM_FAIL("scene '%s': animation node %u has invalid skin %d", name, i, n->skin);
        if (!all_finite(n->translation, 3) || !all_finite(n->rotation, 4) || !all_finite(n->scale, 3) ||
            !all_finite(n->world, 16))
            ANIM_FAIL("scene '%s': animation node %u has a NaN or infinite transform", name, i);
    }
    if (d->node_count) {
        unsigned char *state = malloc(d->node_count);
        if (!state)
            return roma_fail(log, ROMA_ERROR_OUT_OF_HOST_MEMORY, "scene '%s': out of host memory", name);
        int ok = parents_acyclic(d->nodes, d->node_count, state);
        free(state);
        if (!ok)
            ANIM_FAIL("scene '%s': animation node parents form a cycle", name);
    }
    for (uint32_t i = 0; i < d->skin_count; ++i)
        if ((uint64_t)d->skins[i].first_joint + d->skins[i].joint_count > d->joint_total)
            ANIM_FAIL("scene '%s': skin %u joint range is past the %u joints", name, i, d->joint_total);
    for (uint32_t j = 0; j < d->joint_total; ++j)
        if (d->joint_nodes[j] >= d->node_count)
            ANIM_FAIL("scene '%s': joint %u refers to node %u of %u", name, j, d->joint_nodes[j],
                      d->node_count);
    if (d->joint_total && !all_finite(d->inverse_binds, (size_t)d->joint_total * 16))
        ANIM_FAIL("scene '%s': an inverse bind matrix has a NaN or infinite value", name);

    for (uint32_t v = 0; v < s->vertex_count; ++v) {
        if (d->vertex_node && d->vertex_node[v] >= d->node_count)
            ANIM_FAIL("scene '%s': vertex %u refers to node %u of %u", name, v, d->vertex_node[v],
                      d->node_count);
        int32_t skin = d->vertex_skin ? d->vertex_skin[v] : -1;
        if (skin < -1 || skin >= (int64_t)d->skin_count)
            ANIM_FAIL("scene '%s': vertex %u refers to skin %d of %u", name, v, skin, d->skin_count);
        /* A skinned vertex needs its joints and weights (the animator and roma_scene_pose read them). */
        if (skin >= 0 && (!d->vertex_joints || !d->vertex_weights))
            ANIM_FAIL("scene '%s': vertex %u is skinned but the vertex joints or weights are missing", name, v);
        if (skin >= 0 && d->vertex_joints)
            for (int k = 0; k < 4; ++k)
                if (d->vertex_joints[4 * (size_t)v + k] >= d->skins[skin].joint_count)
                    ANIM_FAIL("scene '%s': vertex %u uses joint %u of a %u-joint skin", name, v,
                              d->vertex_joints[4 * (size_t)v + k], d->skins[skin].joint_count);
        if (d->vertex_weights) {
            const float *w = d->vertex_weights + 4 * (size_t)v;
            if (!all_finite(w, 4) || w[0] < 0.0f || w[1] < 0.0f || w[2] < 0.0f || w[3] < 0.0f)
                ANIM_FAIL("scene '%s': vertex %u has a negative or non-finite skin weight", name, v);
        }
        if (d->vertex_rest_local && !all_finite(d->vertex_rest_local + 3 * (size_t)v, 3))
            ANIM_FAIL("scene '%s': vertex %u has a non-finite rest position", name, v);
    }

    uint64_t times = 0, values = 0;
    for (uint32_t i = 0; i < d->channel_count; ++i) {
        const roma_scene_anim_channel *c = d->channels + i;
        int want = c->path == ROMA_ANIM_ROTATION ? 4 : c->path == ROMA_ANIM_WEIGHTS ? 0 : 3;
        if (c->animation >= d->animation_count || c->node >= d->node_count)
            ANIM_FAIL("scene '%s': channel %u refers to animation %u / node %u out of range", name, i,
                      c->animation, c->node);
        if (c->path < ROMA_ANIM_TRANSLATION || c->path > ROMA_ANIM_WEIGHTS ||
            (int)c->interpolation < ROMA_ANIM_LINEAR || c->interpolation > ROMA_ANIM_CUBICSPLINE ||
            c->key_count == 0 || c->components == 0 || (want && c->components != (uint32_t)want))
            ANIM_FAIL("scene '%s': channel %u has an invalid path, interpolation, key or component count",
                      name, i);
        /* Cubic splines store in-tangent, value, out-tangent per key. */
        uint64_t keys = (uint64_t)c->key_count * (c->interpolation == ROMA_ANIM_CUBICSPLINE ? 3u : 1u);
        uint64_t t_end = (uint64_t)c->first_time + c->key_count;
        uint64_t v_end = (uint64_t)c->first_value + keys * c->components;
        times = t_end > times ? t_end : times;
        values = v_end > values ? v_end : values;
    }
    if (times > SIZE_MAX / sizeof(float) || values > SIZE_MAX / sizeof(float))
        return roma_fail(log, ROMA_ERROR_OUT_OF_HOST_MEMORY, "scene '%s': animation data too large", name);
    if (d->channel_count && (!all_finite(d->times, (size_t)times) || !all_finite(d->values, (size_t)values)))
        ANIM_FAIL("scene '%s': animation keys have NaN or infinite values", name);
#undef ANIM_FAIL
    *out_times = (size_t)times;
    *out_values = (size_t)values;
    return ROMA_SUCCESS;
}

roma_result roma_scene_set_animation_data(roma_scene *scene, const roma_scene_animation_data *data,
                                          const roma_logger *logger)
{
    if (!scene || !data)
        return roma_fail(logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_scene_set_animation_data: scene and data must not be NULL");
    size_t times = 0, values = 0;
    roma_result r = validate_animation(scene, data, logger, &times, &values);
    if (r != ROMA_SUCCESS)
        return r;

    /* Per-vertex arrays are optional one by one; copy what is there. */
    size_t nv = scene->vertex_count;
    roma_scene_animation_data a = *data;
#define DUP_OR_NULL(field, count, elem)                                                       \
    a.field = data->field ? dup_array(data->field, (count), (elem)) : NULL;                   \
    int ok_##field = !data->field || a.field;
    DUP_OR_NULL(nodes, data->node_count, sizeof(roma_scene_node))
    DUP_OR_NULL(skins, data->skin_count, sizeof(roma_scene_skin))
    DUP_OR_NULL(joint_nodes, data->joint_total, sizeof(uint32_t))
    DUP_OR_NULL(inverse_binds, (size_t)data->joint_total * 16, sizeof(float))
    DUP_OR_NULL(vertex_node, nv, sizeof(uint32_t))
    DUP_OR_NULL(vertex_skin, nv, sizeof(int32_t))
    DUP_OR_NULL(vertex_joints, nv * 4, sizeof(uint16_t))
    DUP_OR_NULL(vertex_weights, nv * 4, sizeof(float))
    DUP_OR_NULL(vertex_rest_local, nv * 3, sizeof(float))
    DUP_OR_NULL(channels, data->channel_count, sizeof(roma_scene_anim_channel))
    DUP_OR_NULL(times, times, sizeof(float))
    DUP_OR_NULL(values, values, sizeof(float))
#undef DUP_OR_NULL
    /* Names: one block holding the pointers and then the strings. */
    a.animation_names = NULL;
    int ok_names = 1;
    if (data->animation_names && data->animation_count) {
        size_t bytes = sizeof(char *) * data->animation_count;
        for (uint32_t i = 0; i < data->animation_count; ++i)
            bytes += strlen(data->animation_names[i] ? data->animation_names[i] : "") + 1;
        char **block = malloc(bytes);
        ok_names = block != NULL;
        if (block) {
            char *text = (char *)(block + data->animation_count);
            for (uint32_t i = 0; i < data->animation_count; ++i) {
                const char *n = data->animation_names[i] ? data->animation_names[i] : "";
                size_t len = strlen(n) + 1;
                memcpy(text, n, len);
                block[i] = text;
                text += len;
            }
            a.animation_names = (const char *const *)block;
        }
    }
    if (!(ok_names && ok_nodes && ok_skins && ok_joint_nodes && ok_inverse_binds && ok_vertex_node && ok_vertex_skin &&
          ok_vertex_joints && ok_vertex_weights && ok_vertex_rest_local && ok_channels && ok_times &&
          ok_values)) {
        free_animation(&a);
        return roma_fail(logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "scene '%s': out of host memory",
                         scene->name);
    }
    free_animation(&scene->anim);
    scene->anim = a;
    return ROMA_SUCCESS;
}
