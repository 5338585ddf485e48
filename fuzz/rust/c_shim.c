/*
 * What the differential target asks of the C pair, in terms of bytes only (the Rust side needs
 * no nmea_sentence layout): decode's JSON of a line with options, encode's output for a line of
 * JSON, the framer's items for a stream fed in chunks, an AIS payload's JSON and encoding, and
 * the AIS assembler's events for lines.
 */
#include <stdio.h>
#include <string.h>

#include "nmea.h"
#include "nmea_ais.h"

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

/* Appends an item as "L<len>:<bytes>", "T<len>;" (an overlong line), "F<protocol>:<len>:<bytes>"
   (a binary frame) or "B<protocol>.<error>:<len>:<bytes>" (a rejected one's sync bytes), the
   numbers those of nmea_protocol and nmea_frame_error; 0 when out is full. */
static size_t put_item(const nmea_framed *item, char *out, size_t cap)
{
    char head[32];
    size_t n;
    if (item->protocol != NMEA_LINE) {
        n = item->error == NMEA_FRAME_OK
                ? (size_t)snprintf(head, sizeof head, "F%d:%lu:", (int)item->protocol, (unsigned long)item->len)
                : (size_t)snprintf(head, sizeof head, "B%d.%d:%lu:", (int)item->protocol, (int)item->error,
                                   (unsigned long)item->len);
    } else if (item->ptr == NULL) {
        n = (size_t)snprintf(head, sizeof head, "T%lu;", (unsigned long)item->len);
        if (n > cap)
            return 0;
        memcpy(out, head, n);
        return n;
    }
    else
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
    while (nmea_framer_end(&framer, &item)) {
        if ((n = put_item(&item, out + used, cap - used)) == 0)
            return used;
        used += n;
    }
    return used;
}

/* An AIS payload's JSON (or its error's), then "|", the armored characters and fill bits it
   encodes to (or "|bad_value") when it decodes. */
size_t shim_ais(const char *payload, size_t len, unsigned fill_bits, char *out, size_t cap)
{
    static nmea_ais_message message;
    static nmea_ais_armored armored;
    nmea_ais_error err;
    size_t n;
    if (!nmea_ais_decode(payload, len, fill_bits, &message, &err))
        return nmea_ais_error_json(&err, out, cap);
    n = nmea_ais_json(&message, fill_bits, out, cap);
    if (n >= cap)
        return n;
    if (nmea_ais_encode(&message, &armored, &err))
        return n + (size_t)snprintf(out + n, cap - n, "|%s,%u", armored.chars, (unsigned)armored.fill_bits);
    return n + (size_t)snprintf(out + n, cap - n, "|%s", nmea_ais_error_kind_name(err.kind));
}

typedef struct {
    char *out;
    size_t cap, used;
} events;

/* An event as "<line>,<line>...:P<payload>,<fill bits>;" or ":I<incomplete message>;". */
static void put_event(const nmea_ais_assembled *done, void *context)
{
    events *e = context;
    char message[64];
    size_t i;
    for (i = 0; i < done->n && e->used < e->cap; i++)
        e->used += (size_t)snprintf(e->out + e->used, e->cap - e->used, "%s%lu", i ? "," : "",
                                    (unsigned long)done->lines[i]);
    nmea_ais_incomplete_message(done, message, sizeof message);
    if (e->used < e->cap)
        e->used += done->complete ? (size_t)snprintf(e->out + e->used, e->cap - e->used, ":P%.*s,%u;",
                                                     (int)done->payload_len, done->payload, done->fill_bits)
                                  : (size_t)snprintf(e->out + e->used, e->cap - e->used, ":I%s;", message);
    if (e->used > e->cap)
        e->used = e->cap;
}

/* The assembler's events for the lines of `data` (split on LF, each parsed strictly). */
size_t shim_assemble(const char *data, size_t len, unsigned lifetime, char *out, size_t cap)
{
    static nmea_ais_assembler assembler;
    static const nmea_text no_tags = {NULL, 0};
    const char *line = data, *end = data + len;
    events e;
    e.out = out;
    e.cap = cap;
    e.used = 0;
    nmea_ais_assembler_init(&assembler, lifetime);
    while (line < end) {
        const char *lf = memchr(line, '\n', (size_t)(end - line));
        size_t n = (size_t)((lf ? lf : end) - line);
        nmea_sentence s;
        nmea_error err;
        nmea_ais_fragment fragment;
        bool is_fragment = nmea_parse(&s, line, n, &err) && nmea_ais_fragment_of(&s, &fragment);
        nmea_ais_assembler_feed(&assembler, is_fragment ? &fragment : NULL, is_fragment ? s.tag_blocks : no_tags,
                                put_event, &e);
        line += n + 1;
    }
    nmea_ais_assembler_finish(&assembler, put_event, &e);
    return e.used;
}
