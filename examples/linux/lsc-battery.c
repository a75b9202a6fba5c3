/* A program using the installed lsc library's client and virtual controller:
 * it moves servo 1 and asks for the battery voltage, exactly as it would over
 * a serial port (lsc/serial.h), but talking to an in-process simulated board.
 * Built only when the installed lsc has the client and the simulator. */
#include <lsc/lsc.h>

#include <stdio.h>

int main(void)
{
    lsc_sim board;
    lsc_io io;
    lsc_client client;
    if (lsc_sim_init(&board) != 0 || lsc_sim_io_init(&board, &io) != 0 ||
        lsc_client_init(&client, &io) != 0) {
        fprintf(stderr, "init failed\n");
        return 1;
    }
    lsc_sim_set_battery(&board, 7400);

    int r = lsc_client_move_one(&client, 1, 2000, 500);
    if (r < 0) {
        fprintf(stderr, "move: %s\n", lsc_strerror(r));
        return 1;
    }
    lsc_sim_advance_ms(&board, 600);
    uint16_t mv = 0;
    r = lsc_client_get_battery(&client, &mv, 100);
    if (r < 0) {
        fprintf(stderr, "battery: %s\n", lsc_strerror(r));
        return 1;
    }
    printf("servo 1 at %u, battery %u mV\n", (unsigned)lsc_sim_position(&board, 1), (unsigned)mv);
    return lsc_sim_position(&board, 1) == 2000 && mv == 7400 ? 0 : 1;
}
