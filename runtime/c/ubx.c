/* UBX messages: the frame, the descriptors' reader, writer and JSON (see ubx.h). */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *nmea_ubx_error_kind_name(nmea_ubx_error_kind kind)
{
    static const char *const names[] = {"ok",         "bad_frame",        "bad_checksum", "short_payload",
                                        "too_many_entries", "bad_value", "no_room"};
    return names[kind];
}

static bool ubx_fail(nmea_ubx_error *err, nmea_ubx_error_kind kind, const char *message, const char *field)
{
    err->kind = kind;
    err->message = message;
    err->field = field;
    return false;
}

/* Two, four and eight bytes at `p`, little endian (the generated fast readers'; one load each
   where the host is little endian). */
static inline uint16_t ubx_u16(const uint8_t *p)
{
    return (uint16_t)(p[0] | p[1] << 8);
}

static inline uint32_t ubx_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static inline uint64_t ubx_u64(const uint8_t *p)
{
    return (uint64_t)ubx_u32(p) | (uint64_t)ubx_u32(p + 4) << 32;
}

/* Fletcher-8 over `len` bytes (UBX-13003221, "UBX checksum"): CK_A in the low byte. The sums
   wrap modulo a power of two at least 256 (unsigned arithmetic), so their low bytes are the sums
   modulo 256 without a mask a byte. A 64-bit host takes eight bytes a step as four 16-bit lanes
   of even bytes and four of odd ones, each lane its own A (the sum of its bytes) and B (the sum of
   the A of every step before), two steps at a time (the second's B takes the first's bytes). A
   lane holds 16 bits: the lanes are brought back modulo 256 (a mask, so that no lane carries into
   the next) every 112 bytes, before B's could outgrow them. The bytes after the last whole step
   are the last eight bytes' word shifted down: a step of those bytes followed by `pad` zeros,
   which add nothing to A and `pad` times A to B, taken off at the end. At the end A is the lanes'
   sum, and B eight times their B plus each lane's A weighted by the running values of its step
   that a byte in its place is in (8 for the first byte of a step, 7, ..., 1 for the last): weighted
   sums of lanes as the top lane of a multiplication (the bench's UBX decode: about half the
   instructions of a step of eight bytes masked every step with the last bytes one by one). Else
   four bytes a step, B taking A's four running values at once. Neither waits on a chain of one
   addition a byte. */
static unsigned ubx_checksum(const uint8_t *p, size_t len)
{
    size_t i = 0;
#if SIZE_MAX > 0xFFFFFFFFu
    const uint64_t lanes = UINT64_C(0x00FF00FF00FF00FF);
    uint64_t even = 0, odd = 0, before = 0, a, b, w, v, pad = 0;
    size_t stop;
    while (len - i >= 16) {
        stop = len - i >= 112 ? i + 112 : i + ((len - i) & ~(size_t)15);
        for (; i < stop; i += 16) { /* two steps: the second's B takes the first's lanes */
            w = ubx_u64(p + i);
            v = ubx_u64(p + i + 8);
            before += 2 * (even + odd) + (w & lanes) + (w >> 8 & lanes);
            even += (w & lanes) + (v & lanes);
            odd += (w >> 8 & lanes) + (v >> 8 & lanes);
        }
        before &= lanes;
        even &= lanes;
        odd &= lanes;
    }
    if (len >= 8) {
        if (len - i >= 8) { /* one step */
            w = ubx_u64(p + i);
            before = (before + even + odd) & lanes;
            even = (even + (w & lanes)) & lanes;
            odd = (odd + (w >> 8 & lanes)) & lanes;
            i += 8;
        }
        if (i < len) { /* the last bytes, as a step padded with zeros */
            pad = 8 - (len - i);
            w = ubx_u64(p + len - 8) >> 8 * pad;
            before = (before + even + odd) & lanes;
            even = (even + (w & lanes)) & lanes;
            odd = (odd + (w >> 8 & lanes)) & lanes;
            i = len;
        }
    }
    a = (even + odd) * UINT64_C(0x0001000100010001) >> 48;
    b = 8 * (before * UINT64_C(0x0001000100010001) >> 48) + (even * UINT64_C(0x0008000600040002) >> 48) +
        (odd * UINT64_C(0x0007000500030001) >> 48) - pad * a;
#else
    unsigned a = 0, b = 0;
    for (; i + 4 <= len; i += 4) {
        unsigned x0 = p[i], x1 = p[i + 1], x2 = p[i + 2], x3 = p[i + 3];
        b += 4 * a + 4 * x0 + 3 * x1 + 2 * x2 + x3;
        a += x0 + x1 + x2 + x3;
    }
#endif
    for (; i < len; i++) { /* under eight bytes (a 64-bit host); the last of a four-byte step (else) */
        a += p[i];
        b += a;
    }
    return (unsigned)(a & 0xFF) | (unsigned)(b & 0xFF) << 8;
}

/* The `n` bytes (at most 8) at `p`, little endian (the common widths spelt out: a compiler reads
   them with one load where the host is little endian). */
static uint64_t ubx_le(const uint8_t *p, size_t n)
{
    uint64_t raw = 0;
    switch (n) {
    case 1:
        return p[0];
    case 2:
        return ubx_u16(p);
    case 4:
        return ubx_u32(p);
    case 8:
        return ubx_u64(p);
    default:
        while (n-- > 0)
            raw = raw << 8 | p[n];
        return raw;
    }
}

/* The `n` bytes (at most 8) at `p`, big endian (SkyTraq, SiRF). */
static uint64_t ubx_be(const uint8_t *p, size_t n)
{
    uint64_t raw = 0;
    size_t i;
    for (i = 0; i < n; i++)
        raw = raw << 8 | p[i];
    return raw;
}

/* The checksum of `len` bytes as the frame sends it, read as a big-endian number. */
static unsigned long ubx_check(nmea_ubx_check kind, const uint8_t *p, size_t len)
{
    unsigned long sum = 0;
    unsigned sums;
    size_t i;
    switch (kind) {
    case NMEA_UBX_CHECK_FLETCHER8:
        sums = ubx_checksum(p, len);
        return (unsigned long)(sums & 0xFF) << 8 | sums >> 8;
    case NMEA_UBX_CHECK_XOR8:
        for (i = 0; i < len; i++)
            sum ^= p[i];
        return sum;
    case NMEA_UBX_CHECK_SUM15:
        for (i = 0; i < len; i++)
            sum += p[i];
        return sum & 0x7FFF;
    case NMEA_UBX_CHECK_CRC16_CCITT: /* MSB first, no reflection; sent little endian */
        for (i = 0; i < len; i++) {
            unsigned bit;
            sum ^= (unsigned long)p[i] << 8;
            for (bit = 0; bit < 8; bit++)
                sum = (sum & 0x8000 ? sum << 1 ^ 0x1021 : sum << 1) & 0xFFFF;
        }
        return (sum & 0xFF) << 8 | sum >> 8;
    case NMEA_UBX_CHECK_CRC32: /* reflected 0xEDB88320, initial value 0, no final inversion; sent little endian
                                  (bitwise: decoding a message is not the stream framer's hot path) */
        for (i = 0; i < len; i++) {
            unsigned bit;
            sum ^= p[i];
            for (bit = 0; bit < 8; bit++)
                sum = sum & 1 ? sum >> 1 ^ 0xEDB88320ul : sum >> 1;
        }
        return (sum & 0xFF) << 24 | (sum >> 8 & 0xFF) << 16 | (sum >> 16 & 0xFF) << 8 | sum >> 24;
    default: /* SUM32: little-endian words, a short last one padded with zeros; sent little endian */
        for (i = 0; i < len; i++)
            sum = (sum + ((unsigned long)p[i] << 8 * (i & 3))) & 0xFFFFFFFFul;
        return (sum & 0xFF) << 24 | (sum >> 8 & 0xFF) << 16 | (sum >> 16 & 0xFF) << 8 | sum >> 24;
    }
}

/* A member of `member` bytes at `m` as an integer (signed: sign-extended). */
static uint64_t ubx_get(const uint8_t *m, unsigned member, bool is_signed)
{
    uint8_t u8;
    uint16_t u16;
    uint32_t u32;
    uint64_t u64;
    switch (member) {
    case 1:
        memcpy(&u8, m, 1);
        return is_signed ? (uint64_t)(int64_t)(int8_t)u8 : u8;
    case 2:
        memcpy(&u16, m, 2);
        return is_signed ? (uint64_t)(int64_t)(int16_t)u16 : u16;
    case 4:
        memcpy(&u32, m, 4);
        return is_signed ? (uint64_t)(int64_t)(int32_t)u32 : u32;
    default:
        memcpy(&u64, m, 8);
        return u64;
    }
}

static void ubx_set(uint8_t *m, unsigned member, uint64_t value)
{
    uint8_t u8 = (uint8_t)value;
    uint16_t u16 = (uint16_t)value;
    uint32_t u32 = (uint32_t)value;
    switch (member) {
    case 1:
        memcpy(m, &u8, 1);
        break;
    case 2:
        memcpy(m, &u16, 2);
        break;
    case 4:
        memcpy(m, &u32, 4);
        break;
    default:
        memcpy(m, &value, 8);
    }
}

/* `raw` of `bits` bits read as two's complement. */
static uint64_t ubx_sign(uint64_t raw, unsigned bits)
{
    return bits < 64 && raw >> (bits - 1) & 1 ? raw | ~(uint64_t)0 << bits : raw;
}

/* A payload being read. */
typedef struct {
    const uint8_t *p;
    size_t len, pos;
    const char *address;
    nmea_ubx_error *err;
    bool big; /* its protocol's fields are big endian */
} ubx_reader;

static bool ubx_short(ubx_reader *r, const char *field, size_t need)
{
    if (need == 1)
        snprintf(r->err->text, sizeof r->err->text, "%s needs byte %lu, the payload has %lu", field,
                 (unsigned long)r->pos, (unsigned long)r->len);
    else
        snprintf(r->err->text, sizeof r->err->text, "%s needs bytes %lu-%lu, the payload has %lu", field,
                 (unsigned long)r->pos, (unsigned long)(r->pos + need - 1), (unsigned long)r->len);
    return ubx_fail(r->err, NMEA_UBX_SHORT_PAYLOAD, r->address, field);
}

/* Whether an item is a part of the bitfield word before it. */
#define UBX_IS_PART(it) ((it)->kind >= NMEA_UBX_ITEM_PART && (it)->kind <= NMEA_UBX_ITEM_PART_FLAG)

/* Reads a part of bitfield word `word` into the struct at `m` (the readers' loops call it
   themselves: the most frequent item, read without ubx_read_field's call). */
static void ubx_read_part(const nmea_ubx_item *it, uint8_t *m, uint64_t word)
{
    uint8_t *at = m + it->offset;
    uint64_t raw = word >> it->low & (it->size < 64 ? ((uint64_t)1 << it->size) - 1 : ~(uint64_t)0);
    if (it->kind == NMEA_UBX_ITEM_PART_FLAG)
        *(bool *)(void *)at = raw != 0;
    else
        ubx_set(at, it->member, it->kind == NMEA_UBX_ITEM_PART_SIGNED ? ubx_sign(raw, it->size) : raw);
}

/* Reads one field (not a group, not a part) into the struct at `m`; `*word` is set to a number's
   raw value (a bitfield's word, whose parts follow it). False with the error set; `*done` set when
   an optional field is missing (nothing after it is read). */
static bool ubx_read_field(ubx_reader *r, const nmea_ubx_item *it, uint8_t *m, uint64_t *word, bool *done)
{
    uint8_t *at = m + it->offset;
    size_t left = r->len - r->pos;
    uint64_t raw;
    if (it->kind == NMEA_UBX_ITEM_VIEW) {
        nmea_ubx_bytes view;
        view.ptr = r->p + r->pos;
        view.len = left > it->after ? left - it->after : 0;
        memcpy(at, &view, sizeof view);
        r->pos += view.len;
        return true;
    }
    if (it->size > left) {
        if (it->optional) {
            *done = true;
            return true;
        }
        return ubx_short(r, it->id, it->size);
    }
    if (it->optional)
        *(bool *)(void *)(m + it->has) = true;
    if (it->kind == NMEA_UBX_ITEM_ARRAY) {
        memcpy(at, r->p + r->pos, it->size);
    } else {
        raw = r->big ? ubx_be(r->p + r->pos, it->size) : ubx_le(r->p + r->pos, it->size);
        if (it->kind == NMEA_UBX_ITEM_FLOAT && it->size == 4) {
            uint32_t bits = (uint32_t)raw;
            memcpy(at, &bits, 4); /* a float's bits, as sent (a NaN's too) */
        } else if (it->kind == NMEA_UBX_ITEM_FLOAT) {
            memcpy(at, &raw, 8);
        } else {
            ubx_set(at, it->member, it->kind == NMEA_UBX_ITEM_SIGNED ? ubx_sign(raw, 8u * it->size) : raw);
        }
        *word = raw;
    }
    r->pos += it->size;
    return true;
}

/* Reads the entries of group `g` (the item `id`) into the array at `array` from its index `done`
   on, and stores their number at `*read`: `owner` holds the member its count names (the message,
   or the entry whose nested group it is), `m` the message (its stride, the nested group's array).
   An entry's fields are read within its stride's bytes (a stride's last item, a view, takes those
   after the fields), then the entries of its nested group, if any (the reader recurses that once:
   a nested group holds fields only, rule B010). False with the error set. */
static bool ubx_read_group(ubx_reader *r, const char *id, const nmea_ubx_group *g, uint8_t *m, const uint8_t *owner,
                           uint8_t *array, size_t done, size_t *read)
{
    size_t left = r->len - r->pos, count, stride, len = r->len, k, f, nested = 0;
    /* a stride (SBF's SBLength): each entry is that many bytes, at least its fields' */
    stride = g->stride_member ? (size_t)ubx_get(m + g->stride_offset, g->stride_member, false) : g->entry_bytes;
    count = g->count_kind == NMEA_UBX_COUNT_FIXED   ? g->count
            : g->count_kind == NMEA_UBX_COUNT_FIELD ? (size_t)ubx_get(owner + g->count_offset, g->count_member, false)
                                                    : 1; /* counted below, the stride checked first */
    if (count && stride < g->entry_bytes) { /* (the stride of no entry says nothing) */
        snprintf(r->err->text, sizeof r->err->text, "%s is %lu, an entry of %s takes at least %u bytes", g->stride_id,
                 (unsigned long)stride, id, (unsigned)g->entry_bytes);
        return ubx_fail(r->err, NMEA_UBX_BAD_VALUE, r->address, g->stride_id);
    }
    if (g->count_kind == NMEA_UBX_COUNT_LEFT) {
        count = left > g->after ? (left - g->after) / stride : 0;
        if (count > g->limit)
            count = g->limit;
    }
    if (count < g->min || count * stride > left) {
        /* as Python says it: a group of the bytes left needs at least its least */
        bool at_least = g->count_kind == NMEA_UBX_COUNT_LEFT;
        snprintf(r->err->text, sizeof r->err->text, "%s needs %s%lu entries of %lu bits, %lu bits left", id,
                 at_least ? "at least " : "", (unsigned long)(at_least ? g->min : count), 8ul * (unsigned long)stride,
                 8ul * (unsigned long)left);
        return ubx_fail(r->err, NMEA_UBX_SHORT_PAYLOAD, r->address, id);
    }
    if (count > g->max - done) {
        snprintf(r->err->text, sizeof r->err->text, "%s has %lu entries, this build holds %u (NMEA_UBX_MAX_ENTRIES)", id,
                 (unsigned long)(done + count), (unsigned)g->max);
        return ubx_fail(r->err, NMEA_UBX_TOO_MANY, r->address, id);
    }
    memset(array + done * g->entry_size, 0, count * g->entry_size);
    for (k = 0; k < count; k++) {
        uint64_t entry_word = 0;
        bool ignored = false;
        uint8_t *entry = array + (done + k) * g->entry_size;
        size_t end = r->pos + stride;
        if (stride > len - r->pos) { /* (after a nested group's entries: the next entry cut) */
            snprintf(r->err->text, sizeof r->err->text, "%s needs %lu entries of %lu bits, %lu bits left", id,
                     (unsigned long)(count - k), 8ul * (unsigned long)stride, 8ul * (unsigned long)(len - r->pos));
            return ubx_fail(r->err, NMEA_UBX_SHORT_PAYLOAD, r->address, id);
        }
        r->len = end; /* the entry's bytes */
        for (f = 0; f < g->n_items; f++) {
            if (UBX_IS_PART(&g->items[f]))
                ubx_read_part(&g->items[f], entry, entry_word);
            else if (!ubx_read_field(r, &g->items[f], entry, &entry_word, &ignored)) {
                r->len = len;
                return false;
            }
        }
        r->len = len;
        r->pos = end;
#ifdef NMEA_UBX_NESTED
        if (g->nested) { /* its own entries, after its bytes, in the message's array of them */
            size_t got = 0;
            uint16_t first = (uint16_t)nested;
            memcpy(entry + g->nested_first, &first, sizeof first);
            if (!ubx_read_group(r, g->nested_id, g->nested, m, entry, m + g->nested_offset, nested, &got))
                return false;
            nested += got;
        }
#endif
    }
#ifdef NMEA_UBX_NESTED
    if (g->nested) {
        uint16_t stored = (uint16_t)nested;
        memcpy(m + g->nested->n_offset, &stored, sizeof stored);
    }
#endif
    (void)nested;
    *read = count;
    return true;
}

/* Reads a layout's `items` into the struct at `m`, a group's entries field by field. False with
   the error set. */
static bool ubx_read_items(ubx_reader *r, const nmea_ubx_item *items, size_t n, uint8_t *m)
{
    uint64_t word = 0;
    bool done = false;
    size_t i;
    for (i = 0; i < n && !done; i++) {
        const nmea_ubx_item *it = &items[i];
        const nmea_ubx_group *g = (const nmea_ubx_group *)it->extra;
        size_t count = 0;
        uint16_t stored;
        if (UBX_IS_PART(it)) {
            ubx_read_part(it, m, word);
            continue;
        }
        if (it->kind != NMEA_UBX_ITEM_GROUP) {
            if (!ubx_read_field(r, it, m, &word, &done))
                return false;
            continue;
        }
        if (!ubx_read_group(r, it->id, g, m, m, m + it->offset, 0, &count))
            return false;
        stored = (uint16_t)count;
        memcpy(m + g->n_offset, &stored, sizeof stored);
    }
    return true;
}

/* A payload being written after the frame's header bytes. */
typedef struct {
    uint8_t *buf;
    size_t cap, len;
    const char *address;
    nmea_ubx_error *err;
    bool big; /* its protocol's fields are big endian */
} ubx_writer;

static bool ubx_put(ubx_writer *w, const uint8_t *bytes, size_t n, const char *field)
{
    if (n > w->cap - w->len) {
        snprintf(w->err->text, sizeof w->err->text, "the frame needs more than the buffer's %lu bytes", (unsigned long)w->cap);
        return ubx_fail(w->err, NMEA_UBX_NO_ROOM, w->address, field);
    }
    memcpy(w->buf + w->len, bytes, n);
    w->len += n;
    return true;
}

/* A number of `n` bytes in the writer's byte order. */
static bool ubx_put_number(ubx_writer *w, uint64_t value, size_t n, const char *field)
{
    uint8_t bytes[8];
    size_t i;
    for (i = 0; i < n; i++)
        bytes[w->big ? n - 1 - i : i] = (uint8_t)(value >> 8 * i);
    return ubx_put(w, bytes, n, field);
}

static bool ubx_bad_value(ubx_writer *w, const char *field, unsigned bits)
{
    snprintf(w->err->text, sizeof w->err->text, "%s does not fit in %u bits", field, bits);
    return ubx_fail(w->err, NMEA_UBX_BAD_VALUE, w->address, field);
}

/* Whether `value` (sign-extended when `is_signed`) fits `bits` bits. */
static bool ubx_fits(uint64_t value, unsigned bits, bool is_signed)
{
    if (bits >= 64)
        return true;
    if (is_signed)
        return (int64_t)value >= -((int64_t)1 << (bits - 1)) && (int64_t)value < ((int64_t)1 << (bits - 1));
    return value >> bits == 0;
}

/* Writes field `items[i]` (not a group) of the struct at `m`: a bitfield word with its parts,
   which follow it, in their bits; a part is written with its word. */
static bool ubx_write_field(ubx_writer *w, const nmea_ubx_item *items, size_t n, size_t i, const uint8_t *m)
{
    const nmea_ubx_item *it = &items[i];
    const uint8_t *at = m + it->offset;
    uint64_t value = 0;
    size_t k;
    switch (it->kind) {
    case NMEA_UBX_ITEM_PART:
    case NMEA_UBX_ITEM_PART_SIGNED:
    case NMEA_UBX_ITEM_PART_FLAG:
        return true;
    case NMEA_UBX_ITEM_VIEW: {
        nmea_ubx_bytes view;
        memcpy(&view, at, sizeof view);
        return !view.len || ubx_put(w, view.ptr, view.len, it->id);
    }
    case NMEA_UBX_ITEM_ARRAY:
        return ubx_put(w, at, it->size, it->id);
    case NMEA_UBX_ITEM_FLOAT:
        if (it->size == 4) {
            uint32_t bits;
            memcpy(&bits, at, 4);
            value = bits;
        } else {
            memcpy(&value, at, 8);
        }
        return ubx_put_number(w, value, it->size, it->id);
    case NMEA_UBX_ITEM_WORD:
        /* The word with its parts' values in their bits; bits no part names stay as they are. */
        value = ubx_get(at, it->member, false);
        for (k = i + 1; k < n && items[k].kind >= NMEA_UBX_ITEM_PART && items[k].kind <= NMEA_UBX_ITEM_PART_FLAG; k++) {
            const nmea_ubx_item *part = &items[k];
            uint64_t mask = part->size < 64 ? ((uint64_t)1 << part->size) - 1 : ~(uint64_t)0;
            uint64_t bits = part->kind == NMEA_UBX_ITEM_PART_FLAG
                                ? *(const bool *)(const void *)(m + part->offset)
                                : ubx_get(m + part->offset, part->member, part->kind == NMEA_UBX_ITEM_PART_SIGNED);
            if (!ubx_fits(bits, part->size, part->kind == NMEA_UBX_ITEM_PART_SIGNED))
                return ubx_bad_value(w, part->id, part->size);
            value = (value & ~(mask << part->low)) | (bits & mask) << part->low;
        }
        return ubx_put_number(w, value, it->size, it->id);
    default:
        value = ubx_get(at, it->member, it->kind == NMEA_UBX_ITEM_SIGNED);
        if (!ubx_fits(value, 8u * it->size, it->kind == NMEA_UBX_ITEM_SIGNED))
            return ubx_bad_value(w, it->id, 8u * it->size);
        return ubx_put_number(w, value, it->size, it->id);
    }
}

/* Writes the entries `first` to `first + count - 1` of group `g` (the item `id`) of the array at
   `array` (`m`: the message): each entry's fields, of as many bytes as its stride says, then the
   entries of its nested group, if any (those its index and count member say, within the message's
   array of them). */
static bool ubx_write_group(ubx_writer *w, const char *id, const nmea_ubx_group *g, const uint8_t *m,
                            const uint8_t *array, size_t first, size_t count)
{
    size_t k, f;
    if (first + count > g->max) {
        snprintf(w->err->text, sizeof w->err->text, "%s has %lu entries, its array holds %u", id,
                 (unsigned long)(first + count), (unsigned)g->max);
        return ubx_fail(w->err, NMEA_UBX_BAD_VALUE, w->address, id);
    }
    for (k = first; k < first + count; k++) {
        const uint8_t *entry = array + k * g->entry_size;
        size_t start = w->len;
        for (f = 0; f < g->n_items; f++)
            if (!ubx_write_field(w, g->items, g->n_items, f, entry))
                return false;
        if (g->stride_member) { /* an entry of as many bytes as its stride says */
            uint64_t stride = ubx_get(m + g->stride_offset, g->stride_member, false);
            if (w->len - start != stride) {
                snprintf(w->err->text, sizeof w->err->text, "%s takes the bytes of each entry of %s (%lu), not %lu",
                         g->stride_id, id, (unsigned long)(w->len - start), (unsigned long)stride);
                return ubx_fail(w->err, NMEA_UBX_BAD_VALUE, w->address, g->stride_id);
            }
        }
#ifdef NMEA_UBX_NESTED
        if (g->nested) { /* its own entries: from its index on, as many as its count member says */
            const nmea_ubx_group *in = g->nested;
            uint16_t from, total;
            size_t n = (size_t)ubx_get(entry + in->count_offset, in->count_member, false);
            memcpy(&from, entry + g->nested_first, sizeof from);
            memcpy(&total, m + in->n_offset, sizeof total);
            if ((size_t)from + n > total || total > in->max) {
                snprintf(w->err->text, sizeof w->err->text, "%s has %u entries, an entry of %s names %lu from %u",
                         g->nested_id, (unsigned)total, id, (unsigned long)n, (unsigned)from);
                return ubx_fail(w->err, NMEA_UBX_BAD_VALUE, w->address, g->nested_id);
            }
            if (!ubx_write_group(w, g->nested_id, in, m, m + g->nested_offset, from, n))
                return false;
        }
#endif
    }
    return true;
}

/* Writes a layout's `items` of the struct at `m`, a group's entries field by field; stops at an
   optional field whose flag is false. */
static bool ubx_write_items(ubx_writer *w, const nmea_ubx_item *items, size_t n, const uint8_t *m)
{
    size_t i;
    for (i = 0; i < n; i++) {
        const nmea_ubx_item *it = &items[i];
        const nmea_ubx_group *g = (const nmea_ubx_group *)it->extra;
        uint16_t count;
        if (it->optional && !*(const bool *)(const void *)(m + it->has))
            return true;
        if (it->kind != NMEA_UBX_ITEM_GROUP) {
            if (!ubx_write_field(w, items, n, i, m))
                return false;
            continue;
        }
        memcpy(&count, m + g->n_offset, sizeof count);
        if (!ubx_write_group(w, it->id, g, m, m + it->offset, 0, count))
            return false;
    }
    return true;
}

/* JSON written into a caller's buffer; `len` counts what did not fit too. */
typedef struct {
    char *buf;
    size_t cap, len;
    bool empty;
} ubx_json_out;

static void ubx_json_put(ubx_json_out *j, const char *text, size_t len)
{
    if (j->len < j->cap)
        memcpy(j->buf + j->len, text, j->len + len < j->cap ? len : j->cap - j->len);
    j->len += len;
    if (j->cap)
        j->buf[j->len < j->cap ? j->len : j->cap - 1] = '\0';
}

static void ubx_json_puts(ubx_json_out *j, const char *text)
{
    ubx_json_put(j, text, strlen(text));
}

static void ubx_json_key(ubx_json_out *j, const char *name)
{
    if (!j->empty)
        ubx_json_puts(j, ",");
    j->empty = false;
    ubx_json_puts(j, "\"");
    ubx_json_puts(j, name);
    ubx_json_puts(j, "\":");
}

static void ubx_json_number(ubx_json_out *j, uint64_t value, bool is_signed)
{
    char text[24];
    ubx_json_put(j, text,
                 (size_t)(is_signed ? snprintf(text, sizeof text, "%lld", (long long)(int64_t)value)
                                    : snprintf(text, sizeof text, "%llu", (unsigned long long)value)));
}

#include "repr.c"

/* A float as Python's repr writes it; "nan", "inf", "-inf" as the strings Python's JSON of a
   payload gives. */
static void ubx_json_float(ubx_json_out *j, double value)
{
    char text[NMEA_REPR_SIZE];
    if (value != value || value - value != 0) {
        ubx_json_puts(j, value != value ? "\"nan\"" : value > 0 ? "\"inf\"" : "\"-inf\"");
        return;
    }
    nmea_repr_double(value, text);
    ubx_json_puts(j, text);
}

/* Characters (ISO 8859-1) as a JSON string: '"' and '\' escaped, the bytes outside 0x20-0x7E as
   Python's json.dumps writes them (\n, \u00e9). */
static void ubx_json_chars(ubx_json_out *j, const uint8_t *p, size_t len)
{
    static const char hex[] = "0123456789abcdef";
    size_t i;
    ubx_json_puts(j, "\"");
    for (i = 0; i < len; i++) {
        char esc[7] = {'\\', 'u', '0', '0', hex[p[i] >> 4], hex[p[i] & 15], 0};
        const char *named = p[i] == '"' ? "\\\"" : p[i] == '\\' ? "\\\\" : p[i] == '\n' ? "\\n" : p[i] == '\r' ? "\\r"
                                                   : p[i] == '\t' ? "\\t" : p[i] == '\b' ? "\\b" : p[i] == '\f' ? "\\f"
                                                                                                         : NULL;
        if (named)
            ubx_json_puts(j, named);
        else if (p[i] < 0x20 || p[i] > 0x7E)
            ubx_json_puts(j, esc);
        else
            ubx_json_put(j, (const char *)p + i, 1);
    }
    ubx_json_puts(j, "\"");
}

static void ubx_json_hex(ubx_json_out *j, const uint8_t *p, size_t len)
{
    static const char hex[] = "0123456789abcdef";
    size_t i;
    ubx_json_puts(j, "\"");
    for (i = 0; i < len; i++) {
        char pair[2];
        pair[0] = hex[p[i] >> 4];
        pair[1] = hex[p[i] & 15];
        ubx_json_put(j, pair, 2);
    }
    ubx_json_puts(j, "\"");
}

/* The decimal digits of a little-endian integer of `len` bytes (at most 32). */
static void ubx_json_big(ubx_json_out *j, const uint8_t *p, size_t len)
{
    uint8_t n[32];
    char digits[80];
    size_t i, count = 0;
    bool zero;
    memcpy(n, p, len);
    do { /* divide by 10, most significant byte first; the remainder is the next digit */
        unsigned rest = 0;
        zero = true;
        for (i = len; i-- > 0;) {
            unsigned cur = rest << 8 | n[i];
            n[i] = (uint8_t)(cur / 10);
            rest = cur % 10;
            zero = zero && n[i] == 0;
        }
        digits[count++] = (char)('0' + rest);
    } while (!zero);
    while (count-- > 0)
        ubx_json_put(j, &digits[count], 1);
}

/* The JSON member of field `it` (not a group) of the struct at `m`. */
static void ubx_json_field(ubx_json_out *j, const nmea_ubx_item *it, const uint8_t *m)
{
    const uint8_t *at = m + it->offset;
    bool is_signed = it->kind == NMEA_UBX_ITEM_SIGNED || it->kind == NMEA_UBX_ITEM_PART_SIGNED;
    uint64_t value;
    size_t k;
    ubx_json_key(j, it->id);
    switch (it->kind) {
    case NMEA_UBX_ITEM_VIEW: {
        nmea_ubx_bytes view;
        memcpy(&view, at, sizeof view);
        if (it->print == NMEA_UBX_PRINT_CHARS)
            ubx_json_chars(j, view.ptr, view.len);
        else
            ubx_json_hex(j, view.ptr, view.len);
        return;
    }
    case NMEA_UBX_ITEM_ARRAY:
        if (it->print == NMEA_UBX_PRINT_CHARS)
            ubx_json_chars(j, at, it->size);
        else if (it->print == NMEA_UBX_PRINT_HEX)
            ubx_json_hex(j, at, it->size);
        else
            ubx_json_big(j, at, it->size);
        return;
    case NMEA_UBX_ITEM_FLOAT:
        if (it->extra) { /* a special value (its bit pattern in the field's width): its id */
            const nmea_ubx_scale *s = (const nmea_ubx_scale *)it->extra;
            uint64_t bits = 0;
            if (it->size == 4) {
                uint32_t bits32;
                memcpy(&bits32, at, 4);
                bits = bits32;
            } else {
                memcpy(&bits, at, 8);
            }
            for (k = 0; k < s->n_specials; k++)
                if ((uint64_t)s->specials[k].raw == bits) {
                    ubx_json_puts(j, "\"");
                    ubx_json_puts(j, s->specials[k].id);
                    ubx_json_puts(j, "\"");
                    return;
                }
        }
        if (it->size == 4) {
            float f;
            memcpy(&f, at, 4);
            ubx_json_float(j, (double)f);
        } else {
            double d;
            memcpy(&d, at, 8);
            ubx_json_float(j, d);
        }
        return;
    case NMEA_UBX_ITEM_PART_FLAG:
        ubx_json_puts(j, *(const bool *)(const void *)at ? "true" : "false");
        return;
    default:
        break;
    }
    value = ubx_get(at, it->member, is_signed);
    if (it->print == NMEA_UBX_PRINT_CODE) { /* an enum's code: its id, or the number of one it does not name */
        const nmea_ubx_codes *codes = (const nmea_ubx_codes *)it->extra;
        const char *id = NULL;
        for (k = 0; k < codes->n && !id; k++)
            if (codes->codes[k].code == (int64_t)value)
                id = codes->codes[k].id;
        if (id) {
            ubx_json_puts(j, "\"");
            ubx_json_puts(j, id);
            ubx_json_puts(j, "\"");
        } else {
            ubx_json_number(j, value, is_signed);
        }
    } else if (it->print == NMEA_UBX_PRINT_SCALED) { /* its value or special value's id, then its raw integer */
        const nmea_ubx_scale *s = (const nmea_ubx_scale *)it->extra;
        const char *special = NULL;
        char raw_name[64];
        for (k = 0; k < s->n_specials && !special; k++)
            if (s->specials[k].raw == (int64_t)value)
                special = s->specials[k].id;
        if (special) {
            ubx_json_puts(j, "\"");
            ubx_json_puts(j, special);
            ubx_json_puts(j, "\"");
        } else if (s->real) {
            ubx_json_float(j, (is_signed ? (double)(int64_t)value : (double)value) / s->divisor + s->base);
        } else {
            ubx_json_number(j, value + (uint64_t)(int64_t)s->base, true);
        }
        snprintf(raw_name, sizeof raw_name, "%s_raw", it->id);
        ubx_json_key(j, raw_name);
        ubx_json_number(j, value, is_signed);
    } else {
        ubx_json_number(j, value, is_signed);
    }
}

/* The JSON member `id` of the entries `first` to `first + count - 1` of group `g` of the array at
   `array` (`m`: the message): an array of objects, an entry's fields then its nested group's
   entries (those its index and count member say; a count past the array's stops at its end). */
static void ubx_json_group(ubx_json_out *j, const char *id, const nmea_ubx_group *g, const uint8_t *m,
                           const uint8_t *array, size_t first, size_t count)
{
    size_t k, f;
    (void)m; /* (a nested group's array) */
    ubx_json_key(j, id);
    ubx_json_puts(j, "[");
    for (k = first; k < first + count && k < g->max; k++) {
        const uint8_t *entry = array + k * g->entry_size;
        ubx_json_puts(j, k > first ? ",{" : "{");
        j->empty = true;
        for (f = 0; f < g->n_items; f++)
            ubx_json_field(j, &g->items[f], entry);
#ifdef NMEA_UBX_NESTED
        if (g->nested) {
            uint16_t from, total;
            size_t n = (size_t)ubx_get(entry + g->nested->count_offset, g->nested->count_member, false);
            memcpy(&from, entry + g->nested_first, sizeof from);
            memcpy(&total, m + g->nested->n_offset, sizeof total);
            ubx_json_group(j, g->nested_id, g->nested, m, m + g->nested_offset, from,
                           from >= total ? 0 : n < (size_t)(total - from) ? n : (size_t)(total - from));
        }
#endif
        ubx_json_puts(j, "}");
    }
    ubx_json_puts(j, "]");
    j->empty = false;
}

/* The JSON members of a layout's `items` of the struct at `m` (those of
   generated/vectors/ubx.jsonl), a group's entries field by field. */
static void ubx_json_items(ubx_json_out *j, const nmea_ubx_item *items, size_t n, const uint8_t *m)
{
    size_t i;
    for (i = 0; i < n; i++) {
        const nmea_ubx_item *it = &items[i];
        const nmea_ubx_group *g = (const nmea_ubx_group *)it->extra;
        uint16_t count;
        if (it->optional && !*(const bool *)(const void *)(m + it->has))
            return;
        if (it->kind != NMEA_UBX_ITEM_GROUP) {
            ubx_json_field(j, it, m);
            continue;
        }
        memcpy(&count, m + g->n_offset, sizeof count);
        ubx_json_group(j, it->id, g, m, m + it->offset, 0, count);
    }
}

/* The layout a payload of `len` bytes of class and id `first` to `last` (in spec order) is read
   as: the first whose fixed length (when it has one) and selector byte (`select_value`, `select_at`: a
   type, command or version byte, when it has one) are the payload's; else the first with a
   selector whose fixed length is the payload's; else the first the receiver sends, else the last. */
static size_t ubx_layout_for(const nmea_ubx_layout_info *layouts, size_t first, size_t last, const uint8_t *payload,
                             size_t len)
{
    size_t i;
    for (i = first; i <= last; i++) {
        const nmea_ubx_layout_info *l = &layouts[i];
        if (l->length >= 0 && (size_t)l->length != len)
            continue;
        if (l->select_value >= 0 && (l->select_at >= len || payload[l->select_at] != l->select_value))
            continue;
        return i;
    }
    for (i = first; i <= last; i++) /* a selector value no layout names: the selected layout of its length */
        if (layouts[i].select_value >= 0 && layouts[i].length >= 0 && (size_t)layouts[i].length == len)
            return i;
    for (i = first; i <= last; i++)
        if (layouts[i].output)
            return i;
    return last;
}

/* The header fields a message of protocol `f` keeps (its `header`), read from its frame into the
   message at `m`. */
static void ubx_read_kept(const nmea_ubx_framing *f, const uint8_t *frame, uint8_t *m)
{
    size_t i, k;
    for (i = 0; i < f->n_kept; i++) {
        const nmea_ubx_header_field *h = &f->kept[i];
        uint64_t value = 0;
        for (k = 0; k < h->size; k++)
            value = value << 8 | frame[h->at + (f->big ? k : h->size - 1 - k)];
        ubx_set(m + h->offset, h->size, value);
    }
}

/* ... written from the message at `m` into a frame's header at `buf`. */
static void ubx_write_kept(const nmea_ubx_framing *f, const uint8_t *m, uint8_t *buf)
{
    size_t i, k;
    for (i = 0; i < f->n_kept; i++) {
        const nmea_ubx_header_field *h = &f->kept[i];
        uint64_t value = ubx_get(m + h->offset, h->size, false);
        for (k = 0; k < h->size; k++)
            buf[h->at + (f->big ? h->size - 1 - k : k)] = (uint8_t)(value >> 8 * k);
    }
}

/* ... as the JSON member `header` (none for a protocol whose messages keep none). */
static void ubx_json_kept(ubx_json_out *j, const nmea_ubx_framing *f, const uint8_t *m)
{
    size_t i;
    if (!f->n_kept)
        return;
    ubx_json_key(j, "header");
    ubx_json_puts(j, "{");
    j->empty = true;
    for (i = 0; i < f->n_kept; i++) {
        ubx_json_key(j, f->kept[i].name);
        ubx_json_number(j, ubx_get(m + f->kept[i].offset, f->kept[i].size, false), false);
    }
    ubx_json_puts(j, "}");
    j->empty = false;
}

/* Reads a payload as layout `l` into the struct at `m`: its members before `trailing` zeroed first
   (every has_ flag false), then read; a group's entries are zeroed as they are read (the entries
   past a group's count are not: its count says how many hold a value). Only the layout's bytes are
   written, not the whole message's union, whose largest member (NAV-SAT's 255 satellites) is
   kilobytes. */
static bool ubx_read_layout(const nmea_ubx_layout_info *l, const nmea_ubx_framing *f, const uint8_t *payload,
                            size_t len, uint8_t *m, nmea_ubx_error *err)
{
    ubx_reader r;
    nmea_ubx_bytes trailing;
    r.p = payload;
    r.len = len;
    r.pos = 0;
    r.address = l->address;
    r.err = err;
    r.big = f->big;
    err->protocol = l->protocol;
    memset(m, 0, l->trailing); /* the members come first, then trailing, then the groups' arrays */
    if (!ubx_read_items(&r, l->items, l->n_items, m))
        return false;
    trailing.ptr = payload + r.pos;
    trailing.len = len - r.pos;
    memcpy(m + l->trailing, &trailing, sizeof trailing);
    return true;
}

/* Writes the frame of layout `l` of protocol `f` (NULL: an unknown message's `unknown`) into `buf`:
   sync, header (the length, the key where the header holds it), the key where the payload starts
   with it, the payload, checksum and end bytes. Its length, 0 with the error set. */
static size_t ubx_write_frame(const nmea_ubx_framing *f, const nmea_ubx_layout_info *l, const uint8_t *m,
                              const nmea_ubx_unknown *unknown, const uint8_t *message, uint8_t *buf, size_t cap,
                              nmea_ubx_error *err)
{
    ubx_writer w;
    size_t payload, trailer = (size_t)(f->check_at ? 0 : f->check_size) + f->end_len, i, length;
    unsigned long sum;
    uint8_t key[2];
    size_t key_len = l ? (f->key_at ? 2 : l->key_len) : (f->key_at ? 2 : unknown->key_len);
    key[0] = l ? l->msg_class : unknown->msg_class;
    key[1] = l ? l->msg_id : unknown->msg_id;
    w.buf = buf;
    w.cap = cap;
    w.len = 0;
    w.address = l ? l->address : NULL;
    w.err = err;
    w.big = f->big;
    err->protocol = l ? l->protocol : unknown->protocol;
    if (cap < f->header + trailer) {
        snprintf(err->text, sizeof err->text, "a frame needs at least %u bytes, the buffer has %lu",
                 (unsigned)(f->header + trailer), (unsigned long)cap);
        return (size_t)ubx_fail(err, NMEA_UBX_NO_ROOM, w.address, NULL);
    }
    w.cap = cap - trailer; /* room for the checksum and end bytes */
    w.len = f->header;
    if (!f->key_at && key_len && !ubx_put(&w, key, key_len, NULL))
        return 0;
    if (l) {
        nmea_ubx_bytes trailing;
        memcpy(&trailing, m + l->trailing, sizeof trailing);
        if (!ubx_write_items(&w, l->items, l->n_items, m) ||
            (trailing.len && !ubx_put(&w, trailing.ptr, trailing.len, "trailing")))
            return 0;
    } else if (unknown->payload.len && !ubx_put(&w, unknown->payload.ptr, unknown->payload.len, "payload")) {
        return 0;
    }
    payload = w.len - f->header;
    length = w.len + trailer - f->length_adds; /* the payload's bytes, or the whole frame's (SBF) */
    if (length > f->length_mask) {
        snprintf(err->text, sizeof err->text, "the payload is %lu bytes, a frame holds %u", (unsigned long)payload,
                 (unsigned)(f->length_mask + f->length_adds - f->header - trailer));
        return (size_t)ubx_fail(err, NMEA_UBX_BAD_VALUE, w.address, NULL);
    }
    memset(buf, 0, f->header);
    memcpy(buf, f->sync, f->sync_len);
    buf[f->length_at + (f->big ? 1 : 0)] = (uint8_t)(length & 0xFF);
    buf[f->length_at + (f->big ? 0 : 1)] = (uint8_t)(length >> 8);
    if (f->key_at) {
        buf[f->key_at] = key[0];
        buf[f->key_at + 1] = key[1];
    }
    ubx_write_kept(f, message, buf);
    sum = ubx_check((nmea_ubx_check)f->check, buf + f->check_from, w.len - f->check_from);
    for (i = 0; i < f->check_size; i++) /* after the payload, or in the header (SBF) */
        buf[(f->check_at ? f->check_at : w.len) + i] = (uint8_t)(sum >> 8 * (f->check_size - 1 - i));
    memcpy(buf + w.len + (f->check_at ? 0 : f->check_size), f->end, f->end_len);
    return w.len + trailer;
}

/* Checks a whole frame's sync, length and checksum: its class, id and payload. */
static bool ubx_open_frame(const uint8_t *frame, size_t len, const uint8_t **payload, size_t *payload_len,
                           nmea_ubx_error *err)
{
    unsigned sum;
    if (len < NMEA_UBX_OVERHEAD || frame[0] != 0xB5 || frame[1] != 0x62) {
        snprintf(err->text, sizeof err->text, "a UBX frame is B5 62, class, id, length, payload and two checksum bytes");
        return ubx_fail(err, NMEA_UBX_BAD_FRAME, NULL, NULL);
    }
    *payload_len = (size_t)frame[4] | (size_t)frame[5] << 8;
    if (len != NMEA_UBX_OVERHEAD + *payload_len) {
        snprintf(err->text, sizeof err->text, "the length field says %lu payload bytes, the frame has %lu",
                 (unsigned long)*payload_len, (unsigned long)(len - NMEA_UBX_OVERHEAD));
        return ubx_fail(err, NMEA_UBX_BAD_FRAME, NULL, NULL);
    }
    sum = ubx_checksum(frame + 2, len - 4);
    if ((sum & 0xFF) != frame[len - 2] || sum >> 8 != frame[len - 1]) {
        snprintf(err->text, sizeof err->text, "checksum %02X %02X, computed %02X %02X", frame[len - 2], frame[len - 1],
                 sum & 0xFF, sum >> 8);
        return ubx_fail(err, NMEA_UBX_BAD_CHECKSUM, NULL, NULL);
    }
    *payload = frame + 6;
    return true;
}

/* Checks a whole frame of protocol `f` (not UBX: its own errors are ubx_open_frame's): its sync,
   length, checksum and end bytes; its header and payload. */
static bool ubx_open_frame_of(const nmea_ubx_framing *f, const uint8_t *frame, size_t len, const uint8_t **payload,
                              size_t *payload_len, nmea_ubx_error *err)
{
    size_t trailer = (size_t)(f->check_at ? 0 : f->check_size) + f->end_len, i, size;
    unsigned long sum, sent = 0;
    if (len < (size_t)f->header + trailer || memcmp(frame, f->sync, f->sync_len) != 0) {
        char third[4] = "";
        if (f->sync_len > 2)
            snprintf(third, sizeof third, " %02X", f->sync[2]);
        snprintf(err->text, sizeof err->text, "a %s frame is %02X %02X%s, a header of %u bytes, payload, checksum%s",
                 f->upper, f->sync[0], f->sync[1], third, (unsigned)f->header, f->end_len ? " and end bytes" : "");
        return ubx_fail(err, NMEA_UBX_BAD_FRAME, NULL, NULL);
    }
    size = ((f->big ? (size_t)frame[f->length_at] << 8 | frame[f->length_at + 1]
                    : (size_t)frame[f->length_at] | (size_t)frame[f->length_at + 1] << 8) &
            f->length_mask) +
           f->length_adds; /* the frame's bytes */
    if (len != size || size < (size_t)f->header + trailer) {
        snprintf(err->text, sizeof err->text, "the length field says %lu bytes, the frame has %lu", (unsigned long)size,
                 (unsigned long)len);
        return ubx_fail(err, NMEA_UBX_BAD_FRAME, NULL, NULL);
    }
    *payload_len = len - f->header - trailer;
    sum = ubx_check((nmea_ubx_check)f->check, frame + f->check_from, len - trailer - f->check_from);
    for (i = 0; i < f->check_size; i++) /* after the payload, or in the header (SBF) */
        sent = sent << 8 | frame[(f->check_at ? f->check_at : len - trailer) + i];
    if (sent != sum || (f->end_len && memcmp(frame + len - f->end_len, f->end, f->end_len) != 0)) {
        snprintf(err->text, sizeof err->text, "checksum %0*lX, computed %0*lX%s", 2 * f->check_size, sent,
                 2 * f->check_size, sum, sent == sum ? ", its end bytes are not the protocol's" : "");
        return ubx_fail(err, NMEA_UBX_BAD_CHECKSUM, NULL, NULL);
    }
    *payload = frame + f->header;
    return true;
}

/* JSON opened on a caller's buffer. */
static void ubx_json_start(ubx_json_out *j, char *buf, size_t cap)
{
    j->buf = buf;
    j->cap = cap;
    j->len = 0;
    j->empty = true;
    if (cap)
        buf[0] = '\0';
    ubx_json_puts(j, "{");
}
