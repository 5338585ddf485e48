/*
 * nmea-c: `decode` NMEA lines to JSON, `encode` that JSON back to sentences, `stream` a byte
 * stream that may hold garbage, cut lines or sentences run together (hand-written:
 * runtime/c/tool.c). Same behaviour, byte for byte, as nmea-py and nmea-rs; see docs/json.md.
 *
 *     nmea-c decode [--values] [--lenient] [--require-checksum] [--strict]   stdin: NMEA lines
 *     nmea-c stream [--values] [--lenient] [--require-checksum] [--strict]   stdin: any bytes
 *     nmea-c encode                                               stdin: decode's output
 *     nmea-c fixes                                                stdin: NMEA lines
 *
 * decode splits its input on LF and drops one CR before it; stream frames it with nmea_framer.
 * fixes prints one JSON object per epoch, the fix its sentences make (Python's Fix.to_dict);
 * decode and stream print one JSON object per line; a line longer than NMEA_MAX_LINE is counted, not stored.
 * encode holds one line at a time (up to ENCODE_MAX bytes).
 */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "nmea.h"

#define CHUNK 65536
#define DECODE_MAX (NMEA_MAX_LINE + 1) /* a line and its CR */
#define ENCODE_MAX (1u << 20)

/* The tool's buffers: a line being assembled across reads, the output being gathered. */
static char input[CHUNK];
static char pending[ENCODE_MAX];
/* a text command needs its texts twice, a sentence with problems room for them too */
static char scratch[2 * ENCODE_MAX + sizeof(nmea_problems) + 16];
static char output[4 * ENCODE_MAX + NMEA_JSON_MAX + 1];

typedef enum { TOOL_DECODE, TOOL_ENCODE, TOOL_FIXES } tool_verb;

typedef struct {
    tool_verb verb;
    bool values;
    nmea_options options;
    nmea_problems problems; /* of the line decoded last */
    size_t out_len;
} tool;

static void flush(tool *t)
{
    fwrite(output, 1, t->out_len, stdout);
    t->out_len = 0;
}

/* Room for one more output line of up to `need` bytes. */
static char *room(tool *t, size_t need)
{
    if (sizeof output - t->out_len < need)
        flush(t);
    return output + t->out_len;
}

static void emit(tool *t, size_t n)
{
    output[t->out_len + n] = '\n';
    t->out_len += n + 1;
}

#ifdef NMEA_TEST_HOOKS
static void disagree(const char *what, const char *line, size_t len)
{
    fprintf(stderr, "nmea-c: the fast path %s unlike the general path: %.*s\n", what, (int)len, line);
    abort();
}

/* A test build checks that the fast paths of nmea_parse_ex and nmea_serialize decode and write
   every line as their general paths do (the tests run it over every real log and edge case). */
static void check_general(const tool *t, const char *line, size_t len, const char *json, size_t n)
{
    static char general[NMEA_JSON_MAX], fast[NMEA_JSON_MAX];
    nmea_sentence s;
    nmea_error err;
    bool parsed = nmea_parse_general(&s, line, len, &t->options, &err);
    size_t m = parsed ? nmea_to_json(&s, t->values, general, sizeof general)
                      : nmea_error_to_json(&err, general, sizeof general);
    if (m != n || memcmp(general, json, n) != 0)
        disagree("decodes this line", line, len);
    if (parsed && (nmea_serialize(&s, fast, sizeof fast) != nmea_serialize_general(&s, general, sizeof general)
                   || strcmp(fast, general) != 0))
        disagree("writes this line", line, len);
}

/* The same for a sentence rebuilt from JSON, written into `out` (`cap` bytes, `n` of them). */
static void check_written(const nmea_sentence *s, const char *out, size_t cap, size_t n, const char *line, size_t len)
{
    static char general[sizeof output];
    if (nmea_serialize_general(s, general, cap) != n || memcmp(general, out, n) != 0)
        disagree("writes this JSON", line, len);
}
#endif

static void decode_line(tool *t, const char *line, size_t len)
{
    char *out = room(t, NMEA_JSON_MAX + 1);
    size_t n;
    if (len > NMEA_MAX_LINE) {
        nmea_error err;
        nmea_error_too_long(&err, len);
        n = nmea_error_to_json(&err, out, NMEA_JSON_MAX);
    } else {
        n = nmea_decode_json_ex(line, len, t->values, &t->options, out, NMEA_JSON_MAX);
#ifdef NMEA_TEST_HOOKS
        check_general(t, line, len, out, n);
#endif
    }
    emit(t, n);
}

static void encode_line(tool *t, const char *line, size_t len, bool complete)
{
    size_t cap = 4 * len + NMEA_JSON_MAX; /* the sentence, or an error quoting the line twice */
    char *out = room(t, cap + 1);
    nmea_sentence s;
    nmea_error err;
    size_t n;

    if (!complete) {
        /* longer than this tool takes: not a line decode could have printed */
        char json[256];
        sprintf(json, "{\"ok\":false,\"error\":{\"kind\":\"bad_json\",\"address\":null,\"field\":null,"
                      "\"name\":null,\"message\":\"line is %lu bytes, the limit is %lu\"}}",
                (unsigned long)len, (unsigned long)ENCODE_MAX);
        n = strlen(json);
        memcpy(out, json, n);
    } else if (nmea_json_is_failure(line, len)) {
        return;
    } else if (nmea_from_json(&s, line, len, scratch, sizeof scratch, &err)) {
        n = nmea_serialize(&s, out, cap);
#ifdef NMEA_TEST_HOOKS
        check_written(&s, out, cap, n, line, len);
#endif
    } else {
        n = nmea_error_to_json(&err, out, cap);
    }
    emit(t, n);
}

/* The epochs of the lines read so far (fixes): a line that does not parse is skipped. */
static nmea_fix_assembler assembler;
static nmea_gnss_fix fix;

static void print_fix(tool *t)
{
    emit(t, nmea_fix_to_json(&fix, room(t, NMEA_FIX_JSON_MAX + 1), NMEA_FIX_JSON_MAX));
}

static void fix_line(tool *t, const char *line, size_t len)
{
    nmea_sentence s;
    nmea_error err;
    if (len <= NMEA_MAX_LINE && nmea_parse(&s, line, len, &err) && nmea_fix_feed(&assembler, &s, &fix))
        print_fix(t);
}

/* One line, without its LF: `len` bytes in all, of which the first `kept` are in `line`. */
static void handle(tool *t, const char *line, size_t len, size_t kept, char last)
{
    if (last == '\r') {
        len--;
        if (kept > len)
            kept = len;
    }
    if (t->verb == TOOL_ENCODE)
        encode_line(t, line, len, kept == len);
    else if (t->verb == TOOL_FIXES)
        fix_line(t, line, len);
    else
        decode_line(t, line, len);
}

/* The flags of decode and stream, each at most once, in any order. */
static bool decode_flags(tool *t, int argc, char **argv)
{
    int i;
    bool lenient = false, required = false, strict = false;
    for (i = 2; i < argc; i++) {
        bool *flag = strcmp(argv[i], "--values") == 0 ? &t->values
            : strcmp(argv[i], "--lenient") == 0 ? &lenient
            : strcmp(argv[i], "--require-checksum") == 0 ? &required
            : strcmp(argv[i], "--strict") == 0 ? &strict : NULL;
        if (!flag || *flag)
            return false;
        *flag = true;
    }
    t->options.lenient = lenient;
    t->options.require_checksum = required;
    t->options.strict = strict;
    t->options.problems = &t->problems;
    return true;
}

/* stream: the framed lines of stdin, each decoded. */
static int stream(tool *t)
{
    static nmea_framer framer;
    nmea_framed line;
    size_t got;

    nmea_framer_init(&framer);
    while ((got = fread(input, 1, sizeof input, stdin)) > 0) {
        const char *p = input;
        while (nmea_framer_push(&framer, &p, &got, &line))
            decode_line(t, line.ptr, line.len);
    }
    if (nmea_framer_end(&framer, &line))
        decode_line(t, line.ptr, line.len);
    flush(t);
    return ferror(stdin) ? 1 : 0;
}

int main(int argc, char **argv)
{
    tool t;
    size_t got, pending_len = 0, line_len = 0;
    char last = 0;

    memset(&t, 0, sizeof t);
    if (argc >= 2 && strcmp(argv[1], "stream") == 0 && decode_flags(&t, argc, argv)) {
        return stream(&t);
    } else if (argc >= 2 && strcmp(argv[1], "decode") == 0 && decode_flags(&t, argc, argv)) {
        t.verb = TOOL_DECODE;
    } else if (argc == 2 && strcmp(argv[1], "encode") == 0) {
        t.verb = TOOL_ENCODE;
    } else if (argc == 2 && strcmp(argv[1], "fixes") == 0) {
        t.verb = TOOL_FIXES;
    } else if (argc == 2 && strcmp(argv[1], "--version") == 0) {
        puts("nmea-c " NMEA_VERSION);
        return 0;
    } else {
        fputs("usage: nmea-c decode|stream [--values] [--lenient] [--require-checksum] [--strict] | encode"
              " | fixes | --version\n"
              "       (reads stdin, writes stdout)\n",
              stderr);
        return 2;
    }
    /* A line that ends inside one chunk is handled where it lies; one that spans chunks is
       gathered in `pending` (as far as it fits: a longer one is only counted). */
    while ((got = fread(input, 1, sizeof input, stdin)) > 0) {
        const char *p = input, *end = input + got;
        while (p < end) {
            const char *lf = memchr(p, '\n', (size_t)(end - p));
            const char *stop = lf ? lf : end;
            size_t n = (size_t)(stop - p);
            if (n)
                last = stop[-1];
            if (lf && line_len == 0) {
                handle(&t, p, n, n, last);
            } else {
                size_t cap = t.verb == TOOL_ENCODE ? sizeof pending : DECODE_MAX;
                size_t keep = pending_len + n <= cap ? n : cap - pending_len;
                memcpy(pending + pending_len, p, keep);
                pending_len += keep;
                line_len += n;
                if (lf)
                    handle(&t, pending, line_len, pending_len, last);
            }
            if (lf) {
                pending_len = line_len = 0;
                last = 0;
            }
            p = lf ? lf + 1 : end;
        }
    }
    if (line_len)
        handle(&t, pending, line_len, pending_len, last);
    if (t.verb == TOOL_FIXES && nmea_fix_finish(&assembler, &fix))
        print_fix(&t);
    flush(&t);
    return ferror(stdin) ? 1 : 0;
}
