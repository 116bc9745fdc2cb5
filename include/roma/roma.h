/** @file
 * libroma: fast approximate ray tracing of dynamic triangle scenes with a
 * Ray-aligned Occupancy Map Array. Umbrella header. */

/** @mainpage libroma
 *
 * libroma traces rays approximately, and fast, through dynamic triangle scenes in Vulkan
 * compute: every frame it voxelizes the scene into a binary grid and resamples it into
 * A x A occupancy maps aligned with candidate directions (a Ray-aligned Occupancy Map
 * Array, ROMA); a ray is then one texel fetch (snapped) or a short walk (un-snapped).
 *
 * Headers (roma/roma.h includes all but roma/gltf.h, roma/image.h and roma/builtin_scenes.h):
 *  - roma/result.h: result codes and the log callback;
 *  - roma/context.h: the Vulkan context (own or the engine's device) and GPU timers;
 *  - roma/scene.h, roma/gltf.h: immutable triangle scenes, from arrays or glTF files
 *    (library roma_gltf);
 *  - roma/map.h: the map array, its build, instances, and batch traces;
 *  - roma/presets.h: named quality presets (RES and A) from the measured accuracy-time front;
 *  - roma/trace_types.h: what the C API and the engine's shaders (roma/trace.glsl) share;
 *  - roma/ao_effect.h, roma/light_effect.h, roma/gi_effect.h: AO, shadowed direct light (many
 *    lights too) and one-bounce GI on the engine's G-buffer, recorded into its command buffers;
 *  - roma/temporal_effect.h: their accumulation over frames (reprojected) and a spatial filter;
 *  - roma/animation.h: glTF skins and node animations played on the GPU;
 *  - roma/effects.h: the plan of passes a frame of effects runs;
 *  - roma/camera.h, roma/sampling.h: camera and sample sequences shared with the reference;
 *  - roma/image.h, roma/builtin_scenes.h: images, metrics and test scenes (roma_tools).
 *
 * Threads (roma/context.h): a context may be used from any number of threads; each object made
 * from it (map, effect, pixel list, animator, timer) by one thread at a time, different objects
 * from different threads at once. Scenes are immutable and may be read from any number of
 * threads. */
#ifndef ROMA_ROMA_H
#define ROMA_ROMA_H

#include "roma/animation.h"
#include "roma/ao_effect.h"
#include "roma/camera.h"
#include "roma/context.h"
#include "roma/effects.h"
#include "roma/gi_effect.h"
#include "roma/light_effect.h"
#include "roma/map.h"
#include "roma/pixel_list.h"
#include "roma/presets.h"
#include "roma/result.h"
#include "roma/sampling.h"
#include "roma/scene.h"
#include "roma/temporal_effect.h"

/** Major version: the shared library's SONAME (libroma.so.0). */
#define ROMA_VERSION_MAJOR 0
/** Minor version. */
#define ROMA_VERSION_MINOR 1
/** Patch version. */
#define ROMA_VERSION_PATCH 0

#endif /* ROMA_ROMA_H */
