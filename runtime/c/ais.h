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

/* Text of a message a program builds (a name, a call sign, a safety message): `text` (NUL-ended)
   armored into `buf` (`cap` bytes, a byte a character, no NUL added) and `out` its bits. A field
   of fixed width takes exactly its characters: pad a shorter text with '@', as transmitters do.
   false (bad_value in `err`) for a character six-bit text cannot carry or a text longer than `cap`. */
bool nmea_ais_text(const char *text, char *buf, size_t cap, nmea_ais_bits *out, nmea_ais_error *err);

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

/* The error as the tools' JSON error object (kind, address `AIS type N` or `AIS`, field null,
   the field as name, message) into `buf` (NUL-terminated when `cap` > 0): the length it needs. */
size_t nmea_ais_error_json(const nmea_ais_error *err, char *buf, size_t cap);

/* Messages across sentences: how many may be under way at once, and how many payload characters
   each may hold (nine fragments of 62); a firmware may set both. */
#ifndef NMEA_AIS_SLOTS
#define NMEA_AIS_SLOTS 16
#endif
#ifndef NMEA_AIS_CAPACITY
#define NMEA_AIS_CAPACITY 558
#endif
/* The most fragments of one message (NMEA 0183: a count is one digit). */
#define NMEA_AIS_MAX_FRAGMENTS 9
/* The bytes of a key: a TAG source and group id, or a talker, sentence, channel and id. */
#define NMEA_AIS_KEY_CAPACITY 40

/* What an encapsulation sentence (!AIVDM) says of the message it carries all or part of: the
   fields its spec's `encapsulates` names, with its talker and sentence id for the key. Views of
   the parsed line. */
typedef struct {
    nmea_text talker, sentence;
    uint8_t count, number; /* how many fragments the message has (1-9), which this is */
    int sequence;          /* the sequential message id, -1 for none */
    nmea_text channel;     /* empty: none */
    nmea_text payload;
    uint8_t fill_bits;
} nmea_ais_fragment;

/* What an encapsulation sentence says of its message; false for another sentence, or one whose
   count is not 1-9 or whose number is empty. */
bool nmea_ais_fragment_of(const nmea_sentence *s, nmea_ais_fragment *out);

/* A message done with: the lines that carried it (their indices among the lines fed, in fragment
   order) with their fragment numbers and, when it is whole, its joined payload and the last
   fragment's fill bits; else it was given up (incomplete_message). Valid during the callback. */
typedef struct {
    const uint32_t *lines;
    const uint8_t *numbers;
    size_t n;
    uint8_t count;
    bool complete;
    const char *payload;
    size_t payload_len;
    uint8_t fill_bits;
} nmea_ais_assembled;

typedef void nmea_ais_done(const nmea_ais_assembled *done, void *context);

typedef struct {
    uint8_t number, fill_bits;
    uint32_t line;
    size_t start, end; /* of its payload in the slot's */
} nmea_ais_part;

/* A message under way (`count` 0: a free slot); payloads kept in the order they came. */
typedef struct {
    char key[NMEA_AIS_KEY_CAPACITY];
    size_t key_len;
    uint8_t count;
    uint32_t started;
    nmea_ais_part parts[NMEA_AIS_MAX_FRAGMENTS];
    size_t n_parts;
    char payload[NMEA_AIS_CAPACITY];
} nmea_ais_slot;

/* Joins the fragments of multi-sentence AIS messages in fixed memory, as Python's
   nmeaspec.assembly and Rust's assembly::Assembler do (tests/data/ais/assembly_cases.jsonl).
   A message of one sentence comes back at once; one of several with its last missing fragment,
   whatever their order, interleaved with other sentences, joined under its key: the TAG group
   (with its source) when the line has one, else the talker, sentence, channel and sequential id.
   It is given up when a fragment it has comes again or one with another count, when `lifetime`
   encapsulation sentences have come since its first fragment, when every slot is taken and a
   newer message needs one (the oldest goes), when its payload outgrows NMEA_AIS_CAPACITY or its
   key NMEA_AIS_KEY_CAPACITY, and at nmea_ais_assembler_finish. */
typedef struct {
    nmea_ais_slot slots[NMEA_AIS_SLOTS];
    uint32_t lifetime, lines, seen;
    uint32_t out_lines[NMEA_AIS_MAX_FRAGMENTS];
    uint8_t out_numbers[NMEA_AIS_MAX_FRAGMENTS];
    char out_payload[NMEA_AIS_CAPACITY];
} nmea_ais_assembler;

/* An empty assembler that gives a message up after `lifetime` (at least 1) encapsulation
   sentences. */
void nmea_ais_assembler_init(nmea_ais_assembler *a, uint32_t lifetime);

/* Counts a line (from 0) and calls `done` with what its fragment (NULL: the line carries no AIS
   message) completes or gives up, in order; `tag_blocks` are the line's (nmea_sentence's). */
void nmea_ais_assembler_feed(nmea_ais_assembler *a, const nmea_ais_fragment *fragment, nmea_text tag_blocks,
                             nmea_ais_done *done, void *context);

/* Gives up every message still under way, oldest first (the stream has ended). */
void nmea_ais_assembler_finish(nmea_ais_assembler *a, nmea_ais_done *done, void *context);

/* The message of a given-up message's incomplete_message error ("fragment 2 of 2 never came")
   into `buf` (NUL-terminated when `cap` > 0): the length it needs. */
size_t nmea_ais_incomplete_message(const nmea_ais_assembled *done, char *buf, size_t cap);
