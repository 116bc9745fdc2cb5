#include "study/gbuffer.h"
#include "study/study_shaders.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vulkan/vk_internal.h"

#define ROMA_GBUFFER_MAX_SIZE 16384u
#define ROMA_GBUFFER_DEPTH_FORMAT VK_FORMAT_D32_SFLOAT

struct roma_gbuffer {
    roma_context *ctx;
    uint32_t width, height;
    VkPipelineLayout layout;
    VkPipeline depth_pipeline;   /* pass 1: depth only, GREATER (reversed Z); stochastic: with discards */
    int stochastic;              /* a layer of a stochastic depth map (roma_gbuffer_create_stochastic) */
    VkPipeline shade_pipeline;   /* pass 2: EQUAL, early tests, writes the pixels */
    int shared_pipelines;        /* layout and pipelines are another G-buffer's (roma_gbuffer_create_sharing) */
    VkImage depth;
    VkDeviceMemory depth_memory;
    VkDeviceSize depth_bytes; /* counted against the context's memory use */
    VkImageView depth_view;
    roma_buffer params;          /* roma_gbuffer_params, written with vkCmdUpdateBuffer */
    roma_buffer pixels;          /* width * height roma_gbuffer_pixel */
};

static roma_result create_pipelines(roma_gbuffer *g)
{
    roma_context *ctx = g->ctx;
    VkShaderModule vert = VK_NULL_HANDLE, frag = VK_NULL_HANDLE;
    roma_result res = roma_push_layout_create(ctx, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                              sizeof(roma_gbuffer_push), &g->layout);
    if (res == ROMA_SUCCESS)
        res = roma_shader_module_create(ctx, "gbuffer.vert", &vert);
    if (res == ROMA_SUCCESS)
        res = roma_shader_module_create(ctx, "gbuffer.frag", &frag);
    VkShaderModule drop = VK_NULL_HANDLE;
    if (res == ROMA_SUCCESS && g->stochastic)
        res = roma_shader_module_create(ctx, "gbuffer_stochastic.frag", &drop);
    /* Reversed Z (near = 1, far = 0): the nearest surface has the greatest depth.
     * Pass 2 re-runs the same vertex shader (clip position computed `precise`), so the
     * surviving fragment's depth is bit-identical and EQUAL selects it. The depth pass
     * needs no fragment shader but in a stochastic layer, where it drops fragments; the
     * G-buffer goes to a storage buffer. */
    roma_graphics_pipeline_desc depth_pass = {
        .vert = vert, .frag = drop, .frag_name = "gbuffer_stochastic.frag", .layout = g->layout,
        .depth_format = ROMA_GBUFFER_DEPTH_FORMAT,
        .depth_write = 1, .depth_compare = VK_COMPARE_OP_GREATER,
        .label = "vkCreateGraphicsPipelines (G-buffer depth)",
    };
    roma_graphics_pipeline_desc shade_pass = {
        .vert = vert, .frag = frag, .frag_name = "gbuffer.frag", .layout = g->layout,
        .depth_format = ROMA_GBUFFER_DEPTH_FORMAT,
        .depth_write = 0, .depth_compare = VK_COMPARE_OP_EQUAL,
        .label = "vkCreateGraphicsPipelines (G-buffer shading)",
    };
    if (res == ROMA_SUCCESS)
        res = roma_graphics_pipeline_create(ctx, &depth_pass, &g->depth_pipeline);
    if (res == ROMA_SUCCESS)
        res = roma_graphics_pipeline_create(ctx, &shade_pass, &g->shade_pipeline);
    if (vert)
        vkDestroyShaderModule(ctx->device, vert, ctx->allocator);
    if (frag)
        vkDestroyShaderModule(ctx->device, frag, ctx->allocator);
    if (drop)
        vkDestroyShaderModule(ctx->device, drop, ctx->allocator);
    return res;
}

static roma_result create_depth(roma_gbuffer *g)
{
    roma_context *ctx = g->ctx;
    VkImageCreateInfo info = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
        .imageType = VK_IMAGE_TYPE_2D,
        .format = ROMA_GBUFFER_DEPTH_FORMAT,
        .extent = {g->width, g->height, 1},
        .mipLevels = 1,
        .arrayLayers = 1,
        .samples = VK_SAMPLE_COUNT_1_BIT,
        .tiling = VK_IMAGE_TILING_OPTIMAL,
        .usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
        .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
    };
    roma_result res = roma_vk_check(ctx, vkCreateImage(ctx->device, &info, ctx->allocator, &g->depth), "vkCreateImage");
    if (res != ROMA_SUCCESS)
        return res;
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(ctx->device, g->depth, &req);
    /* Device-local if offered, else any type the image accepts. */
    uint32_t type = UINT32_MAX;
    const VkPhysicalDeviceMemoryProperties *mp = &ctx->memory_properties;
    for (int pass = 0; pass < 2 && type == UINT32_MAX; ++pass)
        for (uint32_t i = 0; i < mp->memoryTypeCount && type == UINT32_MAX; ++i)
            if ((req.memoryTypeBits & (1u << i)) &&
                (pass == 1 || (mp->memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)))
                type = i;
    if (type == UINT32_MAX)
        return roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_DEVICE_MEMORY,
                         "roma_gbuffer_create: no memory type for the depth image");
    VkMemoryAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = req.size,
        .memoryTypeIndex = type,
    };
    res = roma_device_memory_reserve(ctx, req.size, "roma_gbuffer_create: depth image");
    if (res != ROMA_SUCCESS)
        return res;
    g->depth_bytes = req.size;
    res = roma_vk_check(ctx, vkAllocateMemory(ctx->device, &alloc, ctx->allocator, &g->depth_memory), "vkAllocateMemory");
    if (res == ROMA_SUCCESS)
        res = roma_vk_check(ctx, vkBindImageMemory(ctx->device, g->depth, g->depth_memory, 0),
                            "vkBindImageMemory");
    if (res == ROMA_SUCCESS) {
        VkImageViewCreateInfo view = {
            .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
            .image = g->depth,
            .viewType = VK_IMAGE_VIEW_TYPE_2D,
            .format = ROMA_GBUFFER_DEPTH_FORMAT,
            .subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1},
        };
        res = roma_vk_check(ctx, vkCreateImageView(ctx->device, &view, ctx->allocator, &g->depth_view), "vkCreateImageView");
    }
    return res;
}

/* source: NULL, or the G-buffer whose pipelines the new one uses (of its kind). */
static roma_result create_gbuffer(roma_context *ctx, uint32_t width, uint32_t height, int stochastic,
                                  const roma_gbuffer *source, roma_gbuffer **out)
{
    roma_study_shaders_use(ctx); /* its shaders are in the study table */
    if (!out)
        return ROMA_ERROR_INVALID_ARGUMENT;
    *out = NULL;
    if (!ctx)
        return ROMA_ERROR_INVALID_ARGUMENT;
    if (width < 1 || height < 1 || width > ROMA_GBUFFER_MAX_SIZE || height > ROMA_GBUFFER_MAX_SIZE)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_gbuffer_create: size %ux%u outside 1..%u", width, height,
                         (unsigned)ROMA_GBUFFER_MAX_SIZE);
    /* The tracing passes read it as a texel buffer of 4 RGBA32F texels a pixel. */
    if (4ull * width * height > ctx->properties.limits.maxTexelBufferElements)
        return roma_fail(&ctx->logger, ROMA_ERROR_UNSUPPORTED,
                         "roma_gbuffer_create: %ux%u needs %llu texels, above this device's maxTexelBufferElements "
                         "(%u)", width, height, 4ull * width * height, ctx->properties.limits.maxTexelBufferElements);
    roma_gbuffer *g = calloc(1, sizeof *g);
    if (!g)
        return roma_fail(&ctx->logger, ROMA_ERROR_OUT_OF_HOST_MEMORY, "roma_gbuffer_create: out of memory");
    g->ctx = ctx;
    g->width = width;
    g->height = height;
    g->stochastic = stochastic;
    roma_result res = ROMA_SUCCESS;
    if (source) {
        g->layout = source->layout;
        g->depth_pipeline = source->depth_pipeline;
        g->shade_pipeline = source->shade_pipeline;
        g->shared_pipelines = 1;
    } else {
        res = create_pipelines(g);
    }
    if (res == ROMA_SUCCESS)
        res = create_depth(g);
    if (res == ROMA_SUCCESS)
        res = roma_buffer_create(ctx, sizeof(roma_gbuffer_params),
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                 ROMA_MEMORY_DEVICE, &g->params);
    if (res == ROMA_SUCCESS)
        res = roma_buffer_create(ctx, (VkDeviceSize)width * height * sizeof(roma_gbuffer_pixel),
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                     VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, /* read by the tracing passes */
                                 ROMA_MEMORY_DEVICE, &g->pixels);
    if (res != ROMA_SUCCESS) {
        roma_gbuffer_destroy(g);
        return res;
    }
    *out = g;
    return ROMA_SUCCESS;
}

roma_result roma_gbuffer_create(roma_context *ctx, uint32_t width, uint32_t height, roma_gbuffer **out)
{
    return create_gbuffer(ctx, width, height, 0, NULL, out);
}

roma_result roma_gbuffer_create_stochastic(roma_context *ctx, uint32_t width, uint32_t height, roma_gbuffer **out)
{
    return create_gbuffer(ctx, width, height, 1, NULL, out);
}

roma_result roma_gbuffer_create_sharing(const roma_gbuffer *source, uint32_t width, uint32_t height,
                                        roma_gbuffer **out)
{
    if (!source) {
        if (out)
            *out = NULL;
        return ROMA_ERROR_INVALID_ARGUMENT;
    }
    return create_gbuffer(source->ctx, width, height, source->stochastic, source, out);
}

void roma_gbuffer_destroy(roma_gbuffer *g)
{
    if (!g)
        return;
    VkDevice dev = g->ctx->device;
    roma_buffer_destroy(g->ctx, &g->pixels);
    roma_buffer_destroy(g->ctx, &g->params);
    if (g->depth_view)
        vkDestroyImageView(dev, g->depth_view, g->ctx->allocator);
    if (g->depth)
        vkDestroyImage(dev, g->depth, g->ctx->allocator);
    if (g->depth_memory)
        vkFreeMemory(dev, g->depth_memory, g->ctx->allocator);
    roma_device_memory_release(g->ctx, g->depth_bytes);
    if (g->shared_pipelines) {
        free(g);
        return;
    }
    if (g->shade_pipeline)
        vkDestroyPipeline(dev, g->shade_pipeline, g->ctx->allocator);
    if (g->depth_pipeline)
        vkDestroyPipeline(dev, g->depth_pipeline, g->ctx->allocator);
    if (g->layout)
        vkDestroyPipelineLayout(dev, g->layout, g->ctx->allocator);
    free(g);
}

float roma_gbuffer_near_plane(const roma_scene *scene)
{
    roma_scene_view view;
    roma_scene_get_view(scene, &view);
    float diag = 0.0f;
    for (int k = 0; k < 3; ++k)
        diag += (view.bounds_max[k] - view.bounds_min[k]) * (view.bounds_max[k] - view.bounds_min[k]);
    return 1e-4f * sqrtf(diag);
}

int roma_gbuffer_camera_make(const roma_camera *cam, uint32_t w, uint32_t h, float near_plane,
                             roma_gbuffer_camera *out)
{
    roma_camera_frame f;
    if (!roma_camera_make_frame(cam, w, h, &f))
        return 0;
    memset(out, 0, sizeof *out);
    for (int i = 0; i < 3; ++i) {
        out->eye[i] = f.origin[i];
        out->right[i] = f.right[i];
        out->up[i] = f.up[i];
        out->forward[i] = f.forward[i];
    }
    out->eye[3] = near_plane;
    out->right[3] = 1.0f / (f.tan_half_fovy * f.aspect);
    out->up[3] = 1.0f / f.tan_half_fovy;
    return 1;
}

roma_result roma_gbuffer_record(roma_gbuffer *g, VkCommandBuffer cmd, const roma_gbuffer_inputs *in)
{
    if (!g)
        return ROMA_ERROR_INVALID_ARGUMENT;
    roma_context *ctx = g->ctx;
    if (!cmd || !in)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_gbuffer_record: cmd and in are required");
    if (in->triangle_count > (UINT32_MAX - 3u) / 3u)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_gbuffer_record: %u triangles exceed one draw", in->triangle_count);
    if (in->triangle_count && (!in->positions || !in->normals || !in->indices || !in->albedo))
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_gbuffer_record: a buffer address is zero");
    if (!(in->near_plane > 0.0f) || !isfinite(in->near_plane))
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT,
                         "roma_gbuffer_record: near_plane must be finite and > 0");
    roma_gbuffer_params params = {.dims = {g->width, g->height, in->triangle_count, 0}};
    if (!roma_gbuffer_camera_make(&in->camera, g->width, g->height, in->near_plane, &params.camera) ||
        !roma_gbuffer_camera_make(&in->previous_camera, g->width, g->height, in->near_plane, &params.previous))
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_gbuffer_record: degenerate camera");

    /* Inputs written by transfers or compute made visible; WAR/WAW against the
     * previous recording's reads of params and writes/copies of the pixels. */
    roma_cmd_memory_barrier(cmd,
                            VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                                VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                            VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                                VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                            VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                                VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    /* Recorded into the command buffer, so several recordings need no host sync. */
    vkCmdUpdateBuffer(cmd, g->params.buffer, 0, sizeof params, &params);
    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT);

    /* Old depth contents are discarded (cleared below); waits for the previous
     * recording's depth accesses. */
    VkImageMemoryBarrier2 to_depth = {
        .sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2,
        .srcStageMask = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
        .srcAccessMask = VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
        .dstStageMask = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
        .dstAccessMask = VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                         VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
        .oldLayout = VK_IMAGE_LAYOUT_UNDEFINED,
        .newLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
        .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
        .image = g->depth,
        .subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1},
    };
    VkDependencyInfo dep = {
        .sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO,
        .imageMemoryBarrierCount = 1,
        .pImageMemoryBarriers = &to_depth,
    };
    vkCmdPipelineBarrier2(cmd, &dep);

    VkRenderingAttachmentInfo depth_attachment = {
        .sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
        .imageView = g->depth_view,
        .imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
        .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
        .storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
        .clearValue = {.depthStencil = {0.0f, 0}}, /* reversed Z: 0 is the far plane */
    };
    VkRenderingInfo rendering = {
        .sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
        .renderArea = {{0, 0}, {g->width, g->height}},
        .layerCount = 1,
        .pDepthAttachment = &depth_attachment,
    };
    /* A stochastic layer keeps each fragment with probability keep (the shaders: 0 or 1 keep all). */
    const float keep = g->stochastic && in->keep > 0.0f && in->keep < 1.0f ? in->keep : 0.0f;
    uint32_t keep_bits;
    memcpy(&keep_bits, &keep, sizeof keep_bits);
    roma_gbuffer_push push = {
        .positions = in->positions,
        .normals = in->normals,
        .indices = in->indices,
        .albedo = in->albedo,
        .params = g->params.address,
        .pixels = g->pixels.address,
        .config = {in->triangle_count, keep_bits, in->seed, 0},
    };
    /* Both passes in one rendering: depth writes of the first draw are ordered
     * before the tests of the second by primitive order. */
    vkCmdBeginRendering(cmd, &rendering);
    VkViewport viewport = {0.0f, 0.0f, (float)g->width, (float)g->height, 0.0f, 1.0f};
    VkRect2D scissor = {{0, 0}, {g->width, g->height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    vkCmdPushConstants(cmd, g->layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof push,
                       &push);
    if (in->triangle_count) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, g->depth_pipeline);
        vkCmdDraw(cmd, 3 * in->triangle_count, 1, 0, 0);
    }
    /* The 3 extra vertices are the background triangle at depth 0: it passes
     * EQUAL exactly where no geometry wrote depth. */
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, g->shade_pipeline);
    vkCmdDraw(cmd, 3 * in->triangle_count + 3, 1, 0, 0);
    vkCmdEndRendering(cmd);

    roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                                VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
    return ROMA_SUCCESS;
}

VkBuffer roma_gbuffer_pixels_buffer(const roma_gbuffer *g)
{
    return g ? g->pixels.buffer : VK_NULL_HANDLE;
}

VkDeviceAddress roma_gbuffer_pixels_address(const roma_gbuffer *g)
{
    return g ? g->pixels.address : 0;
}

roma_result roma_gbuffer_download(roma_gbuffer *g, roma_gbuffer_pixel *out)
{
    if (!g)
        return ROMA_ERROR_INVALID_ARGUMENT;
    roma_context *ctx = g->ctx;
    if (!out)
        return roma_fail(&ctx->logger, ROMA_ERROR_INVALID_ARGUMENT, "roma_gbuffer_download: out is required");
    const VkDeviceSize bytes = (VkDeviceSize)g->width * g->height * sizeof(roma_gbuffer_pixel);
    roma_buffer readback = {0};
    roma_result res = roma_buffer_create(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, ROMA_MEMORY_READBACK,
                                         &readback);
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    if (res == ROMA_SUCCESS)
        res = roma_begin_one_shot(ctx, &cmd);
    if (res == ROMA_SUCCESS) {
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferCopy copy = {0, 0, bytes};
        vkCmdCopyBuffer(cmd, g->pixels.buffer, readback.buffer, 1, &copy);
        roma_cmd_memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        res = roma_submit_one_shot(ctx, cmd);
    }
    if (res == ROMA_SUCCESS)
        res = roma_buffer_invalidate(ctx, &readback);
    if (res == ROMA_SUCCESS)
        memcpy(out, readback.mapped, (size_t)bytes);
    roma_buffer_destroy(ctx, &readback);
    return res;
}
