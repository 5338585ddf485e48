/* Which layout reads a line: nmea_parse_<layout>'s framing (parse_with: the line must have the
   layout's address), the tables of layouts by address that the generated code writes
   (nmea_layouts, find_layouts), and the rules that pick among the layouts of one address: the
   first that reads the line wins, the error of the layouts whose keyword the line holds is the
   one reported, a second reading keeps numbers outside their range or (lenient) leaves the
   fields at fault empty, one at a time (refit). */

/* The wire of a line whose address must be $--<sentence> (or !--<sentence>: `start`). */
NMEA_INTERNAL bool frame_known(nmea_wire *wire, const char *line, size_t len, char start, const char *sentence,
                               nmea_error *err)
{
    nmea_frame f;
    if (!frame_line(&f, line, len, 0, err))
        return false;
    if (!is_standard_address(&f) || f.start.ptr[0] != start || f.address.len != talker_length(sentence) + strlen(sentence) ||
        !text_is(text_span(f.address.ptr + talker_length(sentence), f.address.ptr + f.address.len), sentence)) {
        fail(err, NMEA_ERR_NOT_A_SENTENCE,
             start == '!' ? ERROR_TEXT("line is not a !--%s sentence") : ERROR_TEXT("line is not a $--%s sentence"));
        set_address(err, f.address, NULL);
        err->str[0] = sentence;
        return false;
    }
    wire_of(wire, &f, sentence, NULL);
    return true;
}

/* The wire of a line whose address must be $<address>. */
NMEA_INTERNAL bool frame_proprietary(nmea_wire *wire, const char *line, size_t len, const char *address,
                                     nmea_error *err)
{
    nmea_frame f;
    if (!frame_line(&f, line, len, 0, err))
        return false;
    if (f.start.ptr[0] != '$' || !text_is(f.address, address)) {
        fail(err, NMEA_ERR_NOT_A_SENTENCE, ERROR_TEXT("line is not a $%s sentence"));
        set_address(err, f.address, NULL);
        err->str[0] = address;
        return false;
    }
    wire_of(wire, &f, NULL, NULL);
    return true;
}

/* The wire of a text command whose word must be `command` (in upper case). */
NMEA_INTERNAL bool frame_command(nmea_wire *wire, const char *line, size_t len, const char *command,
                                 nmea_error *err)
{
    nmea_frame f;
    if ((len && (line[0] == '$' || line[0] == '!')) || !word_is(first_word(line, len), command)) {
        fail(err, NMEA_ERR_NOT_A_SENTENCE, ERROR_TEXT("line is not a %s command"));
        err->str[0] = command;
        return false;
    }
    if (!text_frame(&f, line, len, err))
        return false;
    wire_of(wire, &f, NULL, line);
    return true;
}

/* The length of a line without one trailing LF or CR LF: the parsers take a line as it was read,
   as the Rust and Python ones do. A framed overlong line has no bytes (NULL): not read. */
static size_t without_line_ending(const char *line, size_t len)
{
    if (line && len && line[len - 1] == '\n')
        len -= len > 1 && line[len - 2] == '\r' ? 2 : 1;
    return len;
}

/* nmea_parse_<layout>: the line framed as layout `l` says, then read into `out`, a struct of it. */
static bool parse_with(const layout *l, void *out, const char *line, size_t len, nmea_error *err)
{
    nmea_wire wire;
    len = without_line_ending(line, len);
    if (l->kind == LAYOUT_STANDARD)
        return frame_known(&wire, line, len, l->start, l->sentence, err) && read_with(l, out, &wire, err);
    if (l->kind == LAYOUT_PROPRIETARY)
        return frame_proprietary(&wire, line, len, l->address, err) && read_with(l, out, &wire, err);
    return frame_command(&wire, line, len, l->command, err) && read_with(l, out, &wire, err);
}

/* The layouts a line may have, in the order they are tried. */
typedef struct {
    const char *key;
    size_t key_len;
    const char *suffix; /* a standard sentence: its id, after the talker in the address */
    const nmea_sentence_id *ids;
    size_t count;
} nmea_layouts;

/* The entry of a table sorted by key whose key is `key`, or NULL. The keys are compared byte by
   byte (as memcmp would, but the first byte mostly decides, sooner than a call). */
NMEA_INTERNAL inline const nmea_layouts *find_layouts(const nmea_layouts *table, size_t n, nmea_text key)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = (lo + hi) / 2, len = table[mid].key_len, common = len < key.len ? len : key.len, k;
        const unsigned char *entry = (const unsigned char *)table[mid].key, *want = (const unsigned char *)key.ptr;
        int order;
        for (k = 0; k < common && entry[k] == want[k]; k++)
            continue;
        order = k < common ? entry[k] - want[k] : len < key.len ? -1 : len > key.len;
        if (order == 0)
            return &table[mid];
        if (order < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return NULL;
}

/* A formatter of 3 or 4 characters (`id.len`) as a number (big-endian), as the _CODES tables
   hold them. */
NMEA_INTERNAL inline uint32_t standard_code(nmea_text id)
{
    uint32_t code = (uint32_t)(unsigned char)id.ptr[0] << 16 | (uint32_t)(unsigned char)id.ptr[1] << 8 |
                    (unsigned char)id.ptr[2];
    return id.len == 4 ? code << 8 | (unsigned char)id.ptr[3] : code;
}

/* Wire field `index` (0-based) of `fields` (separated by `sep`); empty past the end. */
static nmea_text field_at(nmea_text fields, char sep, size_t index)
{
    const char *p = fields.ptr, *end = fields.ptr + fields.len, *stop;
    for (; index > 0 && p < end; index--) {
        while (p < end && *p != sep)
            p++;
        if (p < end)
            p++;
        else
            return text_span(end, end);
    }
    for (stop = p; stop < end && *stop != sep; stop++)
        continue;
    return text_span(p, stop);
}

/* Whether a line with `count` wire fields holds the keyword of layout `id` in its place (ignoring
   case); blanked fields (lenient parsing) hold nothing. */
static bool holds_selector(nmea_sentence_id id, const nmea_wire *wire)
{
    const layout *l = LAYOUTS[id];
    if (!l->selector || l->selector_at >= wire->count)
        return false;
    if (wire->blanks && is_blank(wire->blank, wire->blanks, l->selector_at + 1u))
        return false;
    return upper_is(field_at(wire->fields, wire->sep, l->selector_at), l->selector);
}

/* Whether the line's first field reads as the first field of layout `l` (a number outside its
   range does; a layout without fields: whether the line has none). A layout that starts with a
   group, or a line too short for the first field, is left to the reader's count. */
static bool reads_first(const layout *l, const nmea_wire *wire)
{
    nmea_reader r;
    nmea_error err;
    field_value value;
    if (!l->before && !l->group && !l->optional)
        return wire->count == 0;
    if ((!l->before && l->group) || wire->count < field_width(&l->fields[0]))
        return true;
    reader_start(&r, wire, &err);
    r.any_range = true;
    return read_field(&r, &l->fields[0], &value);
}

/* Whether one of the layouts of a `$` line's address may read it: one whose keyword the line
   holds, or one without a keyword, when no layout of the address has one or when the line's
   first field reads as that layout's first (reads_first); else the line is a message of a known
   family that the spec does not know, kept as a generic sentence ($PASHR,BTS,... beside RT300's
   keyword-less $PASHR,<time>,...). */
NMEA_INTERNAL bool claimed(const nmea_layouts *layouts, const nmea_wire *wire)
{
    size_t i;
    bool keyed = false;
    for (i = 0; i < layouts->count; i++)
        keyed = keyed || LAYOUTS[layouts->ids[i]]->selector;
    for (i = 0; i < layouts->count; i++) {
        const layout *l = LAYOUTS[layouts->ids[i]];
        if (l->selector ? holds_selector(layouts->ids[i], wire) : !keyed || reads_first(l, wire))
            return true;
    }
    return false;
}

/* Parses the wire with one layout. */
NMEA_LEAF bool read_layout(nmea_sentence *out, nmea_sentence_id id, const nmea_wire *wire, nmea_error *err)
{
    out->id = id;
    return read_with(LAYOUTS[id], &out->as, wire, err);
}

/* The first of the layouts that reads the line, as first_fit would pick it: a layout whose field
   count does not fit is passed over, any other doubt ends the fast path. */
static bool fast_fit(nmea_sentence *out, const nmea_layouts *layouts, const char *line, const char *fields,
                     const char *end, size_t count)
{
    size_t i;
    for (i = 0; i < layouts->count; i++) {
        fast_result result = fast_read_layout(out, layouts->ids[i], line, fields, end, count);
        if (result != FAST_NOT_THIS)
            return result == FAST_OK;
    }
    return false;
}

/* Keeps the layout whose error to report, `kept` (its index times two, plus one for a bad field),
   in `*at`: the first one, or the first bad field that comes after it. */
static void keep_error(int *at, int kept)
{
    if (*at < 0 || (!(*at & 1) && (kept & 1)))
        *at = kept;
}

/* Whether variant `l` reads wire field `field` as its main layout does (see same_as_main). */
static bool same_as_main(const layout *l, unsigned field)
{
    const uint16_t *at;
    for (at = l->same_as_main; at && *at; at++)
        if (*at == field)
            return true;
    return false;
}

/* The first of the layouts that reads the wire; a variant is passed over when the main layout
   of its sentence, tried last before it, refused a field the variant reads the same way. When
   none does, `err` gets the error of the layouts whose keyword the first field holds (else of
   all of them): the first bad field among them, else their first error. */
NMEA_LEAF bool first_of_many(nmea_sentence *out, const nmea_layouts *layouts, const nmea_wire *wire,
                                nmea_error *err)
{
    /* The errors to report are kept as the layouts that made them, read again at the end: an
       error copied per candidate would triple this frame on the deepest path of nmea_parse.
       Each is its index times two plus whether it was a bad field (-1: none yet), so that this
       loop's state takes few registers where it is inlined. */
    int chosen = -1, fallback = -1, last = -1, i, n = (int)layouts->count;
    const char *refused = NULL; /* the sentence of the main layout tried last, when it refused */
    unsigned refused_field = 0; /* and the field it refused */
    bool again = false;         /* reading the layout whose error to report again */

    for (i = 0;; i++) {
        const layout *l;
        int kept;
        if (i == n) { /* none reads the wire */
            i = (chosen >= 0 ? chosen : fallback) / 2;
            if (i == last) /* reading is deterministic: the same error again */
                return false;
            again = true;
        }
        l = LAYOUTS[layouts->ids[i]];
        if (!again && l->variant && refused && words_equal(refused, l->sentence) && same_as_main(l, refused_field))
            continue;
        if (read_layout(out, layouts->ids[i], wire, err))
            return true; /* (never when again) */
        if (again)
            return false;
        last = i;
        kept = 2 * i + (err->kind == NMEA_ERR_BAD_FIELD);
        if (!l->variant) {
            refused = err->kind == NMEA_ERR_BAD_FIELD && err->field ? l->sentence : NULL;
            refused_field = err->field;
        }
        if (holds_selector(layouts->ids[i], wire))
            keep_error(&chosen, kept);
        keep_error(&fallback, kept);
    }
}

/* first_of_many, and for the usual single layout just that layout's reader (inlined here: no
   bookkeeping of errors to compare; at -Os first_of_many reads a single layout too, so that the
   reader is inlined once). */
NMEA_LEAF bool first_fit(nmea_sentence *out, const nmea_layouts *layouts, const nmea_wire *wire, nmea_error *err)
{
#if defined(__GNUC__) && defined(__OPTIMIZE_SIZE__)
    if (NMEA_MAX_LAYOUTS == 1) /* (a spec of one layout an address has no first_of_many) */
        return read_layout(out, layouts->ids[0], wire, err);
#else
    if (NMEA_MAX_LAYOUTS == 1 || layouts->count == 1)
        return read_layout(out, layouts->ids[0], wire, err);
#endif
    return first_of_many(out, layouts, wire, err);
}

/* After first_fit fails: the field at fault, a number outside its range kept as sent (unless
   options->strict) or any other (options->lenient) read as empty, kept as problem `*count` in
   options->problems (NULL: not kept), so that the layouts read the wire again (true); false when
   the field cannot be helped or a problem would be one too many. Out of line, beside the
   reading rather than above it: its frame is not on the stack under the layouts' reading. */
NMEA_OUTLINE bool refit(nmea_wire *wire, const nmea_options *options, const nmea_error *err, size_t *count)
{
    nmea_problems *keep = options->problems;
    nmea_problem_kind kind;
    /* a bad field's text is the field's text on the wire, empty once it has been left empty */
    if (err->kind != NMEA_ERR_BAD_FIELD || !err->field || !err->text.len || *count >= WIRE_BLANKS)
        return false;
    if (err->out_of_range && !options->strict) {
        kind = NMEA_PROBLEM_OUT_OF_RANGE;
        wire->blank[wire->blanks++] = (uint16_t)(err->field | RANGE_KEPT);
    } else if (options->lenient) {
        kind = NMEA_PROBLEM_LEFT_EMPTY;
        wire->blank[wire->blanks++] = (uint16_t)err->field;
    } else {
        return false;
    }
    if (keep)
        problem_of(&keep->list[*count], err, kind); /* written as they come: they count once a layout reads the wire */
    ++*count;
    return true;
}

/* The first of the layouts that reads the wire (first_fit); when none does, the fields at fault
   one at a time (refit) until a layout reads it, unless the options are strict and not lenient
   (then nothing is kept; nor in a build without problems). The sentence's problems are then
   kept in options->problems (NULL: not kept). */
NMEA_LEAF bool fit(nmea_sentence *out, const nmea_layouts *layouts, nmea_wire *wire, const nmea_options *options,
                       nmea_error *err)
{
#ifdef NMEA_NO_PROBLEMS
    (void)options;
    return first_fit(out, layouts, wire, err);
#else
    size_t count = 0;
    while (!first_fit(out, layouts, wire, err)) /* (one call: inlined once) */
        if (!refit(wire, options, err, &count))
            return false;
    if (count) {
        if (options->problems)
            options->problems->count = (uint8_t)count;
        out->problems = options->problems;
    }
    return true;
#endif
}

static void write_sentence(nmea_writer *w, const nmea_sentence *s)
{
    if (s->id == NMEA_SENTENCE_GENERIC)
        write_generic(w, &s->as.generic);
    else
        write_with(w, LAYOUTS[s->id], &s->as, s->problems);
}
