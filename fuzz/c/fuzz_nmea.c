/*
 * libFuzzer target for the generated C codec (build: make fuzz-smoke / make fuzz).
 *
 * The input is tried as an NMEA line, as a line of decode's JSON and as a byte stream:
 * - a line that parses must serialize back to exactly its bytes, its lossless JSON must rebuild
 *   the same sentence, and both JSON forms must fit NMEA_JSON_MAX; lenient parsing must give the
 *   same JSON, and requiring a checksum must refuse it exactly when it has none;
 * - a line that does not parse must describe its error as JSON; when lenient parsing keeps it, it
 *   must still serialize back to exactly its bytes, and its JSON (problems included) must rebuild
 *   it the same way;
 * - the fast paths of nmea_parse_ex and nmea_serialize must decode and write the line exactly as
 *   their general paths do (nmea_parse_general, nmea_serialize_general: built with
 *   NMEA_TEST_HOOKS), into any buffer size;
 * - JSON that rebuilds a sentence must serialize, and that sentence must parse again;
 * - the stream framer must cut the input into the same items as a byte-at-a-time model of the
 *   Python reference's Framer, whether it gets the input whole or in chunks of any size (the
 *   chunk sizes are derived from the input);
 * - AIS: a payload that decodes (a VDM/VDO line's of one sentence, one the assembler joins, or the
 *   input itself after a first byte that gives the fill bits) must encode back to its characters
 *   and fill bits when it fits a message's bits, and its JSON or its error's must be written;
 *   the assembler fed the input's lines must account for every fragment exactly once.
 * Any broken promise aborts, and AddressSanitizer/UndefinedBehaviorSanitizer catch the rest.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "nmea.h"
#include "nmea_ais.h"

static char text[NMEA_MAX_LINE + 8];
static char again[NMEA_MAX_LINE + 8];
static char json[NMEA_JSON_MAX];
static char json2[NMEA_JSON_MAX];
static char scratch[NMEA_JSON_MAX];

static nmea_problems problems;
static const nmea_options LENIENT = {true, false, &problems, false};
static const nmea_options REQUIRED = {false, true, NULL, false};

static void check(bool ok)
{
    if (!ok)
        abort();
}

static bool ends_with(const char *s, size_t n, const char *suffix)
{
    size_t m = strlen(suffix);
    return n >= m && memcmp(s + n - m, suffix, m) == 0;
}

static bool contains(const char *s, size_t n, const char *part)
{
    size_t m = strlen(part), i;
    for (i = 0; i + m <= n; i++)
        if (memcmp(s + i, part, m) == 0)
            return true;
    return false;
}

/* nmea_serialize must write what its general path writes, whatever the buffer's size (sizes
   around the sentence's length and the fast path's margin, taken from `seed`). */
static void same_writing(const nmea_sentence *s, size_t seed)
{
    size_t sizes[4], i, n, m;
    sizes[0] = sizeof text;
    sizes[1] = seed % 80;
    sizes[2] = seed % 80 + 64;
    sizes[3] = nmea_serialize_general(s, again, sizeof again) + 1 - seed % 3;
    for (i = 0; i < 4; i++) {
        if (sizes[i] > sizeof text)
            continue;
        n = nmea_serialize(s, text, sizes[i]);
        m = nmea_serialize_general(s, again, sizes[i]);
        check(n == m && (sizes[i] == 0 || memcmp(text, again, n + 1) == 0));
    }
}

/* The sentence's lossless JSON must rebuild it, and the rebuilt one must serialize to `line`. */
static void json_round_trip(const nmea_sentence *s, const char *line, size_t size)
{
    nmea_sentence rebuilt;
    nmea_error err;
    size_t n, j;

    check(nmea_to_json(s, true, json, sizeof json) != 0);
    j = nmea_to_json(s, false, json, sizeof json);
    check(j != 0 && nmea_from_json(&rebuilt, json, j, scratch, sizeof scratch, &err));
    n = nmea_serialize(&rebuilt, again, sizeof again);
    check(n == size && memcmp(again, line, size) == 0);
}

/* The JSON of a parse: the sentence's lossless JSON, or the error's. */
static size_t parse_json(bool ok, const nmea_sentence *s, const nmea_error *err, char *buf, size_t cap)
{
    return ok ? nmea_to_json(s, false, buf, cap) : nmea_error_to_json(err, buf, cap);
}

static void as_line(const char *data, size_t size)
{
    nmea_sentence s, other;
    nmea_error err;
    size_t n, j, k, i;
    bool no_checksum, text_command, parsed;

    parsed = nmea_parse(&s, data, size, &err);
    j = parse_json(parsed, &s, &err, json, sizeof json);
    k = parse_json(nmea_parse_general(&other, data, size, NULL, &err), &other, &err, json2, sizeof json2);
    check(j == k && memcmp(json, json2, j) == 0);
    if (size && data[size - 1] == '\n') {
        /* one trailing LF or CR LF is not part of the line: the line without it reads the same
           (the round trips below are checked on lines without one) */
        size -= size > 1 && data[size - 2] == '\r' ? 2 : 1;
        if (size == 0 || data[size - 1] != '\n') {
            k = parse_json(nmea_parse(&other, data, size, &err), &other, &err, json2, sizeof json2);
            check(j == k && memcmp(json, json2, j) == 0);
        }
        return;
    }
    if (!parsed) {
        check(nmea_error_to_json(&err, json, sizeof json) != 0);
        if (!nmea_parse_ex(&s, data, size, &LENIENT, &err)) {
            check(nmea_error_to_json(&err, json, sizeof json) != 0);
            return;
        }
        /* kept leniently: the problems' texts are written back in their places */
        n = nmea_serialize(&s, text, sizeof text);
        check(n == size && memcmp(text, data, size) == 0);
        json_round_trip(&s, data, size);
        return;
    }
    same_writing(&s, size);
    n = nmea_serialize(&s, text, sizeof text);
    check(n == size && memcmp(text, data, size) == 0);
    json_round_trip(&s, data, size);

    /* lenient parsing of a line that parses changes nothing: what it lists are the numbers kept
       outside their range, which nmea_parse keeps without listing them */
    j = nmea_to_json(&s, false, json, sizeof json);
    check(nmea_parse_ex(&other, data, size, &LENIENT, &err));
    for (i = 0; other.problems && i < other.problems->count; i++)
        check(other.problems->list[i].kind == NMEA_PROBLEM_OUT_OF_RANGE);
    other.problems = NULL;
    k = nmea_to_json(&other, false, json2, sizeof json2);
    check(j == k && memcmp(json, json2, j) == 0);

    /* a required checksum refuses exactly the $/! sentences without one (the sentence's checksum
       member is the last, or the one before its TAG blocks or stray '$') */
    no_checksum = ends_with(json, j, "\"checksum\":null}") || ends_with(json, j, "\"checksum\":\"\"}") ||
                  contains(json, j, "\"checksum\":null,\"tag_blocks\":") ||
                  contains(json, j, "\"checksum\":\"\",\"tag_blocks\":") ||
                  contains(json, j, "\"checksum\":null,\"stray\":") ||
                  contains(json, j, "\"checksum\":\"\",\"stray\":");
    text_command = j > 21 && memcmp(json, "{\"ok\":true,\"start\":\"\"", 21) == 0;
    if (nmea_parse_ex(&other, data, size, &REQUIRED, &err)) {
        k = nmea_to_json(&other, false, json2, sizeof json2);
        check(j == k && memcmp(json, json2, j) == 0);
        check(!no_checksum || text_command);
    } else {
        check(err.kind == NMEA_ERR_MISSING_CHECKSUM && no_checksum && !text_command);
    }
}

static void as_json(const char *data, size_t size)
{
    nmea_sentence s;
    nmea_sentence parsed;
    nmea_error err;
    size_t n;

    if (size > sizeof scratch / 2 || !nmea_from_json(&s, data, size, scratch, sizeof scratch, &err))
        return;
    same_writing(&s, size);
    n = nmea_serialize(&s, text, sizeof text);
    if (n == 0 && size < NMEA_MAX_LINE)
        return; /* a sentence rebuilt from JSON may be longer than any line the parser takes */
    if (n > 0 && n <= NMEA_MAX_LINE && !nmea_parse_ex(&parsed, text, n, &LENIENT, &err))
        abort();
}

/* ---------------------------------------------------------------------------------------- */
/* Stream framing */

#define STREAM_MAX 65536

typedef struct {
    size_t start; /* offset in model_bytes of the kept bytes */
    size_t len;   /* the line's length (> NMEA_MAX_LINE: overlong, only counted) */
    nmea_protocol protocol; /* a binary frame's (its bytes at `frame`), else NMEA_LINE */
    nmea_frame_error error; /* a rejected frame's: `frame` holds its sync bytes */
    const char *frame;
} model_item;

static model_item model[STREAM_MAX];
static size_t model_count;
static char model_bytes[STREAM_MAX];
static size_t model_used;

/* The Python reference's Framer, one byte at a time; a binary frame read ahead in the whole input,
   and after a rejected one the input read again from the byte after its sync. */
static void model_finish(size_t *length, size_t *start)
{
    if (*length) {
        model[model_count].start = *start;
        model[model_count].len = *length;
        model[model_count].protocol = NMEA_LINE;
        model_count++;
    }
    *length = 0;
    *start = model_used;
}

static void model_binary(nmea_protocol protocol, nmea_frame_error error, const char *frame, size_t len)
{
    model[model_count].protocol = protocol;
    model[model_count].error = error;
    model[model_count].frame = frame;
    model[model_count].len = len;
    model_count++;
}

/* The frames of spec/binary, written here from the protocols' facts (not from the framer's table):
   protocol, first two bytes (the second under a mask), the third sync byte (when there are three),
   sync bytes, header and trailer (checksum and end bytes) sizes. */
static const struct {
    nmea_protocol protocol;
    unsigned char first, second, mask, third;
    size_t sync, header, trailer;
} MODELS[] = {
    {NMEA_UBX, 0xB5, 0x62, 0xFF, 0, 2, 6, 2},        /* B5 62 class id length(LE) payload CK_A CK_B */
    {NMEA_RTCM3, 0xD3, 0x00, 0xFC, 0, 1, 3, 3},      /* D3, 6 zero bits, 10-bit length, payload, CRC-24Q */
    {NMEA_SKYTRAQ, 0xA0, 0xA1, 0xFF, 0, 2, 4, 3},    /* A0 A1 length(BE) payload XOR 0D 0A */
    {NMEA_SIRF, 0xA0, 0xA2, 0xFF, 0, 2, 4, 4},       /* A0 A2 0-bit, 15-bit length(BE) payload sum15(BE) B0 B3 */
    {NMEA_CASIC, 0xBA, 0xCE, 0xFF, 0, 2, 6, 4},      /* BA CE length(LE) class id payload sum32(LE) */
    {NMEA_SBF, 0x24, 0x40, 0xFF, 0, 2, 8, 0},        /* $ @ CRC(LE) id(LE) length(LE: the whole block) body */
    {NMEA_UNICORE, 0xAA, 0x44, 0xFF, 0xB5, 3, 24, 4}, /* AA 44 B5 cpu id(LE) length(LE) time... body CRC-32(LE) */
};

/* The payload's length a frame's header gives. */
static size_t model_payload(nmea_protocol protocol, const unsigned char *b)
{
    switch (protocol) {
    case NMEA_UBX:
    case NMEA_CASIC:
        return (size_t)b[4 - 2 * (protocol == NMEA_CASIC)] | (size_t)b[5 - 2 * (protocol == NMEA_CASIC)] << 8;
    case NMEA_RTCM3:
        return (size_t)(b[1] & 3) << 8 | b[2];
    case NMEA_UNICORE: /* the body's length, after the id */
        return (size_t)b[6] | (size_t)b[7] << 8;
    case NMEA_SBF: /* the whole block's length, less its header (wrapping when under it) */
        return ((size_t)b[6] | (size_t)b[7] << 8) - 8;
    default: /* SkyTraq, SiRF (whose top bit, reserved and zero, makes the frame too long when set) */
        return (size_t)b[2] << 8 | b[3];
    }
}

/* The trailer a frame of `len` bytes before it must end with, as a big-endian number. */
static unsigned long model_checksum(nmea_protocol protocol, const unsigned char *b, size_t len)
{
    unsigned long a = 0, c = 0, word;
    size_t i;
    int bit;
    switch (protocol) {
    case NMEA_UBX:
        for (i = 2; i < len; i++) {
            a = (a + b[i]) % 256;
            c = (c + a) % 256;
        }
        return a << 8 | c;
    case NMEA_SKYTRAQ:
        for (i = 4; i < len; i++)
            c ^= b[i];
        return c << 16 | 0x0D0A;
    case NMEA_SIRF:
        for (i = 4; i < len; i++)
            c += b[i];
        return (c & 0x7FFF) << 16 | 0xB0B3;
    case NMEA_CASIC: /* little-endian words from the length on, sent little endian */
        for (i = 2; i < len; i += 4) {
            for (word = 0, bit = 3; bit >= 0; bit--)
                word = word << 8 | (i + (size_t)bit < len ? b[i + (size_t)bit] : 0);
            c = (c + word) & 0xFFFFFFFFUL;
        }
        return (c & 0xFF) << 24 | (c >> 8 & 0xFF) << 16 | (c >> 16 & 0xFF) << 8 | c >> 24;
    case NMEA_SBF: /* CRC-CCITT from the id on, sent little endian right after the sync */
        for (i = 4; i < len; i++) {
            c ^= (unsigned long)b[i] << 8;
            for (bit = 0; bit < 8; bit++)
                c = (c << 1 ^ (c & 0x8000 ? 0x1021 : 0)) & 0xFFFF;
        }
        return (c & 0xFF) << 8 | c >> 8;
    case NMEA_UNICORE: /* CRC-32: reflected 0xEDB88320, initial 0, no final inversion, sent little endian */
        for (i = 0; i < len; i++) {
            c ^= b[i];
            for (bit = 0; bit < 8; bit++)
                c = c >> 1 ^ (c & 1 ? 0xEDB88320UL : 0);
        }
        return (c & 0xFF) << 24 | (c >> 8 & 0xFF) << 16 | (c >> 16 & 0xFF) << 8 | c >> 24;
    default:
        for (i = 0; i < len; i++) {
            c ^= (unsigned long)b[i] << 16;
            for (bit = 0; bit < 8; bit++)
                c = (c << 1 ^ (c & 0x800000 ? 0x1864CFB : 0)) & 0xFFFFFF;
        }
        return c;
    }
}

/* What the framer makes of a first sync byte at data[i] (outside a TAG block): the items, and
   where reading goes on; 0 when it starts no frame (a byte of the line). */
static size_t model_sync(const char *data, size_t size, size_t i, size_t *length, size_t *start)
{
    const unsigned char *b = (const unsigned char *)data + i;
    size_t left = size - i, frame, k, m, sync, header, trailer;
    nmea_protocol protocol;
    unsigned long sent = 0;
    for (m = 0; m < sizeof MODELS / sizeof MODELS[0]; m++)
        if (left >= 2 && b[0] == MODELS[m].first && (b[1] & MODELS[m].mask) == MODELS[m].second
            && (MODELS[m].sync < 3 || (left >= 3 && b[2] == MODELS[m].third)))
            break;
    if (m == sizeof MODELS / sizeof MODELS[0])
        return 0;
    protocol = MODELS[m].protocol;
    sync = MODELS[m].sync;
    header = MODELS[m].header;
    trailer = MODELS[m].trailer;
    model_finish(length, start);
    if (left < header) {
        model_binary(protocol, NMEA_FRAME_CUT, data + i, sync);
        return i + sync;
    }
    for (k = sync; k < header && b[k] == 0; k++)
        ;
    if (k == header) {
        model_binary(protocol, NMEA_FRAME_NUL_HEADER, data + i, sync);
        return i + sync;
    }
    frame = header + trailer + model_payload(protocol, b);
    if (frame <= NMEA_MAX_FRAME && frame < header + trailer) { /* (SBF's length under its header's) */
        model_binary(protocol, NMEA_FRAME_TOO_SHORT, data + i, sync);
        return i + sync;
    }
    if (frame > NMEA_MAX_FRAME || frame > left) {
        model_binary(protocol, frame > NMEA_MAX_FRAME ? NMEA_FRAME_TOO_LONG : NMEA_FRAME_CUT, data + i, sync);
        return i + sync;
    }
    for (k = frame - trailer; k < frame; k++)
        sent = sent << 8 | b[k];
    if (protocol == NMEA_SBF)
        sent = (unsigned long)b[2] << 8 | b[3];
    if (sent != model_checksum(protocol, b, frame - trailer)) {
        model_binary(protocol, NMEA_FRAME_BAD_CHECKSUM, data + i, sync);
        return i + sync;
    }
    model_binary(protocol, NMEA_FRAME_OK, data + i, frame);
    return i + frame;
}

static void model_frame(const char *data, size_t size)
{
    enum { OUTSIDE, IN_TAG, AFTER_TAG } tag = OUTSIDE; /* where the line is as to TAG blocks */
    size_t i, length = 0, start = 0;
    model_count = 0;
    model_used = 0;
    for (i = 0; i < size; i++) {
        char c = data[i];
        size_t after;
        if (((unsigned char)c == 0xB5 || (unsigned char)c == 0xD3 || (unsigned char)c == 0xA0 || (unsigned char)c == 0xBA
             || (unsigned char)c == 0xAA || c == '$')
            && tag == OUTSIDE
            && (after = model_sync(data, size, i, &length, &start)) != 0) {
            i = after - 1;
            continue;
        }
        if (c == '\r' || c == '\n') {
            model_finish(&length, &start);
            tag = OUTSIDE;
            continue;
        }
        if (c == '\\' && (length == 0 || tag != OUTSIDE)) {
            tag = tag == IN_TAG ? AFTER_TAG : IN_TAG; /* opens a block, or closes the open one */
        } else if ((c == '$' || c == '!') && tag == OUTSIDE) {
            model_finish(&length, &start);
        } else if (tag == AFTER_TAG) {
            tag = OUTSIDE;
        }
        length++;
        if (length <= NMEA_MAX_LINE)
            model_bytes[model_used++] = c;
    }
    model_finish(&length, &start);
}

/* The item must be the model's next one. */
static void expect_item(size_t *next, nmea_framed item)
{
    const model_item *m;
    check(*next < model_count);
    m = &model[(*next)++];
    check(item.len == m->len && item.protocol == m->protocol);
    if (item.protocol != NMEA_LINE)
        check(item.error == m->error && item.ptr != NULL && memcmp(item.ptr, m->frame, item.len) == 0);
    else if (item.len > NMEA_MAX_LINE)
        check(item.ptr == NULL);
    else
        check(item.ptr != NULL && memcmp(item.ptr, model_bytes + m->start, item.len) == 0);
}

/* Frames the input in chunks: `sizes` (n of them, each at least 1) cycled. */
static void frame_chunked(const char *data, size_t size, const size_t *sizes, size_t n, bool decode)
{
    static nmea_framer framer;
    nmea_framed item;
    size_t pos = 0, next = 0, k = 0;

    nmea_framer_init(&framer);
    while (pos < size) {
        const char *p = data + pos;
        size_t len = sizes[k++ % n];
        if (len > size - pos)
            len = size - pos;
        pos += len;
        while (nmea_framer_push(&framer, &p, &len, &item)) {
            expect_item(&next, item);
            if (decode && item.protocol == NMEA_LINE)
                nmea_decode_json_ex(item.ptr, item.len, false, &LENIENT, json, sizeof json);
        }
        check(len == 0 && p == data + pos);
    }
    while (nmea_framer_end(&framer, &item))
        expect_item(&next, item);
    check(next == model_count && !nmea_framer_end(&framer, &item));
}

static void as_stream(const char *data, size_t size)
{
    static const size_t cycle[] = {1, 2, 3, 4, 5, 6, 7};
    size_t sizes[16], i, whole = size ? size : 1;

    if (size > STREAM_MAX)
        return;
    model_frame(data, size);
    frame_chunked(data, size, &whole, 1, true);
    frame_chunked(data, size, cycle, 7, false);
    for (i = 0; i < 16; i++) /* chunk sizes taken from the input */
        sizes[i] = i < size ? (size_t)((unsigned char)data[i] % 64 + 1) : 1 + i;
    frame_chunked(data, size, sizes, 16, false);
}

/* ---------------------------------------------------------------------------------------- */
/* AIS */

static char ais_json[1 << 17];

static void ais_round_trip(const char *payload, size_t len, unsigned fill_bits)
{
    static nmea_ais_message message;
    static nmea_ais_armored armored;
    nmea_ais_error err;
    if (!nmea_ais_decode(payload, len, fill_bits, &message, &err)) {
        check(nmea_ais_error_json(&err, ais_json, sizeof ais_json) < sizeof ais_json);
        return;
    }
    check(nmea_ais_json(&message, fill_bits, ais_json, sizeof ais_json) < sizeof ais_json);
    if (nmea_ais_encode(&message, &armored, &err))
        check(armored.fill_bits == fill_bits && strlen(armored.chars) == len && memcmp(armored.chars, payload, len) == 0);
    else
        check(len > NMEA_AIS_MAX_CHARS);
}

/* Counts what the assembler gives back, and checks each message it completes. */
static size_t ais_reported;

static void ais_done(const nmea_ais_assembled *done, void *context)
{
    char message[64];
    (void)context;
    check(done->n >= 1 && done->n <= NMEA_AIS_MAX_FRAGMENTS && done->payload_len <= NMEA_AIS_CAPACITY + NMEA_MAX_LINE);
    ais_reported += done->n;
    if (done->complete)
        ais_round_trip(done->payload, done->payload_len, done->fill_bits);
    else
        check(nmea_ais_incomplete_message(done, message, sizeof message) < sizeof message);
}

static void as_ais(const char *data, size_t size)
{
    static nmea_ais_assembler assembler;
    static const nmea_text no_tags = {NULL, 0};
    const char *line = data, *end = data + size;
    size_t fed = 0;
    if (size)
        ais_round_trip(data + 1, size - 1, (unsigned char)data[0] % 8);
    ais_reported = 0;
    nmea_ais_assembler_init(&assembler, 1 + (size ? (unsigned char)data[size - 1] % 8 : 0));
    while (line < end) { /* the input's lines, each fed */
        const char *lf = memchr(line, '\n', (size_t)(end - line));
        size_t len = (size_t)((lf ? lf : end) - line);
        nmea_sentence s;
        nmea_error err;
        nmea_ais_fragment fragment;
        bool is_fragment = nmea_parse(&s, line, len, &err) && nmea_ais_fragment_of(&s, &fragment);
        nmea_ais_assembler_feed(&assembler, is_fragment ? &fragment : NULL, is_fragment ? s.tag_blocks : no_tags,
                                ais_done, NULL);
        fed += is_fragment;
        line += len + 1;
    }
    nmea_ais_assembler_finish(&assembler, ais_done, NULL);
    check(ais_reported == fed);
}

/* field_mutator.c: sentences mutated field by field, their checksums made right again. */
size_t nmea_fuzz_mutate(uint8_t *data, size_t size, size_t max_size, unsigned int seed);

size_t LLVMFuzzerCustomMutator(uint8_t *data, size_t size, size_t max_size, unsigned int seed)
{
    return nmea_fuzz_mutate(data, size, max_size, seed);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    as_line((const char *)data, size);
    as_json((const char *)data, size);
    as_stream((const char *)data, size);
    as_ais((const char *)data, size);
    return 0;
}
