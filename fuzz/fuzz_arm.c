/* Fuzz harness for lscctl's arm profile reader and its move targets
 * (cli/lscctl_arm.c, docs/arm-profile.md): the file behind --arm / LSC_ARM.
 *
 * Input: byte 0 is the length L of a move target (JOINT:VALUE), bytes
 * 1..L the target, the rest the profile text. Checked on every input:
 *  - the parse succeeds with 1..LSCCTL_ARM_JOINTS_MAX joints, each valid for
 *    lsc/units.h (lsc_joint_valid), reading 0 degrees at its zero, with a
 *    non-empty name of letters, digits, _ and - that starts with a letter;
 *    names and ids distinct;
 *  - or it fails with a reason that starts with the file's name and no
 *    joints counted;
 *  - a target accepted against a parsed profile gives a joint's servo and a
 *    position inside that joint's range (or a servo that is no joint);
 *    a refused one gives a reason.
 */
#include <string.h>

#include "fuzz.h"
#include "lscctl_arm.h"

static bool name_ok(const char *s)
{
    size_t n = strlen(s);
    if (n == 0 || n > LSCCTL_ARM_NAME_MAX || !((s[0] >= 'a' && s[0] <= 'z') ||
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

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static lscctl_arm arm;
    char why[256], target[256];
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
    if (lscctl_arm_parse(&arm, text, len, "fuzz.conf", why, sizeof why) != 0) {
        FUZZ_CHECK(strncmp(why, "fuzz.conf:", 10) == 0);
        FUZZ_CHECK(arm.n <= LSCCTL_ARM_JOINTS_MAX);
        return 0;
    }
    FUZZ_CHECK(arm.n >= 1 && arm.n <= LSCCTL_ARM_JOINTS_MAX);
    for (size_t i = 0; i < arm.n; i++) {
        const lsc_joint *j = &arm.joints[i].joint;
        int32_t cdeg = 1;
        FUZZ_CHECK(name_ok(arm.joints[i].name));
        FUZZ_CHECK(lsc_joint_valid(j));
        FUZZ_CHECK(lsc_joint_to_cdeg(j, j->zero, &cdeg) == 0 && cdeg == 0);
        for (size_t k = 0; k < i; k++) {
            FUZZ_CHECK(strcmp(arm.joints[k].name, arm.joints[i].name) != 0);
            FUZZ_CHECK(arm.joints[k].joint.id != j->id);
        }
        FUZZ_CHECK(lscctl_arm_find(&arm, arm.joints[i].name, strlen(arm.joints[i].name)) ==
                   &arm.joints[i]);
    }
    lsc_servo s;
    why[0] = '\0';
    if (memchr(target, '\0', tlen) == NULL &&
        lscctl_arm_target(&arm, target, &s, why, sizeof why) == 0) {
        char id[8];
        snprintf(id, sizeof id, "%u", s.id);
        const lscctl_arm_joint *aj = lscctl_arm_find(&arm, id, strlen(id));
        FUZZ_CHECK(aj == NULL ||
                   (s.position >= aj->joint.pos_min && s.position <= aj->joint.pos_max));
    } else {
        FUZZ_CHECK(memchr(target, '\0', tlen) != NULL || why[0] != '\0');
    }
    return 0;
}
