#!/usr/bin/python3
"""settings.py - which setting, and what does it cost? One run, one chart.

Run with /usr/bin/python3 (Debian's, with python3-matplotlib for the
chart; --no-chart runs on the standard library alone).

Six settings: --precision float, mixed and auto (on a CPU device such as
lavapipe auto is double; on a GPU it is mixed), each with the default
pruning (--bailout 1/255) and without it (--bailout 0). Double without
pruning is the exact image of SPEC 4, the reference.

1. Time. On the bench scenes (bench.py's: the corpus, scenes/ and
   bench/scenes/, minus those with a texmap pigment) at --time-size
   (default 1920x1080): one untimed warm-up per scene and setting at 200x150
   (fills the pipeline caches), then --runs timed runs (default 1) of each
   setting, the order rotated from scene to scene. Whole-process wall time.
   Each setting's time is divided by float's on the same scene; the chart
   gives the geometric mean of those ratios and their min and max.
2. Accuracy. On scenes/*.txt, tests/stress/*.txt and bench/scenes/
   spheres.txt at --acc-size (default 400x300), the scene's own samples:
   each setting's PFM against the exact one (double --bailout 0, the same
   samples, so only precision and pruning vary), by tp2-imgcmp. A scene
   meets the accuracy bar (docs/accuracy.md, tests/check_accuracy.py) when at
   least 99.95% of channel values are within +-1 level and at most 10
   pixels are off by more than 8 levels.
3. Samples per pixel. The default setting at --spp-list (default 1,4,16)
   on scenes/*.txt minus showpiece at --acc-size, against the exact image
   at 64 spp: time relative to 1 spp (geometric mean) and the median mae.

Outputs: docs/settings.csv (every measurement, headed by build, date,
machine and device) and docs/settings.png (--csv, --chart); --plot-only
redraws the chart from the CSV. Time it on an otherwise idle machine.

    /usr/bin/python3 bench/settings.py [--tp2 build/tp2] [--runs 1]
"""

import argparse
import csv
import datetime
import glob
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import bench  # noqa: E402  (its scene list and machine description)
import lavapipe  # noqa: E402

SETTINGS = [  # (label, options)
    ('float', ['--precision', 'float']),
    ('float, no pruning', ['--precision', 'float', '--bailout', '0']),
    ('mixed', ['--precision', 'mixed']),
    ('mixed, no pruning', ['--precision', 'mixed', '--bailout', '0']),
    ('auto', []),
    ('double, no pruning', ['--precision', 'double', '--bailout', '0']),
]
DEFAULT = 'auto'
EXACT = ['--precision', 'double', '--bailout', '0']
MIN_WITHIN1 = 0.9995
MAX_BAD8 = 10
FIELDS = ['part', 'scene', 'setting', 'spp', 'size', 'wall_s', 'within1',
          'bad8', 'mae']


def make_env():
    env = dict(os.environ)
    if 'VK_ICD_FILENAMES' not in env and os.path.isfile(lavapipe.ICD):
        env['VK_ICD_FILENAMES'] = lavapipe.ICD
    env.setdefault('XDG_RUNTIME_DIR', '/tmp')
    return env


def run(tp2, env, opts, scene, out, size, timeout=900):
    cmd = [tp2, '--quiet'] + opts + [scene, out] + size.split('x')
    t0 = time.perf_counter()
    r = subprocess.run(cmd, env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, timeout=timeout)
    dt = time.perf_counter() - t0
    if r.returncode != 0:
        sys.exit('settings: %s failed: %s' % (' '.join(cmd),
                                               r.stdout.decode()[-500:]))
    return dt


def compare(imgcmp, img, ref):
    r = subprocess.run([imgcmp, img, ref], stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE)
    vals = {}
    for tok in r.stdout.decode().split():
        k, _, v = tok.partition('=')
        try:
            vals[k] = float(v)
        except ValueError:
            pass
    return vals


def header(tp2, env, args):
    ver = subprocess.run([tp2, '--version'], env=env, stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT).stdout.decode().strip()
    dev = subprocess.run([tp2, '--list-devices'], env=env,
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT
                         ).stdout.decode().strip().splitlines()
    cpu = platform.processor() or platform.machine()
    try:
        with open('/proc/cpuinfo') as fh:
            for line in fh:
                if line.startswith('model name'):
                    cpu = line.split(':', 1)[1].strip()
                    break
    except OSError:
        pass
    return {
        'date': datetime.datetime.utcnow().strftime('%Y-%m-%d %H:%M UTC'),
        'build': ver.splitlines()[0] if ver else '?',
        'machine': '%s, %d cores (nproc), Linux %s' % (
            cpu, os.cpu_count() or 0, platform.release()),
        'device': dev[0] if dev else '?',
        'command': 'bench/settings.py ' + ' '.join(sys.argv[1:]),
        'load': '%.2f %.2f %.2f at start' % os.getloadavg(),
    }


def measure(args):
    env = make_env()
    tp2 = os.path.abspath(args.tp2)
    imgcmp = args.imgcmp or os.path.join(os.path.dirname(tp2), 'tests',
                                         'tp2-imgcmp')
    info = header(tp2, env, args)
    rows = []
    tmp = tempfile.mkdtemp(prefix='tp2-settings-')
    out = os.path.join(tmp, 'out.ppm')
    t_start = time.time()

    bench_scenes = args.scenes or bench.default_scenes(tp2, args.corpus)
    print('time: %d scenes at %s' % (len(bench_scenes), args.time_size),
          flush=True)
    for i, scene in enumerate(bench_scenes):
        name = os.path.basename(scene)
        for _, opts in SETTINGS:
            run(tp2, env, opts, scene, out, '200x150')
        order = SETTINGS[i % len(SETTINGS):] + SETTINGS[:i % len(SETTINGS)]
        times = {label: [] for label, _ in SETTINGS}
        for _ in range(args.runs):
            for label, opts in order:
                times[label].append(run(tp2, env, opts, scene, out,
                                        args.time_size))
        for label, _ in SETTINGS:
            rows.append({'part': 'time', 'scene': name, 'setting': label,
                         'spp': '', 'size': args.time_size,
                         'wall_s': '%.4f' % statistics.median(times[label])})
        print('  %-28s %s' % (name, ' '.join(
            '%.2f' % statistics.median(times[l]) for l, _ in SETTINGS)),
            flush=True)

    acc_scenes = args.acc_scenes or (sorted(glob.glob(os.path.join(REPO, 'scenes', '*.txt'))) +
                  sorted(glob.glob(os.path.join(REPO, 'tests', 'stress',
                                                '*.txt'))) +
                  [os.path.join(REPO, 'bench', 'scenes', 'spheres.txt')])
    print('accuracy: %d scenes at %s' % (len(acc_scenes), args.acc_size),
          flush=True)
    ref = os.path.join(tmp, 'ref.pfm')
    img = os.path.join(tmp, 'img.pfm')
    for scene in acc_scenes:
        name = os.path.relpath(scene, REPO)
        run(tp2, env, EXACT, scene, ref, args.acc_size)
        line = []
        for label, opts in SETTINGS:
            dt = run(tp2, env, opts, scene, img, args.acc_size)
            v = compare(imgcmp, img, ref)
            rows.append({'part': 'accuracy', 'scene': name, 'setting': label,
                         'spp': '', 'size': args.acc_size,
                         'wall_s': '%.4f' % dt,
                         'within1': '%.6f' % v['within1'],
                         'bad8': '%d' % v['bad8'], 'mae': '%.6f' % v['mae']})
            line.append('%.6f/%d' % (v['within1'], v['bad8']))
        print('  %-40s %s' % (name, ' '.join(line)), flush=True)

    spp_list = [int(s) for s in args.spp_list.split(',')]
    spp_scenes = args.spp_scenes or [s for s in sorted(glob.glob(os.path.join(REPO, 'scenes',
                                                           '*.txt')))
                  if os.path.basename(s) != 'showpiece.txt']
    print('spp: %d scenes at %s' % (len(spp_scenes), args.acc_size),
          flush=True)
    for scene in spp_scenes:
        name = os.path.relpath(scene, REPO)
        run(tp2, env, EXACT + ['--spp', str(args.spp_ref)], scene, ref,
            args.acc_size)
        for spp in spp_list:
            dt = run(tp2, env, ['--spp', str(spp)], scene, img, args.acc_size)
            v = compare(imgcmp, img, ref)
            rows.append({'part': 'spp', 'scene': name, 'setting': DEFAULT,
                         'spp': str(spp), 'size': args.acc_size,
                         'wall_s': '%.4f' % dt,
                         'within1': '%.6f' % v['within1'],
                         'bad8': '%d' % v['bad8'], 'mae': '%.6f' % v['mae']})
    info['minutes'] = '%.1f' % ((time.time() - t_start) / 60)
    info['load'] += ', %.2f %.2f %.2f at end' % os.getloadavg()
    return info, rows


def write_csv(path, info, rows):
    with open(path, 'w', newline='') as fh:
        for k in ('date', 'build', 'machine', 'device', 'command', 'minutes',
                  'load'):
            fh.write('# %s: %s\n' % (k, info[k]))
        w = csv.DictWriter(fh, FIELDS)
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, '') for k in FIELDS})


def read_csv(path):
    info, lines = {}, []
    with open(path) as fh:
        for line in fh:
            if line.startswith('# '):
                k, _, v = line[2:].partition(': ')
                info[k] = v.strip()
            else:
                lines.append(line)
    return info, list(csv.DictReader(lines))


def geomean(xs):
    return math.exp(sum(math.log(x) for x in xs) / len(xs))


def summarise(rows):
    """Per setting: (geomean ratio to float, min, max, scenes meeting the
    bar, scenes, worst bad8, worst scene); and the spp points."""
    t = {}
    for r in rows:
        if r['part'] == 'time':
            t.setdefault(r['scene'], {})[r['setting']] = float(r['wall_s'])
    out = {}
    for label, _ in SETTINGS:
        ratios = [s[label] / s['float'] for s in t.values()]
        acc = [r for r in rows if r['part'] == 'accuracy'
               and r['setting'] == label]
        meets = [r for r in acc if float(r['within1']) >= MIN_WITHIN1
                 and int(r['bad8']) <= MAX_BAD8]
        worst = max(acc, key=lambda r: (int(r['bad8']),
                                        -float(r['within1'])))
        out[label] = (geomean(ratios), min(ratios), max(ratios), len(meets),
                      len(acc), int(worst['bad8']), worst['scene'],
                      statistics.mean(float(r['mae']) for r in acc))
    spp = {}
    for r in rows:
        if r['part'] == 'spp':
            spp.setdefault(int(r['spp']), []).append(r)
    by_scene1 = {r['scene']: float(r['wall_s']) for r in spp.get(1, [])}
    spp_pts = []
    for n in sorted(spp):
        rs = spp[n]
        ratio = geomean([float(r['wall_s']) / by_scene1[r['scene']]
                         for r in rs]) if by_scene1 else float('nan')
        spp_pts.append((n, ratio, statistics.median(float(r['mae'])
                                                     for r in rs)))
    return out, spp_pts, len(t)


def print_table(info, summary, spp_pts, nscenes):
    print('# %s; %s; %s' % (info.get('build'), info.get('device'),
                            info.get('machine')))
    print('%-20s %8s %13s %10s %9s %9s' % (
        'setting', 'time', 'min-max', 'meet bar', 'worst b8', 'mean mae'))
    for label, _ in SETTINGS:
        g, lo, hi, m, n, b8, _, mae = summary[label]
        print('%-20s %7.2fx %6.2f-%-6.2f %5d/%-4d %9d %9.4f%s' % (
            label, g, lo, hi, m, n, b8, mae,
            '  (default)' if label == DEFAULT else ''))
    print('time: x float, geometric mean over %d bench scenes' % nscenes)
    for n, ratio, mae in spp_pts:
        print('spp %-3d %6.2fx spp 1   median mae %.4f' % (n, ratio, mae))


def print_scene_tables(rows):
    """Per-scene tables for docs/performance.md and docs/accuracy.md."""
    labels = [l for l, _ in SETTINGS]
    t = {}
    for r in rows:
        if r['part'] == 'time':
            t.setdefault(r['scene'], {})[r['setting']] = float(r['wall_s'])
    print('\ntime at %s, seconds (x float in brackets)' % next(
        r['size'] for r in rows if r['part'] == 'time'))
    print('    %-26s' % 'scene' + ''.join('%16s' % l.replace(', no pruning',
                                                            ' b0')
                                      for l in labels))
    for scene, v in t.items():
        print('    %-26s' % scene + ''.join(
            '%16s' % ('%.2f' % v[l] if l == 'float' else
                      '%.2f (%.2f)' % (v[l], v[l] / v['float']))
            for l in labels))
    print('\naccuracy against the exact image: within1 / pixels off by > 8')
    show = ['float', 'mixed', 'auto']
    print('    %-44s' % 'scene' + ''.join('%18s' % l for l in show))
    acc = {}
    for r in rows:
        if r['part'] == 'accuracy':
            acc.setdefault(r['scene'], {})[r['setting']] = r
    for scene, v in acc.items():
        print('    %-44s' % scene + ''.join(
            '%18s' % ('%s / %s%s' % (v[l]['within1'], v[l]['bad8'],
                                     '' if float(v[l]['within1']) >= MIN_WITHIN1
                                     and int(v[l]['bad8']) <= MAX_BAD8 else '!'))
            for l in show))


def draw_chart(path, info, summary, spp_pts, nscenes):
    import textwrap
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    from matplotlib.ticker import FixedLocator, NullLocator, FuncFormatter
    fig, (ax, ax2) = plt.subplots(
        1, 2, figsize=(11, 6.2), gridspec_kw={'width_ratios': [3.2, 1]})
    colours = {'float': 'tab:blue', 'mixed': 'tab:orange',
               'auto': 'tab:green', 'double': 'tab:green'}
    n = summary['float'][4]
    # Labels stacked in a column beside each group of points that share a
    # height, joined to their points by thin lines, so none overlaps.
    groups = {}
    for label, _ in SETTINGS:
        groups.setdefault(summary[label][3], []).append(label)
    xs = [summary[l][0] for l, _ in SETTINGS]
    x_text = max(summary[l][2] for l, _ in SETTINGS) * 1.15
    dodge = 2.2  # points sharing a count drawn this far apart, in scenes
    for label, _ in SETTINGS:
        g, lo, hi, m, _, b8, worst, _ = summary[label]
        pruned = 'no pruning' not in label
        c = colours[label.split(',')[0]]
        peers = sorted(groups[m], key=lambda l: -summary[l][0])
        k = peers.index(label)
        y = m + ((len(peers) - 1) / 2 - k) * dodge
        ax.errorbar([g], [y], xerr=[[g - lo], [hi - g]], fmt='none',
                    ecolor=c, alpha=0.45, capsize=4, linewidth=1.5)
        ax.plot([g], [y], marker='*' if label == DEFAULT else
                ('o' if pruned else 's'), markersize=20 if label == DEFAULT
                else 10, color=c, markerfacecolor=c if pruned else 'white',
                markeredgewidth=2, linestyle='none', zorder=3)
        y_text = m + 6 + ((len(peers) - 1) / 2 - k) * 3.6
        name = label + (' (default; double here)' if label == DEFAULT
                        else '')
        ax.annotate('%s: %.2fx, %d/%d, worst %d px' % (name, g, m, n, b8),
                    (g, y), xytext=(x_text, y_text), fontsize=9,
                    color='black', va='center',
                    fontweight='bold' if label == DEFAULT else 'normal',
                    arrowprops=dict(arrowstyle="-", color=c, alpha=0.7, relpos=(0, 0.5),
                                    linewidth=0.8))
    ax.set_xscale('log')
    lo_x = min(summary[l][1] for l, _ in SETTINGS)
    hi_x = max(summary[l][2] for l, _ in SETTINGS)
    ax.set_xlim(lo_x / 1.2, hi_x * 9)
    ticks = [t for t in (0.5, 0.75, 1, 1.5, 2, 3, 5, 10, 20)
             if lo_x / 1.2 <= t <= hi_x * 1.2]
    ax.xaxis.set_major_locator(FixedLocator(ticks))
    ax.xaxis.set_minor_locator(NullLocator())
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: '%gx' % v))
    ax.set_ylim(0, n + 20)
    ax.axhline(n, color='grey', linestyle=':', linewidth=1)
    ax.set_xlabel('time relative to --precision float: geometric mean over '
                  '%d bench scenes at 1920x1080\n(whiskers: the fastest and '
                  'the slowest scene; one timed run each)' % nscenes)
    ax.set_ylabel('scenes meeting the accuracy bar, of %d (400x300)' % n)
    ax.set_title('Which setting, and what does it cost?  '
                 '(filled: default pruning; hollow: --bailout 0)',
                 fontsize=11)
    ax.grid(True, alpha=0.3)
    ax2.plot([p[1] for p in spp_pts], [p[2] for p in spp_pts], marker='o',
             color='tab:green')
    for sp, x, y in spp_pts:
        ax2.annotate('%d spp' % sp, (x, y), textcoords='offset points',
                     xytext=(6, 4), fontsize=9)
    ax2.set_xscale('log')
    ax2.xaxis.set_major_locator(FixedLocator([1, 2, 4, 8, 16]))
    ax2.xaxis.set_minor_locator(NullLocator())
    ax2.xaxis.set_major_formatter(FuncFormatter(lambda v, _: '%gx' % v))
    ax2.set_xlim(0.8, max(p[1] for p in spp_pts) * 1.6)
    ax2.set_ylim(0, max(p[2] for p in spp_pts) * 1.15)
    ax2.set_xlabel('time relative to 1 spp')
    ax2.set_ylabel('median mean error (levels) against 64 spp')
    ax2.set_title('Samples per pixel (default setting)', fontsize=10)
    ax2.grid(True, alpha=0.3)
    caption = ('%s; %s; %s; %s. Bar: at least 99.95%% of channel values '
               'within one level and at most 10 pixels off by more than 8 '
               'levels, against --precision double --bailout 0 at the same '
               'samples (so only precision and pruning vary). All points '
               'from one run of bench/settings.py; points that share a count '
               'are drawn slightly apart.' % (
                   info.get('build'), info.get('date'), info.get('device'),
                   info.get('machine')))
    fig.text(0.01, 0.01, '\n'.join(textwrap.wrap(caption, 190)),
             fontsize=7.5, va='bottom')
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    fig.savefig(path, dpi=100)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--tp2', default=os.path.join(REPO, 'build', 'tp2'))
    ap.add_argument('--imgcmp')
    ap.add_argument('--corpus', default=bench.DEFAULT_CORPUS)
    ap.add_argument('--scenes', nargs='+', help='bench scenes for the times')
    ap.add_argument('--acc-scenes', nargs='+', help='accuracy scenes')
    ap.add_argument('--spp-scenes', nargs='+', help='spp panel scenes')
    ap.add_argument('--runs', type=int, default=1)
    ap.add_argument('--time-size', default='1920x1080')
    ap.add_argument('--acc-size', default='400x300')
    ap.add_argument('--spp-list', default='1,4,16')
    ap.add_argument('--spp-ref', type=int, default=64)
    ap.add_argument('--csv', default=os.path.join(REPO, 'docs',
                                                  'settings.csv'))
    ap.add_argument('--chart', default=os.path.join(REPO, 'docs',
                                                    'settings.png'))
    ap.add_argument('--no-chart', action='store_true')
    ap.add_argument('--plot-only', action='store_true')
    ap.add_argument('--scene-tables', action='store_true',
                    help='also print per-scene time and accuracy tables')
    args = ap.parse_args()
    if args.plot_only:
        info, rows = read_csv(args.csv)
    else:
        info, rows = measure(args)
        write_csv(args.csv, info, rows)
    summary, spp_pts, nscenes = summarise(rows)
    print_table(info, summary, spp_pts, nscenes)
    if args.scene_tables:
        print_scene_tables(rows)
    if not args.no_chart:
        draw_chart(args.chart, info, summary, spp_pts, nscenes)


if __name__ == '__main__':
    main()
