// ParserRules: a test sketch, not an example (run-arduino.sh builds it with
// the simavr console). The core's parser as a sketch compiles it: at -Os,
// its feed inlined at the one place that calls it, with a capacity the
// compiler sees (32 bytes, as LSC's own), which gives it a length of one byte
// (src/core/parser.c). Each input goes in byte by byte; a line shows the
// result of every byte: '.' more needed, 'F' a frame (its fields checked
// against the bytes fed), 'S' LSC_ESYNC, 'E' LSC_EFRAME, 'B' LSC_ETOOBIG.
// The expected results and counters are the rules of lsc/core.h and
// docs/parser.md, the same on every build.
#include <LSC.h>
// check() and failures: sketch_check.h (run-arduino.sh includes it)

struct Input {
    const char *name;
    uint8_t n;
    uint8_t bytes[10];
    const char *want;
};

static const Input inputs[] = {
    {"battery reply", 6, {0x55, 0x55, 0x04, 0x0F, 0x7C, 0x1D}, ".....F"},
    {"noise, group stop", 6, {0x00, 0xFF, 0x55, 0x55, 0x02, 0x07}, "SS...F"},
    {"LEN 0x55: one more header byte", 5, {0x55, 0x55, 0x55, 0x02, 0x07}, "..S.F"},
    {"header byte, noise", 2, {0x55, 0x01}, ".S"},
    {"LEN below 2", 3, {0x55, 0x55, 0x01}, "..E"},
    {"LEN 31: too big for 32 bytes", 3, {0x55, 0x55, 0x1F}, "..B"},
    {"LEN 255", 3, {0x55, 0x55, 0xFF}, "..B"},
    {"group stop of LEN 3", 4, {0x55, 0x55, 0x03, 0x07}, "...E"},
    {"battery of LEN 3", 4, {0x55, 0x55, 0x03, 0x0F}, "...E"},
    {"move of LEN 5", 4, {0x55, 0x55, 0x05, 0x03}, "...E"},
    {"position read, count 2 in LEN 4", 5, {0x55, 0x55, 0x04, 0x15, 0x02}, "....E"},
    {"unload of count 0", 5, {0x55, 0x55, 0x04, 0x14, 0x00}, "....E"},
    {"count 0x55 begins a frame", 10, {0x55, 0x55, 0x04, 0x15, 0x55, 0x55, 0x04, 0x15, 0x01, 0x05},
     "....E....F"},
    {"position reply of 1 servo", 8, {0x55, 0x55, 0x06, 0x15, 0x01, 0x05, 0xE8, 0x03}, ".......F"},
    {"move of 1 servo", 10, {0x55, 0x55, 0x08, 0x03, 0x01, 0xE8, 0x03, 0x01, 0xDC, 0x05},
     ".........F"},
    {"unknown command, any LEN", 5, {0x55, 0x55, 0x03, 0x30, 0xAA}, "....F"},
    {"command 0x55", 5, {0x55, 0x55, 0x03, 0x55, 0x00}, "....F"},
    {"LEN 30: a frame of 32 bytes", 4, {0x55, 0x55, 0x1E, 0x40}, "...."},
};

static char result(int rc)
{
    switch (rc) {
    case 0: return '.';
    case 1: return 'F';
    case LSC_ESYNC: return 'S';
    case LSC_EFRAME: return 'E';
    case LSC_ETOOBIG: return 'B';
    default: return '?';
    }
}

static void show(const char *name, const char *got, const char *want)
{
    EXAMPLE_CONSOLE.print(name);
    EXAMPLE_CONSOLE.print(": ");
    EXAMPLE_CONSOLE.print(got);
    if (strcmp(got, want) != 0) {
        EXAMPLE_CONSOLE.print(" FAIL, want ");
        EXAMPLE_CONSOLE.print(want);
        failures++;
    }
    EXAMPLE_CONSOLE.println();
}

void setup()
{
    uint8_t buf[32];
    lsc_parser p;
    lsc_parser_init(&p, buf, sizeof buf);
    // the inputs, then the 28 parameter bytes of the frame of LEN 30 begun
    // by the last one, in one loop (one call of lsc_parser_feed)
    uint8_t input = 0, at = 0;
    char got[30];
    for (;;) {
        const bool params = input == sizeof inputs / sizeof inputs[0];
        const Input *in = params ? 0 : &inputs[input];
        const uint8_t n = params ? 28 : in->n;
        const uint8_t b = params ? at : in->bytes[at];
        lsc_frame f;
        int rc = lsc_parser_feed(&p, b, &f);
        got[at] = result(rc);
        // a frame: its fields, and (but for the frame of LEN 30) its bytes
        // as the last ones fed
        if (rc == 1 && (f.params != buf + 4 || f.nparams + 4u != p.len || f.cmd != buf[3] ||
                        (!params && (at + 1u < p.len ||
                                     memcmp(buf, &in->bytes[at + 1 - p.len], p.len) != 0))))
            got[at] = '!';
        if (++at < n)
            continue;
        got[at] = 0;
        if (params) {
            show("  its 28 parameter bytes", got, "...........................F");
            break;
        }
        show(in->name, got, in->want);
        at = 0;
        input++;
    }
    check("frames", (long)p.frames, 9);
    check("discarded", (long)p.discarded, 40);
    check("errors", (long)p.errors, 9);
    EXAMPLE_EXIT(failures == 0 ? 0 : 1);
}

void loop()
{
}
