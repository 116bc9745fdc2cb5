#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "app_common.h"
#include "roma/builtin_scenes.h"
#include "roma/gltf.h"

static int has_suffix(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    if (n < m)
        return 0;
    for (size_t i = 0; i < m; ++i) /* case-insensitive: .GLB is a glb */
        if ((s[n - m + i] | 0x20) != (suffix[i] | 0x20))
            return 0;
    return 1;
}

roma_result roma_app_load_scene(const char *arg, const roma_logger *logger, uint32_t camera_index,
                                roma_scene **out_scene)
{
    if (strcmp(arg, "builtin") == 0)
        return roma_scene_create_builtin(NULL, logger, out_scene);
    if (strncmp(arg, "builtin:", 8) == 0) {
        roma_result r = roma_scene_create_builtin(arg + 8, logger, out_scene);
        const char *near = r == ROMA_ERROR_INVALID_ARGUMENT ? roma_app_suggest(arg + 8, roma_builtin_scene_names())
                                                            : NULL;
        if (near)
            fprintf(stderr, "did you mean builtin:%s?\n", near);
        return r;
    }
    /* The causes a person can act on, named before the loader sees the file. */
    struct stat st;
    if (stat(arg, &st) != 0) {
        fprintf(stderr, "cannot open %s: %s\n", arg, strerror(errno));
        return ROMA_ERROR_IO;
    }
    if (S_ISDIR(st.st_mode)) {
        fprintf(stderr, "%s is a directory, not a scene file (a .gltf or .glb file, or builtin:NAME)\n", arg);
        return ROMA_ERROR_IO;
    }
    if (!has_suffix(arg, ".gltf") && !has_suffix(arg, ".glb")) {
        fprintf(stderr, "%s: only glTF 2.0 files (.gltf, .glb) and built-in scenes (builtin:NAME) are supported\n",
                arg);
        return ROMA_ERROR_UNSUPPORTED;
    }
    roma_gltf_desc desc = {.camera_index = camera_index};
    if (logger)
        desc.logger = *logger;
    return roma_scene_load_gltf(arg, &desc, out_scene);
}

int roma_app_make_dir(const char *path)
{
    char buf[4096];
    size_t len = strlen(path);
    if (len == 0 || len >= sizeof buf) {
        errno = ENAMETOOLONG;
        return 0;
    }
    memcpy(buf, path, len + 1);
    for (char *p = buf + 1; *p; ++p) {
        if (*p != '/')
            continue;
        *p = '\0';
        if (mkdir(buf, 0755) != 0 && errno != EEXIST)
            return 0;
        *p = '/';
    }
    if (mkdir(buf, 0755) == 0)
        return 1;
    if (errno != EEXIST)
        return 0;
    struct stat st;
    if (stat(buf, &st) == 0 && !S_ISDIR(st.st_mode)) {
        errno = ENOTDIR;
        return 0;
    }
    return 1;
}
