/** @file
 * libroma tools (library roma_tools): the built-in scenes the tools and tests use.
 * Generated deterministically in C, without shared state: any thread. */
#ifndef ROMA_BUILTIN_SCENES_H
#define ROMA_BUILTIN_SCENES_H

#include "roma/api.h"

#include "roma/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Names of the built-in scenes, NULL-terminated. The first is the default.
 *
 * @return a static array ("cornell", "blinds", "plates", "cornell_spot", NULL); never NULL,
 *         never to be freed.
 * @par Threads
 * Any thread. */
ROMA_API const char *const *roma_builtin_scene_names(void);

/** Generates a built-in scene (through roma_scene_create).
 *
 * @param name    one of roma_builtin_scene_names(), or NULL for the default ("cornell").
 * @param logger  where messages go; NULL: stderr (warnings and errors).
 * @param[out] out_scene  the new scene, owned by the caller (roma_scene_destroy); NULL on
 *                failure.
 * @return ROMA_SUCCESS; ROMA_ERROR_INVALID_ARGUMENT for a NULL out_scene or an unknown name;
 *         ROMA_ERROR_OUT_OF_HOST_MEMORY.
 * @par Threads
 * Any thread. */
ROMA_API roma_result roma_scene_create_builtin(const char *name, const roma_logger *logger,
                                               roma_scene **out_scene);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_BUILTIN_SCENES_H */
