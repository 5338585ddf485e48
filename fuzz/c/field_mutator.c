/*
 * A structure-aware mutator for the fuzz targets (the C target's LLVMFuzzerCustomMutator, and the
 * Rust targets' through fuzz_mutator!): a sentence is mutated field by field, and its checksum is
 * then made right again most of the time.
 *
 * libFuzzer's own byte mutations almost always break the checksum, so the parser refuses the line
 * before any field reader sees it. Here a field is replaced by a token that sits on a boundary of
 * some field type (an empty field, a sign, an overlong number, a time of 24:00, a hemisphere
 * letter, a byte outside ASCII, ...), mutated in place, duplicated, deleted, swapped with another
 * or replaced by a run of digits, and the checksum is recomputed (upper case, now and then lower
 * case, now and then left wrong). A JSON input ('{') and one in eight others get libFuzzer's own
 * mutation only, so nothing the plain fuzzer reached is lost.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

size_t LLVMFuzzerMutate(uint8_t *data, size_t size, size_t max_size);

#define WORK 4096   /* the longest input mutated field by field */
#define MAX_FIELDS 128

static const char *const TOKENS[] = {
    "", "0", "00", "-1", "-0", "+1", "1.", ".5", "-.5", "0.000001", "65535", "65536", "4294967296",
    "999999999999999999", "9999999999999999999", "18446744073709551616", "1e5", "0x1F",
    "A", "V", "N", "S", "E", "W", "M", "K", "T", "D", "Z", "GP", "GN", "FF", "ff", "7E",
    "235959.99", "240000", "235960", "311299", "290200", "320101", "9000.0000", "18000.0000",
    "9060.0000", "12345.67890123", "-", " ", "\"", "\\", "$", "!", "*", "\x7f", "\xff", "\x01",
};

typedef struct {
    size_t start, end;   /* a field's bytes: [start, end) */
} span;

static uint32_t rng(uint32_t *state)
{
    uint32_t x = *state ? *state : 0x9E3779B9u;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    return *state = x;
}

/* The fields of a `$` or `!` sentence: split on ',' from after its start character up to its
   '*' (or its end); the address is field 0. Returns their number, 0 for anything else. */
static size_t fields_of(const uint8_t *d, size_t n, span *fields, size_t *star)
{
    size_t i, count = 0, start = 1;
    if (n < 2 || (d[0] != '$' && d[0] != '!'))
        return 0;
    *star = n;
    for (i = 1; i < n; i++)
        if (d[i] == '*') {
            *star = i;
            break;
        }
    for (i = 1; i <= *star && count < MAX_FIELDS; i++)
        if (i == *star || d[i] == ',') {
            fields[count].start = start;
            fields[count].end = i;
            count++;
            start = i + 1;
        }
    return count;
}

/* Writes `a` then `b` then `c` into `out` (at most `cap` bytes); returns the length, 0 when it
   does not fit. */
static size_t splice(uint8_t *out, size_t cap, const uint8_t *a, size_t an, const uint8_t *b, size_t bn,
                     const uint8_t *c, size_t cn)
{
    if (an + bn + cn > cap)
        return 0;
    memmove(out, a, an);
    if (bn)
        memcpy(out + an, b, bn);
    if (cn)
        memcpy(out + an + bn, c, cn);
    return an + bn + cn;
}

static const char HEX_UPPER[] = "0123456789ABCDEF", HEX_LOWER[] = "0123456789abcdef";

/* Recomputes the checksum after '*' (adding "*HH" to half the sentences without one). */
static size_t fix_checksum(uint8_t *d, size_t n, size_t cap, uint32_t *state)
{
    size_t i, star = n;
    uint8_t sum = 0;
    const char *hex = rng(state) % 16 == 0 ? HEX_LOWER : HEX_UPPER;
    if (n < 2 || (d[0] != '$' && d[0] != '!'))
        return n;
    for (i = 1; i < n; i++) {
        if (d[i] == '*') {
            star = i;
            break;
        }
        sum ^= d[i];
    }
    if (star == n) {
        if (rng(state) % 2 || n + 3 > cap)
            return n;
        d[n++] = '*';
        d[n++] = (uint8_t)hex[sum >> 4];
        d[n++] = (uint8_t)hex[sum & 15];
        return n;
    }
    if (star + 2 < n) {   /* two characters after '*' to overwrite */
        d[star + 1] = (uint8_t)hex[sum >> 4];
        d[star + 2] = (uint8_t)hex[sum & 15];
    }
    return n;
}

size_t nmea_fuzz_mutate(uint8_t *data, size_t size, size_t max_size, unsigned int seed)
{
    static uint8_t work[WORK], piece[WORK];
    span fields[MAX_FIELDS];
    size_t count, star, cap = max_size < WORK ? max_size : WORK, n = 0, i, j, len;
    uint32_t state = seed;

    count = size <= cap ? fields_of(data, size, fields, &star) : 0;
    if (count == 0 || rng(&state) % 8 == 0)
        return LLVMFuzzerMutate(data, size, max_size);
    i = rng(&state) % count;
    j = rng(&state) % count;
    const uint8_t *field = data + fields[i].start;
    len = fields[i].end - fields[i].start;
    switch (rng(&state) % 6) {
    case 0: { /* a boundary token */
        const char *token = TOKENS[rng(&state) % (sizeof TOKENS / sizeof TOKENS[0])];
        n = splice(work, cap, data, fields[i].start, (const uint8_t *)token, strlen(token), field + len,
                   size - fields[i].end);
        break;
    }
    case 1: /* the field's own bytes mutated */
        memcpy(piece, field, len);
        len = LLVMFuzzerMutate(piece, len, len + 16 < cap ? len + 16 : cap);
        n = splice(work, cap, data, fields[i].start, piece, len, data + fields[i].end, size - fields[i].end);
        break;
    case 2: /* duplicated */
        piece[0] = ',';
        memcpy(piece + 1, field, len);
        n = splice(work, cap, data, fields[i].end, piece, len + 1, data + fields[i].end, size - fields[i].end);
        break;
    case 3: /* deleted with its comma (not the address) */
        if (i == 0)
            i = count - 1;
        if (i == 0)
            return LLVMFuzzerMutate(data, size, max_size);
        n = splice(work, cap, data, fields[i].start - 1, NULL, 0, data + fields[i].end, size - fields[i].end);
        break;
    case 4: { /* another field's text in its place */
        size_t other = fields[j].end - fields[j].start;
        memcpy(piece, data + fields[j].start, other);
        n = splice(work, cap, data, fields[i].start, piece, other, data + fields[i].end, size - fields[i].end);
        break;
    }
    default: { /* a run of digits, with a point now and then */
        size_t k, digits = 1 + rng(&state) % 24;
        for (k = 0; k < digits; k++)
            piece[k] = (uint8_t)('0' + rng(&state) % 10);
        if (digits > 2 && rng(&state) % 2)
            piece[rng(&state) % digits] = '.';
        n = splice(work, cap, data, fields[i].start, piece, digits, data + fields[i].end, size - fields[i].end);
        break;
    }
    }
    if (n == 0)
        return LLVMFuzzerMutate(data, size, max_size);
    if (rng(&state) % 16 != 0)
        n = fix_checksum(work, n, cap, &state);
    memcpy(data, work, n);
    return n;
}
