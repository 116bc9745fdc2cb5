/** @file
 * libroma tools (library roma_tools): the built-in scenes the tools and tests use. */
#ifndef ROMA_BUILTIN_SCENES_H
#define ROMA_BUILTIN_SCENES_H

#include "roma/api.h"

#include "roma/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Names of the built-in scenes, NULL-terminated. The first is the default. */
ROMA_API const char *const *roma_builtin_scene_names(void);

/** name: one of roma_builtin_scene_names(), or NULL for the default ("cornell"). */
ROMA_API roma_result roma_scene_create_builtin(const char *name, const roma_logger *logger,
                                               roma_scene **out_scene);

#ifdef __cplusplus
}
#endif

#endif /**< ROMA_BUILTIN_SCENES_H */
