/* ------------------------------------------------------------------------------------------ */
/* Parsing and writing any sentence (the hand-written runtime's API: runtime/c/api.h, after the
   sentences' types; the functions of each layout follow it). */

/**
 * Parses one line (a trailing LF or CR LF is allowed) into `out`: a known sentence into its layout, any
 * other well-formed line into out->as.generic. A line that does not start with '$' or '!' and
 * whose first word is, ignoring case, the word of a text command is that command. The layouts a
 * line may have (a standard sentence's, or those of every proprietary sentence with its address,
 * those starting with a keyword first) are tried in order and the first that reads it wins.
 * Returns false and fills `err` otherwise: when no layout fits, the error of the layouts whose
 * keyword the first field holds (else of all of them), the first bad field among them, else their
 * first error. A line longer than NMEA_MAX_LINE is rejected before any of its bytes is read.
 */
bool nmea_parse(nmea_sentence *out, const char *line, size_t len, nmea_error *err);

/** nmea_parse with options (see nmea_options; NULL: strict, as nmea_parse). */
bool nmea_parse_ex(nmea_sentence *out, const char *line, size_t len, const nmea_options *options, nmea_error *err);

#ifdef NMEA_TEST_HOOKS
/* For tests: nmea_parse_ex without its fast path for sentences in the usual form, which must
   give the same results (NMEA_NO_FAST_PATH makes nmea_parse_ex and nmea_serialize their
   general paths). */
bool nmea_parse_general(nmea_sentence *out, const char *line, size_t len, const nmea_options *options, nmea_error *err);
/* For tests: nmea_serialize without its fast path. */
size_t nmea_serialize_general(const nmea_sentence *s, char *buf, size_t cap);
#endif

/** The sentence text after its TAG blocks (no line ending); returns its length, 0 when it (and its
    NUL) does not fit in `cap` bytes. */
size_t nmea_serialize(const nmea_sentence *s, char *buf, size_t cap);

/**
 * The typed builders: the exact bytes to send for a sentence or command, CR LF included (and a
 * NUL after them), once the text has been read back with the layout's parser, the way a
 * receiver would read it. Returns their length; returns 0 and fills `err` with the usual typed
 * error naming the field at fault when an argument does not fit (the refused text is then left
 * in `buf`, NUL-terminated: the error points into it), or too_long when `cap` is too small (then
 * `buf` holds an empty string). A zeroed struct is a valid start: keywords are implied, the
 * checksum upper case.
 * nmea_build takes any sentence (a generic one is only checked to be a well-formed line), without
 * its TAG blocks: nmea_tag_write writes a block to put before the bytes.
 */
size_t nmea_build(const nmea_sentence *s, char *buf, size_t cap, nmea_error *err);

/** The layouts of the sentences that answer a command (every layout of each reply the spec
    names), `*count` of them; NULL and 0 for any other layout. */
const nmea_sentence_id *nmea_replies(nmea_sentence_id command, size_t *count);

/** What a parsed sentence is to a command. */
typedef enum {
    NMEA_REPLY_NONE = 0, /* not an answer to this command */
    NMEA_REPLY_OK,       /* answers it: the command was carried out, or here is what it asked for */
    NMEA_REPLY_ERROR     /* answers it: the receiver refused the command or failed to carry it out */
} nmea_reply;

/** Whether `s` answers the command layout `command` (one of its replies, holding the field values
    the spec pairs it by, e.g. the command number in $PMTK001) and, if so, whether it reports
    success. */
nmea_reply nmea_reply_to(const nmea_sentence *s, nmea_sentence_id command);

/* The field values as numbers to compute with (no heap, no libm; Python and Rust give the same). */

/** Two-digit years below it are 20yy, the others 19yy (00-68: 2000-2068, 69-99: 1969-1999): the
    POSIX rule of strptime's %y, as pynmea2 reads them (gpsd takes its build century, 20yy). */
#define NMEA_PIVOT_YEAR 69

/** The number as a double: the nearest one for up to 15 significant digits (digits < 2^53). */
double nmea_to_double(const nmea_number *n);

/** nmea_to_double rounded to a float. */
float nmea_to_float(const nmea_number *n);

/** Signed degrees x 10^7 (south and west negative), exact integer arithmetic rounded half away
    from zero: 4916.45,N is 492741667 (49.2741666...). */
int32_t nmea_coordinate_e7(const nmea_coordinate *c);

/** Milliseconds since midnight, digits after the third decimal dropped; a leap second (60)
    counts on past 86400000. */
uint32_t nmea_time_ms(const nmea_time *t);

/** The four-digit year of a date (NMEA_PIVOT_YEAR). */
int nmea_date_year(const nmea_date *d);

/** Days since 1970-01-01 of year-month-day (proleptic Gregorian, years 1 to 9999); false for a
    day its month lacks. For a date in three fields (ZDA: day, month, four-digit year). */
bool nmea_days_from_civil(int32_t year, int month, int day, int32_t *days);

/** nmea_days_from_civil of a ddmmyy date, its year by NMEA_PIVOT_YEAR. */
bool nmea_date_days(const nmea_date *d, int32_t *days);

/** Milliseconds since 1970-01-01T00:00Z of a date and a time; false when either is not present,
    for a day its month lacks and for a leap second (as Python's datetime and Rust's). */
bool nmea_datetime_ms(const nmea_date *d, const nmea_time *t, int64_t *ms);

#ifndef NMEA_NO_FIXES
/* Fixes assembled across sentences, one per epoch (docs/fixes.md; the rules are those of the
   Python runtime's fixes.py, the same fixes on the same lines): no heap, fixed capacities a
   firmware may set; -DNMEA_NO_FIXES leaves them out. The types are nmea_gnss_*: nmea_<id> is the
   struct of a sentence, and a spec may have a sentence FIX. */

/** Satellites in view a fix holds (every signal's GSV set of NMEA 4.11: up to 36 satellites per
    talker and signal, for GPS, GLONASS, Galileo and BeiDou on two signals each and more). */
#ifndef NMEA_FIX_MAX_SATELLITES
#define NMEA_FIX_MAX_SATELLITES 288
#endif
/** Satellites used a fix holds (GSA: 12 ids per line and system, up to 6 systems and more). */
#ifndef NMEA_FIX_MAX_USED
#define NMEA_FIX_MAX_USED 96
#endif
/** Sentences a fix names (an epoch of every GSV set above, and the rest). */
#ifndef NMEA_FIX_MAX_SENTENCES
#define NMEA_FIX_MAX_SENTENCES 96
#endif
/** GSV sets under way at once, and talkers that count satellites used in one epoch. */
#ifndef NMEA_FIX_MAX_SETS
#define NMEA_FIX_MAX_SETS 16
#endif

/** The facts of spec/fix.yaml, as the generated table names them. */
typedef enum {
    NMEA_FACT_TIME,
    NMEA_FACT_DATE,
    NMEA_FACT_DAY,
    NMEA_FACT_MONTH,
    NMEA_FACT_YEAR,
    NMEA_FACT_LATITUDE,
    NMEA_FACT_LONGITUDE,
    NMEA_FACT_ALTITUDE_MSL,
    NMEA_FACT_GEOID_SEPARATION,
    NMEA_FACT_ALTITUDE_HAE,
    NMEA_FACT_SPEED,
    NMEA_FACT_COURSE,
    NMEA_FACT_FIX_QUALITY,
    NMEA_FACT_FIX_STATUS,
    NMEA_FACT_POS_MODE,
    NMEA_FACT_MODE,
    NMEA_FACT_PDOP,
    NMEA_FACT_HDOP,
    NMEA_FACT_VDOP,
    NMEA_FACT_TDOP,
    NMEA_FACT_LAT_ERROR,
    NMEA_FACT_LON_ERROR,
    NMEA_FACT_ALT_ERROR,
    NMEA_FACT_HORIZONTAL_ERROR,
    NMEA_FACT_SATELLITES_USED,
    NMEA_FACT_USED_SYSTEM,
    NMEA_FACT_USED_SATELLITE,
    NMEA_FACT_IN_VIEW_TOTAL,
    NMEA_FACT_SET_SIZE,
    NMEA_FACT_SET_INDEX,
    NMEA_FACT_SIGNAL,
    NMEA_FACT_SATELLITE,
    NMEA_FACT_ELEVATION,
    NMEA_FACT_AZIMUTH,
    NMEA_FACT_SNR,
    NMEA_FACT_SATELLITE_USED,
    NMEA_FACT_COUNT
} nmea_fact;

/** A satellite in view, as one signal's GSV set (or PUBX,03) reports it. Texts are the spec's
    value ids (static). */
typedef struct {
    const char *system; /* gps, sbas, glonass, galileo, beidou, qzss, navic; NULL: not told */
    const char *signal; /* the signal id of its set (NMEA 4.10), e.g. signal_1; NULL before it */
    int32_t id;         /* in the NMEA numbering of its talker */
    char talker[3];     /* "" for a proprietary sentence */
    bool has_elevation, has_azimuth, has_snr;
    int16_t elevation; /* degrees */
    int16_t azimuth;   /* degrees */
    int16_t snr;       /* dB-Hz; not had: not tracked */
    int8_t used;       /* 1 or 0 where the receiver says so beside it (PUBX,03), else -1 */
} nmea_gnss_satellite;

/** A satellite used, and its GNSS ("unknown" when no rule tells it). */
typedef struct {
    const char *system;
    int32_t id;
} nmea_gnss_used;

/** A sentence a fix came from: talker and sentence id (GP, GGA), or "" and the spec's id of a
    proprietary sentence (PUBX_POSITION). */
typedef struct {
    char talker[3];
    const char *sentence;
} nmea_gnss_source;

/**
 * What the sentences of one epoch say. A fact is there when bit (1 << nmea_fact) of `known` is
 * set; units are those of spec/fix.yaml (degrees, metres, metres per second); texts are the
 * spec's value ids (static).
 */
typedef struct {
    uint64_t known;
    uint64_t whole; /* the bits of the facts read from integer fields in their unit, which the JSON
                       writes as integers (Python's int); decimals are written as doubles */
    uint32_t time_ms;   /* UTC time of day */
    int32_t date_days;  /* days since 1970-01-01 */
    double latitude;    /* signed degrees, as Python's and Rust's (degrees + minutes / 60) */
    double longitude;
    double altitude_msl;
    double geoid_separation;
    double altitude_hae; /* as sent (PUBX,00), else altitude_msl + geoid_separation */
    double speed;
    double course;
    const char *fix_quality; /* a value id of gga_quality */
    const char *fix_status;  /* valid, invalid */
    const char *pos_mode;    /* a value id of pos_mode */
    const char *mode;        /* no_fix, fix_2d, fix_3d: the receiver's, else inferred */
    double pdop, hdop, vdop, tdop;
    double lat_error, lon_error, alt_error, horizontal_error;
    int32_t satellites_used; /* the combined talker's count (GN), else a proprietary sentence's (the
                                receiver's total), else the sum of each talker's */
    uint16_t used_count;
    uint16_t in_view_len;
    uint16_t sentence_count;
    uint16_t overflow; /* satellites and sentences the capacities above left out */
    /* Only the first used_count, in_view_len and sentence_count entries are written. */
    nmea_gnss_used used[NMEA_FIX_MAX_USED]; /* in the order GSA lists them */
    nmea_gnss_satellite in_view[NMEA_FIX_MAX_SATELLITES]; /* one per satellite and signal */
    nmea_gnss_source sentences[NMEA_FIX_MAX_SENTENCES];
} nmea_gnss_fix;

/** Whether the epoch gave fact `fact`. */
bool nmea_fix_has(const nmea_gnss_fix *fix, nmea_fact fact);

/** Whether a number fact was read from an integer field, in its unit (its JSON has no point). */
bool nmea_fix_is_whole(const nmea_gnss_fix *fix, nmea_fact fact);

/** How many distinct satellites are in view (a satellite of several signals once). */
size_t nmea_fix_in_view_count(const nmea_gnss_fix *fix);

/** A set of GSV sentences under way (one talker and signal). */
typedef struct {
    char talker[3];
    const char *signal;
    uint8_t index; /* the last message number received */
} nmea_gnss_set;

/** The satellites used of one talker, as its GGA (GNS, PUBX,00) counts them. */
typedef struct {
    char talker[3];
    int32_t count;
} nmea_gnss_count;

/** Turns a stream of sentences into fixes: zero it (or nmea_fix_init), nmea_fix_feed each
    sentence in order, nmea_fix_finish at the end of the stream. It is large (two fixes' worth of
    satellites): keep it static or in a long-lived object rather than on a small stack. */
typedef struct {
    nmea_gnss_fix fix; /* the epoch under way */
    bool open;
    bool has_last_date, last_has_time;
    int32_t last_date; /* the last epoch with a date: its date and time */
    uint32_t last_time;
    uint8_t set_count, count_count;
    nmea_gnss_set sets[NMEA_FIX_MAX_SETS];
    nmea_gnss_count counts[NMEA_FIX_MAX_SETS];
    uint16_t pending_len; /* the satellites of the sets under way */
    nmea_gnss_satellite pending[NMEA_FIX_MAX_SATELLITES];
} nmea_fix_assembler;

void nmea_fix_init(nmea_fix_assembler *a);

/** Adds one parsed sentence; true when it closed an epoch, whose fix is then in `out`. */
bool nmea_fix_feed(nmea_fix_assembler *a, const nmea_sentence *s, nmea_gnss_fix *out);

/** Ends the stream: true when an epoch was under way, its fix then in `out`. */
bool nmea_fix_finish(nmea_fix_assembler *a, nmea_gnss_fix *out);
#endif /* NMEA_NO_FIXES */

#ifndef NMEA_NO_JSON
/* The tools' JSON (json.md of the docs), which -DNMEA_NO_JSON leaves out of a build that only
   parses and writes sentences: about a quarter of the code. */

/** The tools' JSON for a sentence: the lossless field texts, or (values) the decoded values. */
size_t nmea_to_json(const nmea_sentence *s, bool values, char *buf, size_t cap);

/** What `nmea-c decode` prints for one line: the sentence's JSON or the error's JSON. */
size_t nmea_decode_json(const char *line, size_t len, bool values, char *buf, size_t cap);

/** What `nmea-c decode` prints for one line with its options (--lenient, --require-checksum). */
size_t nmea_decode_json_ex(const char *line, size_t len, bool values, const nmea_options *options, char *buf,
                           size_t cap);

/**
 * Rebuilds a sentence from one line of decode's lossless JSON (what `nmea-c encode` does):
 * the fields' texts are put back on the wire and parsed again by the sentence's layout (with the
 * texts of its "problems" in their places, leniently, when lenient decoding kept it).
 * Strings of the JSON are copied into `scratch` (the sentence points into it); 2 * `len` bytes
 * of scratch are always enough (`len` but for a text command, whose line as received is built
 * there too, or a sentence with problems, whose texts are joined again there), and
 * sizeof(nmea_problems) + 16 more for a sentence with problems, which are kept there too.
 */
bool nmea_from_json(nmea_sentence *out, const char *json, size_t len, char *scratch, size_t scratch_cap,
                    nmea_error *err);

#ifndef NMEA_NO_FIXES
/** The longest JSON of a fix: its facts, and each satellite, satellite used and sentence at its
    longest. */
#define NMEA_FIX_JSON_MAX (2048 + 192 * NMEA_FIX_MAX_SATELLITES + 24 * NMEA_FIX_MAX_USED + 48 * NMEA_FIX_MAX_SENTENCES)

/** A fix as Python's Fix.to_dict() in JSON (`nmea-c fixes`): the length written (not counting
    the NUL it adds), or 0 when `cap` is too small. */
size_t nmea_fix_to_json(const nmea_gnss_fix *fix, char *buf, size_t cap);
#endif
#endif /* NMEA_NO_JSON */
