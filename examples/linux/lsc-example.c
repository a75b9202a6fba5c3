/* A program using the installed lsc library: it encodes a servo move, prints
 * the frame, reads it back with the byte-at-a-time parser and prints what it
 * decoded. Build it with pkg-config or CMake (see README.md next to it). */
#include <lsc/lsc.h>

#include <stdio.h>

int main(void)
{
    const lsc_servo targets[] = {{1, 1500}, {2, 2000}};
    uint8_t frame[LSC_FRAME_MAX];
    int n = lsc_encode_servo_move(frame, sizeof frame, 1000, targets, 2);
    if (n < 0) {
        fprintf(stderr, "encode: %s\n", lsc_strerror(n));
        return 1;
    }
    printf("servo_move frame:");
    for (int i = 0; i < n; i++)
        printf(" %02X", frame[i]);
    printf("\n");

    uint8_t buf[LSC_FRAME_MAX];
    lsc_parser parser;
    lsc_frame f;
    int r = lsc_parser_init(&parser, buf, sizeof buf);
    for (int i = 0; r == 0 && i < n; i++)
        r = lsc_parser_feed(&parser, frame[i], &f);
    if (r != 1) {
        fprintf(stderr, "parse: %s\n", r < 0 ? lsc_strerror(r) : "incomplete frame");
        return 1;
    }
    uint16_t time_ms;
    lsc_servo got[LSC_MOVE_MAX];
    int count = lsc_decode_servo_move(&f, &time_ms, got, LSC_MOVE_MAX);
    if (count < 0) {
        fprintf(stderr, "decode: %s\n", lsc_strerror(count));
        return 1;
    }
    printf("decoded: move %d servo(s) over %u ms:", count, (unsigned)time_ms);
    for (int i = 0; i < count; i++)
        printf(" id %u -> %u", (unsigned)got[i].id, (unsigned)got[i].position);
    printf("\n");
    return count == 2 && got[1].position == 2000 ? 0 : 1;
}
