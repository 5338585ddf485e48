/* RTCM 3 messages: the frame (preamble D3, 10-bit length, payload, CRC-24Q), a bit reader and
   writer over a payload's bytes (most significant bit first), sign-magnitude numbers, characters
   as sent and JSON, the C side of the Python runtime's rtcm3.py and ais.py's bit layouts (their
   rules, error kinds and messages). A pair that needs nothing of nmea.h. No heap: characters,
   data (an MSM's cell mask), the bits after a layout and an unknown message's payload are views of
   the decoded payload; a group is an array of the layout's maximum (an MSM: 64 satellites, 64
   cells). Facts from the public field lists named in spec/binary/rtcm3/protocol.yaml (pyrtcm,
   gpsd, RTKLIB). */

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* The most bytes of a payload (its length has 10 bits) and of a frame (3 before it, 3 after). */
#define NMEA_RTCM3_MAX_PAYLOAD 1023
#define NMEA_RTCM3_MAX_FRAME (NMEA_RTCM3_MAX_PAYLOAD + 6)

typedef enum {
    NMEA_RTCM3_OK,
    NMEA_RTCM3_BAD_SYNC,      /* the first byte is not the preamble D3 */
    NMEA_RTCM3_SHORT_FRAME,   /* fewer bytes than 6, or than the length field says */
    NMEA_RTCM3_LONG_FRAME,    /* more bytes than the length field says */
    NMEA_RTCM3_BAD_CHECKSUM,  /* the CRC-24Q sent is not the computed one */
    NMEA_RTCM3_SHORT_PAYLOAD, /* the payload ends before a field's last bit, or a group's entries */
    NMEA_RTCM3_BAD_VALUE      /* masks set more bits than a group holds; a value its field cannot hold */
} nmea_rtcm3_error_kind;

/* An error: its kind, the message number (-1 before it is read) and field, and its message. */
typedef struct {
    nmea_rtcm3_error_kind kind;
    int message_number;
    const char *field;
    char message[112];
} nmea_rtcm3_error;

/* The kind as the JSON contract names it ("short_payload"). */
const char *nmea_rtcm3_error_kind_name(nmea_rtcm3_error_kind kind);

/* The error as the tools' JSON error object (kind, address `RTCM3 N` or `RTCM3`, field null, the
   field as name, message) into `buf` (NUL-terminated when `cap` > 0): the length it needs. */
size_t nmea_rtcm3_error_json(const nmea_rtcm3_error *err, char *buf, size_t cap);

/* CRC-24Q (polynomial 0x1864CFB, initial value 0) of `len` bytes. */
uint32_t nmea_rtcm3_crc24q(const uint8_t *data, size_t len);

/* The payload of the one frame `frame` holds, its preamble, length and checksum checked. */
bool nmea_rtcm3_payload_of(const uint8_t *frame, size_t len, const uint8_t **payload, size_t *payload_len,
                           nmea_rtcm3_error *err);

/* Bits of a payload read in place: characters, data, the bits after a layout. */
typedef struct {
    const uint8_t *data;
    size_t offset, len;
} nmea_rtcm3_bits;

/* The bits of a payload, read most significant first. */
typedef struct {
    const uint8_t *data;
    size_t pos, end;
    int message_number;
    nmea_rtcm3_error *err;
} nmea_rtcm3_reader;

/* A payload being written (the bits not written yet are 0). */
typedef struct {
    uint8_t bytes[NMEA_RTCM3_MAX_PAYLOAD];
    size_t len; /* bits */
    int message_number;
    nmea_rtcm3_error *err;
} nmea_rtcm3_writer;

/* A frame of a message number the spec does not describe (4001-4095, ...), kept with its payload
   (message_number -1 for a payload of fewer than two bytes). */
typedef struct {
    int message_number;
    const uint8_t *payload;
    size_t len;
} nmea_rtcm3_unknown;

/* JSON being written into a caller's buffer (its length counts what did not fit). */
typedef struct {
    char *buf;
    size_t cap, len;
    bool empty;
} nmea_rtcm3_json_out;

/* A raw value that is no number ("invalid", "negative_zero"). */
typedef struct {
    int64_t raw;
    const char *id;
} nmea_rtcm3_special;
