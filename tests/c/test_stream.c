/*
 * The five-sentence firmware's reading (make test-c): the C pair generated with
 * --only GGA,RMC,GSV,GSA,VTG and its default NMEA_MAX_LINE, the longest line those sentences can
 * have, reading a receiver's byte stream fed one byte at a time (nmea_framer_feed) and pushed in
 * chunks of every size (nmea_framer_push): the same lines come out, each parses and serializes
 * back to itself, and a GSV with an NMEA 4.10 signal id decodes its satellites and no phantom one.
 */

#include <stdio.h>
#include <string.h>

#include "nmea.h"

static int failures;

#define CHECK(cond)                                                                                                  \
    do {                                                                                                             \
        if (!(cond)) {                                                                                               \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond);                                 \
            failures++;                                                                                              \
        }                                                                                                            \
    } while (0)

/* Real lines (a u-blox NEO-F10T and a GlobalSat BU-353N5, /work/shared/corpus/real/hazer), with
   every line ending, empty lines, garbage before a sentence and a sentence cut short by the next. */
static const char *const SENTENCES[] = {
    "$GNGGA,120213.000,5957.0062,N,01100.6429,E,2,00,1.3,168.9,M,39.5,M,,*4A",
    "$GNRMC,120213.000,A,5957.0062,N,01100.6429,E,0.00,0.00,310722,,,D,V*0A",
    "$GNGSA,A,3,68,69,70,78,84,85,,,,,,,1.5,1.3,1.0,2*3D",
    "$GPGSV,1,1,01,36,19,156,51,,,,,,,,,,,,,1*5E",
    "$GLGSV,3,1,10,85,85,247,32,69,53,053,37,70,52,187,27,86,36,310,,1*72",
    "$GPGSA,A,3,65,66,67,80,81,,,,,,,,1.3,0.7,1.1*34",
    "$GNVTG,,T,,M,0.003,N,0.005,K,A*3B",
};
static const char *const ENDINGS[] = {"\r\n", "\n", "\r", "\r\n\r\n"};

static char stream[4096];
static size_t stream_len;

static void append(const char *text, size_t len)
{
    memcpy(stream + stream_len, text, len);
    stream_len += len;
}

/* The stream: the sentences with their endings, then garbage, a line over NMEA_MAX_LINE, and a
   GGA cut short by a '$' and the last sentence without an ending. */
static void build_stream(void)
{
    size_t i;
    for (i = 0; i < sizeof SENTENCES / sizeof SENTENCES[0]; i++) {
        append(SENTENCES[i], strlen(SENTENCES[i]));
        append(ENDINGS[i % 4], strlen(ENDINGS[i % 4]));
    }
    append("noise", 5);
    append(SENTENCES[0], strlen(SENTENCES[0]));
    append("\n$GPTXT,", 8);
    for (i = 0; i < NMEA_MAX_LINE; i++)
        append("x", 1);
    append("\r\n$GNGGA,1202", 13);
    append(SENTENCES[6], strlen(SENTENCES[6]));
}

/* What a firmware makes of one framed line, appended to `out`: its text and the sentence's
   serialization, or the error's kind. */
static size_t take_line(nmea_framed line, char *out, size_t used, size_t cap)
{
    nmea_sentence s;
    nmea_error err;
    char text[NMEA_MAX_LINE + 1];
    if (!line.ptr)
        return used + (size_t)snprintf(out + used, cap - used, "[%lu bytes]\n", (unsigned long)line.len);
    if (!nmea_parse(&s, line.ptr, line.len, &err))
        return used + (size_t)snprintf(out + used, cap - used, "%.*s -> %s\n", (int)line.len, line.ptr,
                                       nmea_error_kind_name(err.kind));
    CHECK(nmea_serialize(&s, text, sizeof text) == line.len && memcmp(text, line.ptr, line.len) == 0);
    return used + (size_t)snprintf(out + used, cap - used, "%s ok %d\n", text, (int)s.id);
}

/* Everything the firmware makes of the stream, pushed in chunks of `chunk` bytes (0: fed one byte
   at a time). */
static size_t read_stream(size_t chunk, char *out, size_t cap)
{
    nmea_framer framer;
    nmea_framed line;
    size_t used = 0, at = 0;
    nmea_framer_init(&framer);
    while (at < stream_len) {
        const char *p = stream + at;
        size_t n = stream_len - at < chunk ? stream_len - at : chunk;
        if (chunk == 0) {
            if (nmea_framer_feed(&framer, stream[at++], &line))
                used = take_line(line, out, used, cap);
            continue;
        }
        at += n;
        while (nmea_framer_push(&framer, &p, &n, &line))
            used = take_line(line, out, used, cap);
    }
    if (nmea_framer_end(&framer, &line))
        used = take_line(line, out, used, cap);
    return used;
}

static void test_chunks(void)
{
    static char expected[8192], got[8192];
    char overlong[32];
    size_t n = read_stream(stream_len, expected, sizeof expected), chunk, i, oks = 0;
    for (i = 0; i < n; i++)
        oks += memcmp(expected + i, " ok ", 4) == 0;
    CHECK(oks == sizeof SENTENCES / sizeof SENTENCES[0] + 2); /* the GGA after the garbage, the last VTG */
    CHECK(strstr(expected, "noise -> not_a_sentence\n") && strstr(expected, "$GNGGA,1202 -> too_few_fields\n"));
    snprintf(overlong, sizeof overlong, "[%d bytes]\n", NMEA_MAX_LINE + 7);
    CHECK(strstr(expected, overlong) != NULL);
    for (chunk = 0; chunk < stream_len; chunk++) {
        size_t m = read_stream(chunk, got, sizeof got);
        CHECK(m == n && memcmp(got, expected, n) == 0);
        if (m != n || memcmp(got, expected, n) != 0)
            fprintf(stderr, "chunk %lu:\n%.*s\n", (unsigned long)chunk, (int)m, got);
    }
}

/* NMEA 4.10 puts the signal id after the last satellite: it is the signal, not a satellite. */
static void test_signal_id(void)
{
    nmea_sentence s;
    nmea_error err;
    nmea_gsv_satellite sat;
    size_t i, with_prn = 0;
    const char *line = SENTENCES[3];
    CHECK(nmea_parse(&s, line, strlen(line), &err) && s.id == NMEA_SENTENCE_GSV);
    CHECK(s.as.gsv.signal_id.present && strcmp(s.as.gsv.signal_id.code, "1") == 0);
    for (i = 0; nmea_gsv_satellites_at(&s.as.gsv, i, &sat); i++)
        with_prn += sat.prn.present;
    CHECK(i == 4 && with_prn == 1);
    CHECK(nmea_gsv_satellites_at(&s.as.gsv, 0, &sat) && sat.prn.digits == 36 && sat.snr.digits == 51);
    line = SENTENCES[4];
    CHECK(nmea_parse(&s, line, strlen(line), &err) && s.as.gsv.satellites.count == 4);
    CHECK(nmea_gsv_satellites_at(&s.as.gsv, 3, &sat) && sat.prn.digits == 86 && !sat.snr.present);
}

int main(void)
{
    build_stream();
    test_chunks();
    test_signal_id();
    if (failures) {
        fprintf(stderr, "%d check(s) failed\n", failures);
        return 1;
    }
    printf("C stream, --only GGA,RMC,GSV,GSA,VTG, NMEA_MAX_LINE %d: all checks passed\n", NMEA_MAX_LINE);
    return 0;
}
