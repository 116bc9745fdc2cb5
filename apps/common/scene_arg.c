#include <errno.h>
#include <string.h>
#include <sys/stat.h>

#include "app_common.h"
#include "roma/builtin_scenes.h"
#include "roma/gltf.h"

roma_result roma_app_load_scene(const char *arg, const roma_logger *logger, roma_scene **out_scene)
{
    if (strcmp(arg, "builtin") == 0)
        return roma_scene_create_builtin(NULL, logger, out_scene);
    if (strncmp(arg, "builtin:", 8) == 0)
        return roma_scene_create_builtin(arg + 8, logger, out_scene);
    roma_gltf_desc desc = {0};
    if (logger)
        desc.logger = *logger;
    return roma_scene_load_gltf(arg, &desc, out_scene);
}

int roma_app_make_dir(const char *path)
{
    char buf[4096];
    size_t len = strlen(path);
    if (len == 0 || len >= sizeof buf)
        return 0;
    memcpy(buf, path, len + 1);
    for (char *p = buf + 1; *p; ++p) {
        if (*p != '/')
            continue;
        *p = '\0';
        if (mkdir(buf, 0755) != 0 && errno != EEXIST)
            return 0;
        *p = '/';
    }
    return mkdir(buf, 0755) == 0 || errno == EEXIST;
}
