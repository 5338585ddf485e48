/* Reading the fields of a layout: a cursor over the comma-separated fields, which knows the
   address and the field being read for the errors. */

#if defined(__GNUC__) && defined(__OPTIMIZE_SIZE__)
#define NMEA_READER_END_OF_WIRE
#endif

/* The fields a wire may read as empty (or keep outside their range): strict reading (a build
   without problems, -DNMEA_NO_PROBLEMS) blanks none, and its wire, on the stack under the whole
   parse, keeps room for one only. */
#ifdef NMEA_NO_PROBLEMS
#define WIRE_BLANKS 1
#else
#define WIRE_BLANKS NMEA_MAX_PROBLEMS
#endif

/* The fields of a line (or of decode's JSON) for a layout to read, and the address its errors
   name: `address` followed by `suffix` (a standard sentence: the talker and the sentence id). */
typedef struct {
    nmea_text address;
    const char *suffix;
    nmea_text fields;
#ifndef NMEA_NO_COMMANDS
    nmea_text line;               /* a text command: the command as received */
#endif
    uint16_t blank[WIRE_BLANKS];   /* the wire fields at fault: read as empty (lenient parsing), */
    uint8_t blanks;               /* or with RANGE_KEPT, numbers read without their range */
    char sep;                     /* between fields: ',' or ' ' (the words of a text command) */
    bool ignore_case;             /* a text command: keywords and enum codes match ignoring case */
    uint8_t checksum;             /* nmea_checksum_style (small types: the wire is on the stack all
                                     the while a line is parsed) */
    uint16_t count;               /* fields */
} nmea_wire;

/* Added to a wire index in nmea_wire.blank: the number there is kept outside its range. (No
   line has that many fields, and an index so marked is never taken for a field read as empty.) */
#define RANGE_KEPT 0x8000u

/* The cursor of a layout's reading. It refers to the wire (the address and the blanks, for
   errors and lenient parsing) rather than copying it, and keeps the field being read (its id and
   what it takes), so that each field type's reader takes the cursor, its value and at most two
   more arguments: the calls from read_field are then jumps, and nmea_parse's descent stays
   within a few hundred bytes of stack on a microcontroller. */
typedef struct {
    const char *next;
#ifndef NMEA_READER_END_OF_WIRE
    const char *end;
#endif
    const nmea_wire *wire;
    const char *group;
    uint16_t index; /* 1-based wire index of the field read last */
    uint16_t entry;
#ifndef NMEA_TERSE_ERRORS /* (a terse build's errors name no field: a smaller frame of read_with) */
    const char *name;     /* the field being read: its id, */
    const char *expected; /* and what it takes */
#endif
    char sep;
    bool ignore_case;
    bool any_range;   /* numbers are not held to their range (a parsed sentence's entries read again) */
    uint8_t blanks;   /* of wire->blank */
    nmea_error *err;
} nmea_reader;

/* The end of the fields the reader reads. At -Os (a firmware's build) it is the wire's, read there
   each time: the reader is on the stack all the while a layout reads the line (read_with), and a
   member less keeps that frame smaller. */
NMEA_INLINE const char *reader_end(const nmea_reader *r)
{
#ifdef NMEA_READER_END_OF_WIRE
    return r->wire->fields.ptr + r->wire->fields.len;
#else
    return r->end;
#endif
}

static void reader_start(nmea_reader *r, const nmea_wire *wire, nmea_error *err)
{
    r->next = wire->fields.ptr;
#ifndef NMEA_READER_END_OF_WIRE
    r->end = wire->fields.ptr + wire->fields.len;
#endif
    r->index = 0;
    r->wire = wire;
    r->group = NULL;
    r->entry = 0;
    r->sep = wire->sep;
    r->ignore_case = wire->ignore_case;
    r->any_range = false;
    r->blanks = wire->blanks;
    r->err = err;
}

/* Zeroes the `size` first bytes of a layout struct before it is read, with the C library's
   memset: the size is read back from a volatile so that the compiler cannot see it is a
   constant of a few hundred bytes, which it would inline as `rep stos`, slow to start. */
NMEA_OUTLINE void clear_layout(void *s, size_t size)
{
    volatile size_t unknown = size;
    memset(s, 0, unknown);
}

/* Whether lenient parsing reads wire field `index` (1-based) as empty. */
NMEA_RARE_LEAF bool is_blank(const uint16_t *blank, unsigned blanks, unsigned index)
{
    unsigned i;
    for (i = 0; i < blanks; i++)
        if (blank[i] == index)
            return true;
    return false;
}

/* From now on the fields read belong to entry `index` (0-based) of `group` (NULL: none). */
NMEA_INTERNAL void reader_entry(nmea_reader *r, const char *group, size_t index)
{
    r->group = group;
    r->entry = (uint16_t)(index + 1);
}

NMEA_INLINE nmea_text next_field(nmea_reader *r)
{
    const char *p = r->next, *q = p, *end = reader_end(r); /* (locals: the bytes read could alias r) */
    char sep = r->sep;
    nmea_text t;
    r->index++;
    while (q < end && *q != sep)
        q++;
    t = text_span(p, q);
    r->next = q < end ? q + 1 : q;
    if (r->blanks && is_blank(r->wire->blank, r->blanks, r->index))
        t.len = 0;
    return t;
}

/* A field count refused (too_few_fields; too_many sets its own kind after): four arguments, none
   passed on the stack, so that read_with's frame has no room for one. Its sentence (the layout's
   id, str[0]) is the layout reader's to set (read_start): the reader does not keep it, one member
   less in read_with's frame. */
static bool count_error(nmea_reader *r, const char *pattern, size_t n, size_t m)
{
    fail(r->err, NMEA_ERR_TOO_FEW_FIELDS, pattern);
    set_address(r->err, r->wire->address, r->wire->suffix);
    r->err->num[0] = n;
    r->err->num[1] = m;
    return false;
}

static bool too_few(nmea_reader *r, size_t need, size_t found)
{
    return count_error(r, ERROR_TEXT("%s needs at least %n fields, found %n"), need, found);
}

static bool too_many(nmea_reader *r, size_t limit, size_t found)
{
    count_error(r, ERROR_TEXT("%s takes at most %n fields, found %n"), limit, found);
    r->err->kind = NMEA_ERR_TOO_MANY_FIELDS;
    return false;
}

/* A layout without a repeated group: `fixed` required fields, `max` in all. Sets `optional` to
   the number of optional trailing wire fields present. */
/* The wire of a framed line: a standard sentence's address is its talker (2 characters, 4 for a
   query) followed by `suffix` (its sentence id); a text command (`line`, as received) has words separated by
   spaces. */
static void wire_of(nmea_wire *wire, const nmea_frame *f, const char *suffix, const char *line)
{
    /* a standard sentence's talker: the address but the sentence id (two talker IDs of a query) */
    wire->address = suffix ? text_span(f->address.ptr, f->address.ptr + f->address.len - strlen(suffix)) : f->address;
    wire->suffix = suffix;
    wire->fields = f->fields;
    wire->count = (uint16_t)f->count;
    wire->sep = line ? ' ' : ',';
    wire->ignore_case = line != NULL;
    wire->checksum = (uint8_t)f->checksum;
#ifndef NMEA_NO_COMMANDS
    wire->line = line ? text_span(line, f->fields.ptr + f->fields.len) : nmea_text_of(NULL);
#endif
    wire->blanks = 0;
}

/* For nmea_build_*: the sentence just written to w (which must hold it, its CR LF and a NUL),
   framed again as a receiver frames it. */
NMEA_INTERNAL bool build_wire(nmea_writer *w, bool text, nmea_wire *wire, nmea_error *err)
{
    nmea_frame f;
    if (w->len + 2 >= w->cap) {
        fail(err, NMEA_ERR_TOO_LONG, ERROR_TEXT("the sentence, its CR LF and a NUL need %n bytes, the buffer holds %n"));
        err->num[0] = w->len + 3;
        err->num[1] = w->cap;
        w->len = w->cap; /* nothing of it is kept */
        return false;
    }
    if (!(text ? text_frame(&f, w->buf, w->len, err) : frame_line(&f, w->buf, w->len, 0, err)))
        return false;
    wire_of(wire, &f, NULL, text ? w->buf : NULL);
    return true;
}

/* A refused sentence stays in the buffer (the error points into it); one too long is not kept. */
NMEA_INTERNAL size_t build_failed(nmea_writer *w)
{
    writer_finish(w);
    return 0;
}

NMEA_INTERNAL size_t build_end(nmea_writer *w)
{
    put_char(w, '\r');
    put_char(w, '\n');
    return writer_finish(w);
}

NMEA_INTERNAL inline bool read_count(nmea_reader *r, size_t count, size_t fixed, size_t max, size_t *optional)
{
    *optional = 0; /* (set first: once inlined, gcc -O1 cannot tell it is read only on success) */
    if (count < fixed)
        return too_few(r, fixed, count);
    if (count > max)
        return too_many(r, max, count);
    *optional = count - fixed;
    return true;
}

/* The error of the field being read, at wire field `index`, whose `text` is not what it takes. */
NMEA_FRAME bool bad_field(nmea_reader *r, unsigned index, nmea_text text)
{
    nmea_error *err = r->err;
    /* fail's work, in this frame (the deepest of nmea_parse's paths end here): the error cleared
       around `text`, stored first, so that no argument is held across the calls */
    err->text = text;
    memset(err, 0, offsetof(nmea_error, text));
    memset((char *)err + offsetof(nmea_error, text) + sizeof err->text, 0,
           sizeof *err - offsetof(nmea_error, text) - sizeof err->text);
    err->kind = NMEA_ERR_BAD_FIELD;
    err->pattern = ERROR_TEXT("expected %s, found %q");
    err->has_address = true;
    err->address = r->wire->address;
    err->address_suffix = r->wire->suffix;
    err->field = index;
    err->group = r->group;
    err->entry = r->entry;
#ifndef NMEA_TERSE_ERRORS
    err->name = r->name;
    err->str[0] = r->expected;
#endif
    return false;
}

/* The general reading of an integer or decimal field: out of its range, an error that says so
   (out_of_range), unless the field is one whose number is kept outside its range. */
NMEA_RARE bool read_number(nmea_reader *r, nmea_number *out, const nmea_range *range, bool integer)
{
    nmea_text t = next_field(r);
    if (!t.len)
        return true;
    if (!parse_number(t, integer, out))
        return bad_field(r, r->index, t);
    if (in_range(out, range) || r->any_range || is_blank(r->wire->blank, r->blanks, r->index | RANGE_KEPT))
        return true;
    bad_field(r, r->index, t);
    r->err->out_of_range = true;
    return false;
}

/* The common case of read_number, in the one pass that finds the end of the field: an empty
   field, or digits with (`integer` false) at most one point, NMEA_NUMBER_DIGITS digits in all, in
   `range`. Anything else (a sign, more digits, not a number, out of range, a field at fault
   in a second reading) is left to read_number: returns false without having read it. */
NMEA_HOT bool quick_number(nmea_reader *r, nmea_number *out, const nmea_range *range, bool integer)
{
    const char *p = r->next, *end = reader_end(r), *point = NULL;
    uint64_t digits = 0; /* unsigned: a run too long for it is refused below, not undefined */
    unsigned digit;      /* unsigned: a byte below '0' wraps to a large value */
    size_t whole, count;
    nmea_number n;

    if (r->blanks)
        return false;
    for (; p < end && (digit = (unsigned)(unsigned char)*p - '0') < 10; p++)
        digits = digits * 10 + digit;
    whole = (size_t)(p - r->next);
    if (!integer && p < end && *p == '.')
        for (point = p++; p < end && (digit = (unsigned)(unsigned char)*p - '0') < 10; p++)
            digits = digits * 10 + digit;
    count = (size_t)(p - r->next) - (point != NULL); /* digits before and after the point */
    if ((p < end && *p != r->sep) || count > NMEA_NUMBER_DIGITS || (point && count == 0))
        return false;
    if (count) {
        n.digits = (nmea_digits)digits;
        n.scale = (uint8_t)(count - whole);
        n.width = (uint8_t)whole;
        n.sign = 0;
        n.point = point != NULL;
        n.present = true;
        if (!in_range(&n, range))
            return false;
        *out = n;
    }
    r->index++;
    r->next = p < end ? p + 1 : p;
    return true;
}

/* An integer or decimal field: quick_number, else read_number. A build for size (-Os) has one
   scanner of numbers, read_number: quick_number is there for speed only. */
#if defined(__GNUC__) && defined(__OPTIMIZE_SIZE__)
#define QUICK_NUMBER(r, out, range, integer) false
#else
#define QUICK_NUMBER(r, out, range, integer) quick_number(r, out, range, integer)
#endif

NMEA_HOT_FRAME bool read_integer(nmea_reader *r, nmea_number *out, const nmea_range *range)
{
    return QUICK_NUMBER(r, out, range, true) || read_number(r, out, range, true);
}

NMEA_HOT_FRAME bool read_decimal(nmea_reader *r, nmea_number *out, const nmea_range *range)
{
    return QUICK_NUMBER(r, out, range, false) || read_number(r, out, range, false);
}

NMEA_FRAME bool read_hex(nmea_reader *r, nmea_hex *out)
{
    nmea_text t = next_field(r);
    if (t.len && !parse_hex(t, out))
        return bad_field(r, r->index, t);
    return true;
}

NMEA_FRAME bool read_time(nmea_reader *r, nmea_time *out)
{
    nmea_text t = next_field(r);
    if (t.len && !parse_time(t, out))
        return bad_field(r, r->index, t);
    return true;
}

NMEA_FRAME bool read_date(nmea_reader *r, nmea_date *out)
{
    nmea_text t = next_field(r);
    if (t.len && !parse_date(t, out))
        return bad_field(r, r->index, t);
    return true;
}

/* A value field and a hemisphere field, both empty or both set. A value that does not read is
   refused before the hemisphere is taken (the same error: the reading ends there), so that the
   two fields' texts are not both held across the parsing: 8 bytes less of this frame on
   nmea_parse's deepest path at -Os. */
static bool read_coordinate(nmea_reader *r, nmea_coordinate *out, const char *hemisphere_expected, bool longitude)
{
    const char *hemispheres = longitude ? "EW" : "NS";
    nmea_text value = next_field(r), hemisphere;
    if (value.len && !parse_coordinate(value, 2u + longitude, longitude ? 180 : 90, out))
        return bad_field(r, r->index, value);
    hemisphere = next_field(r);
    if (!value.len) {
        if (hemisphere.len)
            return bad_field(r, r->index - 1, value);
        return true;
    }
    if (hemisphere.len != 1 || (hemisphere.ptr[0] != hemispheres[0] && hemisphere.ptr[0] != hemispheres[1])) {
        out->present = false;
#ifndef NMEA_TERSE_ERRORS
        r->expected = hemisphere_expected;
#else
        (void)hemisphere_expected;
#endif
        return bad_field(r, r->index, hemisphere);
    }
    out->hemisphere = hemisphere.ptr[0];
    return true;
}

NMEA_FRAME bool read_latitude(nmea_reader *r, nmea_coordinate *out, const char *hemisphere_expected)
{
    return read_coordinate(r, out, hemisphere_expected, false);
}

NMEA_FRAME bool read_longitude(nmea_reader *r, nmea_coordinate *out, const char *hemisphere_expected)
{
    return read_coordinate(r, out, hemisphere_expected, true);
}

NMEA_FRAME bool read_char(nmea_reader *r, char *out)
{
    nmea_text t = next_field(r);
    if (t.len > 1)
        return bad_field(r, r->index, t);
    *out = t.len ? t.ptr[0] : 0;
    return true;
}

NMEA_FRAME bool read_literal(nmea_reader *r, bool *out, const char *literal)
{
    nmea_text t = next_field(r);
    if (t.len && !text_is(t, literal))
        return bad_field(r, r->index, t);
    *out = t.len > 0;
    return true;
}

/* A fixed word that must be there (it picks the layout); in a text command ignoring case. */
NMEA_FRAME bool read_keyword(nmea_reader *r, const char *keyword)
{
    nmea_text t = next_field(r);
    if (!text_is(t, keyword) && !(r->ignore_case && upper_is(t, keyword)))
        return bad_field(r, r->index, t);
    return true;
}

NMEA_FRAME bool read_text(nmea_reader *r, nmea_text *out, size_t max_length)
{
    nmea_text t = next_field(r);
    if (max_length && t.len > max_length)
        return bad_field(r, r->index, t);
    *out = t;
    return true;
}

/* A known code, or a well-formed unknown one (kept in `code`). */
NMEA_FRAME bool read_enum(nmea_reader *r, nmea_enum *out, const nmea_enum_def *def)
{
    nmea_text t = next_field(r);
    size_t i;
    if (!t.len)
        return true;
#ifdef NMEA_NO_COMMANDS
    out->value = enum_find(def, t.ptr, t.len);
#else
    out->value = r->ignore_case ? enum_find_upper(def, t) : enum_find(def, t.ptr, t.len);
#endif
    if (out->value == NMEA_UNKNOWN_CODE && !is_code_like(def, t.ptr, t.len, def->min_len, def->max_len))
        return bad_field(r, r->index, t);
    for (i = 0; i < t.len; i++) /* t.len <= max_len <= NMEA_CODE_MAX; a code is a character or two */
        out->code[i] = t.ptr[i];
    out->code[t.len] = 0;
    out->present = true;
    return true;
}

/* A run of one-character codes (GNS mode "ANNN"), kept as text. */
NMEA_FRAME bool read_enum_chars(nmea_reader *r, nmea_text *out, const nmea_enum_def *def, size_t max_length)
{
    nmea_text t = next_field(r);
    size_t i;
    if (max_length && t.len > max_length)
        return bad_field(r, r->index, t);
    for (i = 0; i < t.len; i++)
        if (enum_find(def, t.ptr + i, 1) == NMEA_UNKNOWN_CODE && !is_code_like(def, t.ptr + i, 1, 1, 1))
            return bad_field(r, r->index, t);
    *out = t;
    return true;
}
