/* Meshes and instances of a roma_map: host bookkeeping in the API calls, GPU work in
 * the next build (mesh uploads, the new geometry layout, the per-instance transforms). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "map/map_internal.h"
#include "util/log.h"
#include "voxelize/bom_voxelize.h"

static const float identity[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};

int roma_map_instance_is_dynamic(const roma_map_instance *in)
{
    return (in->flags & ROMA_INSTANCE_DYNAMIC) != 0;
}

void roma_map_instance_box(const roma_map *map, const roma_map_instance *in, float bmin[3], float bmax[3])
{
    const roma_map_mesh *m = &map->meshes[in->mesh];
    for (int c = 0; c < 8; ++c) {
        float p[3] = {c & 1 ? m->bmax[0] : m->bmin[0], c & 2 ? m->bmax[1] : m->bmin[1],
                      c & 4 ? m->bmax[2] : m->bmin[2]};
        for (int a = 0; a < 3; ++a) {
            const float *row = in->transform + 4 * a;
            float w = row[0] * p[0] + row[1] * p[1] + row[2] * p[2] + row[3];
            bmin[a] = fminf(bmin[a], w);
            bmax[a] = fmaxf(bmax[a], w);
        }
    }
}

static int grow(void **items, uint32_t *capacity, uint32_t count, size_t size)
{
    if (count < *capacity)
        return 1;
    uint32_t cap = *capacity ? 2 * *capacity : 8;
    void *p = realloc(*items, size * cap);
    if (!p)
        return 0;
    *items = p;
    *capacity = cap;
    return 1;
}

/* Room for n more retired entries, made before anything is changed, so that the retires
 * that follow cannot fail half-way. */
static roma_result reserve_retired(roma_map *map, uint32_t n)
{
    while (map->retired_capacity < map->retired_count + n)
        if (!grow((void **)&map->retired, &map->retired_capacity, map->retired_capacity, sizeof *map->retired))
            return roma_fail(&map->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_map: out of host memory");
    return ROMA_SUCCESS;
}

static roma_result retire(roma_map *map, roma_buffer *buffer, struct roma_bom_voxelizer *voxelizer)
{
    if (!grow((void **)&map->retired, &map->retired_capacity, map->retired_count, sizeof *map->retired))
        return roma_fail(&map->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_map: out of host memory");
    roma_map_retired *r = &map->retired[map->retired_count++];
    memset(r, 0, sizeof *r);
    if (buffer) {
        r->buffer = *buffer;
        memset(buffer, 0, sizeof *buffer);
    }
    r->voxelizer = voxelizer;
    /* Used up to the build being recorded now (map->builds); each later build of another
     * slot comes after the caller waited for that slot's previous command buffer. */
    r->release_at = map->builds + map->frames_in_flight;
    return ROMA_SUCCESS;
}

void roma_map_instances_release(roma_map *map, int all)
{
    uint32_t kept = 0;
    for (uint32_t i = 0; i < map->retired_count; ++i) {
        roma_map_retired *r = &map->retired[i];
        if (all || r->release_at <= map->builds) {
            roma_buffer_destroy(map->ctx, &r->buffer);
            roma_bom_voxelizer_destroy(r->voxelizer);
        } else {
            map->retired[kept++] = *r;
        }
    }
    map->retired_count = kept;
    if (all) {
        for (uint32_t m = 0; m < map->mesh_count; ++m) {
            roma_buffer_destroy(map->ctx, &map->meshes[m].local);
            roma_buffer_destroy(map->ctx, &map->meshes[m].staging);
            free(map->meshes[m].indices);
        }
        free(map->meshes);
        free(map->instances);
        free(map->retired);
    }
}

roma_result roma_map_add_mesh(roma_map *map, const roma_scene *scene, uint32_t *out_mesh)
{
    if (out_mesh)
        *out_mesh = UINT32_MAX;
    if (!map || !scene || !out_mesh)
        return roma_fail(map ? &map->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_add_mesh: %s is NULL",
                         !map ? "map" : !scene ? "mesh" : "out_mesh");
    if (!grow((void **)&map->meshes, &map->mesh_capacity, map->mesh_count, sizeof *map->meshes))
        return roma_fail(&map->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_map_add_mesh: out of host memory");
    roma_scene_view v;
    roma_scene_get_view(scene, &v);
    roma_map_mesh mesh = {.live = 1, .vertex_count = v.vertex_count, .triangle_count = v.triangle_count};
    memcpy(mesh.bmin, v.bounds_min, sizeof mesh.bmin);
    memcpy(mesh.bmax, v.bounds_max, sizeof mesh.bmax);
    mesh.indices = malloc(12ull * v.triangle_count);
    if (!mesh.indices)
        return roma_fail(&map->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_map_add_mesh: out of host memory");
    memcpy(mesh.indices, v.indices, 12ull * v.triangle_count);
    roma_result r = roma_buffer_create(map->ctx, 16ull * v.vertex_count,
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                           VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                       ROMA_MEMORY_DEVICE, &mesh.local);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(map->ctx, 16ull * v.vertex_count, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, ROMA_MEMORY_UPLOAD,
                               &mesh.staging);
    if (r != ROMA_SUCCESS) {
        roma_buffer_destroy(map->ctx, &mesh.local);
        free(mesh.indices);
        return r;
    }
    float *dst = mesh.staging.mapped;
    for (uint32_t i = 0; i < v.vertex_count; ++i) {
        memcpy(dst + 4 * (size_t)i, v.positions + 3 * (size_t)i, 3 * sizeof(float));
        dst[4 * (size_t)i + 3] = 1.0f;
    }
    map->meshes[map->mesh_count] = mesh;
    *out_mesh = map->mesh_count++;
    return ROMA_SUCCESS;
}

roma_result roma_map_remove_mesh(roma_map *map, uint32_t id)
{
    if (!map)
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_remove_mesh: map is NULL");
    if (id >= map->mesh_count || !map->meshes[id].live)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_remove_mesh: no mesh %u", id);
    roma_map_mesh *m = &map->meshes[id];
    if (m->users)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_map_remove_mesh: mesh %u still has %u instances", id, m->users);
    roma_result r = reserve_retired(map, 2);
    if (r != ROMA_SUCCESS)
        return r;
    retire(map, &m->local, NULL); /* cannot fail now */
    if (m->staging.buffer)
        retire(map, &m->staging, NULL);
    free(m->indices);
    m->indices = NULL;
    m->live = 0;
    return ROMA_SUCCESS;
}

static roma_result check_transform(const roma_map *map, const float *t, const char *fn)
{
    for (int i = 0; i < 12; ++i)
        if (!isfinite(t[i]))
            return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT, "%s: the transform is not finite", fn);
    return ROMA_SUCCESS;
}

roma_result roma_map_add_instance(roma_map *map, const roma_instance_desc *desc, uint32_t *out_instance)
{
    if (out_instance)
        *out_instance = UINT32_MAX;
    if (!map || !desc || !out_instance)
        return roma_fail(map ? &map->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_add_instance: %s is NULL",
                         !map ? "map" : !desc ? "desc" : "out_instance");
    if (desc->mesh >= map->mesh_count || !map->meshes[desc->mesh].live)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_add_instance: no mesh %u", desc->mesh);
    if (desc->flags & ~ROMA_INSTANCE_DYNAMIC)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_add_instance: unknown flags 0x%x",
                         desc->flags);
    static const float zero[12];
    const float *t = memcmp(desc->transform, zero, sizeof zero) == 0 ? identity : desc->transform;
    roma_result r = check_transform(map, t, "roma_map_add_instance");
    if (r != ROMA_SUCCESS)
        return r;
    const roma_map_mesh *m = &map->meshes[desc->mesh];
    if (map->live_vertices + m->vertex_count > UINT32_MAX / 16 ||
        map->live_triangles + m->triangle_count > UINT32_MAX / 12)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_add_instance: too much geometry");
    if (!grow((void **)&map->instances, &map->instance_capacity, map->instance_count, sizeof *map->instances))
        return roma_fail(&map->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_map_add_instance: out of host memory");
    roma_map_instance *in = &map->instances[map->instance_count];
    memset(in, 0, sizeof *in);
    in->live = 1;
    in->mesh = desc->mesh;
    in->flags = desc->flags;
    memcpy(in->transform, t, sizeof in->transform);
    map->meshes[desc->mesh].users++;
    map->live_vertices += m->vertex_count;
    map->live_triangles += m->triangle_count;
    map->layout_dirty = 1;
    *out_instance = map->instance_count++;
    return ROMA_SUCCESS;
}

roma_result roma_map_remove_instance(roma_map *map, uint32_t id)
{
    if (!map)
        return roma_fail(NULL, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_remove_instance: map is NULL");
    if (id >= map->instance_count || !map->instances[id].live)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_remove_instance: no instance %u", id);
    map->instances[id].live = 0;
    map->meshes[map->instances[id].mesh].users--;
    map->live_vertices -= map->meshes[map->instances[id].mesh].vertex_count;
    map->live_triangles -= map->meshes[map->instances[id].mesh].triangle_count;
    map->layout_dirty = 1;
    return ROMA_SUCCESS;
}

roma_result roma_map_set_instance_transform(roma_map *map, uint32_t id, const float transform[12])
{
    if (!map || !transform)
        return roma_fail(map ? &map->logger : NULL, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_map_set_instance_transform: %s is NULL", map ? "transform" : "map");
    if (id >= map->instance_count || !map->instances[id].live)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_map_set_instance_transform: no instance %u",
                         id);
    if (!(map->instances[id].flags & ROMA_INSTANCE_DYNAMIC))
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_map_set_instance_transform: instance %u is static (add it with ROMA_INSTANCE_DYNAMIC)",
                         id);
    static const float zero[12];
    const float *t = memcmp(transform, zero, sizeof zero) == 0 ? identity : transform; /* as when added */
    roma_result r = check_transform(map, t, "roma_map_set_instance_transform");
    if (r == ROMA_SUCCESS) {
        memcpy(map->instances[id].transform, t, sizeof map->instances[id].transform);
        map->transforms_dirty = 1;
    }
    return r;
}

roma_result roma_map_instances_prepare(roma_map *map, roma_map_layout *out)
{
    memset(out, 0, sizeof *out);
    /* Room for what the recording retires: new meshes' staging, and the old layout. */
    uint32_t retiring = 3;
    for (uint32_t m = 0; m < map->mesh_count; ++m)
        retiring += map->meshes[m].live && map->meshes[m].staging.buffer;
    roma_result rr = reserve_retired(map, retiring);
    if (rr != ROMA_SUCCESS)
        return rr;
    if (!map->layout_dirty)
        return ROMA_SUCCESS;
    uint64_t vertices = map->vertex_count, triangles = map->triangle_count;
    for (uint32_t i = 0; i < map->instance_count; ++i)
        if (map->instances[i].live) {
            vertices += map->meshes[map->instances[i].mesh].vertex_count;
            triangles += map->meshes[map->instances[i].mesh].triangle_count;
        }
    if (vertices > UINT32_MAX / 16 || triangles > UINT32_MAX / 12) /* add_instance keeps below this */
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT, "map: too much geometry in its instances");
    const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    roma_result r = roma_buffer_create(map->ctx, 16ull * vertices, storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                       VK_BUFFER_USAGE_TRANSFER_SRC_BIT, ROMA_MEMORY_DEVICE, &out->positions);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(map->ctx, 12ull * triangles, storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               ROMA_MEMORY_DEVICE_MAPPED, &out->indices);
    if (r == ROMA_SUCCESS && !out->indices.mapped) /* copied by the build that takes the layout */
        r = roma_buffer_create(map->ctx, 12ull * triangles, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, ROMA_MEMORY_UPLOAD,
                               &out->indices_staging);
    if (r == ROMA_SUCCESS && map->voxelizer)
        r = roma_bom_voxelizer_create(map->ctx, map->res, out->positions.buffer, out->indices.buffer, map->bom.buffer,
                                      map->bom.size, &out->voxelizer);
    if (r != ROMA_SUCCESS) {
        roma_buffer_destroy(map->ctx, &out->positions);
        roma_buffer_destroy(map->ctx, &out->indices);
        roma_buffer_destroy(map->ctx, &out->indices_staging);
        memset(out, 0, sizeof *out);
        return r;
    }
    /* Scene first, then each live static instance, then each dynamic one (so that a build can
     * voxelize the static triangles and the dynamic ones apart): vertices and triangles
     * renumbered. */
    uint32_t *idx = out->indices.mapped ? out->indices.mapped : out->indices_staging.mapped;
    memcpy(idx, map->indices_host, 12ull * map->triangle_count);
    uint32_t v_at = map->vertex_count;
    size_t t_at = 3ull * map->triangle_count;
    out->static_triangles = map->triangle_count;
    for (int dynamic = 0; dynamic < 2; ++dynamic)
        for (uint32_t i = 0; i < map->instance_count; ++i) {
            if (!map->instances[i].live || roma_map_instance_is_dynamic(&map->instances[i]) != dynamic)
                continue;
            const roma_map_mesh *m = &map->meshes[map->instances[i].mesh];
            for (size_t k = 0; k < 3ull * m->triangle_count; ++k)
                idx[t_at + k] = m->indices[k] + v_at;
            t_at += 3ull * m->triangle_count;
            v_at += m->vertex_count;
            out->static_triangles += dynamic ? 0 : m->triangle_count;
        }
    out->changed = 1;
    out->total_vertices = (uint32_t)vertices;
    out->total_triangles = (uint32_t)triangles;
    return ROMA_SUCCESS;
}

void roma_map_instances_record_copies(roma_map *map, VkCommandBuffer cmd, roma_map_layout *layout)
{
    for (uint32_t m = 0; m < map->mesh_count; ++m) {
        roma_map_mesh *mesh = &map->meshes[m];
        if (!mesh->live || !mesh->staging.buffer)
            continue;
        VkBufferCopy copy = {0, 0, 16ull * mesh->vertex_count};
        vkCmdCopyBuffer(cmd, mesh->staging.buffer, mesh->local.buffer, 1, &copy);
        if (retire(map, &mesh->staging, NULL) != ROMA_SUCCESS) /* kept until the map goes */
            break;
    }
    if (!layout->changed)
        return;
    /* The scene's positions carry over; the instances are placed again by the transforms. */
    VkBufferCopy copy = {0, 0, 16ull * map->vertex_count};
    vkCmdCopyBuffer(cmd, map->positions.buffer, layout->positions.buffer, 1, &copy);
    if (layout->indices_staging.buffer) {
        const VkBufferCopy indices = {0, 0, layout->indices_staging.size};
        vkCmdCopyBuffer(cmd, layout->indices_staging.buffer, layout->indices.buffer, 1, &indices);
        retire(map, &layout->indices_staging, NULL); /* kept until the builds that read it are done */
    }
    retire(map, &map->positions, NULL);
    retire(map, &map->indices, NULL);
    if (map->voxelizer)
        retire(map, NULL, map->voxelizer);
    map->positions = layout->positions;
    map->indices = layout->indices;
    if (layout->voxelizer)
        map->voxelizer = layout->voxelizer;
    map->total_vertices = layout->total_vertices;
    map->total_triangles = layout->total_triangles;
    map->static_triangles = layout->static_triangles;
    uint32_t v_at = map->vertex_count; /* the order of roma_map_instances_prepare */
    for (int dynamic = 0; dynamic < 2; ++dynamic)
        for (uint32_t i = 0; i < map->instance_count; ++i)
            if (map->instances[i].live && roma_map_instance_is_dynamic(&map->instances[i]) == dynamic) {
                map->instances[i].first_vertex = v_at;
                v_at += map->meshes[map->instances[i].mesh].vertex_count;
            }
    map->layout_dirty = 0;
}

void roma_map_instances_record_transforms(roma_map *map, VkCommandBuffer cmd, int all)
{
    int bound = 0;
    for (uint32_t i = 0; i < map->instance_count; ++i) {
        const roma_map_instance *in = &map->instances[i];
        if (!in->live || !(all || (in->flags & ROMA_INSTANCE_DYNAMIC)))
            continue;
        const roma_map_mesh *m = &map->meshes[in->mesh];
        if (!bound) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, map->transform_instances.pipeline);
            bound = 1;
        }
        roma_instance_push push = {.src = m->local.address,
                                   .dst = map->positions.address + 16ull * in->first_vertex,
                                   .config = {m->vertex_count, 0, 0, 0}};
        memcpy(push.row0, in->transform, sizeof push.row0);
        memcpy(push.row1, in->transform + 4, sizeof push.row1);
        memcpy(push.row2, in->transform + 8, sizeof push.row2);
        vkCmdPushConstants(cmd, map->transform_instances.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
        roma_cmd_dispatch_linear(cmd, m->vertex_count, ROMA_GATHER_WORKGROUP_SIZE);
    }
}

int roma_map_instances_bounds(const roma_map *map, int dynamic_only, float bmin[3], float bmax[3])
{
    int found = 0;
    for (uint32_t i = 0; i < map->instance_count; ++i) {
        const roma_map_instance *in = &map->instances[i];
        if (!in->live || (dynamic_only && !roma_map_instance_is_dynamic(in)))
            continue;
        found = 1;
        roma_map_instance_box(map, in, bmin, bmax);
    }
    return found;
}

int roma_map_instances_dynamic(const roma_map *map)
{
    for (uint32_t i = 0; i < map->instance_count; ++i)
        if (map->instances[i].live && roma_map_instance_is_dynamic(&map->instances[i]))
            return 1;
    return 0;
}

roma_result roma_map_mesh_positions_check(const roma_map *map, const roma_map_frame_desc *f, const char *fn)
{
    if (f->mesh_position_count && !f->mesh_positions)
        return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT, "%s: mesh_positions is NULL with a count of %u", fn,
                         f->mesh_position_count);
    for (uint32_t e = 0; e < f->mesh_position_count; ++e) {
        const roma_mesh_positions *p = &f->mesh_positions[e];
        if (p->mesh >= map->mesh_count || !map->meshes[p->mesh].live)
            return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT, "%s: mesh_positions[%u]: no mesh %u", fn, e,
                             p->mesh);
        for (uint32_t o = 0; o < e; ++o)
            if (f->mesh_positions[o].mesh == p->mesh)
                return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                                 "%s: mesh_positions[%u] and [%u] both give mesh %u", fn, o, e, p->mesh);
        /* A static instance is voxelized into the static part once: it would not follow. */
        for (uint32_t i = 0; i < map->instance_count; ++i)
            if (map->instances[i].live && map->instances[i].mesh == p->mesh &&
                !roma_map_instance_is_dynamic(&map->instances[i]))
                return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                                 "%s: mesh_positions[%u]: mesh %u has a static instance (%u); give its instances "
                                 "ROMA_INSTANCE_DYNAMIC", fn, e, p->mesh, i);
        const uint32_t stride = p->gpu_position_stride ? p->gpu_position_stride : 12u;
        if (stride < 12u || stride % 4u)
            return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                             "%s: mesh_positions[%u]: gpu_position_stride %u must be a multiple of 4 and at least 12",
                             fn, e, stride);
        if (!p->gpu_positions || p->gpu_positions % 4u)
            return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                             "%s: mesh_positions[%u]: gpu_positions is %s", fn, e, p->gpu_positions ? "not 4-byte aligned" : "0");
        /* The gather addresses 32-bit words with a 32-bit index (gather_positions.comp). */
        if ((uint64_t)map->meshes[p->mesh].vertex_count * stride > ((uint64_t)1 << 34))
            return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                             "%s: mesh_positions[%u]: %u vertices of %u bytes span more than 16 GiB", fn, e,
                             map->meshes[p->mesh].vertex_count, stride);
        for (int a = 0; a < 3; ++a)
            if (!isfinite(p->bounds.min[a]) || !isfinite(p->bounds.max[a]) || !(p->bounds.min[a] <= p->bounds.max[a]))
                return roma_fail(&map->logger, ROMA_ERROR_INVALID_ARGUMENT,
                                 "%s: mesh_positions[%u]: bounds min (%g, %g, %g), max (%g, %g, %g): not a finite box",
                                 fn, e, (double)p->bounds.min[0], (double)p->bounds.min[1], (double)p->bounds.min[2],
                                 (double)p->bounds.max[0], (double)p->bounds.max[1], (double)p->bounds.max[2]);
    }
    return ROMA_SUCCESS;
}

void roma_map_mesh_positions_take_bounds(roma_map *map, const roma_map_frame_desc *f, int restore)
{
    for (uint32_t e = 0; e < f->mesh_position_count; ++e) {
        roma_map_mesh *m = &map->meshes[f->mesh_positions[e].mesh];
        if (restore) {
            memcpy(m->bmin, m->kept_bmin, sizeof m->bmin);
            memcpy(m->bmax, m->kept_bmax, sizeof m->bmax);
        } else {
            memcpy(m->kept_bmin, m->bmin, sizeof m->bmin);
            memcpy(m->kept_bmax, m->bmax, sizeof m->bmax);
            memcpy(m->bmin, f->mesh_positions[e].bounds.min, sizeof m->bmin);
            memcpy(m->bmax, f->mesh_positions[e].bounds.max, sizeof m->bmax);
        }
    }
}

void roma_map_mesh_positions_record(roma_map *map, VkCommandBuffer cmd, const roma_map_frame_desc *f)
{
    if (!f->mesh_position_count)
        return;
    /* A mesh added since the last build was uploaded into the same buffer just before. */
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, map->gather_positions.pipeline);
    for (uint32_t e = 0; e < f->mesh_position_count; ++e) {
        const roma_mesh_positions *p = &f->mesh_positions[e];
        const roma_map_mesh *m = &map->meshes[p->mesh];
        const uint32_t stride = p->gpu_position_stride ? p->gpu_position_stride : 12u;
        roma_gather_positions_push push = {
            .src = p->gpu_positions, .dst = m->local.address, .config = {m->vertex_count, stride / 4u, 0, 0}};
        vkCmdPushConstants(cmd, map->gather_positions.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
        roma_cmd_dispatch_linear(cmd, m->vertex_count, ROMA_GATHER_WORKGROUP_SIZE);
    }
}

int roma_map_mesh_positions_used(const roma_map *map, const roma_map_frame_desc *f)
{
    for (uint32_t e = 0; e < f->mesh_position_count; ++e)
        if (map->meshes[f->mesh_positions[e].mesh].users)
            return 1;
    return 0;
}
