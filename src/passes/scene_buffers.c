#include "passes/scene_buffers.h"

#include <string.h>

roma_result roma_scene_buffers_create(roma_context *ctx, const roma_scene *scene, roma_scene_buffers *g)
{
    if (!g)
        return ROMA_ERROR_INVALID_ARGUMENT;
    memset(g, 0, sizeof *g);
    roma_scene_view v;
    if (!ctx || roma_scene_get_view(scene, &v) != ROMA_SUCCESS)
        return ROMA_ERROR_INVALID_ARGUMENT;
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    roma_result r = roma_buffer_create(ctx, (VkDeviceSize)v.vertex_count * 16, usage, ROMA_MEMORY_UPLOAD, &g->positions);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, (VkDeviceSize)v.vertex_count * 16, usage, ROMA_MEMORY_UPLOAD, &g->normals);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, (VkDeviceSize)v.triangle_count * 12, usage, ROMA_MEMORY_UPLOAD, &g->indices);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create(ctx, (VkDeviceSize)v.triangle_count * 16, usage, ROMA_MEMORY_UPLOAD, &g->albedo);
    if (r != ROMA_SUCCESS) {
        roma_scene_buffers_destroy(ctx, g);
        return r;
    }
    g->vertex_count = v.vertex_count;
    g->triangle_count = v.triangle_count;
    float *p = g->positions.mapped, *n = g->normals.mapped, *a = g->albedo.mapped;
    for (uint32_t i = 0; i < v.vertex_count; ++i)
        for (int k = 0; k < 4; ++k) {
            p[4 * i + k] = k < 3 ? v.positions[3 * i + k] : 1.0f;
            /* Zero normals make the passes use the face normal. */
            n[4 * i + k] = k < 3 && v.normals ? v.normals[3 * i + k] : 0.0f;
        }
    memcpy(g->indices.mapped, v.indices, (size_t)v.triangle_count * 12);
    for (uint32_t t = 0; t < v.triangle_count; ++t)
        for (int k = 0; k < 4; ++k)
            a[4 * t + k] = k < 3 ? v.materials[v.triangle_materials[t]].base_color[k] : 1.0f;
    return ROMA_SUCCESS;
}

void roma_scene_buffers_destroy(roma_context *ctx, roma_scene_buffers *g)
{
    if (!ctx || !g)
        return;
    roma_buffer_destroy(ctx, &g->positions);
    roma_buffer_destroy(ctx, &g->normals);
    roma_buffer_destroy(ctx, &g->indices);
    roma_buffer_destroy(ctx, &g->albedo);
    memset(g, 0, sizeof *g);
}
