/* The UBX messages (nmea_ubx.c) against generated/vectors/ubx.jsonl, which the Python codec decodes
   and encodes too: every frame decodes to the same JSON as Python's or fails with the same error
   kind, and encodes back to the same bytes; the same for the other protocols' messages (SkyTraq,
   SiRF, CASIC, SBF) against the further .jsonl files given (generated/vectors/binary.jsonl, whose
   records name their protocol); then every UBX, SkyTraq, SiRF, CASIC and SBF frame nmea.c's framer
   finds in the logs given (gpsd's, tests/data/{ubx,rtcm3,skytraq,sirf,casic}; pysbf2's, tests/data/sbf) decodes and encodes
   back byte for byte, and a frame cut short, a buffer too small and a count over a group's array
   are refused. With --json, the JSON of every frame of the files given, a frame in hex a line
   (after its protocol's name and a space when not UBX), a line each (tests/ubx/test_c_ubx.py
   compares it with Python's; built with -DUBX_TEST_JSON_ONLY, it needs no nmea.c).
   Usage: test_ubx path/to/ubx.jsonl [path/to/binary.jsonl] log...
          test_ubx path/to/ubx.jsonl --json frames.hex... */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef UBX_TEST_JSON_ONLY
#include "nmea.h"
#endif
#include "nmea_ubx.h"

/* The text of a member of a JSON record into `out` (a string's without its quotes). */
static void member(const char *record, const char *key, char *out, size_t cap)
{
    char pattern[64];
    const char *start;
    size_t len;
    snprintf(pattern, sizeof pattern, "\"%s\":", key);
    start = strstr(record, pattern);
    out[0] = '\0';
    if (!start)
        return;
    start += strlen(pattern);
    if (*start == '"')
        start++;
    len = strcspn(start, "\",}");
    if (len >= cap)
        len = cap - 1;
    memcpy(out, start, len);
    out[len] = '\0';
}

/* Bytes written as hex pairs, spaces between them or not. */
static size_t unhex(const char *text, uint8_t *out, size_t cap)
{
    size_t n = 0;
    unsigned value;
    while (*text && n < cap) {
        if (*text == ' ') {
            text++;
            continue;
        }
        if (sscanf(text, "%2x", &value) != 1)
            break;
        out[n++] = (uint8_t)value;
        text += 2;
    }
    return n;
}

static int failed, cut_payloads, over_maximum, other_frames;

/* A protocol by its name in the tools' JSON (UBX for none). */
static nmea_ubx_protocol protocol_named(const char *name)
{
    int p;
    for (p = 0; nmea_ubx_protocol_name((nmea_ubx_protocol)p); p++)
        if (strcmp(nmea_ubx_protocol_name((nmea_ubx_protocol)p), name) == 0)
            return (nmea_ubx_protocol)p;
    return NMEA_UBX_PROTOCOL_UBX;
}

/* Whether the pair types the protocol of that name (none: UBX). */
static bool typed_here(const char *name)
{
    return name[0] == '\0' || protocol_named(name) != NMEA_UBX_PROTOCOL_UBX || strcmp(name, "ubx") == 0;
}

/* A build with NMEA_UBX_MAX_ENTRIES below what the logs' groups have (make test-c builds one with 8)
   refuses those payloads as too_many_entries, naming the group. */
static bool over_the_maximum(const nmea_ubx_error *err)
{
    if (NMEA_UBX_MAX_ENTRIES < 255 && err->kind == NMEA_UBX_TOO_MANY && err->field) {
        over_maximum++;
        return true;
    }
    return false;
}

/* Decodes a whole frame and encodes it back: false (after saying why) when the bytes differ. */
static bool round_trip(nmea_ubx_protocol protocol, const uint8_t *frame, size_t len, nmea_ubx_message *message,
                       const char *where)
{
    static uint8_t again[70000];
    nmea_ubx_error err;
    size_t n;
    if (!nmea_ubx_decode_frame_of(protocol, frame, len, message, &err)) {
        if (over_the_maximum(&err))
            return false;
        printf("FAIL %s: %s %s: %s\n", where, nmea_ubx_error_kind_name(err.kind), err.message ? err.message : "", err.text);
        failed++;
        return false;
    }
    n = nmea_ubx_encode(message, again, sizeof again, &err);
    if (n != len || memcmp(again, frame, len) != 0) {
        printf("FAIL %s: encodes to %lu other bytes (%s)\n", where, (unsigned long)n, n ? "" : err.text);
        failed++;
        return false;
    }
    /* Too small a buffer by one byte: refused, and nothing written past it. */
    again[len - 1] = 0xA5;
    if (nmea_ubx_encode(message, again, len - 1, &err) != 0 || err.kind != NMEA_UBX_NO_ROOM || again[len - 1] != 0xA5) {
        printf("FAIL %s: a buffer of %lu bytes taken\n", where, (unsigned long)(len - 1));
        failed++;
        return false;
    }
    return true;
}

/* A frame and its JSON, or the kind of error that refuses it, as a line; a frame that decodes
   must also encode back. */
static void print_json(nmea_ubx_protocol protocol, const uint8_t *frame, size_t len, nmea_ubx_message *message)
{
    static char text[1 << 17];
    nmea_ubx_error err;
    size_t i;
    printf("{\"frame\":\"");
    for (i = 0; i < len; i++)
        printf("%02x", frame[i]);
    if (!nmea_ubx_decode_frame_of(protocol, frame, len, message, &err)) {
        printf("\",\"error\":\"%s\",\"field\":\"%s\"}\n", nmea_ubx_error_kind_name(err.kind), err.field ? err.field : "");
        return;
    }
    nmea_ubx_json(message, text, sizeof text);
    printf("\",\"decode\":%s}\n", text);
    round_trip(protocol, frame, len, message, "frame");
}

/* Every frame of a file of frames in hex, a line each, as print_json prints them. */
static int hex_frames(const char *path)
{
    static char line[1 << 17];
    static uint8_t frame[1 << 16];
    static nmea_ubx_message message;
    int frames = 0;
    FILE *file = fopen(path, "r");
    if (!file) {
        printf("FAIL cannot open %s\n", path);
        failed++;
        return 0;
    }
    while (fgets(line, sizeof line, file)) {
        char *hex = line, *space;
        nmea_ubx_protocol protocol = NMEA_UBX_PROTOCOL_UBX;
        line[strcspn(line, "\n")] = '\0';
        if ((space = strchr(line, ' ')) != NULL && space[1] != '\0' && (line[0] < '0' || line[0] > '9') &&
            strspn(line, "abcdefghijklmnopqrstuvwxyz0123456789") == (size_t)(space - line) && space - line > 2) {
            *space = '\0'; /* a protocol's name, then the frame */
            protocol = protocol_named(line);
            hex = space + 1;
        }
        print_json(protocol, frame, unhex(hex, frame, sizeof frame), &message);
        frames++;
    }
    fclose(file);
    return frames;
}

#ifndef UBX_TEST_JSON_ONLY
/* The payload of a frame cut at every length: refused with short_payload, or decoded into a
   message that encodes to the frame of the bytes kept. */
static void cuts(const uint8_t *frame, size_t len)
{
    static uint8_t cut[NMEA_MAX_FRAME], again[NMEA_MAX_FRAME];
    static nmea_ubx_message message;
    nmea_ubx_error err;
    size_t keep, n;
    for (keep = 0; keep + NMEA_UBX_OVERHEAD < len; keep++) {
        cut_payloads++;
        if (!nmea_ubx_decode(frame[2], frame[3], frame + 6, keep, &message, &err)) {
            if ((err.kind != NMEA_UBX_SHORT_PAYLOAD || !err.field) && !over_the_maximum(&err)) {
                printf("FAIL %02x %02x cut to %lu: %s\n", frame[2], frame[3], (unsigned long)keep, err.text);
                failed++;
            }
            continue;
        }
        memcpy(cut, frame, 6 + keep);
        cut[4] = (uint8_t)(keep & 0xFF);
        cut[5] = (uint8_t)(keep >> 8);
        n = nmea_ubx_encode(&message, again, sizeof again, &err);
        if (n != keep + NMEA_UBX_OVERHEAD || memcmp(again, cut, 6 + keep) != 0) {
            printf("FAIL %02x %02x cut to %lu encodes to other bytes\n", frame[2], frame[3], (unsigned long)keep);
            failed++;
        }
    }
}

/* Every UBX frame of a log, as the framer gives them. */
static int log_frames(const char *path)
{
    static char chunk[4096];
    static nmea_framer framer;
    static nmea_ubx_message message;
    nmea_framed item;
    size_t got;
    int frames = 0;
    static uint8_t seen[65536 / 8]; /* the classes and ids met */
    FILE *file = fopen(path, "rb");
    if (!file) {
        printf("FAIL cannot open %s\n", path);
        failed++;
        return 0;
    }
    memset(seen, 0, sizeof seen);
    nmea_framer_init(&framer);
    for (;;) {
        const char *p = chunk;
        bool more;
        got = fread(chunk, 1, sizeof chunk, file);
        while ((more = got ? nmea_framer_push(&framer, &p, &got, &item) : nmea_framer_end(&framer, &item))) {
            if ((item.protocol == NMEA_SKYTRAQ || item.protocol == NMEA_SIRF || item.protocol == NMEA_CASIC ||
                 item.protocol == NMEA_SBF || item.protocol == NMEA_UNICORE) &&
                item.error == NMEA_FRAME_OK) {
                nmea_ubx_protocol of = item.protocol == NMEA_SKYTRAQ   ? NMEA_UBX_PROTOCOL_SKYTRAQ
                                       : item.protocol == NMEA_SIRF    ? NMEA_UBX_PROTOCOL_SIRF
                                       : item.protocol == NMEA_SBF     ? NMEA_UBX_PROTOCOL_SBF
                                       : item.protocol == NMEA_UNICORE ? NMEA_UBX_PROTOCOL_UNICORE
                                                                       : NMEA_UBX_PROTOCOL_CASIC;
                other_frames++;
                round_trip(of, (const uint8_t *)item.ptr, item.len, &message, path);
            }
            if (item.protocol == NMEA_UBX && item.error == NMEA_FRAME_OK) {
                frames++;
                const uint8_t *frame = (const uint8_t *)item.ptr;
                unsigned key = (unsigned)frame[2] << 8 | frame[3];
                round_trip(NMEA_UBX_PROTOCOL_UBX, frame, item.len, &message, path);
                if (!(seen[key / 8] >> key % 8 & 1)) /* the first of each class and id of the log */
                    cuts(frame, item.len);
                seen[key / 8] |= (uint8_t)(1u << key % 8);
            }
            if (!got && !more)
                break;
        }
        if (feof(file) && !got && !more)
            break;
    }
    fclose(file);
    return frames;
}
#endif

/* Messages built by hand: CFG-RATE at 1 Hz (the frame of u-blox's examples), and a bitfield's
   part set on a decoded CFG-PRT (its word follows: in_proto_mask 0x07 -> 0x27); a NAV-PVT poll
   decoded from no payload (NULL) and encoded. */
static void by_hand(void)
{
    static const uint8_t rate[] = {0xB5, 0x62, 0x06, 0x08, 0x06, 0x00, 0xE8, 0x03, 0x01, 0x00, 0x01, 0x00, 0x01, 0x39};
    static const uint8_t prt[] = {0xB5, 0x62, 0x06, 0x00, 0x14, 0x00, 0x03, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
                                  0x00, 0x00, 0x00, 0x00, 0x07, 0x00, 0x03, 0x00, 0x00, 0x00, 0x00, 0x00, 0x27, 0xCE};
    static const uint8_t poll[] = {0xB5, 0x62, 0x01, 0x07, 0x00, 0x00, 0x08, 0x19};
    static nmea_ubx_message message;
    nmea_ubx_error err;
    uint8_t frame[64];
    size_t n;
    memset(&message, 0, sizeof message);
    message.layout = NMEA_UBX_MSG_CFG_RATE;
    message.as.cfg_rate.meas_rate = 1000;
    message.as.cfg_rate.nav_rate = 1;
    message.as.cfg_rate.time_ref = 1;
    n = nmea_ubx_encode(&message, frame, sizeof frame, &err);
    if (n != sizeof rate || memcmp(frame, rate, n) != 0) {
        printf("FAIL CFG-RATE built by hand\n");
        failed++;
    }
    if (!nmea_ubx_decode(0x01, 0x07, NULL, 0, &message, &err) || message.layout != NMEA_UBX_MSG_NAV_PVT_POLL ||
        nmea_ubx_encode(&message, frame, sizeof frame, &err) != 8 || memcmp(frame, poll, 8) != 0) {
        printf("FAIL a NAV-PVT poll of no payload (NULL)\n");
        failed++;
    }
    if (!nmea_ubx_decode_frame(prt, sizeof prt, &message, &err) || message.layout != NMEA_UBX_MSG_CFG_PRT ||
        message.as.cfg_prt.in_proto_mask != 7 || !message.as.cfg_prt.in_nmea || message.as.cfg_prt.in_rtcm3) {
        printf("FAIL CFG-PRT decoded\n");
        failed++;
        return;
    }
    message.as.cfg_prt.in_rtcm3 = true;
    n = nmea_ubx_encode(&message, frame, sizeof frame, &err);
    if (n != sizeof prt || !nmea_ubx_decode_frame(frame, n, &message, &err) || message.as.cfg_prt.in_proto_mask != 0x27) {
        printf("FAIL CFG-PRT with in_rtcm3 set\n");
        failed++;
    }
}

/* The refusals the vectors do not show: a payload cut inside a group, a count over the array. */
static void refusals(void)
{
    /* NAV-SAT of one satellite (8 + 12 bytes), its numSvs made 2: the second entry is cut. */
    static const uint8_t payload[20] = {1, 0, 0, 0, 1, 1, 0, 0, 0, 5, 40, 30, 0x10, 0, 0, 0, 0x1f, 0, 0, 0};
    static nmea_ubx_message message;
    uint8_t cut[20];
    nmea_ubx_error err;
    uint8_t frame[64];
    memcpy(cut, payload, sizeof cut);
    cut[5] = 2;
    if (nmea_ubx_decode(0x01, 0x35, cut, sizeof cut, &message, &err) || err.kind != NMEA_UBX_SHORT_PAYLOAD ||
        strcmp(err.field, "svs") != 0 || strcmp(err.message, "NAV-SAT") != 0) {
        printf("FAIL a NAV-SAT cut in its second satellite: %s\n", err.text);
        failed++;
    }
    if (!nmea_ubx_decode(0x01, 0x35, payload, sizeof payload, &message, &err) || message.layout != NMEA_UBX_MSG_NAV_SAT ||
        message.as.nav_sat.svs_count != 1 || message.as.nav_sat.svs[0].cno != 40) {
        printf("FAIL a NAV-SAT of one satellite\n");
        failed++;
    }
    message.as.nav_sat.svs_count = NMEA_UBX_NAV_SAT_SVS_MAX + 1;
    if (nmea_ubx_encode(&message, frame, sizeof frame, &err) != 0 || err.kind != NMEA_UBX_BAD_VALUE) {
        printf("FAIL a NAV-SAT of more satellites than its array encoded\n");
        failed++;
    }
    message.as.nav_sat.svs_count = 1;
    message.as.nav_sat.svs[0].quality_ind = 8; /* three bits */
    if (nmea_ubx_encode(&message, frame, sizeof frame, &err) != 0 || err.kind != NMEA_UBX_BAD_VALUE ||
        strcmp(err.field, "quality_ind") != 0) {
        printf("FAIL a quality_ind of 8 encoded in 3 bits\n");
        failed++;
    }
}

/* The records of a vectors file (ubx.jsonl, binary.jsonl): each frame decoded to the JSON the
   record gives, or refused with its error's kind, and encoded back. */
static void vectors(FILE *file, int *decoded, int *refused)
{
    static char record[1 << 17], json[1 << 17], frame_text[1 << 16], error[32], protocol[16];
    static uint8_t frame[1 << 15];
    static nmea_ubx_message message;
    while (fgets(record, sizeof record, file)) {
        nmea_ubx_error err;
        nmea_ubx_protocol of;
        const char *decode;
        size_t len;
        bool ok;
        record[strcspn(record, "\n")] = '\0';
        member(record, "frame", frame_text, sizeof frame_text);
        member(record, "error", error, sizeof error);
        member(record, "protocol", protocol, sizeof protocol);
        if (!typed_here(protocol))
            continue;
        of = protocol_named(protocol);
        if (strstr(record, "\"decode\":")) /* its decoded fields may have an `error` */
            error[0] = '\0';
        len = unhex(frame_text, frame, sizeof frame);
        ok = nmea_ubx_decode_frame_of(of, frame, len, &message, &err);
        if (error[0]) {
            if (ok || strcmp(nmea_ubx_error_kind_name(err.kind), error) != 0) {
                printf("FAIL error %s: %s\n", ok ? "none" : nmea_ubx_error_kind_name(err.kind), record);
                failed++;
            }
            (*refused)++;
            continue;
        }
        if (!ok && over_the_maximum(&err))
            continue;
        if (!ok) {
            printf("FAIL %s: %s\n", err.text, record);
            failed++;
            continue;
        }
        nmea_ubx_json(&message, json, sizeof json);
        decode = strstr(record, "\"decode\":") + 9;
        if (strncmp(json, decode, strlen(decode) - 1) != 0 || strlen(json) != strlen(decode) - 1) {
            printf("FAIL json\n  got  %s\n  want %.*s\n", json, (int)strlen(decode) - 1, decode);
            failed++;
        }
        round_trip(of, frame, len, &message, "vector");
        (*decoded)++;
    }
}

/* The other protocols' messages by hand: a SkyTraq 0xA8 cut to 20 bytes after its id (naming the
   protocol, message and field), an id no layout describes kept with its payload, a SiRF frame whose
   checksum is off by one, a Unicore message's header fields. */
static void other_protocols(void)
{
    static const uint8_t unknown[] = {0xA0, 0xA1, 0x00, 0x02, 0x7E, 0x01, 0x7F, 0x0D, 0x0A};
    static const uint8_t bad[] = {0xA0, 0xA2, 0x00, 0x02, 0x12, 0x00, 0x00, 0x13, 0xB0, 0xB3};
    static nmea_ubx_message message;
    uint8_t frame[64];
    char json[128];
    nmea_ubx_error err;
    memset(frame, 0, sizeof frame);
    memcpy(frame, "\xA0\xA1\x00\x15\xA8", 5); /* 21 bytes: the id and 20 of zeros, their XOR 0xA8 */
    memcpy(frame + 25, "\xA8\x0D\x0A", 3);
    if (nmea_ubx_decode_frame_of(NMEA_UBX_PROTOCOL_SKYTRAQ, frame, 28, &message, &err) ||
        err.kind != NMEA_UBX_SHORT_PAYLOAD || err.protocol != NMEA_UBX_PROTOCOL_SKYTRAQ || strcmp(err.field, "msl_alt") != 0 ||
        strcmp(err.message, "0xA8") != 0 || strcmp(err.text, "msl_alt needs bytes 20-23, the payload has 20") != 0) {
        printf("FAIL a SkyTraq 0xA8 of 20 bytes: %s\n", err.text);
        failed++;
    }
    if (!nmea_ubx_decode_frame_of(NMEA_UBX_PROTOCOL_SKYTRAQ, unknown, sizeof unknown, &message, &err) ||
        message.layout != NMEA_UBX_MSG_UNKNOWN || nmea_ubx_json(&message, json, sizeof json) == 0 ||
        strcmp(json, "{\"message\":null,\"id\":126,\"payload\":\"01\"}") != 0 ||
        nmea_ubx_encode(&message, frame, sizeof frame, &err) != sizeof unknown || memcmp(frame, unknown, sizeof unknown)) {
        printf("FAIL a SkyTraq id no layout describes\n");
        failed++;
    }
    if (nmea_ubx_decode_frame_of(NMEA_UBX_PROTOCOL_SIRF, bad, sizeof bad, &message, &err) ||
        err.kind != NMEA_UBX_BAD_CHECKSUM) {
        printf("FAIL a SiRF frame whose checksum is off by one\n");
        failed++;
    }
    {   /* SBF: pysbf2's ReceiverTime (5914 rev 0; 14 bytes of fields, 2 of padding), its TOW then set
           to the do-not-use value: written back with its length and CRC, read again */
        static const uint8_t time[] = {0x24, 0x40, 0xBD, 0x13, 0x1A, 0x17, 0x18, 0x00, 0x70, 0x2F, 0xCB, 0x1C,
                                       0x3F, 0x09, 0x19, 0x05, 0x17, 0x0E, 0x0B, 0x00, 0x12, 0x07, 0x00, 0x00};
        static char text[512];
        if (!nmea_ubx_decode_frame_of(NMEA_UBX_PROTOCOL_SBF, time, sizeof time, &message, &err) ||
            message.layout != NMEA_UBX_MSG_SBF_RECEIVER_TIME || message.as.sbf_receiver_time.tow != 483078000 ||
            message.as.sbf_receiver_time.utc_year != 25 || message.as.sbf_receiver_time.trailing.len != 2 ||
            nmea_ubx_encode(&message, frame, sizeof frame, &err) != sizeof time || memcmp(frame, time, sizeof time)) {
            printf("FAIL an SBF ReceiverTime\n");
            failed++;
        }
        message.as.sbf_receiver_time.tow = 0xFFFFFFFFu;
        if (nmea_ubx_encode(&message, frame, sizeof frame, &err) != sizeof time ||
            !nmea_ubx_decode_frame_of(NMEA_UBX_PROTOCOL_SBF, frame, sizeof time, &message, &err) ||
            nmea_ubx_json(&message, text, sizeof text) == 0 ||
            !strstr(text, "\"tow\":\"do_not_use\",\"tow_raw\":4294967295,")) {
            printf("FAIL an SBF ReceiverTime of a do-not-use TOW: %s\n", text);
            failed++;
        }
        frame[2] ^= 1;
        if (nmea_ubx_decode_frame_of(NMEA_UBX_PROTOCOL_SBF, frame, sizeof time, &message, &err) ||
            err.kind != NMEA_UBX_BAD_CHECKSUM) {
            printf("FAIL an SBF block whose CRC is off by one\n");
            failed++;
        }
    }
    {   /* Unicore: a message built by hand (an id no layout describes) has its header fields 0 unless
           set; set, they are written into the frame and read back, and its JSON has them */
        static char text[512];
        memset(&message, 0, sizeof message);
        message.layout = NMEA_UBX_MSG_UNKNOWN;
        message.as.unknown.protocol = NMEA_UBX_PROTOCOL_UNICORE;
        message.as.unknown.key_len = 2;
        message.as.unknown.msg_class = 0xE8; /* message id 65512, little endian */
        message.as.unknown.msg_id = 0xFF;
        if (nmea_ubx_encode(&message, frame, sizeof frame, &err) != 28 || frame[10] != 0 || frame[11] != 0) {
            printf("FAIL a Unicore message built by hand: %s\n", err.text);
            failed++;
        }
        message.header.unicore.week = 2407;
        message.header.unicore.time_of_week = 123457250u;
        if (nmea_ubx_encode(&message, frame, sizeof frame, &err) != 28 || frame[10] != 0x67 || frame[11] != 0x09 ||
            !nmea_ubx_decode_frame_of(NMEA_UBX_PROTOCOL_UNICORE, frame, 28, &message, &err) ||
            message.header.unicore.week != 2407 || message.header.unicore.time_of_week != 123457250u ||
            nmea_ubx_json(&message, text, sizeof text) == 0 ||
            !strstr(text, "{\"message\":null,\"header\":{\"cpu_idle\":0,\"time_ref\":0,\"time_status\":0,\"week\":2407,"
                          "\"time_of_week\":123457250,")) {
            printf("FAIL a Unicore message's header fields: %s\n", text);
            failed++;
        }
    }
    {   /* SBF sub-blocks of their SBLength: a SatVisibility of two SatInfo of 10 bytes, the 2 after the
           fields kept as each one's trailing; an SBLength other than theirs not encoded, naming sb_length */
        static const uint8_t sky[] = {0x24, 0x40, 0x15, 0xCD, 0xAC, 0x0F, 0x24, 0x00, 0xE0, 0x52, 0xC9, 0x1C,
                                      0x3F, 0x09, 0x02, 0x0A, 0x03, 0x00, 0x29, 0x1A, 0x96, 0x21, 0x00, 0x02,
                                      0xAA, 0xBB, 0x04, 0x00, 0xAB, 0x43, 0xC6, 0x0C, 0x01, 0x01, 0xCC, 0xDD};
        if (!nmea_ubx_decode_frame_of(NMEA_UBX_PROTOCOL_SBF, sky, sizeof sky, &message, &err) ||
            message.layout != NMEA_UBX_MSG_SBF_SAT_VISIBILITY || message.as.sbf_sat_visibility.sat_info_count != 2 ||
            message.as.sbf_sat_visibility.sat_info[1].svid != 4 || message.as.sbf_sat_visibility.sat_info[1].trailing.len != 2 ||
            message.as.sbf_sat_visibility.sat_info[1].trailing.ptr[0] != 0xCC ||
            nmea_ubx_encode(&message, frame, sizeof frame, &err) != sizeof sky || memcmp(frame, sky, sizeof sky)) {
            printf("FAIL an SBF SatVisibility of sub-blocks of 10 bytes\n");
            failed++;
        }
        message.as.sbf_sat_visibility.sb_length = 8;
        if (nmea_ubx_encode(&message, frame, sizeof frame, &err) || err.kind != NMEA_UBX_BAD_VALUE ||
            strcmp(err.field, "sb_length") != 0 ||
            strcmp(err.text, "sb_length takes the bytes of each entry of sat_info (10), not 8") != 0) {
            printf("FAIL an SBF SatVisibility whose SBLength is not its sub-blocks': %s\n", err.text);
            failed++;
        }
    }
    {   /* SBF sub-blocks of sub-blocks: a MeasEpoch of two Type-1 of 22 bytes, the first followed by two
           Type-2 of 14 (one array of the message, from type2_first), both levels' 2 extra bytes kept; a
           type2_first past the Type-2 entries not encoded, naming type2 */
        static const uint8_t epoch[] = {0x24, 0x40, 0x85, 0xFE, 0xBB, 0x2F, 0x5C, 0x00, 0x68, 0xA2, 0xBF, 0x1C,
                                      0x3F, 0x09, 0x02, 0x16, 0x0E, 0x01, 0x0C, 0x00, 0x01, 0x00, 0x11, 0x01,
                                      0x15, 0xCD, 0x5B, 0x07, 0xE0, 0xB1, 0xFF, 0xFF, 0xF4, 0x01, 0xFD, 0xA0,
                                      0x2A, 0x00, 0x01, 0x02, 0xAA, 0xBB, 0x02, 0x28, 0x96, 0xF7, 0xFF, 0x01,
                                      0xE8, 0xFD, 0x2C, 0x01, 0x39, 0x30, 0xCC, 0xDD, 0x02, 0x28, 0x96, 0xF7,
                                      0xFF, 0x01, 0xE8, 0xFD, 0x2C, 0x01, 0x39, 0x30, 0xEE, 0xFF, 0x02, 0x00,
                                      0x05, 0x01, 0x15, 0xCD, 0x5B, 0x07, 0xE0, 0xB1, 0xFF, 0xFF, 0xF4, 0x01,
                                      0xFD, 0xA0, 0x2A, 0x00, 0x01, 0x00, 0x11, 0x22};
        const nmea_ubx_sbf_meas_epoch *e = &message.as.sbf_meas_epoch;
        uint8_t out[sizeof epoch + 8];
        if (!nmea_ubx_decode_frame_of(NMEA_UBX_PROTOCOL_SBF, epoch, sizeof epoch, &message, &err) ||
            message.layout != NMEA_UBX_MSG_SBF_MEAS_EPOCH || e->type1_count != 2 || e->type2_count != 2 ||
            e->type1[0].n2 != 2 || e->type1[0].type2_first != 0 || e->type1[1].n2 != 0 || e->type1[1].type2_first != 2 ||
            e->type1[1].svid != 5 || e->type1[0].trailing.len != 2 || e->type2[1].trailing.len != 2 ||
            e->type2[1].trailing.ptr[0] != 0xEE || e->type2[0].code_offset_msb != -1 || e->type2[0].doppler_offset_msb != -2 ||
            nmea_ubx_encode(&message, out, sizeof out, &err) != sizeof epoch || memcmp(out, epoch, sizeof epoch)) {
            printf("FAIL an SBF MeasEpoch of Type-1 and Type-2 sub-blocks: %s\n", err.text);
            failed++;
        }
        message.as.sbf_meas_epoch.type1[0].type2_first = 1;
        if (nmea_ubx_encode(&message, out, sizeof out, &err) || err.kind != NMEA_UBX_BAD_VALUE ||
            strcmp(err.field, "type2") != 0) {
            printf("FAIL an SBF MeasEpoch whose Type-1 names Type-2 entries past the array's: %s\n", err.text);
            failed++;
        }
    }
}

int main(int argc, char **argv)
{
    int decoded = 0, refused = 0, frames = 0, logs = 0, i;
    bool as_json = argc > 2 && strcmp(argv[2], "--json") == 0;
    FILE *file = argc > 1 ? fopen(argv[1], "r") : NULL;
    if (!file) {
        fprintf(stderr, "usage: test_ubx ubx.jsonl [--json] log...\n");
        return 2;
    }
    if (!as_json)
        vectors(file, &decoded, &refused);
    fclose(file);
    for (i = 2; !as_json && i < argc; i++) { /* the other protocols' vectors */
        size_t n = strlen(argv[i]);
        if (n < 6 || strcmp(argv[i] + n - 6, ".jsonl") != 0)
            continue;
        if (!(file = fopen(argv[i], "r"))) {
            printf("FAIL cannot open %s\n", argv[i]);
            failed++;
            continue;
        }
        vectors(file, &decoded, &refused);
        fclose(file);
    }
    if (as_json) {
        for (i = 3; i < argc; i++)
            frames += hex_frames(argv[i]);
        return failed != 0;
    }
#ifndef UBX_TEST_JSON_ONLY
    for (i = 2; i < argc; i++) {
        size_t n = strlen(argv[i]);
        if (n >= 6 && strcmp(argv[i] + n - 6, ".jsonl") == 0)
            continue;
        frames += log_frames(argv[i]);
        logs++;
    }
#endif
    refusals();
    by_hand();
    other_protocols();
    printf("%d decoded, %d refused, %d frames (and %d SkyTraq, SiRF, CASIC, SBF, Unicore) of %d logs round-tripped, %d cut payloads, "
           "%d over NMEA_UBX_MAX_ENTRIES %d, %d failed\n",
           decoded, refused, frames, other_frames, logs, cut_payloads, over_maximum, NMEA_UBX_MAX_ENTRIES, failed);
    return failed || decoded < 20 || refused < 2 || frames < 1000 || cut_payloads < 1000 ||
           (logs > 12 && other_frames < 1000) ||
           (NMEA_UBX_MAX_ENTRIES < 255) != (over_maximum > 0);
}
