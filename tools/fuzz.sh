#!/usr/bin/env bash
# tools/fuzz.sh [SECONDS] [TARGET...]: builds the libFuzzer targets of
# tests/fuzz/ with clang (build-fuzz/), assembles their seeds and runs each
# target, one after the other on one core, for SECONDS (default 60).
# TARGET: scene, obj or image (default: all three).
#
#   fuzz-out/corpus/TARGET/    the inputs the fuzzer kept (kept between runs)
#   fuzz-out/seeds/TARGET/     the seeds, rebuilt from scenes/, tests/ and
#                              ../shared/corpus/ (TP2_CORPUS_DIR) every run
#   fuzz-out/findings/TARGET/  crash-*, leak-*, timeout-*, oom-*: findings
#   fuzz-out/TARGET.log        libFuzzer's output, final stats at the end
#
# Exit status: 0 when no target found anything, 1 when one did (its inputs
# are listed; replay one with build-fuzz/tests/fuzz/fuzz_TARGET FILE, and
# once fixed copy it into tests/fuzz/regressions/TARGET/), 2 on usage.
# Environment: TP2_FUZZ_BUILD (build-fuzz), TP2_FUZZ_OUT (fuzz-out),
# TP2_CORPUS_DIR (../shared/corpus), CC (clang); TP2_FUZZ_RUNS=N and
# TP2_FUZZ_SEED=S make a run reproducible (what CI does): each target
# stops after N inputs (SECONDS stays a cap), its mutations drawn from
# seed S, starting from the seeds alone (no kept corpus), so the same
# build tries the same inputs everywhere and a run that passed here
# passes in CI.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

seconds=${1:-60}
case $seconds in
    ''|*[!0-9]*) echo "usage: tools/fuzz.sh [SECONDS] [scene|obj|image...]" >&2; exit 2 ;;
esac
[ $# -gt 0 ] && shift
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene obj image)
for t in "${targets[@]}"; do
    case $t in
        scene|obj|image) ;;
        *) echo "tools/fuzz.sh: unknown target '$t' (scene, obj, image)" >&2; exit 2 ;;
    esac
done

build=${TP2_FUZZ_BUILD:-build-fuzz}
out=${TP2_FUZZ_OUT:-fuzz-out}
corpus_dir=${TP2_CORPUS_DIR:-$root/../shared/corpus}

cmake -S . -B "$build" -DTP2_FUZZ=ON -DCMAKE_C_COMPILER="${CC:-clang}" \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j2 --target "${targets[@]/#/fuzz_}" >/dev/null

# seed DEST FILE...: copies the files that exist, named by their path so
# that equal names from different folders do not collide.
seed() {
    local dest=$1 f
    shift
    for f in "$@"; do
        [ -f "$f" ] || continue
        local name=${f#"$root"/}
        name=${name//\//_}
        cp "$f" "$dest/${name#.._}"
    done
}

shopt -s nullglob
found=0
for t in "${targets[@]}"; do
    rm -rf "$out/seeds/$t"
    mkdir -p "$out/seeds/$t" "$out/corpus/$t" "$out/findings/$t"
    case $t in
    scene)
        seed "$out/seeds/$t" scenes/*.txt bench/scenes/*.txt tests/errors/*.txt \
            tests/render/*.txt tests/stress/*.txt tests/fuzz/regressions/scene/* \
            "$corpus_dir"/*.txt "$corpus_dir"/*.in "$corpus_dir"/dialects/*.in
        max_len=16384 ;;
    obj)
        seed "$out/seeds/$t" scenes/*.obj tests/errors/*.obj tests/render/*.obj \
            tests/stress/*.obj tests/fuzz/files/*.obj tests/fuzz/regressions/obj/*
        max_len=8192 ;;
    image)
        seed "$out/seeds/$t" scenes/*.ppm tests/errors/*.ppm tests/errors/*.png \
            tests/render/*.ppm tests/fuzz/files/*.{ppm,bmp,png,tga} \
            tests/fuzz/files/textures/* tests/fuzz/regressions/image/* \
            "$corpus_dir"/*.{ppm,bmp} "$corpus_dir"/textures/* "$corpus_dir"/dialects/*.ppm
        max_len=16384 ;;
    esac
    limits=(-max_total_time="$seconds")
    if [ -n "${TP2_FUZZ_RUNS:-}" ]; then
        limits+=(-runs="$TP2_FUZZ_RUNS" -seed="${TP2_FUZZ_SEED:-1}")
        rm -rf "$out/corpus/$t"
        mkdir -p "$out/corpus/$t"
    fi
    echo "fuzz_$t: ${seconds} s${TP2_FUZZ_RUNS:+ or $TP2_FUZZ_RUNS inputs (seed ${TP2_FUZZ_SEED:-1})}," \
        "$(ls "$out/seeds/$t" | wc -l) seeds, log $out/$t.log"
    # One job on one core; stdin closed so that nothing can wait on it.
    set +e
    "$build/tests/fuzz/fuzz_$t" "${limits[@]}" -rss_limit_mb=2048 \
        -timeout=10 -max_len=$max_len -dict="tests/fuzz/$t.dict" \
        -artifact_prefix="$out/findings/$t/" -print_final_stats=1 \
        "$out/corpus/$t" "$out/seeds/$t" </dev/null >"$out/$t.log" 2>&1
    rc=$?
    set -e
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$out/$t.log" | tail -1)
    echo "fuzz_$t: exit $rc, ${execs:-?} executions, $(ls "$out/corpus/$t" | wc -l) inputs in corpus"
    findings=("$out/findings/$t"/*)
    if [ $rc -ne 0 ] || [ ${#findings[@]} -gt 0 ]; then
        found=1
        echo "fuzz_$t: FINDINGS:" "${findings[@]}"
        grep -E "^(==[0-9]+==ERROR|SUMMARY|.*runtime error)" "$out/$t.log" | head -5 || true
    fi
done
exit $found
