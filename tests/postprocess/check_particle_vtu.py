#!/usr/bin/env python3
"""Compares the chunked particle output with deal.II's (particle_vtu_writer.sh).

The two writers must give the same file names, the same PVTU records (but
for the line with the date of writing) and, read back with
tools/read_particles.py, the same points with the same values, exactly:
both convert the same doubles to Float32, so any difference is an error.
The chunked files must hold several pieces where a rank has more than 64
points (else the test would not test the chunks)."""
import os
import re
import sys

sys.path.insert(0, sys.argv[1])
from read_particles import read_particles  # noqa: E402

reference, chunked, n_ranks = sys.argv[2], sys.argv[3], int(sys.argv[4])
failed = False


def check(ok, what):
    global failed
    print(("  ok:   " if ok else "  FAIL: ") + what)
    failed = failed or not ok


files = sorted(os.listdir(reference))
check(files == sorted(os.listdir(chunked)),
      "%d ranks: the same files (%s)" % (n_ranks, ", ".join(files)))
for name in files:
    if not name.endswith(".pvtu"):
        continue
    strip = lambda text: re.sub(r"#This file was generated.*\n", "", text)
    a = strip(open(os.path.join(reference, name)).read())
    b = strip(open(os.path.join(chunked, name)).read())
    check(a == b, "%s: the same PVTU record" % name)
    p, q = (read_particles(os.path.join(d, name)) for d in (reference, chunked))
    check(sorted(p) == sorted(q), "%s: the same fields (%d)" % (name, len(p)))
    order = lambda d: sorted(range(len(d["id"])), key=lambda i: d["id"][i])
    ip, iq = order(p), order(q)
    check(len(ip) == len(iq) and len(ip) > 0,
          "%s: the same number of points (%d)" % (name, len(ip)))
    differ = [k for k in p if [p[k][i] for i in ip] != [q[k][j] for j in iq]]
    check(not differ, "%s: the same values of every field at every point "
          "(differing: %s)" % (name, differ or "none"))
    # Pieces per file of the chunked writer: ceil(points / 64), at least 1.
    for piece in re.findall(r'Source="([^"]+)"', a):
        text = open(os.path.join(chunked, piece)).read()
        n_points = sum(int(n) for n in re.findall(r'<Piece NumberOfPoints="(\d+)"', text))
        n_pieces = text.count("<Piece ")
        check(n_pieces == max(1, -(-n_points // 64)),
              "%s: %d points in %d pieces" % (piece, n_points, n_pieces))
sys.exit(1 if failed else 0)
