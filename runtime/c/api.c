/* The API of nmea.h for any sentence: nmea_parse (the fast path first, then the general path
   with its options), nmea_serialize (likewise) and nmea_build (written, then read back). The
   NMEA_TEST_HOOKS build also gives the general paths on their own, for the tests to compare. */

bool nmea_parse(nmea_sentence *out, const char *line, size_t len, nmea_error *err)
{
#if defined(NMEA_SMALL_READER) /* -DNMEA_SMALL: the small reader (small.c) */
    err->kind = NMEA_ERR_TOO_LONG; /* (any kind but SMALL_REQUIRE_CHECKSUM) */
    return small_parse(out, line, len, err);
#elif defined(NMEA_NO_TAG_BLOCKS) && defined(NMEA_NO_FAST_PATH)
    /* A firmware's build: the general path inlined here (PARSE_GENERAL), not below nmea_parse_ex,
       whose fifth argument would take a frame of its own on the stack. */
    return parse_general(out, line, without_line_ending(line, len), NULL, err);
#else
    return nmea_parse_ex(out, line, len, NULL, err);
#endif
}

#ifndef NMEA_NO_TAG_BLOCKS
/* The TAG blocks a line starts with (`line` at its first '\\'), taken off the line: false with
   `err` for bad blocks; `*only` when the line is blocks alone, `out` then its sentence (a generic
   one with an empty start, address and fields). No callback: the stack stays bounded. */
static bool take_tag_blocks(nmea_sentence *out, const char **line, size_t *len, nmea_text *blocks, bool *only,
                            nmea_error *err)
{
    if (*len > NMEA_MAX_LINE) {
        nmea_error_too_long(err, *len);
        return false;
    }
    if (!read_tag_blocks(*line, *len, blocks, err))
        return false;
    *only = blocks->len == *len;
    if (*only) {
        nmea_text kept = *blocks; /* (`blocks` may be out->tag_blocks) */
        memset(out, 0, sizeof *out);
        out->id = NMEA_SENTENCE_GENERIC;
        out->as.generic.checksum = NMEA_CHECKSUM_NONE;
        out->tag_blocks = kept;
    }
    *line += blocks->len;
    *len -= blocks->len;
    return true;
}

/* The `$` a line sends before its sentence's own start ($$GNGSA: the first), taken off the
   line and kept after its TAG blocks in `*before` (they are next to each other on the line):
   false with `err` for a line too long or not printable ASCII (offsets counted from here, as
   for the blocks). */
static bool take_stray(const char **line, size_t *len, nmea_text *before, nmea_error *err)
{
    size_t n = 0;
    if (*len < 2 || (*line)[0] != '$' || (*line)[1] != '$')
        return true;
    if (*len > NMEA_MAX_LINE) {
        nmea_error_too_long(err, *len);
        return false;
    }
    if (!all_printable(*line, *len, err))
        return false;
    while (n + 1 < *len && (*line)[n + 1] == '$')
        n++;
    if (!before->len)
        before->ptr = *line;
    before->len += n;
    *line += n;
    *len -= n;
    return true;
}
#endif

/* The sentence of a line (after its TAG blocks): the fast path, which needs no options (what it
   reads has a checksum, and a line read without a problem is read the same way leniently), then
   the general path. */
NMEA_INTERNAL bool parse_sentence(nmea_sentence *out, const char *line, size_t len, const nmea_options *options,
                           nmea_error *err)
{
#ifndef NMEA_NO_FAST_PATH
    if (fast_parse(out, line, len))
        return true;
#endif
    return parse_general(out, line, len, options, err);
}

bool nmea_parse_ex(nmea_sentence *out, const char *line, size_t len, const nmea_options *options, nmea_error *err)
{
#if defined(NMEA_SMALL_READER) /* strict reading, the only one of -DNMEA_SMALL */
    err->kind = options && options->require_checksum ? SMALL_REQUIRE_CHECKSUM : NMEA_ERR_TOO_LONG;
    return small_parse(out, line, len, err);
#elif !defined(NMEA_NO_TAG_BLOCKS)
    bool only = false;
    len = without_line_ending(line, len);
    out->tag_blocks = nmea_text_of(NULL); /* kept in `out` (no copy on the stack under the parsing) */
    if (line && len && line[0] == '\\' && (!take_tag_blocks(out, &line, &len, &out->tag_blocks, &only, err) || only))
        return only;
    if (line && !take_stray(&line, &len, &out->tag_blocks, err))
        return false;
    return parse_sentence(out, line, len, options, err);
#else
    return parse_sentence(out, line, without_line_ending(line, len), options, err);
#endif
}

#ifdef NMEA_TEST_HOOKS
bool nmea_parse_general(nmea_sentence *out, const char *line, size_t len, const nmea_options *options, nmea_error *err)
{
#ifndef NMEA_NO_TAG_BLOCKS
    nmea_text blocks = nmea_text_of(NULL);
    bool only = false;
    len = without_line_ending(line, len);
    if (line && len && line[0] == '\\' && (!take_tag_blocks(out, &line, &len, &blocks, &only, err) || only))
        return only;
    if (line && !take_stray(&line, &len, &blocks, err))
        return false;
    if (!parse_general(out, line, len, options, err))
        return false;
    out->tag_blocks = blocks;
    return true;
#else
    return parse_general(out, line, without_line_ending(line, len), options, err);
#endif
}
#endif

/* nmea_serialize's general path: every sentence, every buffer. */
static size_t serialize_general(const nmea_sentence *s, char *buf, size_t cap)
{
    nmea_writer w = writer_of(buf, cap);
    write_sentence(&w, s);
    return writer_finish(&w);
}

#ifndef NMEA_NO_TAG_BLOCKS
/* A line of TAG blocks only (take_tag_blocks). */
static bool tag_blocks_only(const nmea_sentence *s)
{
    return s->id == NMEA_SENTENCE_GENERIC && s->tag_blocks.len && !s->as.generic.start.len;
}

/* The sentence's TAG blocks as they are, then the sentence written by `write`: the length, or 0
   (an empty `buf`) when the text and a NUL do not fit. */
static size_t serialize_tagged(const nmea_sentence *s, char *buf, size_t cap,
                               size_t (*write)(const nmea_sentence *, char *, size_t))
{
    size_t tags = s->tag_blocks.len, n = 0;
    if (tags < cap) {
        memcpy(buf, s->tag_blocks.ptr, tags);
        buf[tags] = 0;
        if (tag_blocks_only(s))
            return tags;
        n = write(s, buf + tags, cap - tags);
    }
    if (n)
        return tags + n;
    if (cap)
        buf[0] = 0;
    return 0;
}
#endif

static size_t serialize_sentence(const nmea_sentence *s, char *buf, size_t cap)
{
#ifndef NMEA_NO_FAST_PATH
    size_t n = s->problems && s->problems->count ? 0 : fast_write_sentence(s, buf, cap);
    if (n)
        return n;
#endif
    return serialize_general(s, buf, cap);
}

size_t nmea_serialize(const nmea_sentence *s, char *buf, size_t cap)
{
#ifndef NMEA_NO_TAG_BLOCKS
    if (s->tag_blocks.len)
        return serialize_tagged(s, buf, cap, serialize_sentence);
#endif
    return serialize_sentence(s, buf, cap);
}

#ifdef NMEA_TEST_HOOKS
size_t nmea_serialize_general(const nmea_sentence *s, char *buf, size_t cap)
{
#ifndef NMEA_NO_TAG_BLOCKS
    if (s->tag_blocks.len)
        return serialize_tagged(s, buf, cap, serialize_general);
#endif
    return serialize_general(s, buf, cap);
}
#endif

size_t nmea_build(const nmea_sentence *s, char *buf, size_t cap, nmea_error *err)
{
    nmea_writer w;
    nmea_wire wire;
    nmea_sentence check;

    if (s->id != NMEA_SENTENCE_GENERIC)
        return build_with(LAYOUTS[s->id], &s->as, s->problems, &check.as, buf, cap, err);
    w = writer_of(buf, cap);
    write_generic(&w, &s->as.generic);
    if (!build_wire(&w, false, &wire, err))
        return build_failed(&w);
    return build_end(&w);
}
