/* The layout interpreter's JSON (the tools' two directions, see json.md): json_with writes a
   sentence of any layout as decode's JSON, collect_with gathers the field texts of encode's JSON
   into a wire for read_with. Left out by -DNMEA_NO_JSON, as the rest of the JSON. */

#ifndef NMEA_NO_JSON
/* A field in the JSON under `key` (NULL: a value of a group's array), from `in`, a value of its
   type. */
static void json_field(nmea_writer *w, const char *key, const layout_field *f, const void *in, bool values)
{
    switch ((field_type)f->type) {
    case FIELD_KEYWORD:
        json_keyword(w, key, word_of(f), values);
        break;
    case FIELD_INTEGER:
    case FIELD_DECIMAL:
        json_number(w, key, in, values);
        break;
    case FIELD_HEX:
        json_hex(w, key, in, values);
        break;
    case FIELD_TIME:
        json_time(w, key, in, values);
        break;
    case FIELD_DATE:
        json_date(w, key, in, values);
        break;
    case FIELD_LATITUDE:
    case FIELD_LONGITUDE:
        json_coordinate(w, key, in, values);
        break;
    case FIELD_CHAR:
        json_char(w, key, *(const char *)in, values);
        break;
    case FIELD_LITERAL:
        json_literal(w, key, *(const bool *)in, word_of(f), values);
        break;
    case FIELD_TEXT:
        json_text(w, key, *(const nmea_text *)in, values);
        break;
    case FIELD_ENUM:
        json_enum(w, key, in, table_of(f), values);
        break;
    case FIELD_ENUM_CHARS:
        json_enum_chars(w, key, *(const nmea_text *)in, table_of(f), values);
        break;
    }
}

static void json_fields(nmea_writer *w, const layout_field *f, size_t n, const void *entry, bool values)
{
    size_t i;
    for (i = 0; i < n; i++)
        json_field(w, f[i].id, &f[i], const_member_at(entry, f[i].offset), values);
}

/* The lossless fields of a text command written back as received: each word as written, under
   the ids of the layout's fields in order. */
static void json_words_as_received(nmea_writer *w, const layout *l, nmea_text line)
{
    const char *p = line.ptr, *end = line.ptr + line.len, *space;
    size_t i, count = l->before + l->optional;
    p = memchr(p, ' ', line.len);
    for (i = 0; p && i < count; i++) {
        p++;
        space = memchr(p, ' ', (size_t)(end - p));
        json_key(w, l->fields[i].id);
        if (p == (space ? space : end))
            put_str(w, "null");
        else
            put_json_str(w, text_span(p, space ? space : end), 0);
        p = space;
    }
}

/* The lossless fields of a text command written in the spec's letter case, as the reference
   shows them: each word under its field id, the text of a problem in place of the field's. */
static void json_words_as_written(nmea_writer *w, const layout *l, const void *s, const nmea_problems *problems)
{
    size_t i, count = l->before + optional_of(l, s);
    for (i = 0; i < count; i++)
        if (!problems || !json_problem_word(w, l->fields[i].id, problems, (unsigned)i + 1))
            json_field(w, l->fields[i].id, &l->fields[i], const_member_at(s, l->fields[i].offset), false);
}

/* The entries of the group of `s`, a struct of layout `l`: from the caller's array, else read
   again from the wire field by field. */
static void json_entries(nmea_writer *w, const layout *l, const void *s, bool values)
{
    const layout_group *g = l->group;
    const nmea_entries *e = entries_in(g, s);
    size_t i, j, n = entries_of(g, s);
    bool on_wire = false;
    entry_reader c;
    field_value value;
    const void *in;

    memset(&c, 0, sizeof c);
    json_open(w, g->id, '[');
    for (i = 0; i < n; i++) {
        if (!e || !e->items)
            on_wire = i == 0 ? e && entry_reader_at(&c, l, e, 0) : on_wire && c.r.next < reader_end(&c.r);
        if (!g->single)
            json_open(w, NULL, '{');
        for (j = 0; j < g->field_count; j++) {
            const layout_field *f = &g->fields[j];
            if (e && e->items) {
                in = (const char *)e->items + i * g->entry_size + f->offset;
            } else {
                memset(&value, 0, sizeof value);
                if (on_wire)
                    reread_field(&c, f, &value);
                in = &value;
            }
            json_field(w, g->single ? NULL : f->id, f, in, values);
        }
        if (!g->single)
            json_close(w, '}');
    }
    json_close(w, ']');
}

/* The decode JSON of `s`, a struct of layout `l`, with its `problems` (NULL: none). */
NMEA_OUTLINE void json_with(nmea_writer *w, const layout *l, const void *s, const nmea_problems *problems,
                            bool values)
{
    const layout_group *g = l->group;
    nmea_writer sentence = writer_of(NULL, 0);
    nmea_checksum_style checksum = NMEA_CHECKSUM_NONE;

    write_with(&sentence, l, s, problems);
    if (l->checksum != NO_MEMBER)
        checksum = *(const nmea_checksum_style *)const_member_at(s, l->checksum);
    if (l->kind == LAYOUT_STANDARD) {
        json_begin_sentence(w, l->start, *(const nmea_text *)const_member_at(s, l->head), l->sentence, l->variant);
    } else if (l->kind == LAYOUT_PROPRIETARY) {
        json_begin_proprietary(w, "$", nmea_text_of(l->address), l->sentence, l->variant);
    } else {
        nmea_text as_received = *(const nmea_text *)const_member_at(s, l->head);
        json_begin_proprietary(w, "", text_address(&sentence, as_received, l->address), l->sentence, l->variant);
        if (!values) {
            if (sentence.matched)
                json_words_as_received(w, l, as_received);
            else
                json_words_as_written(w, l, s, problems);
            json_end_sentence(w, &sentence, checksum, problems);
            return;
        }
    }
    json_fields(w, l->fields, l->before, s, values);
    if (g)
        json_entries(w, l, s, values);
    json_fields(w, l->fields + l->before, l->after + optional_of(l, s), s, values);
    json_end_sentence(w, &sentence, checksum, problems);
}

/* The wire fields of a `fields` object of decode's JSON for layout `l`, in wire order. */
static bool collect_with(const layout *l, nmea_collector *c, nmea_json fields)
{
    const layout_field *f = l->fields;
    const layout_group *g = l->group;
    nmea_json entries, entry;
    size_t i;

    for (i = 0; i < l->before; i++)
        if (!collect_field(c, fields, f[i].id, field_width(&f[i])))
            return false;
    if (g) {
        if (!collect_group(c, fields, g->id, &entries))
            return false;
        while (json_next(&entries, &entry))
            for (i = 0; i < g->field_count; i++)
                if (!(g->single ? collect_value(c, entry, field_width(&g->fields[i]))
                                : collect_field(c, entry, g->fields[i].id, field_width(&g->fields[i]))))
                    return false;
    }
    for (f += l->before, i = 0; i < l->after; i++)
        if (!collect_field(c, fields, f[i].id, field_width(&f[i])))
            return false;
    for (f += l->after, i = 0; i < l->optional; i++)
        if (!collect_optional(c, fields, f[i].id, field_width(&f[i])))
            return false;
    return true;
}
#endif /* NMEA_NO_JSON */
