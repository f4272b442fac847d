#!/usr/bin/env python3
"""scripts/render_mesh.py --distance-to: a plane rendered against itself is blue everywhere; against
its left half only, its right part is red and its left part blue.  Usage: render_mesh_test.py
RENDER_MESH.py (exits non-zero on a failure)."""
import os, subprocess, sys, tempfile, zlib


def grid_obj(path, n, x_max):
    """An n x n grid of squares over [0, 1]^2 in z = 0, keeping the squares with x < x_max."""
    with open(path, 'w') as f:
        for j in range(n + 1):
            for i in range(n + 1):
                f.write('v %g %g 0\n' % (i / n, j / n))
        for j in range(n):
            for i in range(n):
                if (i + 1) / n > x_max + 1e-9:
                    continue
                a = j * (n + 1) + i + 1
                f.write('f %d %d %d\nf %d %d %d\n' % (a, a + 1, a + n + 2, a, a + n + 2, a + n + 1))


def read_png(path):
    """Width, height and RGB bytes of a PNG written by render_mesh.py (8-bit RGB, filter 0)."""
    data = open(path, 'rb').read()
    pos, idat, width, height = 8, b'', 0, 0
    while pos < len(data):
        length = int.from_bytes(data[pos:pos + 4], 'big')
        tag, payload = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        if tag == b'IHDR':
            width, height = int.from_bytes(payload[:4], 'big'), int.from_bytes(payload[4:8], 'big')
        elif tag == b'IDAT':
            idat += payload
        pos += 12 + length
    raw = zlib.decompress(idat)
    rows = [raw[y * (3 * width + 1) + 1:(y + 1) * (3 * width + 1)] for y in range(height)]
    return width, height, rows


def pixel(rows, x, y):
    return tuple(rows[y][3 * x:3 * x + 3])


def render(script, out, mesh, other):
    subprocess.run([sys.executable, script, out, mesh, '--distance-to', other, '--distance-scale', '0.1',
                    '--focus', '0.5,0.5,0', '--radius', '0.5', '--size', '100x100'], check=True,
                   stdout=subprocess.DEVNULL)
    return read_png(out)


def main(script):
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        plane, half = os.path.join(tmp, 'plane.obj'), os.path.join(tmp, 'half.obj')
        grid_obj(plane, 10, 1.0)
        grid_obj(half, 10, 0.5)
        # Looking along -Z, x to the right: image column c shows x = c / 100.
        _, _, rows = render(script, os.path.join(tmp, 'self.png'), plane, plane)
        red_self = [(x, y) for y in range(5, 95) for x in range(5, 95)
                    if pixel(rows, x, y)[0] > pixel(rows, x, y)[2]]
        if red_self:
            failures.append('against itself, red pixels at %s' % (red_self[:3],))
        _, _, rows = render(script, os.path.join(tmp, 'half.png'), plane, half)
        for x, expect_red in ((20, False), (35, False), (75, True), (90, True)):
            r, _, b = pixel(rows, x, 50)
            if (r > b) != expect_red:
                failures.append('against the left half, column %d: rgb %s, expected %s' %
                                (x, pixel(rows, x, 50), 'red' if expect_red else 'blue'))
    for failure in failures:
        print('FAIL:', failure)
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1]))
