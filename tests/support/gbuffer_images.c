#include "gbuffer_images.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"

static VkDeviceSize plane_bytes(const roma_test_gbuffer *g) { return (VkDeviceSize)g->width * g->height * 16; }

int roma_test_gbuffer_create(roma_context *ctx, const roma_ref *ref, const roma_camera *camera, uint32_t width,
                             uint32_t height, roma_test_gbuffer *g)
{
    return roma_test_gbuffer_create_bordered(ctx, ref, camera, width, height, 0, g);
}

int roma_test_gbuffer_create_bordered(roma_context *ctx, const roma_ref *ref, const roma_camera *camera,
                                      uint32_t width, uint32_t height, uint32_t border, roma_test_gbuffer *g)
{
    memset(g, 0, sizeof *g);
    g->width = width;
    g->height = height;
    const uint32_t n = width * height;
    g->hits = calloc(n, sizeof *g->hits);
    g->covered = calloc(n, sizeof *g->covered);
    roma_camera_frame cam;
    if (!g->hits || !g->covered || !roma_camera_make_frame(camera, width, height, &cam)) {
        CHECK(!"G-buffer: out of memory or a bad camera");
        return 0;
    }
    const VkDeviceSize plane = plane_bytes(g);
    roma_test_staging_create(ctx, 4 * plane + (VkDeviceSize)n * 4, &g->staging);
    float *host = g->staging.mapped;
    if (!host)
        return 0;
    for (uint32_t p = 0; p < n; ++p) {
        float o[3], d[3];
        roma_camera_ray(&cam, (float)(p % width) + 0.5f, (float)(p / width) + 0.5f, o, d);
        g->covered[p] = p % width >= border && p / width >= border &&
                        roma_ref_intersect(ref, o, d, 0.0f, INFINITY, &g->hits[p]);
        g->covered_count += (uint32_t)g->covered[p];
        for (int a = 0; a < 3; ++a) {
            host[4 * p + a] = g->covered[p] ? g->hits[p].position[a] : 0.0f;
            host[4 * (n + p) + a] = g->covered[p] ? g->hits[p].shading_normal[a] : 0.0f;
            host[4 * (2 * n + p) + a] = g->covered[p] ? g->hits[p].geometric_normal[a] : 0.0f;
        }
        host[4 * p + 3] = g->covered[p] ? 1.0f : 0.0f;
        host[4 * (n + p) + 3] = host[4 * (2 * n + p) + 3] = 0.0f;
    }
    for (int i = 0; i < 3; ++i)
        roma_test_image_create(ctx, width, height, VK_FORMAT_R32G32B32A32_SFLOAT,
                               VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, &g->in[i]);
    roma_test_image_create(ctx, width, height, VK_FORMAT_R32G32B32A32_SFLOAT,
                           VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, &g->rgba);
    roma_test_image_create(ctx, width, height, VK_FORMAT_R32_SFLOAT,
                           VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, &g->r);
    VkDevice dev = g->device = roma_context_device(ctx);
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .queueFamilyIndex = roma_context_queue_family(ctx)};
    CHECK(vkCreateCommandPool(dev, &pi, NULL, &g->pool) == VK_SUCCESS);
    VkCommandBufferAllocateInfo cai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = g->pool,
                                       .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, .commandBufferCount = 1};
    CHECK(g->pool && vkAllocateCommandBuffers(dev, &cai, &g->cmd) == VK_SUCCESS);
    return g->in[0].view && g->in[1].view && g->in[2].view && g->rgba.view && g->r.view && g->cmd;
}

void roma_test_gbuffer_destroy(roma_context *ctx, roma_test_gbuffer *g)
{
    VkDevice dev = roma_context_device(ctx);
    if (g->pool)
        vkDestroyCommandPool(dev, g->pool, NULL);
    for (int i = 0; i < 3; ++i)
        roma_test_image_destroy(dev, &g->in[i]);
    roma_test_image_destroy(dev, &g->rgba);
    roma_test_image_destroy(dev, &g->r);
    roma_test_staging_destroy(dev, &g->staging);
    free(g->hits);
    free(g->covered);
    memset(g, 0, sizeof *g);
}

VkCommandBuffer roma_test_gbuffer_begin(roma_test_gbuffer *g)
{
    vkResetCommandPool(g->device, g->pool, 0);
    VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(g->cmd, &begin);
    if (!g->uploaded) {
        for (int i = 0; i < 3; ++i) {
            roma_test_layout_barrier(g->cmd, g->in[i].image, VK_IMAGE_LAYOUT_UNDEFINED,
                                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                                     VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
            VkBufferImageCopy copy = {.bufferOffset = (VkDeviceSize)i * plane_bytes(g),
                                      .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                      .imageExtent = {g->width, g->height, 1}};
            vkCmdCopyBufferToImage(g->cmd, g->staging.buffer, g->in[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                                   &copy);
            roma_test_layout_barrier(g->cmd, g->in[i].image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                                     VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
        }
        g->uploaded = 1;
    }
    const VkImage outputs[2] = {g->rgba.image, g->r.image};
    for (int i = 0; i < 2; ++i)
        roma_test_layout_barrier(g->cmd, outputs[i], VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                                 VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                                 VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                 VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    return g->cmd;
}

void roma_test_gbuffer_finish(roma_context *ctx, roma_test_gbuffer *g, const float **rgba, const float **r)
{
    const VkImage outputs[2] = {g->rgba.image, g->r.image};
    const VkDeviceSize offsets[2] = {3 * plane_bytes(g), 4 * plane_bytes(g)};
    for (int i = 0; i < 2; ++i) {
        roma_test_layout_barrier(g->cmd, outputs[i], VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                 VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                 VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferImageCopy back = {.bufferOffset = offsets[i],
                                  .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                  .imageExtent = {g->width, g->height, 1}};
        vkCmdCopyImageToBuffer(g->cmd, outputs[i], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, g->staging.buffer, 1, &back);
    }
    roma_test_submit_and_wait(ctx, g->cmd);
    const float *host = g->staging.mapped;
    *rgba = host + 12u * g->width * g->height;
    *r = host + 16u * g->width * g->height;
}

roma_light_images roma_test_gbuffer_light_images(const roma_test_gbuffer *g)
{
    return (roma_light_images){.width = g->width, .height = g->height, .position = g->in[0].view,
                               .normal = g->in[1].view, .geometric_normal = g->in[2].view, .output = g->rgba.view};
}

roma_ao_images roma_test_gbuffer_ao_images(const roma_test_gbuffer *g)
{
    return (roma_ao_images){.width = g->width, .height = g->height, .position = g->in[0].view,
                            .normal = g->in[1].view, .geometric_normal = g->in[2].view, .output = g->r.view};
}
