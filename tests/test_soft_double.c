/* test_soft_double.c: shaders/soft_double.glsl computes what IEEE 754
 * binary64 does, bit for bit.
 *
 * soft_double_probe.comp runs one operation on each of some 200,000 input
 * pairs on the device (through validation; no 64-bit type in the shader,
 * so it also runs under the no_fp64 layer), and each result is compared
 * with the host's double arithmetic (SSE2: correctly rounded, no fused
 * multiply-adds in this file): add, sub, mul, div, sqrt, floor, fract,
 * min, max, the six comparisons, the conversions from and to float and
 * int, negation and absolute value. Inputs: every pair of some 40 special
 * values (zeros, infinities, NaN, subnormals, the ends of the range,
 * ties), random bit patterns, pairs of nearby magnitudes (cancellation),
 * products of 27-bit integers (exact ties in half the cases), and
 * quotients and squares built to round at a half. A NaN equals any NaN.
 * Prints "N passed, M failed" last. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "soft_double_probe_spv.h"
#include "vk_buffer.h"
#include "vk_check.h"
#include "vk_context.h"

#include "unit.h"

enum { OP_ADD, OP_SUB, OP_MUL, OP_DIV, OP_SQRT, OP_FLOOR, OP_FRACT, OP_MIN, OP_MAX, OP_COMPARE,
       OP_TO_FLOAT, OP_FROM_FLOAT, OP_FROM_INT, OP_TO_INT, OP_NEG, OP_ABS, OP_COUNT };
static const char *const op_names[OP_COUNT] = {
    "add", "sub", "mul", "div", "sqrt", "floor", "fract", "min", "max", "compare",
    "to_float", "from_float", "from_int", "to_int", "neg", "abs"};

static uint64_t bits_of(double d)
{
    uint64_t u;
    memcpy(&u, &d, sizeof u);
    return u;
}

static double double_of(uint64_t u)
{
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

static uint32_t float_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

/* xorshift64*: the same inputs every run. */
static uint64_t rng_state = 0x9E3779B97F4A7C15u;
static uint64_t next_random(void)
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return rng_state * 0x2545F4914F6CDD1Du;
}

/* What the library promises, computed by the host. min and max: a NaN
 * operand gives the other; of equal operands (two zeros), the second. */
static uint64_t expected(int op, uint64_t ua, uint64_t ub)
{
    double a = double_of(ua), b = double_of(ub);
    switch (op) {
    case OP_ADD: return bits_of(a + b);
    case OP_SUB: return bits_of(a - b);
    case OP_MUL: return bits_of(a * b);
    case OP_DIV: return bits_of(a / b);
    case OP_SQRT: return bits_of(sqrt(a));
    case OP_FLOOR: return bits_of(floor(a));
    case OP_FRACT: return bits_of(a - floor(a));
    case OP_MIN: return isnan(a) ? ub : isnan(b) ? ua : a < b ? ua : ub;
    case OP_MAX: return isnan(a) ? ub : isnan(b) ? ua : b < a ? ua : ub;
    case OP_COMPARE:
        return (a < b) | (a <= b) << 1 | (a > b) << 2 | (a >= b) << 3 | (a == b) << 4 |
               (a != b) << 5;
    case OP_TO_FLOAT: return float_bits((float)a);
    case OP_FROM_FLOAT: {
        float f;
        uint32_t u = (uint32_t)ua;
        memcpy(&f, &u, sizeof f);
        return bits_of((double)f);
    }
    case OP_FROM_INT: return bits_of((double)(int32_t)(uint32_t)ua);
    case OP_TO_INT:
        return (uint32_t)(a > -2147483649.0 && a < 2147483648.0 ? (int32_t)a : INT32_MIN);
    case OP_NEG: return ua ^ (1ull << 63);
    case OP_ABS: return ua & ~(1ull << 63);
    }
    return 0;
}

static bool is_nan_bits(uint64_t u) { return isnan(double_of(u)); }

/* Whether the device's result r is op's on (a, b): NaN for NaN, else the
 * same bits (a float's NaN for to_float). */
static bool agrees(int op, uint64_t a, uint64_t b, uint64_t r)
{
    uint64_t want = expected(op, a, b);
    if (op == OP_TO_FLOAT) {
        float fw, fr;
        uint32_t w32 = (uint32_t)want, r32 = (uint32_t)r;
        memcpy(&fw, &w32, sizeof fw);
        memcpy(&fr, &r32, sizeof fr);
        return (isnan(fw) && isnan(fr) && r >> 32 == 0) || want == r;
    }
    bool numeric = op != OP_COMPARE && op != OP_TO_INT;
    if (numeric && is_nan_bits(want))
        return is_nan_bits(r);
    return want == r;
}

/* The inputs. */
struct inputs {
    uint64_t (*pair)[2];
    size_t count, capacity;
};

static void add_pair(struct inputs *in, uint64_t a, uint64_t b)
{
    if (in->count == in->capacity) {
        in->capacity = in->capacity ? 2 * in->capacity : 4096;
        in->pair = realloc(in->pair, in->capacity * sizeof *in->pair);
        if (!in->pair)
            abort();
    }
    in->pair[in->count][0] = a;
    in->pair[in->count][1] = b;
    in->count++;
}

static void add_doubles(struct inputs *in, double a, double b)
{
    add_pair(in, bits_of(a), bits_of(b));
}

/* A random double of exponent in [lo, hi] (unbiased) and random sign. */
static double random_double(int lo, int hi)
{
    uint64_t r = next_random();
    double m = 1.0 + (double)(r >> 12) / 4503599627370496.0;
    return ldexp(r & 1 ? -m : m, lo + (int)(next_random() % (uint64_t)(hi - lo + 1)));
}

static void make_inputs(struct inputs *in)
{
    const double specials[] = {
        0.0, -0.0, 1.0, -1.0, 2.0, 0.5, 3.0, -3.0, 0.1, 0.3, 1.5, -2.5, 7.0, 1e-300, -1e300,
        1e300, 4.9406564584124654e-324, -4.9406564584124654e-324, 2.2250738585072009e-308,
        2.2250738585072014e-308, -2.2250738585072014e-308, 1.7976931348623157e308,
        -1.7976931348623157e308, INFINITY, -INFINITY, NAN, -NAN, 0x1p-53, 0x1.8p-53,
        0x1p-54, 1.0 + 0x1p-52, 1.0 - 0x1p-53, 2147483647.0, -2147483648.0, 2147483648.0,
        -2147483649.5, 4503599627370496.5, 0x1p52, -0x1p52 - 1, 3.4028235677973366e38,
        3.4028236e38, 1.1754943508222875e-38, 7.006492321624085e-46, 1.401298464324817e-45,
        0.49999999999999994, -0.49999999999999994, 1e-45, 1e-46};
    size_t n = sizeof specials / sizeof *specials;
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++)
            add_doubles(in, specials[i], specials[j]);
    for (int i = 0; i < 40000; i++)
        add_pair(in, next_random(), next_random());
    for (int i = 0; i < 40000; i++) { /* magnitudes near each other */
        double a = random_double(-30, 30);
        double b = -a * (1.0 + random_double(-60, -1));
        add_doubles(in, a, i & 1 ? b : ldexp(b, (int)(next_random() % 60) - 30));
    }
    for (int i = 0; i < 40000; i++) { /* wide ranges, subnormal ends included */
        add_doubles(in, random_double(-1074, 1023), random_double(-1074, 1023));
        add_doubles(in, random_double(-1060, -1000), random_double(-60, 60));
    }
    for (int i = 0; i < 40000; i++) { /* 27-bit integers: exact ties of products */
        double a = (double)((next_random() % (1u << 26)) | (1u << 26) | 1u);
        double b = (double)((next_random() % (1u << 26)) | (1u << 26) | 1u);
        add_doubles(in, ldexp(a, (int)(next_random() % 200) - 100), b);
        add_doubles(in, a * b, b); /* rounded products: quotients near a half */
    }
    for (int i = 0; i < 20000; i++) { /* exact squares, and the numbers beside them */
        double r = (double)(next_random() >> 38);
        uint64_t s = bits_of(r * r);
        add_pair(in, s, s + 1);
        add_pair(in, s - 1, s);
        add_doubles(in, random_double(-8, 8), random_double(-8, 8));
        add_doubles(in, (double)(int32_t)next_random(), 0.0);
    }
}

/* The probe pipeline and its buffers. */
struct probe {
    struct vk_buffer in, out;
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkShaderModule module;
    VkPipeline pipeline;
    VkDescriptorPool pool;
    VkDescriptorSet set;
    VkCommandPool commands;
    VkCommandBuffer cmd;
    VkFence fence;
};

static int probe_create(const struct vkc *c, struct probe *p, size_t count)
{
    if (vk_buffer_create(c, count * 16, false, &p->in) != 0 ||
        vk_buffer_create(c, count * 8, true, &p->out) != 0)
        return -1;
    VkDescriptorSetLayoutBinding bindings[2];
    for (uint32_t i = 0; i < 2; i++)
        bindings[i] = (VkDescriptorSetLayoutBinding){
            .binding = i,
            .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
            .descriptorCount = 1,
            .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT,
        };
    VkDescriptorSetLayoutCreateInfo set_info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = 2,
        .pBindings = bindings,
    };
    TP2_VK_TRY(vkCreateDescriptorSetLayout(c->device, &set_info, NULL, &p->set_layout));
    VkPushConstantRange push = {.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT, .size = 8};
    VkPipelineLayoutCreateInfo layout_info = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1,
        .pSetLayouts = &p->set_layout,
        .pushConstantRangeCount = 1,
        .pPushConstantRanges = &push,
    };
    TP2_VK_TRY(vkCreatePipelineLayout(c->device, &layout_info, NULL, &p->layout));
    VkShaderModuleCreateInfo module_info = {
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
        .codeSize = sizeof tp2_soft_double_probe,
        .pCode = tp2_soft_double_probe,
    };
    TP2_VK_TRY(vkCreateShaderModule(c->device, &module_info, NULL, &p->module));
    VkComputePipelineCreateInfo pipeline_info = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {
            .sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
            .stage = VK_SHADER_STAGE_COMPUTE_BIT,
            .module = p->module,
            .pName = "main",
        },
        .layout = p->layout,
    };
    TP2_VK_TRY(vkCreateComputePipelines(c->device, VK_NULL_HANDLE, 1, &pipeline_info, NULL,
                                        &p->pipeline));
    VkDescriptorPoolSize size = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2};
    VkDescriptorPoolCreateInfo pool_info = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .maxSets = 1,
        .poolSizeCount = 1,
        .pPoolSizes = &size,
    };
    TP2_VK_TRY(vkCreateDescriptorPool(c->device, &pool_info, NULL, &p->pool));
    VkDescriptorSetAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = p->pool,
        .descriptorSetCount = 1,
        .pSetLayouts = &p->set_layout,
    };
    TP2_VK_TRY(vkAllocateDescriptorSets(c->device, &alloc, &p->set));
    VkDescriptorBufferInfo buffers[2] = {{p->in.buffer, 0, VK_WHOLE_SIZE},
                                         {p->out.buffer, 0, VK_WHOLE_SIZE}};
    VkWriteDescriptorSet writes[2];
    for (uint32_t i = 0; i < 2; i++)
        writes[i] = (VkWriteDescriptorSet){
            .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
            .dstSet = p->set,
            .dstBinding = i,
            .descriptorCount = 1,
            .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
            .pBufferInfo = &buffers[i],
        };
    vkUpdateDescriptorSets(c->device, 2, writes, 0, NULL);
    VkCommandPoolCreateInfo commands_info = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
        .queueFamilyIndex = c->queue_family,
    };
    TP2_VK_TRY(vkCreateCommandPool(c->device, &commands_info, NULL, &p->commands));
    VkCommandBufferAllocateInfo cmd_info = {
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = p->commands,
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    TP2_VK_TRY(vkAllocateCommandBuffers(c->device, &cmd_info, &p->cmd));
    VkFenceCreateInfo fence_info = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    TP2_VK_TRY(vkCreateFence(c->device, &fence_info, NULL, &p->fence));
    return 0;
}

static void probe_destroy(const struct vkc *c, struct probe *p)
{
    if (!c->device)
        return;
    vkDeviceWaitIdle(c->device);
    vkDestroyFence(c->device, p->fence, NULL);
    vkDestroyCommandPool(c->device, p->commands, NULL);
    vkDestroyDescriptorPool(c->device, p->pool, NULL);
    vkDestroyPipeline(c->device, p->pipeline, NULL);
    vkDestroyShaderModule(c->device, p->module, NULL);
    vkDestroyPipelineLayout(c->device, p->layout, NULL);
    vkDestroyDescriptorSetLayout(c->device, p->set_layout, NULL);
    vk_buffer_destroy(c, &p->out);
    vk_buffer_destroy(c, &p->in);
}

/* Runs op on the first `count` pairs already in p->in. */
static int probe_run(const struct vkc *c, struct probe *p, uint32_t op, uint32_t count)
{
    uint32_t push[2] = {op, count};
    VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    TP2_VK_TRY(vkResetCommandBuffer(p->cmd, 0));
    TP2_VK_TRY(vkBeginCommandBuffer(p->cmd, &begin));
    vkCmdBindPipeline(p->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
    vkCmdBindDescriptorSets(p->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 1, &p->set,
                            0, NULL);
    vkCmdPushConstants(p->cmd, p->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, push);
    vkCmdDispatch(p->cmd, (count + 63) / 64, 1, 1);
    VkMemoryBarrier to_host = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_HOST_READ_BIT,
    };
    vkCmdPipelineBarrier(p->cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, NULL, 0, NULL);
    TP2_VK_TRY(vkEndCommandBuffer(p->cmd));
    VkSubmitInfo submit = {
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
        .commandBufferCount = 1,
        .pCommandBuffers = &p->cmd,
    };
    TP2_VK_TRY(vkResetFences(c->device, 1, &p->fence));
    TP2_VK_TRY(vkQueueSubmit(c->queue, 1, &submit, p->fence));
    TP2_VK_TRY(vkWaitForFences(c->device, 1, &p->fence, VK_TRUE, UINT64_MAX));
    return 0;
}

int main(void)
{
    struct inputs in = {0};
    make_inputs(&in);
    struct vkc c = {0};
    struct vkc_options opt = {.device_index = -1, .validate = true};
    if (vkc_create(&c, &opt) != 0) {
        vkc_destroy(&c);
        return 77;
    }
    struct probe p = {0};
    int made = probe_create(&c, &p, in.count);
    CHECK(made == 0);
    uint32_t *words = p.in.mapped;
    for (size_t i = 0; made == 0 && i < in.count; i++)
        for (int k = 0; k < 2; k++) {
            words[4 * i + 2 * k] = (uint32_t)in.pair[i][k];
            words[4 * i + 2 * k + 1] = (uint32_t)(in.pair[i][k] >> 32);
        }
    for (int op = 0; made == 0 && op < OP_COUNT; op++) {
        if (probe_run(&c, &p, (uint32_t)op, (uint32_t)in.count) != 0) {
            CHECK(!"probe dispatched");
            break;
        }
        const uint32_t *out = p.out.mapped;
        size_t wrong = 0;
        for (size_t i = 0; i < in.count; i++) {
            uint64_t r = out[2 * i] | (uint64_t)out[2 * i + 1] << 32;
            uint64_t a = in.pair[i][0], b = in.pair[i][1];
            if (agrees(op, a, b, r))
                continue;
            if (wrong++ < 5)
                printf("%s(%a [%016llx], %a [%016llx]): got %016llx, want %016llx\n",
                       op_names[op], double_of(a), (unsigned long long)a, double_of(b),
                       (unsigned long long)b, (unsigned long long)r,
                       (unsigned long long)expected(op, a, b));
        }
        expect(wrong == 0, "%s: %zu of %zu results differ from the host's", op_names[op],
               wrong, in.count);
    }
    probe_destroy(&c, &p);
    vkc_destroy(&c);
    expect(vkc_validation_message_count() == 0, "validation messages: %u",
           vkc_validation_message_count());
    free(in.pair);
    return unit_report();
}
