#version 450
// specialize_probe.comp: the shapes of control flow spirv_specialize must
// keep valid, each decided by specialization constants (test_spirv_specialize).
layout(local_size_x = 1) in;
layout(constant_id = 0) const bool A = true;
layout(constant_id = 1) const bool B = false;
layout(constant_id = 2) const int K = 3;
layout(std430, binding = 0) buffer Data { int v[]; };

int only_if_a() { return v[10] * 3; }
int only_if_not_a() { return v[11] + 7; }
int only_if_k2() { return v[12] - 1; }
int only_if_b() { return v[13] ^ 5; }

void main()
{
    // Short-circuit and, or: branches and an OpPhi.
    if (A && v[0] > 0)
        v[1] = only_if_a();
    if (!A || v[0] < -1)
        v[1] = only_if_not_a();
    // A switch on a constant.
    switch (K) {
    case 1: v[2] = 10; break;
    case 2: v[2] = only_if_k2(); break;
    default: v[2] = 30; break;
    }
    // A loop left early under A: its continue construct, of several
    // blocks (a short-circuit in the increment), may never run.
    int sum = 0;
    for (int i = 0; i < v[3]; i += (B && v[4] > 0) ? 2 : 1) {
        sum += i;
        if (A)
            break;
    }
    v[5] = sum;
    // A loop whose body calls only under B, carried values in OpPhis.
    int j = 0, acc = 1;
    while (j < v[6]) {
        if (B)
            acc += only_if_b();
        else
            acc *= 2;
        j++;
        if (A && acc > 1000)
            continue;
        acc -= 1;
    }
    v[7] = acc;
    // Nested: a selection inside a branch that K rules out.
    if (K == 2) {
        if (v[8] > 0)
            v[9] = only_if_k2();
        else
            v[9] = 4;
    }
}
