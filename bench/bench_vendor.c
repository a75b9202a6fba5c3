/* The vendor's receive path, rewritten in C (bench_vendor.h says what and how). */
#include "bench_vendor.h"


/* the vendor's command numbers for what the controller sends */
enum { BATTERY = 0x0F, GROUP_RUN = 0x06, GROUP_STOP = 0x07, GROUP_COMPLETE = 0x08 };

/* The Stream as the Arduino core gives it: available() and read() are
 * virtual calls (here through pointers in the stream), and readBytes reads
 * byte by byte through timedRead, which looks at millis() (here a counter)
 * for its timeout. Not inlined, so that callgrind can tell the handler's own
 * instructions from the Stream's (--toggle-collect=vendor_stream_*). */
__attribute__((noinline)) int vendor_stream_available(const vendor_stream *s)
{
    return (int)(s->n - s->at);
}

__attribute__((noinline)) int vendor_stream_read(vendor_stream *s)
{
    return s->at < s->n ? s->data[s->at++] : -1;
}

__attribute__((noinline)) uint32_t vendor_stream_millis(vendor_stream *s)
{
    return (uint32_t)++s->clock;
}

__attribute__((noinline)) int vendor_stream_timed_read(vendor_stream *s)
{
    uint32_t start = s->millis(s);
    do {
        int c = s->read(s);
        if (c >= 0) {
            return c;
        }
    } while (s->millis(s) - start < 1000u);
    return -1;
}

__attribute__((noinline)) size_t vendor_stream_read_bytes(vendor_stream *s, uint8_t *to,
                                                          size_t want)
{
    size_t k = 0;
    while (k < want) {
        int c = vendor_stream_timed_read(s);
        if (c < 0) {
            break;
        }
        to[k++] = (uint8_t)c;
    }
    return k;
}

void vendor_stream_init(vendor_stream *s, const uint8_t *data, size_t n)
{
    s->data = data;
    s->n = n;
    s->at = 0;
    s->clock = 0;
    s->available = vendor_stream_available;
    s->read = vendor_stream_read;
    s->millis = vendor_stream_millis;
}

#define available(s) ((s)->available(s))
#define read_byte(s) ((uint8_t)(s)->read(s))
#define read_bytes vendor_stream_read_bytes

__attribute__((noinline)) void vendor_receive(vendor_state *v, vendor_stream *s)
{
    /* the vendor's is 16 bytes, and not cleared: a short frame reads what an
     * earlier one left */
    uint8_t buf[256] = {0};
    if (!available(s)) {
        return;
    }
    do {
        switch (v->header) {
        case 0:
            if (read_byte(s) == 0x55) {
                v->header = 1;
            }
            break;
        case 1:
            v->header = read_byte(s) == 0x55 ? 2 : 0;
            break;
        case 2:
            v->len = read_byte(s);
            v->header = 3;
            break;
        case 3:
            /* LEN - 1 bytes; a LEN of 0 asks for 255 here (the vendor's
             * reads on until its timeout, past its buffer) */
            if (read_bytes(s, buf, (uint8_t)(v->len - 1u)) == 0) {
                v->len = 0;
                v->header = 0;
                break;
            }
            v->frames++;
            switch (buf[0]) {
            case BATTERY: v->battery_mv = (uint16_t)(buf[1] | buf[2] << 8); break;
            case GROUP_RUN:
                v->group = buf[1];
                v->times = (uint16_t)(buf[2] | buf[3] << 8);
                v->running = 1;
                break;
            case GROUP_STOP:
            case GROUP_COMPLETE:
                v->running = 0;
                v->group = 0xFF;
                v->times = 0;
                break;
            default: break;
            }
            v->len = 0;
            v->header = 0;
            break;
        default:
            v->len = 0;
            v->header = 0;
            break;
        }
    } while (available(s));
}
