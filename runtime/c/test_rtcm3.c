/* The generated RTCM 3 pair (nmea_rtcm3.c) against generated/vectors/rtcm3.jsonl, which the Python
   codec and the reference decoder decode too: every frame decodes to the same JSON as Python's
   (each field's value, raw integer, special value, characters, the cell mask's bits, group entries
   in mask order, trailing bits) or fails with the same error kind, and encodes back to the same
   bytes. Then every RTCM 3 frame of the logs named after the vectors (a preamble, a length and a
   CRC-24Q that match) decodes and encodes back byte-exact, and the first frame of each message
   number, its payload cut at every length, is refused or read within the cut (make test-c, and
   under the sanitizers in make test-c-memory).

   usage: test_rtcm3 VECTORS.jsonl [LOG ...] */

#include "nmea_rtcm3.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures;

#define CHECK(cond, ...)                                                                                               \
    do {                                                                                                               \
        if (!(cond)) {                                                                                                 \
            failures++;                                                                                                \
            fprintf(stderr, __VA_ARGS__);                                                                              \
            fputc('\n', stderr);                                                                                       \
        }                                                                                                              \
    } while (0)

static nmea_rtcm3_message message; /* about 3 kB: an MSM's satellites and cells in place */
static char json[1 << 16];
static uint8_t encoded[NMEA_RTCM3_MAX_FRAME];

/* The text of the string member `key` of a JSON record (no quotes or commas in it). */
static const char *member(const char *record, const char *key, char *out, size_t cap)
{
    char pattern[32];
    const char *start, *end;
    size_t n;
    snprintf(pattern, sizeof pattern, "\"%s\":\"", key);
    start = strstr(record, pattern);
    if (!start)
        return NULL;
    start += strlen(pattern);
    end = strchr(start, '"');
    n = (size_t)(end - start) < cap - 1 ? (size_t)(end - start) : cap - 1;
    memcpy(out, start, n);
    out[n] = '\0';
    return out;
}

static size_t unhex(const char *text, uint8_t *out, size_t cap)
{
    size_t n = 0;
    while (*text && n < cap) {
        unsigned byte;
        if (sscanf(text, "%2x", &byte) != 1)
            break;
        out[n++] = (uint8_t)byte;
        text += 2;
        while (*text == ' ')
            text++;
    }
    return n;
}

static int vectors(const char *path)
{
    static char record[1 << 17];
    static char hex[4 * NMEA_RTCM3_MAX_FRAME];
    static uint8_t frame[NMEA_RTCM3_MAX_FRAME + 8];
    char kind[32];
    int decoded = 0, refused = 0;
    FILE *f = fopen(path, "r");
    if (!f) {
        perror(path);
        return -1;
    }
    while (fgets(record, sizeof record, f)) {
        nmea_rtcm3_error err;
        const char *expected = strstr(record, "\"decode\":");
        size_t len = unhex(member(record, "frame", hex, sizeof hex) ? hex : "", frame, sizeof frame), n;
        bool ok = nmea_rtcm3_decode_frame(frame, len, &message, &err);
        if (!expected) {
            CHECK(!ok && member(record, "error", kind, sizeof kind) && strcmp(nmea_rtcm3_error_kind_name(err.kind), kind) == 0,
                  "refused as %s, not %s: %s", ok ? "none" : nmea_rtcm3_error_kind_name(err.kind), kind, record);
            refused++;
            continue;
        }
        expected += strlen("\"decode\":");
        record[strlen(record) - 2] = '\0'; /* the record's closing brace and newline */
        CHECK(ok, "%s: %s", err.message, record);
        if (!ok)
            continue;
        nmea_rtcm3_json(&message, json, sizeof json);
        CHECK(strcmp(json, expected) == 0, "decoded\n  %s\nnot\n  %s", json, expected);
        n = nmea_rtcm3_encode(&message, encoded, sizeof encoded, &err);
        CHECK(n == len && memcmp(encoded, frame, len) == 0, "encoded back other bytes (%s): %s", err.message, record);
        decoded++;
    }
    fclose(f);
    printf("rtcm3.jsonl: %d decoded, %d refused\n", decoded, refused);
    CHECK(decoded > 40 && refused >= 2, "%d decoded, %d refused", decoded, refused);
    return decoded;
}

/* The first frame of each number, its payload cut at every length. */
static void cut(const uint8_t *payload, size_t len, const char *path)
{
    static nmea_rtcm3_message short_message;
    size_t at;
    for (at = 0; at < len; at++) {
        nmea_rtcm3_error err;
        uint8_t *copy = malloc(at ? at : 1); /* exactly the cut: ASan sees a read past it */
        memcpy(copy, payload, at);
        if (nmea_rtcm3_decode_payload(copy, at, &short_message, &err)) {
            size_t n = nmea_rtcm3_encode(&short_message, encoded, sizeof encoded, &err);
            CHECK(n == at + 6 && memcmp(encoded + 3, copy, at) == 0, "%s: cut at %zu encodes to other bytes", path, at);
        } else
            CHECK(err.kind == NMEA_RTCM3_SHORT_PAYLOAD || err.kind == NMEA_RTCM3_BAD_VALUE, "%s: cut at %zu: %s", path, at,
                  err.message);
        free(copy);
    }
}

static void logs(int argc, char **argv)
{
    static uint8_t data[1 << 22];
    static bool seen[4096];
    int known = 0, unknown = 0, i;
    for (i = 0; i < argc; i++) {
        size_t len, at = 0;
        FILE *f = fopen(argv[i], "rb");
        if (!f) {
            perror(argv[i]);
            failures++;
            continue;
        }
        len = fread(data, 1, sizeof data, f);
        fclose(f);
        while (at + 6 <= len) {
            nmea_rtcm3_error err;
            const uint8_t *payload;
            size_t payload_len, size = data[at] == 0xD3 ? 3 + ((size_t)(data[at + 1] & 3) << 8 | data[at + 2]) + 3 : 0;
            if (!size || at + size > len || !nmea_rtcm3_payload_of(data + at, size, &payload, &payload_len, &err)) {
                at++;
                continue;
            }
            CHECK(nmea_rtcm3_decode_payload(payload, payload_len, &message, &err), "%s at %zu: %s", argv[i], at,
                  err.message);
            if (err.kind == NMEA_RTCM3_OK) {
                size_t n = nmea_rtcm3_encode(&message, encoded, sizeof encoded, &err);
                CHECK(n == size && memcmp(encoded, data + at, size) == 0, "%s at %zu: encoded back other bytes", argv[i],
                      at);
                if (message.id == NMEA_RTCM3_ID_UNKNOWN)
                    unknown++;
                else {
                    int number = payload[0] << 4 | payload[1] >> 4;
                    known++;
                    nmea_rtcm3_json(&message, json, sizeof json);
                    if (!seen[number]) {
                        seen[number] = true;
                        cut(payload, payload_len, argv[i]);
                    }
                }
            }
            at += size;
        }
    }
    printf("RTCM 3 frames of the logs: %d decoded, %d of numbers the spec does not describe\n", known, unknown);
    CHECK(argc == 0 || (known > 200 && unknown < known / 10), "%d known, %d unknown", known, unknown);
}

int main(int argc, char **argv)
{
    nmea_rtcm3_error err;
    if (argc < 2) {
        fprintf(stderr, "usage: test_rtcm3 VECTORS.jsonl [LOG ...]\n");
        return 2;
    }
    vectors(argv[1]);
    logs(argc - 2, argv + 2);
    /* a short payload's error names message number and field */
    {
        static const uint8_t frame[] = {0xD3, 0x00, 0x03, 0x3E, 0xD0, 0x00, 0x7A, 0x79, 0xFE};
        CHECK(!nmea_rtcm3_decode_frame(frame, sizeof frame, &message, &err), "a cut 1005 decodes");
        nmea_rtcm3_error_json(&err, json, sizeof json);
        CHECK(strcmp(json, "{\"kind\":\"short_payload\",\"address\":\"RTCM3 1005\",\"field\":null,\"name\":\"itrf_year\","
                           "\"message\":\"itrf_year needs bits 24-29, the payload has 24\"}") == 0,
              "%s", json);
    }
    if (failures)
        fprintf(stderr, "%d failures\n", failures);
    return failures != 0;
}
