/*
 * Unit tests of the C runtime on its own (make test-runtimes): runtime.h and runtime.c compiled
 * as one unit with the few settings the generated nmea.h gives them, without any sentence. The
 * generated pair is tested over the manuals' examples and the real logs elsewhere; this holds the
 * runtime's own rules (framing, checksum, the errors' messages, the stream framer, numbers and
 * enum lookups) where it is written.
 */

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* What nmea.h defines before the runtime (from the spec): the longest enum code and the JSON
   buffer size. */
#define NMEA_CODE_MAX 3
#define NMEA_JSON_MAX 2048

#include "runtime.h"

/* The generated code is the runtime's only user of its layout interpreter; unused here. */
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-const-variable"
#endif
#include "runtime.c"

static int failures;

#define CHECK(cond)                                                                  \
    do {                                                                             \
        if (!(cond)) {                                                               \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
            failures++;                                                              \
        }                                                                            \
    } while (0)

static bool message_is(const nmea_error *err, const char *expected)
{
    char buf[256];
    size_t n = nmea_error_message(err, buf, sizeof buf);
    if (n == strlen(expected) && memcmp(buf, expected, n) == 0)
        return true;
    fprintf(stderr, "message \"%.*s\", expected \"%s\"\n", (int)n, buf, expected);
    return false;
}

/* frame_line on a NUL-terminated line: true when it frames, else the error's kind and message. */
static bool frames(const char *line, nmea_frame *f, nmea_error *err)
{
    memset(err, 0, sizeof *err);
    return frame_line(f, line, strlen(line), false, err);
}

static void test_framing(void)
{
    nmea_frame f;
    nmea_error err;
    char long_line[NMEA_MAX_LINE + 2];

    CHECK(frames("$GPGLL,5550.6135,N,03732.2515,E,075241.00,A,A*6E", &f, &err));
    CHECK(f.address.len == 5 && memcmp(f.address.ptr, "GPGLL", 5) == 0);
    CHECK(f.count == 7 && f.checksum == NMEA_CHECKSUM_UPPER);
    CHECK(frames("$PSTMSAVEPAR*58", &f, &err) && f.count == 0);
    CHECK(frames("$GPTXT,hello", &f, &err) && f.checksum == NMEA_CHECKSUM_NONE);

    CHECK(!frames("", &f, &err) && err.kind == NMEA_ERR_NOT_A_SENTENCE && message_is(&err, "empty line"));
    CHECK(!frames("GPGGA,1*00", &f, &err) && message_is(&err, "line does not start with '$' or '!'"));
    CHECK(!frames("$GPGLL,5550.6135,N,03732.2515,E,075241.00,A,A*6C", &f, &err));
    CHECK(err.kind == NMEA_ERR_CHECKSUM_MISMATCH && message_is(&err, "checksum is 6C, computed 6E"));
    CHECK(frames("$GPGLL,1*4d", &f, &err) && f.checksum == NMEA_CHECKSUM_LOWER);
    CHECK(!frames("$GPGLL,1*4D4", &f, &err) && err.kind == NMEA_ERR_BAD_CHECKSUM);
    CHECK(!frames("$GPGLL,1*6", &f, &err) && err.kind == NMEA_ERR_BAD_CHECKSUM);
    CHECK(!frames("$GP\x01GLL,1", &f, &err) && err.kind == NMEA_ERR_NOT_A_SENTENCE);
    CHECK(message_is(&err, "byte 0x01 at offset 3 is not printable ASCII"));

    memset(long_line, 'A', sizeof long_line);
    long_line[0] = '$';
    CHECK(!frame_line(&f, long_line, NMEA_MAX_LINE + 1, false, &err) && err.kind == NMEA_ERR_TOO_LONG);
    CHECK(message_is(&err, "line is 1025 bytes, the limit is 1024"));

    memset(&err, 0, sizeof err);
    CHECK(!frame_line(&f, "$GPGLL,1", 8, true, &err) && err.kind == NMEA_ERR_MISSING_CHECKSUM);
    CHECK(message_is(&err, "the sentence has no checksum"));
}

static void test_error_kind_names(void)
{
    CHECK(strcmp(nmea_error_kind_name(NMEA_ERR_TOO_LONG), "too_long") == 0);
    CHECK(strcmp(nmea_error_kind_name(NMEA_ERR_BAD_FIELD), "bad_field") == 0);
    CHECK(strcmp(nmea_error_kind_name(NMEA_ERR_BAD_JSON), "bad_json") == 0);
}

/* Every line the framer gives for `stream`, pushed in chunks of `chunk` bytes, joined by '|'. */
static size_t frame_all(const char *stream, size_t chunk, char *out, size_t cap)
{
    nmea_framer framer;
    nmea_framed line;
    size_t used = 0, at = 0, total = strlen(stream);
    nmea_framer_init(&framer);
    while (at < total) {
        const char *p = stream + at;
        size_t n = total - at < chunk ? total - at : chunk;
        at += n;
        while (nmea_framer_push(&framer, &p, &n, &line))
            used += (size_t)snprintf(out + used, cap - used, "%.*s|", (int)line.len, line.ptr ? line.ptr : "");
    }
    if (nmea_framer_end(&framer, &line))
        used += (size_t)snprintf(out + used, cap - used, "%.*s|", (int)line.len, line.ptr ? line.ptr : "");
    return used;
}

static void test_framer(void)
{
    static const char stream[] = "garbage$GPGLL,1*00\r\n\r\n$GPGLL,2\r$$GPTXT,3\n!AIVDM,4";
    static const char expected[] = "garbage|$GPGLL,1*00|$GPGLL,2|$|$GPTXT,3|!AIVDM,4|";
    char out[256];
    size_t chunk;
    for (chunk = 1; chunk <= sizeof stream; chunk++) {
        size_t n = frame_all(stream, chunk, out, sizeof out);
        CHECK(n == strlen(expected) && memcmp(out, expected, n) == 0);
    }
}

static void test_numbers(void)
{
    nmea_number n = nmea_number_of(-5, 1);
    CHECK(n.present && n.digits == 5 && n.scale == 1 && n.sign == '-');
    CHECK(nmea_number_scaled(&n, 1) == -5 && nmea_number_scaled(&n, 3) == -500);
    n = nmea_number_of(1201, 0);
    CHECK(nmea_number_scaled(&n, 0) == 1201 && nmea_number_scaled(&n, 2) == 120100);
}

static const nmea_enum_code status_codes[] = {{"A", "valid"}, {"V", "invalid"}};
static const nmea_enum_def status_def = {"status", status_codes, 2, 1, 1, NMEA_CODES_LETTERS};

static void test_enums(void)
{
    nmea_enum e = nmea_enum_of(&status_def, 1);
    CHECK(e.present && strcmp(e.code, "V") == 0);
    CHECK(strcmp(nmea_enum_id(&status_def, &e), "invalid") == 0);
    CHECK(nmea_enum_lookup(&status_def, 'A') == 0);
    CHECK(nmea_enum_lookup(&status_def, 'X') == NMEA_UNKNOWN_CODE);
    CHECK(nmea_enum_lookup(&status_def, '\0') == NMEA_UNKNOWN_CODE);
    e.value = NMEA_UNKNOWN_CODE;
    CHECK(nmea_enum_id(&status_def, &e) == NULL);
}

int main(void)
{
    test_framing();
    test_error_kind_names();
    test_framer();
    test_numbers();
    test_enums();
    if (failures) {
        fprintf(stderr, "%d check(s) failed\n", failures);
        return 1;
    }
    printf("C runtime: all checks passed\n");
    return 0;
}
