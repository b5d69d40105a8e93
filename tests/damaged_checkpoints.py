#!/usr/bin/env python3
"""Damage a real checkpoint in many ways and check that the tools reject every variant with exit
code 4 and a message naming the file, never reading it as wrong numbers or crashing.

Every checkpoint starts with a seal (CRC-32 and size of the rest of the file, io/file_seal.hpp),
so any damage is caught before HDF5 reads the file. To test the checks behind the seal too, the
variants made with h5py and the flipped data bytes are sealed again (`reseal`) and must then be
rejected by the reader's own checks (shapes, attributes, Fletcher32).

Variants (all must be rejected): truncations at 12 lengths; one flipped byte in the data of every
non-empty dataset, sealed and resealed (seal, then Fletcher32); 6 missing datasets; an extent larger than the file; contacts out of key order; wrong format attribute; wrong schema
version; a foreign HDF5 file; an empty file; a text file. Also 40 single-bit flips at random
positions anywhere in the file (metadata and seal included): each must be rejected (exit 4), never
read as different numbers or crash.
Usage: damaged_checkpoints.py TOOLS_DIR GOOD.h5 WORKDIR WITH_CONTACTS.h5 (a checkpoint holding contacts)"""
import os
import random
import shutil
import subprocess
import sys
import zlib

import h5py
import numpy as np


SEAL_BYTES = 512
SEAL_MAGIC = b"dem-checkpoint-seal crc32="


def reseal(path):
    """Rewrite the seal of a checkpoint edited on purpose (the format of io/file_seal.cpp)."""
    data = open(path, "rb").read()
    body = data[SEAL_BYTES:]
    line = SEAL_MAGIC + b"%08x size=%d\n" % (zlib.crc32(body), len(body))
    open(path, "wb").write(line.ljust(SEAL_BYTES, b"\0") + body)


def read_back(tools, path, workdir):
    """Exit code of post-macro reading `path` (as the current state) and its output table."""
    csv = os.path.join(workdir, "p.csv")
    if os.path.exists(csv):
        os.remove(csv)
    r = subprocess.run([os.path.join(tools, "post-macro"), "--reference", GOOD, "--in", path, "--csv", csv, "--bins", "7"],
                       capture_output=True, text=True, timeout=60)
    # The first line names the files; the rest are the numbers.
    table = open(csv).read().split("\n", 1)[1] if r.returncode == 0 else None
    return r.returncode, r.stderr, table


def main(tools, good, workdir, with_contacts):
    global GOOD
    GOOD = good
    os.makedirs(workdir, exist_ok=True)
    rc, _, reference_table = read_back(tools, good, workdir)
    assert rc == 0, "the undamaged checkpoint must read"
    size = os.path.getsize(good)
    variants = []
    resealed = []  # paths edited with h5py or at a data byte: sealed again before reading

    def variant(name):
        path = os.path.join(workdir, name + ".h5")
        shutil.copyfile(good, path)
        variants.append((name, path))
        return path

    for frac in (0.0, 0.01, 0.05, 0.1, 0.25, 0.4, 0.5, 0.6, 0.75, 0.9, 0.99):
        with open(variant(f"truncated_{frac}"), "r+b") as f:
            f.truncate(int(size * frac))
    with open(variant("truncated_last_byte"), "r+b") as f:
        f.truncate(size - 1)

    with h5py.File(good, "r") as f:
        chunks = []
        f.visititems(lambda n, o: chunks.append((n, o.id.get_chunk_info(0))) if isinstance(o, h5py.Dataset) and o.chunks else None)
    for name, info in chunks:
        for sealed in (True, False):
            path = variant("flip_" + name.replace("/", "_") + ("" if sealed else "_resealed"))
            at = SEAL_BYTES + info.byte_offset + info.size // 2  # HDF5 addresses start after the seal
            with open(path, "r+b") as f:
                f.seek(at)
                b = f.read(1)
                f.seek(at)
                f.write(bytes([b[0] ^ 0x08]))
            if not sealed:
                resealed.append(path)

    for name in ("particles/position", "particles/id", "state/time", "contacts/pair_spring", "walls/base_vertices", "run/stage"):
        with h5py.File(variant("missing_" + name.replace("/", "_")), "r+") as f:
            del f[name]
    # A dataset whose extent claims far more data than the file holds (chunks never written): must be
    # refused before anything is allocated (a fuzzer-found out-of-memory).
    with h5py.File(variant("huge_extent"), "r+") as f:
        del f["particles/id"]
        f.create_dataset("particles/id", shape=(10**11,), dtype="i8", chunks=(1024,), fletcher32=True)
    # Contact history is carried over by a merge of key-sorted lists: an unsorted list is refused.
    path = os.path.join(workdir, "unsorted_contacts.h5")
    shutil.copyfile(with_contacts, path)
    variants.append(("unsorted_contacts", path))
    with h5py.File(path, "r+") as f:
        ids = f["contacts/pair_ids"][...]
        assert len(ids) >= 2, "the checkpoint must hold contacts"
        f["contacts/pair_ids"][...] = ids[::-1]
    with h5py.File(variant("wrong_format"), "r+") as f:
        f.attrs.modify("format", np.bytes_("other-code"))
    with h5py.File(variant("wrong_schema"), "r+") as f:
        f.attrs.modify("schema_version", np.int32(1))  # the previous version
    resealed += [path for name, path in variants if name.startswith(("huge_extent", "unsorted_", "missing_", "wrong_"))]
    for path in resealed:
        reseal(path)
    variants.append(("unsealed_edit", variant("unsealed_edit")))
    with h5py.File(variants[-1][1], "r+") as f:
        f["state/time"][...] = 1.0  # a well-formed edit without a new seal: refused as such
    foreign = os.path.join(workdir, "foreign.h5")
    with h5py.File(foreign, "w") as f:
        f["particles/position"] = np.zeros((10, 3))
    variants.append(("foreign", foreign))
    for name, content in (("empty", b""), ("text", b"id x y z\n1 0 0 0\n")):
        path = os.path.join(workdir, name + ".h5")
        open(path, "wb").write(content)
        variants.append((name, path))

    failures = 0
    for name, path in variants:
        rc, err, _ = read_back(tools, path, workdir)
        if rc != 4 or path not in err:
            print(f"NOT REJECTED: {name}: exit {rc}: {err.strip()}")
            failures += 1
    print(f"rejected {len(variants) - failures} of {len(variants)} damaged variants")

    rng = random.Random(2026)
    crashes = wrong = rejected = accepted = 0
    for k in range(40):
        path = os.path.join(workdir, f"random_{k}.h5")
        shutil.copyfile(good, path)
        pos = rng.randrange(size)
        with open(path, "r+b") as f:
            f.seek(pos)
            b = f.read(1)
            f.seek(pos)
            f.write(bytes([b[0] ^ (1 << rng.randrange(8))]))
        rc, err, table = read_back(tools, path, workdir)
        if rc == 4:
            rejected += 1
        elif rc == 0 and table == reference_table:
            accepted += 1
            print(f"NOT REJECTED (read back unchanged): byte {pos}")
        elif rc == 0:
            wrong += 1
            print(f"READ AS WRONG NUMBERS: byte {pos}")
        else:
            crashes += 1
            print(f"CRASH or unexpected exit {rc}: byte {pos}: {err.strip()[-200:]}")
    print(f"random single-bit flips: {rejected} rejected, {accepted} accepted unchanged, "
          f"{wrong} read as wrong numbers, {crashes} crashes")
    return 1 if failures or crashes or wrong or accepted else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
