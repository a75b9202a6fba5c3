/* lscd: its log (one line on stderr, escaped) and its clock, for the server
 * and the device thread alike. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "lsc/text.h"
#include "lscd.h"

void lscd_log(const char *fmt, ...)
{
    char line[1024], shown[4 * sizeof line];
    va_list ap;
    va_start(ap, fmt);
    (void)vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    /* one line, whatever the paths, names and messages in it hold: every byte
     * outside printable ASCII escaped by the library's one rule */
    (void)lsc_escape_text(shown, sizeof shown, line, strlen(line));
    (void)fprintf(stderr, LSCD_PROG ": %s\n", shown);
}

uint64_t lscd_now_ms(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) {
        return 0;
    }
    return (uint64_t)ts.tv_sec * 1000u + (uint64_t)ts.tv_nsec / 1000000u;
}
