#!/usr/bin/env python3
"""Compare two checkpoints bit for bit: every dataset (dtype, shape, bytes) and every attribute.
Exit 0 if identical, 1 with the differences listed otherwise."""
import sys

import h5py
import numpy as np


def collect(f):
    items = {}

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset):
            items[name] = obj
    f.visititems(visit)
    return items


def main(a_path, b_path):
    problems = []
    with h5py.File(a_path, "r") as a, h5py.File(b_path, "r") as b:
        da, db = collect(a), collect(b)
        if set(da) != set(db):
            problems.append(f"dataset sets differ: {sorted(set(da) ^ set(db))}")
        for name in sorted(set(da) & set(db)):
            x, y = da[name][()], db[name][()]
            if da[name].dtype != db[name].dtype or np.shape(x) != np.shape(y):
                problems.append(f"{name}: dtype/shape {da[name].dtype}{np.shape(x)} vs {db[name].dtype}{np.shape(y)}")
            elif np.asarray(x).tobytes() != np.asarray(y).tobytes():
                problems.append(f"{name}: contents differ")
            if dict(da[name].attrs) != dict(db[name].attrs):
                problems.append(f"{name}: attributes differ")
        for key in set(a.attrs) | set(b.attrs):
            if key not in a.attrs or key not in b.attrs or a.attrs[key] != b.attrs[key]:
                problems.append(f"root attribute {key} differs")
        count = len(da)
    if problems:
        print("\n".join(problems))
        return 1
    print(f"identical: {count} datasets, bit for bit")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
