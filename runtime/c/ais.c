/* AIS payloads: armoring, the bit reader and writer, text and JSON (see ais.h). */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The characters of six-bit text by their value ('@', value 0, pads a text to its width). */
static const char AIS_TEXT[] = "@ABCDEFGHIJKLMNOPQRSTUVWXYZ[\\]^_ !\"#$%&'()*+,-./0123456789:;<=>?";

const char *nmea_ais_error_kind_name(nmea_ais_error_kind kind)
{
    static const char *const names[] = {"ok", "bad_armor", "short_payload", "unknown_message", "bad_value"};
    return names[kind];
}

/* The six bits an armored character carries ('0'-'W' are 0-39, '`'-'w' 40-63), -1 for none. */
static int ais_armor_value(char ch)
{
    if (ch >= '0' && ch <= 'W')
        return ch - 48;
    if (ch >= '`' && ch <= 'w')
        return ch - 56;
    return -1;
}

static bool ais_fail(nmea_ais_error *err, nmea_ais_error_kind kind, int message_type, const char *field)
{
    err->kind = kind;
    err->message_type = message_type;
    err->field = field;
    return false;
}

/* Checks a payload's characters and fill bits; a reader of its message bits. */
static bool ais_open(nmea_ais_reader *r, const char *armored, size_t len, unsigned fill_bits, nmea_ais_error *err)
{
    size_t i;
    r->armored = armored;
    r->pos = 0;
    r->message_type = -1;
    r->err = err;
    if (fill_bits > 5 || (fill_bits && !len)) {
        snprintf(err->message, sizeof err->message, "fill bits are 0-5 (none for an empty payload), not %u", fill_bits);
        return ais_fail(err, NMEA_AIS_BAD_ARMOR, -1, NULL);
    }
    for (i = 0; i < len; i++) {
        if (ais_armor_value(armored[i]) < 0) {
            snprintf(err->message, sizeof err->message, "character '%c' at offset %zu is not six-bit armoring",
                     armored[i], i);
            return ais_fail(err, NMEA_AIS_BAD_ARMOR, -1, NULL);
        }
    }
    r->end = len * 6 - fill_bits;
    return true;
}

/* The `width` bits (at most 64) at `offset` of checked characters. */
static uint64_t ais_raw(const char *armored, size_t offset, size_t width)
{
    uint64_t raw = 0;
    size_t pos = offset, end = offset + width;
    while (pos < end) {
        size_t in_char = pos % 6, take = 6 - in_char < end - pos ? 6 - in_char : end - pos;
        unsigned chunk = ((unsigned)ais_armor_value(armored[pos / 6]) >> (6 - in_char - take)) & ((1u << take) - 1);
        raw = raw << take | chunk;
        pos += take;
    }
    return raw;
}

static bool ais_check(nmea_ais_reader *r, size_t offset, size_t width, const char *field)
{
    if (offset + width <= r->end)
        return true;
    snprintf(r->err->message, sizeof r->err->message, "%s needs bits %zu-%zu, the payload has %zu", field, offset,
             offset + width - 1, r->end);
    return ais_fail(r->err, NMEA_AIS_SHORT_PAYLOAD, r->message_type, field);
}

static bool ais_peek(nmea_ais_reader *r, size_t offset, size_t width, const char *field, uint64_t *out)
{
    if (!ais_check(r, offset, width, field))
        return false;
    *out = ais_raw(r->armored, offset, width);
    return true;
}

static bool ais_take(nmea_ais_reader *r, size_t width, const char *field, uint64_t *out)
{
    if (!ais_peek(r, r->pos, width, field, out))
        return false;
    r->pos += width;
    return true;
}

static bool ais_take_signed(nmea_ais_reader *r, size_t width, const char *field, int64_t *out)
{
    uint64_t raw;
    if (!ais_take(r, width, field, &raw))
        return false;
    *out = raw >> (width - 1) ? (int64_t)(raw - ((uint64_t)1 << (width - 1))) - ((int64_t)1 << (width - 1))
                              : (int64_t)raw;
    return true;
}

static bool ais_take_bits(nmea_ais_reader *r, size_t width, const char *field, nmea_ais_bits *out)
{
    if (!ais_check(r, r->pos, width, field))
        return false;
    out->armored = r->armored;
    out->offset = r->pos;
    out->len = width;
    r->pos += width;
    return true;
}

static size_t ais_remaining(const nmea_ais_reader *r)
{
    return r->end - r->pos;
}

/* The bits from here to the end (the bits after a layout). */
static nmea_ais_bits ais_rest(nmea_ais_reader *r)
{
    nmea_ais_bits bits;
    bits.armored = r->armored;
    bits.offset = r->pos;
    bits.len = r->end - r->pos;
    r->pos = r->end;
    return bits;
}

/* A reader of `bits` alone (an application's layout in a message's data). */
static nmea_ais_reader ais_bits_reader(nmea_ais_bits bits, nmea_ais_error *err)
{
    nmea_ais_reader r;
    r.armored = bits.armored;
    r.pos = bits.offset;
    r.end = bits.offset + bits.len;
    r.message_type = -1;
    r.err = err;
    return r;
}

/* How many entries of `width` bits a repeated group holds (see ais.py's Group). */
static bool ais_entries(nmea_ais_reader *r, size_t min, size_t max, size_t width, size_t after, const char *field,
                        size_t *count)
{
    size_t left = ais_remaining(r);
    *count = (left > after ? left - after : 0) / width;
    if (*count > max)
        *count = max;
    if (*count >= min)
        return true;
    snprintf(r->err->message, sizeof r->err->message, "%s needs at least %zu entries of %zu bits, %zu bits left",
             field, min, width, left);
    return ais_fail(r->err, NMEA_AIS_SHORT_PAYLOAD, r->message_type, field);
}

static void ais_writer_init(nmea_ais_writer *w, int message_type, nmea_ais_error *err)
{
    memset(w->values, 0, sizeof w->values);
    w->len = 0;
    w->message_type = message_type;
    w->err = err;
}

static bool ais_put_raw(nmea_ais_writer *w, uint64_t raw, size_t width, const char *field)
{
    size_t left = width;
    if (w->len + width > NMEA_AIS_MAX_BITS) {
        snprintf(w->err->message, sizeof w->err->message, "%s does not fit in a message of %d bits", field,
                 NMEA_AIS_MAX_BITS);
        return ais_fail(w->err, NMEA_AIS_BAD_VALUE, w->message_type, field);
    }
    while (left > 0) {
        size_t in_char = w->len % 6, put = 6 - in_char < left ? 6 - in_char : left;
        uint8_t chunk = (uint8_t)((raw >> (left - put)) & ((1u << put) - 1));
        w->values[w->len / 6] = (uint8_t)(w->values[w->len / 6] << put | chunk);
        w->len += put;
        left -= put;
    }
    return true;
}

/* `raw` in `width` bits; a value wider is refused. */
static bool ais_put(nmea_ais_writer *w, uint64_t raw, size_t width, const char *field)
{
    if (width < 64 && raw >> width) {
        snprintf(w->err->message, sizeof w->err->message, "%s takes a raw value of %zu bits, not %llu", field, width,
                 (unsigned long long)raw);
        return ais_fail(w->err, NMEA_AIS_BAD_VALUE, w->message_type, field);
    }
    return ais_put_raw(w, raw, width, field);
}

/* `value` in `width` bits, two's complement. */
static bool ais_put_signed(nmea_ais_writer *w, int64_t value, size_t width, const char *field)
{
    int64_t low = -((int64_t)1 << (width - 1)), high = ((int64_t)1 << (width - 1)) - 1;
    if (value < low || value > high) {
        snprintf(w->err->message, sizeof w->err->message, "%s takes a raw value of %zu bits, not %lld", field, width,
                 (long long)value);
        return ais_fail(w->err, NMEA_AIS_BAD_VALUE, w->message_type, field);
    }
    return ais_put_raw(w, (uint64_t)value & (width == 64 ? UINT64_MAX : ((uint64_t)1 << width) - 1), width, field);
}

/* Bits kept as sent, bit for bit. */
static bool ais_put_bits(nmea_ais_writer *w, nmea_ais_bits bits, const char *field)
{
    size_t start;
    for (start = 0; start < bits.len; start += 64) {
        size_t width = bits.len - start < 64 ? bits.len - start : 64;
        if (!ais_put_raw(w, ais_raw(bits.armored, bits.offset + start, width), width, field))
            return false;
    }
    return true;
}

/* Bits of a field of fixed width: exactly `width` of them (a text built by a program may have
   fewer characters than its field). */
static bool ais_put_fixed(nmea_ais_writer *w, nmea_ais_bits bits, size_t width, bool text, const char *field)
{
    if (bits.len != width) {
        if (text)
            snprintf(w->err->message, sizeof w->err->message, "%s takes %zu six-bit text characters, not %zu", field,
                     width / 6, bits.len / 6);
        else
            snprintf(w->err->message, sizeof w->err->message, "%s takes %zu bits, not %zu", field, width, bits.len);
        return ais_fail(w->err, NMEA_AIS_BAD_VALUE, w->message_type, field);
    }
    return ais_put_bits(w, bits, field);
}

bool nmea_ais_text(const char *text, char *buf, size_t cap, nmea_ais_bits *out, nmea_ais_error *err)
{
    size_t i, len = strlen(text);
    if (len > cap) {
        snprintf(err->message, sizeof err->message, "text of %zu characters does not fit in %zu bytes", len, cap);
        return ais_fail(err, NMEA_AIS_BAD_VALUE, -1, NULL);
    }
    for (i = 0; i < len; i++) {
        const char *found = text[i] ? strchr(AIS_TEXT, text[i]) : NULL;
        int value = found ? (int)(found - AIS_TEXT) : -1;
        if (value < 0) {
            snprintf(err->message, sizeof err->message, "text takes six-bit text characters, not '%c'", text[i]);
            return ais_fail(err, NMEA_AIS_BAD_VALUE, -1, NULL);
        }
        buf[i] = (char)(value < 40 ? value + 48 : value + 56);
    }
    out->armored = buf;
    out->offset = 0;
    out->len = 6 * len;
    return true;
}

/* The armored payload, its last character padded with `padding` (the fill bits' values). */
static bool ais_finish(nmea_ais_writer *w, unsigned padding, nmea_ais_armored *out)
{
    size_t i, chars;
    unsigned fill_bits = (unsigned)((6 - w->len % 6) % 6);
    if (padding >> fill_bits) {
        snprintf(w->err->message, sizeof w->err->message, "padding takes a raw value of %u bits, not %u", fill_bits,
                 padding);
        return ais_fail(w->err, NMEA_AIS_BAD_VALUE, w->message_type, "padding");
    }
    if (!ais_put_raw(w, padding, fill_bits, "padding"))
        return false;
    chars = w->len / 6;
    for (i = 0; i < chars; i++)
        out->chars[i] = (char)(w->values[i] < 40 ? w->values[i] + 48 : w->values[i] + 56);
    out->chars[chars] = '\0';
    out->fill_bits = (uint8_t)fill_bits;
    return true;
}

/* The special value of `raw` among `specials`, NULL for a number. */
static const char *ais_special(int64_t raw, const nmea_ais_special *specials, size_t count)
{
    size_t i;
    for (i = 0; i < count; i++)
        if (specials[i].raw == raw)
            return specials[i].id;
    return NULL;
}

static void ais_json_put(nmea_ais_json_out *j, const char *text, size_t len)
{
    if (j->len < j->cap)
        memcpy(j->buf + j->len, text, j->len + len < j->cap ? len : j->cap - j->len);
    j->len += len;
    if (j->cap)
        j->buf[j->len < j->cap ? j->len : j->cap - 1] = '\0';
}

static void ais_json_puts(nmea_ais_json_out *j, const char *text)
{
    ais_json_put(j, text, strlen(text));
}

static void ais_json_open(nmea_ais_json_out *j)
{
    ais_json_puts(j, "{");
    j->empty = true;
}

static void ais_json_close(nmea_ais_json_out *j)
{
    ais_json_puts(j, "}");
    j->empty = false;
}

static void ais_json_key(nmea_ais_json_out *j, const char *name)
{
    if (!j->empty)
        ais_json_puts(j, ",");
    j->empty = false;
    ais_json_puts(j, "\"");
    ais_json_puts(j, name);
    ais_json_puts(j, "\":");
}

/* An unsigned field's value: all 64 bits of one (a spare of 64 bits) are more than a long long holds. */
static void ais_json_uint(nmea_ais_json_out *j, const char *name, unsigned long long value)
{
    char text[24];
    ais_json_key(j, name);
    ais_json_put(j, text, (size_t)snprintf(text, sizeof text, "%llu", value));
}

static void ais_json_int(nmea_ais_json_out *j, const char *name, long long value)
{
    char text[24];
    if (value >= 0) {
        ais_json_uint(j, name, (unsigned long long)value);
        return;
    }
    ais_json_key(j, name);
    ais_json_put(j, text, (size_t)snprintf(text, sizeof text, "%lld", value));
}

static void ais_json_flag(nmea_ais_json_out *j, const char *name, bool value)
{
    ais_json_key(j, name);
    ais_json_puts(j, value ? "true" : "false");
}

static void ais_json_string(nmea_ais_json_out *j, const char *name, const char *value)
{
    ais_json_key(j, name);
    ais_json_puts(j, "\"");
    ais_json_puts(j, value);
    ais_json_puts(j, "\"");
}

/* Six-bit text as sent, '"' and '\' escaped. */
static void ais_json_text(nmea_ais_json_out *j, const char *name, nmea_ais_bits bits)
{
    size_t i;
    ais_json_key(j, name);
    ais_json_puts(j, "\"");
    for (i = 0; i + 6 <= bits.len; i += 6) {
        char ch = AIS_TEXT[ais_raw(bits.armored, bits.offset + i, 6)];
        if (ch == '"' || ch == '\\')
            ais_json_puts(j, "\\");
        ais_json_put(j, &ch, 1);
    }
    ais_json_puts(j, "\"");
}

/* Bits as the text of their values ("0110"). */
static void ais_json_bits(nmea_ais_json_out *j, const char *name, nmea_ais_bits bits)
{
    size_t i;
    ais_json_key(j, name);
    ais_json_puts(j, "\"");
    for (i = 0; i < bits.len; i++)
        ais_json_puts(j, ais_raw(bits.armored, bits.offset + i, 1) ? "1" : "0");
    ais_json_puts(j, "\"");
}

#include "repr.c"

static void ais_json_float(nmea_ais_json_out *j, double value)
{
    char text[NMEA_REPR_SIZE];
    nmea_repr_double(value, text);
    ais_json_puts(j, text);
}

/* A number's members: its value (`raw / divisor + base`, a float when `real`, computed as
   `(raw + base * divisor) / divisor`: (819 - 600) / 10 is 21.9, 819 / 10 - 60 is not) or special
   value's id, then its raw integer. */
static void ais_json_reading(nmea_ais_json_out *j, const char *name, int64_t raw, double divisor, double base, bool real,
                             const nmea_ais_special *specials, size_t count)
{
    char raw_name[64];
    const char *special = ais_special(raw, specials, count);
    if (special)
        ais_json_string(j, name, special);
    else if (real) {
        ais_json_key(j, name);
        ais_json_float(j, ((double)raw + base * divisor) / divisor);
    } else
        ais_json_int(j, name, (long long)(raw + (int64_t)base));
    snprintf(raw_name, sizeof raw_name, "%s_raw", name);
    ais_json_int(j, raw_name, (long long)raw);
}

/* An enum's member: the id of its code, or the code it does not name. */
static void ais_json_code(nmea_ais_json_out *j, const char *name, const char *id, uint64_t raw)
{
    if (id)
        ais_json_string(j, name, id);
    else
        ais_json_int(j, name, (long long)raw);
}

size_t nmea_ais_error_json(const nmea_ais_error *err, char *buf, size_t cap)
{
    nmea_ais_json_out j;
    char address[32];
    const char *p;
    j.buf = buf;
    j.cap = cap;
    j.len = 0;
    if (err->message_type >= 0)
        snprintf(address, sizeof address, "AIS type %d", err->message_type);
    else
        strcpy(address, "AIS");
    ais_json_open(&j);
    ais_json_string(&j, "kind", nmea_ais_error_kind_name(err->kind));
    ais_json_string(&j, "address", address);
    ais_json_key(&j, "field");
    ais_json_puts(&j, "null");
    if (err->field)
        ais_json_string(&j, "name", err->field);
    else {
        ais_json_key(&j, "name");
        ais_json_puts(&j, "null");
    }
    ais_json_key(&j, "message");
    ais_json_puts(&j, "\"");
    for (p = err->message; *p; p++) {
        if (*p == '"' || *p == '\\')
            ais_json_puts(&j, "\\");
        ais_json_put(&j, p, 1);
    }
    ais_json_puts(&j, "\"");
    ais_json_close(&j);
    return j.len;
}

void nmea_ais_assembler_init(nmea_ais_assembler *a, uint32_t lifetime)
{
    memset(a, 0, sizeof *a);
    a->lifetime = lifetime;
}

/* Appends `text` and a NUL to the key; false when it does not fit. */
static bool ais_key_put(char *key, size_t *len, const char *text, size_t n)
{
    if (*len + n + 1 > NMEA_AIS_KEY_CAPACITY)
        return false;
    memcpy(key + *len, text, n);
    key[*len + n] = '\0';
    *len += n + 1;
    return true;
}

/* The fragment's key: 'g', the TAG source and group id when the line has a group, else 'a', the
   talker, sentence, channel and sequential id, each ended by a NUL; false when it does not fit. */
static bool ais_key(const nmea_ais_fragment *f, nmea_text tags, char *key, size_t *len)
{
    nmea_text group, source = {"", 0};
    *len = 0;
    if (tags.len && nmea_tag_find(tags, "g", &group)) {
        /* The id is a number (Python compares it as one): leading zeros name the same group. */
        const char *id = group.ptr + group.len;
        size_t n = 0;
        while (id > group.ptr && id[-1] != '-')
            id--, n++;
        while (n > 1 && *id == '0')
            id++, n--;
        if (n == 0)
            id = "0", n = 1;
        nmea_tag_find(tags, "s", &source);
        return ais_key_put(key, len, "g", 1) && ais_key_put(key, len, source.ptr, source.len)
            && ais_key_put(key, len, id, n);
    } else {
        char sequence[2];
        sequence[0] = (char)(f->sequence >= 0);
        sequence[1] = (char)(f->sequence >= 0 ? f->sequence : 0);
        return ais_key_put(key, len, "a", 1) && ais_key_put(key, len, f->talker.ptr, f->talker.len)
            && ais_key_put(key, len, f->sentence.ptr, f->sentence.len)
            && ais_key_put(key, len, f->channel.ptr, f->channel.len) && ais_key_put(key, len, sequence, 2);
    }
}

/* The slot of the message under way that started first, -1 for none. */
static int ais_oldest(const nmea_ais_assembler *a)
{
    int i, oldest = -1;
    for (i = 0; i < NMEA_AIS_SLOTS; i++)
        if (a->slots[i].count && (oldest < 0 || a->slots[i].started < a->slots[oldest].started))
            oldest = i;
    return oldest;
}

/* Frees the slot, its lines, numbers and payload put in fragment order into the output buffers. */
static void ais_join(nmea_ais_assembler *a, int slot, nmea_ais_assembled *out)
{
    nmea_ais_slot *s = &a->slots[slot];
    size_t i, k, used = 0;
    for (i = 1; i < s->n_parts; i++) /* insertion sort by number: at most nine */
        for (k = i; k > 0 && s->parts[k - 1].number > s->parts[k].number; k--) {
            nmea_ais_part swap = s->parts[k];
            s->parts[k] = s->parts[k - 1];
            s->parts[k - 1] = swap;
        }
    for (i = 0; i < s->n_parts; i++) {
        const nmea_ais_part *p = &s->parts[i];
        a->out_lines[i] = p->line;
        a->out_numbers[i] = p->number;
        memcpy(a->out_payload + used, s->payload + p->start, p->end - p->start);
        used += p->end - p->start;
    }
    out->lines = a->out_lines;
    out->numbers = a->out_numbers;
    out->n = s->n_parts;
    out->count = s->count;
    out->complete = false;
    out->payload = a->out_payload;
    out->payload_len = used;
    out->fill_bits = s->n_parts ? s->parts[s->n_parts - 1].fill_bits : 0;
    s->count = 0;
}

static void ais_give_up(nmea_ais_assembler *a, int slot, nmea_ais_done *done, void *context)
{
    nmea_ais_assembled out;
    ais_join(a, slot, &out);
    done(&out, context);
}

/* The fragment alone: complete (a message of one sentence) or given up. */
static void ais_alone(const nmea_ais_fragment *f, uint32_t line, bool complete, nmea_ais_done *done, void *context)
{
    nmea_ais_assembled out;
    out.lines = &line;
    out.numbers = &f->number;
    out.n = 1;
    out.count = f->count;
    out.complete = complete;
    out.payload = f->payload.ptr;
    out.payload_len = complete ? f->payload.len : 0;
    out.fill_bits = f->fill_bits;
    done(&out, context);
}

void nmea_ais_assembler_feed(nmea_ais_assembler *a, const nmea_ais_fragment *f, nmea_text tags, nmea_ais_done *done,
                             void *context)
{
    uint32_t line = a->lines++;
    char key[NMEA_AIS_KEY_CAPACITY];
    size_t key_len, i;
    int slot = -1, oldest;
    nmea_ais_slot *s;
    if (!f)
        return;
    a->seen++;
    while ((oldest = ais_oldest(a)) >= 0 && a->seen - a->slots[oldest].started >= a->lifetime)
        ais_give_up(a, oldest, done, context);
    if (f->count == 1) {
        ais_alone(f, line, true, done, context);
        return;
    }
    if (!ais_key(f, tags, key, &key_len)) {
        ais_alone(f, line, false, done, context);
        return;
    }
    for (i = 0; i < NMEA_AIS_SLOTS && slot < 0; i++)
        if (a->slots[i].count && a->slots[i].key_len == key_len && memcmp(a->slots[i].key, key, key_len) == 0)
            slot = (int)i;
    if (slot >= 0) {
        bool again = a->slots[slot].count != f->count;
        for (i = 0; i < a->slots[slot].n_parts; i++)
            again = again || a->slots[slot].parts[i].number == f->number;
        if (again) { /* a new message under the same key */
            ais_give_up(a, slot, done, context);
            slot = -1;
        }
    }
    if (slot < 0) {
        for (i = 0; i < NMEA_AIS_SLOTS && slot < 0; i++)
            if (!a->slots[i].count)
                slot = (int)i;
        if (slot < 0) {
            slot = ais_oldest(a);
            if (slot < 0) { /* no slot at all */
                ais_alone(f, line, false, done, context);
                return;
            }
            ais_give_up(a, slot, done, context);
        }
        s = &a->slots[slot];
        memcpy(s->key, key, key_len);
        s->key_len = key_len;
        s->count = f->count;
        s->started = a->seen;
        s->n_parts = 0;
    }
    s = &a->slots[slot];
    {
        size_t start = s->n_parts ? s->parts[s->n_parts - 1].end : 0;
        nmea_ais_part *p = &s->parts[s->n_parts];
        if (f->payload.len > NMEA_AIS_CAPACITY - start) {
            if (s->n_parts)
                ais_give_up(a, slot, done, context);
            else
                s->count = 0; /* a message that never started */
            ais_alone(f, line, false, done, context);
            return;
        }
        memcpy(s->payload + start, f->payload.ptr, f->payload.len);
        p->number = f->number;
        p->line = line;
        p->fill_bits = f->fill_bits;
        p->start = start;
        p->end = start + f->payload.len;
        s->n_parts++;
    }
    if (s->n_parts == s->count) {
        nmea_ais_assembled out;
        ais_join(a, slot, &out);
        out.complete = true;
        done(&out, context);
    }
}

void nmea_ais_assembler_finish(nmea_ais_assembler *a, nmea_ais_done *done, void *context)
{
    int oldest;
    while ((oldest = ais_oldest(a)) >= 0)
        ais_give_up(a, oldest, done, context);
}

size_t nmea_ais_incomplete_message(const nmea_ais_assembled *done, char *buf, size_t cap)
{
    char text[64];
    size_t len = 0, k, missing = 0;
    unsigned n;
    text[0] = '\0';
    for (n = 1; n <= done->count; n++) {
        bool came = false;
        for (k = 0; k < done->n; k++)
            came = came || done->numbers[k] == n;
        if (!came)
            len += (size_t)snprintf(text + len, sizeof text - len, "%s%u", missing++ ? ", " : "", n);
    }
    return (size_t)snprintf(buf, cap, "fragment%s %s of %u never came", missing > 1 ? "s" : "", text,
                            (unsigned)done->count);
}
