/* A small streaming JSON writer for the --stats file. */
#ifndef ROMA_STATS_JSON_H
#define ROMA_STATS_JSON_H

#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct roma_json {
    FILE *f;
    int depth;
    int need_comma[32];
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
