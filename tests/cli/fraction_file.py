#!/usr/bin/env python3
"""Reads coverage fractions that `soiq convert --fractional` wrote (NIfTI-1, .nii or .nii.gz, uint8
or float32), with no soiq code and no numpy, and either

  box LO_X,LO_Y,LO_Z HI_X,HI_Y,HI_Z N   checks every voxel against the fraction of an axis-aligned
                                      box (LPS mm) on an axis-aligned grid, computed here: exact
                                      along the rows (i), and N x N sample lines across (j, k) as
                                      soiq samples them; prints the sum of fractions in voxels
  sum                                 prints the sum of the fractions in voxels
  same OTHER                          exits 1 unless OTHER holds the same grid and values

Exit status 1 with one line on stderr on any mismatch."""
import gzip
import math
import struct
import sys


def read_nifti(path):
    raw = open(path, "rb").read()
    if path.endswith(".gz"):
        raw = gzip.decompress(raw)
    dims = struct.unpack_from("<8h", raw, 40)
    datatype = struct.unpack_from("<h", raw, 70)[0]
    vox_offset = int(struct.unpack_from("<f", raw, 108)[0])
    srow = [struct.unpack_from("<4f", raw, 280 + 16 * r) for r in range(3)]
    nx, ny, nz = dims[1], dims[2], dims[3]
    count = nx * ny * nz
    if datatype == 2:  # uint8
        values = [v / 255.0 for v in raw[vox_offset:vox_offset + count]]
        kind = "uint8"
        raw_values = list(raw[vox_offset:vox_offset + count])
    elif datatype == 16:  # float32
        values = list(struct.unpack_from("<%df" % count, raw, vox_offset))
        kind = "float32"
        raw_values = values
    else:
        sys.exit("%s: datatype %d is not uint8 or float32" % (path, datatype))
    return (nx, ny, nz), srow, kind, values, raw_values


def lps(srow, i, j, k):
    """NIfTI's sform is RAS: LPS negates x and y."""
    ras = [srow[r][0] * i + srow[r][1] * j + srow[r][2] * k + srow[r][3] for r in range(3)]
    return (-ras[0], -ras[1], ras[2])


def covered(lo, hi, a, b):
    return max(0.0, min(hi, b) - max(lo, a))


def check_box(path, lo, hi, n):
    dims, srow, kind, values, raw_values = read_nifti(path)
    origin = lps(srow, 0, 0, 0)
    step = [lps(srow, *(1 if a == axis else 0 for a in range(3)))[axis] - origin[axis] for axis in range(3)]
    if any(s <= 0 for s in step):
        sys.exit("box check needs an LPS-aligned grid with positive steps, got %s" % (step,))
    nx, ny, nz = dims

    def samples_inside(axis, index):
        """How many of the N sample positions across voxel `index` along `axis` lie in the box."""
        inside = 0
        for a in range(n):
            x = origin[axis] + step[axis] * (index - 0.5 + (a + 0.5) / n)
            if abs(x - lo[axis]) < 1e-9 or abs(x - hi[axis]) < 1e-9:
                sys.exit("a sample line lies on a face of the box: choose other coordinates")
            inside += lo[axis] < x < hi[axis]
        return inside

    fy = [samples_inside(1, j) / n for j in range(ny)]
    fz = [samples_inside(2, k) / n for k in range(nz)]
    fx = [covered(lo[0], hi[0], origin[0] + step[0] * (i - 0.5), origin[0] + step[0] * (i + 0.5)) / step[0]
          for i in range(nx)]
    total = 0.0
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                f = fx[i] * fy[j] * fz[k]
                index = i + nx * (j + ny * k)
                got = raw_values[index]
                if kind == "uint8":
                    want = 0 if f == 0 else 255 if f == 1 else min(254, max(1, int(math.floor(255 * f + 0.5))))
                    ok = got == want
                else:
                    want = f
                    ok = abs(got - f) <= 1e-6 and ((f in (0.0, 1.0)) == (got in (0.0, 1.0)))
                if not ok:
                    sys.exit("%s: voxel (%d,%d,%d) holds %r, the box covers %.6f of it (expected %r)" %
                             (path, i, j, k, got, f, want))
                total += values[index]
    print("%.6f" % total)


def main():
    path, command = sys.argv[1], sys.argv[2]
    if command == "box":
        lo = [float(v) for v in sys.argv[3].split(",")]
        hi = [float(v) for v in sys.argv[4].split(",")]
        check_box(path, lo, hi, int(sys.argv[5]))
    elif command == "sum":
        print("%.6f" % sum(read_nifti(path)[3]))
    elif command == "same":
        a, b = read_nifti(path), read_nifti(sys.argv[3])
        if a[0] != b[0] or a[2] != b[2] or a[4] != b[4]:
            sys.exit("%s and %s differ" % (path, sys.argv[3]))
        if any(abs(x - y) > 1e-4 for ra, rb in zip(a[1], b[1]) for x, y in zip(ra, rb)):
            sys.exit("%s and %s have other grids" % (path, sys.argv[3]))
    else:
        sys.exit("unknown command " + command)


if __name__ == "__main__":
    main()
