#include "stats_json.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>

/* Adds item under key to the innermost open scope (or makes it the document). */
static void add(roma_json *j, const char *key, cJSON *item)
{
    if (!item) {
        j->failed = 1;
        return;
    }
    if (j->depth == 0) {
        if (j->scopes[0]) { /* a second document: not a use the tools make */
            cJSON_Delete(item);
            j->failed = 1;
            return;
        }
        j->scopes[0] = item;
        return;
    }
    cJSON *parent = j->scopes[j->depth - 1];
    cJSON_bool added = cJSON_IsArray(parent) || !key ? cJSON_AddItemToArray(parent, item)
                                                     : cJSON_AddItemToObject(parent, key, item);
    if (!added) {
        cJSON_Delete(item);
        j->failed = 1;
    }
}

static void open_scope(roma_json *j, const char *key, cJSON *scope)
{
    if (j->depth >= ROMA_JSON_MAX_DEPTH) { /* counted apart, so that the closes stay paired */
        cJSON_Delete(scope);
        j->failed = 1;
        ++j->too_deep;
        return;
    }
    add(j, key, scope);
    /* After a failure the scope still counts, so that the closes stay paired. */
    j->scopes[j->depth] = j->failed ? NULL : scope;
    ++j->depth;
}

static void close_scope(roma_json *j)
{
    if (j->too_deep > 0) {
        --j->too_deep;
        return;
    }
    if (j->depth == 0) {
        j->failed = 1;
        return;
    }
    if (--j->depth > 0)
        return;
    /* The document is complete: print it, or nothing when a part of it is missing. */
    char *text = j->failed ? NULL : cJSON_Print(j->scopes[0]);
    if (text) {
        fputs(text, j->f);
        fputc('\n', j->f);
        cJSON_free(text);
    } else {
        j->failed = 1;
    }
    cJSON_Delete(j->scopes[0]);
    j->scopes[0] = NULL;
}

void roma_json_begin_object(roma_json *j, const char *key) { open_scope(j, key, cJSON_CreateObject()); }
void roma_json_end_object(roma_json *j) { close_scope(j); }
void roma_json_begin_array(roma_json *j, const char *key) { open_scope(j, key, cJSON_CreateArray()); }
void roma_json_end_array(roma_json *j) { close_scope(j); }

void roma_json_string(roma_json *j, const char *key, const char *value)
{
    add(j, key, cJSON_CreateString(value ? value : ""));
}

void roma_json_number(roma_json *j, const char *key, double value)
{
    if (!isfinite(value)) {
        add(j, key, cJSON_CreateNull());
        return;
    }
    /* Nine significant digits, as many as a float holds: 0.1f prints as 0.100000001, not
       with the seventeen digits of its double. */
    char text[32];
    snprintf(text, sizeof text, "%.9g", value);
    add(j, key, cJSON_CreateNumber(strtod(text, NULL)));
}

void roma_json_int(roma_json *j, const char *key, long long value)
{
    /* cJSON keeps numbers as doubles: exact up to 2^53, far above any count or byte size here. */
    add(j, key, cJSON_CreateNumber((double)value));
}
