/** @file
 * libroma: fast approximate ray tracing of dynamic triangle scenes with a
 * Ray-aligned Occupancy Map Array. Umbrella header. */
#ifndef ROMA_ROMA_H
#define ROMA_ROMA_H

#include "roma/animation.h"
#include "roma/ao_effect.h"
#include "roma/camera.h"
#include "roma/context.h"
#include "roma/effects.h"
#include "roma/light_effect.h"
#include "roma/map.h"
#include "roma/result.h"
#include "roma/sampling.h"
#include "roma/scene.h"

/** Major version: the shared library's SONAME (libroma.so.0). */
#define ROMA_VERSION_MAJOR 0
/** Minor version. */
#define ROMA_VERSION_MINOR 1
#define ROMA_VERSION_PATCH 0

#endif /**< ROMA_ROMA_H */
