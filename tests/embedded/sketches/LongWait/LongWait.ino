// LongWait: a test sketch, not an example (run-arduino.sh builds it with the
// simavr console). The wrapper keeps its clock in 16 bits: setTimeout takes
// at most LSC_TIMEOUT_MAX (30 s), and waitForCompletion waits as long as it
// is asked, in parts, across the 16-bit clock's wrap at 65.5 s. Time passes
// quickly here: the wrapper calls yield() while it waits, and this sketch's
// yield() moves millis() on by a second. The waits run on a Stream that
// never answers, and on one whose input never stops, which cannot hold a
// call beyond its time and the 128 reads of 16 bytes it drains after it.
#include <LSC.h>

extern volatile unsigned long timer0_millis; // the Arduino core's millis()

// Swallows what is written; never has anything to read.
class Silent : public Stream {
public:
    size_t write(uint8_t) override { return 1; }
    size_t write(const uint8_t *, size_t n) override { return n; }
    int available() override { return 0; }
    int read() override { return -1; }
    int peek() override { return -1; }
};

// Noise that never stops (0x00 bytes: no frame), counting the bytes read.
class Endless : public Stream {
public:
    unsigned long reads = 0;
    size_t write(uint8_t) override { return 1; }
    size_t write(const uint8_t *, size_t n) override { return n; }
    int available() override { return 1; }
    int read() override
    {
        reads++;
        return 0;
    }
    int peek() override { return 0; }
};

static Silent silent;
static Endless endless;
LSC lsc(silent);
LSC noisy(endless);
// check() and failures: sketch_check.h (run-arduino.sh includes it)

void yield()
{
    noInterrupts();
    timer0_millis += 1000;
    interrupts();
}

// A battery read with the timeout set to ms, on the silent Stream: no
// answer, after waiting from least to least + 1 s (the yield that ends it).
static void timed_read(uint32_t ms, unsigned long least)
{
    lsc.setTimeout(ms);
    uint16_t mv = 0;
    const unsigned long start = millis();
    check("battery read, no answer", lsc.getBatteryVoltage(mv), LSC_ETIMEOUT);
    const unsigned long took = millis() - start;
    check("waited long enough", took >= least, 1);
    check("waited less than a second more", took < least + 1000, 1);
}

void setup()
{
    const unsigned long start = millis();
    check("wait 100 s for a group", lsc.waitForCompletion(100000), LSC_ETIMEOUT);
    const unsigned long took = millis() - start;
    check("waited 100 s or more", took >= 100000, 1);
    check("waited less than 101 s", took < 101000, 1);

    timed_read(100000, 30000); // more than LSC_TIMEOUT_MAX: 30 s
    timed_read(2000, 2000);

    // the read before the request drains 128 chunks, the wait reads about 2 s
    // of chunks (yield: a second each), then drains 128 more; no clock ends
    // a drain (its chunks' yields move millis() on here)
    noisy.setTimeout(2000);
    uint16_t mv = 0;
    check("battery read in endless noise", noisy.getBatteryVoltage(mv), LSC_ETIMEOUT);
    check("bytes read: 2 x 128 chunks of 16 and a few", endless.reads >= 4096 && endless.reads < 4200, 1);

    EXAMPLE_EXIT(failures == 0 ? 0 : 1);
}

void loop()
{
}
