/* Layouts: what the spec says of each sentence layout, as a table the generator writes (the
   LAYOUTS of nmea.c), and the one general reader that interprets them (read_with, and entry_of
   for a repeated group's entries; the writer is layout_write.c, the JSON form layout_json.c).
   Only the fast path has code of its own per layout. */

/* The field types of the spec. */
typedef enum {
    FIELD_KEYWORD,
    FIELD_INTEGER,
    FIELD_DECIMAL,
    FIELD_HEX,
    FIELD_TIME,
    FIELD_DATE,
    FIELD_LATITUDE,
    FIELD_LONGITUDE,
    FIELD_CHAR,
    FIELD_LITERAL,
    FIELD_TEXT,
    FIELD_ENUM,
    FIELD_ENUM_CHARS
} field_type;

/* A field of a layout, or of the entries of its repeated group: 12 bytes on a 32-bit target, 6 in
   a terse build. What it takes besides its type (a range, a lookup table, a word, the texts of its
   errors) is an index into the table of its kind, which holds what the build's fields take, each
   once. */
typedef struct {
    uint16_t offset;    /* of its member in the layout struct (or the entry); 0 for a keyword */
    uint16_t arg;       /* integer, decimal: FIELD_RANGES (NO_ARG: any value); enum, enum_chars:
                           FIELD_ENUMS; keyword, literal: FIELD_WORDS; latitude, longitude:
                           FIELD_EXPECTED, what its hemisphere takes; else NO_ARG */
    uint8_t type;       /* field_type */
    uint8_t max_length; /* text, enum_chars: most characters (0: any number) */
#ifndef NMEA_TERSE_ERRORS
    uint16_t expected;  /* FIELD_EXPECTED: what it takes, for errors */
    const char *id;     /* for errors and the JSON's keys */
#endif
} layout_field;

/* The last members of a layout_field as the generator writes them, which -DNMEA_TERSE_ERRORS
   leaves out with the texts of errors (the table FIELD_EXPECTED too). */
#ifdef NMEA_TERSE_ERRORS
#define FIELD_NAMES(expected, id)
#else
#define FIELD_NAMES(expected, id) expected, id
#endif

/* layout_field.arg of a field that takes nothing besides its type. */
#define NO_ARG 0xFFFFu

/* A field's id, what it takes and what its hemisphere takes (NULL in a terse build). */
NMEA_INTERNAL const char *field_id(const layout_field *f)
{
#ifdef NMEA_TERSE_ERRORS
    (void)f;
    return NULL;
#else
    return f->id;
#endif
}

NMEA_INTERNAL const char *field_expected(const layout_field *f)
{
#ifdef NMEA_TERSE_ERRORS
    (void)f;
    return NULL;
#else
    return FIELD_EXPECTED[f->expected];
#endif
}

static const char *hemisphere_expected(const layout_field *f)
{
#ifdef NMEA_TERSE_ERRORS
    (void)f;
    return NULL;
#else
    return FIELD_EXPECTED[f->arg];
#endif
}

/* Its range (NULL: any value), lookup table and word. */
static const nmea_range *range_of(const layout_field *f)
{
    return f->arg == NO_ARG ? NULL : FIELD_RANGES[f->arg];
}

static const nmea_enum_def *table_of(const layout_field *f)
{
    return FIELD_ENUMS[f->arg];
}

static const char *word_of(const layout_field *f)
{
    return FIELD_WORDS[f->arg];
}

/* The wire fields a field spans: a latitude or longitude and its hemisphere two, any other one. */
static size_t field_width(const layout_field *f)
{
    return f->type == FIELD_LATITUDE || f->type == FIELD_LONGITUDE ? 2 : 1;
}

/* The fields of a layout without any (its `fields` point here, never NULL: no arithmetic on it;
   a spec in which every layout has fields leaves it unused). */
NMEA_INTERNAL const layout_field NO_FIELDS[1];

/* An offset of a member a layout does not have. */
#define NO_MEMBER 0xFFFFu

/* The repeated group of a layout: `min` to `max` entries of `width` wire fields. */
typedef struct {
    const char *id;
    const layout_field *fields; /* offsets in an entry (a single field: 0) */
    uint16_t field_count;
    uint16_t width;
    uint16_t min;
    uint16_t max;
    bool single;           /* one field an entry: the JSON lists its values without keys */
    uint16_t offset;       /* of its nmea_entries (NO_MEMBER: none, the entries hold only keywords) */
    uint16_t entry_size;   /* of an entry of nmea_entries.items */
    uint16_t count_offset; /* of the uint8_t entry count (NO_MEMBER: always `max` entries) */
} layout_group;

typedef enum { LAYOUT_STANDARD, LAYOUT_PROPRIETARY, LAYOUT_TEXT } layout_kind;

/* A sentence layout. Its fields are those before the group, after it, and the optional trailing
   ones, in wire order. */
typedef struct {
    const char *sentence;      /* the spec's sentence id */
    const char *address;       /* a proprietary sentence's address, a text command's word; NULL */
    const char *command;       /* a text command: its word in upper case; NULL */
    const char *variant;       /* NULL: the sentence's main layout */
    const char *selector;      /* the keyword (upper case) every line of it holds, or NULL */
    const uint16_t *same_as_main; /* a variant: the wire fields (1-based, then 0) it reads as its
                                     main layout does, which it is not tried for; or NULL */
    const layout_field *fields; /* NO_FIELDS: none */
    const layout_group *group;  /* NULL: none */
    uint16_t selector_at;      /* the selector's wire index (0-based) */
    uint16_t before;           /* fields before the group (all required ones without a group) */
    uint16_t after;            /* required fields after the group */
    uint16_t optional;         /* optional trailing fields */
    uint16_t fixed;            /* required wire fields besides the group */
    uint16_t max_fields;       /* wire fields at most (without a group) */
    uint16_t optional_max;     /* optional wire fields at most */
    uint16_t size;             /* of the struct */
    uint16_t head;             /* offset of the talker (standard) or as_received (text); NO_MEMBER */
    uint16_t optional_count;   /* offset of the uint8_t optional_count; NO_MEMBER */
    uint16_t checksum;         /* offset of the nmea_checksum_style; NO_MEMBER (a text command) */
    uint8_t kind;              /* layout_kind */
    char start;                /* '$' or '!' */
} layout;

NMEA_INLINE void *member_at(void *s, uint16_t offset)
{
    return (char *)s + offset;
}

NMEA_INLINE const void *const_member_at(const void *s, uint16_t offset)
{
    return (const char *)s + offset;
}

/* How many optional trailing fields `optional` wire fields hold (a latitude needs both of its). */
static size_t optional_present(const layout *l, size_t optional)
{
    const layout_field *f = l->fields + l->before + l->after;
    size_t n, wire = 0;
    for (n = 0; n < l->optional; n++) {
        wire += field_width(&f[n]);
        if (wire > optional)
            break;
    }
    return n;
}

/* The entries of a layout's group that are on the wire (a struct's count may be too big). */
static size_t entries_of(const layout_group *g, const void *s)
{
    size_t n;
    if (g->count_offset == NO_MEMBER)
        return g->max;
    n = *(const uint8_t *)const_member_at(s, g->count_offset);
    return n < g->max ? n : g->max;
}

/* The optional trailing fields of a struct that are on the wire. */
static size_t optional_of(const layout *l, const void *s)
{
    return l->optional_count == NO_MEMBER ? 0 : *(const uint8_t *)const_member_at(s, l->optional_count);
}

/* The entries of a layout's group (NULL: it stores nothing, its entries hold only keywords). */
static const nmea_entries *entries_in(const layout_group *g, const void *s)
{
    return g->offset == NO_MEMBER ? NULL : (const nmea_entries *)const_member_at(s, g->offset);
}

/* Reads field `f` into `out`, a value of its type (nothing for a keyword). The field's id and
   what it takes go in the reader, for its errors: each type's reader takes at most four
   arguments, so that at -Os these calls are jumps (no frame of read_field under them). */
static bool read_field(nmea_reader *r, const layout_field *f, void *out)
{
#ifndef NMEA_TERSE_ERRORS
    r->name = field_id(f);
    r->expected = field_expected(f);
#endif
    switch ((field_type)f->type) {
    case FIELD_KEYWORD:
        return read_keyword(r, word_of(f));
    case FIELD_INTEGER:
        return read_integer(r, out, range_of(f));
    case FIELD_DECIMAL:
        return read_decimal(r, out, range_of(f));
    case FIELD_HEX:
        return read_hex(r, out);
    case FIELD_TIME:
        return read_time(r, out);
    case FIELD_DATE:
        return read_date(r, out);
    case FIELD_LATITUDE:
        return read_latitude(r, out, hemisphere_expected(f));
    case FIELD_LONGITUDE:
        return read_longitude(r, out, hemisphere_expected(f));
    case FIELD_CHAR:
        return read_char(r, out);
    case FIELD_LITERAL:
        return read_literal(r, out, word_of(f));
    case FIELD_TEXT:
        return read_text(r, out, f->max_length);
    case FIELD_ENUM:
        return read_enum(r, out, table_of(f));
    case FIELD_ENUM_CHARS:
        return read_enum_chars(r, out, table_of(f), f->max_length);
    }
    return false;
}

NMEA_LEAF bool read_fields(nmea_reader *r, const layout_field *f, size_t n, void *entry)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (!read_field(r, &f[i], member_at(entry, f[i].offset)))
            return false;
    return true;
}

/* Any value a field holds, for reading one field of a group entry on its own. */
typedef union {
    nmea_number number;
    nmea_hex hex;
    nmea_time time;
    nmea_date date;
    nmea_coordinate coordinate;
    char c;
    bool literal;
    nmea_text text;
    nmea_enum enumeration;
} field_value;

/* The size of the value of field `f` (0: a keyword holds none). */
static size_t field_size(const layout_field *f)
{
    switch ((field_type)f->type) {
    case FIELD_KEYWORD:
        return 0;
    case FIELD_INTEGER:
    case FIELD_DECIMAL:
        return sizeof(nmea_number);
    case FIELD_HEX:
        return sizeof(nmea_hex);
    case FIELD_TIME:
        return sizeof(nmea_time);
    case FIELD_DATE:
        return sizeof(nmea_date);
    case FIELD_LATITUDE:
    case FIELD_LONGITUDE:
        return sizeof(nmea_coordinate);
    case FIELD_CHAR:
        return sizeof(char);
    case FIELD_LITERAL:
        return sizeof(bool);
    case FIELD_TEXT:
    case FIELD_ENUM_CHARS:
        return sizeof(nmea_text);
    case FIELD_ENUM:
        return sizeof(nmea_enum);
    }
    return 0;
}

/* The end of the `n` fields (n > 0) that start at `p`, before `end`. */
static const char *fields_end(const char *p, const char *end, char sep, size_t n)
{
    for (;; p++) {
        while (p < end && *p != sep)
            p++;
        if (p == end || --n == 0)
            return p;
    }
}

/* Reads a parsed sentence's group entries again, field by field, from their wire text. */
typedef struct {
    nmea_reader r;
    nmea_error err;
    nmea_wire wire;
} entry_reader;

static bool entry_reader_at(entry_reader *c, const layout *l, const nmea_entries *e, size_t i);

/* The next field `f` of an entry, into `out`, as parsing read it (lenient parsing's blanks
   included). A field that does not read (in a struct the parser did not make) is empty. */
static void reread_field(entry_reader *c, const layout_field *f, void *out)
{
    const char *next = c->r.next;
    unsigned index = c->r.index;
    size_t size = field_size(f);

    if (size)
        memset(out, 0, size);
    if (read_field(&c->r, f, out))
        return;
    if (size)
        memset(out, 0, size);
    c->r.next = fields_end(next, reader_end(&c->r), c->r.sep, field_width(f));
    c->r.next += c->r.next < reader_end(&c->r);
    c->r.index = index + (unsigned)field_width(f);
}

/* A layout with a repeated group (`width` wire fields, `min` to `max` times) and `fixed`
   required fields besides: how many times it occurs and how many optional wire fields follow. */
static bool read_group_count(nmea_reader *r, const layout *l, size_t count, size_t *repeats, size_t *optional)
{
    const layout_group *g = l->group;
    size_t rest, extra, width = g->width;
    *repeats = 0; /* (set first: gcc cannot tell they are read only on success) */
    *optional = 0;
    if (count < l->fixed + g->min * width)
        return too_few(r, l->fixed + g->min * width, count);
    rest = count - l->fixed;
    *repeats = rest / width < g->max ? rest / width : g->max;
    extra = rest - *repeats * width;
    if (extra > l->optional_max) {
        if (*repeats == g->max)
            return too_many(r, l->fixed + g->max * width + l->optional_max, count);
        count_error(r, ERROR_TEXT("%s %s entries take %n fields each, %n left over"), width, extra);
        r->err->str[1] = g->id;
        return false;
    }
    *optional = extra;
    return true;
}

/* Reads the entries of the group of layout `l` (they stay on the wire, each checked here) into
   its nmea_entries in `s`, a struct of the layout. Each value is read into that nmea_entries,
   which is only filled afterwards: no value on the stack (a keyword, the only field of a group
   that stores nothing, reads into nothing). */
NMEA_LEAF bool read_entries(nmea_reader *r, const layout *l, void *s, size_t repeats)
{
    const layout_group *g = l->group;
    const char *start = r->next;
    unsigned first = r->index;
    void *value = member_at(s, g->offset == NO_MEMBER ? 0 : g->offset);
    size_t i, j;
    typedef char value_fits[sizeof(field_value) <= sizeof(nmea_entries) ? 1 : -1];
    (void)sizeof(value_fits);

    for (i = 0; i < repeats; i++) {
        reader_entry(r, g->id, i);
        for (j = 0; j < g->field_count; j++)
            if (!read_field(r, &g->fields[j], value))
                return false;
    }
    if (g->offset != NO_MEMBER) { /* the entries stay on the wire, read when asked for */
        const nmea_wire *wire = r->wire;
        nmea_entries *e = (nmea_entries *)value;
        memset(e, 0, sizeof *e);
        e->wire = text_span(start, repeats ? fields_end(start, reader_end(r), r->sep, repeats * g->width) : start);
        for (j = 0; j < wire->blanks; j++)
            if (wire->blank[j] > first && wire->blank[j] <= r->index)
                e->blank[e->blanks++] = (uint16_t)(wire->blank[j] - first);
    }
    if (g->count_offset != NO_MEMBER)
        *(uint8_t *)member_at(s, g->count_offset) = (uint8_t)repeats;
    reader_entry(r, NULL, 0);
    return true;
}

/* The start of read_with: the wire's field count checked against layout `l`, `s` cleared and
   given what the wire holds besides the fields; `counts` the entries of the group and the
   optional fields on the wire. */
NMEA_LEAF bool read_start(nmea_reader *r, const layout *l, void *s, uint16_t *counts)
{
    const nmea_wire *wire = r->wire;
    size_t optional, repeats = 0;

    if (l->group ? !read_group_count(r, l, wire->count, &repeats, &optional)
                 : !read_count(r, wire->count, l->fixed, l->max_fields, &optional)) {
        r->err->str[0] = l->sentence; /* (see count_error) */
        return false;
    }
    counts[0] = (uint16_t)repeats; /* (at most a group's `max`) */
    clear_layout(s, l->size);
    if (l->head != NO_MEMBER)
#ifdef NMEA_NO_COMMANDS
        *(nmea_text *)member_at(s, l->head) = wire->address;
#else
        *(nmea_text *)member_at(s, l->head) = l->kind == LAYOUT_TEXT ? wire->line : wire->address;
#endif
    if (l->checksum != NO_MEMBER)
        *(nmea_checksum_style *)member_at(s, l->checksum) = (nmea_checksum_style)wire->checksum;
    counts[1] = (uint16_t)optional_present(l, optional);
    if (l->optional_count != NO_MEMBER)
        *(uint8_t *)member_at(s, l->optional_count) = (uint8_t)counts[1];
    return true;
}

/* Reads the wire into `s`, a struct of layout `l`: read_with, and at -Os nmea_parse's reading
   of a layout, inlined there (read_layout) so that the descent saves the registers once. */
NMEA_LEAF bool read_layout_with(const layout *l, void *s, const nmea_wire *wire, nmea_error *err)
{
    nmea_reader r;
    uint16_t counts[2]; /* the group's entries, the optional fields present (small: read_with's frame) */

    reader_start(&r, wire, err);
    return read_start(&r, l, s, counts) && read_fields(&r, l->fields, l->before, s) &&
           (!l->group || read_entries(&r, l, s, counts[0])) &&
           read_fields(&r, l->fields + l->before, l->after + counts[1], s);
}

NMEA_OUTLINE bool read_with(const layout *l, void *s, const nmea_wire *wire, nmea_error *err)
{
    return read_layout_with(l, s, wire, err);
}

/* Starts `c` at entry `i` of the group of layout `l` whose entries `e` holds on the wire; false
   when the wire ends before it. */
static bool entry_reader_at(entry_reader *c, const layout *l, const nmea_entries *e, size_t i)
{
    nmea_wire *w = &c->wire;
    const char *p = e->wire.ptr, *end = p ? p + e->wire.len : NULL;
    size_t skip;

    memset(w, 0, sizeof *w);
    w->sep = l->kind == LAYOUT_TEXT ? ' ' : ',';
    w->ignore_case = l->kind == LAYOUT_TEXT;
    for (skip = i * l->group->width; skip > 0; skip--) {
        p = fields_end(p, end, w->sep, 1);
        if (p == end)
            return false;
        p++;
    }
    if (p == NULL || (p == end && i > 0))
        return false;
    w->fields = text_span(p, end);
    w->blanks = e->blanks < WIRE_BLANKS ? e->blanks : WIRE_BLANKS;
    memcpy(w->blank, e->blank, w->blanks * sizeof w->blank[0]);
    reader_start(&c->r, w, &c->err);
    c->r.any_range = true; /* parsing has held each number to its range, or kept it outside */
    c->r.index = (unsigned)(i * l->group->width); /* the blanks count from the first entry */
    return true;
}

/* Entry `i` of the group of `s`, a struct of layout `l`, into `out` (an entry, or the value of a
   group of one field): false when the group has fewer entries. */
NMEA_OUTLINE bool entry_of(const layout *l, const void *s, size_t i, void *out)
{
    const layout_group *g = l->group;
    const nmea_entries *e = entries_in(g, s);
    entry_reader c;
    size_t j;

    if (i >= entries_of(g, s))
        return false;
    if (e->items) {
        memcpy(out, (const char *)e->items + i * g->entry_size, g->entry_size);
        return true;
    }
    memset(out, 0, g->entry_size);
    if (!entry_reader_at(&c, l, e, i))
        return true; /* past what the wire holds: an empty entry */
    for (j = 0; j < g->field_count; j++)
        reread_field(&c, &g->fields[j], member_at(out, g->fields[j].offset));
    return true;
}
