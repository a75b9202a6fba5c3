// OddStreams: a test sketch, not an example (run-arduino.sh builds it with
// the simavr console). The wrapper on Streams that are no controller: one
// that never answers, two whose input never stops (noise, and header bytes
// that keep a frame partial for ever), and one that echoes what is written,
// as a half-duplex line does.
// The wrapper keeps its clock in 16 bits: setTimeout takes at most
// LSC_TIMEOUT_MAX (30 s), and waitForCompletion waits as long as it is
// asked, in parts, across the 16-bit clock's wrap at 65.5 s. Time passes
// quickly here: the wrapper calls yield() while it waits, and this sketch's
// yield() moves millis() on by a second.
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

// The same byte for ever, counting the bytes read.
class Endless : public Stream {
public:
    explicit Endless(uint8_t b) : byte_(b) {}
    unsigned long reads = 0;
    size_t write(uint8_t) override { return 1; }
    size_t write(const uint8_t *, size_t n) override { return n; }
    int available() override { return 1; }
    int read() override
    {
        reads++;
        return byte_;
    }
    int peek() override { return byte_; }

private:
    uint8_t byte_;
};

// Reads back what was written (up to 32 bytes at a time).
class Echo : public Stream {
public:
    size_t write(uint8_t b) override
    {
        if (n_ == sizeof buf_)
            return 0;
        buf_[n_++] = b;
        return 1;
    }
    int available() override { return n_ - at_; }
    int read() override
    {
        if (at_ == n_) {
            at_ = n_ = 0;
            return -1;
        }
        return buf_[at_++];
    }
    int peek() override { return at_ == n_ ? -1 : buf_[at_]; }

private:
    uint8_t buf_[32];
    uint8_t n_ = 0, at_ = 0;
};

static Silent silent;
static Endless noise(0x00), headers(0x55);
static Echo echo;
LSC lsc(silent);
LSC noisy(noise);
LSC partial(headers);
LSC echoed(echo);
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

// A battery read in input that never stops: the read before the request
// drains 128 chunks of 16 bytes, the wait reads about 2 s of chunks (yield:
// a second each), then drains 128 more; no clock ends a drain (its chunks'
// yields move millis() on here), and a frame kept partial is cut.
static void endless_read(const char *what, LSC &l, const Endless &s)
{
    l.setTimeout(2000);
    uint16_t mv = 0;
    check(what, l.getBatteryVoltage(mv), LSC_ETIMEOUT);
    check("bytes read: 2 x 128 chunks of 16 and a few", s.reads >= 4096 && s.reads < 4200, 1);
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

    endless_read("battery read in endless noise", noisy, noise);
    endless_read("battery read in endless header bytes", partial, headers);

    // the request read back: a position frame of the request's shape, which
    // is no reply (and is not walked as one)
    echoed.setTimeout(2000);
    const uint8_t one = 1;
    LSCServo s = {0, 0};
    check("position read, its request echoed", echoed.readPositions(&one, 1, &s), LSC_EREPLY);
    check("nothing written", s.id, 0);

    EXAMPLE_EXIT(failures == 0 ? 0 : 1);
}

void loop()
{
}
