/* The library's per-frame host cost: roma_map_record_build as an engine calls it every
 * frame, with two frame slots, timed on the host around the call alone (recording only:
 * the command buffers are reset, never submitted, so no GPU time is in the figure). */
#include "record_cost.h"

#include <stdlib.h>

#include "app_common.h"
#include "roma/map.h"
#include "vulkan/vk_internal.h"

int roma_bench_record_cost(roma_context *ctx, const roma_scene *scene, uint32_t runs, FILE *csv)
{
    roma_scene_view sv;
    roma_scene_get_view(scene, &sv);
    roma_map *map = NULL;
    roma_map_desc desc = {.resolution = 128, .angular = 4, .frames_in_flight = 2};
    roma_buffer gpu_positions = {0};
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmds[2];
    VkDevice dev = roma_context_device(ctx);
    VkCommandPoolCreateInfo pool_info = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                         .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                         .queueFamilyIndex = roma_context_queue_family(ctx)};
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 2};
    const uint32_t n = runs * 10;
    double *samples = malloc(sizeof(double) * n);
    int status = 1;
    if (!samples || roma_map_create(ctx, &desc, scene, &map) != ROMA_SUCCESS ||
        roma_buffer_create(ctx, 12ull * sv.vertex_count, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                           VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT, ROMA_MEMORY_DEVICE, &gpu_positions) != ROMA_SUCCESS ||
        vkCreateCommandPool(dev, &pool_info, NULL, &pool) != VK_SUCCESS)
        goto done;
    ai.commandPool = pool;
    if (vkAllocateCommandBuffers(dev, &ai, cmds) != VK_SUCCESS)
        goto done;
    roma_box volume;
    for (int a = 0; a < 3; ++a)
        volume.min[a] = sv.bounds_min[a], volume.max[a] = sv.bounds_max[a];
    static const char *names[3] = {"static geometry", "host positions", "GPU positions"};
    printf("\nPer-frame host cost of roma_map_record_build (RES 128, A 4, 2 frame slots, %u vertices, %u "
           "triangles; recording only, median of %u calls)\n\n| frame | us per call |\n|---|---|\n",
           sv.vertex_count, sv.triangle_count, n);
    for (int c = 0; c < 3; ++c) {
        for (uint32_t k = 0; k < n; ++k) {
            uint32_t slot = k % 2;
            roma_map_frame_desc fd = {.frame = k, .seed = 1, .jitter_grid = 1, .jitter_directions = 1, .slot = slot};
            if (c == 1)
                fd.positions = sv.positions, fd.vertex_count = sv.vertex_count;
            if (c == 2)
                fd.gpu_positions = gpu_positions.address, fd.vertex_count = sv.vertex_count, fd.volume = &volume;
            VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
            vkResetCommandBuffer(cmds[slot], 0);
            vkBeginCommandBuffer(cmds[slot], &bi);
            double t0 = roma_app_now_ms();
            roma_result r = roma_map_record_build(map, cmds[slot], &fd, NULL);
            samples[k] = (roma_app_now_ms() - t0) * 1000.0;
            vkEndCommandBuffer(cmds[slot]);
            if (r != ROMA_SUCCESS)
                goto done;
        }
        double us = roma_app_median(samples, (int)n);
        printf("| %s | %.1f |\n", names[c], us);
        if (csv)
            fprintf(csv, "record,%s,128,4,%.3f,us\n", names[c], us);
    }
    status = 0;
done:
    if (pool)
        vkDestroyCommandPool(dev, pool, NULL);
    roma_buffer_destroy(ctx, &gpu_positions);
    roma_map_destroy(map);
    free(samples);
    return status;
}
