/** @file
 * libroma: the Vulkan context every GPU object hangs off.
 *
 * Two modes:
 *  - own device (default): libroma creates a headless instance, device and
 *    queue, preferring a discrete GPU, then integrated, virtual, and finally a
 *    CPU implementation such as Mesa lavapipe;
 *  - external device: desc.external holds the caller's instance, physical
 *    device, device and a queue with graphics + compute. They must outlive the
 *    context. The device must have been created with what
 *    roma_get_device_requirements lists, and external.enabled_features says what
 *    was enabled: a missing feature is refused by name (ROMA_ERROR_MISSING_FEATURE).
 *
 * Requirements (roma_get_device_requirements): Vulkan 1.3 with dynamicRendering,
 * synchronization2, hostQueryReset, bufferDeviceAddress, fragmentStoresAndAtomics;
 * no device extension; a queue family with graphics, compute and timestamps; subgroup
 * arithmetic and ballot in compute shaders; maxUniformBufferRange >= 36,912 bytes.
 * geometryShader is optional: libroma enables it on its own device when offered; no pass
 * needs it (the raster BOM modes use a vertex and a fragment shader).
 *
 * Threads, in Vulkan's terms (each function's "@par Threads" says which applies):
 *  - The context is thread-safe: its functions and the creation of objects on it may be
 *    called from any number of threads at once (a loader thread creating maps and effects
 *    while the render thread records frames).
 *  - Each object made from it (map, effect, pixel list, animator, timer) is externally
 *    synchronised: one thread at a time calls functions on it, its destruction included.
 *    Different objects may be used from different threads at once: worker threads may record
 *    different objects' passes into their own (secondary) command buffers.
 *  - A call that reads another object (an effect's record reads its map and pixel list) may
 *    run beside other calls that only read it, never beside one that changes it (a build,
 *    mesh and instance edits, a destroy).
 *  - Command buffers given to record calls are externally synchronised, as Vulkan requires;
 *    record calls never submit or wait.
 *  - libroma submits to the context's queue only in object creation and in the blocking
 *    convenience calls (roma_map_build, roma_map_trace, downloads, the self-test), waiting on
 *    its own fence. A queue is externally synchronised in Vulkan: an engine that submits to it
 *    from other threads passes roma_context_desc.queue_lock, which libroma takes around each
 *    of its submissions; without it, no other thread submits to the queue during those calls.
 *  - The logger and the allocation callbacks are called from whichever thread calls libroma:
 *    with several threads they must be thread-safe. They may be called while libroma holds
 *    the context's locks, so they must not call libroma.
 *  - The context is destroyed by one thread, after every object, with no call on it running.
 *  `tests/test_threads.c` holds libroma to this, under ThreadSanitizer too (make test-tsan).
 *
 * Environment (read once in roma_context_create, only where the desc is silent):
 *   ROMA_DEVICE=NAME          choose the physical device whose name contains NAME
 *   ROMA_VALIDATION=1         enable VK_LAYER_KHRONOS_validation (own device only)
 *
 * No global state: several contexts may coexist, independent of each other. */
#ifndef ROMA_CONTEXT_H
#define ROMA_CONTEXT_H

#include "roma/api.h"

#include <stdint.h>
#include <vulkan/vulkan.h>

#include "roma/result.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A Vulkan device and queue libroma works on, and the pipelines and caches its objects share
 * (opaque). Thread-safe (see the file comment).
 */
typedef struct roma_context roma_context;

/** Bits of roma_context_desc.flags. The first three apply to libroma's own device only and
 * are ignored when roma_context_desc.external is set. */
typedef enum roma_context_flags {
    /** Enable the Khronos validation layer and route its messages to the logger;
     * creation fails with ROMA_ERROR_MISSING_FEATURE if the layer is absent. */
    ROMA_CONTEXT_VALIDATION = 1u << 0,
    /** Never pick a CPU implementation (lavapipe): ROMA_ERROR_NO_DEVICE if no GPU qualifies. */
    ROMA_CONTEXT_REQUIRE_GPU = 1u << 1,
    /** Validation with synchronization validation (hazards between commands, across
     * submissions); implies ROMA_CONTEXT_VALIDATION. Own device only. */
    ROMA_CONTEXT_SYNC_VALIDATION = 1u << 2,
    /** Trace with the corrected division and square root (roma/trace.glsl's roma_div and
     * roma_sqrt, IEEE's rounding from products and sums rounded to nearest) on CPU devices
     * too, where they are off by default (their division is IEEE's already, and the
     * correction costs time): a test of the correction on any device. Own or external. */
    ROMA_CONTEXT_CORRECTED_DIVISION = 1u << 3
} roma_context_flags;

/** A device the engine created and owns, adopted by roma_context_create (it must outlive the
 * context).
 */
typedef struct roma_external_device {
    VkInstance instance; /**< the caller's instance (Vulkan 1.3) */
    VkPhysicalDevice physical_device; /**< the device's physical device */
    VkDevice device; /**< the caller's device, created with what roma_get_device_requirements lists */
    uint32_t queue_family_index; /**< must support graphics, compute and timestamps */
    VkQueue queue; /**< a queue of queue_family_index: the only one libroma submits to */
    /** The features the device was created with: the VkDeviceCreateInfo pNext chain's
     * VkPhysicalDeviceFeatures2 (followed through pNext: Vulkan11/12/13Features and the
     * single-feature structs are read). Required. */
    const VkPhysicalDeviceFeatures2 *enabled_features;
} roma_external_device;

/** What libroma needs of a device, for an engine that creates its own. The features
 * form a chain inside the struct (features.pNext -> features12 -> features13): use
 * it in place, or OR its VK_TRUE fields into the engine's own chain. */
typedef struct roma_device_requirements {
    uint32_t api_version; /**< VK_API_VERSION_1_3: the instance's apiVersion and the device's */
    VkPhysicalDeviceFeatures2 features; /**< core features to enable; pNext points to features12 */
    /** Vulkan 1.2 features to enable; pNext points to features13. */
    VkPhysicalDeviceVulkan12Features features12;
    VkPhysicalDeviceVulkan13Features features13; /**< Vulkan 1.3 features to enable */
    uint32_t extension_count;      /**< device extensions to enable: none today (0) */
    const char *const *extensions; /**< extension_count device extension names */
    VkQueueFlags queue_flags;      /**< the queue's family: GRAPHICS | COMPUTE, timestampValidBits > 0 */
} roma_device_requirements;

/** Fills out with what libroma needs of a device. Never fails.
 *
 * @param[out] out  the requirements; its pNext chain points into *out itself, so the struct
 *                  must not be copied while the chain is used. NULL: nothing is done.
 * @par Threads
 * Any thread (no state). */
ROMA_API void roma_get_device_requirements(roma_device_requirements *out);

/** The engine's lock of a queue it shares with libroma (roma_context_desc.queue_lock). */
typedef struct roma_queue_lock {
    /** Called with locked = 1 right before, and with 0 right after, each vkQueueSubmit libroma
     * makes on the context's queue (object creation and the blocking convenience calls), from
     * the thread making that call. */
    void (*fn)(int locked, void *user_data);
    void *user_data; /**< passed to fn */
} roma_queue_lock;

/** Settings of roma_context_create; the zero value gives libroma's own headless device. */
typedef struct roma_context_desc {
    uint32_t flags;                       /**< roma_context_flags; unknown bits are rejected */
    /** Case-insensitive substring of the device name; NULL = ROMA_DEVICE or auto (the best
     * kind), "" = auto. Own device only. */
    const char *device_name;
    const roma_external_device *external; /**< NULL = libroma creates its own device */
    roma_logger logger; /**< where messages go; zero: stderr, warnings and errors only */
    /** Used for every Vulkan object libroma creates (and, own device, for the instance
     * and device); NULL = the driver's. Must outlive the context. */
    const VkAllocationCallbacks *allocation_callbacks;
    /** Bytes of device memory (every vkAllocateMemory: device-local and staging) that
     * objects on this context may hold together; 0 = no limit but the device's.
     * Any call that would pass it (a create, a first build, a trace that needs larger
     * staging buffers) fails with ROMA_ERROR_OUT_OF_DEVICE_MEMORY and keeps nothing
     * it allocated (a failed trace also drops its staging buffers, a cache). */
    uint64_t device_memory_budget;
    /** For an engine that submits to the context's queue (its own, or roma_context_queue) from
     * other threads than the ones calling libroma's creation and blocking calls: libroma takes
     * this lock around its submissions, as Vulkan requires of a queue. Zero: the engine makes
     * sure no other thread submits to the queue during those calls. */
    roma_queue_lock queue_lock;
} roma_context_desc;

/** Creates a context: on libroma's own instance and device (external NULL) or on the engine's.
 * Own device: creates the instance (with validation if asked), picks the device (discrete,
 * integrated, virtual, then CPU), creates the device and a queue. Both modes then create
 * a command pool, a fence and a pipeline cache.
 *
 * @param desc  settings; NULL = the zero value (own headless device, stderr logging, no
 *              budget). Copied: only desc->external's handles and allocation_callbacks must
 *              outlive the context.
 * @param[out] out_context  the new context; NULL on failure.
 * @return ROMA_SUCCESS;
 *   ROMA_ERROR_INVALID_ARGUMENT: NULL out_context, unknown flag bits; external: a NULL
 *   handle, a queue family index the device does not have, enabled_features NULL or not a
 *   VkPhysicalDeviceFeatures2;
 *   ROMA_ERROR_NO_VULKAN: no loader, a loader below Vulkan 1.3, or no usable driver;
 *   ROMA_ERROR_NO_DEVICE: no device matches (name, ROMA_CONTEXT_REQUIRE_GPU, requirements);
 *   ROMA_ERROR_MISSING_FEATURE (named in the log): validation asked for but the layer is
 *   absent; external: the queue family lacks graphics, compute or timestamps, or the device
 *   lacks or was created without a required feature;
 *   ROMA_ERROR_OUT_OF_HOST_MEMORY, or a Vulkan failure code (roma_result).
 * @par Threads
 * Any thread. */
ROMA_API roma_result roma_context_create(const roma_context_desc *desc, roma_context **out_context);
/** Waits for libroma's work, then destroys what libroma created: own device, vkDeviceWaitIdle
 * and the device and instance; external device, no wait (libroma's own submissions, in
 * creation calls and the blocking convenience calls, have all finished when those calls
 * return) and the engine's device, instance and queue stay.
 *
 * @param context  the context, or NULL (nothing is done). Every object made from it (maps,
 *                 effects, animators, timers) must have been destroyed before.
 * @par Threads
 * One thread, with no other call on the context running. On an external device it touches
 * neither the queue nor the engine's work, so it may run while other threads submit. */
ROMA_API void roma_context_destroy(roma_context *context);

/** The device a context runs on and what libroma did with it (roma_context_get_info). */
typedef struct roma_context_info {
    char device_name[VK_MAX_PHYSICAL_DEVICE_NAME_SIZE]; /**< the device's name, as Vulkan gives it */
    VkPhysicalDeviceType device_type; /**< CPU (lavapipe) or a GPU kind */
    uint32_t api_version; /**< the device's Vulkan version */
    uint32_t driver_version; /**< the driver's version, vendor-encoded */
    float timestamp_period_ns;  /**< nanoseconds per timestamp tick */
    int validation_enabled; /**< 1 when the Khronos validation layer is on */
    int owns_device;            /**< 0 when running on the caller's device */
    uint64_t device_memory_in_use; /**< bytes libroma's objects on this context hold now */
    uint64_t device_memory_budget; /**< desc.device_memory_budget (0 = none) */
    uint64_t max_allocation_size;  /**< the device's largest single allocation */
    /** vkQueueSubmit and waits (fence, queue idle) libroma made on the context's queue
     * since creation: the blocking convenience calls and object creation make them;
     * record calls never do. */
    uint64_t queue_submits;
    uint64_t queue_waits; /**< waits libroma made on the queue since creation (vkQueueWaitIdle or a fence) */
    /** Compute pipelines compiled so far. Every object of the context shares them: a map
     * of another RES or A, or a second map, compiles none (kept until the context goes). */
    uint32_t pipelines_compiled;
    /** The value libroma gives roma/trace.glsl's ROMA_CORRECTED_DIVISION_CONSTANT_ID in its
     * own pipelines (roma/trace_types.h): VK_TRUE but on CPU devices (there too with
     * ROMA_CONTEXT_CORRECTED_DIVISION). An engine tracing from
     * its own shaders specializes them with it to trace as libroma does. */
    VkBool32 corrected_division;
    /** VK_TRUE where libroma's pipelines declare RoundingModeRTE for 32-bit floats (the device
     * supports it: VkPhysicalDeviceFloatControlsProperties::shaderRoundingModeRTEFloat32). The
     * trace rounds products and sums to nearest only under it, as Vulkan guarantees nothing
     * else; an engine tracing from its own shaders declares it too (GLSL:
     * GL_EXT_spirv_intrinsics, spirv_capability(4467) and spirv_execution_mode(4462, 32)). */
    VkBool32 rounding_mode_rte;
} roma_context_info;

/** The device and counters of a context.
 *
 * @param context        the context.
 * @param[out] out_info  the device and counters now; zeroed on failure.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL argument.
 * @par Threads
 * Any thread (the counters may change meanwhile, in other threads' calls). */
ROMA_API roma_result roma_context_get_info(const roma_context *context, roma_context_info *out_info);

/** Errors reported by the validation layer since creation.
 *
 * @param context  the context; NULL gives 0.
 * @return the number of validation-layer errors (0 when validation is off).
 * @par Threads
 * Any thread while the context lives (an atomic counter). */
ROMA_API uint32_t roma_context_validation_error_count(const roma_context *context);

/** The context's instance (the engine's when adopted).
 *
 * @param context  the context; NULL gives VK_NULL_HANDLE.
 * @return the VkInstance, owned by the context (own device) or by the engine; valid until
 *         roma_context_destroy.
 * @par Threads
 * Any thread while the context lives (reads a field set at creation). */
ROMA_API VkInstance roma_context_instance(const roma_context *context);
/** The context's physical device.
 *
 * @param context  the context; NULL gives VK_NULL_HANDLE.
 * @return the VkPhysicalDevice the context runs on.
 * @par Threads
 * Any thread while the context lives. */
ROMA_API VkPhysicalDevice roma_context_physical_device(const roma_context *context);
/** The context's device.
 *
 * @param context  the context; NULL gives VK_NULL_HANDLE.
 * @return the VkDevice, owned by the context (own device; valid until roma_context_destroy)
 *         or by the engine.
 * @par Threads
 * Any thread while the context lives. */
ROMA_API VkDevice roma_context_device(const roma_context *context);
/** The queue libroma submits to.
 *
 * @param context  the context; NULL gives VK_NULL_HANDLE.
 * @return the VkQueue. Submitting to it from another thread during libroma's blocking calls
 *         is not allowed (Vulkan's external synchronisation of queues).
 * @par Threads
 * Any thread while the context lives. */
ROMA_API VkQueue roma_context_queue(const roma_context *context);
/** That queue's family index.
 *
 * @param context  the context; NULL gives UINT32_MAX.
 * @return the queue family index of roma_context_queue.
 * @par Threads
 * Any thread while the context lives. */
ROMA_API uint32_t roma_context_queue_family(const roma_context *context);

/** Runs a tiny compute shader end to end (upload-free fill, readback, timestamp)
 * to prove the device, the embedded SPIR-V and the timers work. Optional. Submits to the
 * context's queue and waits.
 *
 * @param context          the context.
 * @param[out] out_gpu_ms  GPU time of the fill dispatch in milliseconds; may be NULL. Set
 *                         to 0 first, so 0 on failure.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL context; ROMA_ERROR_VULKAN
 *         when the shader wrote wrong values; ROMA_ERROR_NOT_READY if the timestamps are not
 *         available after the wait; ROMA_ERROR_OUT_OF_HOST_MEMORY, or a Vulkan failure code
 *         (roma_result).
 * @par Threads
 * Any thread; submits to the context's queue (roma_context_desc.queue_lock). */
ROMA_API roma_result roma_context_self_test(roma_context *context, double *out_gpu_ms);

/* --- GPU timers: timestamp queries around named passes --- */

/** GPU timestamps around named scopes of recorded work (opaque).
 *
 * Record begin/end into any command buffer of the context's queue family;
 * read after the work completed. Names are copied. Caveat measured on Mesa
 * lavapipe 22.3: its timestamps cover rasterization but not compute dispatches
 * (they are written before the dispatch runs), so on that device compute passes
 * read as near zero; roma-bench reports host-observed times beside them.
 * A timer is externally synchronised: used by one thread at a time (and by one record call:
 * two maps recording into one timer on two threads at once would race). */
typedef struct roma_gpu_timer roma_gpu_timer;

/** One scope's measured time (roma_gpu_timer_read). */
typedef struct roma_gpu_timing {
    char name[48]; /**< the scope's name */
    double milliseconds; /**< GPU time between the scope's begin and end */
} roma_gpu_timing;

/** A timer of max_scopes scopes (1 to 4096): a query pool of 2 * max_scopes timestamps,
 * reset on the host at creation (so a read before any use gives ROMA_ERROR_NOT_READY).
 *
 * @param context          the context whose device the queries live on; must outlive the timer.
 * @param max_scopes       scopes per use, 1 to 4096.
 * @param[out] out_timer   the new timer; NULL on failure.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for NULL arguments or a count outside
 *         that range; ROMA_ERROR_OUT_OF_HOST_MEMORY; a Vulkan failure code (roma_result).
 * @par Threads
 * Any thread. */
ROMA_API roma_result roma_gpu_timer_create(roma_context *context, uint32_t max_scopes,
                                           roma_gpu_timer **out_timer);
/** Destroys a timer and its query pool.
 *
 * @param timer  the timer, or NULL (nothing is done). No submitted work may still write its
 *               queries.
 * @par Threads
 * Any thread, the timer externally synchronised. */
ROMA_API void roma_gpu_timer_destroy(roma_gpu_timer *timer);
/** Records the query reset into cmd and forgets the scopes begun so far (on the host, now);
 * call once per use, before the first begin.
 *
 * @param timer  the timer; NULL: nothing is done.
 * @param cmd    a command buffer of the context's queue family in the recording state, outside
 *               a render pass; VK_NULL_HANDLE: nothing is done.
 * @par Threads
 * Any thread, the timer externally synchronised; cmd externally synchronised. */
ROMA_API void roma_gpu_timer_reset(roma_gpu_timer *timer, VkCommandBuffer cmd);
/** Opens a scope: records its begin timestamp (ALL_COMMANDS stage) into cmd.
 *
 * @param timer  the timer.
 * @param cmd    a command buffer of the context's queue family in the recording state.
 * @param name   the scope's name, copied (up to 47 bytes); NULL = "".
 * @return the scope index for roma_gpu_timer_end, or UINT32_MAX when max_scopes is exhausted
 *         or timer or cmd is NULL (nothing recorded).
 * @par Threads
 * Any thread, the timer externally synchronised; cmd externally synchronised. */
ROMA_API uint32_t roma_gpu_timer_begin(roma_gpu_timer *timer, VkCommandBuffer cmd, const char *name);
/** Records the end timestamp of scope (from roma_gpu_timer_begin) into cmd.
 *
 * @param timer  the timer; NULL: nothing is done.
 * @param cmd    a command buffer of the context's queue family; VK_NULL_HANDLE: nothing is done.
 * @param scope  from roma_gpu_timer_begin since the last reset; UINT32_MAX, an unknown scope or
 *               one already ended is ignored.
 * @par Threads
 * Any thread, the timer externally synchronised; cmd externally synchronised. */
ROMA_API void roma_gpu_timer_end(roma_gpu_timer *timer, VkCommandBuffer cmd, uint32_t scope);
/** Copies up to *count timings, in the order the scopes were begun; *count becomes the
 * number of scopes recorded. Does not wait.
 *
 * @param timer             the timer.
 * @param[out] out_timings  room for *count timings; may be NULL when *count is 0 (to ask how
 *                          many scopes there are).
 * @param[in,out] count     in: room in out_timings; out: scopes begun since the last reset.
 * @return ROMA_SUCCESS; ROMA_ERROR_NOT_READY if the GPU has not finished them;
 *         ROMA_ERROR_INVALID_ARGUMENT for a NULL timer or count, or NULL out_timings with
 *         *count > 0; ROMA_ERROR_OUT_OF_HOST_MEMORY; a Vulkan failure code (roma_result).
 * @par Threads
 * Any thread, the timer externally synchronised. */
ROMA_API roma_result roma_gpu_timer_read(roma_gpu_timer *timer, roma_gpu_timing *out_timings,
                                         uint32_t *count);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_CONTEXT_H */
