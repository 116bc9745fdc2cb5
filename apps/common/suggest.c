/* "Did you mean ...?": the closest of a list of names to what was typed (edit distance). */
#include <string.h>

#include "app_common.h"

static size_t edit_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    if (la > 63 || lb > 63)
        return (size_t)-1;
    size_t row[64];
    for (size_t j = 0; j <= lb; ++j)
        row[j] = j;
    for (size_t i = 1; i <= la; ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= lb; ++j) {
            size_t up = row[j];
            size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            size_t best = diagonal + cost;
            if (row[j] + 1 < best)
                best = row[j] + 1;
            if (row[j - 1] + 1 < best)
                best = row[j - 1] + 1;
            row[j] = best;
            diagonal = up;
        }
    }
    return row[lb];
}

const char *roma_app_suggest(const char *typed, const char *const *names)
{
    const char *best = NULL;
    size_t best_distance = (size_t)-1;
    for (const char *const *n = names; typed && *n; ++n) {
        size_t d = edit_distance(typed, *n);
        if (d < best_distance)
            best = *n, best_distance = d;
    }
    /* Only close calls: at most a third of the name, and at most 3 edits. */
    if (!best || best_distance > 3 || best_distance * 3 > strlen(best))
        return NULL;
    return best;
}
