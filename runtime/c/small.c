/* The small profile's reader (-DNMEA_SMALL, issue 32): nmea_parse for a firmware short of flash,
   of another design than the general reader (layout.c, reader.c, dispatch.c), for the same
   results. A line is framed in one pass (printable bytes, checksum, fields counted), its address
   found by a linear scan over the packed ids of the build's standard sentences, and its layouts
   read by one loop over packed descriptors, two bytes a field (its type and the index of what it
   takes, the offset of its member), whose readers are one switch over one scanner of digits: a
   number, a time, a date and a coordinate are digits with a point, told apart by how many there
   are. Ranges are integer pairs, enum codes packed strings. No recursion, no division of 64 bits,
   two frames under nmea_parse (the line's, the fields'), no call from the field readers but to
   leaves.

   The generator writes its tables (SMALL_LAYOUTS, SMALL_FIELDS, SMALL_IDS, SMALL_RANGES,
   SMALL_ENUMS, SMALL_WORDS: generator/emit_c.py, small_view) and defines NMEA_SMALL_READER in a
   -DNMEA_SMALL build of a spec whose layouts it can describe (standard `$` sentences without a
   keyword that picks the layout or a field of enum characters); any other spec keeps the general
   reader in that build. The reading is strict, as -DNMEA_NO_PROBLEMS has it, and the errors are
   terse: kind, address and wire field (bad fields: out_of_range). */

#ifdef NMEA_SMALL_READER

/* The field types the small reader reads (the generator writes them: field_types.py c_small). */
enum {
    SMALL_INTEGER, /* (those before SMALL_ENUM: digits with a point) */
    SMALL_DECIMAL,
    SMALL_TIME,
    SMALL_DATE,
    SMALL_ENUM,
    SMALL_LITERAL,
    SMALL_CHAR,
    SMALL_HEX,
    SMALL_LATITUDE, /* (from here on an empty field is more than no value) */
    SMALL_LONGITUDE,
    SMALL_KEYWORD,
    SMALL_TEXT
};

/* small_layout.flags: a variant (not its sentence's main layout). */
#define SMALL_VARIANT 1

/* A layout: its fields are descriptors in SMALL_FIELDS, two bytes each (type | arg << 4, the
   offset of the member), in wire order: those before the group, the required ones after it, the
   optional trailing ones, then those of a group entry. Offsets and sizes are bytes (the
   generator checks that a sentence struct holds fewer than 256). */
typedef struct {
    uint32_t same_as_main;  /* a variant: bit n set when it reads wire field n as its main layout does */
    uint8_t fields;         /* its first descriptor */
    uint8_t before;         /* descriptors before the group (the required ones, without a group) */
    uint8_t after;          /* required descriptors after the group */
    uint8_t optional;       /* optional trailing descriptors */
    uint8_t fixed;          /* required wire fields besides the group */
    uint8_t most;           /* without a group: wire fields at most; with one: optional wire fields at most */
    uint8_t size;           /* of its struct */
    uint8_t checksum;       /* offset of its nmea_checksum_style (its talker is at 0) */
    uint8_t optional_count; /* offset of its uint8_t optional_count, 0: none */
    uint8_t flags;
    uint8_t entry_fields;   /* its group: descriptors of an entry (0: no group), */
    uint8_t width;          /* wire fields of an entry, */
    uint8_t min, max;       /* entries, */
    uint8_t entries;        /* offset of its nmea_entries, */
    uint8_t count;          /* of their uint8_t count (0: always `max` entries) */
} small_layout;

/* A lookup table: `count` codes of `width` characters (a shorter one ends with NUL bytes), each
   the value of its index. */
typedef struct {
    const char *codes;
    uint8_t count;
    uint8_t width;
    uint8_t min_len;
    uint8_t code_class; /* nmea_code_class */
} small_enum;

/* A range: min * 10^-(scales >> 4) to max * 10^-(scales & 15); a bound the field lacks is
   INT32_MIN or INT32_MAX, which no number of 9 digits reaches. */
typedef struct {
    int32_t min;
    int32_t max;
    uint8_t scales;
} small_range;

/* The generated tables (sizes from the top of nmea.c). SMALL_SENTENCES: per standard sentence
   (its id in SMALL_IDS, SMALL_ID_WIDTH characters padded with NUL bytes), its first layout
   (nmea_sentence_id) and how many it has. */
static const small_layout SMALL_LAYOUTS[NMEA_SENTENCE_COUNT - 1];
static const uint8_t SMALL_FIELDS[SMALL_FIELD_BYTES];
static const char SMALL_IDS[SMALL_SENTENCE_COUNT * SMALL_ID_WIDTH + 1];
static const uint8_t SMALL_SENTENCES[SMALL_SENTENCE_COUNT][2];
static const small_range SMALL_RANGES[SMALL_RANGE_COUNT];
static const small_enum SMALL_ENUMS[SMALL_ENUM_COUNT];
#if defined(SMALL_READS_LITERAL) || defined(SMALL_READS_KEYWORD) /* what literals and keywords read */
static const char *const SMALL_WORDS[SMALL_WORD_COUNT];
#endif

/* nmea_error.kind as nmea_parse_ex hands it to small_parse: require a checksum. */
#define SMALL_REQUIRE_CHECKSUM ((nmea_error_kind)0x7F)

/* The reading of a line: the next field, the end of the fields and of the last field read, the
   wire index of the last field read, the address (for errors). */
typedef struct {
    const char *next;
    const char *end;
    const char *last_end;
    const char *address;
    uint16_t address_len;
    uint16_t index;
    nmea_error *err;
} small_cursor;

/* An error of kind `kind` at wire field `field` (0: none), in the error small_parse zeroed first:
   a leaf (no frame below the readers'). */
static bool small_fail(small_cursor *c, nmea_error_kind kind, unsigned field)
{
    nmea_error *err = c->err;
    err->kind = kind;
    err->field = field;
    err->out_of_range = false;
    err->has_address = c->address_len > 0;
    err->address = text_span(c->address, c->address + c->address_len);
    return false;
}

/* The next field's text. */
static nmea_text small_next(small_cursor *c)
{
    const char *p = c->next, *q = p;
    while (q < c->end && *q != ',')
        q++;
    c->index++;
    c->last_end = q;
    c->next = q < c->end ? q + 1 : q;
    return text_span(p, q);
}

/* The digits of a field: [+-]digits[.digits], at most 9 before and 9 after the point. */
typedef struct {
    uint32_t whole;  /* the digits before the point, as a number */
    uint32_t frac;   /* after it */
    uint8_t whole_n; /* how many */
    uint8_t frac_n;
    char sign;       /* '+', '-' or 0 */
    bool point;
} small_digits;

static bool small_scan(nmea_text t, small_digits *d)
{
    const char *p = t.ptr, *end = t.ptr + t.len;
    uint32_t *value = &d->whole;
    uint8_t *n = &d->whole_n;
    memset(d, 0, sizeof *d);
    if (p < end && (*p == '+' || *p == '-'))
        d->sign = *p++;
    for (; p < end; p++) {
        if (*p == '.' && !d->point) {
            d->point = true;
            value = &d->frac;
            n = &d->frac_n;
        } else if (is_digit(*p) && *n < 9) {
            *value = *value * 10 + (uint32_t)(*p - '0');
            ++*n;
        } else {
            return false;
        }
    }
    return true;
}

static uint32_t small_pow10(unsigned k)
{
    uint32_t p = 1;
    while (k--)
        p *= 10;
    return p;
}

/* Whether value * 10^-scale is at most bound * 10^-bound_scale (-1: at least). */
static bool small_within(int64_t value, unsigned scale, int64_t bound, unsigned bound_scale, int sign)
{
    int64_t a = value * small_pow10(bound_scale), b = bound * small_pow10(scale);
    return sign > 0 ? a <= b : a >= b;
}

/* Whether a code of a table with class `code_class` may be `t` though the table does not know it. */
static bool small_code_like(const small_enum *e, nmea_text t)
{
    size_t i;
    if (e->code_class == NMEA_CODES_CLOSED || t.len < e->min_len || t.len > e->width)
        return false;
    for (i = 0; i < t.len; i++)
        if (e->code_class == NMEA_CODES_DIGITS ? !is_digit(t.ptr[i])
            : e->code_class == NMEA_CODES_LETTERS ? !is_letter(t.ptr[i]) : !is_alnum(t.ptr[i]))
            return false;
    return true;
}

/* The value of code `t` in table `e`, or NMEA_UNKNOWN_CODE. */
static int small_code(const small_enum *e, nmea_text t)
{
    int i;
    size_t k;
    for (i = 0; i < e->count; i++) {
        const char *code = e->codes + i * e->width;
        for (k = 0; k < t.len && k < e->width && code[k] && code[k] == t.ptr[k]; k++)
            continue;
        if (k == t.len && (k == e->width || code[k] == 0))
            return i;
    }
    return NMEA_UNKNOWN_CODE;
}

/* Reads the field of descriptor `d` into `out`, a value of its type; false with the error. */
static bool small_field(small_cursor *c, const uint8_t *d, void *out)
{
    unsigned type = d[0] & 15, arg = d[0] >> 4;
    nmea_text t = small_next(c);
    small_digits n;

    if (!t.len && type < SMALL_LATITUDE) /* no value: the struct is zeroed */
        return true;
    if (t.len && (type < SMALL_ENUM || type == SMALL_LATITUDE || type == SMALL_LONGITUDE) && !small_scan(t, &n))
        return small_fail(c, NMEA_ERR_BAD_FIELD, c->index); /* (the one scan: inlined) */
    switch (type) {
#if defined(SMALL_READS_INTEGER) || defined(SMALL_READS_DECIMAL)
    case SMALL_INTEGER:
    case SMALL_DECIMAL: {
        const small_range *r = &SMALL_RANGES[arg];
        nmea_number *x = (nmea_number *)out;
        int32_t v;
        if (n.whole_n + n.frac_n == 0 || n.whole_n + n.frac_n > NMEA_NUMBER_DIGITS ||
            (type == SMALL_INTEGER && n.point))
            break;
        v = (int32_t)(n.whole * small_pow10(n.frac_n) + n.frac);
        x->digits = v;
        x->scale = n.frac_n;
        x->width = n.whole_n;
        x->sign = n.sign;
        x->point = n.point;
        x->present = true;
        if (n.sign == '-')
            v = -v;
        if (small_within(v, n.frac_n, r->min, r->scales >> 4, -1) && small_within(v, n.frac_n, r->max, r->scales & 15, 1))
            return true;
        small_fail(c, NMEA_ERR_BAD_FIELD, c->index);
        c->err->out_of_range = true;
        return false;
    }
#endif
#ifdef SMALL_READS_TIME
    case SMALL_TIME: {
        nmea_time *x = (nmea_time *)out;
        if (n.sign || n.whole_n != 6)
            break;
        x->hour = (uint8_t)(n.whole / 10000);
        x->minute = (uint8_t)(n.whole / 100 % 100);
        x->second = (uint8_t)(n.whole % 100);
        if (x->hour > 23 || x->minute > 59 || x->second > 60)
            break;
        x->fraction = n.frac;
        x->fraction_digits = n.frac_n;
        x->point = n.point;
        x->present = true;
        return true;
    }
#endif
#ifdef SMALL_READS_DATE
    case SMALL_DATE: {
        nmea_date *x = (nmea_date *)out;
        if (n.sign || n.point || n.whole_n != 6)
            break;
        x->day = (uint8_t)(n.whole / 10000);
        x->month = (uint8_t)(n.whole / 100 % 100);
        x->year = (uint8_t)(n.whole % 100);
        if (x->day < 1 || x->day > 31 || x->month < 1 || x->month > 12)
            break;
        x->present = true;
        return true;
    }
#endif
#if defined(SMALL_READS_LATITUDE) || defined(SMALL_READS_LONGITUDE)
    case SMALL_LATITUDE:
    case SMALL_LONGITUDE: {
        /* a value and a hemisphere, both empty or both set; the value is refused before the
           hemisphere is read */
        nmea_coordinate *x = (nmea_coordinate *)out;
        nmea_text h;
        unsigned lon = type == SMALL_LONGITUDE;
        const char *hemispheres = lon ? "EW" : "NS";
        uint32_t minutes;
        if (t.len) {
            if (n.sign || n.whole_n < 2 || n.whole_n > 4 + lon ||
                n.frac_n > NMEA_NUMBER_DIGITS - 2 || n.whole / 100 > (lon ? 180u : 90u))
                break;
            minutes = n.whole % 100 * small_pow10(n.frac_n) + n.frac;
            if (minutes > 60 * small_pow10(n.frac_n))
                break;
            x->degrees = (uint16_t)(n.whole / 100);
            x->degree_digits = (uint8_t)(n.whole_n - 2);
            x->minutes.digits = (nmea_digits)minutes;
            x->minutes.scale = n.frac_n;
            x->minutes.width = 2;
            x->minutes.point = n.point;
            x->minutes.present = true;
            x->present = true;
        }
        h = small_next(c);
        if (!t.len)
            return h.len ? small_fail(c, NMEA_ERR_BAD_FIELD, c->index - 1u) : true;
        if (h.len != 1 || (h.ptr[0] != hemispheres[0] && h.ptr[0] != hemispheres[1])) {
            x->present = false;
            break;
        }
        x->hemisphere = h.ptr[0];
        return true;
    }
#endif
#ifdef SMALL_READS_ENUM
    case SMALL_ENUM: {
        nmea_enum *x = (nmea_enum *)out;
        const small_enum *e = &SMALL_ENUMS[arg];
        int value = small_code(e, t);
        size_t i;

        if (value == NMEA_UNKNOWN_CODE && !small_code_like(e, t))
            break;
        x->value = value;
        for (i = 0; i < t.len; i++) /* t.len <= the table's width <= NMEA_CODE_MAX */
            x->code[i] = t.ptr[i];
        x->code[t.len] = 0;
        x->present = true;
        return true;
    }
#endif
#if defined(SMALL_READS_LITERAL) || defined(SMALL_READS_KEYWORD)
    case SMALL_LITERAL:
    case SMALL_KEYWORD: { /* its word (a literal's field here is not empty) */
        const char *word = SMALL_WORDS[arg];
        size_t i;
        for (i = 0; i < t.len && word[i] && word[i] == t.ptr[i]; i++)
            continue;
        if (i < t.len || word[i])
            break;
        if (type == SMALL_LITERAL) /* (a keyword stores nothing) */
            *(bool *)out = true;
        return true;
    }
#endif
#ifdef SMALL_READS_CHAR
    case SMALL_CHAR:
        if (t.len > 1)
            break;
        *(char *)out = t.ptr[0];
        return true;
#endif
#ifdef SMALL_READS_HEX
    case SMALL_HEX: {
        nmea_hex *x = (nmea_hex *)out;
        bool lower = false, upper = false;
        size_t i;
        uint64_t v = 0;
        if (t.len > 16)
            break;
        for (i = 0; i < t.len; i++) {
            int digit = hex_value(t.ptr[i]);
            if (digit < 0)
                break;
            lower = lower || t.ptr[i] >= 'a';
            upper = upper || (t.ptr[i] >= 'A' && t.ptr[i] <= 'F');
            v = v << 4 | (unsigned)digit;
        }
        if (i < t.len || (lower && upper))
            break;
        x->value = v;
        x->digits = (uint8_t)t.len;
        x->lower = lower;
        x->present = true;
        return true;
    }
#endif
#ifdef SMALL_READS_TEXT
    case SMALL_TEXT: /* its range's max is its longest length */
        if ((int32_t)t.len > SMALL_RANGES[arg].max)
            break;
        *(nmea_text *)out = t;
        return true;
#endif
    }
    return small_fail(c, NMEA_ERR_BAD_FIELD, c->index);
}

/* Reads `n` descriptors from `d` into the struct at `s` (group: every value into `s` itself). */
static bool small_fields(small_cursor *c, const uint8_t *d, size_t n, char *s, bool group)
{
    for (; n > 0; n--, d += 2)
        if (!small_field(c, d, s + (group ? 0 : d[1])))
            return false;
    return true;
}

/* The wire fields a descriptor spans: a latitude or longitude and its hemisphere two. */
static unsigned small_width(const uint8_t *d)
{
    return (d[0] & 15) == SMALL_LATITUDE || (d[0] & 15) == SMALL_LONGITUDE ? 2 : 1;
}

/* Reads the `count` wire fields from c->next into `s`, a struct of layout `l`. */
static bool small_layout_read(small_cursor *c, const small_layout *l, char *s, unsigned count, uint8_t checksum)
{
    const uint8_t *d = SMALL_FIELDS + 2 * l->fields;
    unsigned repeats = 0, optional, present = 0, wire;
    const char *start;
    nmea_entries *entries;

    if (l->entry_fields) {
        unsigned need = l->fixed + l->min * l->width, rest;
        if (count < need)
            return small_fail(c, NMEA_ERR_TOO_FEW_FIELDS, 0);
        rest = count - l->fixed;
        repeats = rest / l->width < l->max ? rest / l->width : l->max;
        optional = rest - repeats * l->width;
        if (optional > l->most)
            return small_fail(c, repeats == l->max ? NMEA_ERR_TOO_MANY_FIELDS : NMEA_ERR_TOO_FEW_FIELDS, 0);
    } else {
        if (count < l->fixed)
            return small_fail(c, NMEA_ERR_TOO_FEW_FIELDS, 0);
        if (count > l->most)
            return small_fail(c, NMEA_ERR_TOO_MANY_FIELDS, 0);
        optional = count - l->fixed;
    }
    for (wire = 0; present < l->optional; present++) { /* the optional fields whose wire fields are all there */
        wire += small_width(d + 2 * (l->before + l->after + present));
        if (wire > optional)
            break;
    }
    memset(s, 0, l->size);
    *(nmea_text *)s = text_span(c->address, c->address + 2);
    *(nmea_checksum_style *)(s + l->checksum) = (nmea_checksum_style)checksum;
    if (l->optional_count)
        s[l->optional_count] = (char)present;
    if (!small_fields(c, d, l->before, s, false))
        return false;
    if (l->entry_fields) { /* the entries stay on the wire, each read (into their nmea_entries) to check it */
        start = c->next;
        entries = (nmea_entries *)(s + l->entries);
        for (wire = 0; wire < repeats; wire++)
            if (!small_fields(c, d + 2 * (l->before + l->after + l->optional), l->entry_fields, (char *)entries, true))
                return false;
        memset(entries, 0, sizeof *entries);
        entries->wire = text_span(start, repeats ? c->last_end : start);
        if (l->count)
            s[l->count] = (char)repeats;
    }
    return small_fields(c, d + 2 * l->before, l->after + present, s, false);
}

/* nmea_parse (`require_checksum` false) and nmea_parse_ex: four arguments, so that nmea_parse's
   call is a jump (no frame of its own). */
static bool small_parse(nmea_sentence *out, const char *line, size_t len, nmea_error *err)
{
    small_cursor c;
    bool require_checksum = err->kind == SMALL_REQUIRE_CHECKSUM;
    const char *p, *end, *star = NULL, *comma = NULL;
    unsigned sum = 0, commas = 0, i, n, first, last, fallback, refused = 0, at;
    int high, low;
    bool named, again = false;
    nmea_checksum_style checksum = NMEA_CHECKSUM_NONE;

    memset(err, 0, sizeof *err);
    c.err = err;
    c.address = line;
    c.address_len = 0;
    out->problems = NULL;
    if (line && len && line[len - 1] == '\n') /* one trailing LF or CR LF */
        len -= len > 1 && line[len - 2] == '\r' ? 2 : 1;
    if (len > NMEA_MAX_LINE)
        return small_fail(&c, NMEA_ERR_TOO_LONG, 0);
    if (len == 0 || (line[0] != '$' && line[0] != '!'))
        return small_fail(&c, NMEA_ERR_NOT_A_SENTENCE, 0);
    /* one pass: the body's checksum and commas up to a '*' or a byte that is not printable, the
       checksum's printable bytes after a '*' */
    end = line + len;
    for (p = line + 1; p < end && is_printable(*p) && *p != '*'; p++) {
        sum ^= (unsigned char)*p;
        if (*p == ',' && !commas++)
            comma = p;
    }
    if (p < end && *p == '*')
        for (star = p++; p < end && is_printable(*p); p++)
            continue;
    if (p < end)
        return small_fail(&c, NMEA_ERR_NOT_A_SENTENCE, 0);
    end = star ? star : end;
    c.address = line + 1;
    p = comma ? comma : end;
    named = p > c.address;
    for (c.next = c.address; c.next < p; c.next++)
        named = named && is_alnum(*c.next);
    c.address_len = named ? (uint16_t)(p - c.address) : 0;
    if (star && star + 1 == line + len) {
        checksum = NMEA_CHECKSUM_EMPTY;
    } else if (star) { /* two hex digits of one letter case */
        bool lower = false, upper = false;
        high = low = -1;
        if (star + 3 == line + len) {
            high = hex_value(star[1]);
            low = hex_value(star[2]);
            lower = star[1] >= 'a' || star[2] >= 'a';
            upper = (star[1] >= 'A' && star[1] <= 'F') || (star[2] >= 'A' && star[2] <= 'F');
        }
        if (high < 0 || low < 0 || (lower && upper))
            return small_fail(&c, NMEA_ERR_BAD_CHECKSUM, 0);
        if ((unsigned)(high * 16 + low) != sum)
            return small_fail(&c, NMEA_ERR_CHECKSUM_MISMATCH, 0);
        checksum = lower ? NMEA_CHECKSUM_LOWER : NMEA_CHECKSUM_UPPER;
    }
    if (!named)
        return small_fail(&c, NMEA_ERR_NOT_A_SENTENCE, 0);
    if (require_checksum && (checksum == NMEA_CHECKSUM_NONE || checksum == NMEA_CHECKSUM_EMPTY))
        return small_fail(&c, NMEA_ERR_MISSING_CHECKSUM, 0);
    c.end = end;
    /* a standard sentence of the build: $, a talker, an id of SMALL_IDS */
    i = SMALL_SENTENCE_COUNT;
    if (line[0] == '$' && c.address[0] != 'P' && (c.address_len == 5 || c.address_len == 6))
        for (i = 0; i < SMALL_SENTENCE_COUNT; i++) {
            const char *id = SMALL_IDS + i * SMALL_ID_WIDTH;
            for (n = 0; n < SMALL_ID_WIDTH && id[n] && n + 2u < c.address_len && id[n] == c.address[n + 2]; n++)
                continue;
            if (n + 2u == c.address_len && (n == SMALL_ID_WIDTH || id[n] == 0))
                break;
        }
    if (i == SMALL_SENTENCE_COUNT) {
        out->id = NMEA_SENTENCE_GENERIC;
        out->as.generic.start = text_span(line, line + 1);
        out->as.generic.address = text_span(c.address, c.address + c.address_len);
        out->as.generic.fields = commas ? text_span(comma + 1, end) : text_span(end, end);
        out->as.generic.field_count = commas;
        out->as.generic.checksum = checksum;
        return true;
    }
    /* the first of the sentence's layouts that reads the line (a variant passed over when its
       main layout refused a field it reads the same way); when none does, the error of the first
       that refused a field, else of the first (kept as 2 * its index + whether a bad field) */
    first = SMALL_SENTENCES[i][0];
    n = SMALL_SENTENCES[i][1];
    fallback = 2 * n;
    last = n;
    for (i = 0;; i++) {
        const small_layout *l;
        if (i == n) {
            i = fallback / 2;
            if (i == last)
                return false;
            again = true;
        }
        l = &SMALL_LAYOUTS[first + i - 1];
        if (!again && refused < 32 && (l->same_as_main >> refused & 1))
            continue;
        c.next = comma ? comma + 1 : end;
        c.index = 0;
        out->id = (nmea_sentence_id)(first + i);
        if (small_layout_read(&c, l, (char *)&out->as, commas, (uint8_t)checksum))
            return true;
        if (again)
            return false;
        last = i;
        at = 2 * i + (err->kind == NMEA_ERR_BAD_FIELD);
        if (!(l->flags & SMALL_VARIANT))
            refused = err->kind == NMEA_ERR_BAD_FIELD ? err->field : 0;
        if (fallback == 2 * n || (!(fallback & 1) && (at & 1)))
            fallback = at;
    }
}

#endif /* NMEA_SMALL_READER */
