/* UBX messages: the frame (sync B5 62, class, id, little-endian length, payload, Fletcher-8) and
   one interpreter of the generated layout descriptors that reads a payload into a layout's struct,
   writes it back byte for byte and prints its JSON, the C side of the Python runtime's ubx.py
   (its rules and error kinds). The messages of the other binary protocols the spec types
   (SkyTraq, SiRF, CASIC, SBF: the Python runtime's binary.py) go through the same interpreter, in their
   byte order, framed by their row of the generated framing table (sync, length, checksum, end). No heap: a field of the bytes left, the trailing bytes and an
   unknown message's payload are views of the decoded payload. Facts from u-blox UBX-13003221
   ("UBX frame structure", "UBX checksum", "Data types"). */

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* The bytes around a payload: sync (2), class, id, length (2) and the checksum (2). */
#define NMEA_UBX_OVERHEAD 8

typedef enum {
    NMEA_UBX_OK,
    NMEA_UBX_BAD_FRAME,      /* no sync, or a length field other than the frame's */
    NMEA_UBX_BAD_CHECKSUM,   /* the Fletcher-8 sent is not the computed one */
    NMEA_UBX_SHORT_PAYLOAD,  /* the payload ends before a field's last byte */
    NMEA_UBX_TOO_MANY,       /* a group has more entries than its struct holds (NMEA_UBX_MAX_ENTRIES) */
    NMEA_UBX_BAD_VALUE,      /* a value to encode its field cannot hold */
    NMEA_UBX_NO_ROOM         /* the buffer to encode into is too small */
} nmea_ubx_error_kind;

/* An error: its kind, its protocol (nmea_ubx_protocol), the message (`NAV-PVT`, NULL before one is
   known) and field, and its text. */
typedef struct {
    nmea_ubx_error_kind kind;
    uint8_t protocol;
    const char *message;
    const char *field;
    char text[112];
} nmea_ubx_error;

/* The kind as the JSON contract names it ("short_payload"). */
const char *nmea_ubx_error_kind_name(nmea_ubx_error_kind kind);

/* Bytes of a decoded payload, read in place (characters: ISO 8859-1, as sent). */
typedef struct {
    const uint8_t *ptr;
    size_t len;
} nmea_ubx_bytes;

/* A frame of a class and id (a key) the spec does not describe, kept with its payload. Of another
   protocol than UBX (`protocol`, a nmea_ubx_protocol; 0 is UBX): msg_class and msg_id hold its key,
   `key_len` bytes of it (CASIC's class and id; SkyTraq's and SiRF's message id, the payload's
   first byte, and `payload` the bytes after it). */
typedef struct {
    uint8_t msg_class, msg_id;
    nmea_ubx_bytes payload;
    uint8_t protocol, key_len;
} nmea_ubx_unknown;

/* The checksums of the binary protocols' frames. */
typedef enum {
    NMEA_UBX_CHECK_FLETCHER8, /* two 8-bit running sums, sent in that order */
    NMEA_UBX_CHECK_XOR8,      /* the XOR of the bytes */
    NMEA_UBX_CHECK_SUM15,     /* the bytes' sum modulo 2^15, two bytes big endian */
    NMEA_UBX_CHECK_SUM32,     /* the sum of the bytes as 32-bit little-endian words, sent little endian */
    NMEA_UBX_CHECK_CRC16_CCITT, /* CRC-CCITT (polynomial 0x1021, initial value 0), sent little endian (SBF) */
    NMEA_UBX_CHECK_CRC32      /* CRC-32 (reflected 0xEDB88320, initial value 0, no final inversion), sent little
                                 endian (Unicore) */
} nmea_ubx_check;

/* A field of the header that tells the message (an unknown message's JSON names it): its name, its
   lowest bit in the 16-bit word of the key's two bytes (read in the protocol's byte order), its bits. */
typedef struct {
    const char *name;
    uint8_t low, bits;
} nmea_ubx_key_field;

/* A header field that a decoded message keeps and its frame is written with (Unicore's time and
   status: spec/binary/<protocol>/protocol.yaml's fields of `identity: false`): its name, its first
   byte in the frame, its bytes (1, 2 or 4: unsigned, in the protocol's byte order) and the offset of
   its member (of as many bytes) in nmea_ubx_message. */
typedef struct {
    const char *name;
    uint8_t at, size;
    uint16_t offset;
} nmea_ubx_header_field;

/* The framing of a protocol (spec/binary/<protocol>/protocol.yaml; generated, not for use by hand).
   Offsets count from the first sync byte. */
typedef struct {
    const char *name;     /* as the tools' JSON names it: skytraq */
    const char *upper;    /* as errors name it: SKYTRAQ */
    uint8_t sync[3];      /* its sync bytes, sync_len of them */
    uint8_t sync_len;
    uint8_t header;       /* bytes before the payload, sync included */
    uint8_t length_at;    /* the length field's first byte (two bytes, the protocol's byte order) */
    uint16_t length_mask; /* its bits that count the payload's bytes */
    uint8_t key_at;       /* the header's byte of the class, then the id (UBX, CASIC; SBF: its two bytes of
                             block number and revision; Unicore: its 16-bit message id, little endian); 0: the
                             key is the payload's first byte (the id;
                             SkyTraq, SiRF) */
    uint8_t check;        /* nmea_ubx_check */
    uint8_t check_from;   /* the first byte the checksum covers (to the payload's end) */
    uint8_t check_size;
    uint8_t end[2], end_len;
    bool big;             /* its fields are big endian */
    uint8_t length_adds;  /* the frame's bytes beyond what the length counts (0: it counts the whole frame: SBF) */
    uint8_t check_at;     /* the checksum's first byte in the header (SBF); 0: after the payload */
    nmea_ubx_key_field key_fields[2]; /* where the header holds the key: its fields */
    const nmea_ubx_header_field *kept; /* the header fields a message keeps (`header`), n_kept of them */
    uint8_t n_kept;
} nmea_ubx_framing;

/* The descriptors the interpreter walks (generated per layout; not for use by hand). */
typedef enum {
    NMEA_UBX_ITEM_UNSIGNED, /* u1..u8 (and a reserved field of up to 8 bytes) */
    NMEA_UBX_ITEM_SIGNED,   /* i1..i8 */
    NMEA_UBX_ITEM_WORD,     /* x1..x4: its parts follow it */
    NMEA_UBX_ITEM_FLOAT,    /* r4, r8: float, double (their bits as sent) */
    NMEA_UBX_ITEM_ARRAY,    /* ch, bytes, reserved of a fixed width: an array of that many bytes */
    NMEA_UBX_ITEM_VIEW,     /* ch, bytes of the bytes left: a view */
    NMEA_UBX_ITEM_PART,     /* a bitfield's unsigned part */
    NMEA_UBX_ITEM_PART_SIGNED,
    NMEA_UBX_ITEM_PART_FLAG,
    NMEA_UBX_ITEM_GROUP
} nmea_ubx_kind;

/* How an item prints in JSON besides its kind. */
typedef enum {
    NMEA_UBX_PRINT_NUMBER,
    NMEA_UBX_PRINT_CHARS, /* an array or view of characters */
    NMEA_UBX_PRINT_HEX,   /* bytes: lower-case hex */
    NMEA_UBX_PRINT_BIG,   /* a reserved array: its little-endian integer */
    NMEA_UBX_PRINT_CODE,  /* a number that is a code of an enum: its id */
    NMEA_UBX_PRINT_SCALED /* a number in a unit, beside its raw integer */
} nmea_ubx_print;

/* A raw value that is no number ("not_available", ...); of a float field (r4, r8), the bit
   pattern of the float that stands for it (SBF's do-not-use -2e10), an r8's as its int64_t. */
typedef struct {
    int64_t raw;
    const char *id;
} nmea_ubx_special;

/* A number in a unit: raw / divisor + base (a float when `real`), or a special value. */
typedef struct {
    double divisor, base;
    bool real;
    const nmea_ubx_special *specials;
    uint8_t n_specials;
} nmea_ubx_scale;

/* A code of an enum by its id. */
typedef struct {
    int64_t code;
    const char *id;
} nmea_ubx_code;

typedef struct {
    const nmea_ubx_code *codes;
    uint16_t n;
} nmea_ubx_codes;

typedef struct {
    const char *id;
    const void *extra; /* a nmea_ubx_scale (PRINT_SCALED; a FLOAT's special values), nmea_ubx_codes (PRINT_CODE),
                          nmea_ubx_group */
    uint16_t offset;   /* of its member in the layout's struct */
    uint16_t has;      /* an optional field (present when the payload has its bytes): its flag's offset */
    uint16_t after;    /* a field of the bytes left: the bytes of the required fields after it */
    uint8_t kind;      /* nmea_ubx_kind */
    uint8_t size;      /* bytes in the payload (0: the bytes left); a part: its bits */
    uint8_t member;    /* bytes of the member (a number), of the array */
    uint8_t low;       /* a part: its lowest bit in the word */
    uint8_t print;     /* nmea_ubx_print */
    bool optional;
} nmea_ubx_item;

typedef enum {
    NMEA_UBX_COUNT_FIXED, /* `count` entries */
    NMEA_UBX_COUNT_FIELD, /* as many as the member at `count_offset` says */
    NMEA_UBX_COUNT_LEFT   /* while the bytes left before `after` hold one, at most `max` */
} nmea_ubx_count;

typedef struct nmea_ubx_group {
    const nmea_ubx_item *items;
    uint8_t n_items;
    uint8_t count_kind;     /* nmea_ubx_count */
    uint8_t count_member;   /* bytes of the count's member */
    uint16_t count_offset;  /* of the count's member */
    uint16_t count;         /* a fixed count */
    uint16_t min, limit;    /* limit: the most the bytes left may give (the spec's maximum) */
    uint16_t max;           /* the entries its array holds */
    uint16_t entry_bytes;   /* of an entry in the payload */
    uint16_t entry_size;    /* sizeof an entry's struct */
    uint16_t after;         /* bytes of the required fields after the group */
    uint16_t n_offset;      /* of the member that says how many entries the array holds (uint16_t) */
    uint8_t stride_member;  /* a stride's (SBF's SBLength: the bytes of each entry, its last item a view of
                               those after its fields): bytes of its member; 0: entries of entry_bytes */
    uint16_t stride_offset; /* of the stride's member */
    const char *stride_id;  /* the stride's field (errors name it) */
    const struct nmea_ubx_group *nested; /* the group each entry ends with (SBF's Type-2 sub-blocks after each
                               Type-1), or NULL: counted by a member of the entry (its count_offset the entry's),
                               its entries after the entry's stride bytes; every entry's in one array of the
                               message, an entry's from its index at nested_first */
    const char *nested_id;  /* the nested group's field (errors and JSON name it) */
    uint16_t nested_offset; /* of the nested group's array in the message */
    uint16_t nested_first;  /* of an entry's uint16_t index of its first entry in that array */
} nmea_ubx_group;

typedef struct {
    const char *id;      /* nav_pvt */
    const char *address; /* NAV-PVT */
    uint8_t msg_class, msg_id; /* its key (SkyTraq, SiRF: the id and sub-id, `key_len` of them) */
    bool output;         /* the receiver sends it */
    uint8_t protocol;    /* nmea_ubx_protocol */
    int32_t length;      /* its fixed payload bytes, -1 for none */
    int16_t select_value; /* the value of its selector byte (a version, type or command) that tells it
                             apart, -1 for none */
    uint16_t select_at;   /* ... at this byte */
    const nmea_ubx_item *items;
    uint8_t n_items;
    uint8_t key_len;     /* SkyTraq, SiRF: the bytes of the payload before its fields (id, sub-id) */
    uint16_t trailing;   /* the offset of its `trailing` member */
} nmea_ubx_layout_info;
