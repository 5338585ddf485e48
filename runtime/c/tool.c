/*
 * nmea-c: `decode` NMEA lines to JSON, `encode` that JSON back to sentences, `stream` a byte
 * stream that may hold garbage, cut lines or sentences run together (hand-written:
 * runtime/c/tool.c). Same behaviour, byte for byte, as nmea-py and nmea-rs; see docs/json.md.
 *
 *     nmea-c decode [--values] [--lenient] [--require-checksum] [--strict] [--ubx]   stdin: NMEA lines
 *     nmea-c stream [--values] [--lenient] [--require-checksum] [--strict] [--ubx] [--rtcm3]   stdin: any bytes
 *     nmea-c encode                                               stdin: decode's output
 *     nmea-c fixes                                                stdin: NMEA lines
 *
 * decode splits its input on LF and drops one CR before it; stream frames it with nmea_framer.
 * fixes prints one JSON object per epoch, the fix its sentences make (Python's Fix.to_dict);
 * decode and stream print one JSON object per line; a line longer than NMEA_MAX_LINE is counted, not stored.
 * With the AIS pair, a line's object ends with the AIS message it carries (decode: a message of
 * one sentence; stream: also one joined across sentences, and an incomplete_message line after the
 * line that gave a message up). With the UBX pair and --ubx, a UBX frame's object of stream ends
 * with the message it carries (or the error its payload gives).
 * encode holds one line at a time (up to ENCODE_MAX bytes).
 */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "nmea.h"
#ifdef NMEA_WITH_AIS
#include "nmea_ais.h"
#endif
#ifdef NMEA_WITH_RTCM3
#include "nmea_rtcm3.h"
#endif
#ifdef NMEA_WITH_UBX
#include "nmea_ubx.h"
#endif

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
    bool stream; /* decode joins AIS messages across lines */
    bool values;
    bool ubx; /* stream: a UBX frame with its decoded message */
    bool rtcm3; /* stream: an RTCM 3 frame with its decoded message */
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

#ifdef NMEA_WITH_AIS
/* The JSON of a message of a payload as long as a line holds. */
#define AIS_JSON_MAX (1u << 17)

/* The messages stream joins across lines, and the errors of those given up for the line fed last
   (each line ends with a LF; a feed gives up at most every slot, one more message and a fragment). */
static nmea_ais_assembler ais_assembler;
static char given_up[(NMEA_AIS_SLOTS + 2) * 256];
static size_t given_up_len;

/* A line's JSON object, to which its AIS message is added. */
typedef struct {
    char *json;
    size_t len;
} object;

/* Adds "ais", the message of the payload, or "ais_error", why none decodes from it, as the
   object's last member. */
static void add_message(object *o, const char *payload, size_t len, unsigned fill_bits)
{
    static nmea_ais_message message;
    nmea_ais_error err;
    char *at = o->json + o->len - 1; /* its closing brace */
    if (nmea_ais_decode(payload, len, fill_bits, &message, &err)) {
        memcpy(at, ",\"ais\":", 7);
        at += 7 + nmea_ais_json(&message, fill_bits, at + 7, AIS_JSON_MAX);
    } else {
        memcpy(at, ",\"ais_error\":", 13);
        at += 13 + nmea_ais_error_json(&err, at + 13, AIS_JSON_MAX);
    }
    *at++ = '}';
    o->len = (size_t)(at - o->json);
}

static void assembled(const nmea_ais_assembled *done, void *context)
{
    char message[64];
    if (done->complete) {
        add_message(context, done->payload, done->payload_len, done->fill_bits);
        return;
    }
    nmea_ais_incomplete_message(done, message, sizeof message);
    given_up_len += (size_t)sprintf(given_up + given_up_len,
                                    "{\"ok\":false,\"error\":{\"kind\":\"incomplete_message\",\"address\":\"AIS\","
                                    "\"field\":null,\"name\":null,\"message\":\"%s\"}}\n", message);
}

/* Adds the AIS message a decoded line carries or completes to its JSON (`out`, `n` bytes). */
static size_t with_message(tool *t, const char *line, size_t len, char *out, size_t n)
{
    nmea_sentence s;
    nmea_error err;
    nmea_ais_fragment fragment;
    object o;
    o.json = out;
    o.len = n;
    if ((line[0] != '!' && line[0] != '\\') || !nmea_parse_ex(&s, line, len, &t->options, &err)
        || !nmea_ais_fragment_of(&s, &fragment))
        return n;
    if (t->stream)
        nmea_ais_assembler_feed(&ais_assembler, &fragment, s.tag_blocks, assembled, &o);
    else if (fragment.count == 1)
        add_message(&o, fragment.payload.ptr, fragment.payload.len, fragment.fill_bits);
    return o.len;
}

/* The errors of the messages given up, as lines of their own. */
static void emit_given_up(tool *t)
{
    memcpy(room(t, given_up_len), given_up, given_up_len);
    t->out_len += given_up_len;
    given_up_len = 0;
}
#endif

static void decode_line(tool *t, const char *line, size_t len)
{
#ifdef NMEA_WITH_AIS
    char *out = room(t, NMEA_JSON_MAX + AIS_JSON_MAX + 32);
#else
    char *out = room(t, NMEA_JSON_MAX + 1);
#endif
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
#ifdef NMEA_WITH_AIS
        n = with_message(t, line, len, out, n);
#endif
    }
    emit(t, n);
#ifdef NMEA_WITH_AIS
    emit_given_up(t);
#endif
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
            : strcmp(argv[i], "--strict") == 0 ? &strict
#ifdef NMEA_WITH_UBX
            : strcmp(argv[i], "--ubx") == 0 ? &t->ubx
#endif
#ifdef NMEA_WITH_RTCM3
            : strcmp(argv[i], "--rtcm3") == 0 ? &t->rtcm3
#endif
            : NULL;
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

#ifdef NMEA_WITH_UBX
/* stream --ubx (docs/json.md, "UBX messages in stream"): the message a UBX frame carries, decoded
   once; ubx_member appends `,"ubx":` and its JSON, or `,"ubx_error":` and the error its payload
   gives; a SkyTraq, SiRF, CASIC or SBF frame's alike, under its protocol's name. */
static nmea_ubx_message ubx_message; /* 10 kB: not on the stack */
static nmea_ubx_error ubx_error;
static bool ubx_decoded;
static size_t ubx_json_len; /* of the decoded message's JSON */
static const char *ubx_protocol; /* its name: ubx, skytraq */

/* The UBX pair's protocol of a framing's name (`name`: ubx, skytraq): false for one it does not type. */
static bool ubx_typed(const char *name, nmea_ubx_protocol *protocol)
{
    int p;
    for (p = 0; nmea_ubx_protocol_name((nmea_ubx_protocol)p); p++)
        if (strcmp(nmea_ubx_protocol_name((nmea_ubx_protocol)p), name) == 0) {
            *protocol = (nmea_ubx_protocol)p;
            return true;
        }
    return false;
}

/* Decodes the frame; the bytes its member takes at most. */
static size_t ubx_decode(nmea_ubx_protocol protocol, const unsigned char *frame, size_t len)
{
    ubx_protocol = nmea_ubx_protocol_name(protocol);
    ubx_decoded = nmea_ubx_decode_frame_of(protocol, frame, len, &ubx_message, &ubx_error);
    ubx_json_len = ubx_decoded ? nmea_ubx_json(&ubx_message, NULL, 0) : 0;
    return ubx_decoded ? 16 + ubx_json_len : 220 + sizeof ubx_error.text;
}

static size_t ubx_member(char *out)
{
    size_t m, i;
    char upper[16];
    if (ubx_decoded) {
        m = (size_t)sprintf(out, ",\"%s\":", ubx_protocol);
        return m + nmea_ubx_json(&ubx_message, out + m, ubx_json_len + 1);
    }
    for (i = 0; ubx_protocol[i] && i + 1 < sizeof upper; i++) /* the errors' address: SKYTRAQ 0xA8 */
        upper[i] = (char)(ubx_protocol[i] >= 'a' && ubx_protocol[i] <= 'z' ? ubx_protocol[i] - 'a' + 'A' : ubx_protocol[i]);
    upper[i] = '\0';
    m = (size_t)sprintf(out, ",\"%s_error\":{\"kind\":\"%s\",\"address\":\"%s%s%s\",\"field\":null,\"name\":",
                        ubx_protocol, nmea_ubx_error_kind_name(ubx_error.kind), upper, ubx_error.message ? " " : "",
                        ubx_error.message ? ubx_error.message : "");
    m += (size_t)(ubx_error.field ? sprintf(out + m, "\"%s\"", ubx_error.field) : sprintf(out + m, "null"));
    return m + (size_t)sprintf(out + m, ",\"message\":\"%s\"}", ubx_error.text);
}
#endif

#ifdef NMEA_WITH_RTCM3
/* stream --rtcm3 (docs/json.md, "RTCM 3 messages in stream"): the message an RTCM 3 frame carries
   (the framer checked its preamble, length and CRC), decoded once; rtcm3_member appends
   `,"rtcm3":` and its JSON, or `,"rtcm3_error":` and the error its payload gives. */
static nmea_rtcm3_message rtcm3_message; /* about 3 kB: not on the stack */
static nmea_rtcm3_error rtcm3_error;
static bool rtcm3_decoded;
static size_t rtcm3_json_len; /* of the decoded message's JSON, or of the error's */

/* Decodes the frame's payload; the room its member takes. */
static size_t rtcm3_decode(const unsigned char *frame, size_t len)
{
    rtcm3_decoded = len >= 6 && nmea_rtcm3_decode_payload(frame + 3, len - 6, &rtcm3_message, &rtcm3_error);
    rtcm3_json_len = rtcm3_decoded ? nmea_rtcm3_json(&rtcm3_message, NULL, 0) : nmea_rtcm3_error_json(&rtcm3_error, NULL, 0);
    return 16 + rtcm3_json_len;
}

static size_t rtcm3_member(char *out)
{
    size_t m;
    if (rtcm3_decoded) {
        m = (size_t)sprintf(out, ",\"rtcm3\":");
        return m + nmea_rtcm3_json(&rtcm3_message, out + m, rtcm3_json_len + 1);
    }
    m = (size_t)sprintf(out, ",\"rtcm3_error\":");
    return m + nmea_rtcm3_error_json(&rtcm3_error, out + m, rtcm3_json_len + 1);
}
#endif

/* A binary frame's JSON (docs/json.md, "Binary frames in stream"): a frame with its identity and
   bytes, or the sync bytes of what was not one with the reason. */
static void emit_frame(tool *t, const nmea_framed *item)
{
    static const char hex[] = "0123456789abcdef", upper[] = "0123456789ABCDEF";
    const unsigned char *b = (const unsigned char *)item->ptr;
    const nmea_framing *framing = &nmea_framings[item->protocol - 1];
    const char *protocol = framing->name;
    size_t n, i, width = (size_t)framing->check_size + framing->end_len, at, extra = 0;
    size_t trailer = (size_t)(framing->check_at ? 0 : framing->check_size) + framing->end_len;
    unsigned long value;
    unsigned bit;
    char *out;
#ifdef NMEA_WITH_UBX
    nmea_ubx_protocol typed;
    bool with_ubx = t->ubx && item->error == NMEA_FRAME_OK && ubx_typed(protocol, &typed);
#endif
#ifdef NMEA_WITH_RTCM3
    bool with_rtcm3 = t->rtcm3 && item->error == NMEA_FRAME_OK && item->protocol == NMEA_RTCM3;
    if (with_rtcm3)
        extra = rtcm3_decode(b, item->len); /* its JSON may be long: room for it first */
#endif
#ifdef NMEA_WITH_UBX
    if (with_ubx)
        extra = ubx_decode(typed, b, item->len); /* its JSON may be long: room for it first */
#endif
    out = room(t, 160 + 2 * NMEA_MAX_FRAME + extra);
    if (item->error == NMEA_FRAME_OK) {
        n = (size_t)sprintf(out, "{\"ok\":true,\"protocol\":\"%s\",", protocol);
        for (i = 0; i < 2 && framing->identity[i].name; i++) { /* null past the payload */
            at = framing->identity[i].bit;
            if (at + framing->identity[i].bits > 8 * (item->len - trailer)) {
                n += (size_t)sprintf(out + n, "\"%s\":null,", framing->identity[i].name);
                continue;
            }
            if (framing->big_endian) /* bits most significant first */
                for (value = 0, bit = 0; bit < framing->identity[i].bits; bit++, at++)
                    value = value << 1 | (unsigned long)(b[at / 8] >> (7 - at % 8) & 1);
            else /* least significant first */
                for (value = 0, bit = 0; bit < framing->identity[i].bits; bit++, at++)
                    value |= (unsigned long)(b[at / 8] >> (at % 8) & 1) << bit;
            n += (size_t)sprintf(out + n, "\"%s\":%lu,", framing->identity[i].name, value);
        }
        n += (size_t)sprintf(out + n, "\"length\":%lu,\"frame\":\"", (unsigned long)item->len);
    } else {
        n = (size_t)sprintf(out, "{\"ok\":false,\"protocol\":\"%s\",\"error\":{\"kind\":\"%s\",\"message\":\"",
                            protocol, item->error == NMEA_FRAME_BAD_CHECKSUM ? "bad_checksum"
                                      : item->error == NMEA_FRAME_TOO_LONG   ? "too_long"
                                      : item->error == NMEA_FRAME_NUL_HEADER ? "nul_header"
                                      : item->error == NMEA_FRAME_TOO_SHORT  ? "too_short"
                                                                             : "cut");
        if (item->error == NMEA_FRAME_BAD_CHECKSUM) {
            n += (size_t)sprintf(out + n, "checksum");
            for (i = width; i-- > 0;)
                n += (size_t)sprintf(out + n, " %c%c", upper[item->sent >> (8 * i + 4) & 15], upper[item->sent >> 8 * i & 15]);
            n += (size_t)sprintf(out + n, ", computed");
            for (i = width; i-- > 0;)
                n += (size_t)sprintf(out + n, " %c%c", upper[item->computed >> (8 * i + 4) & 15],
                                     upper[item->computed >> 8 * i & 15]);
        } else if (item->error == NMEA_FRAME_TOO_LONG) {
            n += (size_t)sprintf(out + n, "frame is %lu bytes, the limit is %d", (unsigned long)item->size, NMEA_MAX_FRAME);
        } else if (item->error == NMEA_FRAME_TOO_SHORT) {
            n += (size_t)sprintf(out + n, "frame is %lu bytes, the least is %lu", (unsigned long)item->size,
                                 (unsigned long)(framing->header + trailer));
        } else if (item->error == NMEA_FRAME_NUL_HEADER) {
            n += (size_t)sprintf(out + n, "the header after the sync is NUL bytes");
        } else {
            n += (size_t)sprintf(out + n, "the stream ends inside the frame");
        }
        n += (size_t)sprintf(out + n, "\"},\"bytes\":\"");
    }
    for (i = 0; i < item->len; i++) {
        out[n++] = hex[b[i] >> 4];
        out[n++] = hex[b[i] & 15];
    }
    out[n++] = '"';
#ifdef NMEA_WITH_UBX
    if (with_ubx)
        n += ubx_member(out + n);
#endif
#ifdef NMEA_WITH_RTCM3
    if (with_rtcm3)
        n += rtcm3_member(out + n);
#endif
    out[n++] = '}';
    emit(t, n);
}

/* One framed item of stdin, as JSON. */
static void emit_item(tool *t, const nmea_framed *item)
{
    if (item->protocol != NMEA_LINE)
        emit_frame(t, item);
    else
        decode_line(t, item->ptr, item->len);
}

/* stream: the framed items of stdin, each line decoded, each binary frame told. */
static int stream(tool *t)
{
    static nmea_framer framer;
    nmea_framed line;
    size_t got;

    nmea_framer_init(&framer);
#ifdef NMEA_WITH_AIS
    t->stream = true;
    nmea_ais_assembler_init(&ais_assembler, 100);
#endif
    while ((got = fread(input, 1, sizeof input, stdin)) > 0) {
        const char *p = input;
        while (nmea_framer_push(&framer, &p, &got, &line))
            emit_item(t, &line);
    }
    while (nmea_framer_end(&framer, &line))
        emit_item(t, &line);
#ifdef NMEA_WITH_AIS
    nmea_ais_assembler_finish(&ais_assembler, assembled, NULL);
    emit_given_up(t);
#endif
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
        fputs("usage: nmea-c decode|stream [--values] [--lenient] [--require-checksum] [--strict]"
#ifdef NMEA_WITH_UBX
              " [--ubx]"
#endif
#ifdef NMEA_WITH_RTCM3
              " [--rtcm3]"
#endif
              " | encode"
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
