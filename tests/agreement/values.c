/* The C pair's value accessors over generated/vectors/values.jsonl, for test_values.py: each line
   of stdin is one value as its parts (the struct members), each line of stdout what the
   accessors give for it ("-" where they return false). */

#include <stdio.h>
#include <string.h>

#include "nmea.h"

int main(void)
{
    char kind[16];
    while (scanf("%15s", kind) == 1) {
        long long a, b, c, d, e, f;
        if (!strcmp(kind, "number") && scanf("%lld %lld %lld", &a, &b, &c) == 3) {
            nmea_number n = {a, (uint8_t)b, 1, c ? '-' : 0, false, true};
            printf("%.17g %.17g\n", nmea_to_double(&n), (double)nmea_to_float(&n));
        } else if (!strcmp(kind, "coordinate") && scanf("%lld %lld %lld %lld", &a, &b, &c, &d) == 4) {
            nmea_coordinate co = {(uint16_t)a, 2, (char)d, true, {b, (uint8_t)c, 2, 0, true, true}};
            printf("%ld\n", (long)nmea_coordinate_e7(&co));
        } else if (!strcmp(kind, "time") && scanf("%lld %lld %lld %lld %lld", &a, &b, &c, &d, &e) == 5) {
            nmea_time t = {(uint8_t)a, (uint8_t)b, (uint8_t)c, (uint8_t)e, (uint32_t)d, e > 0, true};
            printf("%lu\n", (unsigned long)nmea_time_ms(&t));
        } else if (!strcmp(kind, "date") && scanf("%lld %lld %lld", &a, &b, &c) == 3) {
            nmea_date date = {(uint8_t)a, (uint8_t)b, (uint8_t)c, true};
            int32_t days;
            if (nmea_date_days(&date, &days))
                printf("%d %ld\n", nmea_date_year(&date), (long)days);
            else
                printf("%d -\n", nmea_date_year(&date));
        } else if (!strcmp(kind, "datetime") &&
                   scanf("%lld %lld %lld %lld %lld %lld", &a, &b, &c, &d, &e, &f) == 6) {
            long long g, h;
            if (scanf("%lld %lld", &g, &h) != 2)
                return 2;
            nmea_date date = {(uint8_t)a, (uint8_t)b, (uint8_t)c, true};
            nmea_time t = {(uint8_t)d, (uint8_t)e, (uint8_t)f, (uint8_t)h, (uint32_t)g, h > 0, true};
            int64_t ms;
            if (nmea_datetime_ms(&date, &t, &ms))
                printf("%lld\n", (long long)ms);
            else
                printf("-\n");
        } else if (!strcmp(kind, "civil") && scanf("%lld %lld %lld", &a, &b, &c) == 3) {
            int32_t days;
            if (nmea_days_from_civil((int32_t)a, (int)b, (int)c, &days))
                printf("%ld\n", (long)days);
            else
                printf("-\n");
        } else {
            return 2;
        }
    }
    return 0;
}
