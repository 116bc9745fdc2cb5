#include "budget.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

const char *budget_default_cache(void)
{
    static char path[4096];
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    int n;
    if (xdg && *xdg)
        n = snprintf(path, sizeof path, "%s/libroma/budget.tsv", xdg);
    else if (home && *home)
        n = snprintf(path, sizeof path, "%s/.cache/libroma/budget.tsv", home);
    else
        return NULL;
    return n > 0 && (size_t)n < sizeof path ? path : NULL;
}

/* Reads the cached times of `key`: lines "key<TAB>preset name<TAB>ms"; the last line of a
 * key and preset wins. A missing file is an empty cache. */
static void read_cache(const char *path, const char *key, budget_choice *c)
{
    FILE *f = path ? fopen(path, "r") : NULL;
    if (!f)
        return;
    char line[8192];
    const size_t key_len = strlen(key);
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, key, key_len) != 0 || line[key_len] != '\t')
            continue;
        char *name = line + key_len + 1, *tab = strchr(name, '\t');
        if (!tab)
            continue;
        *tab = '\0';
        roma_preset p;
        char *end = NULL;
        double ms = strtod(tab + 1, &end);
        if (roma_preset_parse(name, &p) == ROMA_SUCCESS && end != tab + 1 && ms >= 0.0) {
            c->ms[p] = ms;
            c->cached[p] = 1;
        }
    }
    fclose(f);
}

/* Makes the folders above path (mkdir -p of its dirname). */
static void make_parents(const char *path)
{
    char dir[4096];
    if (snprintf(dir, sizeof dir, "%s", path) >= (int)sizeof dir)
        return;
    for (char *s = dir + 1; *s; ++s)
        if (*s == '/') {
            *s = '\0';
            if (mkdir(dir, 0777) != 0 && errno != EEXIST)
                return;
            *s = '/';
        }
}

static void append_cache(const char *path, const char *key, roma_preset p, double ms)
{
    make_parents(path);
    FILE *f = fopen(path, "a");
    int ok = f != NULL;
    if (f) {
        ok = fprintf(f, "%s\t%s\t%.3f\n", key, roma_preset_name(p), ms) > 0;
        ok = fclose(f) == 0 && ok;
    }
    if (!ok)
        fprintf(stderr, "roma-render: cannot keep the measurement in %s: %s\n", path, strerror(errno));
}

int budget_choose(double budget_ms, const char *key, const char *cache_path, budget_measure_fn measure,
                  void *user_data, budget_choice *out)
{
    memset(out, 0, sizeof *out);
    for (unsigned p = 0; p <= ROMA_PRESET_COUNT; ++p)
        out->ms[p] = -1.0;
    out->preset = ROMA_PRESET_LOW;
    read_cache(cache_path, key, out);
    for (unsigned p = ROMA_PRESET_LOW; p <= ROMA_PRESET_COUNT; ++p) {
        if (out->ms[p] < 0.0) {
            out->ms[p] = measure((roma_preset)p, user_data);
            if (out->ms[p] < 0.0)
                return 0;
            if (cache_path)
                append_cache(cache_path, key, (roma_preset)p, out->ms[p]);
        }
        if (out->ms[p] > budget_ms)
            break; /* the next presets are slower still */
        out->preset = (roma_preset)p;
        out->fits = 1;
    }
    return 1;
}
