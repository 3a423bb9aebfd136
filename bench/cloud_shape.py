#!/usr/bin/env python3
"""Shape of a cloud from a cloud-particle PLY (WriteCloudParticles): height, base width, their
ratio, width per tenth of the height, and how flat the base is.

Usage: python3 bench/cloud_shape.py out/figure6/cloud.0480.ply [...]

- base / top: the 1st percentile and the maximum of z; height H = top - base.
- width of a slab: the larger of the x and y extents between the 2nd and 98th percentiles.
- base width: the width of the lowest tenth of H.
- base flatness: in 250 m columns holding at least 200 particles, the 10th, 50th and 90th
  percentiles of the column's lowest particle (a flat base gives close values).
"""
import struct
import sys

SIZES = {'float': 4, 'uchar': 1, 'int': 4, 'uint': 4}


def load(path):
    data = open(path, 'rb').read()
    end = data.index(b'end_header\n') + len(b'end_header\n')
    header = data[:end].decode()
    n = int(header.split('element vertex ')[1].split()[0])
    props = [line.split()[1] for line in header.splitlines() if line.startswith('property')]
    record = sum(SIZES[p] for p in props)
    return [struct.unpack_from('<fff', data, end + i * record) for i in range(n)]


def percentile(sorted_values, q):
    return sorted_values[min(len(sorted_values) - 1, int(q * len(sorted_values)))]


def width(points, lo, hi):
    xs = sorted(p[0] for p in points if lo <= p[2] < hi)
    ys = sorted(p[1] for p in points if lo <= p[2] < hi)
    if len(xs) < 20:
        return 0.0
    return max(percentile(xs, 0.98) - percentile(xs, 0.02), percentile(ys, 0.98) - percentile(ys, 0.02))


def main():
    for path in sys.argv[1:]:
        points = load(path)
        z = sorted(p[2] for p in points)
        base, top = percentile(z, 0.01), z[-1]
        h = top - base
        tenths = [width(points, base + i * h / 10, base + (i + 1) * h / 10) for i in range(10)]
        lowest, count = {}, {}
        for x, y, zz in points:
            key = (int(x // 250.0), int(y // 250.0))
            lowest[key] = min(lowest.get(key, zz), zz)
            count[key] = count.get(key, 0) + 1
        bottoms = sorted(lowest[k] for k in lowest if count[k] >= 200)
        print(f'{path}: {len(points)} particles, base {base:.0f} m, top {top:.0f} m, '
              f'height {h:.0f} m, base width {tenths[0]:.0f} m, ratio {h / tenths[0]:.2f}')
        print('  width by tenth of the height (m):', ' '.join(f'{w:.0f}' for w in tenths))
        if bottoms:
            print(f'  column bottoms ({len(bottoms)} columns) 10/50/90%: '
                  f'{percentile(bottoms, 0.1):.0f} {percentile(bottoms, 0.5):.0f} {percentile(bottoms, 0.9):.0f} m')


if __name__ == '__main__':
    main()
