/* test_device_chosen.c: vkc_options.chosen, which lets --precision auto
 * decide what to pack while the logical device is still being made.
 *
 * The callback must come once, after the physical device is chosen and
 * what it offers is known (props, float64: as they end up), and before
 * the logical device exists; never when no device is chosen. Prints
 * "N passed, M failed" last. */
#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>
#include <string.h>

#include "vk_context.h"

#include "unit.h"

struct seen {
    int calls;
    bool device_made; /* the logical device existed at the call */
    bool float64;
    VkPhysicalDeviceType type;
    char name[VK_MAX_PHYSICAL_DEVICE_NAME_SIZE];
};

static void on_chosen(const struct vkc *c, void *user)
{
    struct seen *s = user;
    s->calls++;
    s->device_made = c->device != VK_NULL_HANDLE;
    s->float64 = c->float64;
    s->type = c->props.deviceType;
    memcpy(s->name, c->props.deviceName, sizeof s->name);
}

/* Makes a context with the callback, checks what it saw; 0 or -1 as
 * vkc_create. */
static int chosen_with(int device_index, struct seen *s)
{
    struct vkc c;
    struct vkc_options opt = {.device_index = device_index, .want_float64 = true,
                              .chosen = on_chosen, .chosen_user = s};
    memset(s, 0, sizeof *s);
    int rc = vkc_create(&c, &opt);
    if (rc == 0) {
        expect(s->calls == 1, "one call, got %d", s->calls);
        CHECK(!s->device_made);
        CHECK(c.device != VK_NULL_HANDLE);
        expect(s->float64 == c.float64, "float64 at the call %d, after %d", s->float64,
               c.float64);
        CHECK(s->type == c.props.deviceType);
        CHECK(strcmp(s->name, c.props.deviceName) == 0 && s->name[0] != '\0');
    }
    vkc_destroy(&c);
    return rc;
}

int main(void)
{
    struct seen s;
    /* The tests pick lavapipe (VK_ICD_FILENAMES): a CPU device with
     * shaderFloat64. */
    CHECK(chosen_with(-1, &s) == 0);
    CHECK(s.type == VK_PHYSICAL_DEVICE_TYPE_CPU && s.float64);
    setenv("TP2_FLOAT64", "0", 1); /* as a device without it */
    CHECK(chosen_with(-1, &s) == 0);
    CHECK(!s.float64);
    unsetenv("TP2_FLOAT64");
    CHECK(chosen_with(99, &s) != 0); /* no such device: never chosen */
    expect(s.calls == 0, "no device, yet %d calls", s.calls);
    return unit_report();
}
