/* The hardware ray-tracing baseline of the ROMA paper's comparison (its HWRT column): the
 * same rays as ROMA and Embree traced by the driver's ray-tracing pipeline
 * (VK_KHR_ray_tracing_pipeline) through acceleration structures of the scene
 * (VK_KHR_acceleration_structure) that are built again every frame, as a dynamic scene needs.
 *
 * The extensions live on a device the tools create the way an engine creates its own
 * (roma_get_device_requirements plus the ray-tracing extensions), and libroma runs on that
 * device through roma_context_desc.external, so ROMA and the hardware trace the same buffers
 * on one device. Where no device offers the extensions (lavapipe), roma_hwrt_device_create
 * says why and the tools skip the rows. Part of the study library: never installed. */
#ifndef ROMA_STUDY_HW_RAY_TRACING_H
#define ROMA_STUDY_HW_RAY_TRACING_H

#include <stddef.h>
#include <stdint.h>
#include <vulkan/vulkan.h>

#include "roma/camera.h"
#include "roma/context.h"
#include "roma/scene.h"

/* An instance and device with the ray-tracing extensions (opaque). */
typedef struct roma_hwrt_device roma_hwrt_device;

/* Creates an instance (with the validation layer when validation is non-zero) and a device
 * with what libroma needs and the ray-tracing extensions and features (and, where offered,
 * VK_KHR_pipeline_executable_properties): the first device whose
 * name contains device_name (NULL or "": any) that offers them, GPUs before others.
 * ROMA_ERROR_MISSING_FEATURE, with why filled (e.g. "llvmpipe (LLVM 15.0.6, 256 bits) offers
 * no VK_KHR_ray_tracing_pipeline"), where none does; ROMA_ERROR_NO_VULKAN without a loader
 * or driver. On failure nothing is left and *out is NULL. */
roma_result roma_hwrt_device_create(const char *device_name, int validation, roma_hwrt_device **out, char *why,
                                    size_t why_size);
/* Accepts NULL (returns 0). Every context and object on the device must have been destroyed
 * before. Returns the validation errors of the device's whole life, its destruction included. */
uint32_t roma_hwrt_device_destroy(roma_hwrt_device *device);
/* What roma_context_desc.external takes; valid while the device lives. */
const roma_external_device *roma_hwrt_device_external(const roma_hwrt_device *device);
/* Whether the device was created with VK_KHR_pipeline_executable_properties (enabled where
 * offered: pipelines created with VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR report their
 * registers, spills and the like). */
int roma_hwrt_device_has_pipeline_statistics(const roma_hwrt_device *device);

/* The scene's acceleration structures, the ray-tracing pipeline and its shader binding table
 * (opaque). */
typedef struct roma_hwrt roma_hwrt;

/* Uploads the scene's triangles, builds its acceleration structures (one bottom level of
 * every triangle, one top level of one instance) and creates the pipeline. context must
 * run on device (roma_hwrt_device_external). */
roma_result roma_hwrt_create(roma_context *context, const roma_hwrt_device *device, const roma_scene *scene,
                             roma_hwrt **out);
/* Accepts NULL. The caller makes sure no submitted work still uses it. */
void roma_hwrt_destroy(roma_hwrt *hwrt);

/* Records the build of both acceleration structures from the uploaded triangles, as a
 * dynamic scene's frame does (the bottom level built for a fast build, then the top level),
 * after earlier traces (a barrier from the ray-tracing shaders) and ending with a barrier to
 * them. */
void roma_hwrt_record_build(roma_hwrt *hwrt, VkCommandBuffer cmd);

/* Records a trace of count roma_ray at rays into count roma_hit at hits (both buffers with
 * SHADER_DEVICE_ADDRESS usage, as roma_map_record_trace's): closest = 0 ends each ray at its
 * first hit without a hit shader (t = INFINITY, as ROMA's any-hit), 1 finds the closest (t its
 * distance). The
 * caller orders its writes of rays before and its reads of hits after (ray-tracing shader
 * stage). Rays start at max(tmin, 0): hardware rays have no negative tmin. */
void roma_hwrt_record_trace(roma_hwrt *hwrt, VkCommandBuffer cmd, VkDeviceAddress rays, VkDeviceAddress hits,
                            uint32_t count, int closest);

/* The most layers roma_hwrt_record_depth_layers keeps (hwrt_depth_payload.glsl). */
#define ROMA_HWRT_MAX_DEPTH_LAYERS 8u

/* Records the ray-traced stochastic depth map of the seed paper (Brüll and Grosch, after
 * Vardis et al.): one view ray per pixel of camera's width x height image (pixel centres, the
 * near plane's depth on), every surface it passes offered to an any-hit shader that keeps a
 * reservoir of `layers` of them (the nearer on a tie of slots; after 8 surfaces only nearer
 * ones are offered); each kept surface written as a roma_gbuffer_pixel into pixels, layer
 * after layer (width * height each; an empty slot as a background pixel), with seed drawing
 * the reservoir. pixels needs SHADER_DEVICE_ADDRESS usage. The caller builds the structures
 * first (roma_hwrt_record_build) and orders the writes (ray-tracing shader stage) before its
 * reads, and earlier reads of pixels before them. ROMA_ERROR_INVALID_ARGUMENT for a bad
 * camera, size or layers (1 .. ROMA_HWRT_MAX_DEPTH_LAYERS); ROMA_ERROR_UNSUPPORTED for more
 * pixels than one launch takes. */
roma_result roma_hwrt_record_depth_layers(roma_hwrt *hwrt, VkCommandBuffer cmd, const roma_camera *camera,
                                          float near_plane, VkDeviceAddress pixels, uint32_t width, uint32_t height,
                                          uint32_t layers, uint32_t seed);
/* Whether one launch takes a width x height depth map (what roma_hwrt_record_depth_layers
 * checks first). */
int roma_hwrt_depth_layers_fit(const roma_hwrt *hwrt, uint32_t width, uint32_t height);

#endif /* ROMA_STUDY_HW_RAY_TRACING_H */
