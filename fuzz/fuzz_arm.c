/* Fuzz harness for the library's arm profiles and move targets
 * (src/arm, include/lsc/arm.h, docs/arm-profile.md): the file behind
 * lscctl's --arm / LSC_ARM.
 *
 * Input: byte 0 is the length L of a move target (JOINT:VALUE), bytes
 * 1..L the target, the rest the profile text. Checked on every input:
 *  - the parse succeeds with 1..LSC_ARM_JOINTS_MAX joints, each valid for
 *    lsc/units.h (lsc_joint_valid), reading 0 degrees at its zero, allowing
 *    at least one position of its servo, with a non-empty name of letters,
 *    digits, _ and - that starts with a letter; names and ids distinct;
 *    found again by name and by id; a copy equal to it;
 *  - or it fails with a one-line reason that starts with the file's name,
 *    and no profile;
 *  - a target accepted against a parsed profile gives a joint's servo and a
 *    position the joint's limits allow (the position sent is what is
 *    checked), which lsc_arm_check accepts too, or a servo that is no joint;
 *    a refused one gives a one-line reason;
 *  - the geometry lines (chain:, links:): lsc_arm_chain gives a chain that
 *    lsc/kinematics.h accepts, with distinct joints of the profile in its
 *    roles (the gripper's may be -1), or a one-line reason.
 */
#include <string.h>

#include "fuzz.h"
#include "lsc/arm.h"

static bool name_ok(const char *s)
{
    size_t n = strlen(s);
    if (n == 0 || n > LSC_ARM_NAME_MAX || !((s[0] >= 'a' && s[0] <= 'z') ||
                                             (s[0] >= 'A' && s[0] <= 'Z'))) {
        return false;
    }
    for (size_t i = 0; i < n; i++) {
        char c = s[i];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
              c == '_' || c == '-')) {
            return false;
        }
    }
    return true;
}

/* one line of printable text: no control byte (file names and arguments escaped) */
static bool one_line(const char *s)
{
    for (; *s != '\0'; s++) {
        if ((unsigned char)*s < 0x20 || (unsigned char)*s == 0x7f) {
            return false;
        }
    }
    return true;
}

static bool some_position(const lsc_joint *j)
{
    for (uint32_t p = j->pos_min; p <= j->pos_max; p++) {
        if (lsc_joint_allows_pos(j, (uint16_t)p)) {
            return true;
        }
    }
    return false;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    lsc_arm *arm = NULL;
    char why[LSC_ARM_MESSAGE_MAX], target[256];
    size_t tlen = size > 0 ? data[0] : 0;
    if (tlen > size - (size > 0 ? 1u : 0u)) {
        tlen = size > 0 ? size - 1u : 0u;
    }
    if (size > 0) {
        memcpy(target, data + 1, tlen);
    }
    target[tlen] = '\0';
    const char *text = size > 0 ? (const char *)data + 1 + tlen : "";
    size_t len = size > 0 ? size - 1u - tlen : 0u;
    why[0] = '\0';
    if (lsc_arm_parse(text, len, "fuzz.conf", &arm, why, sizeof why) != 0) {
        FUZZ_CHECK(strncmp(why, "fuzz.conf", 9) == 0 && one_line(why));
        FUZZ_CHECK(arm == NULL);
        return 0;
    }
    size_t n = lsc_arm_count(arm);
    FUZZ_CHECK(n >= 1 && n <= LSC_ARM_JOINTS_MAX);
    FUZZ_CHECK(lsc_arm_name(arm, n) == NULL && lsc_arm_joint(arm, n) == NULL);
    lsc_arm *copy = lsc_arm_copy(arm);
    FUZZ_CHECK(copy != NULL && lsc_arm_count(copy) == n);
    for (size_t i = 0; i < n; i++) {
        const lsc_joint *j = lsc_arm_joint(arm, i);
        const char *name = lsc_arm_name(arm, i);
        int32_t cdeg = 1;
        FUZZ_CHECK(name_ok(name));
        FUZZ_CHECK(lsc_joint_valid(j));
        FUZZ_CHECK(lsc_joint_to_cdeg(j, j->zero, &cdeg) == 0 && cdeg == 0);
        FUZZ_CHECK(some_position(j));
        for (size_t k = 0; k < i; k++) {
            FUZZ_CHECK(strcmp(lsc_arm_name(arm, k), name) != 0);
            FUZZ_CHECK(lsc_arm_joint(arm, k)->id != j->id);
        }
        FUZZ_CHECK(lsc_arm_find(arm, name) == (int)i);
        FUZZ_CHECK(lsc_arm_by_id(arm, j->id) == (int)i);
        FUZZ_CHECK(strcmp(lsc_arm_name(copy, i), name) == 0);
        const lsc_joint *c = lsc_arm_joint(copy, i);
        FUZZ_CHECK(c->id == j->id && c->direction == j->direction && c->zero == j->zero &&
                   c->pos_min == j->pos_min && c->pos_max == j->pos_max &&
                   c->span_cdeg == j->span_cdeg && c->min_cdeg == j->min_cdeg &&
                   c->max_cdeg == j->max_cdeg);
    }
    lsc_arm_free(copy);
    lsc_kin_chain chain;
    int joints[LSC_ARM_CHAIN_MAX];
    why[0] = '\0';
    if (lsc_arm_chain(arm, &chain, joints, why, sizeof why) == 0) {
        FUZZ_CHECK(lsc_kin_chain_valid(&chain));
        for (size_t i = 0; i < LSC_ARM_CHAIN_MAX; i++) {
            FUZZ_CHECK(joints[i] < (int)n && (joints[i] >= 0 || i == LSC_ARM_GRIPPER));
            for (size_t k = 0; k < i; k++) {
                FUZZ_CHECK(joints[i] < 0 || joints[k] != joints[i]);
            }
        }
    } else {
        FUZZ_CHECK(why[0] != '\0' && one_line(why));
    }
    lsc_servo s;
    why[0] = '\0';
    if (memchr(target, '\0', tlen) == NULL &&
        lsc_arm_target(arm, target, &s, why, sizeof why) == 0) {
        int i = lsc_arm_by_id(arm, s.id);
        char deg[LSC_ARM_DEGREES_MAX];
        FUZZ_CHECK(i < 0 || lsc_joint_allows_pos(lsc_arm_joint(arm, (size_t)i), s.position));
        FUZZ_CHECK(lsc_arm_check(arm, &s, 1, why, sizeof why) == 0);
        FUZZ_CHECK(lsc_arm_degrees(arm, &s, deg, sizeof deg) == i);
        FUZZ_CHECK(i < 0 ? deg[0] == '\0' : deg[0] != '\0');
    } else {
        FUZZ_CHECK(memchr(target, '\0', tlen) != NULL || (why[0] != '\0' && one_line(why)));
    }
    lsc_arm_free(arm);
    return 0;
}
