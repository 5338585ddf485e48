/*
 * libFuzzer target for the generated C codec (build: make fuzz-smoke / make fuzz).
 *
 * The input is tried as an NMEA line and as a line of decode's JSON:
 * - a line that parses must serialize back to exactly its bytes, its lossless JSON must rebuild
 *   the same sentence, and both JSON forms must fit NMEA_JSON_MAX;
 * - a line that does not parse must describe its error as JSON;
 * - JSON that rebuilds a sentence must serialize, and that sentence must parse again.
 * Any broken promise aborts, and AddressSanitizer/UndefinedBehaviorSanitizer catch the rest.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "nmea.h"

static char text[NMEA_MAX_LINE + 8];
static char again[NMEA_MAX_LINE + 8];
static char json[NMEA_JSON_MAX];
static char scratch[NMEA_JSON_MAX];

static void as_line(const char *data, size_t size)
{
    nmea_sentence s;
    nmea_sentence rebuilt;
    nmea_error err;
    size_t n;
    size_t j;

    if (!nmea_parse(&s, data, size, &err)) {
        if (nmea_error_to_json(&err, json, sizeof json) == 0)
            abort();
        return;
    }
    n = nmea_serialize(&s, text, sizeof text);
    if (n != size || memcmp(text, data, size) != 0)
        abort();
    if (nmea_to_json(&s, true, json, sizeof json) == 0)
        abort();
    j = nmea_to_json(&s, false, json, sizeof json);
    if (j == 0 || !nmea_from_json(&rebuilt, json, j, scratch, sizeof scratch, &err))
        abort();
    n = nmea_serialize(&rebuilt, again, sizeof again);
    if (n != size || memcmp(again, data, size) != 0)
        abort();
}

static void as_json(const char *data, size_t size)
{
    nmea_sentence s;
    nmea_sentence parsed;
    nmea_error err;
    size_t n;

    if (size > sizeof scratch || !nmea_from_json(&s, data, size, scratch, sizeof scratch, &err))
        return;
    n = nmea_serialize(&s, text, sizeof text);
    if (n == 0 && size < NMEA_MAX_LINE)
        return; /* a sentence rebuilt from JSON may be longer than any line the parser takes */
    if (n > 0 && n <= NMEA_MAX_LINE && !nmea_parse(&parsed, text, n, &err))
        abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    as_line((const char *)data, size);
    as_json((const char *)data, size);
    return 0;
}
