#include "stats_json.h"

#include <math.h>

static void write_escaped(FILE *f, const char *s)
{
    fputc('"', f);
    for (; s && *s; ++s) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

static void prefix(roma_json *j, const char *key)
{
    if (j->need_comma[j->depth])
        fputc(',', j->f);
    j->need_comma[j->depth] = 1;
    fputc('\n', j->f);
    for (int i = 0; i < j->depth; ++i)
        fputs("  ", j->f);
    if (key) {
        write_escaped(j->f, key);
        fputs(": ", j->f);
    }
}

static void open_scope(roma_json *j, const char *key, char c)
{
    if (j->depth > 0 || j->need_comma[0])
        prefix(j, key);
    fputc(c, j->f);
    if (j->depth < 31)
        j->need_comma[++j->depth] = 0;
}

static void close_scope(roma_json *j, char c)
{
    int had_items = j->need_comma[j->depth];
    if (j->depth > 0)
        --j->depth;
    if (had_items) {
        fputc('\n', j->f);
        for (int i = 0; i < j->depth; ++i)
            fputs("  ", j->f);
    }
    fputc(c, j->f);
    if (j->depth == 0)
        fputc('\n', j->f);
}

void roma_json_begin_object(roma_json *j, const char *key) { open_scope(j, key, '{'); }
void roma_json_end_object(roma_json *j) { close_scope(j, '}'); }
void roma_json_begin_array(roma_json *j, const char *key) { open_scope(j, key, '['); }
void roma_json_end_array(roma_json *j) { close_scope(j, ']'); }

void roma_json_string(roma_json *j, const char *key, const char *value)
{
    prefix(j, key);
    write_escaped(j->f, value);
}

void roma_json_number(roma_json *j, const char *key, double value)
{
    prefix(j, key);
    if (isfinite(value))
        fprintf(j->f, "%.9g", value);
    else
        fputs("null", j->f);
}

void roma_json_int(roma_json *j, const char *key, long long value)
{
    prefix(j, key);
    fprintf(j->f, "%lld", value);
}
