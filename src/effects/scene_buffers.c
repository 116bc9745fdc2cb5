#include "effects/scene_buffers.h"

#include <stdlib.h>
#include <string.h>

#include "vulkan/upload.h"

roma_result roma_scene_buffers_create(roma_context *ctx, const roma_scene *scene, roma_scene_buffers *g)
{
    if (!g)
        return ROMA_ERROR_INVALID_ARGUMENT;
    memset(g, 0, sizeof *g);
    roma_scene_view v;
    if (!ctx || roma_scene_get_view(scene, &v) != ROMA_SUCCESS)
        return ROMA_ERROR_INVALID_ARGUMENT;
    /* Laid out on the host, then into device-local memory (vulkan/upload.h). */
    float *p = malloc((size_t)v.vertex_count * 16), *n = malloc((size_t)v.vertex_count * 16);
    float *a = malloc((size_t)v.triangle_count * 16);
    roma_result r = p && n && a ? ROMA_SUCCESS
                                : roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "scene buffers: out of memory");
    for (uint32_t i = 0; r == ROMA_SUCCESS && i < v.vertex_count; ++i)
        for (int k = 0; k < 4; ++k) {
            p[4 * i + k] = k < 3 ? v.positions[3 * i + k] : 1.0f;
            /* Zero normals make the passes use the face normal. */
            n[4 * i + k] = k < 3 && v.normals ? v.normals[3 * i + k] : 0.0f;
        }
    for (uint32_t t = 0; r == ROMA_SUCCESS && t < v.triangle_count; ++t)
        for (int k = 0; k < 4; ++k)
            a[4 * t + k] = k < 3 ? v.materials[v.triangle_materials[t]].base_color[k] : 1.0f;
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create_filled(ctx, (VkDeviceSize)v.vertex_count * 16, usage, p, &g->positions);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create_filled(ctx, (VkDeviceSize)v.vertex_count * 16, usage, n, &g->normals);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create_filled(ctx, (VkDeviceSize)v.triangle_count * 12, usage, v.indices, &g->indices);
    if (r == ROMA_SUCCESS)
        r = roma_buffer_create_filled(ctx, (VkDeviceSize)v.triangle_count * 16, usage, a, &g->albedo);
    free(p);
    free(n);
    free(a);
    if (r != ROMA_SUCCESS) {
        roma_scene_buffers_destroy(ctx, g);
        return r;
    }
    g->vertex_count = v.vertex_count;
    g->triangle_count = v.triangle_count;
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
