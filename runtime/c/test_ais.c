/* The AIS messages (nmea_ais.c) against generated/vectors/ais.jsonl, which the Python codec
   decodes and encodes too: every payload decodes to the same JSON as Python's or fails with the
   same error kind, and encodes back to the same armored characters and fill bits. Then the
   assembler against tests/data/ais/assembly_cases.jsonl, the events Python's gives of the same
   lines: those cases whose slots are this build's NMEA_AIS_SLOTS (the Makefile builds it twice).
   Usage: test_ais path/to/ais.jsonl path/to/assembly_cases.jsonl */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "nmea_ais.h"

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

/* The events of an assembly case as the file writes them, gathered by the callback. */
typedef struct {
    char text[8192];
    size_t len;
    long after; /* the line fed last, -1 once finished */
} events;

static void add_event(const nmea_ais_assembled *done, void *context)
{
    events *e = context;
    nmea_ais_message message;
    nmea_ais_error err;
    size_t i;
    char *out = e->text + e->len;
    size_t cap = sizeof e->text - e->len;
    int n = e->after < 0 ? snprintf(out, cap, "{\"after\":null,\"lines\":[")
                         : snprintf(out, cap, "{\"after\":%ld,\"lines\":[", e->after);
    for (i = 0; i < done->n; i++)
        n += snprintf(out + n, cap - (size_t)n, "%s%lu", i ? "," : "", (unsigned long)done->lines[i]);
    if (done->complete) {
        n += snprintf(out + n, cap - (size_t)n, "],\"payload\":\"%.*s\",\"fill_bits\":%u", (int)done->payload_len,
                      done->payload, done->fill_bits);
        if (!nmea_ais_decode(done->payload, done->payload_len, done->fill_bits, &message, &err))
            n += snprintf(out + n, cap - (size_t)n, ",\"error\":\"%s\"", nmea_ais_error_kind_name(err.kind));
        n += snprintf(out + n, cap - (size_t)n, "},");
    } else {
        n += snprintf(out + n, cap - (size_t)n, "],\"error\":\"incomplete_message\"},");
    }
    e->len += (size_t)n;
}

/* The next JSON string of `*p` (whose only escapes are \\ and \") into `out`; false at the
   array's end. */
static bool next_string(const char **p, char *out, size_t cap)
{
    size_t len = 0;
    while (**p == ',' || **p == '[')
        (*p)++;
    if (**p != '"')
        return false;
    for ((*p)++; **p && **p != '"'; (*p)++) {
        if (**p == '\\')
            (*p)++;
        if (len + 1 < cap)
            out[len++] = **p;
    }
    (*p)++;
    out[len] = '\0';
    return true;
}

/* Runs the case of `record` when its slots are this build's: 1 passed, 0 skipped, -1 failed. */
static int assembly_case(const char *record)
{
    static nmea_ais_assembler assembler;
    static events got;
    char slots[8], lifetime[8], line[NMEA_MAX_LINE + 1];
    const char *p = strstr(record, "\"lines\":[") + 8;
    const char *want = strstr(record, "\"events\":") + 9;
    member(record, "slots", slots, sizeof slots);
    member(record, "lifetime", lifetime, sizeof lifetime);
    if (atoi(slots) != NMEA_AIS_SLOTS)
        return 0;
    nmea_ais_assembler_init(&assembler, (uint32_t)atoi(lifetime));
    got.text[0] = '[';
    got.len = 1;
    for (got.after = 0; next_string(&p, line, sizeof line); got.after++) {
        nmea_sentence s;
        nmea_error err;
        nmea_ais_fragment fragment;
        if (!nmea_parse(&s, line, strlen(line), &err)) {
            char message[256];
            nmea_error_message(&err, message, sizeof message);
            printf("FAIL %s: %s\n", message, line);
            return -1;
        }
        nmea_ais_assembler_feed(&assembler, nmea_ais_fragment_of(&s, &fragment) ? &fragment : NULL, s.tag_blocks,
                                add_event, &got);
    }
    got.after = -1;
    nmea_ais_assembler_finish(&assembler, add_event, &got);
    got.len -= got.len > 1; /* the last comma */
    got.text[got.len++] = ']';
    if (got.len != strlen(want) - 1 || strncmp(got.text, want, got.len) != 0) {
        printf("FAIL assembly\n  got  %.*s\n  want %s\n", (int)got.len, got.text, want);
        return -1;
    }
    return 1;
}

/* A message a program builds with its own text: a safety broadcast (text to the end) and a static
   data report's name (a field of 20 characters, padded with '@'); 0 when all is as said. */
static int built_messages(void)
{
    char text[32], name[20], json[1024];
    nmea_ais_message message, back;
    nmea_ais_armored armored;
    nmea_ais_error err;
    int failed = 0;
    memset(&message, 0, sizeof message);
    message.layout = NMEA_AIS_SAFETY_BROADCAST;
    message.as.safety_broadcast.message_type = 14;
    message.as.safety_broadcast.mmsi = 366999999;
    failed |= !nmea_ais_text("ALL SHIPS: BUOY ADRIFT", text, sizeof text, &message.as.safety_broadcast.text, &err);
    failed |= !nmea_ais_encode(&message, &armored, &err) ||
              !nmea_ais_decode(armored.chars, strlen(armored.chars), armored.fill_bits, &back, &err);
    nmea_ais_json(&back, armored.fill_bits, json, sizeof json);
    failed |= strstr(json, "\"text\":\"ALL SHIPS: BUOY ADRIFT\"") == NULL;

    memset(&message, 0, sizeof message);
    message.layout = NMEA_AIS_STATIC_DATA_REPORT;
    message.as.static_data_report.message_type = 24;
    message.as.static_data_report.mmsi = 257000000;
    message.as.static_data_report.has_shipname = message.as.static_data_report.has_spare = true;
    failed |= !nmea_ais_text("NORDIC STAR@@@@@@@@@", name, sizeof name, &message.as.static_data_report.shipname, &err);
    failed |= !nmea_ais_encode(&message, &armored, &err) ||
              !nmea_ais_decode(armored.chars, strlen(armored.chars), armored.fill_bits, &back, &err);
    nmea_ais_json(&back, armored.fill_bits, json, sizeof json);
    failed |= strstr(json, "\"shipname\":\"NORDIC STAR@@@@@@@@@\"") == NULL;
    /* a name short of its field's 20 characters, a character six-bit text lacks, a buffer too short */
    failed |= !nmea_ais_text("NORDIC STAR", name, sizeof name, &message.as.static_data_report.shipname, &err);
    failed |= nmea_ais_encode(&message, &armored, &err) || err.kind != NMEA_AIS_BAD_VALUE ||
              strcmp(err.message, "shipname takes 20 six-bit text characters, not 11") != 0;
    failed |= nmea_ais_text("nordic", name, sizeof name, &message.as.static_data_report.shipname, &err) ||
              strcmp(err.message, "text takes six-bit text characters, not 'n'") != 0;
    failed |= nmea_ais_text("NORDIC STAR", name, 4, &message.as.static_data_report.shipname, &err) ||
              err.kind != NMEA_AIS_BAD_VALUE;
    if (failed)
        printf("FAIL a message built with its own text\n");
    return failed;
}

int main(int argc, char **argv)
{
    static char record[8192], json[8192];
    char payload[512], fill[8], error[32];
    int decoded = 0, refused = 0, failed = 0, assembled = 0, records = 0;
    FILE *file = argc > 2 ? fopen(argv[1], "r") : NULL;
    FILE *cases = argc > 2 ? fopen(argv[2], "r") : NULL;
    if (!file || !cases) {
        fprintf(stderr, "usage: test_ais ais.jsonl assembly_cases.jsonl\n");
        return 2;
    }
    while (fgets(record, sizeof record, file)) {
        nmea_ais_message message;
        nmea_ais_error err;
        nmea_ais_armored armored;
        unsigned fill_bits;
        const char *decode;
        bool ok;
        record[strcspn(record, "\n")] = '\0';
        records++;
        member(record, "payload", payload, sizeof payload);
        member(record, "fill_bits", fill, sizeof fill);
        member(record, "error", error, sizeof error);
        fill_bits = (unsigned)atoi(fill);
        ok = nmea_ais_decode(payload, strlen(payload), fill_bits, &message, &err);
        if (error[0]) {
            if (ok || strcmp(nmea_ais_error_kind_name(err.kind), error) != 0) {
                printf("FAIL error %s: %s\n", ok ? "none" : nmea_ais_error_kind_name(err.kind), record);
                failed++;
            }
            refused++;
            continue;
        }
        if (!ok) {
            printf("FAIL %s: %s\n", err.message, record);
            failed++;
            continue;
        }
        nmea_ais_json(&message, fill_bits, json, sizeof json);
        decode = strstr(record, "\"decode\":") + 9;
        if (strncmp(json, decode, strlen(decode) - 1) != 0 || strlen(json) != strlen(decode) - 1) {
            printf("FAIL json\n  got  %s\n  want %.*s\n", json, (int)strlen(decode) - 1, decode);
            failed++;
        }
        if (!nmea_ais_encode(&message, &armored, &err) || strcmp(armored.chars, payload) != 0 ||
            armored.fill_bits != fill_bits) {
            printf("FAIL encode %s,%u: %s\n", armored.chars, armored.fill_bits, record);
            failed++;
        }
        decoded++;
    }
    fclose(file);
    while (fgets(record, sizeof record, cases)) {
        int outcome;
        record[strcspn(record, "\n")] = '\0';
        outcome = assembly_case(record);
        assembled += outcome > 0;
        failed += outcome < 0;
    }
    fclose(cases);
    failed += built_messages();
    printf("%d decoded, %d refused, %d assembly cases of %d slots, %d failed\n", decoded, refused, assembled,
           NMEA_AIS_SLOTS, failed);
    /* Every record decoded or refused as it says (a record to refuse names its error), and the
       vectors hold some of each. */
    return failed || decoded + refused != records || !decoded || !refused || !assembled;
}
