/*
 * The C benchmark driver: reads the corpus into memory once, then times one operation of one
 * implementation over every line and prints a JSON object.
 *
 *     bench-c ours|ceiling|ours-ais|ours-ubx parse|serialize|roundtrip|fixes|none CORPUS [--by-type]
 *
 * parse: nmea_parse of every line (ok = lines parsed). serialize: the lines are parsed chunk by
 * chunk outside the timed region, then only nmea_serialize of the chunk is timed, the sentences
 * written one after another into one buffer as a program writing a stream would (ok = lines
 * written back byte for byte). roundtrip: parse then serialize each line, comparing with the input.
 * ceiling: ceiling_scan (checksum and field boundaries), parse only. --by-type repeats the timing
 * over the lines of each sentence type separately. none: nothing (the cost of reading the corpus,
 * which bench/run.py subtracts from instruction counts). ours-ais (over the AIS corpus), parse only:
 * each line parsed and, when it is a whole message, its AIS message decoded, every field (ok =
 * messages decoded). fixes (ours): each line parsed and fed to the fix assembler, nmea_fix_feed
 * (ok = lines parsed). ours-ubx (over the UBX corpus, a frame as hex digits a line, turned into
 * bytes before the timing), parse only: nmea_ubx_decode_frame of each frame, its sync, length and
 * checksum checked and every field of its layout read into the message's struct (ok = frames of a
 * class and id the spec describes).
 *
 *     bench-c framer frame LOG
 *
 * framer (over any byte stream: the mixed corpus of NMEA, UBX and RTCM 3, or the NMEA corpus):
 * nmea_framer_push over the whole file in chunks of 4,096 bytes, as a serial port's reads deliver
 * them, then nmea_framer_end; each item's kind counted (lines: ok lines are those kept, frames:
 * ok frames are those whose checksum holds). Prints ns per item and per byte ("ns_per_byte").
 */
#define _POSIX_C_SOURCE 199309L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ceiling.h"
#include "nmea.h"
#include "nmea_ais.h"
#include "nmea_ubx.h"

#define CHUNK 2048

typedef struct {
    const char *ptr;
    size_t len;
} line_ref;

typedef struct {
    double seconds;
    size_t ok;
    size_t lines;
} timing;

static volatile size_t sink; /* keeps results observable so nothing is optimised away */

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static char *read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    char *data;
    long n;
    if (!f || fseek(f, 0, SEEK_END) != 0 || (n = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        perror(path);
        exit(2);
    }
    data = malloc((size_t)n + 1);
    if (!data || fread(data, 1, (size_t)n, f) != (size_t)n) {
        perror(path);
        exit(2);
    }
    fclose(f);
    *size = (size_t)n;
    return data;
}

/* Splits the corpus into lines without their CR LF. */
static line_ref *split_lines(const char *data, size_t size, size_t *count)
{
    size_t n = 0, cap = 1024, start = 0, i;
    line_ref *lines = malloc(cap * sizeof *lines);
    for (i = 0; i < size; i++) {
        if (data[i] != '\n')
            continue;
        if (n == cap) {
            cap *= 2;
            lines = realloc(lines, cap * sizeof *lines);
        }
        lines[n].ptr = data + start;
        lines[n].len = i - start - (i > start && data[i - 1] == '\r');
        n++;
        start = i + 1;
    }
    *count = n;
    return lines;
}

static timing time_parse(const line_ref *lines, size_t n)
{
    nmea_sentence s;
    nmea_error err;
    size_t ok = 0, i, ids = 0;
    double start = now();
    for (i = 0; i < n; i++) {
        if (nmea_parse(&s, lines[i].ptr, lines[i].len, &err)) {
            ok++;
            ids += (size_t)s.id;
        }
    }
    start = now() - start;
    sink = ids;
    return (timing){start, ok, n};
}

static timing time_ais_decode(const line_ref *lines, size_t n)
{
    nmea_sentence s;
    nmea_error err;
    nmea_ais_fragment fragment;
    nmea_ais_message message;
    nmea_ais_error ais_err;
    size_t ok = 0, i, layouts = 0;
    double start = now();
    for (i = 0; i < n; i++) {
        if (nmea_parse(&s, lines[i].ptr, lines[i].len, &err) && nmea_ais_fragment_of(&s, &fragment)
            && fragment.count == 1
            && nmea_ais_decode(fragment.payload.ptr, fragment.payload.len, fragment.fill_bits, &message, &ais_err)) {
            ok++;
            layouts += (size_t)message.layout;
        }
    }
    start = now() - start;
    sink = layouts;
    return (timing){start, ok, n};
}

static int hex_digit(char c)
{
    return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
}

/* The UBX corpus's frames, as bytes: `lines` of hex digits turned back into one buffer, each
 * frame's bytes next to the previous one's (a line_ref each, into `bytes`). */
static line_ref *ubx_frames(const line_ref *lines, size_t n, char **bytes)
{
    size_t total = 0, i, k, used = 0;
    line_ref *frames = malloc((n ? n : 1) * sizeof *frames);
    for (i = 0; i < n; i++)
        total += lines[i].len / 2;
    *bytes = malloc(total ? total : 1);
    if (!frames || !*bytes) {
        perror("malloc");
        exit(2);
    }
    for (i = 0; i < n; i++) {
        frames[i].ptr = *bytes + used;
        frames[i].len = lines[i].len / 2;
        for (k = 0; k < frames[i].len; k++) {
            int high = hex_digit(lines[i].ptr[2 * k]), low = hex_digit(lines[i].ptr[2 * k + 1]);
            if (high < 0 || low < 0) {
                fprintf(stderr, "not hex: line %zu\n", i + 1);
                exit(2);
            }
            (*bytes)[used++] = (char)(high << 4 | low);
        }
    }
    return frames;
}

static timing time_ubx_decode(const line_ref *lines, size_t n)
{
    static nmea_ubx_message message; /* a NAV-SAT's 255 satellites and more: not on the stack */
    nmea_ubx_error err;
    char *bytes;
    line_ref *frames = ubx_frames(lines, n, &bytes);
    size_t ok = 0, i, layouts = 0;
    double start = now();
    for (i = 0; i < n; i++) {
        if (nmea_ubx_decode_frame((const uint8_t *)frames[i].ptr, frames[i].len, &message, &err)) {
            ok += message.layout != NMEA_UBX_MSG_UNKNOWN;
            layouts += (size_t)message.layout;
        }
    }
    start = now() - start;
    sink = layouts;
    free(frames);
    free(bytes);
    return (timing){start, ok, n};
}

static timing time_fixes(const line_ref *lines, size_t n)
{
    static nmea_fix_assembler assembler; /* two fixes' worth of satellites: not on the stack */
    static nmea_gnss_fix fix;
    nmea_sentence s;
    nmea_error err;
    size_t ok = 0, i, fixes = 0;
    double start = now();
    nmea_fix_init(&assembler);
    for (i = 0; i < n; i++) {
        if (nmea_parse(&s, lines[i].ptr, lines[i].len, &err)) {
            ok++;
            fixes += nmea_fix_feed(&assembler, &s, &fix);
        }
    }
    fixes += nmea_fix_finish(&assembler, &fix);
    start = now() - start;
    sink = fixes;
    return (timing){start, ok, n};
}

static timing time_ceiling(const line_ref *lines, size_t n)
{
    unsigned short starts[CEILING_MAX_FIELDS];
    size_t ok = 0, i, total = 0;
    double start = now();
    for (i = 0; i < n; i++) {
        int fields = ceiling_scan(lines[i].ptr, lines[i].len, starts);
        if (fields > 0) {
            ok++;
            total += starts[fields - 1];
        }
    }
    start = now() - start;
    sink = total;
    return (timing){start, ok, n};
}

static timing time_serialize(const line_ref *lines, size_t n)
{
    static nmea_sentence parsed[CHUNK];
    static char out[CHUNK * (NMEA_MAX_LINE + 3)]; /* the chunk's sentences one after another */
    static size_t offsets[CHUNK + 1];
    nmea_error err;
    size_t ok = 0, done, i, count;
    double seconds = 0;
    for (done = 0; done < n; done += count) {
        const line_ref *chunk = lines + done;
        size_t kept = 0, used = 0;
        size_t index[CHUNK];
        double start;
        count = n - done < CHUNK ? n - done : CHUNK;
        for (i = 0; i < count; i++)
            if (nmea_parse(&parsed[kept], chunk[i].ptr, chunk[i].len, &err))
                index[kept++] = i;
        start = now();
        for (i = 0; i < kept; i++) { /* each NUL is overwritten by the next sentence */
            offsets[i] = used;
            used += nmea_serialize(&parsed[i], out + used, sizeof out - used);
        }
        seconds += now() - start;
        offsets[kept] = used;
        for (i = 0; i < kept; i++) {
            const line_ref *line = &chunk[index[i]];
            ok += offsets[i + 1] - offsets[i] == line->len && memcmp(out + offsets[i], line->ptr, line->len) == 0;
        }
    }
    return (timing){seconds, ok, n};
}

static timing time_roundtrip(const line_ref *lines, size_t n)
{
    nmea_sentence s;
    nmea_error err;
    char out[NMEA_MAX_LINE + 3];
    size_t ok = 0, i;
    double start = now();
    for (i = 0; i < n; i++) {
        size_t len;
        if (!nmea_parse(&s, lines[i].ptr, lines[i].len, &err))
            continue;
        len = nmea_serialize(&s, out, sizeof out);
        ok += len == lines[i].len && memcmp(out, lines[i].ptr, len) == 0;
    }
    start = now() - start;
    return (timing){start, ok, n};
}

static timing run(const char *impl, const char *op, const line_ref *lines, size_t n)
{
    if (strcmp(op, "none") == 0) /* reading the corpus only: the baseline of instruction counts */
        return (timing){0, 0, n};
    if (strcmp(impl, "ceiling") == 0 && strcmp(op, "parse") == 0)
        return time_ceiling(lines, n);
    if (strcmp(impl, "ours") == 0 && strcmp(op, "parse") == 0)
        return time_parse(lines, n);
    if (strcmp(impl, "ours-ais") == 0 && strcmp(op, "parse") == 0)
        return time_ais_decode(lines, n);
    if (strcmp(impl, "ours-ubx") == 0 && strcmp(op, "parse") == 0)
        return time_ubx_decode(lines, n);
    if (strcmp(impl, "ours") == 0 && strcmp(op, "serialize") == 0)
        return time_serialize(lines, n);
    if (strcmp(impl, "ours") == 0 && strcmp(op, "roundtrip") == 0)
        return time_roundtrip(lines, n);
    if (strcmp(impl, "ours") == 0 && strcmp(op, "fixes") == 0)
        return time_fixes(lines, n);
    fprintf(stderr, "unknown implementation/operation %s %s\n", impl, op);
    exit(2);
}

typedef struct {
    double seconds;
    size_t items, ok, lines, frames, rejected;
} framed_counts;

static void count_item(framed_counts *c, const nmea_framed *item)
{
    c->items++;
    if (item->protocol == NMEA_LINE) {
        c->lines++;
        c->ok += item->ptr != NULL;
    } else if (item->error == NMEA_FRAME_OK) {
        c->frames++;
        c->ok++;
    } else {
        c->rejected++;
    }
}

/* Splits `size` bytes into items with one nmea_framer, fed `chunk` bytes at a time. */
static framed_counts time_framer(const char *data, size_t size, size_t chunk)
{
    static nmea_framer framer;
    framed_counts c = {0, 0, 0, 0, 0, 0};
    nmea_framed item;
    size_t done;
    double start = now();
    nmea_framer_init(&framer);
    for (done = 0; done < size; done += chunk) {
        const char *p = data + done;
        size_t n = size - done < chunk ? size - done : chunk;
        while (nmea_framer_push(&framer, &p, &n, &item))
            count_item(&c, &item);
    }
    while (nmea_framer_end(&framer, &item))
        count_item(&c, &item);
    c.seconds = now() - start;
    sink = c.ok;
    return c;
}

static int run_framer(const char *op, const char *path)
{
    size_t size;
    char *data = read_file(path, &size);
    framed_counts c;
    if (strcmp(op, "frame") != 0 && strcmp(op, "none") != 0) {
        fprintf(stderr, "unknown implementation/operation framer %s\n", op);
        return 2;
    }
    c = time_framer(data, size < 1000000 ? size : 1000000, 4096); /* warm the caches and branch predictors */
    if (strcmp(op, "frame") == 0)
        c = time_framer(data, size, 4096);
    printf("{\"impl\": \"framer\", \"op\": \"%s\", \"lines\": %zu, \"bytes\": %zu, \"ns_per_line\": %.2f, "
           "\"ns_per_byte\": %.4f, \"ok_lines\": %zu, \"text_lines\": %zu, \"frames\": %zu, \"rejected\": %zu}\n",
           op, c.items, size, c.seconds * 1e9 / (double)(c.items ? c.items : 1), c.seconds * 1e9 / (double)size, c.ok,
           c.lines, c.frames, c.rejected);
    free(data);
    return 0;
}

/* The sentence type of a line: the three letters after `$` and the talker. */
static int type_of(const line_ref *line, char type[4])
{
    if (line->len < 6)
        return 0;
    memcpy(type, line->ptr + 3, 3);
    type[3] = '\0';
    return 1;
}

static void print_by_type(const char *impl, const char *op, const line_ref *lines, size_t n)
{
    char types[64][4];
    size_t ntypes = 0, i, t;
    line_ref *group = malloc(n * sizeof *group);
    char *text = malloc(lines[n - 1].ptr + lines[n - 1].len - lines[0].ptr);
    for (i = 0; i < n; i++) {
        char type[4];
        if (!type_of(&lines[i], type))
            continue;
        for (t = 0; t < ntypes && strcmp(types[t], type) != 0; t++)
            ;
        if (t == ntypes && ntypes < 64)
            memcpy(types[ntypes++], type, 4);
    }
    printf(", \"by_type\": {");
    for (t = 0; t < ntypes; t++) {
        size_t m = 0, used = 0;
        timing r;
        for (i = 0; i < n; i++) {
            char type[4];
            if (type_of(&lines[i], type) && strcmp(type, types[t]) == 0) {
                /* copied next to each other, so that a group is read as sequentially as the corpus */
                memcpy(text + used, lines[i].ptr, lines[i].len);
                group[m].ptr = text + used;
                group[m++].len = lines[i].len;
                used += lines[i].len;
            }
        }
        r = run(impl, op, group, m);
        printf("%s\"%s\": {\"ns_per_line\": %.2f, \"ok_lines\": %zu, \"lines\": %zu}", t ? ", " : "", types[t],
               r.seconds * 1e9 / (double)m, r.ok, m);
    }
    printf("}");
    free(text);
    free(group);
}

int main(int argc, char **argv)
{
    size_t size, n;
    char *data;
    line_ref *lines;
    timing r;
    if (argc < 4) {
        fprintf(stderr, "usage: %s ours|ceiling|ours-ais|ours-ubx parse|serialize|roundtrip|fixes|none CORPUS [--by-type]\n"
                        "       %s framer frame|none LOG\n", argv[0], argv[0]);
        return 2;
    }
    if (strcmp(argv[1], "framer") == 0)
        return run_framer(argv[2], argv[3]);
    data = read_file(argv[3], &size);
    lines = split_lines(data, size, &n);
    run(argv[1], argv[2], lines, n < 10000 ? n : 10000); /* warm the caches and branch predictors */
    r = run(argv[1], argv[2], lines, n);
    printf("{\"impl\": \"%s\", \"op\": \"%s\", \"lines\": %zu, \"bytes\": %zu, \"ns_per_line\": %.2f, \"ok_lines\": %zu",
           argv[1], argv[2], n, size, r.seconds * 1e9 / (double)n, r.ok);
    if (argc > 4 && strcmp(argv[4], "--by-type") == 0)
        print_by_type(argv[1], argv[2], lines, n);
    printf("}\n");
    free(lines);
    free(data);
    return 0;
}
