// roma-viewer: the rasterized G-buffer the effects read (world position with w = 1 on
// geometry, face normal, base colour) and its depth buffer.
#pragma once

#include "vk_base.h"

struct gbuffer_pass {
    vk_image position, normal, albedo, depth;
    uint32_t width = 0, height = 0;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
};

struct gbuffer_draw {
    float clip_rows[4][4]; // world -> clip
    float eye[4];
    VkDeviceAddress positions; // 3 floats per vertex
    VkDeviceAddress albedo;    // vec4 per triangle
    VkDeviceAddress indices;   // uint32, 3 per triangle
    uint32_t triangle_count;
};

bool gbuffer_pass_create(const vk_base &b, gbuffer_pass &g);
// (Re)creates the images at a new size; the old ones must be idle.
bool gbuffer_pass_resize(const vk_base &b, gbuffer_pass &g, uint32_t width, uint32_t height);
void gbuffer_pass_destroy(const vk_base &b, gbuffer_pass &g);
// Leaves the three colour images in SHADER_READ_ONLY_OPTIMAL, visible to compute shaders.
void gbuffer_pass_record(const gbuffer_pass &g, VkCommandBuffer cmd, const gbuffer_draw &draw);
