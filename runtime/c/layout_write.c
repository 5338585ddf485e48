/* The general writer of any layout: write_with writes a sentence's fields from its struct (its
   keywords, its repeated group from the wire or the caller's items, the texts of its problems in
   their places); serialize_with and build_with (written, then read back) are the per-layout
   nmea_serialize_<layout> and nmea_build_<layout>. */

/* Writes field `f` (its separator and text) from `in`, a value of its type. */
static void write_field(nmea_writer *w, const layout_field *f, const void *in)
{
    switch ((field_type)f->type) {
    case FIELD_KEYWORD:
        put_keyword(w, word_of(f));
        break;
    case FIELD_INTEGER:
    case FIELD_DECIMAL:
        put_number(w, in);
        break;
    case FIELD_HEX:
        put_hex(w, in);
        break;
    case FIELD_TIME:
        put_time(w, in);
        break;
    case FIELD_DATE:
        put_date(w, in);
        break;
    case FIELD_LATITUDE:
    case FIELD_LONGITUDE:
        put_coordinate(w, in);
        break;
    case FIELD_CHAR:
        put_char_field(w, *(const char *)in);
        break;
    case FIELD_LITERAL:
        put_literal(w, *(const bool *)in, word_of(f));
        break;
    case FIELD_TEXT:
    case FIELD_ENUM_CHARS:
        put_text_field(w, *(const nmea_text *)in);
        break;
    case FIELD_ENUM:
        put_enum(w, in, table_of(f));
        break;
    }
}

static void write_fields(nmea_writer *w, const layout_field *f, size_t n, const void *entry)
{
    size_t i;
    for (i = 0; i < n; i++)
        write_field(w, &f[i], const_member_at(entry, f[i].offset));
}

/* The entries of a group: from the caller's array, else their fields as received (a field a
   problem names is written with the problem's text, which is the same). The fields of entries
   neither holds are empty; a group of keywords writes its keywords. */
static void write_entries(nmea_writer *w, const layout_group *g, const void *s)
{
    const nmea_entries *e = entries_in(g, s);
    size_t i, n = entries_of(g, s);
    const char *p, *end, *stop;

    if (e && e->items) {
        for (i = 0; i < n; i++)
            write_fields(w, g->fields, g->field_count, (const char *)e->items + i * g->entry_size);
        return;
    }
    if (!e) {
        for (i = 0; i < n; i++)
            write_fields(w, g->fields, g->field_count, s);
        return;
    }
    p = e->wire.ptr;
    end = p ? p + e->wire.len : NULL;
    for (i = 0; i < n * g->width; i++) {
        stop = fields_end(p, end, w->sep, 1);
        /* (a field lenient parsing read as empty is written empty, or as its problem's text) */
        if (!put_sep(w) && stop != p && !(e->blanks && is_blank(e->blank, e->blanks, (unsigned)i + 1)))
            put_text(w, text_span(p, stop));
        p = stop < end ? stop + 1 : stop;
    }
}

/* Writes `s`, a struct of layout `l`, with the texts of its `problems` (NULL: none) in their
   places. */
NMEA_OUTLINE void write_with(nmea_writer *w, const layout *l, const void *s, const nmea_problems *problems)
{
    const layout_group *g = l->group;

    if (l->kind == LAYOUT_STANDARD)
        begin_sentence(w, l->start, *(const nmea_text *)const_member_at(s, l->head), l->sentence, problems);
    else if (l->kind == LAYOUT_PROPRIETARY)
        begin_sentence(w, '$', nmea_text_of(NULL), l->address, problems);
    else
        begin_text(w, l->address, *(const nmea_text *)const_member_at(s, l->head), problems);
    write_fields(w, l->fields, l->before, s);
    if (g)
        write_entries(w, g, s);
    write_fields(w, l->fields + l->before, l->after + optional_of(l, s), s);
    if (l->kind == LAYOUT_TEXT)
        end_text(w);
    else
        end_sentence(w, *(const nmea_checksum_style *)const_member_at(s, l->checksum));
}

/* The sentence `s` of layout `l` (with `problems`, NULL: none) written to buf. */
static size_t serialize_with(const layout *l, const void *s, const nmea_problems *problems, char *buf, size_t cap)
{
    nmea_writer w = writer_of(buf, cap);
    write_with(&w, l, s, problems);
    return writer_finish(&w);
}

/* nmea_build_*: the sentence written, then read back into `check` (a struct of the layout). */
static size_t build_with(const layout *l, const void *s, const nmea_problems *problems, void *check, char *buf,
                         size_t cap, nmea_error *err)
{
    nmea_writer w = writer_of(buf, cap);
    nmea_wire wire;

    write_with(&w, l, s, problems);
    if (!build_wire(&w, l->kind == LAYOUT_TEXT, &wire, err) || !read_with(l, check, &wire, err))
        return build_failed(&w);
    return build_end(&w);
}
