/* A program using the installed lsc library's core: it builds the request
 * that reads servos 1 and 2, then parses a controller's reply to it, byte by
 * byte as a serial port would deliver it, and decodes the positions.
 * Build it with pkg-config or CMake (see README.md next to it). */
#include <lsc/lsc.h>

#include <stdio.h>

int main(void)
{
    const uint8_t ids[] = {1, 2};
    uint8_t request[LSC_FRAME_MAX];
    int n = lsc_encode_pos_request(request, sizeof request, ids, sizeof ids);
    if (n < 0) {
        fprintf(stderr, "request: %s\n", lsc_strerror(n));
        return 1;
    }
    printf("request:");
    for (int i = 0; i < n; i++)
        printf(" %02X", request[i]);
    printf("\n");

    /* The reply: servo 1 at 1500, servo 2 at 2000. */
    static const uint8_t reply[] = {0x55, 0x55, 0x09, 0x15, 0x02, 0x01,
                                    0xDC, 0x05, 0x02, 0xD0, 0x07};
    uint8_t buf[LSC_FRAME_MAX];
    lsc_parser parser;
    if (lsc_parser_init(&parser, buf, sizeof buf) != 0)
        return 1;
    for (size_t i = 0; i < sizeof reply; i++) {
        lsc_frame frame;
        int r = lsc_parser_feed(&parser, reply[i], &frame);
        if (r < 0) {
            fprintf(stderr, "reply byte %zu: %s\n", i, lsc_strerror(r));
            return 1;
        }
        if (r == 1) {
            lsc_servo servos[LSC_READ_MAX];
            int count = lsc_decode_pos_reply(&frame, servos, LSC_READ_MAX);
            if (count < 0) {
                fprintf(stderr, "decode: %s\n", lsc_strerror(count));
                return 1;
            }
            printf("positions:");
            for (int k = 0; k < count; k++)
                printf(" servo %u at %u", (unsigned)servos[k].id, (unsigned)servos[k].position);
            printf("\n");
            return count == 2 && servos[1].position == 2000 ? 0 : 1;
        }
    }
    fprintf(stderr, "no complete reply\n");
    return 1;
}
