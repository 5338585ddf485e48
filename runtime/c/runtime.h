/*
 * Runtime types (hand-written: runtime/c/runtime.h).
 *
 * Conventions of the whole API:
 * - No heap, no global mutable state: every struct is owned by the caller, every function is
 *   reentrant. Nothing here needs more than a few kilobytes of stack (parsing: well under one).
 * - Texts are nmea_text slices (pointer + length, not NUL-terminated). A parsed sentence points
 *   into the line given to the parser (text, enum_chars and talker fields, the raw fields of an
 *   nmea_generic): keep that line alive and unchanged while the sentence is used. Sentences
 *   rebuilt from JSON point into the caller's scratch buffer the same way. nmea_error points
 *   into the line (or scratch buffer) too.
 * - Every field can be empty on the wire; each value type says how it marks "no value"
 *   (`present == false`, a zero char, an empty slice).
 * - Functions that write text (nmea_serialize, nmea_to_json, ...) take a buffer and its capacity,
 *   write a NUL-terminated string and return its length, or return 0 (writing at most a NUL at
 *   buf[0]) when the text and its NUL do not fit. They never write past `cap`.
 */

/**
 * Longest line (without its line ending) the parser accepts and the stream framer holds. By
 * default the longest line a sentence of the generated pair can have (each field at the longest
 * text its type takes), at most 1024, the bound of the tools; a build sets its own with
 * -DNMEA_MAX_LINE=N, the same for nmea.c and every file that includes nmea.h. NMEA 0183 allows
 * 82 bytes, but receivers send longer lines (NMEA 4.11 fields, proprietary sentences).
 */
#ifndef NMEA_MAX_LINE
#define NMEA_MAX_LINE 1024
#endif

/** Most digits a number's text may have (a TAG block's integer too). */
#define NMEA_MAX_DIGITS 18

/**
 * The digits of a number field (nmea_number.digits) and how many it holds: NMEA_MAX_DIGITS in a
 * signed 64-bit integer; with -DNMEA_DIGITS_32 (a firmware short of RAM: 8-byte numbers, not 16)
 * 9 in a 32-bit one, and a number field of more digits is then refused as a bad field, as one of
 * more than 18 is by default.
 */
#ifdef NMEA_DIGITS_32
typedef int32_t nmea_digits;
#define NMEA_NUMBER_DIGITS 9
#else
typedef int64_t nmea_digits;
#define NMEA_NUMBER_DIGITS NMEA_MAX_DIGITS
#endif

/** A run of bytes that belongs to someone else (usually the parsed line). */
typedef struct {
    const char *ptr;
    size_t len;
} nmea_text;

/** A slice of a NUL-terminated string (which must outlive the slice). */
nmea_text nmea_text_of(const char *s);

/** How the checksum of a sentence is written. */
typedef enum {
    NMEA_CHECKSUM_UPPER = 0, /* "*6A" (also the style of an all-digit checksum) */
    NMEA_CHECKSUM_LOWER,     /* "*6a" */
    NMEA_CHECKSUM_NONE,      /* no checksum at all */
    NMEA_CHECKSUM_EMPTY,     /* a bare '*': the checksum left out, as ST's manual writes commands */
    NMEA_CHECKSUM_SHORT_UPPER, /* "*B": one hex digit, a checksum under 16 as some instruments send it
                                  (kept unless nmea_options.strict; two digits once the sum is 16 or more) */
    NMEA_CHECKSUM_SHORT_LOWER  /* "*b" */
} nmea_checksum_style;

/**
 * A fixed-point number as received (integer and decimal fields): its value is
 * digits * 10^-scale, negative when sign is '-'. `width` (integer digits written, leading zeros
 * included), `sign` ('+', '-' or 0) and `point` (a '.' was written, even with no decimals) keep
 * the exact text for the round trip: "-007.50" is {750, 2, 3, '-', true}.
 */
typedef struct {
    nmea_digits digits;
    uint8_t scale;
    uint8_t width;
    char sign;
#ifdef NMEA_DIGITS_32 /* the two flags in one byte: 8 bytes in all, not 12 */
    bool point : 1;
    bool present : 1;
#else
    bool point;
    bool present;
#endif
} nmea_number;

/** The value of `n` in units of 10^-scale (truncated toward zero), e.g. scale 3 for
    thousandths. Digits beyond the int64 range are not checked for: keep scale small. */
int64_t nmea_number_scaled(const nmea_number *n, unsigned scale);

/** The number value * 10^-scale written the plain way (no leading zeros, no '+', `scale`
    decimals), for a struct to build: nmea_number_of(1201, 0) is "1201", (-5, 1) is "-0.5".
    `scale` is at most NMEA_MAX_DIGITS, `value` of at most NMEA_NUMBER_DIGITS digits. */
nmea_number nmea_number_of(int64_t value, unsigned scale);

/** An inclusive value range (integer and decimal fields, table parameters): min * 10^-min_scale
    to max * 10^-max_scale, each bound only when has_min / has_max. (The small members last: 24
    bytes, not 40; the generated code initializes it by member names.) */
typedef struct {
    int64_t min;
    int64_t max;
    uint8_t min_scale;
    uint8_t max_scale;
    bool has_min;
    bool has_max;
} nmea_range;

/** An unsigned hexadecimal number; the digit count and the letter case are kept. */
typedef struct {
    uint64_t value;
    uint8_t digits;
    bool lower;
    bool present;
} nmea_hex;

/** A UTC time of day hhmmss[.f...]: `fraction` has `fraction_digits` digits (0 to 9);
    `point` says whether a '.' was written. */
typedef struct {
    uint8_t hour;
    uint8_t minute;
    uint8_t second;
    uint8_t fraction_digits;
    uint32_t fraction;
    bool point;
    bool present;
} nmea_time;

/** A date ddmmyy with its two-digit year. */
typedef struct {
    uint8_t day;
    uint8_t month;
    uint8_t year;
    bool present;
} nmea_date;

/** A latitude (ddmm.mmmm,N) or longitude (dddmm.mmmm,E) as received: whole degrees (written
    with `degree_digits` digits), minutes as a fixed-point number and the hemisphere letter. */
typedef struct {
    uint16_t degrees;
    uint8_t degree_digits;
    char hemisphere;
    bool present; /* before `minutes`, in the padding its alignment leaves: 24 bytes, not 32 */
    nmea_number minutes;
} nmea_coordinate;

/** Which characters a code unknown to the spec may use to be kept rather than rejected;
    NMEA_CODES_CLOSED: none (a closed set such as N/S or A/V refuses every other code). */
typedef enum { NMEA_CODES_DIGITS, NMEA_CODES_LETTERS, NMEA_CODES_ALNUM, NMEA_CODES_CLOSED } nmea_code_class;

/** One code of a lookup table: the wire text and the spec's id. */
typedef struct {
    const char *code;
    const char *id;
} nmea_enum_code;

/** A lookup table of the spec (one per spec/enums file): nmea_<enum>_def. */
typedef struct {
    const char *name;
    const nmea_enum_code *codes; /* indexed by the table's C enum */
    uint8_t count;
    uint8_t min_len;
    uint8_t max_len;
    nmea_code_class code_class;
} nmea_enum_def;

/** The value `nmea_enum.value` has for a well-formed code the table does not know. */
#define NMEA_UNKNOWN_CODE (-1)

/**
 * An enum field: `value` is one of the table's C enum constants, or NMEA_UNKNOWN_CODE for a
 * code the spec does not know; `code` holds the code as received (NUL-terminated). The
 * serializer writes the table's code for a known value and `code` for an unknown one.
 */
typedef struct {
    int value;
    char code[NMEA_CODE_MAX + 1];
    bool present;
} nmea_enum;

/** A known value of a lookup table, for a struct to build (`value` one of its C enum
    constants). */
nmea_enum nmea_enum_of(const nmea_enum_def *def, int value);

/** The spec id of an enum value ("gps"), or NULL when it is empty or unknown. */
const char *nmea_enum_id(const nmea_enum_def *def, const nmea_enum *e);

/** The table's constant for a one-character code (the elements of an enum_chars field, e.g.
    GNS mode "ANNN"), or NMEA_UNKNOWN_CODE. */
int nmea_enum_lookup(const nmea_enum_def *def, char code);

/** What went wrong (the "kind" of the tools' JSON). */
typedef enum {
    NMEA_ERR_TOO_LONG,
    NMEA_ERR_NOT_A_SENTENCE,
    NMEA_ERR_BAD_TAG_BLOCK, /* a TAG block before the sentence (or on its own) is malformed */
    NMEA_ERR_BAD_CHECKSUM,
    NMEA_ERR_CHECKSUM_MISMATCH,
    NMEA_ERR_MISSING_CHECKSUM, /* nmea_options.require_checksum, and the sentence has none */
    NMEA_ERR_TOO_FEW_FIELDS,
    NMEA_ERR_TOO_MANY_FIELDS,
    NMEA_ERR_BAD_FIELD,
    NMEA_ERR_BAD_JSON,
    NMEA_ERR_BAD_VALUE /* a value a parameter table refuses (nmea_param_*); never printed by the tools */
} nmea_error_kind;

/** "too_long", "bad_field", ... */
const char *nmea_error_kind_name(nmea_error_kind kind);

/**
 * Why a line was rejected. The message is not stored as text: it is rendered on demand by
 * nmea_error_message / nmea_error_to_json from a static pattern and the parts below, so the
 * struct stays small. `address` (and `text`) point into the parsed line or JSON scratch buffer
 * (or at the spec's address of a proprietary sentence).
 */
typedef struct {
    nmea_error_kind kind;
    bool has_address;
    bool out_of_range;          /* bad_field: a number of the right form outside its field's range */
    nmea_text address;          /* the address, or the talker when address_suffix is set */
    const char *address_suffix; /* the sentence id after the talker, or NULL */
    unsigned field;             /* 1-based wire field after the address; 0 when none */
    const char *group;          /* for a field in a repeated group: the group id, */
    unsigned entry;             /* the 1-based entry, */
    const char *name;           /* and the field id (or NULL when no field is at fault) */
    const char *pattern;        /* the message, with %-directives for the parts below */
    nmea_text text;
    bool text_json;             /* `text` is the inside of a JSON string, escapes and all */
    const char *str[2];
    size_t num[3];
} nmea_error;

/** The message ("checksum is 40, computed 6C"; in a build with -DNMEA_TERSE_ERRORS, which leaves
    the texts of errors out, the kind's name: the wire field is in `field`); returns its length
    (0 when it does not fit). */
size_t nmea_error_message(const nmea_error *err, char *buf, size_t cap);

/** The name of the field at fault ("satellites[2].prn"), or 0 when there is none. */
size_t nmea_error_name(const nmea_error *err, char *buf, size_t cap);

#ifndef NMEA_NO_JSON
/** The tools' JSON for an error: {"ok":false,"error":{...}}. */
size_t nmea_error_to_json(const nmea_error *err, char *buf, size_t cap);
#endif

/** The too_long error for a line of `len` bytes (for readers that stream long lines away). */
void nmea_error_too_long(nmea_error *err, size_t len);

/** Most problems one sentence may have (numbers kept outside their range and fields left
    empty, together). */
#define NMEA_MAX_PROBLEMS 8

/** What parsing did with a field at fault (the "kind" of a problem in the tools' JSON). */
typedef enum {
    NMEA_PROBLEM_LEFT_EMPTY,  /* "left_empty": lenient parsing read it as empty */
    NMEA_PROBLEM_OUT_OF_RANGE, /* "out_of_range": a number outside its field's range, kept as sent */
    NMEA_PROBLEM_SHORT_CHECKSUM /* "short_checksum": a checksum sent as one hex digit, kept as sent; never
                                   in nmea_problems (the sentence's NMEA_CHECKSUM_SHORT_* style says
                                   it), listed first by the tools' JSON */
} nmea_problem_kind;

/**
 * A field at fault in a sentence parsing kept: a number outside its field's range, kept as sent
 * (unless nmea_options.strict), or a field whose text does not fit its type, which lenient
 * parsing (nmea_options.lenient) left empty. Where it is, its text as received (the serializer
 * writes the text of a field left empty back in its place, so the round trip stays exact) and
 * what was expected. The message ("expected integer 0..99, found \"x\"") is rendered by
 * nmea_problem_message.
 */
typedef struct {
    uint16_t field;       /* 1-based wire field after the address */
    uint16_t entry;       /* in a repeated group: the 1-based entry */
    uint8_t kind;         /* nmea_problem_kind */
    const char *group;    /* in a repeated group: the group id, else NULL */
    const char *name;     /* the field id */
    const char *expected; /* what the field takes */
    nmea_text text;       /* the field's text as received */
} nmea_problem;

/** The problems of a sentence parsing kept (see nmea_options.problems). */
typedef struct {
    uint8_t count;
    nmea_problem list[NMEA_MAX_PROBLEMS];
} nmea_problems;

/**
 * The entries of a repeated group (GSV's satellites, ...). A parsed sentence keeps them as
 * received: `wire` is the text of their fields (separators between them, none around), and
 * nmea_<layout>_<group>_at reads entry i when it is asked for. A sentence struct is thus the
 * size of its other fields however many entries its group may take. A sentence to build points
 * `items` at the caller's array of `count` entries (the group's entry struct, or the value type
 * of a group of one field), which must outlive the struct; `items` wins over `wire`. A group of
 * a fixed number of entries always has that many (those neither array nor wire holds are
 * empty).
 */
typedef struct {
    const void *items;
    nmea_text wire;
    uint8_t count;
    uint8_t blanks;                    /* lenient parsing: how many fields of `wire` it read as empty, */
    uint16_t blank[NMEA_MAX_PROBLEMS]; /* and which (1-based in `wire`) */
} nmea_entries;

/** A problem's message ("expected ..., found \"TEXT\""); returns its length (0 when it does not
    fit). */
size_t nmea_problem_message(const nmea_problem *p, char *buf, size_t cap);

/** A problem's field name ("satellites[2].prn"); returns its length (0 when it does not fit). */
size_t nmea_problem_name(const nmea_problem *p, char *buf, size_t cap);

/**
 * How nmea_parse_ex reads a line (a zeroed struct, or NULL, is nmea_parse's reading). By default
 * a `$`/`!` sentence with a number of the right form outside its field's range (the manual's
 * `min`/`max`) is decoded with the number kept as sent, each such field a problem
 * (NMEA_PROBLEM_OUT_OF_RANGE); the fields at fault are taken one at a time in the order the
 * errors come.
 * - strict: such a number is refused as NMEA_ERR_BAD_FIELD (or, lenient, left empty).
 * - lenient: a `$`/`!` sentence whose fields do not all fit their types is still decoded: the
 *   other fields at fault are read as empty (NMEA_PROBLEM_LEFT_EMPTY). A field that is already
 *   empty and still does not fit (a keyword, a hemisphere without its latitude), or a problem
 *   more than NMEA_MAX_PROBLEMS, ends the attempt with its error. Text commands are always read
 *   strictly.
 * - require_checksum: a `$`/`!` sentence without a checksum (or with a bare '*') is refused as
 *   NMEA_ERR_MISSING_CHECKSUM.
 * - problems: where parsing lists the problems (the sentence's `problems` then points here, and
 *   serializing it writes the texts of the fields left empty back in their places, so the round
 *   trip stays exact); NULL: they are not kept, and the fields left empty are written empty.
 *   Parsing writes the list as it goes (no copy on the stack) and sets `count` when it succeeds.
 * A build with -DNMEA_NO_PROBLEMS (a firmware short of flash) keeps no problems: it reads every
 * sentence strictly, whatever the options say.
 */
typedef struct {
    bool lenient;
    bool require_checksum;
    nmea_problems *problems;
    bool strict;
} nmea_options;

/* ------------------------------------------------------------------------------------------ */
/* Stream framing: bytes as a serial port or socket delivers them, in chunks of any size. */

#ifndef NMEA_NO_BINARY_FRAMES
/** The longest binary frame the framer holds: an RTCM 3 frame's 1,029 bytes, and the long UBX
    frames of a multi-band receiver (a ZED-F9P's NAV-SAT or RXM-RAWX of 40 signals: 1,200 bytes). */
#define NMEA_MAX_FRAME 2048

/** Why what began like a binary frame is not one (NMEA_FRAME_OK: it is one). */
typedef enum { NMEA_FRAME_OK, NMEA_FRAME_BAD_CHECKSUM, NMEA_FRAME_TOO_LONG, NMEA_FRAME_NUL_HEADER, NMEA_FRAME_CUT,
               NMEA_FRAME_TOO_SHORT } nmea_frame_error;

/** The checksums of binary frames: Fletcher-8 (two 8-bit running sums), XOR-8, the 15-bit sum of
    the bytes, the 32-bit sum of their little-endian words, CRC-24Q, CRC-CCITT, CRC-32 (spec/schema/binary_protocol). */
typedef enum { NMEA_CHECKSUM_FLETCHER8, NMEA_CHECKSUM_XOR8, NMEA_CHECKSUM_SUM15, NMEA_CHECKSUM_SUM32, NMEA_CHECKSUM_CRC24Q,
               NMEA_CHECKSUM_CRC16_CCITT, NMEA_CHECKSUM_CRC32 } nmea_checksum_kind;

/** The framing of a binary protocol (spec/binary/<protocol>/protocol.yaml): a row of nmea_framings,
    which the generator writes (runtime/c/framings.c). Offsets count from the first sync byte. */
typedef struct {
    const char *name;           /* its name in the tools' JSON: "ubx" */
    unsigned char sync[3];      /* the first sync byte; the value of the next byte's bits under follow_mask;
                                   the third (when sync_len is 3), checked as it comes */
    unsigned char follow_mask;
    unsigned char sync_len;     /* its sync bytes (1 to 3): what a rejected frame is handed on as */
    unsigned char length_at;    /* the length field, big or little endian, of 1 or 2 bytes */
    unsigned char length_size;
    unsigned char big_endian;
    unsigned short length_mask; /* the field's bits that are the length */
    unsigned char header;       /* bytes before the payload, sync included */
    unsigned char length_adds;  /* the frame's bytes beyond what the length counts (0: it counts them all) */
    unsigned char checksum;     /* nmea_checksum_kind, from byte check_from to the payload's end */
    unsigned char check_from;
    unsigned char check_at;     /* where the checksum sits in the header; 0: after the payload */
    unsigned char check_size;   /* the checksum's bytes */
    unsigned char end[2];       /* the bytes after it that end every frame (end_len of them) */
    unsigned char end_len;
    struct {
        const char *name;       /* NULL: none */
        unsigned short bit;     /* from the first sync byte, most significant bit first (least in a little-endian frame) */
        unsigned char bits;
    } identity[2];              /* the fields that tell the frame's message ("class", "id") */
} nmea_framing;
#endif

#include "framings.h"

#ifndef NMEA_NO_BINARY_FRAMES
/** The framing of each binary protocol, by its nmea_protocol less one. */
extern const nmea_framing nmea_framings[NMEA_FRAMING_COUNT];
#endif

/**
 * Cuts a byte stream into lines: CR LF, LF and a bare CR end a line, and empty lines are skipped;
 * a '$' or '!' always starts a new line, so whatever came before it (garbage, a sentence cut
 * short) is a line of its own; a line longer than NMEA_MAX_LINE is not kept, only counted.
 * Unless -DNMEA_NO_BINARY_FRAMES, it also takes the binary frames (nmea_framings) a receiver interleaves
 * with its sentences: outside a TAG block, a frame's sync bytes end the line before them, and the
 * frame is handed on whole once its checksum matches; a frame whose checksum fails, that the
 * stream cuts short or that is longer than NMEA_MAX_FRAME is handed on as its sync bytes with
 * the reason, and the bytes after them are read again, so that nothing intact they held is lost.
 * The struct holds the line and the frame being assembled across chunks (no heap): zero it, or
 * nmea_framer_init.
 */
typedef struct {
    size_t length;             /* bytes of the current line so far (counted past NMEA_MAX_LINE) */
    char next;                 /* nmea_framer_feed: the '$' or '!' that starts the next line, or 0 */
    unsigned char tag;         /* where the line is as to TAG blocks: outside, in one, right after one */
    char line[NMEA_MAX_LINE];  /* its first NMEA_MAX_LINE bytes */
#ifndef NMEA_NO_BINARY_FRAMES
    unsigned char protocol;    /* nmea_protocol of the frame under way */
    size_t frame_len;          /* its bytes so far, from its first sync byte; 0: none under way */
    size_t frame_size;         /* its length from its header, once that is in */
    size_t replay;             /* bytes of rejected frames to read again, at the end of `frame` */
    unsigned char frame[NMEA_MAX_FRAME];
#endif
} nmea_framer;

/** A framed item: a line of `len` bytes at `ptr`, or for a line longer than NMEA_MAX_LINE its
    length in `len` and `ptr` NULL (nmea_parse refuses it as too_long without reading it, so it
    can be handed on as it is). `ptr` points into the chunk given to nmea_framer_push or into the
    framer, and stays valid until the framer's next call. */
typedef struct {
    const char *ptr;
    size_t len;
#ifndef NMEA_NO_BINARY_FRAMES
    nmea_protocol protocol;    /* NMEA_LINE, or a binary frame's: `ptr` holds it, sync to checksum */
    nmea_frame_error error;    /* not NMEA_FRAME_OK: no frame, `ptr` holds its sync bytes */
    unsigned long sent, computed; /* NMEA_FRAME_BAD_CHECKSUM: the checksum and end bytes, as big-endian numbers */
    size_t size;               /* NMEA_FRAME_TOO_LONG: the length its header says */
#endif
} nmea_framed;

void nmea_framer_init(nmea_framer *f);

/**
 * Takes bytes from `*data` (`*len` of them) until a line is complete: returns true with it in
 * `*out`, having advanced `*data` and `*len` past what it used (the line ending, but not a '$' or
 * '!' that starts the next line); returns false once every byte is used without completing a
 * line (the rest is kept for the next chunk). Call it until it returns false:
 *
 *     while (nmea_framer_push(&framer, &p, &n, &line))
 *         handle(line);
 */
bool nmea_framer_push(nmea_framer *f, const char **data, size_t *len, nmea_framed *out);

/**
 * nmea_framer_push for one byte, as an interrupt handler or a DMA callback has it: true when the
 * byte completes a line, which is then in `*out` (it points into the framer and stays valid until
 * the framer's next call). The lines are those nmea_framer_push gives for the same bytes. With
 * binary frames, a rejected frame's bytes read again can complete more items: after a true, call
 * nmea_framer_next until it returns false before feeding the next byte.
 *
 *     if (nmea_framer_feed(&framer, byte, &line) && line.ptr)
 *         nmea_parse(&sentence, line.ptr, line.len, &err);
 */
bool nmea_framer_feed(nmea_framer *f, char byte, nmea_framed *out);

#ifndef NMEA_NO_BINARY_FRAMES
/** After nmea_framer_feed: the next item the bytes of a rejected frame complete (true), else false. */
bool nmea_framer_next(nmea_framer *f, nmea_framed *out);
#endif

/** At the end of the stream: the last line, when it had no line ending, and what a frame cut
    short by the end held; call it until it returns false. */
bool nmea_framer_end(nmea_framer *f, nmea_framed *out);

#ifndef NMEA_NO_TAG_BLOCKS
/* ------------------------------------------------------------------------------------------ */
/* TAG blocks (NMEA 0183 4.00, IEC 61162-450): `\g:1-2-73874,s:r003669945,c:1241544035*hh\` before
   a sentence or on a line of their own. A parsed line keeps the text of its blocks
   (nmea_sentence.tag_blocks, checked, pointing into the line), which nmea_serialize writes back
   as it is; these functions read the parameters out of it and write a new block. A firmware
   whose receiver sends none builds with -DNMEA_NO_TAG_BLOCKS (and -DNMEA_NO_JSON): no reader,
   writer nor nmea_sentence.tag_blocks, and a '\' is a byte like any other (a line that starts
   with one is not_a_sentence). */

/** The value types of the codes the spec names (spec/tag_block.yaml). */
typedef enum {
    NMEA_TAG_INTEGER, /* 1 to 18 digits, kept as sent (c: UNIX time, n: line count, ...) */
    NMEA_TAG_GROUP,   /* sentence number, count and group id joined by '-' (g) */
    NMEA_TAG_TEXT     /* anything but ',', '*' and '\' (s: source, d: destination, ...) */
} nmea_tag_type;

/** A code the spec names: nmea_tag_codes (nmea.h) lists them. */
typedef struct {
    const char *code; /* as written before the ':' */
    const char *id;   /* the spec's id: "time", "source", ... */
    const char *name;
    nmea_tag_type type;
} nmea_tag_code;

/** A parameter of a TAG block: its code and value as written (any code: unknown ones are kept). */
typedef struct {
    nmea_text code;
    nmea_text value;
} nmea_tag_param;

/** The next block of `*blocks` (the text of a line's TAG blocks): true with its parameters' text
    (between '\' and '*') in `*params`, `*blocks` moved past it; false at the end. */
bool nmea_tag_next_block(nmea_text *blocks, nmea_text *params);

/** The next parameter of a block's `*params`: true with it in `*out`, `*params` moved past it. */
bool nmea_tag_next_param(nmea_text *params, nmea_tag_param *out);

/** The value of the first parameter with `code` in a line's TAG blocks; false when none has it. */
bool nmea_tag_find(nmea_text blocks, const char *code, nmea_text *value);

/** The code the spec names `code`, or NULL. */
const nmea_tag_code *nmea_tag_code_of(nmea_text code);

/**
 * One TAG block of `n` parameters, its checksum in `style` (NMEA_CHECKSUM_LOWER or upper case),
 * written to `buf` as a received one is read back: returns its length, or 0 with `err` filled
 * (bad_tag_block; too_long when `cap` is too small). Put it before a sentence with
 * nmea_sentence.tag_blocks, or write it before nmea_build's bytes.
 */
size_t nmea_tag_write(const nmea_tag_param *params, size_t n, nmea_checksum_style style, char *buf, size_t cap,
                      nmea_error *err);
#endif /* NMEA_NO_TAG_BLOCKS */

/**
 * A well-formed sentence the spec does not describe. `fields` is the raw text of all fields
 * after the address, comma separated, and `field_count` their number (0 when the address is
 * not followed by a comma: "$PSTMSAVEPAR" has none, "$PSTMSAVEPAR," one empty field).
 */
typedef struct {
    nmea_text start; /* "$" or "!" */
    nmea_text address;
    nmea_text fields;
    size_t field_count;
    nmea_checksum_style checksum;
} nmea_generic;

/** Field `index` (0-based) of a generic sentence; an empty slice past the end. */
nmea_text nmea_generic_field(const nmea_generic *g, size_t index);

#ifndef NMEA_NO_JSON
/** Whether a line of decode's JSON output is an object whose "ok" is false (encode skips
    those lines). */
bool nmea_json_is_failure(const char *json, size_t len);
#endif

#ifndef NMEA_NO_TABLES /* a build generated without parameter tables */
/* ------------------------------------------------------------------------------------------ */
/* Configuration parameter tables (spec/tables): the wire text of a value. */

/** How a parameter's value is written on the wire. */
typedef enum {
    NMEA_PARAM_HEX,          /* upper-case hex digits without 0x */
    NMEA_PARAM_DECIMAL,      /* a decimal number */
    NMEA_PARAM_DECIMAL_LIST, /* `count` decimal numbers separated by ',' */
    NMEA_PARAM_TEXT          /* printable ASCII without ',', '*', '$' or '!' */
} nmea_param_encoding;

/** One parameter of a receiver's configuration table; what the table leaves out is 0, NULL or
    an unset bound. */
typedef struct {
    unsigned number;             /* the parameter ID on the wire */
    const char *id;
    const char *name;
    nmea_param_encoding encoding;
    uint8_t size;                /* bytes in the block, or 0 */
    uint8_t count;               /* values of a decimal list, or 0 */
    nmea_range range;            /* allowed values */
    uint8_t max_length;          /* longest text, or 0 */
    const char *default_value;   /* as the table writes it, or NULL */
    const char *unit;            /* or NULL */
    const nmea_enum_def *values; /* the lookup table of its values, or NULL */
    const char *bitfield;        /* the bitfield naming its bits (nmea_<bitfield>_<bits>()), or NULL */
} nmea_parameter;

/** The parameter with this number in a table of `count` parameters, or NULL. */
const nmea_parameter *nmea_param_find(const nmea_parameter *table, size_t count, unsigned number);

/*
 * The wire text of a parameter value, written to `buf` (NUL-terminated) the way the receiver
 * reads it; returns its length. A value the parameter refuses (out of range, too wide for its
 * size, wrong count, bad text, or a function for another encoding) returns 0 and fills `err`
 * (kind NMEA_ERR_BAD_VALUE), as does a buffer too small (kind NMEA_ERR_TOO_LONG). An empty text
 * is the one accepted value whose length is 0 (`err` is then left alone).
 * - hex: upper-case digits ("84356");
 * - decimal: value * 10^-scale, written with `scale` decimals ("-12.50" for -1250, scale 2);
 * - decimal list: `n` such numbers separated by ',';
 * - text: the text itself.
 */
size_t nmea_param_hex(const nmea_parameter *p, uint64_t value, char *buf, size_t cap, nmea_error *err);
size_t nmea_param_decimal(const nmea_parameter *p, int64_t value, unsigned scale, char *buf, size_t cap,
                          nmea_error *err);
size_t nmea_param_decimal_list(const nmea_parameter *p, const int64_t *values, size_t n, unsigned scale, char *buf,
                               size_t cap, nmea_error *err);
size_t nmea_param_text(const nmea_parameter *p, const char *text, char *buf, size_t cap, nmea_error *err);
#endif /* NMEA_NO_TABLES */
