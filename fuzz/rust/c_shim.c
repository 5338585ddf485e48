/*
 * What the differential target asks of the C pair, in terms of bytes only (the Rust side needs
 * no nmea_sentence layout): decode's JSON of a line with options, encode's output for a line of
 * JSON, and the framer's items for a stream fed in chunks.
 */
#include <stdio.h>
#include <string.h>

#include "nmea.h"

#define INPUT_MAX 4096

static nmea_problems problems;
static char scratch[2 * INPUT_MAX + sizeof(nmea_problems) + 16];

size_t shim_decode(const char *line, size_t len, int values, int lenient, int required, char *out, size_t cap)
{
    nmea_options options;
    options.lenient = lenient != 0;
    options.require_checksum = required != 0;
    options.problems = &problems;
    options.strict = false;
    return nmea_decode_json_ex(line, len, values != 0, &options, out, cap);
}

/* What `nmea-c encode` prints for a line of JSON, or (size_t)-1 when it skips a failure line. */
size_t shim_encode(const char *json, size_t len, char *out, size_t cap)
{
    nmea_sentence s;
    nmea_error err;
    if (len > INPUT_MAX)
        return 0;
    if (nmea_json_is_failure(json, len))
        return (size_t)-1;
    if (nmea_from_json(&s, json, len, scratch, sizeof scratch, &err))
        return nmea_serialize(&s, out, cap);
    return nmea_error_to_json(&err, out, cap);
}

/* Appends an item as "L<len>:<bytes>" or "T<len>;" (an overlong line); 0 when out is full. */
static size_t put_item(const nmea_framed *item, char *out, size_t cap)
{
    char head[32];
    size_t n;
    if (item->ptr == NULL) {
        n = (size_t)snprintf(head, sizeof head, "T%lu;", (unsigned long)item->len);
        if (n > cap)
            return 0;
        memcpy(out, head, n);
        return n;
    }
    n = (size_t)snprintf(head, sizeof head, "L%lu:", (unsigned long)item->len);
    if (n + item->len > cap)
        return 0;
    memcpy(out, head, n);
    memcpy(out + n, item->ptr, item->len);
    return n + item->len;
}

/* The framer's items for `data` fed in chunks of `chunk` bytes, as put_item writes them. */
size_t shim_frame(const char *data, size_t len, size_t chunk, char *out, size_t cap)
{
    nmea_framer framer;
    nmea_framed item;
    size_t at = 0, used = 0, n;
    nmea_framer_init(&framer);
    while (at < len) {
        const char *p = data + at;
        size_t left = len - at < chunk ? len - at : chunk;
        at += left;
        while (nmea_framer_push(&framer, &p, &left, &item)) {
            if ((n = put_item(&item, out + used, cap - used)) == 0)
                return used;
            used += n;
        }
    }
    if (nmea_framer_end(&framer, &item) && (n = put_item(&item, out + used, cap - used)) != 0)
        used += n;
    return used;
}
