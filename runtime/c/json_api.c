/* The API of nmea.h for the tools' JSON (json.md): nmea_to_json and nmea_decode_json (decode's
   output for a line), and nmea_from_json (encode's input: the field texts put back on the wire
   and read by the sentence's layout, leniently with the texts of its "problems" in their
   places). Left out by -DNMEA_NO_JSON. */

#ifndef NMEA_NO_JSON
/* The layout that decode's JSON names by its sentence id and variant (NULL: the main one). */
static nmea_sentence_id find_layout(nmea_text sentence, const nmea_text *variant)
{
    size_t id;
    for (id = 1; id < NMEA_SENTENCE_COUNT; id++) {
        const layout *l = LAYOUTS[id];
        if (text_is(sentence, l->sentence) && (variant ? l->variant && text_is(*variant, l->variant) : !l->variant))
            return (nmea_sentence_id)id;
    }
    return NMEA_SENTENCE_GENERIC;
}

/* decode's members for what came before the sentence, and the object's closing brace: the
   "tag_blocks" array (each block's parameters and checksum as received), when there are blocks
   or no stray '$', then "stray" (the '$' sent before the sentence's own start). */
static void json_tag_blocks(nmea_writer *w, nmea_text before)
{
    nmea_text params, blocks = before, stray;
    nmea_tag_param param;
    bool first_block = true, first;
    while (blocks.len && blocks.ptr[blocks.len - 1] == '$') /* a block ends with '\\' */
        blocks.len--;
    stray = text_span(before.ptr + blocks.len, before.ptr + before.len);
    if (stray.len && !blocks.len) {
        put_str(w, "\"stray\":");
        put_json_str(w, stray, 0);
        put_char(w, '}');
        return;
    }
    put_str(w, "\"tag_blocks\":[");
    while (nmea_tag_next_block(&blocks, &params)) {
        const char *sum = params.ptr + params.len + 1; /* after the '*' */
        put_str(w, first_block ? "{\"params\":[" : ",{\"params\":[");
        for (first = true; nmea_tag_next_param(&params, &param); first = false) {
            put_str(w, first ? "{\"code\":" : ",{\"code\":");
            put_json_str(w, param.code, 0);
            put_str(w, ",\"value\":");
            put_json_str(w, param.value, 0);
            put_char(w, '}');
        }
        put_str(w, "],\"checksum\":\"");
        put_mem(w, sum, 2);
        put_str(w, "\"}");
        first_block = false;
    }
    put_char(w, ']');
    if (stray.len) {
        put_str(w, ",\"stray\":");
        put_json_str(w, stray, 0);
    }
    put_char(w, '}');
}

size_t nmea_to_json(const nmea_sentence *s, bool values, char *buf, size_t cap)
{
    nmea_writer w = writer_of(buf, cap);
    if (tag_blocks_only(s)) {
        put_str(&w, "{\"ok\":true,");
        json_tag_blocks(&w, s->tag_blocks);
        return writer_finish(&w);
    }
    if (s->id == NMEA_SENTENCE_GENERIC)
        json_generic(&w, &s->as.generic);
    else
        json_with(&w, LAYOUTS[s->id], &s->as, s->problems, values);
    if (s->tag_blocks.len) { /* the blocks come last: in place of the closing brace */
        w.len--;
        put_char(&w, ',');
        json_tag_blocks(&w, s->tag_blocks);
    }
    return writer_finish(&w);
}

size_t nmea_decode_json(const char *line, size_t len, bool values, char *buf, size_t cap)
{
    return nmea_decode_json_ex(line, len, values, NULL, buf, cap);
}

size_t nmea_decode_json_ex(const char *line, size_t len, bool values, const nmea_options *options, char *buf,
                           size_t cap)
{
    static const nmea_options defaults = {false, false, NULL, false};
    nmea_sentence s;
    nmea_error err;
    nmea_problems problems;
    nmea_options keeping = options ? *options : defaults;

    if (!keeping.problems) /* the JSON lists them */
        keeping.problems = &problems;
    if (nmea_parse_ex(&s, line, len, &keeping, &err))
        return nmea_to_json(&s, values, buf, cap);
    return nmea_error_to_json(&err, buf, cap);
}

/* A sentence the spec does not describe: "fields" (raw texts), "start" and "address". */
static bool generic_from_json(nmea_generic *g, nmea_json root, nmea_scratch *scratch, nmea_error *err)
{
    nmea_json fields, entry;
    nmea_collector c;
    nmea_text start;
    bool present, wide;

    if (!json_require(root, "fields", &fields, err))
        return false;
    if (!json_is(fields, '['))
        return bad_json(err, "\"%s\" is not an array", "fields");
    if (!json_text_member(root, "start", false, scratch, &start, &present, &wide, err))
        return false;
    if (wide || !(text_is(start, "$") || text_is(start, "!")))
        return bad_json(err, "\"start\" is not \"$\" or \"!\"", NULL);
    g->start = nmea_text_of(start.ptr[0] == '$' ? "$" : "!");
    if (!json_word_member(root, "address", scratch, &g->address, err))
        return false;
    c.scratch = scratch;
    c.start = scratch->len;
    c.count = 0;
    c.err = err;
    fields = json_items(fields);
    while (json_next(&fields, &entry))
        if (!collect_text(&c, entry))
            return false;
    g->fields = collected(&c);
    g->field_count = c.count;
    return true;
}

/* A text command's line as received from decode's JSON: its word and the collected texts
   (comma separated in the scratch buffer) joined by single spaces. */
static bool command_line(nmea_wire *wire, nmea_text word, nmea_scratch *s, nmea_error *err)
{
    size_t i, start = s->len;
    if (s->cap - s->len < word.len + (wire->count ? 1 + wire->fields.len : 0))
        return scratch_full(err);
    memcpy(s->buf + s->len, word.ptr, word.len);
    s->len += word.len;
    if (wire->count) {
        s->buf[s->len++] = ' ';
        for (i = 0; i < wire->fields.len; i++)
            s->buf[s->len++] = wire->fields.ptr[i] == ',' ? ' ' : wire->fields.ptr[i];
    }
#ifndef NMEA_NO_COMMANDS
    wire->line = text_span(s->buf + start, s->buf + s->len);
#else
    (void)start;
#endif
    return true;
}

/* A JSON integer (no fraction, no exponent) from 1 to n. */
static bool json_index(nmea_json v, size_t n, size_t *index)
{
    const char *p;
    size_t value = 0;
    if (v.p >= v.end)
        return false;
    for (p = v.p; p < v.end; p++) {
        if (!is_digit(*p) || value > n)
            return false;
        value = value * 10 + (size_t)(*p - '0');
    }
    *index = value;
    return value >= 1 && value <= n;
}

/* Room for the problems of a sentence rebuilt from JSON in the scratch buffer (aligned as the
   struct needs), or NULL when it is full. */
static nmea_problems *scratch_problems(nmea_scratch *s)
{
    typedef struct {
        char c;
        nmea_problems p;
    } probe;
    size_t align = offsetof(probe, p), at = s->len + (align - (uintptr_t)(s->buf + s->len) % align) % align;
    if (at > s->cap || s->cap - at < sizeof(nmea_problems))
        return NULL;
    s->len = at + sizeof(nmea_problems);
    return (nmea_problems *)(void *)(s->buf + at);
}

/* The sentence of the JSON's wire read as a received line is, with `options` (a number outside
   its range is kept, as decoding kept it, whether or not the JSON lists it as a problem). */
static bool read_again(nmea_sentence *out, nmea_sentence_id id, nmea_wire *wire, const nmea_options *options,
                       nmea_error *err)
{
    nmea_layouts one;
    one.key = NULL;
    one.key_len = 0;
    one.suffix = NULL;
    one.ids = &id;
    one.count = 1;
    out->problems = NULL;
    return fit(out, &one, wire, options, err);
}

/* A sentence that lenient decoding kept (its JSON has "problems"): the texts of its problem
   fields go back in their places, and its layout parses it leniently again. `wire` holds the
   texts of the `fields` object. */
static bool with_problems(nmea_sentence *out, nmea_sentence_id id, nmea_json root, nmea_json problems,
                          nmea_scratch *s, nmea_wire *wire, nmea_error *err)
{
    nmea_text start, text, texts[NMEA_MAX_FIELDS];
    nmea_json problem, v;
    nmea_options lenient = {true, false, NULL, false};
    const char *p = wire->fields.ptr, *end = p + wire->fields.len, *comma;
    size_t i, index, n = wire->count, need = 0;
    bool present, wide;

    if (!json_text_member(root, "start", false, s, &start, &present, &wide, err))
        return false;
    if (start.len == 0)
        return bad_json(err, "a text command has no problems", NULL);
    if (!json_is(problems, '['))
        return bad_json(err, "\"%s\" is not an array", "problems");
    /* the texts one by one (unless there are more than any layout takes: the layout then refuses
       them whatever they say) */
    for (i = 0; n <= NMEA_MAX_FIELDS && i < n; i++) {
        for (comma = p; comma < end && *comma != ','; comma++)
            continue;
        texts[i] = text_span(p, comma);
        p = comma < end ? comma + 1 : end;
    }
    problems = json_items(problems);
    while (json_next(&problems, &problem)) {
        if (!json_require(problem, "field", &v, err))
            return false;
        if (json_is_null(v)) /* no field's: a short checksum, which "checksum" says */
            continue;
        if (!json_index(v, n, &index))
            return bad_json(err, "a problem's \"field\" is not the index of a field", NULL);
        if (!json_require(problem, "text", &v, err) || !json_field_text(v, s, &text, err))
            return false;
        if (n <= NMEA_MAX_FIELDS)
            texts[index - 1] = text;
    }
    if (!LAYOUTS[id]->address) { /* a standard sentence: the talker and the sentence id */
        if (!json_talker_member(root, LAYOUTS[id]->sentence, s, &wire->address, err))
            return false;
        wire->suffix = LAYOUTS[id]->sentence;
    }
    if (n && n <= NMEA_MAX_FIELDS) { /* the texts joined again */
        for (i = 0; i < n; i++)
            need += texts[i].len + 1;
        if (s->cap - s->len < need)
            return scratch_full(err);
        p = s->buf + s->len;
        for (i = 0; i < n; i++) {
            if (i)
                s->buf[s->len++] = ',';
            if (texts[i].len)
                memcpy(s->buf + s->len, texts[i].ptr, texts[i].len);
            s->len += texts[i].len;
        }
        wire->fields = text_span(p, s->buf + s->len);
    }
    if ((lenient.problems = scratch_problems(s)) == NULL)
        return scratch_full(err);
    return read_again(out, id, wire, &lenient, err);
}

/* The text of a TAG block parameter's code or value from decode's JSON, copied to the scratch
   buffer. */
static bool tag_text_member(nmea_json obj, const char *key, nmea_scratch *s, nmea_error *err)
{
    nmea_json v;
    nmea_text t;
    bool present, wide;
    size_t i;
    if (!json_text_member(obj, key, false, s, &t, &present, &wide, err))
        return false;
    for (i = 0; i < t.len; i++) {
        if (wide || !is_printable(t.ptr[i]) || t.ptr[i] == ',' || t.ptr[i] == '*' || t.ptr[i] == '\\') {
            bad_json(err, "TAG block text %q holds ',', '*', a backslash or a byte outside printable ASCII", NULL);
            json_member(obj, key, &v);
            err->text = json_inside(v);
            err->text_json = true;
            return false;
        }
    }
    return true;
}

/* decode's "tag_blocks" written back into the scratch buffer, and read there as received ones. */
static bool tag_blocks_from_json(nmea_json items, nmea_scratch *s, nmea_text *blocks, nmea_error *err)
{
    nmea_json item, params, param;
    nmea_checksum_style style;
    size_t start = s->len, body;
    nmea_writer w;
    nmea_json first;
    bool first_param;
    if (!json_is(items, '['))
        return bad_json(err, "\"%s\" is not an array of TAG blocks", "tag_blocks");
    first = items = json_items(items);
    if (!json_next(&first, &item)) /* none */
        return bad_json(err, "\"%s\" is not an array of TAG blocks", "tag_blocks");
    while (json_next(&items, &item)) {
        if (s->len >= s->cap)
            return scratch_full(err);
        s->buf[s->len++] = '\\';
        body = s->len;
        if (!json_require(item, "params", &params, err))
            return false;
        if (!json_is(params, '['))
            return bad_json(err, "\"%s\" is not an array", "params");
        for (params = json_items(params), first_param = true; json_next(&params, &param); first_param = false) {
            if (!first_param) {
                if (s->len >= s->cap)
                    return scratch_full(err);
                s->buf[s->len++] = ',';
            }
            if (!tag_text_member(param, "code", s, err))
                return false;
            if (s->len >= s->cap)
                return scratch_full(err);
            s->buf[s->len++] = ':';
            if (!tag_text_member(param, "value", s, err))
                return false;
        }
        if (!json_checksum_style(item, &style, err))
            return false;
        if (s->cap - s->len < 4)
            return scratch_full(err);
        w = writer_of(s->buf + s->len, 4);
        put_char(&w, '*');
        w.sum = xor_bytes(s->buf + body, s->len - body);
        put_char(&w, (style == NMEA_CHECKSUM_LOWER ? HEX_LOWER : HEX_UPPER)[w.sum >> 4]);
        put_char(&w, (style == NMEA_CHECKSUM_LOWER ? HEX_LOWER : HEX_UPPER)[w.sum & 15]);
        s->len += 3;
        s->buf[s->len++] = '\\';
    }
    return read_tag_blocks(s->buf + start, s->len - start, blocks, err);
}

/* decode's "stray" written into the scratch buffer after the TAG blocks (`*before`, which it
   extends): one or more '$'. */
static bool stray_from_json(nmea_json stray, nmea_scratch *s, nmea_text *before, nmea_error *err)
{
    nmea_text text;
    bool wide;
    size_t i;
    if (!json_is(stray, '"'))
        return bad_json(err, "\"stray\" is not one or more \"$\"", NULL);
    if (!json_string(stray, s, &text, &wide))
        return scratch_full(err);
    for (i = 0; i < text.len && text.ptr[i] == '$'; i++)
        continue;
    if (!text.len || i < text.len)
        return bad_json(err, "\"stray\" is not one or more \"$\"", NULL);
    if (!before->len)
        before->ptr = text.ptr;
    before->len += text.len;
    return true;
}

/* nmea_from_json of the sentence (its TAG blocks read already). */
static bool sentence_from_json(nmea_sentence *out, nmea_json root, nmea_scratch *s, nmea_error *err)
{
    nmea_json fields;
    nmea_text sentence, variant, word;
    nmea_json problems;
    bool has_sentence, has_variant, wide_sentence, wide_variant;
    nmea_checksum_style checksum;
    nmea_sentence_id id;
    const layout *info;
    nmea_collector c;
    nmea_wire wire;
    static const nmea_options tolerant = {false, false, NULL, false};

    if (!json_checksum_style(root, &checksum, err)
        || !json_text_member(root, "sentence", true, s, &sentence, &has_sentence, &wide_sentence, err))
        return false;
    if (!has_sentence) {
        out->id = NMEA_SENTENCE_GENERIC;
        out->as.generic.checksum = checksum;
        return generic_from_json(&out->as.generic, root, s, err);
    }
    if (!json_text_member(root, "variant", true, s, &variant, &has_variant, &wide_variant, err))
        return false;
    id = wide_sentence || wide_variant ? NMEA_SENTENCE_GENERIC : find_layout(sentence, has_variant ? &variant : NULL);
    if (id == NMEA_SENTENCE_GENERIC) {
        nmea_json v;
        bad_json(err, "unknown sentence \"%t\"", NULL);
        json_member(root, "sentence", &v);
        err->text = json_inside(v);
        err->text_json = true;
        return false;
    }
    if (!json_require(root, "fields", &fields, err))
        return false;
    if (!json_is(fields, '{'))
        return bad_json(err, "\"%s\" is not an object", "fields");
    c.scratch = s;
    c.start = s->len;
    c.count = 0;
    c.err = err;
    if (!collect_with(LAYOUTS[id], &c, fields))
        return false;
    info = LAYOUTS[id];
    wire.address = nmea_text_of(info->address);
    wire.suffix = NULL;
    wire.fields = collected(&c);
    wire.count = c.count;
    wire.sep = ',';
    wire.ignore_case = false;
    wire.checksum = checksum;
#ifndef NMEA_NO_COMMANDS
    wire.line = nmea_text_of(NULL);
#endif
    wire.blanks = 0;
    if (json_member(root, "problems", &problems)) {
        wire.ignore_case = info->command != NULL;
        return with_problems(out, id, root, problems, s, &wire, err);
    }
    if (!info->address) { /* a standard sentence: the talker and the sentence id */
        if (!json_talker_member(root, info->sentence, s, &wire.address, err))
            return false;
        wire.suffix = info->sentence;
    } else if (info->command) { /* a text command: its word as written, its letter case kept */
        if (!json_word_member(root, "address", s, &word, err))
            return false;
        if (!upper_is(word, info->command)) {
            bad_json(err, "\"address\" is not %s", NULL);
            err->str[0] = info->address;
            return false;
        }
        wire.address = word;
        wire.ignore_case = true;
        wire.checksum = NMEA_CHECKSUM_NONE;
        if (!command_line(&wire, word, s, err))
            return false;
        return read_layout(out, id, &wire, err); /* text commands are always read strictly */
    }
    return read_again(out, id, &wire, &tolerant, err);
}
bool nmea_from_json(nmea_sentence *out, const char *json, size_t len, char *scratch, size_t scratch_cap,
                    nmea_error *err)
{
    nmea_scratch s;
    nmea_json root, tags, stray, start;
    nmea_text blocks = nmea_text_of(NULL);

    s.buf = scratch;
    s.cap = scratch ? scratch_cap : 0;
    s.len = 0;
    out->problems = NULL;
    out->tag_blocks = blocks;
    if (!json_parse(json, len, &root))
        return bad_json(err, "not JSON", NULL);
    if (!json_is(root, '{'))
        return bad_json(err, "not a JSON object", NULL);
    if (json_member(root, "tag_blocks", &tags) && !tag_blocks_from_json(tags, &s, &blocks, err))
        return false;
    if (json_member(root, "stray", &stray) && !stray_from_json(stray, &s, &blocks, err))
        return false;
    if (blocks.len) {
        if (!json_member(root, "start", &start)) { /* a line of TAG blocks only */
            if (blocks.ptr[blocks.len - 1] == '$')
                return bad_json(err, "\"stray\" without a sentence", NULL);
            memset(out, 0, sizeof *out);
            out->id = NMEA_SENTENCE_GENERIC;
            out->as.generic.checksum = NMEA_CHECKSUM_NONE;
            out->tag_blocks = blocks;
            return true;
        }
    }
    if (!sentence_from_json(out, root, &s, err))
        return false;
    out->tag_blocks = blocks;
    return true;
}

#endif /* NMEA_NO_JSON */
