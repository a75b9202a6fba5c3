// ActionGroup: runs an action group stored on the controller and waits for
// it to finish, then runs one in a loop and stops it. The controller reports
// when a group starts, completes or is stopped; onNotification() hands those
// reports to a function of the sketch.
//
// Wiring as in Basic: the controller on Serial (Serial1 where the board has
// one, with Serial printing what happens).
#include <LSC.h>

#if defined(HAVE_HWSERIAL1)
#define CONTROLLER Serial1
#ifndef EXAMPLE_CONSOLE
#define EXAMPLE_CONSOLE Serial
#endif
#else
#define CONTROLLER Serial
#endif
#ifndef EXAMPLE_EXIT
#define EXAMPLE_EXIT(code) (void)(code)
#endif

const uint8_t GROUP = 1;

LSC lsc(CONTROLLER);

void say(const char *text, long value);
void onGroupNews(const LSCNotification &n);

void say(const char *text, long value)
{
#ifdef EXAMPLE_CONSOLE
    EXAMPLE_CONSOLE.print(text);
    EXAMPLE_CONSOLE.println(value);
#else
    (void)text;
    (void)value;
#endif
}

void onGroupNews(const LSCNotification &n)
{
    if (n.cmd == LSC_CMD_GROUP_RUN)
        say("started group ", n.group);
    else if (n.cmd == LSC_CMD_GROUP_COMPLETE)
        say("completed group ", n.group);
    else
        say("stopped, command ", n.cmd);
}

void setup()
{
#if defined(EXAMPLE_CONSOLE) && defined(HAVE_HWSERIAL1)
    Serial.begin(115200);
#endif
    CONTROLLER.begin(9600);
    lsc.begin();
    lsc.onNotification(onGroupNews);
    int failures = 0;

    // Once through, waiting (at most 10 s) until it is done.
    lsc.runActionGroup(GROUP, 1);
    int end = lsc.waitForCompletion(10000);
    say("first run ended with ", end);
    failures += end != LSC_CMD_GROUP_COMPLETE;

    // Over and over (times 0), until the sketch stops it.
    lsc.setActionGroupSpeed(GROUP, 200);
    lsc.runActionGroup(GROUP, 0);
    delay(700);
    bool running = lsc.isRunning();
    say("running after 700 ms: ", running);
    failures += !running;
    lsc.stopActionGroup();
    end = lsc.waitForCompletion(1000);
    say("second run ended with ", end);
    failures += end != LSC_CMD_GROUP_STOP;
    running = lsc.isRunning();
    say("running after the stop: ", running);
    failures += running;

    EXAMPLE_EXIT(failures);
}

void loop()
{
    lsc.poll(); // hands over notifications (a group started from the handle, ...)
}
