/** @file
 * The covered pixels of a frame's G-buffer, listed once and shared by the frame's effects.
 *
 * An effect on G-buffer images (roma_ao_effect, roma_light_effect, roma_gi_effect) whose
 * pixel_dispatch resolves to ROMA_PIXEL_DISPATCH_LIST lists the pixels whose position holds a
 * surface before it traces them, and a frame with AO, direct light and GI lists them three
 * times: on a CPU device each list pass costs about half of tracing AO at one sample per
 * pixel (18 against 35 ms a 1080p frame on lavapipe, docs/benchmark.md). A roma_pixel_list lists them once. Record it after the G-buffer
 * is written and before the effects, into the same command buffer, and name it in each
 * effect's images (roma_ao_images.pixels, roma_light_images.pixels): the effect then traces
 * the listed pixels by an indirect dispatch, whatever its pixel_dispatch, and writes those
 * pixels only; the others keep what its output held (an engine composes them by its own
 * coverage: the position's w). At a resolution divisor above 1 the effect lists the one
 * pixel of each block it traces itself (the shared list must still be the slot's, of the
 * images' size) and its upsample writes the covered pixels only.
 *
 * A record lists the slot's pixels anew. Until the slot's next record, every effect record of
 * that slot may use the list, in this frame or later ones while the position image is
 * unchanged (a still camera accumulating frames lists once); effect records of other slots
 * may not (the slot rules of roma_map_frame_desc.slot: the engine waits for a slot's frames
 * only). The record ends with the barrier that makes the list visible to the effects'
 * compute shaders and indirect dispatches; it starts with one after earlier readers of the
 * list. Before it: the position image's writes made visible to compute-shader sampled reads.
 *
 * Threads (roma/context.h): a list is externally synchronised, used by one thread at a time;
 * records write only into
 * the command buffer they are given and never submit or wait. */
#ifndef ROMA_PIXEL_LIST_H
#define ROMA_PIXEL_LIST_H

#include "roma/api.h"

#include <stdint.h>
#include <vulkan/vulkan.h>

#include "roma/context.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Settings of roma_pixel_list_create; the zero value is the default. */
typedef struct roma_pixel_list_desc {
    uint32_t frames_in_flight; /**< frame slots, [1, ROMA_MAX_FRAMES_IN_FLIGHT]; 0 = 2 */
    roma_logger logger;        /**< 0 = the context's */
} roma_pixel_list_desc;

/** The covered pixels of a G-buffer, one list per frame slot (opaque). */
typedef struct roma_pixel_list roma_pixel_list;

/** Creates a list; its buffers are allocated by the first record of each slot (and grow with
 * the images).
 *
 * @param context  the context.
 * @param desc     settings; NULL = the zero value.
 * @param[out] out the list; NULL on failure.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL context or out or
 *         frames_in_flight above ROMA_MAX_FRAMES_IN_FLIGHT; ROMA_ERROR_OUT_OF_HOST_MEMORY, or a
 *         Vulkan failure code.
 * @par Threads
 * Any thread. */
ROMA_API roma_result roma_pixel_list_create(roma_context *context, const roma_pixel_list_desc *desc,
                                            roma_pixel_list **out);

/** Destroys the list.
 *
 * @param list  the list, or NULL (nothing is done). The caller makes sure no submitted work
 *              still uses it.
 * @par Threads
 * Any thread, the list externally synchronised. */
ROMA_API void roma_pixel_list_destroy(roma_pixel_list *list);

/** The G-buffer image a record lists. */
typedef struct roma_pixel_list_images {
    uint32_t width;             /**< size of the image, pixels: the effects' images have the same */
    uint32_t height;            /**< size of the image, pixels */
    VkImageView position;       /**< sampled (any float format): w > 0 = geometry */
    VkImageLayout input_layout; /**< SHADER_READ_ONLY_OPTIMAL (0 = that) or GENERAL */
    uint32_t frame;             /**< the engine's frame counter, as the effects' settings.frame */
} roma_pixel_list_images;

/** Records the list of the covered pixels of images.position for slot: a pass over every
 * pixel that lists those with position w > 0, one that turns their count into indirect
 * dispatch arguments, with barriers around them (see the file comment). At most 4 records per
 * slot and frame.
 *
 * @param list    the list.
 * @param cmd     a command buffer of the context's queue family, recording.
 * @param slot    the engine's frame slot, below the list's frames_in_flight.
 * @param images  the image; copied. It must outlive the recorded work.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL argument, a slot out of range,
 *         a zero size or position, a width or height above 65,536 (the list packs x and y in
 *         16 bits each), images whose list would exceed the device's storage-buffer range or
 *         more than 4 records in a slot's frame; ROMA_ERROR_OUT_OF_DEVICE_MEMORY or
 *         another Vulkan failure code when the slot's list must grow. Nothing is recorded on
 *         failure.
 * @par Threads
 * Any thread, the list externally synchronised; cmd externally synchronised. */
ROMA_API roma_result roma_pixel_list_record(roma_pixel_list *list, VkCommandBuffer cmd, uint32_t slot,
                                            const roma_pixel_list_images *images);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_PIXEL_LIST_H */
