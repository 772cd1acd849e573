#!/usr/bin/env python3
"""scaling.py - render time against object count, tp2 (and POV-Ray).

Run it with Debian's interpreter, which has python3-matplotlib
(apt-get install -y python3-matplotlib):

    /usr/bin/python3 bench/scaling.py [--n 10,100,1000,10000,100000]
        [--kind spheres|triangles] [--runs 3] [--size 400x300] [--pov] [--timeout 300]
        [--tp2 build/tp2] [--csv docs/scaling.csv]
        [--png docs/scaling.png] [--keep-scenes DIR]

(`python3` on PATH may be a pyenv interpreter without matplotlib; if the
import fails, the script re-runs only its plotting step, `--plot-only`,
under /usr/bin/python3, so the measurements are kept either way.)

For each N it writes a deterministic scene (random.Random(seed + N)): N
spheres of radius 2.5 / N^(1/3) (so they fill about the same share of the
volume at every N) with centres uniform in x, z in [-10, 10] and y in [r, 6],
eight solid colours, two finishes (matte; shiny with kr = 0.3 reflection),
on a checker plane y = 0, an ambient light and two point lights; camera at
(0, 9, 24) looking at (0, 2, 0), vertical fov 40. It renders the scene with
tp2 (and, with --pov, with POV-Ray through bench/scene2pov.py, same options
as bench/bench.py) at 400x300, the median of --runs runs (whole-process
wall time). A run that exceeds --timeout is killed and recorded as a
timeout; larger N are then skipped for that program (recorded as such)
rather than left to hang.

--kind triangles: the same, with N random triangles (edge about twice the
spheres' radius, random orientation) read from an OBJ file by one `mesh`
object in place of the spheres.

tp2 runs with --stats --quiet, and each of its phases (parse, device,
bvh, upload, pipeline, render, readback, write; the median over the runs)
goes into the CSV and the printed table, so the chart can show where the
time goes as N grows: parsing and the BVH grow with N, the render with
the depth of the tree.

Outputs: a CSV (N, program, median_s, runs, status, times_s, and tp2's
phases) and a log-log chart of time against N (timeouts drawn as open
triangles at the time-out; tp2's main phases as dashed lines).
"""

import argparse
import csv
import os
import random
import shutil
import statistics
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True   # no __pycache__ in the source tree
HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import bench      # noqa: E402  (run_timed, convert, pov_cmd, tp2_env)

COLORS = [(0.9, 0.2, 0.2), (0.2, 0.8, 0.3), (0.2, 0.4, 0.9), (0.9, 0.8, 0.2),
          (0.8, 0.3, 0.8), (0.2, 0.8, 0.8), (0.95, 0.95, 0.95),
          (0.9, 0.5, 0.1)]


def make_scene(n, seed):
    rng = random.Random(seed + n)
    r = 2.5 / n ** (1.0 / 3.0)
    lines = ['# scaling.py: %d random spheres (seed %d), r = %.6g' %
             (n, seed, r),
             '0 9 24', '0 2 0', '0 1 0', '40', '',
             '3',
             '0 0 0  0.2 0.2 0.2  1 0 0',
             '15 25 20  0.9 0.9 0.9  1 0 0',
             '-20 15 10  0.5 0.5 0.6  1 0 0', '',
             str(len(COLORS) + 1)]
    lines += ['solid %g %g %g' % c for c in COLORS]
    lines.append('checker 0.9 0.9 0.9  0.25 0.25 0.3  2')
    lines += ['', '2',
              '0.15 0.7 0.3 30 0 0 0',
              '0.1 0.5 0.6 200 0.3 0 0', '',
              str(n + 1)]
    for _ in range(n):
        x = rng.uniform(-10, 10)
        z = rng.uniform(-10, 10)
        y = rng.uniform(r, 6)
        lines.append('%d %d sphere %.6f %.6f %.6f %.6g' % (
            rng.randrange(len(COLORS)), rng.randrange(2), x, y, z, r))
    lines.append('%d 0 plane 0 1 0 0' % len(COLORS))
    return '\n'.join(lines) + '\n'


def make_triangles(n, seed, obj_path):
    """The scene of make_scene with n random triangles (written to
    obj_path as an OBJ) in place of the spheres, all of one pigment and
    finish."""
    rng = random.Random(seed + n)
    r = 2.5 / n ** (1.0 / 3.0)
    with open(obj_path, 'w') as fh:
        fh.write('# scaling.py: %d random triangles (seed %d)\n' % (n, seed))
        for _ in range(n):
            c = (rng.uniform(-10, 10), rng.uniform(r, 6), rng.uniform(-10, 10))
            for _ in range(3):
                fh.write('v %.6f %.6f %.6f\n' % tuple(
                    c[a] + rng.uniform(-r, r) for a in range(3)))
        for i in range(n):
            fh.write('f %d %d %d\n' % (3 * i + 1, 3 * i + 2, 3 * i + 3))
    lines = make_scene(1, seed).splitlines()
    lines[-3:] = ['2', '0 1 mesh %s' % os.path.basename(obj_path),
                  '%d 0 plane 0 1 0 0' % len(COLORS)]
    lines[0] = '# scaling.py: %d random triangles (seed %d)' % (n, seed)
    return '\n'.join(lines) + '\n'


def measure(args, env, prog, scene, w, h, work):
    """(times, status, phases): phases are tp2's median phase times."""
    out = os.path.join(work, '%s.ppm' % prog)
    phases = []
    if prog == 'tp2':
        cmd = [args.tp2, '--stats', '--quiet', '--bailout', repr(args.bailout), scene,
               out, str(w), str(h)]
        e = env
    else:
        pov = os.path.splitext(scene)[0] + '.pov'
        extra = bench.convert(args.tp2, scene, w, h, pov, args.bailout)
        cmd, e = bench.pov_cmd(args.povray, pov, out, w, h, args.threads,
                               extra), None
    times, status = [], 'ok'
    for _ in range(args.runs):
        dt, st, tail, _cpu = bench.run_timed(cmd, e, work, args.timeout)
        if st != 'ok':
            status = ('timeout (> %gs)' % args.timeout if st == 'timeout'
                      else st)
            if args.verbose and tail:
                sys.stderr.write(tail + '\n')
            break
        times.append(dt)
        if prog == 'tp2':
            phases.append(bench.tp2_phases(tail))
        if args.verbose:
            print('  %s N run %.3fs' % (prog, dt), file=sys.stderr)
    return times, status, bench.phase_medians(phases) if phases else {}


def write_csv(path, rows, header):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    tmp = path + '.tmp'
    with open(tmp, 'w', newline='') as fh:
        for ln in header:
            fh.write('# %s\n' % ln)
        wr = csv.DictWriter(fh, fieldnames=['n', 'program', 'median_s',
                                            'runs', 'status', 'times_s'] +
                            ['%s_s' % p for p in bench.PHASES], restval='')
        wr.writeheader()
        for r in rows:
            wr.writerow(r)
    os.replace(tmp, path)


def read_csv(path):
    with open(path) as fh:
        data = [ln for ln in fh if not ln.startswith('#')]
    return list(csv.DictReader(data))


def plot(csv_path, png_path, timeout):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    import matplotlib.ticker  # noqa: F401  (used as matplotlib.ticker)
    rows = read_csv(csv_path)
    fig, ax = plt.subplots(figsize=(6.4, 4.2), dpi=100)
    styles = {'tp2': ('tab:blue', 'o'), 'povray': ('tab:orange', 's')}
    for prog in ('tp2', 'povray'):
        pr = [r for r in rows if r['program'] == prog]
        if not pr:
            continue
        color, marker = styles[prog]
        ok = [(int(r['n']), float(r['median_s'])) for r in pr
              if r['median_s']]
        if ok:
            ax.plot([p[0] for p in ok], [p[1] for p in ok], marker=marker,
                    color=color, label=prog + ' (median)')
        if prog == 'tp2':
            for phase, shade in (('parse', 'tab:green'), ('bvh', 'tab:red'),
                                 ('render', 'tab:purple')):
                pts = [(int(r['n']), float(r[phase + '_s'])) for r in pr
                       if r.get(phase + '_s') and float(r[phase + '_s']) > 0]
                if pts:
                    ax.plot([p[0] for p in pts], [p[1] for p in pts], linestyle='--',
                            marker='.', color=shade, label='tp2 ' + phase)
        to = [int(r['n']) for r in pr if r['status'].startswith('timeout')]
        if to:
            ax.plot(to, [timeout] * len(to), linestyle='none', marker='^',
                    markerfacecolor='none', color=color, markersize=9,
                    label='%s timed out (> %g s)' % (prog, timeout))
    ax.set_xscale('log')
    ax.set_yscale('log')
    plain = matplotlib.ticker.FuncFormatter(lambda v, _: '%g' % v)
    ax.yaxis.set_major_formatter(plain)
    ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.xaxis.set_major_formatter(plain)
    ax.set_xlabel('objects N (spheres, or triangles of one mesh)')
    ax.set_ylabel('whole-process wall time, s')
    ax.set_title('Time vs object count, %s' % os.path.basename(csv_path))
    ax.grid(True, which='both', alpha=0.3)
    ax.legend(fontsize='small')
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(png_path)), exist_ok=True)
    fig.savefig(png_path)
    plt.close(fig)


def plot_anywhere(csv_path, png_path, timeout):
    import importlib.util
    if importlib.util.find_spec('matplotlib') is None:
        other = '/usr/bin/python3'
        if os.path.exists(other) and os.path.realpath(other) != \
                os.path.realpath(sys.executable):
            r = subprocess.run([other, os.path.abspath(__file__),
                                '--plot-only', '--csv', csv_path,
                                '--png', png_path, '--timeout', str(timeout)])
            return r.returncode == 0
        print('scaling: matplotlib is missing (apt-get install -y '
              'python3-matplotlib); no chart', file=sys.stderr)
        return False
    plot(csv_path, png_path, timeout)
    return True


def main(argv=None):
    ap = argparse.ArgumentParser(description='tp2 render time against '
                                             'object count')
    ap.add_argument('--n', default='10,100,1000,10000,100000',
                    help='comma-separated sphere counts')
    ap.add_argument('--kind', choices=('spheres', 'triangles'), default='spheres')
    ap.add_argument('--runs', type=int, default=3)
    ap.add_argument('--size', default='400x300')
    ap.add_argument('--seed', type=int, default=1)
    ap.add_argument('--pov', action='store_true', help='time POV-Ray too')
    ap.add_argument('--timeout', type=float, default=300.0,
                    help='seconds per run before it is killed (default 300)')
    ap.add_argument('--tp2', default=os.path.join(REPO, 'build', 'tp2'))
    ap.add_argument('--povray', default='povray')
    ap.add_argument('--bailout', type=float, default=1 / 255,
                    help="both programs' least traced ray weight (default 1/255)")
    ap.add_argument('--threads', type=int, default=2)
    ap.add_argument('--no-icd', action='store_true')
    ap.add_argument('--csv', default=os.path.join(REPO, 'docs',
                                                  'scaling.csv'))
    ap.add_argument('--png', default=os.path.join(REPO, 'docs',
                                                  'scaling.png'))
    ap.add_argument('--keep-scenes', metavar='DIR',
                    help='keep the generated scenes (and .pov files) here')
    ap.add_argument('--plot-only', action='store_true',
                    help='only draw --png from an existing --csv')
    ap.add_argument('-v', '--verbose', action='store_true')
    args = ap.parse_args(argv)
    if args.plot_only:
        plot(args.csv, args.png, args.timeout)
        return 0
    args.tp2 = os.path.abspath(args.tp2)
    ns = [int(x) for x in args.n.split(',')]
    w, h = (int(v) for v in args.size.lower().split('x'))
    env = bench.tp2_env(not args.no_icd)
    progs = ['tp2'] + (['povray'] if args.pov else [])
    work = args.keep_scenes or tempfile.mkdtemp(prefix='tp2-scaling-')
    os.makedirs(work, exist_ok=True)
    info = bench.machine_info(args.tp2, env)
    header = ['tp2 scaling: %s, %s CPUs; tp2 device %s; %s' % (
        info['cpu'], info['nproc'], info['device'], info['povray']),
        'size %dx%d, %s, median of %d runs, timeout %g s, seed %d' % (
        w, h, args.kind, args.runs, args.timeout, args.seed),
        'phases: tp2 --stats (median per phase)',
        'command: %s' % ' '.join([sys.executable] + sys.argv)]
    for ln in header:
        print(ln)
    rows = []
    stopped = {p: None for p in progs}
    try:
        for n in ns:
            scene = os.path.join(work, '%s-%d.txt' % (args.kind, n))
            with open(scene, 'w') as fh:
                if args.kind == 'spheres':
                    fh.write(make_scene(n, args.seed))
                else:
                    fh.write(make_triangles(n, args.seed, os.path.join(
                        work, 'triangles-%d.obj' % n)))
            for prog in progs:
                if stopped[prog] is not None:
                    rows.append({'n': n, 'program': prog, 'median_s': '',
                                 'runs': 0, 'times_s': '',
                                 'status': 'skipped (N=%d timed out)' %
                                 stopped[prog]})
                    continue
                times, status, phases = measure(args, env, prog, scene, w, h, work)
                med = statistics.median(times) if times else None
                row = {'n': n, 'program': prog,
                       'median_s': '' if med is None else '%.4f' % med,
                       'runs': len(times), 'status': status,
                       'times_s': ' '.join('%.4f' % t for t in times)}
                row.update({'%s_s' % p: '%.4f' % v for p, v in phases.items()})
                rows.append(row)
                print('N=%-7d %-6s %s %s%s' % (
                    n, prog, '-' if med is None else '%.3f s' % med,
                    '' if status == 'ok' else status,
                    ''.join('  %s %.3f' % (p, v) for p, v in phases.items())))
                sys.stdout.flush()
                if status.startswith('timeout'):
                    stopped[prog] = n
    finally:
        if not args.keep_scenes:
            shutil.rmtree(work, ignore_errors=True)
    write_csv(args.csv, rows, header)
    print('CSV: %s' % args.csv)
    if plot_anywhere(args.csv, args.png, args.timeout):
        print('chart: %s' % args.png)
    return 0


if __name__ == '__main__':
    sys.exit(main())
