/* RTCM 3: the frame, the bit reader and writer over bytes, characters and JSON (see rtcm3.h). */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *nmea_rtcm3_error_kind_name(nmea_rtcm3_error_kind kind)
{
    static const char *const names[] = {"ok",           "bad_sync",      "short_frame", "long_frame",
                                        "bad_checksum", "short_payload", "bad_value"};
    return (unsigned)kind < sizeof names / sizeof names[0] ? names[kind] : "bad_value";
}

static bool rtcm3_fail(nmea_rtcm3_error *err, nmea_rtcm3_error_kind kind, int message_number, const char *field)
{
    err->kind = kind;
    err->message_number = message_number;
    err->field = field;
    return false;
}

uint32_t nmea_rtcm3_crc24q(const uint8_t *data, size_t len)
{
    uint32_t crc = 0;
    size_t i;
    int bit;
    for (i = 0; i < len; i++) {
        crc ^= (uint32_t)data[i] << 16;
        for (bit = 0; bit < 8; bit++)
            crc = crc & 0x800000u ? (crc << 1) ^ 0x1864CFBu : crc << 1;
    }
    return crc & 0xFFFFFFu;
}

bool nmea_rtcm3_payload_of(const uint8_t *frame, size_t len, const uint8_t **payload, size_t *payload_len,
                           nmea_rtcm3_error *err)
{
    size_t size;
    uint32_t sent, computed;
    if (!len || frame[0] != 0xD3) {
        rtcm3_fail(err, NMEA_RTCM3_BAD_SYNC, -1, NULL);
        if (len)
            snprintf(err->message, sizeof err->message, "an RTCM 3 frame starts with D3, not %02X", frame[0]);
        else
            snprintf(err->message, sizeof err->message, "an RTCM 3 frame starts with D3, not nothing");
        return false;
    }
    if (len < 6) {
        snprintf(err->message, sizeof err->message, "a frame takes at least 6 bytes, there are %zu", len);
        return rtcm3_fail(err, NMEA_RTCM3_SHORT_FRAME, -1, NULL);
    }
    size = 3 + ((size_t)(frame[1] & 0x03) << 8 | frame[2]) + 3;
    if (len != size) {
        snprintf(err->message, sizeof err->message, "the length field says %zu bytes, the frame has %zu", size, len);
        return rtcm3_fail(err, len < size ? NMEA_RTCM3_SHORT_FRAME : NMEA_RTCM3_LONG_FRAME, -1, NULL);
    }
    sent = (uint32_t)frame[size - 3] << 16 | (uint32_t)frame[size - 2] << 8 | frame[size - 1];
    computed = nmea_rtcm3_crc24q(frame, size - 3);
    if (sent != computed) {
        snprintf(err->message, sizeof err->message, "checksum %02X %02X %02X, computed %02X %02X %02X",
                 (unsigned)(sent >> 16), (unsigned)(sent >> 8 & 0xFF), (unsigned)(sent & 0xFF),
                 (unsigned)(computed >> 16), (unsigned)(computed >> 8 & 0xFF), (unsigned)(computed & 0xFF));
        return rtcm3_fail(err, NMEA_RTCM3_BAD_CHECKSUM, -1, NULL);
    }
    *payload = frame + 3;
    *payload_len = size - 6;
    return true;
}

/* The `width` bits (at most 64) at bit `offset` of `data`, most significant first. */
static uint64_t rtcm3_raw(const uint8_t *data, size_t offset, size_t width)
{
    uint64_t raw = 0;
    size_t pos = offset, end = offset + width;
    while (pos < end) {
        size_t in_byte = pos % 8, take = 8 - in_byte < end - pos ? 8 - in_byte : end - pos;
        unsigned chunk = (unsigned)(data[pos / 8] >> (8 - in_byte - take)) & ((1u << take) - 1);
        raw = raw << take | chunk;
        pos += take;
    }
    return raw;
}

static void rtcm3_reader_init(nmea_rtcm3_reader *r, const uint8_t *payload, size_t len, int message_number,
                              nmea_rtcm3_error *err)
{
    r->data = payload;
    r->pos = 0;
    r->end = 8 * len;
    r->message_number = message_number;
    r->err = err;
}

static size_t rtcm3_remaining(const nmea_rtcm3_reader *r)
{
    return r->end - r->pos;
}

static bool rtcm3_check(nmea_rtcm3_reader *r, size_t offset, size_t width, const char *field)
{
    if (offset + width <= r->end)
        return true;
    snprintf(r->err->message, sizeof r->err->message, "%s needs bits %zu-%zu, the payload has %zu", field, offset,
             offset + width - 1, r->end);
    return rtcm3_fail(r->err, NMEA_RTCM3_SHORT_PAYLOAD, r->message_number, field);
}

static bool rtcm3_peek(nmea_rtcm3_reader *r, size_t offset, size_t width, const char *field, uint64_t *out)
{
    if (!rtcm3_check(r, offset, width, field))
        return false;
    *out = rtcm3_raw(r->data, offset, width);
    return true;
}

static bool rtcm3_take(nmea_rtcm3_reader *r, size_t width, const char *field, uint64_t *out)
{
    if (!rtcm3_peek(r, r->pos, width, field, out))
        return false;
    r->pos += width;
    return true;
}

/* Two's complement. */
static bool rtcm3_take_signed(nmea_rtcm3_reader *r, size_t width, const char *field, int64_t *out)
{
    uint64_t raw;
    if (!rtcm3_take(r, width, field, &raw))
        return false;
    *out = raw >> (width - 1) ? (int64_t)(raw - ((uint64_t)1 << (width - 1))) - ((int64_t)1 << (width - 1))
                              : (int64_t)raw;
    return true;
}

/* Sign and magnitude: the number, or its negative zero as the bits sent (1 << (width - 1)). */
static bool rtcm3_take_smag(nmea_rtcm3_reader *r, size_t width, const char *field, int64_t *out)
{
    uint64_t raw, sign = (uint64_t)1 << (width - 1);
    if (!rtcm3_take(r, width, field, &raw))
        return false;
    *out = raw & sign && raw != sign ? -(int64_t)(raw & (sign - 1)) : (int64_t)raw;
    return true;
}

static bool rtcm3_take_bits(nmea_rtcm3_reader *r, size_t width, const char *field, nmea_rtcm3_bits *out)
{
    if (!rtcm3_check(r, r->pos, width, field))
        return false;
    out->data = r->data;
    out->offset = r->pos;
    out->len = width;
    r->pos += width;
    return true;
}

static nmea_rtcm3_bits rtcm3_rest(nmea_rtcm3_reader *r)
{
    nmea_rtcm3_bits bits;
    bits.data = r->data;
    bits.offset = r->pos;
    bits.len = r->end - r->pos;
    r->pos = r->end;
    return bits;
}

static size_t rtcm3_count_ones(nmea_rtcm3_bits bits)
{
    size_t i, n = 0;
    for (i = 0; i < bits.len; i++)
        n += (size_t)rtcm3_raw(bits.data, bits.offset + i, 1);
    return n;
}

static size_t rtcm3_ones(uint64_t mask)
{
    size_t n = 0;
    for (; mask; mask &= mask - 1)
        n++;
    return n;
}

/* How many entries of `width` bits a group counted by a field or by mask bits holds: `count`,
   when the bits left hold them (else short_payload) and its array holds them (else bad_value). */
static bool rtcm3_counted(nmea_rtcm3_reader *r, size_t count, size_t max, size_t width, const char *field,
                          size_t *out)
{
    size_t left = rtcm3_remaining(r);
    if (count * width > left) {
        snprintf(r->err->message, sizeof r->err->message, "%s needs %zu entries of %zu bits, %zu bits left", field,
                 count, width, left);
        return rtcm3_fail(r->err, NMEA_RTCM3_SHORT_PAYLOAD, r->message_number, field);
    }
    if (count > max) {
        snprintf(r->err->message, sizeof r->err->message, "%s has %zu entries, at most %zu", field, count, max);
        return rtcm3_fail(r->err, NMEA_RTCM3_BAD_VALUE, r->message_number, field);
    }
    *out = count;
    return true;
}

static void rtcm3_writer_init(nmea_rtcm3_writer *w, int message_number, nmea_rtcm3_error *err)
{
    memset(w->bytes, 0, sizeof w->bytes);
    w->len = 0;
    w->message_number = message_number;
    w->err = err;
}

static bool rtcm3_put_raw(nmea_rtcm3_writer *w, uint64_t raw, size_t width, const char *field)
{
    size_t left = width;
    if (w->len + width > 8 * NMEA_RTCM3_MAX_PAYLOAD) {
        snprintf(w->err->message, sizeof w->err->message, "%s does not fit in a payload of %d bytes", field,
                 NMEA_RTCM3_MAX_PAYLOAD);
        return rtcm3_fail(w->err, NMEA_RTCM3_BAD_VALUE, w->message_number, field);
    }
    while (left > 0) {
        size_t in_byte = w->len % 8, put = 8 - in_byte < left ? 8 - in_byte : left;
        unsigned chunk = (unsigned)(raw >> (left - put)) & ((1u << put) - 1);
        w->bytes[w->len / 8] |= (uint8_t)(chunk << (8 - in_byte - put));
        w->len += put;
        left -= put;
    }
    return true;
}

static bool rtcm3_too_wide(nmea_rtcm3_writer *w, long long value, size_t width, const char *field)
{
    snprintf(w->err->message, sizeof w->err->message, "%s takes a raw value of %zu bits, not %lld", field, width,
             value);
    return rtcm3_fail(w->err, NMEA_RTCM3_BAD_VALUE, w->message_number, field);
}

static bool rtcm3_put(nmea_rtcm3_writer *w, uint64_t raw, size_t width, const char *field)
{
    if (width < 64 && raw >> width)
        return rtcm3_too_wide(w, (long long)raw, width, field);
    return rtcm3_put_raw(w, raw, width, field);
}

static bool rtcm3_put_signed(nmea_rtcm3_writer *w, int64_t value, size_t width, const char *field)
{
    int64_t low = -((int64_t)1 << (width - 1)), high = ((int64_t)1 << (width - 1)) - 1;
    if (value < low || value > high)
        return rtcm3_too_wide(w, (long long)value, width, field);
    return rtcm3_put_raw(w, (uint64_t)value & (((uint64_t)1 << width) - 1), width, field);
}

/* Sign and magnitude; 1 << (width - 1) writes the negative zero. */
static bool rtcm3_put_smag(nmea_rtcm3_writer *w, int64_t value, size_t width, const char *field)
{
    uint64_t sign = (uint64_t)1 << (width - 1);
    uint64_t magnitude = value < 0 ? (uint64_t)0 - (uint64_t)value : (uint64_t)value;
    if ((uint64_t)value == sign)
        return rtcm3_put_raw(w, sign, width, field);
    if (magnitude >= sign)
        return rtcm3_too_wide(w, (long long)value, width, field);
    return rtcm3_put_raw(w, value < 0 ? sign | magnitude : magnitude, width, field);
}

static bool rtcm3_put_bits(nmea_rtcm3_writer *w, nmea_rtcm3_bits bits, const char *field)
{
    size_t start;
    for (start = 0; start < bits.len; start += 64) {
        size_t width = bits.len - start < 64 ? bits.len - start : 64;
        if (!rtcm3_put_raw(w, rtcm3_raw(bits.data, bits.offset + start, width), width, field))
            return false;
    }
    return true;
}

/* Bits of a field counted by another: as many `units` of `unit_bits` as the count says. */
static bool rtcm3_put_counted(nmea_rtcm3_writer *w, nmea_rtcm3_bits bits, size_t units, size_t unit_bits,
                              const char *field)
{
    if (bits.len != units * unit_bits) {
        snprintf(w->err->message, sizeof w->err->message, "%s takes %zu units, as its count says, not %zu bits",
                 field, units, bits.len);
        return rtcm3_fail(w->err, NMEA_RTCM3_BAD_VALUE, w->message_number, field);
    }
    return rtcm3_put_bits(w, bits, field);
}

/* A group of `len` entries whose masks' bits set say `count`. */
static bool rtcm3_entries_said(nmea_rtcm3_writer *w, size_t len, size_t count, const char *field)
{
    if (len == count)
        return true;
    snprintf(w->err->message, sizeof w->err->message, "%s has %zu entries, its masks' bits set say %zu", field, len,
             count);
    return rtcm3_fail(w->err, NMEA_RTCM3_BAD_VALUE, w->message_number, field);
}

/* A field a case of a choice has that the message leaves out. */
static bool rtcm3_missing(nmea_rtcm3_writer *w, const char *field)
{
    snprintf(w->err->message, sizeof w->err->message, "%s is missing: the message's case of its layout has it",
             field);
    return rtcm3_fail(w->err, NMEA_RTCM3_BAD_VALUE, w->message_number, field);
}

static void rtcm3_json_put(nmea_rtcm3_json_out *j, const char *text, size_t len)
{
    if (j->len < j->cap)
        memcpy(j->buf + j->len, text, j->len + len < j->cap ? len : j->cap - j->len);
    j->len += len;
    if (j->cap)
        j->buf[j->len < j->cap ? j->len : j->cap - 1] = '\0';
}

static void rtcm3_json_puts(nmea_rtcm3_json_out *j, const char *text)
{
    rtcm3_json_put(j, text, strlen(text));
}

static void rtcm3_json_open(nmea_rtcm3_json_out *j)
{
    rtcm3_json_puts(j, "{");
    j->empty = true;
}

static void rtcm3_json_close(nmea_rtcm3_json_out *j)
{
    rtcm3_json_puts(j, "}");
    j->empty = false;
}

static void rtcm3_json_key(nmea_rtcm3_json_out *j, const char *name)
{
    if (!j->empty)
        rtcm3_json_puts(j, ",");
    j->empty = false;
    rtcm3_json_puts(j, "\"");
    rtcm3_json_puts(j, name);
    rtcm3_json_puts(j, "\":");
}

static void rtcm3_json_int(nmea_rtcm3_json_out *j, const char *name, long long value)
{
    char text[24];
    rtcm3_json_key(j, name);
    rtcm3_json_put(j, text, (size_t)snprintf(text, sizeof text, "%lld", value));
}

static void rtcm3_json_uint(nmea_rtcm3_json_out *j, const char *name, unsigned long long value)
{
    char text[24];
    rtcm3_json_key(j, name);
    rtcm3_json_put(j, text, (size_t)snprintf(text, sizeof text, "%llu", value));
}

static void rtcm3_json_flag(nmea_rtcm3_json_out *j, const char *name, bool value)
{
    rtcm3_json_key(j, name);
    rtcm3_json_puts(j, value ? "true" : "false");
}

static void rtcm3_json_string(nmea_rtcm3_json_out *j, const char *name, const char *value)
{
    rtcm3_json_key(j, name);
    rtcm3_json_puts(j, "\"");
    rtcm3_json_puts(j, value);
    rtcm3_json_puts(j, "\"");
}

/* Bits as the text of their values ("0110"). */
static void rtcm3_json_bits(nmea_rtcm3_json_out *j, const char *name, nmea_rtcm3_bits bits)
{
    size_t i;
    rtcm3_json_key(j, name);
    rtcm3_json_puts(j, "\"");
    for (i = 0; i < bits.len; i++)
        rtcm3_json_puts(j, rtcm3_raw(bits.data, bits.offset + i, 1) ? "1" : "0");
    rtcm3_json_puts(j, "\"");
}

/* A character (a code point) in a JSON string as Python's json.dumps writes it: ASCII only. */
static void rtcm3_json_char(nmea_rtcm3_json_out *j, uint32_t ch)
{
    char text[16];
    switch (ch) {
    case '"': rtcm3_json_puts(j, "\\\""); return;
    case '\\': rtcm3_json_puts(j, "\\\\"); return;
    case '\n': rtcm3_json_puts(j, "\\n"); return;
    case '\r': rtcm3_json_puts(j, "\\r"); return;
    case '\t': rtcm3_json_puts(j, "\\t"); return;
    case '\b': rtcm3_json_puts(j, "\\b"); return;
    case '\f': rtcm3_json_puts(j, "\\f"); return;
    default: break;
    }
    if (ch >= 0x20 && ch < 0x7F) {
        text[0] = (char)ch;
        rtcm3_json_put(j, text, 1);
    } else if (ch >= 0x10000) {
        ch -= 0x10000;
        rtcm3_json_put(j, text, (size_t)snprintf(text, sizeof text, "\\u%04x\\u%04x", (unsigned)(0xD800 + (ch >> 10)),
                                                 (unsigned)(0xDC00 + (ch & 0x3FF))));
    } else
        rtcm3_json_put(j, text, (size_t)snprintf(text, sizeof text, "\\u%04x", (unsigned)ch));
}

/* Characters as sent: ISO 8859-1, or (utf8) UTF-8 code units, a byte that is no UTF-8 as its
   surrogate escape \udcXX (Python's surrogateescape). */
static void rtcm3_json_chars(nmea_rtcm3_json_out *j, const char *name, nmea_rtcm3_bits bits, bool utf8)
{
    size_t n = bits.len / 8, at = 0, k;
    rtcm3_json_key(j, name);
    rtcm3_json_puts(j, "\"");
    while (at < n) {
        unsigned first = (unsigned)rtcm3_raw(bits.data, bits.offset + 8 * at, 8);
        size_t more = first < 0x80 ? 0 : first >= 0xC2 && first <= 0xDF ? 1 : first >= 0xE0 && first <= 0xEF ? 2
                    : first >= 0xF0 && first <= 0xF4 ? 3 : 4;
        uint32_t ch = first;
        bool whole = true;
        if (!utf8 || more == 0) {
            rtcm3_json_char(j, first);
            at++;
            continue;
        }
        if (more == 4 || at + more >= n)
            whole = false;
        for (k = 1; whole && k <= more; k++) {
            unsigned next = (unsigned)rtcm3_raw(bits.data, bits.offset + 8 * (at + k), 8);
            if ((next & 0xC0) != 0x80)
                whole = false;
            ch = ch << 6 | (next & 0x3F);
        }
        if (whole) {
            ch &= more == 1 ? 0x7FFu : more == 2 ? 0xFFFFu : 0x1FFFFFu;
            /* overlong, surrogate or beyond U+10FFFF: no UTF-8 */
            if ((more == 2 && (ch < 0x800 || (ch >= 0xD800 && ch <= 0xDFFF))) ||
                (more == 3 && (ch < 0x10000 || ch > 0x10FFFF)))
                whole = false;
        }
        if (whole) {
            rtcm3_json_char(j, ch);
            at += more + 1;
        } else {
            char text[8];
            rtcm3_json_put(j, text, (size_t)snprintf(text, sizeof text, "\\udc%02x", first));
            at++;
        }
    }
    rtcm3_json_puts(j, "\"");
}

#include "repr.c"

static void rtcm3_json_float(nmea_rtcm3_json_out *j, double value)
{
    char text[NMEA_REPR_SIZE];
    nmea_repr_double(value, text);
    rtcm3_json_puts(j, text);
}

/* The special value of `raw` among `specials`, NULL for a number. */
static const char *rtcm3_special(int64_t raw, const nmea_rtcm3_special *specials, size_t count)
{
    size_t i;
    for (i = 0; i < count; i++)
        if (specials[i].raw == raw)
            return specials[i].id;
    return NULL;
}

/* A number's members: its value (`raw / divisor`, a float when `real`) or special value's id,
   then its raw integer (`raw_always`: also beside a value; else beside a special value only). */
static void rtcm3_json_reading(nmea_rtcm3_json_out *j, const char *name, int64_t raw, double divisor, bool real,
                               const nmea_rtcm3_special *specials, size_t count, bool raw_always)
{
    char raw_name[64];
    const char *special = rtcm3_special(raw, specials, count);
    if (special)
        rtcm3_json_string(j, name, special);
    else if (real) {
        rtcm3_json_key(j, name);
        rtcm3_json_float(j, (double)raw / divisor);
    } else
        rtcm3_json_int(j, name, (long long)raw);
    if (!special && !raw_always)
        return;
    snprintf(raw_name, sizeof raw_name, "%s_raw", name);
    rtcm3_json_int(j, raw_name, (long long)raw);
}

static void rtcm3_json_unknown(nmea_rtcm3_json_out *j, const nmea_rtcm3_unknown *m)
{
    size_t i;
    char hex[3];
    rtcm3_json_key(j, "message");
    rtcm3_json_puts(j, "null");
    if (m->message_number >= 0)
        rtcm3_json_int(j, "message_number", m->message_number);
    else {
        rtcm3_json_key(j, "message_number");
        rtcm3_json_puts(j, "null");
    }
    rtcm3_json_key(j, "payload");
    rtcm3_json_puts(j, "\"");
    for (i = 0; i < m->len; i++)
        rtcm3_json_put(j, hex, (size_t)snprintf(hex, sizeof hex, "%02x", m->payload[i]));
    rtcm3_json_puts(j, "\"");
}

size_t nmea_rtcm3_error_json(const nmea_rtcm3_error *err, char *buf, size_t cap)
{
    nmea_rtcm3_json_out j;
    char address[32];
    const char *p;
    j.buf = buf;
    j.cap = cap;
    j.len = 0;
    if (err->message_number >= 0)
        snprintf(address, sizeof address, "RTCM3 %d", err->message_number);
    else
        strcpy(address, "RTCM3");
    rtcm3_json_open(&j);
    rtcm3_json_string(&j, "kind", nmea_rtcm3_error_kind_name(err->kind));
    rtcm3_json_string(&j, "address", address);
    rtcm3_json_key(&j, "field");
    rtcm3_json_puts(&j, "null");
    if (err->field)
        rtcm3_json_string(&j, "name", err->field);
    else {
        rtcm3_json_key(&j, "name");
        rtcm3_json_puts(&j, "null");
    }
    rtcm3_json_key(&j, "message");
    rtcm3_json_puts(&j, "\"");
    for (p = err->message; *p; p++) {
        if (*p == '"' || *p == '\\')
            rtcm3_json_puts(&j, "\\");
        rtcm3_json_put(&j, p, 1);
    }
    rtcm3_json_puts(&j, "\"");
    rtcm3_json_close(&j);
    return j.len;
}
