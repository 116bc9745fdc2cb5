/** @file
 * libroma: temporal accumulation and an edge-aware spatial filter for the effects' noisy
 * images, on the engine's images, recorded into the engine's command buffer.
 *
 * ROMA's effects are meant to be averaged over frames: every frame brings new jitter of the
 * grid and the directions and new samples (the ROMA paper, 4.3), so one frame of
 * roma_ao_effect, roma_light_effect or roma_gi_effect output is noisy and biased by its one
 * array, and the mean over frames is not. This effect keeps that mean while the camera moves:
 *
 *  1. Accumulation: each pixel's surface point is projected with the previous frame's
 *     world-to-clip matrix to where it was on the previous picture; the history there is kept
 *     when the previous frame saw the same surface there (its position within three pixel
 *     footprints, the footprint measured from this frame's positions: the distance to the
 *     nearest neighbouring pixel's point). The output averages the new value with it over at
 *     most max_history frames (a running mean, then an exponential one): a still camera
 *     converges, a moving one does not smear. Background pixels (position w <= 0) get the
 *     value with a history of 0 frames.
 *  2. Spatial filter (when a `filtered` image is given): filter_iterations iterations of an
 *     a-trous wavelet filter (5 x 5 taps of the B3 spline, 1, 2, 4 .. pixels apart), each tap
 *     weighted down where its surface leaves this pixel's tangent plane (relative to the
 *     footprint) or its normal turns away; it runs only where the history is shorter than
 *     filter_below frames (a moved camera, a disocclusion) and passes the rest through.
 *
 * The engine owns every image, the history included: it passes last frame's `accumulated`
 * image as this frame's `history` (two images, swapped every frame) and keeps last frame's
 * position image. A single-channel input (an R32F AO image) comes out in r.
 *
 * Synchronisation the caller records: the inputs' writes (and last frame's `accumulated`)
 * made visible to compute-shader sampled reads; the sampled inputs in input_layout
 * (SHADER_READ_ONLY_OPTIMAL or GENERAL), the history in history_layout, the storage images
 * (accumulated, filtered, scratch) in GENERAL. Between its own dispatches the effect records
 * the barriers it needs; after the record, compute-shader storage writes to the engine's
 * readers. Descriptor sets come from a pool per frame slot (8 records per slot and frame);
 * slots and frames follow the rules of roma_ao_effect (count frames in settings.frame).
 * Nothing here reads a ROMA map: the effect may run on any engine image. Like every record
 * call of libroma, it binds its own compute pipeline, descriptor sets and push constants:
 * bind yours again after it.
 *
 * Threads (roma/context.h): an effect is externally synchronised, used by one thread at a time;
 * records write only
 * into the command buffer they are given and never submit or wait. */
#ifndef ROMA_TEMPORAL_EFFECT_H
#define ROMA_TEMPORAL_EFFECT_H

#include "roma/api.h"

#include <stdint.h>
#include <vulkan/vulkan.h>

#include "roma/context.h"
#include "roma/map.h" /* ROMA_MAX_FRAMES_IN_FLIGHT */

#ifdef __cplusplus
extern "C" {
#endif

/** Default of roma_temporal_settings.max_history (frames). Defaults are resolved in one place
 * (roma_temporal_settings_resolve). */
#define ROMA_DEFAULT_TEMPORAL_HISTORY 32u
/** Default of roma_temporal_settings.filter_iterations. */
#define ROMA_DEFAULT_FILTER_ITERATIONS 3u
/** Default of roma_temporal_settings.filter_below (frames of history). */
#define ROMA_DEFAULT_FILTER_BELOW 4u
/** Most filter iterations a record runs. */
#define ROMA_MAX_FILTER_ITERATIONS 5u

/** Per-record settings; the zero value is the default (roma_temporal_settings_resolve): a
 * still camera, 32 frames of history, 3 filter iterations below 4 frames. */
typedef struct roma_temporal_settings {
    /** The previous frame's world-to-clip matrix, column-major, Vulkan clip space (pixel
     * ((ndc + 1) / 2) * size, row 0 at ndc.y = -1). All zero = the camera did not move (the
     * history is read at the same pixel). */
    float previous_view_proj[16];
    uint32_t max_history;       /**< frames a pixel averages at most, >= 1; 0 = ROMA_DEFAULT_TEMPORAL_HISTORY */
    uint32_t reset;             /**< non-zero: no history this frame (the first frame, a cut) */
    uint32_t filter_iterations; /**< 1..ROMA_MAX_FILTER_ITERATIONS; 0 = ROMA_DEFAULT_FILTER_ITERATIONS */
    uint32_t filter_below;      /**< the filter runs where the history is shorter; 0 = ROMA_DEFAULT_FILTER_BELOW */
    uint32_t frame;             /**< the engine's frame counter: a new frame of the slot */
} roma_temporal_settings;

/** The zero value's meaning filled in (the one place defaults are resolved).
 *
 * @param in        the settings; NULL = the zero value (all defaults).
 * @param[out] out  the resolved settings; zeroed on failure. May equal in.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL out, a NaN or infinite matrix
 *         entry, or filter_iterations above ROMA_MAX_FILTER_ITERATIONS.
 * @par Threads
 * Any thread (pure). */
ROMA_API roma_result roma_temporal_settings_resolve(const roma_temporal_settings *in, roma_temporal_settings *out);

/** Temporal accumulation and spatial filter on the engine's images (opaque). Used by one
 * thread at a time (roma/context.h). */
typedef struct roma_temporal_effect roma_temporal_effect;

/** Settings of roma_temporal_effect_create; the zero value is the default. */
typedef struct roma_temporal_effect_desc {
    uint32_t frames_in_flight; /**< [1, ROMA_MAX_FRAMES_IN_FLIGHT]; 0 = 2 */
    roma_logger logger;        /**< 0 = the context's */
} roma_temporal_effect_desc;

/** Creates the effect: two compute pipelines and a descriptor pool per slot.
 *
 * @param context   the context; must outlive the effect.
 * @param desc      settings; NULL = the zero value. Copied.
 * @param[out] out  the new effect; NULL on failure.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL context or out, or
 *         frames_in_flight above ROMA_MAX_FRAMES_IN_FLIGHT; ROMA_ERROR_OUT_OF_HOST_MEMORY, or a
 *         Vulkan failure code (roma_result).
 * @par Threads
 * Any thread. */
ROMA_API roma_result roma_temporal_effect_create(roma_context *context, const roma_temporal_effect_desc *desc,
                                                 roma_temporal_effect **out);

/** Destroys the effect.
 *
 * @param effect  the effect, or NULL (nothing is done). The caller makes sure no submitted
 *                work still uses it.
 * @par Threads
 * Any thread, the effect externally synchronised. */
ROMA_API void roma_temporal_effect_destroy(roma_temporal_effect *effect);

/** The engine's images the temporal effect reads and writes (all width x height). */
typedef struct roma_temporal_images {
    uint32_t width;  /**< pixels */
    uint32_t height; /**< pixels */
    VkImageView current;  /**< sampled: this frame's value (rgb; a one-channel image gives r) */
    VkImageView position; /**< sampled: this frame's world position, w > 0 = geometry */
    VkImageView normal;   /**< sampled: this frame's shading normal (the filter's edge test) */
    /** Sampled: the previous frame's position image; may be VK_NULL_HANDLE with reset. */
    VkImageView previous_position;
    /** Sampled: the previous frame's `accumulated`; may be VK_NULL_HANDLE with reset. */
    VkImageView history;
    /** Storage R32G32B32A32_SFLOAT, GENERAL: rgb the mean, a the frames in it (the next frame's history). */
    VkImageView accumulated;
    /** Storage R32G32B32A32_SFLOAT, GENERAL, optional: the filtered picture; without it no filter runs. */
    VkImageView filtered;
    /** Storage R32G32B32A32_SFLOAT, GENERAL: the filter's ping-pong, needed for 2 or more iterations. */
    VkImageView scratch;
    /** Layout of current, position, normal and previous_position: SHADER_READ_ONLY_OPTIMAL (0) or GENERAL. */
    VkImageLayout input_layout;
    /** Layout of history: GENERAL (0) or SHADER_READ_ONLY_OPTIMAL. */
    VkImageLayout history_layout;
} roma_temporal_images;

/** Records the accumulation (one dispatch of 8 x 8 pixel groups) and, with a filtered image,
 * the filter's iterations (one dispatch each, a barrier between).
 *
 * @param effect    the effect.
 * @param cmd       a command buffer of the context's queue family, recording.
 * @param slot      the engine's frame slot, below the effect's frames_in_flight.
 * @param images    the images; copied. They must outlive the recorded work.
 * @param settings  NULL = the zero value (roma_temporal_settings_resolve).
 * @return ROMA_SUCCESS;
 *   ROMA_ERROR_INVALID_ARGUMENT: a NULL effect, cmd or images, a zero width or height, no
 *   current, position, normal or accumulated view, no history or previous_position without
 *   reset, no scratch for 2 or more filter iterations with a filtered image, an output view
 *   (accumulated, filtered, scratch) that is also an input view or another output view, settings
 *   roma_temporal_settings_resolve rejects, a slot not below frames_in_flight, more than 8
 *   records in one frame of a slot;
 *   a Vulkan failure code (roma_result) for a descriptor set.
 * @par Threads
 * Any thread, the effect externally synchronised; cmd externally synchronised. Never submits or
 * waits. */
ROMA_API roma_result roma_temporal_effect_record(roma_temporal_effect *effect, VkCommandBuffer cmd, uint32_t slot,
                                                 const roma_temporal_images *images,
                                                 const roma_temporal_settings *settings);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_TEMPORAL_EFFECT_H */
