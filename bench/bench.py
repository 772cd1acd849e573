#!/usr/bin/env python3
"""bench.py - time tp2 against POV-Ray 3.7 on the same scenes.

For each scene and each image size, both programs render the scene R times
(default 5), alternately (tp2 first in even rounds, POV-Ray first in odd
ones, so that neither always runs on a machine the other just warmed), after
one untimed warm-up run each (--warmup; it fills the OS file cache and
tp2's on-disk pipeline cache, as for any user's second run). Each run is
timed as whole-process wall time: time.perf_counter() around
subprocess.run(), so process start, Vulkan start-up, parsing, rendering and
writing the PPM all count, for both programs. The median of the R runs is
reported per program, and the ratio tp2 / POV-Ray of the medians. The
median CPU time (user + system, from RUSAGE_CHILDREN) is reported beside
it: POV-Ray 3.7's Unix front end sleeps while it polls its render threads,
so about 0.6 s of its wall time at any size is idle (see the first row, a
built-in 3-object scene at 16x12: the fixed cost of each program).

POV-Ray gets the scene converted by bench/scene2pov.py (conversion is not
timed: it stands for the scene author writing POV-Ray SDL) and runs as
    povray +I<scene>.pov +O<out>.ppm +FP +W<W> +H<H> -A -D +WT<threads>
           File_Gamma=1.0 -GA
(-A: no anti-aliasing, as tp2 traces one ray per pixel; -D: no display;
+WT: worker threads, default 2 = this machine's cores; -GA: no console text
streams; File_Gamma=1.0: linear output like tp2). tp2 runs as
    tp2 <scene> <out>.ppm <W> <H>
with VK_ICD_FILENAMES set to the lavapipe ICD when that file exists and the
variable is not already set (--no-icd leaves the environment alone), and
XDG_RUNTIME_DIR=/tmp when unset.

Targets checked (the project's): ratio <= 0.5 at 1920x1080, <= 1.0 at
400x300.

Outputs: a plain-text table on stdout (for docs/performance.md) with the
machine, date and exact command, and a CSV (default docs/bench.csv;
--csv). --compare also compares the two programs' last images (same picture
check, with build/tests/tp2-imgcmp: mean error in levels, % of pixels off
by more than 8).

--phases: tp2 runs with --stats, and a second table gives the median of
each phase tp2 reports (parse, device, bvh, upload, pipeline, render,
readback, write; see tp2 --help, --stats) beside its wall time, so a
reader sees where the time goes at each size. --stats also counts rays
on the device, which costs some render time: compare wall times of runs
made the same way.

--smoke: renders a small built-in scene once with each program at 64x48 and
checks that both exit 0 and write a 64x48 PPM (for CI; no timings asserted,
no CSV written). Exit status 0 if both do, 1 if not, 77 (CTest's usual
SKIP_RETURN_CODE) if povray is not installed.

python3 standard library only.
"""

import argparse
import csv
import datetime
import glob
import os
import platform
import resource
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True   # no __pycache__ in the source tree
HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import lavapipe  # noqa: E402
import scene2pov  # noqa: E402

LVP_ICD = lavapipe.ICD
DEFAULT_CORPUS = os.environ.get('TP2_CORPUS', os.path.join(REPO, '..', 'shared', 'corpus'))
TARGETS = {(1920, 1080): 0.5, (400, 300): 1.0}

SMOKE_SCENE = """# bench.py --smoke: two spheres on a checker plane
0 1 6
0 0 0
0 1 0
45
2
0 0 0  0.2 0.2 0.2  1 0 0
4 6 6  1 1 1  1 0 0
2
solid 0.9 0.2 0.2
checker 1 1 1  0.1 0.1 0.1  1
2
0.2 0.7 0.3 40 0 0 0
0.1 0.6 0.2 20 0.3 0 0
3
0 0 sphere -0.8 0 0 0.7
0 1 sphere 0.9 0.2 -1 0.9
1 1 plane 0 1 0 0.75
"""


def fmt_s(x):
    if x is None:
        return '-'
    return '%.3f' % x


def machine_info(tp2, env):
    info = {}
    try:
        info['nproc'] = len(os.sched_getaffinity(0))
    except AttributeError:
        info['nproc'] = os.cpu_count()
    model = platform.processor() or '?'
    try:
        with open('/proc/cpuinfo') as fh:
            for line in fh:
                if line.startswith('model name'):
                    model = line.split(':', 1)[1].strip()
                    break
    except OSError:
        pass
    info['cpu'] = model
    try:
        with open('/proc/meminfo') as fh:
            kb = int(fh.readline().split()[1])
        info['mem'] = '%.1f GiB' % (kb / 1048576.0)
    except (OSError, ValueError, IndexError):
        info['mem'] = '?'
    dev = '?'
    try:
        r = subprocess.run([tp2, '--list-devices'], env=env,
                           capture_output=True, text=True, timeout=60)
        lines = [ln.strip() for ln in r.stdout.splitlines() if ln.strip()]
        default = [ln for ln in lines if '[default]' in ln]
        dev = (default or lines or ['? (exit %d)' % r.returncode])[0]
    except (OSError, subprocess.TimeoutExpired) as e:
        dev = '? (%s)' % e
    info['device'] = dev
    try:
        r = subprocess.run(['povray', '--version'], capture_output=True,
                           text=True, timeout=60)
        txt = r.stdout + r.stderr
        ver = [ln for ln in txt.splitlines() if ln.startswith('POV-Ray')]
        info['povray'] = ver[0].strip() if ver else '?'
    except (OSError, subprocess.TimeoutExpired):
        info['povray'] = 'not found'
    try:
        rev = subprocess.run(['git', '-C', REPO, 'rev-parse', '--short',
                              'HEAD'], capture_output=True, text=True,
                             timeout=30).stdout.strip()
        dirty = subprocess.run(['git', '-C', REPO, 'status', '--porcelain',
                                '--untracked-files=no'], capture_output=True,
                               text=True, timeout=30).stdout.strip()
        info['git'] = (rev or '?') + (' + uncommitted changes' if dirty
                                      else '')
    except (OSError, subprocess.TimeoutExpired):
        info['git'] = '?'
    info['kernel'] = platform.release()
    try:
        info['tp2_mtime'] = datetime.datetime.fromtimestamp(
            os.path.getmtime(tp2), datetime.timezone.utc).strftime(
            '%Y-%m-%d %H:%M UTC')
    except OSError:
        info['tp2_mtime'] = '?'
    return info


def loadavg():
    try:
        return ' '.join(open('/proc/loadavg').read().split()[:3])
    except OSError:
        return '?'


def tp2_env(use_icd):
    env = dict(os.environ)
    if use_icd and 'VK_ICD_FILENAMES' not in env and os.path.exists(LVP_ICD):
        env['VK_ICD_FILENAMES'] = LVP_ICD
    env.setdefault('XDG_RUNTIME_DIR', '/tmp')
    return env


def has_texmap(tp2, path):
    try:
        sc = scene2pov.load_scene(tp2, path)
    except (OSError, scene2pov.SceneError):
        return False
    return any(p['type'] == 'texmap' for p in sc['pigments'])


def default_scenes(tp2, corpus):
    found = []
    if corpus and os.path.isdir(corpus):
        found += sorted(glob.glob(os.path.join(corpus, '*.txt')))
        found += sorted(glob.glob(os.path.join(corpus, '*.in')))
    found += sorted(glob.glob(os.path.join(REPO, 'scenes', '*.txt')))
    found += sorted(glob.glob(os.path.join(REPO, 'bench', 'scenes', '*.txt')))
    return [p for p in found if not has_texmap(tp2, p)]


def convert(tp2, scene, w, h, pov_path, bailout):
    sc = scene2pov.load_scene(tp2, scene)
    sdl, opts = scene2pov.convert(sc, w, h, os.path.basename(scene),
                                  os.path.dirname(pov_path), bailout)
    with open(pov_path, 'w') as fh:
        fh.write(sdl)
    return opts


def _children_cpu():
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def run_timed(cmd, env, cwd, timeout):
    """(wall seconds, status, tail of output, CPU seconds). status: 'ok',
    'exit N', 'timeout', or 'error: ...'. CPU = user + system time of the
    process and its waited-for children (runs are sequential, so the
    RUSAGE_CHILDREN delta is this run's)."""
    c0 = _children_cpu()
    t0 = time.perf_counter()
    try:
        r = subprocess.run(cmd, env=env, cwd=cwd, stdin=subprocess.DEVNULL,
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        return time.perf_counter() - t0, 'timeout', '', None
    except OSError as e:
        return None, 'error: %s' % e, '', None
    dt = time.perf_counter() - t0
    cpu = _children_cpu() - c0
    tail = r.stdout.decode('latin-1', 'replace')[-2000:]
    return (dt, ('ok' if r.returncode == 0 else 'exit %d' % r.returncode),
            tail, cpu)


PHASES = ['parse', 'device', 'bvh', 'upload', 'pipeline', 'render', 'readback',
          'write']


def tp2_phases(text):
    """{phase: seconds} from tp2 --stats output (lines 'tp2: NAME  X s')."""
    out = {}
    for line in text.splitlines():
        w = line.split()
        if len(w) >= 4 and w[0] == 'tp2:' and w[1] in PHASES and w[3] == 's':
            try:
                out[w[1]] = float(w[2])
            except ValueError:
                pass
    return out


def phase_medians(samples):
    """Median per phase over a list of tp2_phases() dicts."""
    return {p: statistics.median(d[p] for d in samples if p in d)
            for p in PHASES if any(p in d for d in samples)}


def pov_cmd(povray, pov, out, w, h, threads, extra):
    return [povray, '+I' + pov, '+O' + out, '+FP', '+W%d' % w, '+H%d' % h,
            '-A', '-D', '+WT%d' % threads, 'File_Gamma=1.0', '-GA'] + extra


def check_ppm(path, w, h):
    try:
        with open(path, 'rb') as f:
            head = f.read(256)
        # Header fields, skipping '#' comments (POV-Ray writes one).
        words = b' '.join(line.split(b'#')[0] for line in head.split(b'\n')).split()
        magic, pw, ph = words[0], int(words[1]), int(words[2])
    except (OSError, ValueError, IndexError) as e:
        return 'bad output (%s)' % e
    if magic != b'P6':
        return 'bad output (not a P6 file)'
    if (pw, ph) != (w, h):
        return 'output is %dx%d, not %dx%d' % (pw, ph, w, h)
    return None


def smoke(args, env):
    work = tempfile.mkdtemp(prefix='tp2-smoke-')
    try:
        scene = args.scenes[0] if args.scenes else os.path.join(work,
                                                                 'smoke.txt')
        if not args.scenes:
            with open(scene, 'w') as fh:
                fh.write(SMOKE_SCENE)
        w, h = 64, 48
        ok = True
        t_out = os.path.join(work, 'tp2.ppm')
        dt, st, tail, _ = run_timed([args.tp2, scene, t_out, str(w),
                                     str(h)], env, work, args.timeout)
        bad = st if st != 'ok' else check_ppm(t_out, w, h)
        print('smoke: tp2 %s: %s' % (os.path.basename(scene), bad or 'ok'))
        if bad:
            ok = False
            sys.stdout.write(tail)
        pov = os.path.join(work, 'scene.pov')
        try:
            extra = convert(args.tp2, scene, w, h, pov, args.bailout)
        except (OSError, scene2pov.SceneError) as e:
            print('smoke: scene2pov failed: %s' % e)
            return 1
        p_out = os.path.join(work, 'pov.ppm')
        dt, st, tail, _ = run_timed(pov_cmd(args.povray, pov, p_out, w, h,
                                            args.threads, extra),
                                    None, work, args.timeout)
        bad = st if st != 'ok' else check_ppm(p_out, w, h)
        print('smoke: povray %s: %s' % (os.path.basename(scene), bad or 'ok'))
        if bad:
            ok = False
            sys.stdout.write(tail)
        return 0 if ok else 1
    finally:
        shutil.rmtree(work, ignore_errors=True)


def bench_one(args, env, scene, w, h, work):
    base = os.path.splitext(os.path.basename(scene))[0]
    tag = '%s-%dx%d' % (base, w, h)
    pov = os.path.join(work, tag + '.pov')
    row = {'scene': os.path.basename(scene), 'width': w, 'height': h,
           'runs': args.runs, 'tp2_status': 'ok', 'povray_status': 'ok'}
    try:
        extra = convert(args.tp2, scene, w, h, pov, args.bailout)
    except (OSError, scene2pov.SceneError, ValueError) as e:
        row['povray_status'] = 'scene2pov: %s' % e
        extra = None
    t_out = os.path.join(work, tag + '.tp2.ppm')
    p_out = os.path.join(work, tag + '.pov.ppm')
    stats = ['--stats', '--quiet'] if args.phases else []
    cmds = {'tp2': ([args.tp2] + stats + ['--bailout', repr(args.bailout), scene, t_out,
                                          str(w), str(h)], env, t_out)}
    if extra is not None:
        cmds['povray'] = (pov_cmd(args.povray, pov, p_out, w, h, args.threads,
                                  extra), None, p_out)
    times = {'tp2': [], 'povray': []}
    cpus = {'tp2': [], 'povray': []}
    phases = []
    dead = {k: (k not in cmds) for k in ('tp2', 'povray')}

    def one(prog, timed):
        cmd, e, out = cmds[prog]
        dt, st, tail, cpu = run_timed(cmd, e, work, args.timeout)
        if st == 'ok':
            bad = check_ppm(out, w, h)
            if bad:
                st = bad
        if st != 'ok':
            dead[prog] = True
            row[prog + '_status'] = ('timeout (> %gs)' % args.timeout
                                     if st == 'timeout' else st)
            if tail and args.verbose:
                sys.stderr.write('--- %s %s output:\n%s\n' % (prog, tag, tail))
            return
        if timed:
            times[prog].append(dt)
            cpus[prog].append(cpu)
            if prog == 'tp2' and args.phases:
                phases.append(tp2_phases(tail))
        if args.verbose:
            print('  %-6s %s %s %.3fs' % (prog, tag, 'run' if timed else
                                          'warm-up', dt), file=sys.stderr)

    for _ in range(args.warmup):
        for prog in ('tp2', 'povray'):
            if not dead[prog]:
                one(prog, False)
    for r in range(args.runs):
        order = ('tp2', 'povray') if r % 2 == 0 else ('povray', 'tp2')
        for prog in order:
            if not dead[prog]:
                one(prog, True)
    for prog in ('tp2', 'povray'):
        ts = times[prog]
        row[prog + '_median_s'] = statistics.median(ts) if ts else None
        row[prog + '_min_s'] = min(ts) if ts else None
        row[prog + '_max_s'] = max(ts) if ts else None
        row[prog + '_times_s'] = ' '.join('%.4f' % t for t in ts)
        row[prog + '_cpu_median_s'] = (statistics.median(cpus[prog])
                                       if cpus[prog] else None)
        if ts and len(ts) < args.runs and row[prog + '_status'] == 'ok':
            row[prog + '_status'] = 'only %d runs' % len(ts)
    row['phases'] = phase_medians(phases) if phases else {}
    tm, pm = row['tp2_median_s'], row['povray_median_s']
    row['ratio'] = tm / pm if (tm is not None and pm) else None
    target = TARGETS.get((w, h))
    row['target'] = target
    row['met'] = ('' if target is None or row['ratio'] is None else
                  ('yes' if row['ratio'] <= target else 'no'))
    if args.compare and times['tp2'] and times['povray']:
        d = imgcmp(args.imgcmp, t_out, p_out)
        if d:
            row['img_mean_abs_diff'] = d['mae']
            row['img_pct_px_gt8'] = round(100 * d['bad8'] / d['pixels'], 3)
        else:
            row['img_mean_abs_diff'] = 'error'
    return row


def imgcmp(tool, a, b):
    """tp2-imgcmp's figures for images a and b as a dict, or None."""
    r = subprocess.run([tool, a, b], capture_output=True, text=True)
    if r.returncode != 0:
        return None
    return {k: float(v) for k, v in (f.split('=') for f in r.stdout.split())}


CSV_FIELDS = ['scene', 'width', 'height', 'runs', 'tp2_median_s',
              'povray_median_s', 'ratio', 'target', 'met', 'tp2_min_s',
              'tp2_max_s', 'povray_min_s', 'povray_max_s', 'tp2_status',
              'povray_status', 'tp2_cpu_median_s', 'povray_cpu_median_s',
              'img_mean_abs_diff', 'img_pct_px_gt8'] + [
              'tp2_%s_s' % p for p in PHASES] + ['tp2_times_s', 'povray_times_s']


def write_csv(path, rows, header_lines):
    d = os.path.dirname(os.path.abspath(path))
    os.makedirs(d, exist_ok=True)
    tmp = path + '.tmp'
    with open(tmp, 'w', newline='') as fh:
        for ln in header_lines:
            fh.write('# %s\n' % ln)
        wr = csv.DictWriter(fh, fieldnames=CSV_FIELDS, extrasaction='ignore')
        wr.writeheader()
        for r in rows:
            out = {}
            for k in CSV_FIELDS:
                v = r.get(k)
                if k.startswith('tp2_') and k[4:-2] in PHASES:
                    v = r.get('phases', {}).get(k[4:-2])
                if isinstance(v, float):
                    v = '%.4f' % v
                out[k] = '' if v is None else v
            wr.writerow(out)
    os.replace(tmp, path)


def table(rows, compare):
    hdr = ['scene', 'size', 'tp2 median s', 'povray median s', 'tp2/povray',
           'target', 'tp2 CPU s', 'povray CPU s']
    if compare:
        hdr.append('img diff')
    lines = []
    data = []
    for r in rows:
        tm = fmt_s(r.get('tp2_median_s'))
        pm = fmt_s(r.get('povray_median_s'))
        if r['tp2_status'] != 'ok':
            tm = r['tp2_status']
        if r['povray_status'] != 'ok':
            pm = r['povray_status']
        ratio = '-' if r.get('ratio') is None else '%.3f' % r['ratio']
        tgt = ('' if r.get('target') is None else
               '<= %.1f %s' % (r['target'], r['met'] or '?'))
        cells = [r['scene'], '%dx%d' % (r['width'], r['height']), tm, pm,
                 ratio, tgt, fmt_s(r.get('tp2_cpu_median_s')),
                 fmt_s(r.get('povray_cpu_median_s'))]
        if compare:
            dd = r.get('img_mean_abs_diff')
            cells.append('-' if dd is None else
                         (('%.3f/255' % dd) if isinstance(dd, float) else dd))
        data.append(cells)
    widths = [max(len(str(c)) for c in col) for col in zip(hdr, *data)]
    right = {2, 3, 4, 6, 7}

    def fmt(cells):
        return '  '.join((str(c).rjust(wd) if i in right else
                          str(c).ljust(wd))
                         for i, (c, wd) in enumerate(zip(cells, widths))
                         ).rstrip()
    lines.append(fmt(hdr))
    lines.append('  '.join('-' * wd for wd in widths))
    for cells in data:
        lines.append(fmt(cells))
    return lines


def phase_table(rows):
    """Where tp2's wall time goes: median seconds per phase."""
    hdr = ['scene', 'size', 'wall'] + PHASES
    data = [[r['scene'], '%dx%d' % (r['width'], r['height']),
             fmt_s(r.get('tp2_median_s'))] +
            [fmt_s(r['phases'].get(p)) for p in PHASES]
            for r in rows if r.get('phases')]
    widths = [max(len(str(c)) for c in col) for col in zip(hdr, *data)]

    def fmt(cells):
        return '  '.join(str(c).ljust(wd) if i < 2 else str(c).rjust(wd)
                         for i, (c, wd) in enumerate(zip(cells, widths))).rstrip()
    return [fmt(hdr), '  '.join('-' * wd for wd in widths)] + [fmt(c) for c in data]


def main(argv=None):
    ap = argparse.ArgumentParser(
        description='Benchmark tp2 against POV-Ray 3.7 (whole-process wall '
                    'time, median of R alternating runs).')
    ap.add_argument('--runs', type=int, default=5,
                    help='timed runs per program, scene and size (default 5)')
    ap.add_argument('--warmup', type=int, default=1,
                    help='untimed runs of each program first (default 1)')
    ap.add_argument('--sizes', default='400x300,1920x1080',
                    help='comma-separated WxH list (default 400x300,1920x1080)')
    ap.add_argument('--scenes', nargs='+', metavar='FILE',
                    help='scene files (default: the corpus\'s, scenes/ and bench/scenes/ '
                         'scenes without texmap)')
    ap.add_argument('--corpus', default=DEFAULT_CORPUS,
                    help='folder of corpus scenes (default %(default)s, '
                         'or $TP2_CORPUS)')
    ap.add_argument('--tp2', default=os.path.join(REPO, 'build', 'tp2'),
                    help='tp2 binary (default build/tp2 in the repository)')
    ap.add_argument('--povray', default='povray', help='POV-Ray binary')
    ap.add_argument('--bailout', type=float, default=1 / 255,
                    help='least ray weight traced, the same for both programs: '
                         "tp2 --bailout and POV-Ray's adc_bailout (default 1/255, "
                         'both defaults; 0: the exact model)')
    ap.add_argument('--imgcmp', default=os.path.join(REPO, 'build', 'tests', 'tp2-imgcmp'),
                    help='tp2-imgcmp binary, for --compare')
    ap.add_argument('--threads', type=int, default=2,
                    help='POV-Ray worker threads (+WT; default 2)')
    ap.add_argument('--timeout', type=float, default=600.0,
                    help='seconds before a run is killed (default 600); a '
                         'timed-out program is not run again on that '
                         'scene and size')
    ap.add_argument('--csv', default=os.path.join(REPO, 'docs',
                                                  'bench.csv'),
                    help='CSV to write (default docs/bench.csv)')
    ap.add_argument('--no-csv', action='store_true', help='write no CSV')
    ap.add_argument('--compare', action='store_true',
                    help='compare the two programs\' images (mean abs diff)')
    ap.add_argument('--keep', metavar='DIR',
                    help='keep .pov files and images in DIR')
    ap.add_argument('--no-icd', action='store_true',
                    help='do not set VK_ICD_FILENAMES to lavapipe')
    ap.add_argument('--no-baseline', action='store_true',
                    help='skip the fixed-cost row (built-in 3-object scene '
                         'at 16x12: start-up, parse, write)')
    ap.add_argument('--phases', action='store_true',
                    help='run tp2 with --stats and print its phase times')
    ap.add_argument('--smoke', action='store_true',
                    help='one 64x48 render per program; check exit 0')
    ap.add_argument('-v', '--verbose', action='store_true',
                    help='print each run\'s time on stderr')
    args = ap.parse_args(argv)
    args.tp2 = os.path.abspath(args.tp2)
    if args.scenes:
        args.scenes = [os.path.abspath(s) for s in args.scenes]
    env = tp2_env(not args.no_icd)
    if not os.access(args.tp2, os.X_OK):
        print('bench: tp2 binary %s not found (build it, or pass --tp2)' %
              args.tp2, file=sys.stderr)
        return 2
    if shutil.which(args.povray) is None:
        print('bench: %s not found (apt-get install povray)%s' % (
            args.povray, '; smoke test skipped' if args.smoke else ''),
            file=sys.stderr)
        return 77 if args.smoke else 2
    if args.smoke:
        return smoke(args, env)
    if args.runs < 1:
        ap.error('--runs must be >= 1')
    try:
        sizes = [tuple(int(v) for v in s.lower().split('x'))
                 for s in args.sizes.split(',')]
        assert all(len(s) == 2 and s[0] > 0 and s[1] > 0 for s in sizes)
    except (ValueError, AssertionError):
        ap.error('--sizes takes WxH[,WxH...]')
    scenes = args.scenes or default_scenes(args.tp2, args.corpus)
    if not scenes:
        print('bench: no scenes found', file=sys.stderr)
        return 2

    info = machine_info(args.tp2, env)
    now = datetime.datetime.now(datetime.timezone.utc).strftime(
        '%Y-%m-%d %H:%M UTC')
    command = ' '.join(shlex.quote(a) for a in [sys.executable] + sys.argv)
    header = [
        'tp2 vs POV-Ray benchmark, %s' % now,
        'machine: %s, %s CPUs available (nproc), %s RAM, Linux %s' % (
            info['cpu'], info['nproc'], info['mem'], info['kernel']),
        'tp2 %s (built %s; repository at git %s), device: %s' % (
            args.tp2, info['tp2_mtime'], info['git'], info['device']),
        '%s, %d worker threads (+WT%d), no anti-aliasing' % (
            info['povray'], args.threads, args.threads),
        'pruning: tp2 --bailout %.6g, POV-Ray adc_bailout %.6g (0: none)' % (
            args.bailout, args.bailout),
        'time: whole-process wall time, median of %d alternating runs after '
        '%d untimed warm-up run(s) each; CPU = user+system seconds of the '
        'process (median)' % (args.runs, args.warmup),
        'command: %s' % command,
    ] + (['phases: tp2 ran with --stats --quiet (it counts rays on the device)']
         if args.phases else []) + [
        'load average (1, 5, 15 min) at start: %s' % loadavg(),
    ]
    if env.get('VK_ICD_FILENAMES') and not args.no_icd:
        header.append('tp2 environment: VK_ICD_FILENAMES=%s' %
                      env['VK_ICD_FILENAMES'])
    for ln in header:
        print(ln)
    sys.stdout.flush()

    work = args.keep or tempfile.mkdtemp(prefix='tp2-bench-')
    os.makedirs(work, exist_ok=True)
    rows = []
    try:
        if not args.no_baseline:
            tiny = os.path.join(work, 'builtin-tiny.txt')
            with open(tiny, 'w') as fh:
                fh.write(SMOKE_SCENE)
            rows.append(bench_one(args, env, tiny, 16, 12, work))
        for (w, h) in sizes:
            for scene in scenes:
                if args.verbose:
                    print('bench: %s %dx%d' % (scene, w, h), file=sys.stderr)
                rows.append(bench_one(args, env, scene, w, h, work))
    except KeyboardInterrupt:
        print('bench: interrupted; reporting what was measured',
              file=sys.stderr)
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)

    end_load = 'load average at end: %s' % loadavg()
    header.append(end_load)
    print(end_load)
    print()
    for ln in table(rows, args.compare):
        print(ln)
    if args.phases:
        print()
        print('tp2 by phase (median seconds; tp2 ran with --stats):')
        for ln in phase_table(rows):
            print(ln)
    # Summary per size: geometric mean of the ratios.
    print()
    for (w, h) in sizes:
        rs = [r['ratio'] for r in rows
              if (r['width'], r['height']) == (w, h) and r.get('ratio')]
        if rs:
            g = 1.0
            for x in rs:
                g *= x
            g **= 1.0 / len(rs)
            tgt = TARGETS.get((w, h))
            met = sum(1 for r in rows if (r['width'], r['height']) == (w, h)
                      and r.get('met') == 'yes')
            print('%dx%d: geometric mean tp2/povray %.3f over %d scenes%s' % (
                w, h, g, len(rs), '' if tgt is None else
                ('; target <= %.1f met by %d of %d' % (tgt, met, len(rs)))))
    if not args.no_csv:
        write_csv(args.csv, rows, header)
        print('\nCSV: %s' % os.path.relpath(args.csv))
    bad = [r for r in rows if r['tp2_status'] != 'ok' or
           r['povray_status'] != 'ok']
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
