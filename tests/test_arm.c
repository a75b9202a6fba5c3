/* Tests of arm profiles (include/lsc/arm.h, src/arm): the format of
 * docs/arm-profile.md and every reason it gives, JOINT:VALUE targets, the
 * exact limit rule (the position that would be sent is what is checked),
 * profiles whose limits hold no position, only regular files, a UTF-8
 * byte-order mark, file names with control characters in messages, and the
 * internal escaping (src/util/escape.h).
 *
 * malloc and read are interposed with the linker's --wrap
 * (tests/CMakeLists.txt): a test can make the library's next allocation fail,
 * or its reads fail, be interrupted (EINTR) or come a few bytes at a time. */
#define _DEFAULT_SOURCE /* mkdtemp */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include "lsc/arm.h"
#include "../src/util/escape.h"

/* ---- Interposed calls --------------------------------------------------------- */

void *__real_malloc(size_t n); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
void *__wrap_malloc(size_t n); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
void *__real_calloc(size_t n, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
void *__wrap_calloc(size_t n, size_t size); // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
ssize_t __real_read(int fd, void *buf, size_t n);
ssize_t __wrap_read(int fd, void *buf, size_t n);

static int fail_malloc;   /* > 0: the fail_malloc-th allocation from now fails */
static int read_errno;    /* != 0: the next read fails with it */
static size_t read_chunk; /* > 0: reads return at most this many bytes */
static unsigned reads;    /* reads made */

void *__wrap_malloc(size_t n) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    if (fail_malloc > 0 && --fail_malloc == 0) {
        return NULL;
    }
    return __real_malloc(n);
}

/* An optimiser turns malloc then memset 0 into calloc: the same count. */
void *__wrap_calloc(size_t n, size_t size) // NOLINT(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp)
{
    if (fail_malloc > 0 && --fail_malloc == 0) {
        return NULL;
    }
    return __real_calloc(n, size);
}

ssize_t __wrap_read(int fd, void *buf, size_t n)
{
    reads++;
    if (read_errno != 0) {
        errno = read_errno;
        read_errno = 0;
        return -1;
    }
    if (read_chunk > 0 && n > read_chunk) {
        n = read_chunk;
    }
    return __real_read(fd, buf, n);
}

/* ---- Helpers ------------------------------------------------------------------ */

static char why[LSC_ARM_MESSAGE_MAX];

static lsc_arm *parse_ok(const char *text)
{
    lsc_arm *arm = NULL;
    why[0] = '\0';
    int r = lsc_arm_parse(text, strlen(text), "t.conf", &arm, why, sizeof why);
    if (r != 0) {
        fail_msg("'%s' refused: %s", text, why);
    }
    assert_non_null(arm);
    return arm;
}

/* text is refused with exactly want (after "t.conf:") */
static void parse_bad(const char *text, size_t len, const char *want)
{
    lsc_arm *arm = (lsc_arm *)&arm; /* must become NULL */
    char full[LSC_ARM_MESSAGE_MAX + 8];
    assert_true(snprintf(full, sizeof full, "t.conf%s", want) < (int)sizeof full);
    why[0] = '\0';
    assert_int_equal(lsc_arm_parse(text, len, "t.conf", &arm, why, sizeof why), LSC_EINVAL);
    assert_null(arm);
    assert_string_equal(why, full);
}

static void bad(const char *text, const char *want)
{
    parse_bad(text, strlen(text), want);
}

/* target arg through arm: 0 and servo id:pos */
static void target_ok(const lsc_arm *arm, const char *arg, uint8_t id, uint16_t pos)
{
    lsc_servo s = {0, 0};
    why[0] = '\0';
    if (lsc_arm_target(arm, arg, &s, why, sizeof why) != 0) {
        fail_msg("'%s' refused: %s", arg, why);
    }
    assert_int_equal(s.id, id);
    assert_int_equal(s.position, pos);
}

static void target_bad(const lsc_arm *arm, const char *arg, const char *want)
{
    lsc_servo s = {77, 777};
    why[0] = '\0';
    assert_int_equal(lsc_arm_target(arm, arg, &s, why, sizeof why), LSC_EINVAL);
    assert_int_equal(s.id, 77);
    assert_int_equal(s.position, 777);
    assert_string_equal(why, want);
}

static const char xarm[] = "gripper        1  bus  limits=0..700\n"
                           "wrist-rotate   2  bus  limits=-115deg..115deg\n"
                           "wrist          3  bus  limits=-115deg..115deg\n"
                           "elbow          4  bus  limits=-115deg..115deg\n"
                           "shoulder       5  bus  limits=-115deg..115deg\n"
                           "base           6  bus  limits=-115deg..115deg\n";
static const char learm[] = "gripper        1  pwm  limits=1500..2500\n"
                            "wrist-rotate   2  pwm\n"
                            "shoulder       5  pwm  dir=-1  offset=90deg  limits=0deg..175deg\n"
                            "base           6  pwm  limits=-85deg..85deg\n";

/* A scratch directory for files, removed at the end. */
static char dir[64];

static int make_dir(void **state)
{
    (void)state;
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/lsc-arm-XXXXXX", tmp != NULL && strlen(tmp) < 40 ? tmp : "/tmp");
    return mkdtemp(dir) != NULL ? 0 : -1;
}

static void in_dir(char *out, size_t cap, const char *name)
{
    snprintf(out, cap, "%s/%s", dir, name);
}

static void write_file(const char *path, const char *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

static int remove_dir(void **state)
{
    (void)state;
    static const char *const names[] = {"ok.conf", "fifo.conf", "big.conf", "max.conf",
                                        "bom.conf", "a\nb\033[2J.conf"};
    char path[128];
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        in_dir(path, sizeof path, names[i]);
        (void)unlink(path);
    }
    return rmdir(dir);
}

/* ---- The escaping ------------------------------------------------------------- */

static void test_escape(void **state)
{
    (void)state;
    char out[32];
    assert_int_equal(lsc_escape_text(out, sizeof out, "a b~", 4), 4);
    assert_string_equal(out, "a b~");
    assert_int_equal(lsc_escape_text(out, sizeof out, "\\\n\033\x7f\xff", 5), 18);
    assert_string_equal(out, "\\\\\\x0A\\x1B\\x7F\\xFF");
    /* up to n bytes, up to a NUL */
    assert_int_equal(lsc_escape_text(out, sizeof out, "abcdef", 3), 3);
    assert_string_equal(out, "abc");
    assert_int_equal(lsc_escape_text(out, sizeof out, "ab\0cd", 5), 2);
    assert_string_equal(out, "ab");
    assert_int_equal(lsc_escape_text(out, sizeof out, NULL, 0), 0);
    assert_string_equal(out, "");
    /* cut to fit, never inside an escape */
    assert_int_equal(lsc_escape_text(out, 6, "ab\ncd", 5), 2);
    assert_string_equal(out, "ab");
    assert_int_equal(lsc_escape_text(out, 7, "ab\ncd", 5), 6);
    assert_string_equal(out, "ab\\x0A");
    assert_int_equal(lsc_escape_text(out, 3, "a\\", 2), 1);
    assert_string_equal(out, "a");
    assert_int_equal(lsc_escape_text(out, 1, "abc", 3), 0);
    assert_string_equal(out, "");
    out[0] = 'x';
    assert_int_equal(lsc_escape_text(out, 0, "abc", 3), 0);
    assert_int_equal(out[0], 'x');
}

/* ---- The profile -------------------------------------------------------------- */

/* Servo id of sim moved to position at once, by a host's frame. */
static void stand_in_move(lsc_sim *sim, uint8_t id, uint16_t position)
{
    uint8_t frame[LSC_FRAME_MAX];
    const lsc_servo to = {id, position};
    int n = lsc_encode_servo_move(frame, sizeof frame, 0, &to, 1);
    assert_true(n > 0);
    assert_int_equal(lsc_sim_feed(sim, frame, (size_t)n), n);
}

/* A virtual controller standing in for an arm: each joint's servo at its
 * zero (the LeArm's shoulder, zero 90 degrees off its servo's middle, at
 * the end of its range), its moves within its servo's range; other servos
 * as they were. */
static void test_stand_in(void **state)
{
    (void)state;
    static lsc_sim sim;
    lsc_arm *arm = parse_ok("base 6 bus\nshoulder 5 pwm dir=-1 offset=90deg\n");
    assert_int_equal(lsc_sim_init(&sim), 0);
    assert_int_equal(lsc_arm_stand_in(arm, &sim), 0);
    assert_int_equal(lsc_sim_position(&sim, 6), 500);
    assert_int_equal(lsc_sim_position(&sim, 5), lsc_arm_joint(arm, 1)->zero);
    assert_int_equal(lsc_sim_position(&sim, 1), 1500);
    /* their ranges: moves beyond stop at the ends */
    stand_in_move(&sim, 6, 1500);
    assert_int_equal(lsc_sim_position(&sim, 6), 1000);
    stand_in_move(&sim, 5, 100);
    assert_int_equal(lsc_sim_position(&sim, 5), 500);
    stand_in_move(&sim, 5, 3000);
    assert_int_equal(lsc_sim_position(&sim, 5), 2500);
    assert_int_equal(lsc_arm_stand_in(NULL, &sim), LSC_EINVAL);
    assert_int_equal(lsc_arm_stand_in(arm, NULL), LSC_EINVAL);
    lsc_arm_free(arm);
}

static void test_examples(void **state)
{
    (void)state;
    lsc_arm *arm = parse_ok(xarm);
    assert_int_equal(lsc_arm_count(arm), 6);
    assert_string_equal(lsc_arm_name(arm, 0), "gripper");
    assert_string_equal(lsc_arm_name(arm, 5), "base");
    const lsc_joint *j = lsc_arm_joint(arm, 5);
    assert_int_equal(j->id, 6);
    assert_int_equal(j->direction, 1);
    assert_int_equal(j->pos_min, 0);
    assert_int_equal(j->pos_max, 1000);
    assert_int_equal(j->span_cdeg, 24000);
    assert_int_equal(j->zero, 500);
    assert_int_equal(j->min_cdeg, -11500);
    assert_int_equal(j->max_cdeg, 11500);
    j = lsc_arm_joint(arm, 0); /* positions as limits: their angles */
    assert_int_equal(j->min_cdeg, -12000);
    assert_int_equal(j->max_cdeg, 4800);
    lsc_arm_free(arm);

    arm = parse_ok(learm);
    j = lsc_arm_joint(arm, 2);
    assert_int_equal(j->id, 5);
    assert_int_equal(j->direction, -1);
    assert_int_equal(j->zero, 2500); /* 90 degrees of the servo from the middle */
    assert_int_equal(j->min_cdeg, 0);
    assert_int_equal(j->max_cdeg, 17500);
    j = lsc_arm_joint(arm, 1); /* no limits: the whole range */
    assert_int_equal(j->min_cdeg, -9000);
    assert_int_equal(j->max_cdeg, 9000);
    lsc_arm_free(arm);
}

static void test_every_setting(void **state)
{
    (void)state;
    /* a 12-bit servo over 360 degrees, reversed, offset, limits in positions,
     * tabs, comments, CRLF, a lone CR at the very end */
    lsc_arm *arm = parse_ok("# a comment\n\twrist 3 0..4095/360deg dir=-1 offset=-10deg "
                            "limits=100..4000 # c\r\n\n  # c\nb 0x10 bus dir=+1 offset=+20\r");
    assert_int_equal(lsc_arm_count(arm), 2);
    const lsc_joint *j = lsc_arm_joint(arm, 0);
    assert_int_equal(j->direction, -1);
    assert_int_equal(j->zero, 1933); /* 2047 - 113.75 */
    assert_int_equal(j->min_cdeg, -18172); /* 4000's angle, rounded down */
    assert_int_equal(j->max_cdeg, 16115);  /* 100's angle, rounded up */
    assert_true(lsc_joint_allows_pos(j, 100));
    assert_true(lsc_joint_allows_pos(j, 4000));
    assert_false(lsc_joint_allows_pos(j, 99));
    assert_false(lsc_joint_allows_pos(j, 4001));
    j = lsc_arm_joint(arm, 1);
    assert_int_equal(j->id, 16);
    assert_int_equal(j->zero, 520);
    lsc_arm_free(arm);
    /* dir=1, a position offset to the servo's ends, limits in either order, mixed */
    arm = parse_ok("a 1 bus dir=1 offset=500 limits=100deg..990\n"
                   "b 2 bus offset=-500 limits=-0deg..0deg\n"
                   "c 3 bus dir=-1 limits=10..10\n");
    assert_int_equal(lsc_arm_joint(arm, 0)->zero, 1000);
    assert_int_equal(lsc_arm_joint(arm, 0)->min_cdeg, -240);
    assert_int_equal(lsc_arm_joint(arm, 0)->max_cdeg, 10000);
    assert_int_equal(lsc_arm_joint(arm, 1)->zero, 0);
    assert_int_equal(lsc_arm_joint(arm, 2)->min_cdeg, 11760);
    assert_int_equal(lsc_arm_joint(arm, 2)->max_cdeg, 11760);
    lsc_arm_free(arm);
}

/* Without limits a joint allows every position of its servo, the ends too
 * (their angles are rounded outwards). */
static void test_default_limits_keep_the_ends(void **state)
{
    (void)state;
    lsc_arm *arm = parse_ok("w 3 0..4095/360deg\nr 4 0..4095/360deg dir=-1 offset=7\n");
    for (size_t i = 0; i < 2; i++) {
        const lsc_joint *j = lsc_arm_joint(arm, i);
        assert_true(lsc_joint_allows_pos(j, 0));
        assert_true(lsc_joint_allows_pos(j, 4095));
    }
    assert_int_equal(lsc_arm_joint(arm, 0)->max_cdeg, 18005); /* 18004.39 up */
    target_ok(arm, "w:4095", 3, 4095);
    lsc_servo s[] = {{3, 4095}, {3, 0}, {4, 4095}, {4, 0}};
    assert_int_equal(lsc_arm_check(arm, s, 4, why, sizeof why), 0);
    lsc_arm_free(arm);
}

static void test_profile_errors(void **state)
{
    (void)state;
    bad("", ": no joints: a profile names at least one (see docs/arm-profile.md)");
    bad("# nothing\n\n", ": no joints: a profile names at least one (see docs/arm-profile.md)");
    bad("base 6\n", ":1:7: a joint is NAME ID KIND [dir=+1|-1] [offset=VALUE] "
                    "[limits=LOW..HIGH]");
    bad("base\n", ":1:5: a joint is NAME ID KIND [dir=+1|-1] [offset=VALUE] [limits=LOW..HIGH]");
    bad("base 6 bus\nbase 5 bus\n", ":2:1: joint base is named twice");
    bad("base 6 bus\narm 6 bus\n", ":2:5: servo 6 is joint base already");
    bad("6base 6 bus\n", ":1:1: a joint's name starts with a letter and has at most 31 "
                         "characters");
    bad("_base 6 bus\n", ":1:1: a joint's name starts with a letter and has at most 31 "
                         "characters");
    bad("abcdefghijabcdefghijabcdefghijab 6 bus\n",
        ":1:1: a joint's name starts with a letter and has at most 31 characters");
    lsc_arm_free(parse_ok("Abcdefghijabcdefghijabcdefghij_ 6 bus\n"));
    bad("ba.se 6 bus\n", ":1:3: a joint's name has letters, digits, _ and - only");
    bad("ba~se 6 bus\n", ":1:3: a joint's name has letters, digits, _ and - only");
    bad("~base 6 bus\n", ":1:1: a joint's name starts with a letter and has at most 31 "
                         "characters");
    bad("base 256 bus\n", ":1:6: id 256 is out of range: use 0..255");
    bad("base -1 bus\n", ":1:6: id '-1' is negative: use 0..255");
    bad("base x bus\n", ":1:6: id 'x' is not a number: write it in decimal or 0x-hex");
    bad("base 0x bus\n", ":1:6: id '0x' is not a number: write it in decimal or 0x-hex");
    bad("base 0xg bus\n", ":1:6: id '0xg' is not a number: write it in decimal or 0x-hex");
    bad("base 0x00000000000006 bus\n", ":1:6: id: use 0..255");
    bad("base 0x0000000000006 bus\nx\n", ":2:2: a joint is NAME ID KIND [dir=+1|-1] "
                                          "[offset=VALUE] [limits=LOW..HIGH]");
    bad("base 6 servo\n", ":1:8: kind: use pwm (500..2500 over 180 degrees), bus (0..1000 "
                          "over 240 degrees) or MIN..MAX/SPANdeg (0..4095/360deg)");
    static const char *const kinds[] = {
        "pw", "pwmm", "busy", "bux", "0..4095", "0/360deg..5", "x..4095/360deg", "0..x/360deg",
        "0..4095/x", "0deg..4095/360deg", "0..4095deg/360deg", "0..4095/360", "4095/360deg"};
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++) {
        char text[64];
        snprintf(text, sizeof text, "base 6 %s\n", kinds[i]);
        bad(text, ":1:8: kind: use pwm (500..2500 over 180 degrees), bus (0..1000 over 240 "
                  "degrees) or MIN..MAX/SPANdeg (0..4095/360deg)");
    }
    static const char *const ranges[] = {"-1..4095/360deg", "5..5/360deg", "6..5/360deg",
                                         "65539..5/360deg", "0..10001/360deg",
                                         "0..4095/0deg", "0..4095/360.01deg", "0..4095/-1deg"};
    for (size_t i = 0; i < sizeof ranges / sizeof ranges[0]; i++) {
        char text[64];
        snprintf(text, sizeof text, "base 6 %s\n", ranges[i]);
        bad(text, ":1:8: kind: positions are 0 <= MIN < MAX <= 10000 and the span is "
                  "0.01deg..360deg");
    }
    lsc_arm *arm = parse_ok("a 1 0..10000/0.01deg\nb 2 9999..10000/360deg\n");
    lsc_arm_free(arm);
    bad("base 6 bus dir=2\n", ":1:16: dir: use +1 or -1");
    bad("base 6 bus dir=+2\n", ":1:16: dir: use +1 or -1");
    bad("base 6 bus dir=-2\n", ":1:16: dir: use +1 or -1");
    bad("base 6 bus dir=\n", ":1:16: dir: use +1 or -1");
    bad("base 6 bus dir=+1x\n", ":1:16: dir: use +1 or -1");
    bad("base 6 bus  offset=600\n", ":1:20: offset: the joint's zero would be outside the "
                                    "servo's range 0..1000");
    bad("base 6 bus offset=-501\n", ":1:19: offset: the joint's zero would be outside the "
                                    "servo's range 0..1000");
    bad("base 6 bus offset=1.5\n", ":1:19: offset: a position is a whole number: for an "
                                   "angle add deg (15.5deg)");
    bad("base 6 bus offset=400deg\n", ":1:19: offset: the joint's zero would be outside the "
                                      "servo's range 0..1000");
    bad("base 6 bus offset=-999999.99deg\n", ":1:19: offset: the joint's zero would be "
                                             "outside the servo's range 0..1000");
    bad("base 6 bus offset=121deg\n", ":1:19: offset: the joint's zero would be outside the "
                                      "servo's range 0..1000");
    bad("base 6 bus limits=0..70000\n", ":1:12: limits: position 70000 is outside the "
                                        "servo's range 0..1000");
    bad("base 6 bus limits=-1..10\n", ":1:12: limits: position -1 is outside the servo's "
                                      "range 0..1000");
    bad("base 6 bus limits=0..999999\n", ":1:12: limits: position 999999 is outside the "
                                         "servo's range 0..1000");
    bad("base 6 bus limits=0..1001\n", ":1:12: limits: position 1001 is outside the servo's "
                                       "range 0..1000");
    bad("base 6 pwm limits=499..2500\n", ":1:12: limits: position 499 is outside the servo's "
                                         "range 500..2500");
    bad("base 6 bus limits=10deg\n", ":1:19: limits: write LOW..HIGH (-90deg..90deg, 100..900)");
    bad("base 6 bus limits=0..400deg\n", ":1:12: limits: an angle is within -360deg..360deg");
    bad("base 6 bus limits=-360.01deg..0\n", ":1:12: limits: an angle is within "
                                            "-360deg..360deg");
    bad("base 6 bus limits=x..5\n", ":1:12: limits: not a number (a position such as 700, "
                                    "or an angle such as -15.5deg)");
    bad("base 6 bus limits=5..5rad\n", ":1:12: limits: unknown unit: write a position (700) "
                                       "or degrees (30deg, -15.5deg)");
    bad("base 6 bus speed=3\n", ":1:12: 'speed=3': settings are dir=+1|-1, offset=VALUE, "
                                "limits=LOW..HIGH, open=VALUE and closed=VALUE");
    bad("base 6 bus limits\n", ":1:12: 'limits': settings are dir=+1|-1, offset=VALUE, "
                               "limits=LOW..HIGH, open=VALUE and closed=VALUE");
    bad("base 6 bus dirs=1\n", ":1:12: 'dirs=1': settings are dir=+1|-1, offset=VALUE, "
                               "limits=LOW..HIGH, open=VALUE and closed=VALUE");
    /* a field repeated in a reason: at most 40 bytes, non-ASCII escaped */
    bad("base 6 bus \xc3\xa4=1234567890123456789012345678901234567890\n",
        ":1:12: '\\xC3\\xA4=1234567890123456789012345678901234567': settings are "
        "dir=+1|-1, offset=VALUE, limits=LOW..HIGH, open=VALUE and closed=VALUE");
    bad("base 6 bus dir=1 dir=-1\n", ":1:18: dir is given twice");
    bad("base 6 bus offset=1 offset=2\n", ":1:21: offset is given twice");
    bad("base 6 bus limits=1..2 limits=1..2\n", ":1:24: limits is given twice");
    bad("base 6 bus dir=1 offset=0 limits=0..9 open=0 closed=9 x\n",
        ":1:55: too many fields: a joint has at most five settings");
    bad("base 6 bus a b c d e f g h i\n", ":1:26: too many fields: a joint has at most five "
                                          "settings");
    bad("base 6 bus\x01\n", ":1:11: unexpected byte 0x01");
    bad("base 6 bus\x7f\n", ":1:11: unexpected byte 0x7F");
    bad("base 6 bus\r\r\n", ":1:11: unexpected byte 0x0D");
    bad("base\r6 bus\n", ":1:5: unexpected byte 0x0D");
    bad("ok 1 bus\n\n  # c\nbase 6 bus # comment\r\nx\n", ":5:2: a joint is NAME ID KIND "
                                                        "[dir=+1|-1] [offset=VALUE] "
                                                        "[limits=LOW..HIGH]");
    parse_bad("base 6 bus\0\n", 12, ":1:11: unexpected byte 0x00");
    /* a comment may start right after a field */
    arm = parse_ok("base 6 bus#c\n");
    lsc_arm_free(arm);
}

/* A control byte is refused in a comment too (the format says control bytes
 * are refused; a NUL or an escape sequence hidden in a comment is still one). */
static void test_control_bytes_in_comments(void **state)
{
    (void)state;
    bad("base 6 bus # \033[2J\n", ":1:14: unexpected byte 0x1B");
    parse_bad("# \0\nbase 6 bus\n", 14, ":1:3: unexpected byte 0x00");
    lsc_arm *arm = parse_ok("base 6 bus # tab\there, \xc2\xb0 and \\ are fine\n");
    lsc_arm_free(arm);
}

static void test_joints_max(void **state)
{
    (void)state;
    char text[40 * 32 + 64] = "";
    size_t len = 0;
    for (unsigned i = 0; i < LSC_ARM_JOINTS_MAX; i++) {
        len += (size_t)snprintf(text + len, sizeof text - len, "j%u %u bus\n", i, i);
    }
    lsc_arm *arm = parse_ok(text);
    assert_int_equal(lsc_arm_count(arm), LSC_ARM_JOINTS_MAX);
    assert_int_equal(lsc_arm_find(arm, "j31"), 31);
    lsc_arm_free(arm);
    snprintf(text + len, sizeof text - len, "extra 99 bus\n");
    bad(text, ":33:1: too many joints: at most 32");
}

/* A UTF-8 byte-order mark at the start is skipped: columns count after it. */
static void test_byte_order_mark(void **state)
{
    (void)state;
    lsc_arm *arm = parse_ok("\xEF\xBB\xBF"
                            "base 6 bus\n");
    assert_string_equal(lsc_arm_name(arm, 0), "base");
    lsc_arm_free(arm);
    bad("\xEF\xBB\xBF"
        "base 6\n",
        ":1:7: a joint is NAME ID KIND [dir=+1|-1] [offset=VALUE] [limits=LOW..HIGH]");
    bad("\xEF\xBB\xBF", ": no joints: a profile names at least one (see docs/arm-profile.md)");
    /* only at the start, and only whole */
    bad("base 6 bus\n\xEF\xBB\xBF"
        "x 1 bus\n",
        ":2:1: a joint's name starts with a letter and has at most 31 characters");
    bad("\xEF\xBB"
        "base 6 bus\n",
        ":1:1: a joint's name starts with a letter and has at most 31 characters");
}

/* Limits that hold no position of the servo are refused when the profile is
 * read, at the limits; limits that hold exactly one are fine. */
static void test_limits_without_a_position(void **state)
{
    (void)state;
    bad("base 6 bus limits=0.01deg..0.02deg\n",
        ":1:19: limits: 0.01deg..0.02deg hold no position of the servo: widen them");
    bad("x 1 bus\nbase 6 bus dir=-1 limits=0.01deg..0.23deg\n",
        ":2:26: limits: 0.01deg..0.23deg hold no position of the servo: widen them");
    bad("base 6 bus limits=-0.23deg..-0.01deg\n",
        ":1:19: limits: -0.23deg..-0.01deg hold no position of the servo: widen them");
    /* beyond the servo's range (within 360 degrees) */
    bad("base 6 bus limits=121deg..360deg\n",
        ":1:19: limits: 121.00deg..360.00deg hold no position of the servo: widen them");
    bad("base 6 bus dir=-1 limits=-360deg..-120.01deg\n",
        ":1:26: limits: -360.00deg..-120.01deg hold no position of the servo: widen them");
    lsc_arm *arm = parse_ok("a 1 bus limits=0.24deg..0.24deg\n"
                            "b 2 bus dir=-1 limits=0.24deg..0.24deg\n"
                            "c 3 bus limits=120deg..360deg\n");
    lsc_servo s[] = {{1, 501}, {2, 499}, {3, 1000}};
    assert_int_equal(lsc_arm_check(arm, s, 3, why, sizeof why), 0);
    s[0].position = 500;
    assert_int_equal(lsc_arm_check(arm, s, 3, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "position 500 is outside the limits of joint a (servo 1): "
                             "0.24deg..0.24deg, positions 501..501");
    target_bad(arm, "a:0.23deg", "0.23deg is outside the limits of joint a (servo 1): "
                                 "0.24deg..0.24deg, positions 501..501");
    target_ok(arm, "a:0.24deg", 1, 501);
    target_ok(arm, "b:0.24deg", 2, 499);
    lsc_arm_free(arm);
}

/* c centidegrees as text: "-0.24" */
static const char *cdeg_text(char *out, int c)
{
    snprintf(out, 16, "%s%d.%02d", c < 0 ? "-" : "", abs(c) / 100, abs(c) % 100);
    return out;
}

/* The positions a message names are exactly those lsc_joint_allows_pos
 * allows, and a joint is refused exactly when there are none: for many kinds,
 * directions, offsets and limits. */
static void test_positions_match_allows_pos(void **state)
{
    (void)state;
    static const char *const kinds[] = {"bus", "pwm", "0..4095/360deg", "0..100/1deg",
                                        "10..20/300deg", "0..3/0.05deg"};
    static const char *const dirs[] = {"1", "-1"};
    static const char *const offsets[] = {"0", "1", "-1", "5deg"};
    static const int ends[] = {-36000, -9000, -301, -24, -5, -1, 0, 1, 3, 24, 25, 500, 17999};
    const size_t nends = sizeof ends / sizeof ends[0];
    unsigned refused = 0, held = 0;
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        for (size_t d = 0; d < 2; d++) {
            for (size_t o = 0; o < sizeof offsets / sizeof offsets[0]; o++) {
                for (size_t a = 0; a < nends; a++) {
                    for (size_t b = a; b < nends; b++) {
                        char text[128], lo[16], hi[16];
                        lsc_arm *arm = NULL;
                        snprintf(text, sizeof text, "j 1 %s dir=%s offset=%s limits=%sdeg..%sdeg\n",
                                 kinds[k], dirs[d], offsets[o], cdeg_text(lo, ends[a]),
                                 cdeg_text(hi, ends[b]));
                        int r = lsc_arm_parse(text, strlen(text), "t.conf", &arm, why,
                                              sizeof why);
                        if (r != 0 && strstr(why, "offset") != NULL) {
                            continue; /* an offset beyond a tiny range */
                        }
                        /* the joint as it would be: parse it without limits */
                        lsc_arm *whole = NULL;
                        char *lim = strstr(text, " limits=");
                        int32_t lo_c = ends[a], hi_c = ends[b];
                        lim[0] = '\n';
                        lim[1] = '\0';
                        assert_int_equal(lsc_arm_parse(text, strlen(text), "t.conf", &whole,
                                                       why, sizeof why),
                                         0);
                        lsc_joint j = *lsc_arm_joint(whole, 0);
                        lsc_arm_free(whole);
                        j.min_cdeg = lo_c;
                        j.max_cdeg = hi_c;
                        long first = -1, last = -1;
                        for (long p = j.pos_min; p <= j.pos_max; p++) {
                            if (lsc_joint_allows_pos(&j, (uint16_t)p)) {
                                first = first < 0 ? p : first;
                                last = p;
                            }
                        }
                        if (first < 0) {
                            assert_int_equal(r, LSC_EINVAL);
                            assert_non_null(strstr(why, "hold no position of the servo"));
                            refused++;
                            continue;
                        }
                        assert_int_equal(r, 0);
                        held++;
                        const lsc_joint *got = lsc_arm_joint(arm, 0);
                        assert_int_equal(got->zero, j.zero);
                        assert_int_equal(got->direction, j.direction);
                        assert_int_equal(got->min_cdeg, j.min_cdeg);
                        assert_int_equal(got->max_cdeg, j.max_cdeg);
                        lsc_servo s = {1, (uint16_t)(first > j.pos_min ? first - 1 : last + 1)};
                        if (first == j.pos_min && last == j.pos_max) {
                            s.position = (uint16_t)(j.pos_max + 1u);
                        }
                        assert_int_equal(lsc_arm_check(arm, &s, 1, why, sizeof why),
                                         LSC_EINVAL);
                        char want[48];
                        snprintf(want, sizeof want, ", positions %ld..%ld", first, last);
                        assert_string_equal(why + strlen(why) - strlen(want), want);
                        lsc_arm_free(arm);
                    }
                }
            }
        }
    }
    assert_true(refused > 50);
    assert_true(held > 500);
}

static void test_parse_arguments(void **state)
{
    (void)state;
    lsc_arm *arm = (lsc_arm *)&arm;
    assert_int_equal(lsc_arm_parse("a 1 bus", 7, "t.conf", NULL, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "lsc_arm_parse: no text or no out");
    assert_int_equal(lsc_arm_parse(NULL, 1, "t.conf", &arm, why, sizeof why), LSC_EINVAL);
    assert_null(arm);
    assert_int_equal(lsc_arm_parse(NULL, 0, "t.conf", &arm, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "t.conf: no joints: a profile names at least one "
                             "(see docs/arm-profile.md)");
    /* file NULL: "profile"; why NULL or no room: nothing written */
    assert_int_equal(lsc_arm_parse("a 1", 3, NULL, &arm, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "profile:1:4: a joint is NAME ID KIND [dir=+1|-1] "
                             "[offset=VALUE] [limits=LOW..HIGH]");
    assert_int_equal(lsc_arm_parse("a 1", 3, "t.conf", &arm, NULL, 99), LSC_EINVAL);
    why[0] = 'x';
    assert_int_equal(lsc_arm_parse("a 1", 3, "t.conf", &arm, why, 0), LSC_EINVAL);
    assert_int_equal(why[0], 'x');
    /* truncated to fit, NUL-terminated */
    assert_int_equal(lsc_arm_parse("a 1", 3, "t.conf", &arm, why, 10), LSC_EINVAL);
    assert_string_equal(why, "t.conf:1:");
    assert_int_equal(lsc_arm_parse("a 1", 3, "t.conf", &arm, why, 4), LSC_EINVAL);
    assert_string_equal(why, "t.c");
    assert_int_equal(lsc_arm_parse("a 1", 3, "t.conf", &arm, why, 8), LSC_EINVAL);
    assert_string_equal(why, "t.conf:");
    /* text with no NUL after it: only len bytes are read */
    arm = NULL;
    assert_int_equal(lsc_arm_parse("a 1 busXYZ", 7, "t.conf", &arm, why, sizeof why), 0);
    lsc_arm_free(arm);
}

/* A file's name with a newline or an escape sequence stays one line. */
static void test_file_names_escaped(void **state)
{
    (void)state;
    lsc_arm *arm = NULL;
    assert_int_equal(lsc_arm_parse("a 1", 3, "a\nb\033[2J\\.conf", &arm, why, sizeof why),
                     LSC_EINVAL);
    assert_string_equal(why, "a\\x0Ab\\x1B[2J\\\\.conf:1:4: a joint is NAME ID KIND "
                             "[dir=+1|-1] [offset=VALUE] [limits=LOW..HIGH]");
    assert_int_equal(lsc_arm_parse("", 0, "a\nb", &arm, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "a\\x0Ab: no joints: a profile names at least one "
                             "(see docs/arm-profile.md)");
    char path[128], want[256];
    in_dir(path, sizeof path, "a\nb\033[2J.conf");
    assert_int_equal(lsc_arm_load(path, &arm, why, sizeof why), LSC_EIO);
    snprintf(want, sizeof want, "cannot read the arm profile %s/a\\x0Ab\\x1B[2J.conf: %s", dir,
             strerror(ENOENT));
    assert_string_equal(why, want);
    write_file(path, "a 1 bus\nb 2\n", 12);
    assert_int_equal(lsc_arm_load(path, &arm, why, sizeof why), LSC_EINVAL);
    snprintf(want, sizeof want, "%s/a\\x0Ab\\x1B[2J.conf:2:4: a joint is NAME ID KIND "
                                "[dir=+1|-1] [offset=VALUE] [limits=LOW..HIGH]",
             dir);
    assert_string_equal(why, want);
}

/* ---- Files -------------------------------------------------------------------- */

static void test_load(void **state)
{
    (void)state;
    char path[128], want[256];
    lsc_arm *arm = NULL;
    in_dir(path, sizeof path, "ok.conf");
    write_file(path, xarm, strlen(xarm));
    assert_int_equal(lsc_arm_load(path, &arm, why, sizeof why), 0);
    assert_int_equal(lsc_arm_count(arm), 6);
    lsc_arm_free(arm);
    /* a few bytes a read, and a read interrupted: the same profile */
    read_chunk = 7;
    read_errno = EINTR;
    reads = 0;
    assert_int_equal(lsc_arm_load(path, &arm, why, sizeof why), 0);
    assert_true(reads > strlen(xarm) / 7);
    read_chunk = 0;
    assert_int_equal(lsc_arm_count(arm), 6);
    lsc_arm_free(arm);
    /* a read that fails */
    read_errno = EIO;
    arm = (lsc_arm *)&arm;
    assert_int_equal(lsc_arm_load(path, &arm, why, sizeof why), LSC_EIO);
    assert_null(arm);
    snprintf(want, sizeof want, "cannot read the arm profile %s: %s", path, strerror(EIO));
    assert_string_equal(why, want);
    /* no such file */
    in_dir(path, sizeof path, "none.conf");
    assert_int_equal(lsc_arm_load(path, &arm, why, sizeof why), LSC_EIO);
    snprintf(want, sizeof want, "cannot read the arm profile %s: %s", path, strerror(ENOENT));
    assert_string_equal(why, want);
    /* with a BOM */
    in_dir(path, sizeof path, "bom.conf");
    write_file(path, "\xEF\xBB\xBF# xArm\r\nbase 6 bus\r\n", 23);
    assert_int_equal(lsc_arm_load(path, &arm, why, sizeof why), 0);
    lsc_arm_free(arm);
    /* arguments */
    assert_int_equal(lsc_arm_load(NULL, &arm, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "lsc_arm_load: no path or no out");
    assert_int_equal(lsc_arm_load(path, NULL, why, sizeof why), LSC_EINVAL);
}

/* ---- Profiles by name (lsc_arm_open) ------------------------------------------ */

#ifndef LSC_ARMS_INSTALL_DIR
#error "tests/CMakeLists.txt gives test_arm the library's LSC_ARMS_INSTALL_DIR"
#endif

/* dir/a[/b[/c]] made */
static void make_dirs(char *out, size_t cap, const char *sub)
{
    char part[256];
    snprintf(out, cap, "%s/%s", dir, sub);
    for (const char *p = strchr(sub, '/');; p = strchr(p + 1, '/')) {
        snprintf(part, sizeof part, "%s/%.*s", dir, (int)(p != NULL ? (size_t)(p - sub) : strlen(sub)),
                 sub);
        assert_true(mkdir(part, 0700) == 0 || errno == EEXIST);
        if (p == NULL) {
            break;
        }
    }
}

static void put_env(const char *name, const char *value)
{
    if (value != NULL) {
        assert_int_equal(setenv(name, value, 1), 0);
    } else {
        assert_int_equal(unsetenv(name), 0);
    }
}

/* The joints of the profile name opens (-1: an error, in why). */
static int joints_of(const char *name)
{
    lsc_arm *arm = (lsc_arm *)&arm;
    int r = lsc_arm_open(name, &arm, why, sizeof why);
    if (r != 0) {
        assert_null(arm);
        return -1;
    }
    int n = (int)lsc_arm_count(arm);
    lsc_arm_free(arm);
    return n;
}

static void test_open_by_name(void **state)
{
    (void)state;
    char xdg[128], home[128], homearms[160], inst[128], path[256], want[512], base[128];
    static const char one[] = "base 6 bus\n";
    static const char two[] = "base 6 bus\nelbow 4 bus\n";
    make_dirs(xdg, sizeof xdg, "xdg/lsc/arms");
    make_dirs(homearms, sizeof homearms, "home/.config/lsc/arms");
    make_dirs(inst, sizeof inst, "inst");
    snprintf(base, sizeof base, "%s/xdg", dir);
    snprintf(home, sizeof home, "%s/home", dir);
    put_env("XDG_CONFIG_HOME", base);
    put_env("HOME", home);
    put_env("LSC_ARMS_DIR", inst);

    /* arguments */
    lsc_arm *arm = (lsc_arm *)&arm;
    assert_int_equal(lsc_arm_open(NULL, &arm, why, sizeof why), LSC_EINVAL);
    assert_null(arm);
    assert_string_equal(why, "lsc_arm_open: no name or no out");
    assert_int_equal(lsc_arm_open("xarm", NULL, why, sizeof why), LSC_EINVAL);
    assert_int_equal(joints_of(""), -1);
    assert_string_equal(why, "no arm profile given: a profile's name (xarm) or a file's path");

    /* the installed profiles when the user has none of that name */
    in_dir(path, sizeof path, "inst/xarm.conf");
    write_file(path, xarm, strlen(xarm));
    assert_int_equal(joints_of("xarm"), 6);
    /* ... the user's own first */
    in_dir(path, sizeof path, "xdg/lsc/arms/xarm.conf");
    write_file(path, one, strlen(one));
    assert_int_equal(joints_of("xarm"), 1);
    /* a path is a path: '/' or ".conf" */
    in_dir(path, sizeof path, "inst/xarm.conf");
    assert_int_equal(joints_of(path), 6);
    assert_int_equal(joints_of("xarm.conf"), -1); /* the working directory's */
    assert_string_equal(why, "cannot read the arm profile xarm.conf: No such file or directory");
    assert_int_equal(joints_of("no/xarm"), -1);
    assert_string_equal(why, "cannot read the arm profile no/xarm: No such file or directory");
    assert_int_equal(joints_of(".conf"), -1); /* (the ending alone) */
    assert_string_equal(why, "cannot read the arm profile .conf: No such file or directory");

    /* found nowhere: where it looked, in order (short names too) */
    assert_int_equal(joints_of("ab"), -1);
    snprintf(want, sizeof want,
             "no arm profile named ab: looked for %s/xdg/lsc/arms/ab.conf, %s/inst/ab.conf (a "
             "file in this directory: ./ab)",
             dir, dir);
    assert_string_equal(why, want);
    assert_int_equal(lsc_arm_open("ab", &arm, why, sizeof why), LSC_EIO);
    assert_int_equal(lsc_arm_open("ab", &arm, NULL, 0), LSC_EIO); /* no why wanted */

    /* $XDG_CONFIG_HOME not absolute (ignored, as XDG says), or unset: ~/.config */
    in_dir(path, sizeof path, "home/.config/lsc/arms/xarm.conf");
    write_file(path, two, strlen(two));
    put_env("XDG_CONFIG_HOME", "relative");
    assert_int_equal(joints_of("xarm"), 2);
    put_env("XDG_CONFIG_HOME", "");
    assert_int_equal(joints_of("xarm"), 2);
    /* no home at all: the installed ones only */
    put_env("HOME", NULL);
    assert_int_equal(joints_of("xarm"), 6);
    assert_int_equal(joints_of("none"), -1);
    snprintf(want, sizeof want,
             "no arm profile named none: looked for %s/inst/none.conf (a file in this directory: "
             "./none)",
             dir);
    assert_string_equal(why, want);
    /* without $LSC_ARMS_DIR: the prefix's share/lsc/arms */
    put_env("LSC_ARMS_DIR", "");
    assert_int_equal(joints_of("no-such-arm"), -1);
    snprintf(want, sizeof want,
             "no arm profile named no-such-arm: looked for %s/no-such-arm.conf (a file in this "
             "directory: ./no-such-arm)",
             LSC_ARMS_INSTALL_DIR);
    assert_string_equal(why, want);
    put_env("LSC_ARMS_DIR", inst);
    put_env("XDG_CONFIG_HOME", base);

    /* $XDG_CONFIG_HOME a file: not there, on to the installed */
    in_dir(path, sizeof path, "inst/plain");
    write_file(path, one, strlen(one));
    put_env("XDG_CONFIG_HOME", path);
    assert_int_equal(joints_of("xarm"), 6);
    assert_int_equal(unlink(path), 0);
    put_env("XDG_CONFIG_HOME", base);

    /* there but unreadable (a loop of links): that error, not the next place */
    in_dir(path, sizeof path, "xdg/lsc/arms/loop.conf");
    assert_int_equal(symlink(path, path), 0);
    in_dir(want, sizeof want, "inst/loop.conf");
    write_file(want, one, strlen(one));
    assert_int_equal(joints_of("loop"), -1);
    assert_non_null(strstr(why, "cannot read the arm profile "));
    assert_non_null(strstr(why, "/xdg/lsc/arms/loop.conf: "));
    assert_int_equal(unlink(path), 0);
    assert_int_equal(unlink(want), 0);
    /* ... and an error in the first found is that error */
    in_dir(path, sizeof path, "xdg/lsc/arms/bad.conf");
    write_file(path, "base x bus\n", 11);
    in_dir(want, sizeof want, "inst/bad.conf");
    write_file(want, one, strlen(one));
    assert_int_equal(lsc_arm_open("bad", &arm, why, sizeof why), LSC_EINVAL);
    assert_non_null(strstr(why, "/xdg/lsc/arms/bad.conf:1:"));
    assert_int_equal(unlink(path), 0);
    assert_int_equal(unlink(want), 0);

    /* a name no path can hold, with and without the first place */
    static char longname[5000];
    memset(longname, 'a', sizeof longname - 1u);
    assert_int_equal(lsc_arm_open(longname, &arm, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "the arm profile's name is too long (4999 bytes): a name such as "
                             "xarm, or a file's path");
    put_env("XDG_CONFIG_HOME", NULL);
    assert_int_equal(joints_of(longname), -1);
    assert_non_null(strstr(why, "is too long (4999 bytes)"));

    /* names in messages are escaped */
    put_env("XDG_CONFIG_HOME", base);
    assert_int_equal(joints_of("a\nb"), -1);
    assert_non_null(strstr(why, "no arm profile named a\\x0Ab: "));

    /* lsc_arm_path: the file lsc_arm_open would load */
    char found[256], small[8];
    in_dir(want, sizeof want, "xdg/lsc/arms/xarm.conf");
    assert_int_equal(lsc_arm_path("xarm", found, sizeof found, why, sizeof why), 0);
    assert_string_equal(found, want);
    assert_int_equal(lsc_arm_path("no/such.conf", found, sizeof found, why, sizeof why), 0);
    assert_string_equal(found, "no/such.conf");
    assert_int_equal(lsc_arm_path("xarm", small, sizeof small, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "lsc_arm_path: no room for the path");
    assert_int_equal(lsc_arm_path("xarm", NULL, 9, why, sizeof why), LSC_EINVAL);
    assert_int_equal(lsc_arm_path("xarm", found, 0, why, sizeof why), LSC_EINVAL);
    assert_int_equal(lsc_arm_path(NULL, found, sizeof found, why, sizeof why), LSC_EINVAL);
    assert_int_equal(lsc_arm_path("ab", found, sizeof found, why, sizeof why), LSC_EIO);
    longname[0] = '/';
    assert_int_equal(lsc_arm_path(longname, found, sizeof found, why, sizeof why), LSC_EINVAL);
    assert_non_null(strstr(why, "is too long (4999 bytes)"));

    static const char *const files[] = {"xdg/lsc/arms/xarm.conf", "inst/xarm.conf",
                                        "home/.config/lsc/arms/xarm.conf"};
    static const char *const dirs[] = {"xdg/lsc/arms",          "xdg/lsc",          "xdg",
                                       "home/.config/lsc/arms", "home/.config/lsc", "home/.config",
                                       "home",                  "inst"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        in_dir(path, sizeof path, files[i]);
        assert_int_equal(unlink(path), 0);
    }
    for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
        in_dir(path, sizeof path, dirs[i]);
        assert_int_equal(rmdir(path), 0);
    }
}

static void test_load_size(void **state)
{
    (void)state;
    char path[128], want[256];
    lsc_arm *arm = NULL;
    char *text = malloc(LSC_ARM_FILE_MAX + 1u);
    assert_non_null(text);
    memset(text, '#', LSC_ARM_FILE_MAX + 1u);
    /* exactly the most: read whole (a comment without joints) */
    in_dir(path, sizeof path, "max.conf");
    write_file(path, text, LSC_ARM_FILE_MAX);
    assert_int_equal(lsc_arm_load(path, &arm, why, sizeof why), LSC_EINVAL);
    snprintf(want, sizeof want, "%s: no joints: a profile names at least one "
                                "(see docs/arm-profile.md)",
             path);
    assert_string_equal(why, want);
    /* one byte more */
    in_dir(path, sizeof path, "big.conf");
    write_file(path, text, LSC_ARM_FILE_MAX + 1u);
    assert_int_equal(lsc_arm_load(path, &arm, why, sizeof why), LSC_EINVAL);
    snprintf(want, sizeof want, "%s: longer than 65536 bytes: not an arm profile", path);
    assert_string_equal(why, want);
    assert_null(arm);
    free(text);
}

/* A directory, a FIFO and a device are refused at once, without reading (a
 * FIFO without a writer would wait for ever). */
static void test_load_only_regular_files(void **state)
{
    (void)state;
    char path[128], want[256];
    lsc_arm *arm = (lsc_arm *)&arm;
    reads = 0;
    assert_int_equal(lsc_arm_load(dir, &arm, why, sizeof why), LSC_EINVAL);
    assert_null(arm);
    snprintf(want, sizeof want, "cannot read the arm profile %s: it is a directory (an arm "
                                "profile is a regular file)",
             dir);
    assert_string_equal(why, want);
    in_dir(path, sizeof path, "fifo.conf");
    assert_int_equal(mkfifo(path, 0600), 0);
    assert_int_equal(lsc_arm_load(path, &arm, why, sizeof why), LSC_EINVAL);
    snprintf(want, sizeof want, "cannot read the arm profile %s: it is a FIFO (an arm "
                                "profile is a regular file)",
             path);
    assert_string_equal(why, want);
    assert_int_equal(reads, 0);
}

/* (/dev/zero: reading it would give LSC_ARM_FILE_MAX + 1 bytes at once) */
static void test_load_no_device(void **state)
{
    (void)state;
    struct stat st;
    lsc_arm *arm = (lsc_arm *)&arm;
    if (stat("/dev/zero", &st) != 0 || !S_ISCHR(st.st_mode)) {
        print_message("skipped: /dev/zero is not a character device here\n");
        skip();
    }
    reads = 0;
    assert_int_equal(lsc_arm_load("/dev/zero", &arm, why, sizeof why), LSC_EINVAL);
    assert_null(arm);
    assert_string_equal(why, "cannot read the arm profile /dev/zero: it is a device (an arm "
                             "profile is a regular file)");
    assert_int_equal(reads, 0);
}

static void test_out_of_memory(void **state)
{
    (void)state;
    char path[128];
    lsc_arm *arm = (lsc_arm *)&arm;
    fail_malloc = 1;
    assert_int_equal(lsc_arm_parse(xarm, strlen(xarm), "t.conf", &arm, why, sizeof why),
                     LSC_ENOSPC);
    assert_null(arm);
    assert_string_equal(why, "out of memory");
    in_dir(path, sizeof path, "ok.conf");
    write_file(path, xarm, strlen(xarm));
    fail_malloc = 1; /* the file's buffer */
    assert_int_equal(lsc_arm_load(path, &arm, why, sizeof why), LSC_ENOSPC);
    assert_string_equal(why, "out of memory");
    fail_malloc = 2; /* the profile */
    assert_int_equal(lsc_arm_load(path, &arm, why, sizeof why), LSC_ENOSPC);
    assert_null(arm);
    arm = parse_ok(xarm);
    fail_malloc = 1;
    assert_null(lsc_arm_copy(arm));
    fail_malloc = 0;
    lsc_arm *copy = lsc_arm_copy(arm);
    assert_non_null(copy);
    assert_ptr_not_equal(copy, arm);
    lsc_arm_free(arm);
    assert_int_equal(lsc_arm_count(copy), 6);
    assert_string_equal(lsc_arm_name(copy, 5), "base");
    assert_int_equal(lsc_arm_joint(copy, 5)->max_cdeg, 11500);
    lsc_arm_free(copy);
    assert_null(lsc_arm_copy(NULL));
    lsc_arm_free(NULL);
}

/* ---- Joints, targets, checks -------------------------------------------------- */

/* open= and closed=: a gripper's ends, positions or angles inside its limits. */
static void test_gripper_ends(void **state)
{
    (void)state;
    lsc_arm *arm = parse_ok("gripper 1 bus limits=100..700 open=120 closed=24deg\nbase 6 bus\n");
    uint16_t pos = 0;
    assert_int_equal(lsc_arm_end(arm, 0, LSC_ARM_OPEN, &pos), 0);
    assert_int_equal(pos, 120);
    assert_int_equal(lsc_arm_end(arm, 0, LSC_ARM_CLOSED, &pos), 0);
    assert_int_equal(pos, 600);
    assert_int_equal(lsc_arm_end(arm, 0, LSC_ARM_CLOSED, NULL), 0);
    assert_int_equal(lsc_arm_end(arm, 1, LSC_ARM_OPEN, &pos), LSC_EINVAL);
    assert_int_equal(lsc_arm_end(arm, 2, LSC_ARM_OPEN, &pos), LSC_EINVAL);
    assert_int_equal(lsc_arm_end(arm, 0, (lsc_arm_end_kind)2, &pos), LSC_EINVAL);
    assert_int_equal(lsc_arm_end(NULL, 0, LSC_ARM_OPEN, &pos), LSC_EINVAL);
    /* a copy keeps them */
    lsc_arm *copy = lsc_arm_copy(arm);
    assert_int_equal(lsc_arm_end(copy, 0, LSC_ARM_OPEN, &pos), 0);
    assert_int_equal(pos, 120);
    lsc_arm_free(copy);
    lsc_arm_free(arm);
    bad("g 1 bus open=x\n", ":1:14: open: not a number (a position such as 700, or an angle "
                            "such as -15.5deg)");
    bad("g 1 bus closed=1001\n", ":1:16: closed: 1001 is outside the servo's range 0..1000");
    bad("g 1 bus closed=121deg\n", ":1:16: closed: 121deg is outside the servo's range "
                                   "0..1000");
    bad("g 1 bus open=361deg\n", ":1:14: open: 361deg is outside the servo's range 0..1000");
    bad("g 1 bus open=-361deg\n", ":1:14: open: -361deg is outside the servo's range 0..1000");
    bad("g 1 bus open=-5\n", ":1:14: open: -5 is outside the servo's range 0..1000");
    bad("g 1 bus limits=0..700 open=800\n", ":1:28: open: position 800 is outside the "
                                            "joint's limits");
    bad("g 1 bus open=1 open=2\n", ":1:16: open is given twice");
}

static void test_lookups(void **state)
{
    (void)state;
    lsc_arm *arm = parse_ok(xarm);
    assert_int_equal(lsc_arm_count(NULL), 0);
    assert_null(lsc_arm_name(NULL, 0));
    assert_null(lsc_arm_joint(NULL, 0));
    assert_null(lsc_arm_name(arm, 6));
    assert_null(lsc_arm_joint(arm, 6));
    assert_int_equal(lsc_arm_find(arm, "base"), 5);
    assert_int_equal(lsc_arm_find(arm, "gripper"), 0);
    assert_int_equal(lsc_arm_find(arm, "6"), 5);
    assert_int_equal(lsc_arm_find(arm, "0x6"), 5);
    assert_int_equal(lsc_arm_find(arm, "0000006"), 5);
    assert_int_equal(lsc_arm_find(arm, "00000006"), -1); /* more than 7 characters */
    assert_int_equal(lsc_arm_find(arm, "9"), -1);
    assert_int_equal(lsc_arm_find(arm, "256"), -1);
    assert_int_equal(lsc_arm_find(arm, "bas"), -1);
    assert_int_equal(lsc_arm_find(arm, "Base"), -1);
    assert_int_equal(lsc_arm_find(arm, ""), -1);
    assert_int_equal(lsc_arm_find(arm, NULL), -1);
    assert_int_equal(lsc_arm_find(NULL, "6"), -1);
    assert_int_equal(lsc_arm_find(NULL, "base"), -1);
    assert_int_equal(lsc_arm_by_id(arm, 1), 0);
    assert_int_equal(lsc_arm_by_id(arm, 7), -1);
    assert_int_equal(lsc_arm_by_id(NULL, 1), -1);
    lsc_arm_free(arm);
}

static void test_targets(void **state)
{
    (void)state;
    lsc_arm *arm = parse_ok(xarm);
    /* base 30deg -> 500 + 125; shoulder -20deg -> 500 - 83.3 */
    target_ok(arm, "base:30deg", 6, 625);
    target_ok(arm, "shoulder:-20deg", 5, 417);
    target_ok(arm, "2:-15.5deg", 2, 435);
    target_ok(arm, "0x2:+15.50deg", 2, 565);
    target_ok(arm, "gripper:700", 1, 700);
    target_ok(arm, "elbow:6.24deg", 4, 526);
    target_ok(arm, "9:2000", 9, 2000);        /* not a joint: a position */
    target_ok(arm, "9:65535", 9, 65535);
    target_ok(arm, "0000006:500", 6, 500);
    target_ok(arm, "base:-115deg", 6, 21);
    target_bad(arm, "base:115.01deg", "115.01deg is outside the limits of joint base (servo "
                                      "6): -115.00deg..115.00deg, positions 21..979");
    target_bad(arm, "gripper:701", "position 701 is outside the limits of joint gripper "
                                   "(servo 1): -120.00deg..48.00deg, positions 0..700");
    target_bad(arm, "base:-400deg", "-400deg is outside the limits of joint base (servo 6): "
                                    "-115.00deg..115.00deg, positions 21..979");
    target_bad(arm, "base:999999.99deg", "999999.99deg is outside the limits of joint base "
                                         "(servo 6): -115.00deg..115.00deg, positions 21..979");
    target_bad(arm, "base:20", "position 20 is outside the limits of joint base (servo 6): "
                               "-115.00deg..115.00deg, positions 21..979");
    target_bad(arm, "00000006:500", "'00000006' is neither a joint of the arm profile nor a "
                                    "servo id");
    target_bad(arm, "hand:10deg", "'hand' is neither a joint of the arm profile nor a servo id");
    target_bad(arm, "9:10deg", "'9:10deg': servo 9 is not a joint of the arm profile, so it "
                               "has no degrees: give a position");
    target_bad(arm, "base", "'base' is not JOINT:VALUE (base:30deg, 2:-15.5deg, 1:700)");
    target_bad(arm, "wrist:", "'wrist:': not a number (a position such as 700, or an angle "
                              "such as -15.5deg)");
    target_bad(arm, "wrist:+", "'wrist:+': not a number (a position such as 700, or an angle "
                               "such as -15.5deg)");
    target_bad(arm, "wrist:1.5", "'wrist:1.5': a position is a whole number: for an angle add "
                                 "deg (15.5deg)");
    target_bad(arm, "wrist:15.555deg", "'wrist:15.555deg': an angle has at most two decimals "
                                       "(0.01 degree)");
    target_bad(arm, "wrist:1rad", "'wrist:1rad': unknown unit: write a position (700) or "
                                  "degrees (30deg, -15.5deg)");
    target_bad(arm, "base:1.deg", "'base:1.deg': a decimal point needs a digit after it");
    target_bad(arm, "base:1234567", "'base:1234567': too many digits");
    target_bad(arm, "gripper:70000", "'gripper:70000': a position is 0..65535");
    target_bad(arm, "9:-1", "'9:-1': a position is 0..65535");
    target_bad(arm, "9:1:2", "'9:1:2': unknown unit: write a position (700) or degrees (30deg, "
                             "-15.5deg)");
    /* positions are decimal or 0x-hex, as numbers are everywhere */
    target_ok(arm, "gripper:0x2BC", 1, 700);
    target_ok(arm, "base:0x1f4", 6, 500);
    target_ok(arm, "9:0XFFFF", 9, 65535);
    target_bad(arm, "base:0x10", "position 0x10 is outside the limits of joint base (servo 6): "
                                 "-115.00deg..115.00deg, positions 21..979");
    target_bad(arm, "9:0x10000", "'9:0x10000': a position is 0..65535");
    target_bad(arm, "9:-0x1", "'9:-0x1': a position is 0..65535");
    target_bad(arm, "base:0x10deg", "'base:0x10deg': an angle is written in decimal (30deg, "
                                    "-15.5deg)");
    target_bad(arm, "base:0x", "'base:0x': not a number (0x needs hex digits: 0x2BC)");
    target_bad(arm, "base:0x2g", "'base:0x2g': not a number (0x needs hex digits: 0x2BC)");
    target_bad(arm, "base:0x1234567", "'base:0x1234567': too many digits");
    /* what a message repeats: at most 40 bytes, escaped */
    target_bad(arm, "h\033[2J:1", "'h\\x1B[2J' is neither a joint of the arm profile nor a "
                                  "servo id");
    target_bad(arm, "base:\a", "'base:\\x07': not a number (a position such as 700, or an "
                               "angle such as -15.5deg)");
    target_bad(arm, "abcdefghijabcdefghijabcdefghijabcdefghijXYZ",
               "'abcdefghijabcdefghijabcdefghijabcdefghij' is not JOINT:VALUE (base:30deg, "
               "2:-15.5deg, 1:700)");
    lsc_arm_free(arm);

    /* the LeArm: PWM, a reversed shoulder with its zero 90 degrees off */
    arm = parse_ok(learm);
    target_ok(arm, "shoulder:0deg", 5, 2500);
    target_ok(arm, "base:10deg", 6, 1611);
    target_ok(arm, "shoulder:90deg", 5, 1500);
    target_bad(arm, "shoulder:-0.01deg", "-0.01deg is outside the limits of joint shoulder "
                                         "(servo 5): 0.00deg..175.00deg, positions 556..2500");
    target_bad(arm, "base:100deg", "100deg is outside the limits of joint base (servo 6): "
                                   "-85.00deg..85.00deg, positions 556..2444");
    lsc_arm_free(arm);
}

/* The position that would be sent is what is checked: an angle inside the
 * limits that rounds to a position outside them is refused. */
static void test_exact_limits(void **state)
{
    (void)state;
    lsc_arm *arm = parse_ok("base 6 bus limits=0deg..10deg\n"
                            "rev 7 bus dir=-1 limits=-10deg..0deg\n");
    target_bad(arm, "base:542", "position 542 is outside the limits of joint base (servo 6): "
                                "0.00deg..10.00deg, positions 500..541");
    target_bad(arm, "base:10deg", "10deg (position 542) is outside the limits of joint base "
                                  "(servo 6): 0.00deg..10.00deg, positions 500..541");
    target_bad(arm, "base:9.96deg", "9.96deg (position 542) is outside the limits of joint "
                                    "base (servo 6): 0.00deg..10.00deg, positions 500..541");
    target_ok(arm, "base:9.95deg", 6, 541);
    target_ok(arm, "base:541", 6, 541);
    target_ok(arm, "base:0deg", 6, 500);
    /* an angle outside that rounds to a position inside: still refused */
    target_bad(arm, "base:-0.01deg", "-0.01deg is outside the limits of joint base (servo 6): "
                                     "0.00deg..10.00deg, positions 500..541");
    target_bad(arm, "rev:-10deg", "-10deg (position 542) is outside the limits of joint rev "
                                  "(servo 7): -10.00deg..0.00deg, positions 500..541");
    target_ok(arm, "rev:-9.95deg", 7, 541);
    /* lsc_arm_check: position by position */
    lsc_servo s[] = {{9, 5000}, {6, 541}, {7, 500}, {6, 542}};
    assert_int_equal(lsc_arm_check(arm, s, 3, why, sizeof why), 0);
    assert_int_equal(lsc_arm_check(arm, s, 4, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "position 542 is outside the limits of joint base (servo 6): "
                             "0.00deg..10.00deg, positions 500..541");
    s[2].position = 1001; /* beyond the servo's range */
    assert_int_equal(lsc_arm_check(arm, s, 3, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "position 1001 is outside the limits of joint rev (servo 7): "
                             "-10.00deg..0.00deg, positions 500..541");
    assert_int_equal(lsc_arm_check(NULL, s, 4, why, sizeof why), 0);
    assert_int_equal(lsc_arm_check(arm, NULL, 0, why, sizeof why), 0);
    assert_int_equal(lsc_arm_check(arm, NULL, 1, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "lsc_arm_check: no servos");
    lsc_arm_free(arm);
}

/* Without a profile: ID:POSITION only; reasons that need one say so. */
static void test_targets_without_a_profile(void **state)
{
    (void)state;
    target_ok(NULL, "1:1500", 1, 1500);
    target_ok(NULL, "0xff:0xFFFF", 255, 65535);
    target_bad(NULL, "1:30deg", "'1:30deg': servo 1 is not a joint of any arm profile, so it "
                                "has no degrees: give a position");
    target_bad(NULL, "base:30deg", "'base' is not a servo id: a joint name needs an arm "
                                   "profile");
    target_bad(NULL, "base:deg", "'base' is not a servo id: a joint name needs an arm profile");
    target_bad(NULL, "base:1500", "'base' is not a servo id: a joint name needs an arm profile");
    target_bad(NULL, "1:1.5deg5", "position '1.5deg5' is not a number: write it in decimal "
                                  "or 0x-hex");
    target_bad(NULL, "1:x", "position 'x' is not a number: write it in decimal or 0x-hex");
    target_bad(NULL, "1:\a\t2", "position '\\x07\\x092' is not a number: write it in decimal "
                                "or 0x-hex");
    target_bad(NULL, "1:65536", "position 65536 is out of range: use 0..65535");
    target_bad(NULL, "1:-5", "position '-5' is negative: use 0..65535");
    target_bad(NULL, "256:1", "id 256 is out of range: use 0..255");
    target_bad(NULL, ":1", "id '' is not a number: write it in decimal or 0x-hex");
    target_bad(NULL, "1500", "'1500' is not ID:POS (for example 1:1500)");
    target_bad(NULL, "1234567890123456789012345678901:1", "id 1234567890123456789012345678901 "
                                                          "is out of range: use 0..255");
    target_bad(NULL, "12345678901234567890123456789012:1",
               "'12345678901234567890123456789012:1' is not ID:POS (for example 1:1500)");
    target_bad(NULL, "deg", "'deg' is not JOINT:VALUE (base:30deg, 2:-15.5deg, 1:700)");
    target_bad(NULL, "1:999deg", "'1:999deg': servo 1 is not a joint of any arm profile, so "
                                 "it has no degrees: give a position");
    lsc_servo s = {77, 777};
    assert_int_equal(lsc_arm_target(NULL, NULL, &s, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "lsc_arm_target: no argument or no out");
    assert_int_equal(lsc_arm_target(NULL, "1:1", NULL, why, sizeof why), LSC_EINVAL);
    assert_int_equal(lsc_arm_target(NULL, "1:x", &s, NULL, 0), LSC_EINVAL);
}

/* Which arguments need a profile: a joint's name, an angle. */
static void test_needs_profile(void **state)
{
    (void)state;
    assert_int_equal(lsc_arm_needs_profile(NULL), LSC_ARM_NEEDS_NONE);
    assert_int_equal(lsc_arm_needs_profile(""), LSC_ARM_NEEDS_NONE);
    assert_int_equal(lsc_arm_needs_profile("base"), LSC_ARM_NEEDS_JOINT);
    assert_int_equal(lsc_arm_needs_profile("Base:30deg"), LSC_ARM_NEEDS_JOINT);
    assert_int_equal(lsc_arm_needs_profile("1:30deg"), LSC_ARM_NEEDS_DEGREES);
    assert_int_equal(lsc_arm_needs_profile("1:-1.5deg"), LSC_ARM_NEEDS_DEGREES);
    assert_int_equal(lsc_arm_needs_profile("1:1500"), LSC_ARM_NEEDS_NONE);
    assert_int_equal(lsc_arm_needs_profile("1:1deg5"), LSC_ARM_NEEDS_NONE);
    assert_int_equal(lsc_arm_needs_profile("1deg"), LSC_ARM_NEEDS_NONE); /* no JOINT:VALUE */
    assert_int_equal(lsc_arm_needs_profile("1:d"), LSC_ARM_NEEDS_NONE);
    assert_int_equal(lsc_arm_needs_profile("-5"), LSC_ARM_NEEDS_NONE);
    assert_int_equal(lsc_arm_needs_profile("_x"), LSC_ARM_NEEDS_NONE);
    assert_int_equal(lsc_arm_needs_profile("7"), LSC_ARM_NEEDS_NONE);
    assert_int_equal(lsc_arm_needs_profile("~x"), LSC_ARM_NEEDS_NONE);
    assert_int_equal(lsc_arm_needs_profile("1:"), LSC_ARM_NEEDS_NONE);
}

static void test_servo_ids(void **state)
{
    (void)state;
    lsc_arm *arm = parse_ok(xarm);
    uint8_t id = 77;
    assert_int_equal(lsc_arm_servo_id(arm, "base", &id, why, sizeof why), 0);
    assert_int_equal(id, 6);
    assert_int_equal(lsc_arm_servo_id(arm, "7", &id, why, sizeof why), 0);
    assert_int_equal(id, 7);
    assert_int_equal(lsc_arm_servo_id(arm, "0x1F", &id, why, sizeof why), 0);
    assert_int_equal(id, 31);
    assert_int_equal(lsc_arm_servo_id(NULL, "0X0a", &id, why, sizeof why), 0);
    assert_int_equal(id, 10);
    assert_int_equal(lsc_arm_servo_id(arm, "00000006", &id, why, sizeof why), 0);
    assert_int_equal(id, 6);
    id = 77;
    assert_int_equal(lsc_arm_servo_id(arm, "hand", &id, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "'hand' is neither a joint of the arm profile nor a servo id");
    assert_int_equal(lsc_arm_servo_id(arm, "\033]hand", &id, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "'\\x1B]hand' is neither a joint of the arm profile nor a servo id");
    assert_int_equal(lsc_arm_servo_id(NULL, "hand", &id, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "id 'hand' is not a number: write it in decimal or 0x-hex");
    assert_int_equal(lsc_arm_servo_id(arm, "", &id, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "id '' is not a number: write it in decimal or 0x-hex");
    assert_int_equal(lsc_arm_servo_id(NULL, "-5", &id, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "id '-5' is negative: use 0..255");
    assert_int_equal(lsc_arm_servo_id(arm, "256", &id, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "id 256 is out of range: use 0..255");
    assert_int_equal(lsc_arm_servo_id(arm, "0x100", &id, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "id 0x100 is out of range: use 0..255");
    assert_int_equal(lsc_arm_servo_id(arm, "12a", &id, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "id '12a' is not a number: write it in decimal or 0x-hex");
    assert_int_equal(lsc_arm_servo_id(arm, "1:", &id, why, sizeof why), LSC_EINVAL);
    assert_int_equal(id, 77);
    assert_int_equal(lsc_arm_servo_id(arm, NULL, &id, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "lsc_arm_servo_id: no argument or no id");
    assert_int_equal(lsc_arm_servo_id(arm, "1", NULL, why, sizeof why), LSC_EINVAL);
    lsc_arm_free(arm);
}

static void test_degrees(void **state)
{
    (void)state;
    lsc_arm *arm = parse_ok(learm);
    char deg[LSC_ARM_DEGREES_MAX];
    lsc_servo s = {5, 1500};
    assert_int_equal(lsc_arm_degrees(arm, &s, deg, sizeof deg), 2);
    assert_string_equal(deg, "90.00");
    s = (lsc_servo){6, 1328}; /* -15.48 */
    assert_int_equal(lsc_arm_degrees(arm, &s, deg, sizeof deg), 3);
    assert_string_equal(deg, "-15.48");
    s = (lsc_servo){6, 1499};
    assert_int_equal(lsc_arm_degrees(arm, &s, deg, sizeof deg), 3);
    assert_string_equal(deg, "-0.09");
    s = (lsc_servo){6, 2500};
    assert_int_equal(lsc_arm_degrees(arm, &s, deg, sizeof deg), 3);
    assert_string_equal(deg, "90.00"); /* beyond the limits: still an angle */
    s = (lsc_servo){6, 2501};          /* beyond the servo's range: none */
    assert_int_equal(lsc_arm_degrees(arm, &s, deg, sizeof deg), 3);
    assert_string_equal(deg, "");
    s = (lsc_servo){9, 1500};
    assert_int_equal(lsc_arm_degrees(arm, &s, deg, sizeof deg), -1);
    assert_string_equal(deg, "");
    s = (lsc_servo){6, 1500};
    assert_int_equal(lsc_arm_degrees(NULL, &s, deg, sizeof deg), -1);
    assert_string_equal(deg, "");
    assert_int_equal(lsc_arm_degrees(arm, NULL, deg, sizeof deg), -1);
    assert_string_equal(deg, "");
    deg[0] = 'x';
    assert_int_equal(lsc_arm_degrees(arm, &s, deg, 0), 3);
    assert_int_equal(deg[0], 'x');
    assert_int_equal(lsc_arm_degrees(arm, &s, NULL, 16), 3);
    assert_int_equal(lsc_arm_degrees(arm, &s, deg, 4), 3);
    assert_string_equal(deg, "0.0"); /* cut to fit */
    lsc_arm_free(arm);
}


/* ---- The geometry lines --------------------------------------------------- */

#define FIVE "base 6 bus limits=-115deg..115deg\nshoulder 5 bus limits=-90deg..100deg\n" \
             "elbow 4 bus\nwrist 3 bus\nroll 2 bus\ngripper 1 bus\n"
#define LINKS_OK "links: height=64.7mm upper=98.8mm fore=94.7mm tool=158.8mm\n"

static void test_geometry(void **state)
{
    (void)state;
    lsc_kin_chain c;
    int joints[LSC_ARM_CHAIN_MAX];
    lsc_arm *arm = parse_ok(FIVE "chain: base shoulder elbow wrist roll gripper\n" LINKS_OK);
    assert_int_equal(lsc_arm_chain(arm, &c, joints, why, sizeof why), 0);
    assert_true(c.base_mm == 64.7f && c.upper_mm == 98.8f && c.fore_mm == 94.7f &&
                c.tool_mm == 158.8f);
    assert_true(c.min_deg[LSC_KIN_BASE] == -115.0f && c.max_deg[LSC_KIN_BASE] == 115.0f);
    assert_true(c.min_deg[LSC_KIN_SHOULDER] == -90.0f && c.max_deg[LSC_KIN_SHOULDER] == 100.0f);
    assert_true(c.min_deg[LSC_KIN_ELBOW] == -120.0f && c.max_deg[LSC_KIN_ELBOW] == 120.0f);
    assert_true(lsc_kin_chain_valid(&c));
    static const int want[LSC_ARM_CHAIN_MAX] = {0, 1, 2, 3, 4, 5};
    assert_memory_equal(joints, want, sizeof want);
    /* a copy keeps it; NULL joints */
    lsc_arm *copy = lsc_arm_copy(arm);
    assert_int_equal(lsc_arm_chain(copy, &c, NULL, NULL, 0), 0);
    lsc_arm_free(copy);
    lsc_arm_free(arm);
    /* links first, in any order, no gripper, whole millimetres, 0 height and tool */
    arm = parse_ok("links: tool=0mm fore=94mm upper=98.25mm height=0mm\n" FIVE
                   "chain: roll shoulder elbow wrist base\n");
    assert_int_equal(lsc_arm_chain(arm, &c, joints, why, sizeof why), 0);
    assert_true(c.base_mm == 0.0f && c.upper_mm == 98.25f && c.fore_mm == 94.0f &&
                c.tool_mm == 0.0f);
    static const int want2[LSC_ARM_CHAIN_MAX] = {4, 1, 2, 3, 0, -1};
    assert_memory_equal(joints, want2, sizeof want2);
    lsc_arm_free(arm);
    /* without geometry: everything else works, the chain says what is missing */
    arm = parse_ok(FIVE);
    assert_int_equal(lsc_arm_chain(arm, &c, joints, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "the arm profile states no geometry: add its chain: and links: "
                             "lines (docs/arm-profile.md, docs/kinematics.md)");
    assert_int_equal(lsc_arm_chain(arm, NULL, joints, why, sizeof why), LSC_EINVAL);
    assert_string_equal(why, "lsc_arm_chain: no arm profile or no chain");
    assert_int_equal(lsc_arm_chain(NULL, &c, joints, why, sizeof why), LSC_EINVAL);
    lsc_arm_free(arm);
}

static void test_geometry_errors(void **state)
{
    (void)state;
    static const char names[] = "chain: names the joints base, shoulder, elbow, wrist (pitch), "
                                "wrist roll and, if you like, the gripper, in that order";
    char want[256];
    snprintf(want, sizeof want, ":7:1: %s", names);
    bad(FIVE "chain: base shoulder elbow wrist\n" LINKS_OK, want);
    bad(FIVE "chain: base shoulder elbow wrist roll gripper base\n" LINKS_OK, want);
    bad(FIVE "chain: base shoulder elbow wrist roll\nchain: base shoulder elbow wrist roll\n",
        ":8:1: chain: is given twice");
    bad(FIVE "chain: base shoulder elbow wrist hand\n" LINKS_OK,
        ":7:34: chain: 'hand' is no joint of a line above");
    bad("chain: base shoulder elbow wrist roll\n" FIVE LINKS_OK,
        ":1:8: chain: 'base' is no joint of a line above");
    bad(FIVE "chain: base shoulder elbow wrist base\n" LINKS_OK,
        ":7:34: chain: joint base is named twice");
    bad(FIVE "chain: base shoulder elbow wrist roll\n",
        ":7:1: chain: needs a links: line too (docs/arm-profile.md)");
    bad(FIVE "\n" LINKS_OK, ":8:1: links: needs a chain: line too (docs/arm-profile.md)");
    bad(FIVE LINKS_OK LINKS_OK, ":8:1: links: is given twice");
    bad(FIVE "links: height=1mm upper=1mm fore=1mm\n",
        ":7:37: links: gives height=, upper=, fore= and tool= (tool is missing)");
    bad(FIVE "links: tool=1mm upper=1mm fore=1mm\n",
        ":7:35: links: gives height=, upper=, fore= and tool= (height is missing)");
    bad(FIVE "links:\n", ":7:7: links: gives height=, upper=, fore= and tool= (height is "
                         "missing)");
    bad(FIVE "links: length=1mm\n",
        ":7:8: links: 'length=1mm': use height=, upper=, fore= and tool= (mm)");
    bad(FIVE "links: height\n", ":7:8: links: 'height': use height=, upper=, fore= and tool= "
                               "(mm)");
    bad(FIVE "links: height=1mm height=2mm\n", ":7:19: links: height is given twice");
    static const struct {
        const char *value, *why;
    } values[] = {
        {"", "write a length in mm (98.8mm)"},
        {"mm", "write a length in mm (98.8mm)"},
        {"-1mm", "write a length in mm (98.8mm)"},
        {"1", "write a length in mm (98.8mm)"},
        {"1cm", "write a length in mm (98.8mm)"},
        {"1.mm", "a decimal point needs a digit after it"},
        {"1.", "a decimal point needs a digit after it"},
        {"1.234mm", "a length has at most two decimals (0.01mm)"},
        {"10000.01mm", "at most 10000mm"},
        {"99999999999mm", "at most 10000mm"},
        {"0mm", "the arm's links are longer than 0mm"},
        {"0.00mm", "the arm's links are longer than 0mm"},
    };
    for (size_t i = 0; i < sizeof values / sizeof values[0]; i++) {
        char text[512], msg[160];
        snprintf(text, sizeof text, FIVE "links: upper=%s\n", values[i].value);
        snprintf(msg, sizeof msg, ":7:14: links: upper: %s", values[i].why);
        bad(text, msg);
    }
    lsc_arm_free(parse_ok(FIVE "chain: base shoulder elbow wrist roll\n"
                               "links: height=10000mm upper=10000.00mm fore=0.01mm tool=0mm\n"));
    bad(FIVE "links: fore=0mm\n", ":7:13: links: fore: the arm's links are longer than 0mm");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_escape),
        cmocka_unit_test(test_examples),
        cmocka_unit_test(test_stand_in),
        cmocka_unit_test(test_every_setting),
        cmocka_unit_test(test_default_limits_keep_the_ends),
        cmocka_unit_test(test_profile_errors),
        cmocka_unit_test(test_control_bytes_in_comments),
        cmocka_unit_test(test_joints_max),
        cmocka_unit_test(test_byte_order_mark),
        cmocka_unit_test(test_limits_without_a_position),
        cmocka_unit_test(test_positions_match_allows_pos),
        cmocka_unit_test(test_parse_arguments),
        cmocka_unit_test(test_file_names_escaped),
        cmocka_unit_test(test_load),
        cmocka_unit_test(test_load_size),
        cmocka_unit_test(test_open_by_name),
        cmocka_unit_test(test_load_only_regular_files),
        cmocka_unit_test(test_load_no_device),
        cmocka_unit_test(test_out_of_memory),
        cmocka_unit_test(test_gripper_ends),
        cmocka_unit_test(test_lookups),
        cmocka_unit_test(test_targets),
        cmocka_unit_test(test_exact_limits),
        cmocka_unit_test(test_targets_without_a_profile),
        cmocka_unit_test(test_needs_profile),
        cmocka_unit_test(test_servo_ids),
        cmocka_unit_test(test_degrees),
        cmocka_unit_test(test_geometry),
        cmocka_unit_test(test_geometry_errors),
    };
    return cmocka_run_group_tests(tests, make_dir, remove_dir);
}
