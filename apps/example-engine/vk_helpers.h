/* The example engine's Vulkan plumbing: its instance and device, buffers, images, compute
 * pipelines and barriers. Nothing here knows libroma beyond the device contract
 * (roma_get_device_requirements) and trace.glsl's division rule. */
#ifndef EXAMPLE_VK_HELPERS_H
#define EXAMPLE_VK_HELPERS_H

#include "roma/roma.h"

#define SLOTS 2 /* frames in flight: each has its command buffer, its fence and libroma's slot */

typedef struct engine {
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    VkPhysicalDevice physical;
    VkDevice device;
    VkBool32 corrected_division; /* roma_context_info's: how its shaders including roma/trace.glsl divide */
    VkQueue queue;
    uint32_t family;
    unsigned validation_messages;
} engine;

typedef struct buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped; /* host-visible buffers only */
    VkDeviceAddress address;
} buffer;

typedef struct image {
    VkImage image;
    VkDeviceMemory memory;
    VkImageView view;
} image;

/* The instance (validation: 0 none, 1 the Khronos layer, 2 the layer with synchronization
 * validation; every message counts in validation_messages) and the first Vulkan 1.3 device
 * with a graphics + compute queue that has timestamps, created with exactly what libroma
 * lists in *req. */
int engine_create(engine *e, int validation, roma_device_requirements *req);
void engine_destroy(engine *e);

/* Storage buffers with a device address (and transfer destination); host_visible ones are
 * mapped. */
int buffer_create(const engine *e, VkDeviceSize size, int host_visible, buffer *out);
void buffer_destroy(const engine *e, buffer *b);
/* A 2D image of width x height with its view. */
int image_create(const engine *e, uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage,
                 image *out);
void image_destroy(const engine *e, image *im);

/* A compute pipeline from SPIR-V compiled at build time (EXAMPLE_SPV_DIR), with push_size
 * bytes of push constants and trace.glsl's division rule; set_layout may be VK_NULL_HANDLE. */
int pipeline_create(const engine *e, const char *name, uint32_t push_size, VkDescriptorSetLayout set_layout,
                    VkPipelineLayout *layout, VkPipeline *pipeline);
/* A set of count storage images (bindings 0, 1, ...) for compute, in GENERAL layout. */
int storage_image_set_create(const engine *e, uint32_t count, const VkImageView *views, VkDescriptorSetLayout *layout,
                             VkDescriptorPool *pool, VkDescriptorSet *set);
/* Records, submits and waits for the images' move from UNDEFINED to GENERAL, before a
 * compute shader's writes. */
int images_to_general(const engine *e, VkCommandBuffer cmd, uint32_t count, const VkImage *images);

void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                    VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access);

#endif
