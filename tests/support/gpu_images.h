/* Images and host staging for tests of the effects on an engine's images: the test plays the
 * engine, owning device-local images and a host-visible buffer it uploads from and reads
 * back into. Failures count as test failures (harness.h CHECK). */
#ifndef ROMA_TEST_GPU_IMAGES_H
#define ROMA_TEST_GPU_IMAGES_H

#include <stdint.h>
#include <vulkan/vulkan.h>

#include "roma/context.h"

typedef struct roma_test_image {
    VkImage image;
    VkImageView view;
    VkDeviceMemory memory;
} roma_test_image;

/* A memory type of the device with `want` among those in `bits` (0 when none). */
uint32_t roma_test_memory_type(VkPhysicalDevice pd, uint32_t bits, VkMemoryPropertyFlags want);

/* A 2D device-local image of width x height with a view of its one level and layer. */
void roma_test_image_create(roma_context *ctx, uint32_t width, uint32_t height, VkFormat format,
                            VkImageUsageFlags usage, roma_test_image *out);
void roma_test_image_destroy(VkDevice dev, roma_test_image *image);

/* One image barrier (synchronization2) of the colour aspect. */
void roma_test_layout_barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                              VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                              VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access);

/* Ends cmd (recording) after a barrier that makes its copies visible to the host, submits it
 * to the context's queue and waits for the queue to be idle. */
void roma_test_submit_and_wait(roma_context *ctx, VkCommandBuffer cmd);

/* A host-visible, coherent transfer buffer of `bytes`, mapped. */
typedef struct roma_test_staging {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped;
} roma_test_staging;
void roma_test_staging_create(roma_context *ctx, VkDeviceSize bytes, roma_test_staging *out);
void roma_test_staging_destroy(VkDevice dev, roma_test_staging *staging);

/* A host-visible, coherent storage buffer of `bytes` reachable by device address, mapped:
 * what an engine uses for per-frame uploads and readbacks that shaders reach by address. */
typedef struct roma_test_host_buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped;
    VkDeviceAddress address;
} roma_test_host_buffer;
void roma_test_host_buffer_create(roma_context *ctx, VkDeviceSize bytes, roma_test_host_buffer *out);
/* Accepts a zeroed one. */
void roma_test_host_buffer_destroy(VkDevice dev, roma_test_host_buffer *buffer);

#endif /* ROMA_TEST_GPU_IMAGES_H */
