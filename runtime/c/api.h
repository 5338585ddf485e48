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

/** The sentence text (no line ending); returns its length, 0 when it (and its NUL) does not
    fit in `cap` bytes. */
size_t nmea_serialize(const nmea_sentence *s, char *buf, size_t cap);

/**
 * The typed builders: the exact bytes to send for a sentence or command, CR LF included (and a
 * NUL after them), once the text has been read back with the layout's parser, the way a
 * receiver would read it. Returns their length; returns 0 and fills `err` with the usual typed
 * error naming the field at fault when an argument does not fit (the refused text is then left
 * in `buf`, NUL-terminated: the error points into it), or too_long when `cap` is too small (then
 * `buf` holds an empty string). A zeroed struct is a valid start: keywords are implied, the
 * checksum upper case.
 * nmea_build takes any sentence (a generic one is only checked to be a well-formed line).
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
#endif /* NMEA_NO_JSON */
