#!/usr/bin/python3
"""accuracy.py - speed against accuracy, charted.

Run with /usr/bin/python3 (the shebang): the chart needs Debian's
python3-matplotlib (apt-get install -y python3-matplotlib), which a pyenv
`python3` earlier on PATH usually lacks. matplotlib is imported only when
the chart is drawn, so --no-chart runs on the standard library alone.

For each scene (default: scenes/*.txt in the repository, then
tests/stress/far-small-sphere.txt, tests/stress/mirror-corridor.txt,
tests/stress/inside-glass.txt and tests/render/effects.txt; --scenes to
override) and each setting, auto (the default: on a CPU device such as
lavapipe double throughout, elsewhere mixed; rays fainter than 1/255
pruned), mixed (float, pixels where float may have flipped a decision
traced again in double, the same pruning), float (the same pruning,
float alone), float-exact
(--bailout 0) or double (never pruned) x samples per
pixel 1, 4, 16, 64 (--spp-list), tp2 renders the scene as
    tp2 --quiet SETTING-OPTIONS --spp N <scene> <out>.pfm W H
(--size W H, default 200 150). Each run is timed as whole-process wall
time (time.perf_counter() around subprocess.run(): process start, Vulkan
start-up, parsing, shader specialisation, rendering and writing the image
all count) and the median of R runs is reported (--runs, default 3). The
runs are interleaved: round r runs every setting of every scene once, in an
order rotated from round to round, so no setting's runs come back to back.
One untimed warm-up run per scene and setting comes first, at 16x12
(--warmup-size): lavapipe compiles the scene- and setting-specialised
shader on the first run and keeps it in its on-disk shader cache, which
makes a first run some 0.1 to 0.5 s slower than the next; the warm-up
fills that cache and the OS file cache, as for any user's second run.

Error is measured against ONE reference per scene: the double-precision
render at the highest spp of the list (64 by default), rendered once before
the timed runs. Each timed run's image is compared with it by tp2-imgcmp
(linear float PFM in, 8-bit levels out): mae (mean absolute error, in 8-bit
levels; the chart's y axis), psnr (dB), within1 (fraction of channel values
within +-1 level) and bad8 (pixels with a channel off by more than 8
levels). If the runs of one setting give different images (they should
not: tp2's sampling is seeded per pixel), the median of each measure is
kept and a warning printed.

What the error means: at spp 1 every pixel is sampled at its center; at
spp > 1 the samples are stratified over the pixel with a per-pixel random
shift (and lens, area light and other sampled effects are sampled too). So
an spp-N image differs from the spp-64 reference by sampling noise as well
as by precision. At the highest spp the float render uses the reference's
own sample positions, so its error is precision alone (the steep last
segment of each float curve); below it, the float/double difference is
the small gap between the two curves at the same spp, and the fall of each curve along the time
axis shows how error drops as more time is spent on samples. That is the
point of the chart. The double spp-64 setting renders the reference itself
again, so its error is 0 (psnr inf) if tp2 is deterministic. A mae of 0
cannot sit on a log axis: such points are drawn hollow on a dotted floor
line a decade below the smallest non-zero error, and the chart says so.

Outputs:
  stdout                        progress, then a plain-text table (for
                                docs/performance.md) headed by the exact command
  docs/accuracy-spp.csv    scene, precision, spp, median_s, runs, mae,
                                psnr, within1, bad8 (--csv)
  docs/accuracy-spp.png    mae (log) against median time (log), one
                                colour per scene, float solid, double
                                dashed, points labelled with spp (--chart;
                                --no-chart draws none; --plot-only redraws
                                it and the table from the CSV, rendering
                                nothing)

tp2 runs with VK_ICD_FILENAMES set to the lavapipe ICD when that file
exists and the variable is not already set (--no-icd leaves it alone), and
XDG_RUNTIME_DIR=/tmp when unset. Time everything on an otherwise idle
machine: on a machine with about one core of real throughput, two timed
things at once spoil both. The table's header gives the 1-minute load
average at the start and at the end as a rough check of that.
"""

import argparse
import csv
import datetime
import glob
import math
import os
import platform
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

import lavapipe  # bench/lavapipe.py, beside this script

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
LVP_ICD = lavapipe.ICD
EXTRA_SCENES = ['tests/stress/far-small-sphere.txt',
                'tests/stress/mirror-corridor.txt',
                'tests/stress/inside-glass.txt',
                'tests/render/effects.txt']
# The settings compared, as tp2 options: the default (auto: double on a
# CPU device, else mixed; rays fainter than 1/255 pruned), mixed (float
# with a double retrace, the same pruning), float alone with the same
# pruning and with none, and the double reference.
SETTINGS = {
    'auto': ['--precision', 'auto'],
    'mixed': ['--precision', 'mixed'],
    'float': ['--precision', 'float'],
    'float-exact': ['--precision', 'float', '--bailout', '0'],
    'double': ['--precision', 'double'],
}
PRECISIONS = list(SETTINGS)


def default_scenes():
    found = sorted(glob.glob(os.path.join(REPO, 'scenes', '*.txt')))
    for rel in EXTRA_SCENES:
        p = os.path.join(REPO, rel)
        if os.path.isfile(p):
            found.append(p)
    return found


def scene_name(path):
    """Short unique-enough label: parent folder/file stem."""
    parent = os.path.basename(os.path.dirname(os.path.abspath(path)))
    stem = os.path.splitext(os.path.basename(path))[0]
    return '%s/%s' % (parent, stem)


def make_env(no_icd):
    env = dict(os.environ)
    if not no_icd and 'VK_ICD_FILENAMES' not in env and \
            os.path.isfile(LVP_ICD):
        env['VK_ICD_FILENAMES'] = LVP_ICD
    env.setdefault('XDG_RUNTIME_DIR', '/tmp')
    return env


def render(args, env, scene, precision, spp, out, size=None):
    """Run tp2 once with setting `precision` (a key of SETTINGS); return its
    wall time in seconds."""
    size = size or args.size
    cmd = ([args.tp2, '--quiet'] + SETTINGS[precision] + ['--spp', str(spp),
           scene, out, str(size[0]), str(size[1])])
    t0 = time.perf_counter()
    r = subprocess.run(cmd, env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, timeout=args.timeout)
    dt = time.perf_counter() - t0
    if r.returncode != 0:
        sys.stderr.write('accuracy: %s failed (rc %d):\n%s' % (
            ' '.join(shlex.quote(c) for c in cmd), r.returncode,
            r.stderr.decode(errors='replace')))
        sys.exit(1)
    return dt


def compare(args, img, ref):
    """tp2-imgcmp img ref -> dict of floats (psnr, mae, within1, bad8...)."""
    r = subprocess.run([args.imgcmp, img, ref], stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE)
    if r.returncode not in (0, 1):
        sys.stderr.write('accuracy: tp2-imgcmp %s %s failed (rc %d): %s' % (
            img, ref, r.returncode, r.stderr.decode(errors='replace')))
        sys.exit(1)
    vals = {}
    for tok in r.stdout.decode().split():
        if '=' in tok:
            k, v = tok.split('=', 1)
            try:
                vals[k] = float(v)
            except ValueError:
                pass
    for k in ('psnr', 'mae', 'within1', 'bad8'):
        if k not in vals:
            sys.stderr.write('accuracy: unexpected tp2-imgcmp output: %r\n'
                             % r.stdout.decode())
            sys.exit(1)
    return vals


def fmt_psnr(p):
    return 'inf' if math.isinf(p) else '%.2f' % p


def draw_chart(rows, path, title):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    scenes = []
    for r in rows:
        if r['scene'] not in scenes:
            scenes.append(r['scene'])
    cmap = plt.get_cmap('tab10' if len(scenes) <= 10 else 'tab20')
    fig, ax = plt.subplots(figsize=(10, 6.2), dpi=90)
    # mae 0 (an image identical to the reference, in 8-bit terms) has no
    # place on a log axis: such points are drawn hollow on a dotted floor
    # line a decade below the smallest non-zero error.
    pos = [r['mae'] for r in rows if r['mae'] > 0]
    floor = 10 ** math.floor(math.log10(min(pos)) - 1) if pos else 1e-3
    any_zero = False
    handles = []
    for i, sc in enumerate(scenes):
        c = cmap(i % cmap.N)
        handles.append(Line2D([], [], color=c, linewidth=2, label=sc))
        for prec, ls, mk in (('auto', '-.', 'D'), ('mixed', (0, (5, 1)), 'v'),
                             ('float', '-', 'o'),
                             ('float-exact', ':', '^'), ('double', '--', 's')):
            pts = sorted((r for r in rows if r['scene'] == sc and
                          r['precision'] == prec), key=lambda r: r['spp'])
            if not pts:
                continue
            xs = [r['median_s'] for r in pts]
            ys = [r['mae'] if r['mae'] > 0 else floor for r in pts]
            ax.plot(xs, ys, linestyle=ls, marker=mk, color=c,
                    markersize=4, linewidth=1.2)
            zx = [x for x, r in zip(xs, pts) if not r['mae'] > 0]
            if zx:
                any_zero = True
                ax.plot(zx, [floor] * len(zx), linestyle='none', marker=mk,
                        markersize=7, markerfacecolor='white', color=c)
            for x, y, r in zip(xs, ys, pts):
                ax.annotate(str(r['spp']), (x, y),
                            textcoords='offset points',
                            xytext=(3, 3) if prec == 'float' else (3, -8),
                            fontsize=6, color=c)
    if any_zero:
        ax.axhline(floor, linestyle=':', color='0.5', linewidth=0.8)
    ax.set_xscale('log')
    ax.set_yscale('log')
    ax.set_xlabel('wall time per run, median (s, log scale)')
    ax.set_ylabel('mean absolute error vs reference (8-bit levels, log)')
    ax.set_title(title, fontsize=10)
    ax.grid(True, which='both', linewidth=0.4, alpha=0.5)
    handles += [Line2D([], [], color='0.2', linestyle='-.', marker='D',
                       markersize=4, label='auto (default; on a CPU double, bailout 1/255)'),
                Line2D([], [], color='0.2', linestyle=(0, (5, 1)), marker='v',
                       markersize=4, label='mixed (float + double retrace, bailout 1/255)'),
                Line2D([], [], color='0.2', linestyle='-', marker='o',
                       markersize=4, label='float (bailout 1/255)'),
                Line2D([], [], color='0.2', linestyle=':', marker='^',
                       markersize=4, label='float, --bailout 0'),
                Line2D([], [], color='0.2', linestyle='--', marker='s',
                       markersize=4, label='double (no pruning)')]
    if any_zero:
        handles.append(Line2D([], [], color='0.2', linestyle='none',
                              marker='s', markersize=6,
                              markerfacecolor='white',
                              label='mae 0 (drawn at %g)' % floor))
    ax.legend(handles=handles, fontsize=7, loc='upper left',
              bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    note = ('Point labels: samples per pixel. Reference: the double render '
            'at the highest spp, per scene. At that spp the sample '
            'positions\nmatch the reference, so only precision differs '
            '(float vs double); at lower spp the error is mostly sampling '
            'noise, falling as time is spent on samples.')
    fig.text(0.01, 0.01, note, fontsize=7, va='bottom', ha='left',
             color='0.3')
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig.savefig(path)
    plt.close(fig)
    try:  # a palette PNG is a third of the size and looks the same
        from PIL import Image
        im = Image.open(path)
        im.convert('RGB').quantize(colors=128).save(path, optimize=True)
    except Exception:
        pass


def print_table(rows):
    wname = max([len('scene')] + [len(r['scene']) for r in rows])
    hdr = '%-*s  %-6s %4s %8s %9s %7s %8s %6s' % (
        wname, 'scene', 'prec', 'spp', 'time_s', 'mae', 'psnr', 'within1',
        'bad8')
    print(hdr)
    print('-' * len(hdr))
    for r in rows:
        print('%-*s  %-6s %4d %8.3f %9.6f %7s %8.6f %6d' % (
            wname, r['scene'], r['precision'], r['spp'], r['median_s'],
            r['mae'], fmt_psnr(r['psnr']), r['within1'], r['bad8']))


def read_csv(path):
    rows = []
    with open(path, newline='') as fh:
        for d in csv.DictReader(fh):
            rows.append({'scene': d['scene'], 'precision': d['precision'],
                         'spp': int(d['spp']),
                         'median_s': float(d['median_s']),
                         'runs': int(d['runs']), 'mae': float(d['mae']),
                         'psnr': float(d['psnr']),
                         'within1': float(d['within1']),
                         'bad8': float(d['bad8'])})
    return rows


def shown_path(path):
    """Path relative to the repository when inside it, else as given."""
    rel = os.path.relpath(os.path.abspath(path), REPO)
    return path if rel.startswith('..') else rel


def chart_title(size, runs):
    return 'tp2 speed vs accuracy, %s, median of %s runs (%s, %s)' % (
        size, runs, platform.node(), datetime.date.today().isoformat())


def main():
    ap = argparse.ArgumentParser(
        description='tp2 speed against accuracy: float vs double x spp, '
                    'error against a double reference at the highest spp.')
    ap.add_argument('--scenes', nargs='+', metavar='FILE',
                    help='scene files (default: scenes/*.txt and four '
                         'stress/render scenes)')
    ap.add_argument('--spp-list', default='1,4,16,64',
                    help='samples per pixel, comma separated; the highest '
                         'is the reference (default 1,4,16,64)')
    ap.add_argument('--runs', type=int, default=3,
                    help='timed runs per setting (default 3; median kept)')
    ap.add_argument('--size', nargs=2, type=int, default=[200, 150],
                    metavar=('W', 'H'), help='image size (default 200 150)')
    ap.add_argument('--warmup-size', nargs=2, type=int, default=[16, 12],
                    metavar=('W', 'H'),
                    help='size of the untimed warm-up run of each setting '
                         '(default 16 12)')
    ap.add_argument('--tp2', default=os.path.join(REPO, 'build', 'tp2'),
                    help='tp2 binary (default build/tp2 in the repository)')
    ap.add_argument('--imgcmp',
                    help='tp2-imgcmp binary (default tests/tp2-imgcmp '
                         'beside the tp2 binary)')
    ap.add_argument('--csv', default=os.path.join(REPO, 'docs',
                                                  'accuracy-spp.csv'),
                    help='CSV output (default docs/accuracy-spp.csv)')
    ap.add_argument('--chart', default=os.path.join(REPO, 'docs',
                                                    'accuracy-spp.png'),
                    help='PNG chart (default docs/accuracy-spp.png)')
    ap.add_argument('--no-csv', action='store_true', help='write no CSV')
    ap.add_argument('--plot-only', action='store_true',
                    help='render nothing: redraw the chart and print the '
                         'table from an existing --csv (give --size if it '
                         'was not the default; the title says so)')
    ap.add_argument('--no-chart', action='store_true',
                    help='draw no chart (no matplotlib needed)')
    ap.add_argument('--timeout', type=float, default=600.0,
                    help='seconds before one run is abandoned (default 600)')
    ap.add_argument('--no-icd', action='store_true',
                    help='leave VK_ICD_FILENAMES alone')
    args = ap.parse_args()

    t_start = time.perf_counter()
    load_start = os.getloadavg()[0]
    command = ' '.join(shlex.quote(a) for a in
                       [os.path.relpath(sys.argv[0], os.getcwd())
                        if os.path.isabs(sys.argv[0]) else sys.argv[0]]
                       + sys.argv[1:])
    if args.plot_only:
        rows = read_csv(args.csv)
        if not rows:
            sys.stderr.write('accuracy: %s has no rows\n' % args.csv)
            return 1
        size = '%dx%d' % tuple(args.size)
        runs = sorted({r['runs'] for r in rows})
        if not args.no_chart:
            draw_chart(rows, args.chart,
                       chart_title(size, '/'.join(map(str, runs))))
        print('$ %s' % command)
        print('tp2 speed vs accuracy (from %s): %s; median wall time of %s '
              'runs; error vs double at the highest spp'
              % (shown_path(args.csv), size, '/'.join(map(str, runs))))
        print('mae: mean |error| in 8-bit levels; within1: share of channel '
              'values within +-1; bad8: pixels off by > 8')
        print_table(rows)
        if not args.no_chart:
            print('wrote %s' % shown_path(args.chart))
        return 0
    try:
        spps = sorted({int(s) for s in args.spp_list.split(',') if s.strip()})
    except ValueError:
        ap.error('--spp-list: comma-separated integers expected')
    if not spps or spps[0] < 1:
        ap.error('--spp-list: positive integers expected')
    if args.runs < 1:
        ap.error('--runs must be at least 1')
    if args.imgcmp is None:
        args.imgcmp = os.path.join(os.path.dirname(os.path.abspath(args.tp2)),
                                   'tests', 'tp2-imgcmp')
    for what, p in (('tp2', args.tp2), ('tp2-imgcmp', args.imgcmp)):
        if not os.access(p, os.X_OK):
            sys.stderr.write('accuracy: %s binary %s not found (build it, or '
                             'pass --%s)\n' % (what, p,
                                               'tp2' if what == 'tp2'
                                               else 'imgcmp'))
            return 1
    scenes = args.scenes or default_scenes()
    for s in scenes:
        if not os.path.isfile(s):
            sys.stderr.write('accuracy: scene %s not found\n' % s)
            return 1
    if not scenes:
        sys.stderr.write('accuracy: no scenes\n')
        return 1
    names = [scene_name(s) for s in scenes]
    env = make_env(args.no_icd)
    ref_spp = spps[-1]
    settings = [(p, n) for p in PRECISIONS for n in spps]

    tmp = tempfile.mkdtemp(prefix='tp2-accuracy-')
    # 1. warm-ups and references
    refs = {}
    warm = os.path.join(tmp, 'warm.pfm')
    for si, (scene, name) in enumerate(zip(scenes, names)):
        for (p, n) in settings:
            render(args, env, scene, p, n, warm,
                   size=args.warmup_size)
        ref = os.path.join(tmp, 'ref%d.pfm' % si)
        dt = render(args, env, scene, 'double', ref_spp, ref)
        refs[si] = ref
        print('[ref] %-28s double spp %d: %.2f s' % (name, ref_spp, dt),
              flush=True)

    # 2. timed runs, interleaved: every round runs each (scene, setting)
    # once, in an order rotated by one from the previous round.
    jobs = [(si, p, n) for si in range(len(scenes)) for (p, n) in settings]
    times = {j: [] for j in jobs}
    errs = {j: [] for j in jobs}
    total = len(jobs) * args.runs
    done = 0
    for rnd in range(args.runs):
        k = rnd % len(jobs)
        order = jobs[k:] + jobs[:k]
        for (si, p, n) in order:
            out = os.path.join(tmp, 'img%d-%s-%d.pfm' % (si, p, n))
            dt = render(args, env, scenes[si], p, n, out)
            times[(si, p, n)].append(dt)
            errs[(si, p, n)].append(compare(args, out, refs[si]))
            done += 1
            print('[%3d/%d] round %d %-28s %-6s spp %-3d %7.3f s  mae %.6f'
                  % (done, total, rnd + 1, names[si], p, n, dt,
                     errs[(si, p, n)][-1]['mae']), flush=True)

    # 3. summarise
    rows = []
    for (si, p, n) in jobs:
        e = errs[(si, p, n)]
        maes = [x['mae'] for x in e]
        if max(maes) != min(maes):
            print('accuracy: warning: %s %s spp %d: runs differ '
                  '(mae %s); medians kept' % (names[si], p, n,
                                              ' '.join('%.4f' % m
                                                       for m in maes)))
        rows.append({
            'scene': names[si], 'precision': p, 'spp': n,
            'median_s': statistics.median(times[(si, p, n)]),
            'runs': len(times[(si, p, n)]),
            'mae': statistics.median(maes),
            'psnr': statistics.median([x['psnr'] for x in e]),
            'within1': statistics.median([x['within1'] for x in e]),
            'bad8': statistics.median([x['bad8'] for x in e]),
        })
    for f in glob.glob(os.path.join(tmp, '*.pfm')):
        os.remove(f)
    os.rmdir(tmp)

    if not args.no_csv:
        os.makedirs(os.path.dirname(os.path.abspath(args.csv)), exist_ok=True)
        with open(args.csv, 'w', newline='') as fh:
            w = csv.writer(fh)
            w.writerow(['scene', 'precision', 'spp', 'median_s', 'runs',
                        'mae', 'psnr', 'within1', 'bad8'])
            for r in rows:
                w.writerow([r['scene'], r['precision'], r['spp'],
                            '%.4f' % r['median_s'], r['runs'],
                            '%.6f' % r['mae'], fmt_psnr(r['psnr']),
                            '%.6f' % r['within1'], '%d' % r['bad8']])

    size = '%dx%d' % tuple(args.size)
    if not args.no_chart:
        draw_chart(rows, args.chart, chart_title(size, args.runs))

    elapsed = time.perf_counter() - t_start
    load_end = os.getloadavg()[0]
    print()
    print('$ %s' % command)
    print('tp2 speed vs accuracy: %s, %s, %s; median wall time of %d runs; '
          'error vs double spp %d' % (size, platform.node(),
                                      datetime.date.today().isoformat(),
                                      args.runs, ref_spp))
    print('1-min load average %.2f at start, %.2f at end (this script '
          'adds about 1; more means something else ran too)'
          % (load_start, load_end))
    print('mae: mean |error| in 8-bit levels; within1: share of channel '
          'values within +-1; bad8: pixels off by > 8')
    print_table(rows)
    outs = [shown_path(path) for skip, path in
            ((args.no_csv, args.csv), (args.no_chart, args.chart))
            if not skip]
    print('total %.0f s%s' % (elapsed, ('; wrote ' + ', '.join(outs))
                              if outs else ''))
    return 0


if __name__ == '__main__':
    sys.exit(main())
