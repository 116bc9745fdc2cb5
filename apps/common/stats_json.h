/* The tools' --stats and --json files, written in the order the tools know their figures:
 * a thin builder over cJSON (Debian's libcjson), printed when the top-level scope closes. */
#ifndef ROMA_STATS_JSON_H
#define ROMA_STATS_JSON_H

#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

struct cJSON;

#define ROMA_JSON_MAX_DEPTH 32

typedef struct roma_json {
    FILE *f;                                  /* where the document goes; set before the first call */
    int depth;                                /* open scopes */
    struct cJSON *scopes[ROMA_JSON_MAX_DEPTH]; /* scopes[0] is the document */
    int failed;                               /* out of memory or too deep: nothing was written */
    int too_deep;                             /* scopes opened past ROMA_JSON_MAX_DEPTH, still open */
} roma_json;

void roma_json_begin_object(roma_json *j, const char *key); /* key NULL at top level / in arrays */
void roma_json_end_object(roma_json *j);
void roma_json_begin_array(roma_json *j, const char *key);
void roma_json_end_array(roma_json *j);
void roma_json_string(roma_json *j, const char *key, const char *value);
void roma_json_number(roma_json *j, const char *key, double value); /* non-finite -> null */
void roma_json_int(roma_json *j, const char *key, long long value);

#ifdef __cplusplus
}
#endif

#endif /* ROMA_STATS_JSON_H */
