/* Fixes assembled across sentences (nmea_fix_assembler; docs/fixes.md): the rules of the Python
   runtime's fixes.py, the same fixes of the same lines (generated/vectors/fixes.jsonl). Which
   field of which layout carries which fact is the generated table FIX (spec/fix.yaml): each entry
   points at the field's descriptor, read here as read_with reads it. No heap: a fix holds up to
   the NMEA_FIX_MAX_* satellites and sentences, and counts those it leaves out. Left out by
   -DNMEA_NO_FIXES; nmea_fix_to_json also by -DNMEA_NO_JSON. */

#ifndef NMEA_NO_FIXES
/* A field of a layout that carries a fact. */
typedef struct {
    uint8_t fact;               /* nmea_fact */
    bool in_group;              /* a field of the entries of the layout's group */
    const layout_field *field;  /* its descriptor in the layout (or its group) */
    double scale;               /* from the field's unit to the fact's */
    const char *const *values;  /* an enum the fact maps (`from`): the fact's value of each code
                                   (NULL: none); NULL: the fact keeps the enum's value ids */
} fix_field;

typedef struct {
    const fix_field *fields; /* in wire order */
    uint8_t count;           /* 0: the layout carries no fact */
} layout_facts;

/* Texts in arrays, not string literals, here and below: a firmware that does not assemble fixes
   links none of them (-fdata-sections drops a table, not a pooled literal). */
typedef struct {
    char talker[3];
    char system[12];
} fix_talker;

typedef struct {
    char system[12];
    uint16_t first;
    uint16_t last;
} fix_id_range;

/* What spec/fix.yaml says, as the generated code after the runtime defines it. */
typedef struct {
    const layout_facts *layouts; /* by nmea_sentence_id */
    const fix_talker *talkers;
    size_t talker_count;
    const fix_id_range *ids;
    size_t id_count;
    char combined_talker[3]; /* "": none */
} fix_tables;

static const fix_tables FIX;

/* The value ids the rules name. */
static const char FIX_NOT_VALID[] = "not_valid", FIX_INVALID[] = "invalid", FIX_USED[] = "used",
                  FIX_UNKNOWN[] = "unknown", FIX_NO_FIX[] = "no_fix", FIX_2D[] = "fix_2d", FIX_3D[] = "fix_3d";

/* A fact as a sentence gives it: a number (a time in ms, a date in days) or a value id. */
typedef struct {
    bool known;
    bool whole; /* an integer field's number, in the fact's unit: written without a point */
    double number;
    const char *id;
} fact_value;

/* The facts a fix keeps as the sentences give them, under their own names (the later sentence of
   an epoch wins), in the order of Fix.to_dict. */
static const struct {
    char name[18];
    uint8_t fact;
    uint16_t offset;
    bool is_id; /* a const char * member, else a double */
} FIX_SCALARS[] = {
    {"latitude", NMEA_FACT_LATITUDE, offsetof(nmea_gnss_fix, latitude), false},
    {"longitude", NMEA_FACT_LONGITUDE, offsetof(nmea_gnss_fix, longitude), false},
    {"altitude_msl", NMEA_FACT_ALTITUDE_MSL, offsetof(nmea_gnss_fix, altitude_msl), false},
    {"geoid_separation", NMEA_FACT_GEOID_SEPARATION, offsetof(nmea_gnss_fix, geoid_separation), false},
    {"altitude_hae", NMEA_FACT_ALTITUDE_HAE, offsetof(nmea_gnss_fix, altitude_hae), false},
    {"speed", NMEA_FACT_SPEED, offsetof(nmea_gnss_fix, speed), false},
    {"course", NMEA_FACT_COURSE, offsetof(nmea_gnss_fix, course), false},
    {"fix_quality", NMEA_FACT_FIX_QUALITY, offsetof(nmea_gnss_fix, fix_quality), true},
    {"fix_status", NMEA_FACT_FIX_STATUS, offsetof(nmea_gnss_fix, fix_status), true},
    {"pos_mode", NMEA_FACT_POS_MODE, offsetof(nmea_gnss_fix, pos_mode), true},
    {"mode", NMEA_FACT_MODE, offsetof(nmea_gnss_fix, mode), true},
    {"pdop", NMEA_FACT_PDOP, offsetof(nmea_gnss_fix, pdop), false},
    {"hdop", NMEA_FACT_HDOP, offsetof(nmea_gnss_fix, hdop), false},
    {"vdop", NMEA_FACT_VDOP, offsetof(nmea_gnss_fix, vdop), false},
    {"tdop", NMEA_FACT_TDOP, offsetof(nmea_gnss_fix, tdop), false},
    {"lat_error", NMEA_FACT_LAT_ERROR, offsetof(nmea_gnss_fix, lat_error), false},
    {"lon_error", NMEA_FACT_LON_ERROR, offsetof(nmea_gnss_fix, lon_error), false},
    {"alt_error", NMEA_FACT_ALT_ERROR, offsetof(nmea_gnss_fix, alt_error), false},
    {"horizontal_error", NMEA_FACT_HORIZONTAL_ERROR, offsetof(nmea_gnss_fix, horizontal_error), false},
};

#define FIX_SCALAR_COUNT (sizeof FIX_SCALARS / sizeof FIX_SCALARS[0])

static uint64_t fact_bit(unsigned fact) { return (uint64_t)1 << fact; }

bool nmea_fix_has(const nmea_gnss_fix *fix, nmea_fact fact) { return (fix->known & fact_bit(fact)) != 0; }

bool nmea_fix_is_whole(const nmea_gnss_fix *fix, nmea_fact fact) { return (fix->whole & fact_bit(fact)) != 0; }

static bool same_text(const char *a, const char *b) { return a == b || (a && b && strcmp(a, b) == 0); }

size_t nmea_fix_in_view_count(const nmea_gnss_fix *fix)
{
    size_t i, j, n = 0;
    for (i = 0; i < fix->in_view_len; i++) {
        const nmea_gnss_satellite *s = &fix->in_view[i];
        for (j = 0; j < i; j++)
            if (fix->in_view[j].id == s->id && same_text(fix->in_view[j].system, s->system))
                break;
        n += j == i;
    }
    return n;
}

/* Signed degrees as Python's and Rust's: the degrees plus the minutes' double divided by 60. */
static double coordinate_degrees(const nmea_coordinate *c)
{
    double value = (double)c->degrees + nmea_to_double(&c->minutes) / 60.0;
    return c->hemisphere == 'S' || c->hemisphere == 'W' ? -value : value;
}

/* The value id of an enum_chars field (GNS's mode per system): the first that is not not_valid,
   else the first known one. */
static const char *first_mode(const nmea_enum_def *def, nmea_text t)
{
    const char *first = NULL;
    size_t i;
    for (i = 0; i < t.len; i++) {
        int v = nmea_enum_lookup(def, t.ptr[i]);
        if (v == NMEA_UNKNOWN_CODE)
            continue;
        if (strcmp(def->codes[v].id, FIX_NOT_VALID) != 0)
            return def->codes[v].id;
        if (!first)
            first = def->codes[v].id;
    }
    return first;
}

/* The fact of field `ff` whose value (of its field type) is at `at`. */
static fact_value fact_of(const fix_field *ff, const void *at)
{
    const layout_field *f = ff->field;
    fact_value out = {false, false, 0, NULL};
    switch ((field_type)f->type) {
    case FIELD_INTEGER:
    case FIELD_DECIMAL: {
        const nmea_number *n = (const nmea_number *)at;
        out.known = n->present;
        out.number = nmea_to_double(n);
        out.whole = f->type == FIELD_INTEGER && ff->scale == 1.0; /* a decimal is a double, point or not */
        if (ff->scale != 1.0)
            out.number *= ff->scale;
        break;
    }
    case FIELD_TIME: { /* a leap second has no time of day (as Python's datetime) */
        const nmea_time *t = (const nmea_time *)at;
        out.known = t->present && t->second <= 59;
        out.number = out.known ? nmea_time_ms(t) : 0;
        break;
    }
    case FIELD_DATE: {
        const nmea_date *d = (const nmea_date *)at;
        int32_t days = 0;
        out.known = d->present && nmea_date_days(d, &days);
        out.number = days;
        break;
    }
    case FIELD_LATITUDE:
    case FIELD_LONGITUDE: {
        const nmea_coordinate *c = (const nmea_coordinate *)at;
        out.known = c->present;
        out.number = out.known ? coordinate_degrees(c) : 0;
        break;
    }
    case FIELD_ENUM: { /* an unknown code gives no fact */
        const nmea_enum *e = (const nmea_enum *)at;
        if (e->present && e->value != NMEA_UNKNOWN_CODE)
            out.id = ff->values ? ff->values[e->value] : table_of(f)->codes[e->value].id;
        out.known = out.id != NULL;
        break;
    }
    case FIELD_ENUM_CHARS:
        out.id = first_mode(table_of(f), *(const nmea_text *)at);
        out.known = out.id != NULL;
        break;
    default:
        break;
    }
    return out;
}

/* Room for a group entry of the layouts with facts (at most 8 fields, each no larger than a
   field_value: the generated code asserts it of each). */
#define FIX_ENTRY_FIELDS 8

/* The facts of entry `i` of the group of `s`, a sentence of layout `l`, into `facts`. */
static void entry_facts(const layout *l, const layout_facts *fl, const nmea_sentence *s, size_t i,
                        fact_value *facts)
{
    field_value entry[FIX_ENTRY_FIELDS];
    bool read = l->group->entry_size <= sizeof entry && entry_of(l, &s->as, i, entry);
    size_t k;

    for (k = 0; k < fl->count; k++)
        if (fl->fields[k].in_group)
            facts[fl->fields[k].fact] = read ? fact_of(&fl->fields[k], (const char *)entry + fl->fields[k].field->offset)
                                             : (fact_value){false, false, 0, NULL};
}

static void copy_talker(char to[3], const char *from, size_t len)
{
    to[0] = len > 0 ? from[0] : 0;
    to[1] = len > 1 ? from[1] : 0;
    to[2] = 0;
}

/* The GNSS of a satellite id under a talker (of several systems: by the id's range), or NULL. */
static const char *system_of(const char *talker, int32_t id)
{
    size_t i;
    for (i = 0; i < FIX.talker_count; i++)
        if (strcmp(FIX.talkers[i].talker, talker) == 0)
            return FIX.talkers[i].system;
    for (i = 0; i < FIX.id_count; i++)
        if (id >= FIX.ids[i].first && id <= FIX.ids[i].last)
            return FIX.ids[i].system;
    return NULL;
}

static void add_used(nmea_gnss_fix *fix, const char *system, int32_t id)
{
    size_t i;
    for (i = 0; i < fix->used_count; i++)
        if (fix->used[i].id == id && strcmp(fix->used[i].system, system) == 0)
            return;
    if (fix->used_count == NMEA_FIX_MAX_USED) {
        fix->overflow++;
        return;
    }
    fix->used[fix->used_count].system = system;
    fix->used[fix->used_count++].id = id;
}

static bool same_set(const nmea_gnss_satellite *s, const char *talker, const char *signal)
{
    return strcmp(s->talker, talker) == 0 && same_text(s->signal, signal);
}

/* Removes the satellites of a set (talker and signal) from `sats`, keeping the others' order. */
static uint16_t drop_set(nmea_gnss_satellite *sats, uint16_t len, const char *talker, const char *signal)
{
    uint16_t i, kept = 0;
    for (i = 0; i < len; i++)
        if (!same_set(&sats[i], talker, signal))
            sats[kept++] = sats[i];
    return kept;
}

static void drop_progress(nmea_fix_assembler *a, size_t at)
{
    a->sets[at] = a->sets[--a->set_count];
}

/* A satellite in view of a group entry's facts. */
static nmea_gnss_satellite satellite_of(const fact_value *facts, const char *talker, const char *signal)
{
    nmea_gnss_satellite s;
    const fact_value *used = &facts[NMEA_FACT_SATELLITE_USED];
    memset(&s, 0, sizeof s);
    s.id = (int32_t)facts[NMEA_FACT_SATELLITE].number;
    s.system = system_of(talker, s.id);
    s.signal = signal;
    copy_talker(s.talker, talker, strlen(talker));
    s.has_elevation = facts[NMEA_FACT_ELEVATION].known;
    s.elevation = (int16_t)facts[NMEA_FACT_ELEVATION].number;
    s.has_azimuth = facts[NMEA_FACT_AZIMUTH].known;
    s.azimuth = (int16_t)facts[NMEA_FACT_AZIMUTH].number;
    s.has_snr = facts[NMEA_FACT_SNR].known;
    s.snr = (int16_t)facts[NMEA_FACT_SNR].number;
    s.used = (int8_t)(used->known ? strcmp(used->id, FIX_USED) == 0 : -1);
    return s;
}

/* Collects a part of a set of satellites in view; a set is the epoch's when its last part arrives
   (a report in one sentence, PUBX,03, is a set of one); a set missing a part is dropped. */
static void satellites_in_view(nmea_fix_assembler *a, const layout *l, const layout_facts *fl, const nmea_sentence *s,
                               fact_value *facts, const char *talker)
{
    const char *signal = facts[NMEA_FACT_SIGNAL].known ? facts[NMEA_FACT_SIGNAL].id : NULL;
    double size = facts[NMEA_FACT_SET_SIZE].known ? facts[NMEA_FACT_SET_SIZE].number : 0;
    double index = facts[NMEA_FACT_SET_INDEX].known ? facts[NMEA_FACT_SET_INDEX].number : 0;
    nmea_gnss_fix *fix = &a->fix;
    size_t at, i, n = entries_of(l->group, &s->as);

    size = size != 0 ? size : 1; /* Python's `or 1`: none or 0 is a set of one */
    index = index != 0 ? index : 1;
    for (at = 0; at < a->set_count; at++)
        if (strcmp(a->sets[at].talker, talker) == 0 && same_text(a->sets[at].signal, signal))
            break;
    if (at < a->set_count && (index == 1 || a->sets[at].index != index - 1)) {
        a->pending_len = drop_set(a->pending, a->pending_len, talker, signal);
        drop_progress(a, at);
        at = a->set_count;
        if (index != 1)
            return; /* a part missing: the set is incomplete */
    }
    if (at == a->set_count) {
        if (index != 1)
            return;
        if (a->set_count == NMEA_FIX_MAX_SETS) {
            fix->overflow++;
            return;
        }
        copy_talker(a->sets[at].talker, talker, strlen(talker));
        a->sets[at].signal = signal;
        a->set_count++;
    }
    a->sets[at].index = index < 255 ? (uint8_t)index : 255;
    for (i = 0; i < n; i++) {
        entry_facts(l, fl, s, i, facts);
        if (!facts[NMEA_FACT_SATELLITE].known)
            continue;
        if (a->pending_len == NMEA_FIX_MAX_SATELLITES)
            fix->overflow++;
        else
            a->pending[a->pending_len++] = satellite_of(facts, talker, signal);
    }
    if (index != size)
        return;
    fix->in_view_len = drop_set(fix->in_view, fix->in_view_len, talker, signal);
    for (i = 0; i < a->pending_len; i++) {
        if (!same_set(&a->pending[i], talker, signal))
            continue;
        if (fix->in_view_len == NMEA_FIX_MAX_SATELLITES)
            fix->overflow++;
        else
            fix->in_view[fix->in_view_len++] = a->pending[i];
    }
    a->pending_len = drop_set(a->pending, a->pending_len, talker, signal);
    drop_progress(a, at);
}

/* The mode where no sentence of the epoch gives it: no fix when a sentence calls the position
   invalid, 3D with an altitude, 2D without; none without any of position, quality and status. */
static const char *inferred_mode(const nmea_gnss_fix *fix)
{
    bool position = nmea_fix_has(fix, NMEA_FACT_LATITUDE);
    if (!position && !nmea_fix_has(fix, NMEA_FACT_FIX_QUALITY) && !nmea_fix_has(fix, NMEA_FACT_FIX_STATUS))
        return NULL;
    if (same_text(fix->fix_status, FIX_INVALID) || same_text(fix->fix_quality, FIX_INVALID) ||
        same_text(fix->pos_mode, FIX_NOT_VALID) || !position)
        return FIX_NO_FIX;
    return nmea_fix_has(fix, NMEA_FACT_ALTITUDE_MSL) || nmea_fix_has(fix, NMEA_FACT_ALTITUDE_HAE) ? FIX_3D : FIX_2D;
}

/* Closes the epoch under way into `out`. */
static void finish_epoch(nmea_fix_assembler *a, nmea_gnss_fix *out)
{
    nmea_gnss_fix *fix = &a->fix;
    bool has_time = nmea_fix_has(fix, NMEA_FACT_TIME);
    size_t i;

    if (!nmea_fix_has(fix, NMEA_FACT_DATE) && a->has_last_date && has_time) {
        bool rolled_over = a->last_has_time && fix->time_ms < a->last_time;
        fix->date_days = a->last_date + rolled_over;
        fix->known |= fact_bit(NMEA_FACT_DATE);
    }
    if (nmea_fix_has(fix, NMEA_FACT_DATE)) {
        a->has_last_date = true;
        a->last_date = fix->date_days;
        a->last_has_time = has_time;
        a->last_time = fix->time_ms;
    }
    if (a->count_count) {
        int32_t sum = 0;
        for (i = 0; i < a->count_count; i++)
            sum += a->counts[i].count;
        for (i = 0; i < a->count_count; i++) /* a proprietary sentence's is the receiver's total */
            if (a->counts[i].talker[0] == '\0')
                sum = a->counts[i].count;
        for (i = 0; i < a->count_count; i++) /* and the combined talker's before it */
            if (same_text(a->counts[i].talker, FIX.combined_talker))
                sum = a->counts[i].count;
        fix->satellites_used = sum;
        fix->known |= fact_bit(NMEA_FACT_SATELLITES_USED);
        a->count_count = 0;
    }
    if (!nmea_fix_has(fix, NMEA_FACT_ALTITUDE_HAE) && nmea_fix_has(fix, NMEA_FACT_ALTITUDE_MSL) &&
        nmea_fix_has(fix, NMEA_FACT_GEOID_SEPARATION)) {
        fix->altitude_hae = fix->altitude_msl + fix->geoid_separation;
        fix->known |= fact_bit(NMEA_FACT_ALTITUDE_HAE);
        if (nmea_fix_is_whole(fix, NMEA_FACT_ALTITUDE_MSL) && nmea_fix_is_whole(fix, NMEA_FACT_GEOID_SEPARATION))
            fix->whole |= fact_bit(NMEA_FACT_ALTITUDE_HAE);
    }
    if (!nmea_fix_has(fix, NMEA_FACT_MODE)) {
        fix->mode = inferred_mode(fix);
        if (fix->mode)
            fix->known |= fact_bit(NMEA_FACT_MODE);
    }
    /* What the counts cover, not the whole capacity (tens of kilobytes, most of it unused) */
    memcpy(out, fix, offsetof(nmea_gnss_fix, used));
    memcpy(out->used, fix->used, fix->used_count * sizeof fix->used[0]);
    memcpy(out->in_view, fix->in_view, fix->in_view_len * sizeof fix->in_view[0]);
    memcpy(out->sentences, fix->sentences, fix->sentence_count * sizeof fix->sentences[0]);
    a->open = false;
}

/* A date of three numbers (ZDA's day, month, year). */
static bool calendar_date(const fact_value *facts, int32_t *days)
{
    return facts[NMEA_FACT_DAY].known && facts[NMEA_FACT_MONTH].known && facts[NMEA_FACT_YEAR].known &&
           facts[NMEA_FACT_YEAR].number >= 1 && facts[NMEA_FACT_YEAR].number <= 9999 &&
           facts[NMEA_FACT_MONTH].number >= 1 && facts[NMEA_FACT_MONTH].number <= 12 &&
           facts[NMEA_FACT_DAY].number >= 1 && facts[NMEA_FACT_DAY].number <= 31 &&
           nmea_days_from_civil((int32_t)facts[NMEA_FACT_YEAR].number, (int)facts[NMEA_FACT_MONTH].number,
                                (int)facts[NMEA_FACT_DAY].number, days);
}

/* Merges the facts of a sentence of layout `l` into the epoch under way. */
static void merge(nmea_fix_assembler *a, const layout *l, const layout_facts *fl, const nmea_sentence *s,
                  fact_value *facts, const char *talker)
{
    nmea_gnss_fix *fix = &a->fix;
    bool used = false, in_view = false;
    int32_t days;
    size_t i, n;

    for (i = 0; i < FIX_SCALAR_COUNT; i++) {
        const fact_value *v = &facts[FIX_SCALARS[i].fact];
        if (!v->known)
            continue;
        if (FIX_SCALARS[i].is_id)
            *(const char **)member_at(fix, FIX_SCALARS[i].offset) = v->id;
        else
            *(double *)member_at(fix, FIX_SCALARS[i].offset) = v->number;
        fix->known |= fact_bit(FIX_SCALARS[i].fact);
        fix->whole = v->whole ? fix->whole | fact_bit(FIX_SCALARS[i].fact) : fix->whole & ~fact_bit(FIX_SCALARS[i].fact);
    }
    if (facts[NMEA_FACT_SATELLITES_USED].known) {
        for (i = 0; i < a->count_count && strcmp(a->counts[i].talker, talker) != 0; i++)
            ;
        if (i < NMEA_FIX_MAX_SETS) {
            copy_talker(a->counts[i].talker, talker, strlen(talker));
            a->counts[i].count = (int32_t)facts[NMEA_FACT_SATELLITES_USED].number;
            a->count_count += i == a->count_count;
        }
    }
    if (facts[NMEA_FACT_DATE].known || calendar_date(facts, &days)) {
        fix->date_days = facts[NMEA_FACT_DATE].known ? (int32_t)facts[NMEA_FACT_DATE].number : days;
        fix->known |= fact_bit(NMEA_FACT_DATE);
    }
    for (i = 0; i < fl->count; i++) {
        used |= fl->fields[i].fact == NMEA_FACT_USED_SATELLITE;
        in_view |= fl->fields[i].fact == NMEA_FACT_SATELLITE;
    }
    if (used) {
        const char *system = facts[NMEA_FACT_USED_SYSTEM].known ? facts[NMEA_FACT_USED_SYSTEM].id : NULL;
        for (i = 0, n = entries_of(l->group, &s->as); i < n; i++) {
            int32_t id;
            entry_facts(l, fl, s, i, facts);
            if (!facts[NMEA_FACT_USED_SATELLITE].known)
                continue;
            id = (int32_t)facts[NMEA_FACT_USED_SATELLITE].number;
            add_used(fix, system ? system : system_of(talker, id) ? system_of(talker, id) : FIX_UNKNOWN, id);
        }
    }
    if (in_view)
        satellites_in_view(a, l, fl, s, facts, talker);
}

void nmea_fix_init(nmea_fix_assembler *a) { memset(a, 0, sizeof *a); }

/* Whether a layout has a field that carries the time of day. */
static bool carries_time(const layout_facts *fl)
{
    uint8_t i;

    for (i = 0; i < fl->count; i++)
        if (fl->fields[i].fact == NMEA_FACT_TIME)
            return true;
    return false;
}

/* Whether the fix under way came from this talker's sentence already. */
static bool holds_source(const nmea_gnss_fix *fix, const char talker[3], const char *sentence)
{
    uint16_t i;

    for (i = 0; i < fix->sentence_count; i++)
        if (strcmp(fix->sentences[i].sentence, sentence) == 0 && strcmp(fix->sentences[i].talker, talker) == 0)
            return true;
    return false;
}

bool nmea_fix_feed(nmea_fix_assembler *a, const nmea_sentence *s, nmea_gnss_fix *out)
{
    const layout_facts *fl = s->id == NMEA_SENTENCE_GENERIC ? NULL : &FIX.layouts[s->id];
    const layout *l = LAYOUTS[s->id];
    fact_value facts[NMEA_FACT_COUNT];
    char talker[3] = {0};
    bool closed = false;
    size_t i;

    if (!fl || !fl->count)
        return false;
    memset(facts, 0, sizeof facts);
    for (i = 0; i < fl->count; i++)
        if (!fl->fields[i].in_group)
            facts[fl->fields[i].fact] = fact_of(&fl->fields[i], const_member_at(&s->as, fl->fields[i].field->offset));
    if (l->head != NO_MEMBER && l->kind == LAYOUT_STANDARD) {
        const nmea_text *address = (const nmea_text *)const_member_at(&s->as, l->head);
        copy_talker(talker, address->ptr, address->len);
    }
    if (a->open && (facts[NMEA_FACT_TIME].known
                        ? nmea_fix_has(&a->fix, NMEA_FACT_TIME) &&
                              a->fix.time_ms != (uint32_t)facts[NMEA_FACT_TIME].number
                        /* no time of day yet: a sentence with a time field comes once an epoch */
                        : !nmea_fix_has(&a->fix, NMEA_FACT_TIME) && carries_time(fl) &&
                              holds_source(&a->fix, talker, l->sentence))) {
        finish_epoch(a, out);
        closed = true;
    }
    if (!a->open) {
        memset(&a->fix, 0, offsetof(nmea_gnss_fix, used));
        a->open = true;
    }
    if (facts[NMEA_FACT_TIME].known) {
        a->fix.time_ms = (uint32_t)facts[NMEA_FACT_TIME].number;
        a->fix.known |= fact_bit(NMEA_FACT_TIME);
    }
    if (a->fix.sentence_count == NMEA_FIX_MAX_SENTENCES) {
        a->fix.overflow++;
    } else {
        nmea_gnss_source *source = &a->fix.sentences[a->fix.sentence_count++];
        memcpy(source->talker, talker, sizeof talker);
        source->sentence = l->sentence;
    }
    merge(a, l, fl, s, facts, talker);
    return closed;
}

bool nmea_fix_finish(nmea_fix_assembler *a, nmea_gnss_fix *out)
{
    if (!a->open)
        return false;
    finish_epoch(a, out);
    return true;
}

#ifndef NMEA_NO_JSON
#include <stdio.h>
#include <stdlib.h>

#include "repr.c"

static void put_double(nmea_writer *w, double v)
{
    char text[NMEA_REPR_SIZE];
    put_mem(w, text, nmea_repr_double(v, text));
}

static void put_int(nmea_writer *w, int64_t v)
{
    if (v < 0)
        put_char(w, '-');
    put_uint(w, (uint64_t)(v < 0 ? -v : v), 1);
}

/* A JSON string of a static text, or null. */
static void put_id(nmea_writer *w, const char *id)
{
    if (!id) {
        put_str(w, "null");
        return;
    }
    put_char(w, '"');
    put_str(w, id);
    put_char(w, '"');
}

/* Date and time as ISO 8601 (Python's isoformat: microseconds only when not zero). */
static void put_iso_date(nmea_writer *w, int32_t days)
{
    /* The inverse of nmea_days_from_civil (days since 0000-03-01, years from March). */
    int32_t z = days + 719468, era = (z >= 0 ? z : z - 146096) / 146097;
    int32_t doe = z - era * 146097, yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    int32_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100), mp = (5 * doy + 2) / 153;
    int32_t day = doy - (153 * mp + 2) / 5 + 1, month = mp < 10 ? mp + 3 : mp - 9;
    int32_t year = yoe + era * 400 + (month <= 2);
    put_char(w, '"');
    put_uint(w, (uint64_t)year, 4);
    put_char(w, '-');
    put_uint(w, (uint64_t)month, 2);
    put_char(w, '-');
    put_uint(w, (uint64_t)day, 2);
    put_char(w, '"');
}

static void put_iso_time(nmea_writer *w, uint32_t ms)
{
    put_char(w, '"');
    put_uint(w, ms / 3600000, 2);
    put_char(w, ':');
    put_uint(w, ms / 60000 % 60, 2);
    put_char(w, ':');
    put_uint(w, ms / 1000 % 60, 2);
    if (ms % 1000) {
        put_char(w, '.');
        put_uint(w, (uint64_t)(ms % 1000) * 1000, 6);
    }
    put_char(w, '"');
}

static void put_optional_int(nmea_writer *w, bool known, int64_t v)
{
    if (known)
        put_int(w, v);
    else
        put_str(w, "null");
}

static void put_satellite(nmea_writer *w, const nmea_gnss_satellite *s)
{
    put_str(w, "{\"system\":");
    put_id(w, s->system);
    put_str(w, ",\"id\":");
    put_int(w, s->id);
    put_str(w, ",\"talker\":\"");
    put_str(w, s->talker);
    put_str(w, "\",\"signal\":");
    put_id(w, s->signal);
    put_str(w, ",\"elevation\":");
    put_optional_int(w, s->has_elevation, s->elevation);
    put_str(w, ",\"azimuth\":");
    put_optional_int(w, s->has_azimuth, s->azimuth);
    put_str(w, ",\"snr\":");
    put_optional_int(w, s->has_snr, s->snr);
    put_str(w, ",\"used\":");
    put_str(w, s->used < 0 ? "null" : s->used ? "true" : "false");
    put_char(w, '}');
}

/* The satellites used, by GNSS in the order each first appears. */
static void put_used(nmea_writer *w, const nmea_gnss_fix *fix)
{
    size_t i, j, k;
    put_char(w, '{');
    for (i = 0; i < fix->used_count; i++) {
        const char *system = fix->used[i].system;
        for (j = 0; j < i && strcmp(fix->used[j].system, system) != 0; j++)
            ;
        if (j < i)
            continue; /* listed with the first of its system */
        if (i)
            put_char(w, ',');
        put_id(w, system);
        put_str(w, ":[");
        for (k = i; k < fix->used_count; k++) {
            if (strcmp(fix->used[k].system, system) != 0)
                continue;
            if (k != i)
                put_char(w, ',');
            put_int(w, fix->used[k].id);
        }
        put_char(w, ']');
    }
    put_char(w, '}');
}

size_t nmea_fix_to_json(const nmea_gnss_fix *fix, char *buf, size_t cap)
{
    nmea_writer w = writer_of(buf, cap);
    size_t i;

    put_str(&w, "{\"time\":");
    if (nmea_fix_has(fix, NMEA_FACT_TIME))
        put_iso_time(&w, fix->time_ms);
    else
        put_str(&w, "null");
    put_str(&w, ",\"date\":");
    if (nmea_fix_has(fix, NMEA_FACT_DATE))
        put_iso_date(&w, fix->date_days);
    else
        put_str(&w, "null");
    for (i = 0; i < FIX_SCALAR_COUNT; i++) {
        const void *at = const_member_at(fix, FIX_SCALARS[i].offset);
        put_str(&w, ",\"");
        put_str(&w, FIX_SCALARS[i].name);
        put_str(&w, "\":");
        if (!nmea_fix_has(fix, (nmea_fact)FIX_SCALARS[i].fact))
            put_str(&w, "null");
        else if (FIX_SCALARS[i].is_id)
            put_id(&w, *(const char *const *)at);
        else if (nmea_fix_is_whole(fix, (nmea_fact)FIX_SCALARS[i].fact))
            put_int(&w, (int64_t)*(const double *)at);
        else
            put_double(&w, *(const double *)at);
    }
    put_str(&w, ",\"satellites_used\":");
    put_optional_int(&w, nmea_fix_has(fix, NMEA_FACT_SATELLITES_USED), fix->satellites_used);
    put_str(&w, ",\"used\":");
    put_used(&w, fix);
    put_str(&w, ",\"in_view\":[");
    for (i = 0; i < fix->in_view_len; i++) {
        if (i)
            put_char(&w, ',');
        put_satellite(&w, &fix->in_view[i]);
    }
    put_str(&w, "],\"sentences\":[");
    for (i = 0; i < fix->sentence_count; i++) {
        if (i)
            put_char(&w, ',');
        put_char(&w, '"');
        put_str(&w, fix->sentences[i].talker);
        put_str(&w, fix->sentences[i].sentence);
        put_char(&w, '"');
    }
    put_str(&w, "]}");
    return writer_finish(&w);
}
#endif /* NMEA_NO_JSON */
#endif /* NMEA_NO_FIXES */
