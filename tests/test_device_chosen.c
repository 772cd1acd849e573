/* test_device_chosen.c: vkc_options.chosen, which lets --precision auto
 * decide what to pack while the logical device is still being made.
 *
 * The callback must come once, after the physical device is chosen and
 * what it offers is known (props, float64: as they end up), and before
 * the logical device exists; never when no device is chosen.
 *
 * With the argument no_fp64 it runs under VK_LAYER_TP2_no_fp64
 * (tests/layers), as on a device without shaderFloat64: the callback sees
 * none, and the layer refuses a shader module that declares Float64 (the
 * double trace shader); a float module is made without a message (the
 * validation layer checks a module's capabilities against the device's
 * features when a pipeline is made, which the layer forestalls). Prints
 * "N passed, M failed" last. */
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "trace_double_basic_spv.h"
#include "trace_float_basic_spv.h"
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

/* Makes a shader module of `bytes` of code on a validated context's
 * device; its result, and the validation messages it drew in *messages. */
static VkResult module_of(const uint32_t *code, size_t bytes, unsigned *messages)
{
    struct vkc c;
    struct vkc_options opt = {.device_index = -1, .validate = true};
    VkResult r = VK_ERROR_INITIALIZATION_FAILED;
    *messages = 0;
    if (vkc_create(&c, &opt) == 0) {
        unsigned before = vkc_validation_message_count();
        VkShaderModuleCreateInfo info = {
            .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
            .codeSize = bytes,
            .pCode = code,
        };
        VkShaderModule module = VK_NULL_HANDLE;
        r = vkCreateShaderModule(c.device, &info, NULL, &module);
        if (r == VK_SUCCESS)
            vkDestroyShaderModule(c.device, module, NULL);
        *messages = vkc_validation_message_count() - before;
    }
    vkc_destroy(&c);
    return r;
}

int main(int argc, char **argv)
{
    struct seen s;
    /* The tests pick lavapipe (VK_ICD_FILENAMES): a CPU device with
     * shaderFloat64, unless the layer hides it. */
    bool hidden = argc > 1 && strcmp(argv[1], "no_fp64") == 0;
    CHECK(chosen_with(-1, &s) == 0);
    CHECK(s.type == VK_PHYSICAL_DEVICE_TYPE_CPU && s.float64 == !hidden);
    CHECK(chosen_with(99, &s) != 0); /* no such device: never chosen */
    expect(s.calls == 0, "no device, yet %d calls", s.calls);
    if (hidden) {
        unsigned messages;
        VkResult r = module_of(tp2_trace_double_basic, sizeof tp2_trace_double_basic, &messages);
        expect(r == VK_ERROR_FEATURE_NOT_PRESENT, "a Float64 module: %d", (int)r);
        r = module_of(tp2_trace_float_basic, sizeof tp2_trace_float_basic, &messages);
        expect(r == VK_SUCCESS && messages == 0, "a float module: %d, %u messages", (int)r,
               messages);
    }
    return unit_report();
}
