#!/usr/bin/env python3
"""The scaling study of docs/PERFORMANCE.md: `gpurt bench` (gl, cpu, embree in one run each) on
scenes from 36 to 871k triangles at 1024x1024, and on the bunny from 256x256 to 2048x2048.

    scripts/bench-scaling.py [--gpurt build/gpurt] [--out docs/perf] [--runs 5] [--rays primary]

Writes OUT/scaling-RAYS.json (every bench object), OUT/scaling-RAYS.png (two log-log plots) and
prints the Markdown tables. The dragon comes from scripts/fetch-dragon.sh (not committed); the plot
needs matplotlib (Debian: python3-matplotlib), checked before anything runs.
"""
import argparse
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def bench(gpurt, scene, size, runs, rays):
    cmd = [gpurt, 'bench', scene, '--size', size, '--runs', str(runs), '--rays', rays, '--json']
    out = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True).stdout
    result = json.loads(out)
    print(f"{os.path.basename(scene):>16} {size:>9} " + '  '.join(
        f"{b['backend']} {b['ms']:8.2f} ms" for b in result['backends']), file=sys.stderr)
    return result


def table(rows, key_name, key):
    backends = [b['backend'] for b in rows[0]['backends']]
    head = f'| {key_name} | rays | ' + ' | '.join(f'{b} ms | {b} Mrays/s' for b in backends) + ' | gl / embree |'
    lines = [head, '|' + '---|' * (2 + 2 * len(backends) + 1)]
    for r in rows:
        by = {b['backend']: b for b in r['backends']}
        cells = ' | '.join(f"{by[b]['ms']:.1f} | {by[b]['mrays_per_s']:.2f}" for b in backends)
        ratio = by['gl'].get('ratio_to_embree', float('nan'))
        lines.append(f"| {key(r)} | {by['gl']['rays']} | {cells} | {ratio:.3f} |")
    return '\n'.join(lines)


def plot(triangle_rows, size_rows, path, rays):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, rows, x, label in ((axes[0], triangle_rows, lambda r: r['triangles'], 'triangles'),
                               (axes[1], size_rows, lambda r: r['width'] * r['height'], 'pixels (rays)')):
        for backend, style in (('gl', 'o-'), ('cpu', 's-'), ('embree', '^-')):
            pts = [(x(r), b['ms']) for r in rows for b in r['backends'] if b['backend'] == backend]
            if pts:
                ax.plot(*zip(*pts), style, label=backend)
        ax.set_xscale('log')
        ax.set_yscale('log')
        ax.set_xlabel(label)
        ax.set_ylabel(f'{rays} trace time, ms (median)')
        ax.grid(True, which='both', alpha=0.3)
        ax.legend()
    axes[0].set_title('time against triangle count, 1024x1024')
    axes[1].set_title('time against resolution, bunny (69,666 triangles)')
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--gpurt', default='build/gpurt')
    p.add_argument('--out', default='docs/perf')
    p.add_argument('--runs', type=int, default=5)
    p.add_argument('--rays', default='primary', choices=['primary', 'shadow'])
    a = p.parse_args()
    try:  # checked before the benchmarks run, not after
        import matplotlib  # noqa: F401
    except ImportError:
        print(f"{sys.argv[0]}: the plot needs matplotlib for {sys.executable} (Debian: apt-get "
              f"install python3-matplotlib, then run /usr/bin/python3 {sys.argv[0]})", file=sys.stderr)
        sys.exit(2)  # the environment, not the input
    dragon = subprocess.run([os.path.join(ROOT, 'scripts', 'fetch-dragon.sh')], cwd=ROOT, check=True,
                            capture_output=True, text=True).stdout.strip()
    scenes = ['scenes/boxes.json', '../shared/models/teapot.obj', 'scenes/room.json', '../shared/models/bunny_lo.obj',
              'scenes/highlow.json', '../shared/models/bunny.obj', dragon]
    triangle_rows = [bench(a.gpurt, s, '1024x1024', a.runs, a.rays) for s in scenes]
    triangle_rows.sort(key=lambda r: r['triangles'])
    size_rows = [bench(a.gpurt, '../shared/models/bunny.obj', f'{n}x{n}', a.runs, a.rays) for n in (256, 512, 1024, 2048)]
    os.makedirs(os.path.join(ROOT, a.out), exist_ok=True)
    with open(os.path.join(ROOT, a.out, f'scaling-{a.rays}.json'), 'w') as f:
        json.dump({'triangles': triangle_rows, 'resolution': size_rows}, f, indent=1)
    plot(triangle_rows, size_rows, os.path.join(ROOT, a.out, f'scaling-{a.rays}.png'), a.rays)
    print(table(triangle_rows, 'scene (triangles)', lambda r: f"{os.path.basename(r['scene'])} ({r['triangles']})"))
    print()
    print(table(size_rows, 'size', lambda r: f"{r['width']}x{r['height']}"))


if __name__ == '__main__':
    main()
