/* What the generated code after the runtime in nmea.c defines for each spec, declared here for
   the pieces that follow (dispatch.c, api.c, json_api.c); the runtime's tests define a small
   fixture of it instead (test_runtime.c). Besides these, nmea.h gives the sentences' types
   (nmea_sentence, nmea_sentence_id, NMEA_SENTENCE_COUNT), and nmea.c defines before the runtime
   NMEA_MAX_FIELDS, the most wire fields any layout takes, NMEA_MAX_LAYOUTS, the most layouts one
   address has, and the tables layout_field indexes:
   FIELD_RANGES, FIELD_ENUMS, FIELD_WORDS, FIELD_EXPECTED (only what the build's fields take). */

/* Every layout by its nmea_sentence_id (NULL: the generic sentence). */
static const layout *const LAYOUTS[NMEA_SENTENCE_COUNT];

/* Layout `id`'s fast reader on the fields of a line in the usual frame (fast_frame): FAST_NOT_THIS
   for a layout without one. */
static fast_result fast_read_layout(nmea_sentence *out, nmea_sentence_id id, const char *line, const char *fields,
                                    const char *end, size_t count);

/* nmea_parse_ex's fast path, which leaves what it is not sure of to its general path. */
NMEA_INTERNAL bool fast_parse(nmea_sentence *out, const char *line, size_t len);
#if defined(NMEA_NO_TAG_BLOCKS) && defined(NMEA_NO_FAST_PATH) && defined(__GNUC__) && defined(__OPTIMIZE_SIZE__)
#define PARSE_GENERAL static inline __attribute__((always_inline)) /* in nmea_parse, see there */
#else
#define PARSE_GENERAL NMEA_INTERNAL
#endif
PARSE_GENERAL bool parse_general(nmea_sentence *out, const char *line, size_t len, const nmea_options *options,
                                 nmea_error *err);

/* nmea_serialize's fast path: the length, or 0 to leave the sentence to the general writer. */
NMEA_INTERNAL size_t fast_write_sentence(const nmea_sentence *s, char *buf, size_t cap);
