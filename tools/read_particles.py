#!/usr/bin/env python3
"""Reads scarp's particle output (the .vtu pieces of one particles_NNNNN.pvtu,
zlib-compressed binary as deal.II writes them) into plain Python lists.

    from read_particles import read_particles, last_output
    points = read_particles(last_output("output/run"))   # {'x': [...], 'y': [...], name: [...]}

No numpy needed: the test scripts run with Debian's python3 alone.
"""
import base64
import glob
import os
import re
import struct
import zlib


def _decode(text, kind, header_type):
    """One DataArray: a base64 header (block count, block size, last block
    size, compressed sizes) and the base64 compressed blocks."""
    fmt = {"UInt32": "I", "UInt64": "Q"}[header_type]
    size = struct.calcsize(fmt)
    text = "".join(text.split())
    if not text:  # the arrays of a rank without points are empty
        return []
    # The header is base64 of its own; its length follows from the count.
    first = base64.b64decode(text[:12])
    n_blocks = struct.unpack("<" + fmt, first[:size])[0]
    header_bytes = (3 + n_blocks) * size
    header_chars = 4 * ((header_bytes + 2) // 3)
    header = struct.unpack("<" + fmt * (3 + n_blocks),
                           base64.b64decode(text[:header_chars])[:header_bytes])
    data = base64.b64decode(text[header_chars:])
    out, pos = b"", 0
    for c in header[3:]:
        out += zlib.decompress(data[pos:pos + c])
        pos += c
    code = {"Float64": "d", "Float32": "f", "Int32": "i", "UInt8": "B", "Int64": "q", "UInt32": "I"}[kind]
    return list(struct.unpack("<%d%s" % (len(out) // struct.calcsize(code), code), out))


def read_vtu(filename):
    text = open(filename).read()
    header_type = re.search(r'header_type="(\w+)"', text)
    header_type = header_type.group(1) if header_type else "UInt32"
    result = {}
    for m in re.finditer(r'<DataArray([^>]*)>(.*?)</DataArray>', text, re.S):
        attrs, body = m.group(1), m.group(2)
        kind = re.search(r'type="(\w+)"', attrs).group(1)
        name = re.search(r'Name="([^"]*)"', attrs)
        ncomp = re.search(r'NumberOfComponents="(\d+)"', attrs)
        ncomp = int(ncomp.group(1)) if ncomp else 1
        if 'format="ascii"' in attrs:
            continue  # the TIME field
        values = _decode(body, kind, header_type)
        # A file may hold several pieces (scarp writes the points of a rank
        # a chunk at a time): their arrays are concatenated.
        if name is None:  # the points
            for c, axis in enumerate("xyz"):
                result.setdefault(axis, []).extend(values[c::3])
        elif name.group(1) in ("connectivity", "offsets", "types"):
            continue
        elif ncomp == 1:
            result.setdefault(name.group(1), []).extend(values)
        else:
            for c in range(ncomp):
                result.setdefault("%s_%d" % (name.group(1), c),
                                  []).extend(values[c::ncomp])
    return result


def read_particles(pvtu):
    """All pieces of one .pvtu record, concatenated."""
    pieces = re.findall(r'Source="([^"]+)"', open(pvtu).read())
    merged = {}
    for piece in pieces:
        part = read_vtu(os.path.join(os.path.dirname(pvtu), piece))
        for k, v in part.items():
            merged.setdefault(k, []).extend(v)
    return merged


def last_output(directory, prefix="particles"):
    files = sorted(glob.glob(os.path.join(directory, prefix + "_*.pvtu")))
    if not files:
        raise SystemExit("no %s_*.pvtu in %s" % (prefix, directory))
    return files[-1]


def particle_outputs(directory, prefix="particles"):
    """(time, .pvtu path) of every particle output of a run, in the order
    of its <prefix>.pvd."""
    name = os.path.join(directory, prefix + ".pvd")
    try:
        text = open(name).read()
    except OSError as e:
        raise SystemExit(f"{name}: {e.strerror}")
    found = re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', text)
    if not found:
        raise SystemExit(f"{name}: no particle outputs")
    return [(float(t), os.path.join(directory, f)) for t, f in found]


def first_output(directory, prefix="particles"):
    return sorted(glob.glob(os.path.join(directory, prefix + "_*.pvtu")))[0]
