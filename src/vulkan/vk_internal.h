/* Internal Vulkan plumbing shared by every GPU pass: the context layout,
 * result mapping, buffers, one-shot submissions and compute pipelines. */
#ifndef ROMA_VULKAN_VK_INTERNAL_H
#define ROMA_VULKAN_VK_INTERNAL_H

#include <stdatomic.h>
#include "util/mutex.h"

#include "roma/context.h"
#include "util/log.h"

/* Threads (roma/context.h): every field written after creation is an atomic or is guarded:
 * the pipeline table by `lock` (held while a missing pipeline compiles), memory_in_use by
 * `memory_lock` (so that buffers come and go during a compile), the command pool and fence of
 * the blocking submissions by `submit_lock`, held from roma_begin_one_shot to
 * roma_submit_one_shot. Order: submit_lock before the others; none is held while another is
 * taken but that one. */
struct roma_context {
    roma_mutex lock;        /* plain: the pipeline table */
    roma_mutex memory_lock; /* plain: memory_in_use */
    roma_mutex submit_lock; /* recursive: a blocking call may make a one-shot inside another */
    roma_queue_lock queue_lock; /* desc.queue_lock: the engine's lock of a queue it shares */
    roma_logger logger;
    uint32_t flags;
    int owns_device;
    int validation_enabled;
    atomic_uint validation_errors;
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    VkPhysicalDevice physical_device;
    VkDevice device;
    const VkAllocationCallbacks *allocator; /* desc.allocation_callbacks */
    uint32_t queue_family;
    VkQueue queue;
    VkPhysicalDeviceProperties properties;
    VkPhysicalDeviceMemoryProperties memory_properties;
    VkDeviceSize max_allocation_size; /* VkPhysicalDeviceMaintenance3Properties */
    uint64_t memory_budget;           /* desc.device_memory_budget; 0 = none */
    uint64_t memory_in_use;           /* bytes of every vkAllocateMemory libroma made */
    int has_geometry_shader;
    /* roma/trace.glsl corrects divisions to IEEE's (ROMA_CORRECTED_DIVISION_CONSTANT_ID):
     * on every device but CPU implementations, whose division is IEEE's already, and on
     * those too with ROMA_CONTEXT_CORRECTED_DIVISION. */
    int corrected_division;
    /* libroma's modules declare RoundingModeRTE for 32-bit floats (spirv_rounding.h): where the
     * device supports it (shaderRoundingModeRTEFloat32), unless ROMA_NO_ROUNDING_MODE is set
     * (the benchmark's measure of its cost). */
    int rounding_rte;
    _Atomic uint64_t queue_submits, queue_waits; /* made by libroma on `queue` (roma_context_info) */
    _Atomic uint64_t geometry_versions; /* handed out by the maps' builds (roma_map.geometry_version) */
    /* Compute pipelines shared by every object of the context (compute_pipeline.c): made
     * on first use, kept until the context is destroyed, so a map of another RES or A
     * compiles nothing. The VkPipelineCache serves every pipeline libroma creates. */
    struct roma_shared_pipeline *pipelines;
    uint32_t pipeline_count, pipeline_capacity;
    VkPipelineCache pipeline_cache;
    /* Loop iterations one invocation of a split dispatch plans for (loop_budget.h): UINT32_MAX
     * where the device has no budget. */
    uint32_t loop_plan;
    struct roma_loop_guard *loop_guard; /* ROMA_LOOP_GUARD builds (loop_guard.h) */
    /* The accuracy study's shaders (src/study/study_shaders.h), set by their
     * objects' creation; NULL in an engine's context: the installed library has none of them. */
    const struct roma_spirv_module *_Atomic study_modules;
    /* Host data reaches the shaders through staging copies even where device memory is
     * host-visible, as on a discrete GPU (ROMA_FORCE_STAGING=1: tests those paths anywhere). */
    int force_staging;
    /* For the context's own blocking submissions (uploads, readbacks, self-test). */
    VkCommandPool command_pool;
    VkFence fence;
};

/* Maps a VkResult to a roma_result and logs `what` with the Vulkan code on failure. */
roma_result roma_vk_check(const roma_context *ctx, VkResult vr, const char *what);
const char *roma_vk_result_string(VkResult vr);

/* --- device selection (device_select.c) --- */
typedef struct roma_device_choice {
    VkPhysicalDevice physical_device;
    uint32_t queue_family;
} roma_device_choice;

/* Picks the best device: name filter (substring, case-insensitive) if given, Vulkan 1.3,
 * a graphics+compute queue with timestamps, the required features; GPUs before CPUs. */
roma_result roma_select_device(const roma_context *ctx, const char *name_filter, int require_gpu,
                               roma_device_choice *out);
/* Checks that a device offers what libroma needs; logs each missing piece. */
roma_result roma_check_device_support(const roma_context *ctx, VkPhysicalDevice pd,
                                      int *out_has_geometry_shader);

/* --- GPU timers (gpu_timer.c) --- */
/* The context a timer was created on (NULL for NULL), so that callers can refuse a
 * timer whose query pool belongs to another VkDevice. */
const roma_context *roma_gpu_timer_context(const roma_gpu_timer *timer);

/* --- device memory accounting (vk_util.c) --- */
/* Every vkAllocateMemory goes through these: an allocation larger than the device
 * allows, or past the context's budget, fails with ROMA_ERROR_OUT_OF_DEVICE_MEMORY
 * before Vulkan is asked (drivers need not fail cleanly past maxMemoryAllocationSize). */
roma_result roma_device_memory_reserve(roma_context *ctx, VkDeviceSize bytes, const char *what);
void roma_device_memory_release(roma_context *ctx, VkDeviceSize bytes);

/* --- buffers (vk_util.c) --- */
typedef struct roma_buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    VkDeviceSize size;
    void *mapped; /* non-NULL for host-visible buffers */
    VkDeviceAddress address; /* non-zero when created with SHADER_DEVICE_ADDRESS usage */
    VkDeviceSize allocated;  /* bytes counted against the context's memory use */
    VkMemoryPropertyFlags memory_flags; /* of the memory type it was given */
} roma_buffer;

typedef enum roma_memory_kind {
    ROMA_MEMORY_DEVICE = 0, /* device-local, not mapped */
    ROMA_MEMORY_UPLOAD,     /* host-visible, coherent, mapped: staging */
    ROMA_MEMORY_READBACK,   /* host-visible, cached if possible, mapped */
    /* Device-local; also host-visible, coherent and mapped where the device has such memory
     * (CPU and integrated devices, GPUs with a resizable BAR), else not mapped. */
    ROMA_MEMORY_DEVICE_MAPPED
} roma_memory_kind;

roma_result roma_buffer_create(roma_context *ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                               roma_memory_kind kind, roma_buffer *out);
void roma_buffer_destroy(roma_context *ctx, roma_buffer *buffer);
/* Makes device writes visible to the host for non-coherent readback memory. */
roma_result roma_buffer_invalidate(roma_context *ctx, const roma_buffer *buffer);

/* One global memory barrier (synchronization2). */
void roma_cmd_memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                             VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access);

/* 1D work over a 2D grid of workgroups (each dimension is limited to 65535); the
 * shader computes its index as (group.y * groups.x + group.x) * group_size + local.x. */
void roma_cmd_dispatch_linear(VkCommandBuffer cmd, uint64_t invocations, uint32_t group_size);

/* --- one-shot submissions on the context's queue (blocking) --- */
roma_result roma_begin_one_shot(roma_context *ctx, VkCommandBuffer *out_cmd);
/* Ends, submits, waits and frees the command buffer (also on failure). */
roma_result roma_submit_one_shot(roma_context *ctx, VkCommandBuffer cmd);

/* --- compute pipelines from embedded SPIR-V (compute_pipeline.c) --- */
typedef struct roma_compute_pipeline {
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline pipeline;
} roma_compute_pipeline;

/* Storage buffers at bindings 0..storage_buffer_count-1, one push-constant range. */
roma_result roma_compute_pipeline_create(roma_context *ctx, const char *module_name,
                                         uint32_t storage_buffer_count, uint32_t push_size,
                                         roma_compute_pipeline *out);
/* The same with binding i of type types[i] (storage, uniform, texel buffers). */
roma_result roma_compute_pipeline_create_typed(roma_context *ctx, const char *module_name,
                                               const VkDescriptorType *types, uint32_t binding_count,
                                               uint32_t push_size, roma_compute_pipeline *out);
/* The same with specialization constants 0..constant_count-1 (uint32 each): a branch on
 * a constant is compiled out, where a branch on a push constant costs both sides on
 * devices that run shaders as predicated SIMD (CPU implementations). */
roma_result roma_compute_pipeline_create_spec(roma_context *ctx, const char *module_name,
                                              const VkDescriptorType *types, uint32_t binding_count,
                                              uint32_t push_size, const uint32_t *constants, uint32_t constant_count,
                                              roma_compute_pipeline *out);
/* The same with roma_specialization_make's flags (part of what the context shares by). */
roma_result roma_compute_pipeline_create_flags(roma_context *ctx, const char *module_name,
                                               const VkDescriptorType *types, uint32_t binding_count,
                                               uint32_t push_size, const uint32_t *constants,
                                               uint32_t constant_count, uint32_t flags, roma_compute_pipeline *out);
/* Specialization of a shader of module `module`: constants 0..count-1 (uint32 each, at most
 * ROMA_MAX_SPEC_CONSTANTS), then roma/trace.glsl's ROMA_CORRECTED_DIVISION_CONSTANT_ID with
 * the context's choice (ignored by shaders that do not include it) and, in a loop-guard
 * build, the guard's constants (loop_guard.h). Every pipeline libroma creates goes through it. */
#define ROMA_MAX_SPEC_CONSTANTS 16u
typedef struct roma_specialization {
    VkSpecializationMapEntry entries[ROMA_MAX_SPEC_CONSTANTS + 5];
    uint32_t values[ROMA_MAX_SPEC_CONSTANTS + 5];
    VkSpecializationInfo info;
} roma_specialization;
void roma_specialization_make(const roma_context *ctx, const char *module, const uint32_t *constants,
                              uint32_t count, uint32_t flags, roma_specialization *out);
/* roma_specialization_make's flags: the pipeline traces maps of several cascade levels
 * (ROMA_CASCADES_CONSTANT_ID true; without it the cascade code is compiled out). */
#define ROMA_PIPELINE_CASCADES 1u
/* One pipeline of module_name on layout, specialized as above; not shared (the caller owns
 * and destroys it). */
roma_result roma_compute_pipeline_make(roma_context *ctx, const char *module_name, VkPipelineLayout layout,
                                       const uint32_t *constants, uint32_t constant_count, VkPipeline *out);
/* The same with roma_specialization_make's flags. */
roma_result roma_compute_pipeline_make_flags(roma_context *ctx, const char *module_name, VkPipelineLayout layout,
                                             const uint32_t *constants, uint32_t constant_count, uint32_t flags,
                                             VkPipeline *out);
/* Pipelines are shared by the whole context (made once per module, bindings, push size
 * and constants): destroy only forgets the caller's copy. */
void roma_compute_pipeline_destroy(roma_context *ctx, roma_compute_pipeline *pipeline);
/* The context's shared pipelines, at context destruction. */
void roma_shared_pipelines_destroy(roma_context *ctx);

/* The bindings of roma/trace_descriptors.glsl (set 0 of every pass that traces a map):
 * the maps as a uniform texel buffer, the parameters as a uniform buffer. */
extern const VkDescriptorType roma_trace_binding_types[2];

/* --- descriptor sets (descriptors.c): one set for a pipeline's layout, from a pool of its
 * own, written once when the buffers it names are created (never while in use). --- */
typedef struct roma_descriptor_set {
    VkDescriptorPool pool;
    VkDescriptorSet set;
    VkDescriptorSetLayout layout; /* only for sets made with a layout of their own */
} roma_descriptor_set;

/* A compute-stage set layout with binding i of type types[i] (at most 16). */
roma_result roma_descriptor_layout_create(roma_context *ctx, const VkDescriptorType *types, uint32_t binding_count,
                                          VkDescriptorSetLayout *out);
roma_result roma_descriptor_set_create(roma_context *ctx, const roma_compute_pipeline *pipeline,
                                       const VkDescriptorType *types, uint32_t binding_count,
                                       roma_descriptor_set *out);
/* The same with a layout of its own (compute stage, binding i of type types[i]), for sets
 * that several pipelines, the caller's among them, bind. */
roma_result roma_descriptor_set_create_with_layout(roma_context *ctx, const VkDescriptorType *types,
                                                   uint32_t binding_count, roma_descriptor_set *out);
void roma_descriptor_set_destroy(roma_context *ctx, roma_descriptor_set *set);
/* A whole buffer (storage or uniform) or a buffer view (texel buffers) at binding. */
void roma_descriptor_write_buffer(roma_context *ctx, roma_descriptor_set *set, uint32_t binding,
                                  VkDescriptorType type, VkBuffer buffer);
void roma_descriptor_write_view(roma_context *ctx, roma_descriptor_set *set, uint32_t binding,
                                VkDescriptorType type, VkBufferView view);
/* A texel-buffer view of a whole buffer (usage must include the texel-buffer bit). */
roma_result roma_buffer_view_create(roma_context *ctx, VkBuffer buffer, VkFormat format, VkBufferView *out);

/* --- shader modules and graphics pipelines (graphics_pipeline.c) --- */
roma_result roma_shader_module_create(roma_context *ctx, const char *module_name, VkShaderModule *out);
/* A layout with one push-constant range for `stages` (none when push_size is 0) and no sets. */
roma_result roma_push_layout_create(roma_context *ctx, VkShaderStageFlags stages, uint32_t push_size,
                                    VkPipelineLayout *out);

typedef struct roma_graphics_pipeline_desc {
    VkShaderModule vert;
    VkShaderModule frag;        /* VK_NULL_HANDLE: depth-only pipeline */
    const char *frag_name;      /* the embedded module frag was made from (its specialization) */
    VkPipelineLayout layout;
    VkFormat depth_format;      /* VK_FORMAT_UNDEFINED: no depth attachment, no depth test */
    int depth_write;
    VkCompareOp depth_compare;
    const char *label;          /* named in the error message */
} roma_graphics_pipeline_desc;

/* Vertex pulling (no vertex input), triangle lists, no culling, dynamic viewport and
 * scissor, one sample, no colour attachments. */
roma_result roma_graphics_pipeline_create(roma_context *ctx, const roma_graphics_pipeline_desc *desc,
                                          VkPipeline *out);

/* Looks an embedded module up by name ("fill_u32.comp"): libroma's, then the tools' second
 * table where the context was given it (study_modules); NULL if absent. */
const struct roma_spirv_module *roma_find_spirv(const roma_context *ctx, const char *name);

#endif /* ROMA_VULKAN_VK_INTERNAL_H */
