/*
 * The small build of the five-sentence firmware (issue 32; make test-c, and under the sanitizers
 * make test-c-memory): the C pair generated with --only GGA,RMC,GSV,GSA,VTG twice, as it is (nmea.c,
 * the reference) and renamed with --prefix sml, built with -DSML_SMALL and its default
 * SML_MAX_LINE, the longest line those sentences can have. Each line of the file given (the shared
 * vectors' lines of the five sentences) is parsed by the reference on its own; the small build
 * reads them all as one byte stream, fed one byte at a time (sml_framer_feed) and pushed in chunks of
 * every size up to a line and more (sml_framer_push), and must give for each line what the
 * reference gives: the same sentence, which writes back to the line byte for byte, and for a line
 * refused the same error kind and wire field. The small build reads with the small reader
 * (runtime/c/small.c), which must give the struct of its general reader byte for byte, or its
 * error, on those lines, on each of them mutated byte by byte and cut short, and on a few lines of
 * other sentences (with and without a checksum required). The differences the build's options make: a number
 * outside its range, which the reference keeps as a problem, is a bad field there (strict reading,
 * SML_NO_PROBLEMS), as is a number of more than 9 digits (SML_DIGITS_32).
 */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "nmea.h"
#include "sml.h"

static int failures;
static unsigned long general_checks;

#define CHECK(cond, line)                                                                                            \
    do {                                                                                                             \
        if (!(cond)) {                                                                                               \
            if (failures++ < 20)                                                                                     \
                fprintf(stderr, "%s:%d: check failed: %s\n  line: %s\n", __FILE__, __LINE__, #cond, line);           \
        }                                                                                                            \
    } while (0)

#define MAX_LINES 4096

/* The lines, and the reference's result for each. */
typedef struct {
    char *text;
    size_t len;
    bool ok;
    int id;                   /* nmea_sentence_id */
    nmea_error_kind kind;     /* a refused line: its error */
    unsigned field;
    size_t digits;            /* the most digits of a field of the line */
    bool problems;            /* accepted with a number outside its range (kept as a problem) */
    bool refused;             /* which the small build refuses, as its options say */
} expected_line;

static expected_line lines[MAX_LINES];
static size_t line_count, longest;
static char *stream;
static size_t stream_len;

/* The most digits of one of the line's comma-separated fields. */
static size_t most_digits(const char *line, size_t len)
{
    size_t i, run = 0, most = 0;
    for (i = 0; i < len; i++) {
        if (line[i] == ',' || line[i] == '*')
            run = 0;
        else if (line[i] >= '0' && line[i] <= '9' && ++run > most)
            most = run;
    }
    return most;
}

/* Whether the small build's framer takes the line as one line, as it is (not cut at a second
   start, not a line it drops). */
static bool one_line(const char *line, size_t len)
{
    sml_framer framer;
    sml_framed framed;
    size_t i, n = 0;
    bool same = false;
    sml_framer_init(&framer);
    for (i = 0; i < len + 2; i++)
        if (sml_framer_feed(&framer, i < len ? line[i] : "\r\n"[i - len], &framed)) {
            same = framed.ptr && framed.len == len && memcmp(framed.ptr, line, len) == 0;
            n++;
        }
    return n == 1 && same && !sml_framer_end(&framer, &framed);
}

static void read_lines(const char *path)
{
    static char buf[4096];
    FILE *f = fopen(path, "rb");
    size_t at = 0, i;
    if (!f) {
        perror(path);
        exit(2);
    }
    while (fgets(buf, sizeof buf, f) && line_count < MAX_LINES) {
        expected_line *e = &lines[line_count];
        nmea_sentence s;
        nmea_error err;
        nmea_problems problems;
        nmea_options keep = {false, false, &problems, false};
        size_t len = strcspn(buf, "\r\n");
        if (len == 0 || len > SML_MAX_LINE || !one_line(buf, len))
            continue;
        e->text = malloc(len + 1);
        memcpy(e->text, buf, len);
        e->text[len] = 0;
        e->len = len;
        e->ok = nmea_parse_ex(&s, e->text, len, &keep, &err); /* as nmea_parse, the problems kept */
        e->id = e->ok ? (int)s.id : -1;
        e->kind = e->ok ? NMEA_ERR_NOT_A_SENTENCE : err.kind;
        e->field = e->ok ? 0 : err.field;
        e->digits = most_digits(e->text, len);
        e->problems = e->ok && s.problems != NULL;
        longest = len > longest ? len : longest;
        line_count++;
    }
    fclose(f);
    for (i = 0; i < line_count; i++)
        stream_len += lines[i].len + 2;
    stream = malloc(stream_len);
    for (i = 0; i < line_count; i++) {
        memcpy(stream + at, lines[i].text, lines[i].len);
        memcpy(stream + at + lines[i].len, "\r\n", 2);
        at += lines[i].len + 2;
    }
}

/* The small reader's result (-DSML_SMALL: runtime/c/small.c) against the general reader's of the
   same build (sml_parse_general): the same struct, byte for byte (both start from the same bytes;
   at -Os, where the general reader sets each member of a number: at -O2 its quicker pass copies a
   whole nmea_number, the unused bits of its flags' byte and all), or the same error. */
static void same_as_general(const sml_sentence *s, bool ok, const sml_error *err, sml_framed framed, const char *text)
{
    sml_sentence general;
    sml_error general_err;
    bool general_ok;
    memset(&general, 0xA5, sizeof general);
    general_ok = sml_parse_general(&general, framed.ptr, framed.len, NULL, &general_err);
    CHECK(ok == general_ok, text);
    if (ok && general_ok)
        CHECK(memcmp(s, &general, sizeof general) == 0, text);
    else if (!ok && !general_ok)
        CHECK(err->kind == general_err.kind && err->field == general_err.field &&
              err->out_of_range == general_err.out_of_range, text);
    general_checks++;
    /* and with a checksum required (nmea_parse_ex) */
    {
        sml_sentence small;
        sml_error small_err;
        sml_options require = {false, true, NULL, false};
        memset(&small, 0xA5, sizeof small);
        memset(&general, 0xA5, sizeof general);
        ok = sml_parse_ex(&small, framed.ptr, framed.len, &require, &small_err);
        general_ok = sml_parse_general(&general, framed.ptr, framed.len, &require, &general_err);
        CHECK(ok == general_ok, text);
        if (ok && general_ok)
            CHECK(memcmp(&small, &general, sizeof general) == 0, text);
        else if (!ok && !general_ok)
            CHECK(small_err.kind == general_err.kind && small_err.field == general_err.field, text);
    }
}

/* The small reader against the general one over `line` with each byte in turn replaced by each
   of a few bytes, and cut after each byte; a byte replaced before the checksum makes the checksum
   right again (where the line has one): what the vectors' lines do not show, the edges of each
   field type and of the framing. */
static void mutations(const char *line, size_t len)
{
    static const char replacements[] = ",.-+09AaFfNSEWMPx*$! ";
    char text[SML_MAX_LINE + 2];
    size_t at, k, j;
    for (at = 0; at <= len; at++) {
        for (k = 0; k <= sizeof replacements - 1; k++) {
            sml_framed framed;
            sml_sentence s;
            sml_error err;
            size_t n = k == sizeof replacements - 1 ? at : len; /* the last: cut after `at` bytes */
            unsigned sum = 0;
            bool ok;
            if ((at == len && n == len) || len > SML_MAX_LINE)
                continue;
            memcpy(text, line, len);
            if (n == len)
                text[at] = replacements[k];
            if (n >= 3 && text[n - 3] == '*' && at < n - 3) {
                for (j = 1; j < n - 3 && text[j] != '*'; j++)
                    sum ^= (unsigned char)text[j];
                if (j == n - 3) {
                    text[n - 2] = "0123456789ABCDEF"[sum >> 4];
                    text[n - 1] = "0123456789ABCDEF"[sum & 15];
                }
            }
            text[n] = 0;
            framed.ptr = text;
            framed.len = n;
            memset(&s, 0xA5, sizeof s);
            ok = sml_parse(&s, text, n, &err);
            same_as_general(&s, ok, &err, framed, text);
        }
    }
}

/* Lines of other sentences and addresses, which the small reader keeps as generic sentences or
   refuses as the general one does (mutated too). */
static const char *const OTHER_LINES[] = {
    "$GPGLL,4916.45,N,12311.12,W,225444,A*31",
    "!AIVDM,1,1,,B,15MgK45P3@G?fl0E`JbR0OwT0@MS,0*4E",
    "!GPGGA,092750.000,5321.6802,N,00630.3372,W,1,8,1.03,61.7,M,55.2,M,,*77",
    "$PGRME,15.0,M,45.0,M,25.0,M*1C",
    "$GPGGAH,1*00",
    "$GPGG,1*00",
    "$GPGGA",
    "$GPGGA*",
    "$GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E*68",
    "$GNGSA,A,3,21,5,29,25,12,10,26,2,,,,,1.2,0.7,1.0*27",
    "$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*48",
};

/* The small build's reading of framed line `n` against the reference's. *//* The small build's reading of framed line `n` against the reference's. */
static void compare(size_t n, sml_framed framed)
{
    const expected_line *e = &lines[n];
    sml_sentence s;
    sml_error err;
    char text[SML_MAX_LINE + 1];
    bool ok;
    CHECK(framed.ptr && framed.len == e->len && memcmp(framed.ptr, e->text, e->len) == 0, e->text);
    if (!framed.ptr)
        return;
    memset(&s, 0xA5, sizeof s);
    ok = sml_parse(&s, framed.ptr, framed.len, &err);
    same_as_general(&s, ok, &err, framed, e->text);
    if (!ok && e->ok) { /* only a number outside its range (strict reading) or too long for 32 bits */
        CHECK(err.kind == SML_ERR_BAD_FIELD && ((err.out_of_range && e->problems) || e->digits > 9), e->text);
        lines[n].refused = true;
        return;
    }
    CHECK(ok == e->ok, e->text);
    if (ok && e->ok) {
        CHECK((int)s.id == e->id, e->text);
        CHECK(sml_serialize(&s, text, sizeof text) == e->len && memcmp(text, e->text, e->len) == 0, e->text);
    } else if (!ok) {
        CHECK(strcmp(sml_error_kind_name(err.kind), nmea_error_kind_name(e->kind)) == 0, e->text);
        CHECK(err.field == e->field, e->text);
    }
}

/* The stream read by the small build in chunks of `chunk` bytes (0: fed one byte at a time):
   every line comes out in order. */
static void read_stream(size_t chunk)
{
    sml_framer framer;
    sml_framed framed;
    size_t at = 0, n = 0;
    sml_framer_init(&framer);
    while (at < stream_len) {
        const char *p = stream + at;
        size_t left = stream_len - at < chunk ? stream_len - at : chunk;
        if (chunk == 0) {
            if (sml_framer_feed(&framer, stream[at++], &framed) && n < line_count)
                compare(n++, framed);
            continue;
        }
        at += left;
        while (sml_framer_push(&framer, &p, &left, &framed))
            if (n < line_count)
                compare(n++, framed);
    }
    CHECK(!sml_framer_end(&framer, &framed), "(end of the stream)");
    CHECK(n == line_count, "(every line)");
}

int main(int argc, char **argv)
{
    size_t chunk, i, accepted = 0, refused = 0;
    if (argc != 2) {
        fprintf(stderr, "usage: %s LINES\n", argv[0]);
        return 2;
    }
    read_lines(argv[1]);
    for (i = 0; i < line_count; i++)
        accepted += lines[i].ok;
    CHECK(line_count > 100 && accepted > 50, "(the vectors)");
    read_stream(0);
    for (i = 0; i < line_count; i++)
        refused += lines[i].refused;
    CHECK(refused < line_count / 10, "(few lines refused by the options)");
    for (chunk = 1; chunk <= longest + 3; chunk++)
        read_stream(chunk);
    read_stream(stream_len);
    for (i = 0; i < line_count; i++)
        mutations(lines[i].text, lines[i].len);
    for (i = 0; i < sizeof OTHER_LINES / sizeof OTHER_LINES[0]; i++)
        mutations(OTHER_LINES[i], strlen(OTHER_LINES[i]));
    if (failures) {
        fprintf(stderr, "%d check(s) failed\n", failures);
        return 1;
    }
    printf("C small build (SML_SMALL), --only GGA,RMC,GSV,GSA,VTG, SML_MAX_LINE %d: %lu lines (%lu accepted, %lu "
           "refused as its options say) as the default build, fed byte by byte and in chunks of 1 to %lu "
           "bytes; %lu readings as its general reader's\n",
           SML_MAX_LINE, (unsigned long)line_count, (unsigned long)accepted, (unsigned long)refused,
           (unsigned long)longest + 3, general_checks);
    for (i = 0; i < line_count; i++)
        free(lines[i].text);
    free(stream);
    return 0;
}
