/* AIS payloads: the six-bit armoring of !AIVDM/!AIVDO and a bit reader and writer over it, the C
   side of the Python runtime's ais.py (its rules and error kinds). Reading keeps views of the
   armored characters (no copy, no heap); writing fills a fixed buffer. Facts from ITU-R M.1371-5
   (armoring: annex 8, table 47) and gpsd's "AIVDM/AIVDO protocol decoding". */

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* The most bits an encoded message holds: five slots of 256 bits. */
#define NMEA_AIS_MAX_BITS (5 * 256)
#define NMEA_AIS_MAX_CHARS ((NMEA_AIS_MAX_BITS + 5) / 6)

typedef enum {
    NMEA_AIS_OK,
    NMEA_AIS_BAD_ARMOR,       /* a character outside the armoring, fill bits outside 0-5 */
    NMEA_AIS_SHORT_PAYLOAD,   /* the payload ends before a field's last bit */
    NMEA_AIS_UNKNOWN_MESSAGE, /* a message type the spec does not describe */
    NMEA_AIS_BAD_VALUE        /* a value to encode its field cannot hold */
} nmea_ais_error_kind;

/* An error: its kind, the message type (-1 before it is read) and field, and its message. */
typedef struct {
    nmea_ais_error_kind kind;
    int message_type;
    const char *field;
    char message[128];
} nmea_ais_error;

/* The kind as the JSON contract names it ("short_payload"). */
const char *nmea_ais_error_kind_name(nmea_ais_error_kind kind);

/* Bits of an armored payload read in place: a field's view (text, data) or the whole message. */
typedef struct {
    const char *armored;
    size_t offset, len;
} nmea_ais_bits;

/* The bits of a payload read most significant first, up to `end`. */
typedef struct {
    const char *armored;
    size_t pos, end;
    int message_type;
    nmea_ais_error *err;
} nmea_ais_reader;

/* A payload being written. */
typedef struct {
    uint8_t values[NMEA_AIS_MAX_CHARS];
    size_t len;
    int message_type;
    nmea_ais_error *err;
} nmea_ais_writer;

/* An encoded payload: its armored characters (NUL-terminated) and fill bits. */
typedef struct {
    char chars[NMEA_AIS_MAX_CHARS + 1];
    uint8_t fill_bits;
} nmea_ais_armored;

/* A raw value that is no number ("not_available", ...). */
typedef struct {
    int64_t raw;
    const char *id;
} nmea_ais_special;

/* JSON written into a caller's buffer; `len` counts what did not fit too. */
typedef struct {
    char *buf;
    size_t cap, len;
    bool empty;
} nmea_ais_json_out;
